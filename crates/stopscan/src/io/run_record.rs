//! The run record of DESIGN.md (`--out run.json`): one JSON object per run, whose field names
//! are the contract.

use serde::{Deserialize, Serialize};

use crate::kernel::Point;
use crate::offline::polygon::{References, upper_bound};
use crate::protocol::CostModel;
use crate::sim::polygon::PolygonRun;
use crate::world::polygon::PolygonWorld;

/// `"environment"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct EnvironmentInfo {
    /// Name (file stem or family).
    pub name: String,
    /// Vertices.
    pub vertices: usize,
    /// Holes.
    pub holes: usize,
    /// Reflex vertices r.
    pub reflex_vertices: usize,
    /// Free area, m².
    pub free_area: f64,
}

/// `"strategy"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrategyInfo {
    /// Registry name.
    pub name: String,
    /// Parameters.
    pub params: serde_json::Value,
}

/// `"sensor"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SensorInfo {
    /// Range limit R, or null.
    pub range: Option<f64>,
}

/// One scan in a robot's record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScanRecord {
    /// Where.
    pub at: Point,
    /// When it began, seconds.
    pub time: f64,
}

/// `"robots"[i]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotRecord {
    /// Robot id.
    pub id: usize,
    /// The polyline driven.
    pub path: Vec<Point>,
    /// Its scans.
    pub scans: Vec<ScanRecord>,
}

/// `"metrics"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Scans.
    pub scans: u64,
    /// Moves.
    pub moves: u64,
    /// Metres driven.
    pub distance: f64,
    /// Total time, s.
    pub time: f64,
    /// `scan_time · scans`.
    pub scan_time_total: f64,
    /// `move_time · moves`.
    pub move_time_total: f64,
    /// `distance / speed`.
    pub travel_time_total: f64,
    /// The free area less what no scan covers, m².
    pub covered_area: f64,
    /// `covered_area / free_area`, where the area not covered counts only the pieces of the
    /// free space minus the scanned regions that an exact point test confirms unseen
    /// ([`crate::algorithm::cover::uncovered_area`]): 1 exactly on a complete run.
    pub coverage: f64,
    /// Parts of windows (and range chords) of the scanned regions whose far side no other scan
    /// covers and lies in the free space (exact test up to rounding of cut points): 0
    /// certifies that the whole free space was seen.
    pub open_windows: usize,
}

/// `"bounds"`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Bounds {
    /// The paper's r + 1 (full visibility).
    pub scans_upper: usize,
    /// A lower bound on the optimum's scans.
    pub scans_lower: usize,
    /// Scans divided by the optimum, when the optimum is known (null otherwise).
    pub competitive_ratio: Option<f64>,
    /// Which bound `scans_upper` is (Theorem 1's r + 1, or Lemma 4's with a range).
    #[serde(default)]
    pub scans_upper_rule: String,
    /// Views of the offline greedy reference (start and vertex or triangle candidates, each
    /// seen from an earlier one), when computed.
    #[serde(default)]
    pub greedy_reference: Option<usize>,
    /// The exact minimum number of views over the same candidates (integer programming),
    /// when computed and certified.
    #[serde(default)]
    pub optimum: Option<usize>,
}

/// A whole run record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// `"stopscan-run/1"`.
    pub format: String,
    /// The environment.
    pub environment: EnvironmentInfo,
    /// The strategy.
    pub strategy: StrategyInfo,
    /// The cost model.
    pub cost_model: CostModel,
    /// The sensor.
    pub sensor: SensorInfo,
    /// One record per robot.
    pub robots: Vec<RobotRecord>,
    /// The metrics.
    pub metrics: Metrics,
    /// Bounds.
    pub bounds: Bounds,
    /// The seed.
    pub seed: u64,
    /// The library version.
    pub stopscan_version: String,
}

impl RunRecord {
    /// The record of a single-robot polygon run in `world`, measured against `refs`.
    pub fn polygon(
        name: &str,
        world: &PolygonWorld,
        strategy: &str,
        cost: &CostModel,
        run: &PolygonRun,
        refs: &References,
        seed: u64,
    ) -> Self {
        let domain = world.domain();
        let (upper, rule) = upper_bound(domain, world.range());
        let optimum = refs.optimum.as_ref().filter(|o| o.certified).map(|o| o.viewpoints.len());
        let polys: Vec<Vec<Point>> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
        let uncovered = crate::algorithm::cover::uncovered_area(domain, &polys);
        let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
        let open_windows = crate::algorithm::cover::open_windows(&regions, |p| {
            domain.locate(p) == crate::geometry::Location::Interior
        });
        let free = domain.area();
        let r = domain.reflex_vertices().len();
        Self {
            format: "stopscan-run/1".into(),
            environment: EnvironmentInfo {
                name: name.into(),
                vertices: domain.vertex_count(),
                holes: domain.holes().len(),
                reflex_vertices: r,
                free_area: free,
            },
            strategy: StrategyInfo { name: strategy.into(), params: serde_json::json!({}) },
            cost_model: *cost,
            sensor: SensorInfo { range: world.range() },
            robots: vec![RobotRecord {
                id: 0,
                path: run.path.clone(),
                scans: run
                    .scans
                    .iter()
                    .zip(&run.scan_times)
                    .map(|(s, &t)| ScanRecord { at: s.at, time: t })
                    .collect(),
            }],
            metrics: Metrics {
                scans: run.tally.scans,
                moves: run.tally.moves,
                distance: run.tally.distance,
                time: run.time.total(),
                scan_time_total: run.time.scan_time_total,
                move_time_total: run.time.move_time_total,
                travel_time_total: run.time.travel_time_total,
                covered_area: free - uncovered,
                coverage: 1.0 - uncovered / free,
                open_windows,
            },
            bounds: Bounds {
                scans_upper: upper,
                scans_lower: refs.lower.max(optimum.unwrap_or(0)),
                competitive_ratio: optimum.map(|o| run.tally.scans as f64 / o as f64),
                scans_upper_rule: rule.into(),
                greedy_reference: refs
                    .greedy
                    .as_ref()
                    .filter(|g| g.certified)
                    .map(|g| g.viewpoints.len()),
                optimum,
            },
            seed,
            stopscan_version: crate::VERSION.into(),
        }
    }
}
