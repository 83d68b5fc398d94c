//! Pictures: line charts and policy images, written as SVG and PNG side by side.
//!
//! Charts are data (a [`LineChart`] is serialisable), so the CLI, the docs' figures and later
//! the Python bindings draw the same thing.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::prelude::*;
use serde::{Deserialize, Serialize};

use crate::strategy::corner::mdp::Cell;

mod roi;
mod scene;
pub use roi::roi_svg;
pub use scene::{exploration_svg, scene_svg};

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

/// One line of a chart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// `(x, y)` points in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points as well as the line.
    pub markers: bool,
    /// Draw a dashed reference line (bounds) rather than a data line.
    pub dashed: bool,
}

impl Series {
    /// A plain data line.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { label: label.into(), points, markers: false, dashed: false }
    }
    /// A data line with markers.
    #[must_use]
    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }
    /// A dashed reference line.
    #[must_use]
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
}

/// A line chart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineChart {
    /// Caption.
    pub title: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(90, 90, 90),
];

/// Writes `stem.svg` and `stem.png`; returns both paths.
///
/// # Errors
/// [`RenderError`] if the chart is empty or a file cannot be drawn.
pub fn write_chart(chart: &LineChart, stem: &Path) -> Result<Vec<PathBuf>, RenderError> {
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    let size = (900, 560);
    draw_chart(&SVGBackend::new(&svg, size).into_drawing_area(), chart)
        .map_err(|reason| RenderError::Draw { path: svg.clone(), reason })?;
    draw_chart(&BitMapBackend::new(&png, size).into_drawing_area(), chart)
        .map_err(|reason| RenderError::Draw { path: png.clone(), reason })?;
    Ok(vec![svg, png])
}

fn bounds(chart: &LineChart) -> Option<(f64, f64, f64, f64)> {
    let pts =
        chart.series.iter().flat_map(|s| &s.points).filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let mut any = false;
    for &(x, y) in pts {
        any = true;
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if !any {
        return None;
    }
    let pad = |a: f64, b: f64| {
        if b - a < 1e-12 { 0.5 * a.abs().max(1.0) } else { 0.04 * (b - a) }
    };
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    Some((x0 - px, x1 + px, y0 - py, y1 + py))
}

fn draw_chart<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<(), String> {
    let (x0, x1, y0, y1) =
        bounds(chart).ok_or_else(|| format!("chart {:?} has no finite points", chart.title))?;
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let mut ctx = ChartBuilder::on(root)
        .caption(&chart.title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| e.to_string())?;
    ctx.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| e.to_string())?;
    for (k, s) in chart.series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let pts: Vec<(f64, f64)> =
            s.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite()).collect();
        let style = color.stroke_width(if s.dashed { 1 } else { 2 });
        if s.dashed {
            ctx.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))
                .map_err(|e| e.to_string())?
                .label(&s.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
        } else {
            ctx.draw_series(LineSeries::new(pts.clone(), style))
                .map_err(|e| e.to_string())?
                .label(&s.label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        if s.markers {
            ctx.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(|e| e.to_string())?;
        }
    }
    ctx.configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Writes a policy image like the corner paper's Fig. 4 / Fig. 6 as `stem.svg` and `stem.png`.
/// For MDP2, row `i` (downwards) is the robot's stop and column `j` the last scan's stop; for
/// MDP1 (two rows) the columns are stops and the rows `s_i` and `s'_i`. Blue is inaccessible,
/// green reconstruct, red move.
///
/// # Errors
/// [`RenderError`] if the image is empty or cannot be drawn.
pub fn write_policy_image(
    rows: &[Vec<Cell>],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>, RenderError> {
    if rows.is_empty() || rows[0].is_empty() {
        return Err(RenderError::Empty(title.into()));
    }
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    let side = 560u32;
    let h = if rows.len() <= 2 { 220 } else { side + 60 };
    draw_policy(&SVGBackend::new(&svg, (side + 80, h)).into_drawing_area(), rows, title)
        .map_err(|reason| RenderError::Draw { path: svg.clone(), reason })?;
    draw_policy(&BitMapBackend::new(&png, (side + 80, h)).into_drawing_area(), rows, title)
        .map_err(|reason| RenderError::Draw { path: png.clone(), reason })?;
    Ok(vec![svg, png])
}

fn draw_policy<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[Vec<Cell>],
    title: &str,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (n_rows, n_cols) = (rows.len() as f64, rows[0].len() as f64);
    let mut ctx = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 15))
        .margin(10)
        .x_label_area_size(48)
        .y_label_area_size(44)
        .build_cartesian_2d(0.0..n_cols, n_rows..0.0)
        .map_err(|e| e.to_string())?;
    ctx.configure_mesh()
        .disable_mesh()
        .x_desc(if rows.len() <= 2 {
            "stop i   (green: reconstruct, red: move, blue: no such state)"
        } else {
            "last scan stop j   (green: reconstruct, red: move, blue: no such state)"
        })
        .y_desc(if rows.len() <= 2 { "top: s_i, bottom: s'_i" } else { "current stop i" })
        .y_labels(if rows.len() <= 2 { 3 } else { 10 })
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()
        .map_err(|e| e.to_string())?;
    let cells = rows.iter().enumerate().flat_map(|(i, row)| {
        row.iter().enumerate().map(move |(j, c)| {
            let color = match c {
                Cell::Inaccessible => RGBColor(70, 110, 200),
                Cell::Move => RGBColor(200, 50, 50),
                Cell::Reconstruct => RGBColor(60, 170, 70),
            };
            Rectangle::new([(j as f64, i as f64), (j as f64 + 1.0, i as f64 + 1.0)], color.filled())
        })
    });
    ctx.draw_series(cells).map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}
