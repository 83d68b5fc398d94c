//! `corner demo`.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{CornerError, save_chart};
use crate::experiment::corner::{self as exp, LineupOptions};
use crate::io::atomic;
use crate::protocol::CostModel;

/// The demo's circle strategy at one distance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoCircle {
    /// `d`.
    pub distance: f64,
    /// `c(d)`.
    pub ratio: f64,
    /// Intermediate scans.
    pub scans: usize,
    /// Step lengths.
    pub steps: Vec<f64>,
    /// Scan points.
    pub scan_points: Vec<[f64; 2]>,
}

pub use exp::DemoStrategy;

/// The demo's corner-paper setup and strategies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoCorner {
    /// Distance, metres.
    pub distance: f64,
    /// The cost model.
    pub cost_model: CostModel,
    /// δ = τv/D.
    pub delta: f64,
    /// The belief (and truth), described.
    pub belief: String,
    /// The MDPs' stop spacing, degrees.
    pub mdp_step_deg: f64,
    /// The four strategies.
    pub strategies: Vec<DemoStrategy>,
}

/// `corner demo` (`corner-demo.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoReport {
    /// `stopscan-corner-demo/1`.
    pub format: String,
    /// The circle strategy at six distances.
    pub circle: Vec<DemoCircle>,
    /// The corner paper's strategies on one belief.
    pub corner: DemoCorner,
    /// The chart files written.
    pub files: Vec<String>,
    /// The library version.
    pub stopscan_version: String,
}

/// The corner demo: the circle strategy at six distances and the four corner-paper
/// strategies on one belief; writes the `c(d)` chart (`circle-ratio`) and the report
/// (`corner-demo.json`, keys sorted) into `dir`, created if missing.
///
/// # Errors
/// [`CornerError`] if the demo cannot be computed or its files cannot be written.
pub fn demo(dir: &Path) -> Result<DemoReport, CornerError> {
    let exp::Demo { circles, strategies, chart } = exp::demo()?;
    atomic::ensure_dir(dir)?;
    let files = save_chart(dir, "circle-ratio", &chart)?;
    let setup = exp::paper_setup(2.0)?;
    let report = DemoReport {
        format: "stopscan-corner-demo/1".into(),
        circle: circles
            .into_iter()
            .map(|s| DemoCircle {
                distance: s.distance,
                ratio: s.ratio,
                scans: s.scans,
                steps: s.steps,
                scan_points: s.scan_points,
            })
            .collect(),
        corner: DemoCorner {
            distance: setup.distance,
            cost_model: setup.cost,
            delta: setup.delta(),
            belief: "mix:0.5*normal:30,3+0.5*normal:90,3 on 5° buckets (the corner paper's distribution 4)".into(),
            mdp_step_deg: LineupOptions::default().mdp_step.to_degrees(),
            strategies,
        },
        files,
        stopscan_version: crate::VERSION.into(),
    };
    // Not run.json: that is the main job's run record, in the same default folder.
    let path = demo_json(dir);
    atomic::write(&path, |w| {
        let sorted = serde_json::to_value(&report)?;
        serde_json::to_writer_pretty(&mut *w, &sorted)?;
        w.write_all(b"\n")
    })?;
    Ok(report)
}

/// Where [`demo`] writes its report in `dir`.
pub fn demo_json(dir: &Path) -> PathBuf {
    dir.join("corner-demo.json")
}
