//! Pictures: line charts and policy images, written as SVG and PNG side by side, and the
//! hand-written SVG scenes and replays.
//!
//! Charts are data (a [`LineChart`] is serialisable), so the CLI, the docs' figures and later
//! the Python bindings draw the same thing.
//!
//! - `chart`: [`LineChart`], [`Series`] and [`write_chart`] (plotters, SVG and PNG);
//! - `layout`: axis [`ticks`] and the legend's corner ([`legend_corner`]), in pixels;
//! - `policy`: MDP policy images ([`write_policy_image`]);
//! - `scene`: SVG scenes of a domain, its visibility regions and an exploration
//!   ([`scene_svg`], [`exploration_svg`] with its optional layers in [`SceneExtras`]);
//! - `labels`: where an exploration's scan numbers go (none overlaps another, a marker or
//!   the legend);
//! - `roi`: the animated SVG replay of a grid mission ([`roi_svg`]);
//! - `report`: `report.html`, the self-contained browser replay of an exploration
//!   ([`polygon_report`]) or a grid mission ([`roi_report`]);
//! - `mcap`: MCAP recordings with Foxglove's schemas ([`polygon_mcap`], [`roi_mcap`]);
//! - `glyphs`: bitmap text drawn without clipped glyphs (plotters' font stack).

use std::path::PathBuf;

mod chart;
mod glyphs;
mod labels;
mod layout;
pub mod mcap;
mod policy;
mod report;
mod roi;
mod scene;

pub use chart::{CHART_SIZE, LineChart, Series, chart_layout, write_chart};
pub use layout::{
    ChartLayout, LEGEND_CLEARANCE, PixelBox, PixelSize, Ticks, legend_corner, tick_label, ticks,
};
pub use mcap::{McapError, McapWriter, polygon_mcap, roi_mcap};
pub use policy::write_policy_image;
pub use report::{MAX_REPORTED_CELLS, PolygonReplay, RawReplay, polygon_report, roi_report};
pub use roi::roi_svg;
pub use scene::{SceneExtras, exploration_svg, scene_svg};

/// Why a picture could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// Drawing or writing failed (a missing font, an unwritable path).
    #[error("cannot draw {path}: {reason}")]
    Draw {
        /// The file.
        path: PathBuf,
        /// The backend's message.
        reason: String,
    },
    /// There is nothing to draw.
    #[error("chart {0:?} has no finite points")]
    Empty(String),
}
