//! The run record of DESIGN.md (`--out run.json`): one JSON object per run, whose field names
//! are the contract.
//!
//! [`RunRecord`] records a polygon exploration with its certified bounds and offline
//! references, [`GridRunRecord`] a grid mission with the ROI paper's bounds. Both are built
//! from a finished run, its world and the offline results, so this module stands above
//! [`sim`](crate::sim) and [`offline`](crate::offline); [`io`](crate::io), which only reads
//! environments, stands below them.

use serde::{Deserialize, Serialize};

use crate::kernel::Point;
use crate::kernel::tolerance::SAME_VALUE_REL;
use crate::offline::grid::GridBounds;
use crate::offline::polygon::{References, upper_bound};
use crate::protocol::grid::Cell;
use crate::protocol::{CostModel, RunTotals};
use crate::sim::grid::Mission;
use crate::sim::polygon::PolygonRun;
use crate::strategy::polygon::Skipped;
use crate::world::grid::{Drift, GridWorld};
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
    /// The input's frame when computations ran in a local one: every point of the record is
    /// in the input's coordinates, `input = local + frame_origin` (absent when the two agree).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub frame_origin: Option<Point>,
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
    /// Beams per revolution (absent: continuous).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub beams: Option<u32>,
    /// The smallest feature resolved, metres (absent: 0).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_feature: Option<f64>,
    /// The shortest window worth a trip, metres (absent: every window counts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_window: Option<f64>,
    /// The smallest enclosed pocket worth a trip, as a share of the area seen (absent: every
    /// pocket counts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub min_pocket: Option<f64>,
    /// The largest pocket the rule may leave, square metres (absent: every pocket counts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pocket_cap: Option<f64>,
    /// The most the pockets the rule leaves may hold in all, as a share of the area seen
    /// (absent: every pocket counts, or each is judged alone).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pocket_budget: Option<f64>,
    /// The window rule in words (absent: every window counts).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub window_rule: Option<String>,
    /// Windows the rule closed without a visit, and their total length (absent: no rule).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_below_rule: Option<usize>,
    /// Their total length, metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_below_rule_length: Option<f64>,
    /// Window parts closed without a visit because they open into a pocket below
    /// `min_pocket` (absent: no pocket term).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_into_small_pockets: Option<usize>,
    /// Window parts dropped because a move to the viewpoint planned for them failed (absent:
    /// no move failed).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_dropped_by_failed_moves: Option<usize>,
    /// Window parts handled without a trip because a scan had already stood at, or been asked
    /// for at, the viewpoint planned for them (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_looked_at_from_their_viewpoint: Option<usize>,
    /// Window parts closed without a visit because they open onto a pocket enclosed by walls
    /// seen and space seen, smaller than a quarter of the pocket limit, or onto a wall seen
    /// right behind them (raw scans only, every window strategy; absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_into_walled_pockets: Option<usize>,
    /// Windows of raw scans read as the wall they are a gap in: the walls on either side lie
    /// on one line, seen at 30° or less (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub windows_as_gaps_in_a_wall: Option<usize>,
    /// Scans taken where the robot was stuck, its moves and the way back having failed: each
    /// places it again to plan on from (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scans_where_stuck: Option<usize>,
    /// Scans taken at what would have been the end, to place the robot again before window
    /// parts dropped by failed moves are tried once more (absent: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scans_to_place_again: Option<usize>,
    /// `true` when the strategy gave up before every window was explored, stuck again where
    /// it had scanned for being stuck: what it left open is counted nowhere else (absent: it
    /// did not give up).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gave_up: Option<bool>,
}

impl SensorInfo {
    /// The sensor of a run and what its window rule closed.
    pub fn of(sensor: &crate::protocol::polygon::Sensor, skipped: &Skipped) -> Self {
        let rule = !sensor.excludes_nothing();
        Self {
            range: sensor.range,
            beams: sensor.beams,
            min_feature: (sensor.min_feature > 0.0).then_some(sensor.min_feature),
            min_window: rule.then_some(sensor.min_window),
            min_pocket: sensor.has_pocket_term().then_some(sensor.min_pocket),
            pocket_cap: sensor.has_pocket_term().then_some(sensor.pocket_cap),
            pocket_budget: sensor.pocket_budget.filter(|_| sensor.has_pocket_term()),
            window_rule: rule.then(|| sensor.rule()),
            windows_below_rule: rule.then_some(skipped.below_rule),
            windows_below_rule_length: rule.then_some(skipped.below_rule_length),
            windows_into_small_pockets: sensor.has_pocket_term().then_some(skipped.small_pocket),
            windows_dropped_by_failed_moves: (skipped.move_failed > 0)
                .then_some(skipped.move_failed),
            windows_looked_at_from_their_viewpoint: (skipped.looked_from > 0)
                .then_some(skipped.looked_from),
            windows_into_walled_pockets: (skipped.walled_pocket > 0)
                .then_some(skipped.walled_pocket),
            windows_as_gaps_in_a_wall: (skipped.wall_gap > 0).then_some(skipped.wall_gap),
            scans_where_stuck: (skipped.stuck_scans > 0).then_some(skipped.stuck_scans),
            scans_to_place_again: (skipped.placed_again_scans > 0)
                .then_some(skipped.placed_again_scans),
            gave_up: skipped.gave_up.then_some(true),
        }
    }
}

/// `"raw_scans"`: a run driven from simulated laser scans (`explore --sensor lidar`): the
/// lidar, the odometry's drift, how the strategies' footprint was grown for the pose error,
/// and every stop's true and believed pose. The record's metrics measure the ground truth: the
/// exact regions seen from where the scans were truly taken, along the path truly driven.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RawScanInfo {
    /// The lidar model.
    pub lidar: crate::world::lidar::Lidar,
    /// Odometry's drift (position error per metre, per axis; a tenth of it in radians of
    /// heading per metre).
    pub odometry_drift: f64,
    /// The seed of the lidar's noise and the drift.
    pub seed: u64,
    /// How much the strategies' planning clearance was grown over the robot's, metres.
    pub planning_margin: f64,
    /// How scans were read and aligned.
    pub ingest: crate::sensing::ingest::IngestParams,
    /// ICP's settings.
    pub icp: crate::sensing::icp::IcpParams,
    /// The largest position error at a stop after ICP, metres.
    pub max_position_error: f64,
    /// The mean position error at the stops, metres.
    pub mean_position_error: f64,
    /// The largest heading error at a stop after ICP, radians.
    pub max_heading_error: f64,
    /// Stops where ICP kept odometry (too few pairs, a poor fit, an implausible correction, or
    /// returns beyond walls already mapped).
    pub icp_fallbacks: usize,
    /// Stops where the walls left a direction unconstrained (odometry kept along it).
    pub icp_degenerate: usize,
    /// Scan matches to single earlier stops that became edges of the pose graph, over all
    /// stops.
    #[serde(default)]
    pub graph_links: usize,
    /// The relay rule: a trip whose end is predicted not to be placed by ICP, with odometry
    /// off by more than this there (one standard deviation, metres), gets a scan on the way
    /// to place the robot; 0 when off ([`LidarSetup::relay`](crate::sim::lidar::LidarSetup::relay)).
    #[serde(default)]
    pub relay: f64,
    /// Scans taken on the way to place the robot (relays), included in the run's scans and
    /// their time; the strategy was not told of them.
    #[serde(default)]
    pub relays: usize,
    /// Beams in all scans, and what cleaning did to them.
    pub cleaning: crate::sensing::ingest::Cleaning,
    /// Every stop, in order.
    pub stops: Vec<crate::sim::lidar::Stop>,
}

impl RawScanInfo {
    /// The summary of a raw-scan run.
    pub fn of(
        run: &crate::sim::lidar::LidarRun,
        setup: &crate::sim::lidar::LidarSetup,
        planning_margin: f64,
    ) -> Self {
        let stops = &run.stops;
        let mut cleaning = crate::sensing::ingest::Cleaning::default();
        for s in stops {
            let c = &s.cleaning;
            cleaning.beams += c.beams;
            cleaning.returns += c.returns;
            cleaning.no_return += c.no_return;
            cleaning.too_close += c.too_close;
            cleaning.dropouts += c.dropouts;
            cleaning.spurious += c.spurious;
        }
        Self {
            lidar: setup.lidar,
            odometry_drift: setup.drift,
            seed: setup.seed,
            planning_margin,
            ingest: setup.ingest,
            icp: setup.icp,
            max_position_error: stops.iter().map(|s| s.position_error).fold(0.0, f64::max),
            mean_position_error: if stops.is_empty() {
                0.0
            } else {
                stops.iter().map(|s| s.position_error).sum::<f64>() / stops.len() as f64
            },
            max_heading_error: stops.iter().map(|s| s.heading_error.abs()).fold(0.0, f64::max),
            icp_fallbacks: stops
                .iter()
                .filter(|s| s.alignment.is_some_and(|a| a.fallback.is_some()))
                .count(),
            icp_degenerate: stops
                .iter()
                .filter(|s| s.alignment.is_some_and(|a| a.degenerate.is_some()))
                .count(),
            graph_links: stops.iter().map(|s| s.links).sum(),
            relay: setup.relay,
            relays: stops.iter().filter(|s| s.relay).count(),
            cleaning,
            stops: stops.clone(),
        }
    }
}

/// `"robot"`: the footprint and where it can go (absent for a point robot).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotInfo {
    /// The footprint.
    pub footprint: crate::protocol::polygon::Footprint,
    /// The clearance planned moves keep from what has not been seen free, metres.
    pub clearance: f64,
    /// How the configuration space was built.
    pub configuration_space_rule: String,
    /// The area of the configuration space's component at the start, m².
    pub reachable_configuration_space_area: f64,
    /// How many components the configuration space has (the others are out of reach).
    pub configuration_space_components: usize,
    /// The free area seen from the reachable configuration space, m²: the union of the
    /// visibility regions from its vertices, its triangles' centroids and the run's scans
    /// (a lower estimate of the area visible from anywhere the robot can be).
    pub visible_from_reachable_area: f64,
    /// `free_area − visible_from_reachable_area`, m²: space no reachable viewpoint was found
    /// to see, reported apart and not counted as a failure (an upper estimate).
    pub unreachable_area: f64,
    /// `covered_area / visible_from_reachable_area`.
    pub coverage_of_reachable: f64,
    /// Window parts the strategy closed because no viewpoint with the clearance could be
    /// planned for them from the view that saw them.
    pub windows_out_of_reach: usize,
    /// The area where the robot's body can be, m²: the reachable configuration space grown
    /// by the footprint ([`crate::offline::polygon::reach::body_space`]).
    #[serde(default)]
    pub body_space_area: f64,
    /// The part of the area visible from the reachable region inside the body space that the
    /// scans covered.
    #[serde(default)]
    pub coverage_of_body_space: f64,
    /// The area visible from the reachable region, outside the body space, that no scan
    /// covered, m²: crevices narrower than the robot (slots, a laser's see-through spikes on
    /// a traced map), seen only along their length.
    #[serde(default)]
    pub unseen_in_crevices: f64,
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
    /// Scans, moves, distance and the time split into its terms.
    #[serde(flatten)]
    pub totals: RunTotals,
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
    /// A lower bound on the scans of *any* complete exploration, viewpoints anywhere
    /// ([`crate::offline::polygon::bounds`]).
    pub scans_lower: usize,
    /// Which bound `scans_lower` is.
    #[serde(default)]
    pub scans_lower_rule: String,
    /// A lower bound on the metres any complete exploration drives.
    #[serde(default)]
    pub distance_lower: f64,
    /// The lower bound on any complete exploration's time under the run's cost model:
    /// `scan_time·scans_lower + move_time·(scans_lower − 1) + distance_lower/speed`.
    #[serde(default)]
    pub time_lower: f64,
    /// `time / time_lower`: an upper bound on this run's true competitive ratio (the optimum
    /// takes at least `time_lower`).
    #[serde(default)]
    pub certified_ratio: Option<f64>,
    /// Whether the bounds' computation finished within its time budget (they are valid either
    /// way, only weaker when cut short).
    #[serde(default)]
    pub bounds_complete: bool,
    /// Scans divided by the proven optimum over the candidates, when proven (null
    /// otherwise). The candidates restrict the optimum, so this may understate the true
    /// ratio; `certified_ratio` bounds it from above.
    pub competitive_ratio: Option<f64>,
    /// Which bound `scans_upper` is (Theorem 1's r + 1, or Lemma 4's with a range).
    #[serde(default)]
    pub scans_upper_rule: String,
    /// Views of the offline greedy reference (start and vertex or triangle candidates, each
    /// seen from an earlier one), when computed. A reference, not a bound: an online run can
    /// do better.
    #[serde(default)]
    pub greedy_reference: Option<usize>,
    /// The exact minimum number of views over the same candidates (integer programming),
    /// when proven.
    #[serde(default)]
    pub optimum: Option<usize>,
    /// How the search for the optimum ended: `proven`, `budget_reached` or `skipped`.
    #[serde(default)]
    pub optimum_status: String,
    /// The best complete set the search found (the optimum when proven), in views.
    #[serde(default)]
    pub optimum_best: Option<usize>,
    /// The best proven lower bound on the optimum over the candidates.
    #[serde(default)]
    pub optimum_lower: usize,
    /// The search's time budget in seconds (the time it took is left out of the record, so
    /// that the same run gives the same record; it is shown while it runs).
    #[serde(default)]
    pub optimum_budget_seconds: f64,
    /// The integer-programming solver.
    #[serde(default)]
    pub optimum_solver: String,
    /// Why the search was skipped or stopped.
    #[serde(default)]
    pub optimum_note: String,
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
    /// The robot's footprint and where it can go (absent for a point robot).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub robot: Option<RobotInfo>,
    /// The raw-scan run's lidar, drift and pose errors (absent for the exact sensor).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub raw_scans: Option<RawScanInfo>,
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
    /// Why the run was ended before the strategy was done (the record is then the run so
    /// far); absent for a complete run.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
}

impl RunRecord {
    /// The same record with every point moved from the local `frame` to the input's
    /// coordinates (distances, areas and times do not change).
    #[must_use]
    pub fn in_frame(mut self, frame: &crate::geometry::Frame) -> Self {
        if frame.is_identity() {
            return self;
        }
        for r in &mut self.robots {
            for p in &mut r.path {
                *p = frame.to_input(*p);
            }
            for s in &mut r.scans {
                s.at = frame.to_input(s.at);
            }
        }
        if let Some(raw) = &mut self.raw_scans {
            for s in &mut raw.stops {
                for pose in [&mut s.truth, &mut s.odometry, &mut s.estimate] {
                    let p = frame.to_input(pose.at());
                    (pose.x, pose.y) = (p[0], p[1]);
                }
                if let Some(a) = &mut s.alignment {
                    for pose in [&mut a.guess, &mut a.pose] {
                        let p = frame.to_input(pose.at());
                        (pose.x, pose.y) = (p[0], p[1]);
                    }
                }
            }
        }
        self.environment.frame_origin = Some(frame.origin);
        self
    }

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
        let optimum = refs.optimum.views();
        let polys: Vec<Vec<Point>> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
        let uncovered = crate::algorithm::cover::uncovered_area(domain, &polys);
        let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
        let open_windows = crate::algorithm::cover::open_windows(&regions, |p| {
            domain.locate(p) == crate::geometry::Location::Interior
        });
        let free = domain.area();
        let r = domain.reflex_vertices().len();
        let time = run.time.total();
        let time_lower = refs.lower.time(cost);
        Self {
            format: "stopscan-run/1".into(),
            environment: EnvironmentInfo {
                name: name.into(),
                vertices: domain.vertex_count(),
                holes: domain.holes().len(),
                reflex_vertices: r,
                free_area: free,
                frame_origin: None,
            },
            strategy: StrategyInfo { name: strategy.into(), params: serde_json::json!({}) },
            cost_model: *cost,
            sensor: SensorInfo::of(
                &crate::protocol::polygon::Sensor { range: world.range(), ..Default::default() },
                &Skipped::default(),
            ),
            robot: None,
            raw_scans: None,
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
                totals: RunTotals::new(&run.tally, run.time.total(), &run.time),
                covered_area: free - uncovered,
                coverage: 1.0 - uncovered / free,
                open_windows,
            },
            bounds: Bounds {
                scans_upper: upper,
                scans_lower: refs.lower.views,
                scans_lower_rule: refs.lower.views_rule.clone(),
                distance_lower: refs.lower.travel,
                time_lower,
                certified_ratio: (time_lower > 0.0).then(|| time / time_lower),
                bounds_complete: refs.lower.complete,
                competitive_ratio: optimum.map(|o| run.tally.scans as f64 / o as f64),
                scans_upper_rule: rule.into(),
                greedy_reference: refs
                    .greedy
                    .as_ref()
                    .filter(|g| g.certified)
                    .map(|g| g.viewpoints.len()),
                optimum,
                optimum_status: serde_json::to_value(refs.optimum.status)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default(),
                optimum_best: refs.optimum.best.as_ref().map(|b| b.viewpoints.len()),
                optimum_lower: refs.optimum.lower,
                optimum_budget_seconds: refs.optimum.budget_seconds,
                optimum_solver: refs.optimum.solver.name().into(),
                optimum_note: refs.optimum.note.clone(),
            },
            seed,
            stopscan_version: crate::VERSION.into(),
            error: None,
        }
    }
}

/// `"environment"` of a grid run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridEnvironmentInfo {
    /// Name (file stem or generator).
    pub name: String,
    /// C, the region's cells (its outer approximation for a shape).
    pub cells: usize,
    /// The side of a cell, metres.
    pub cell_size: f64,
    /// The smallest and largest (row, col).
    pub bounds: [Cell; 2],
    /// The start cell.
    pub start: Cell,
    /// How the region moves.
    pub drift: Drift,
    /// The true area, m² (the shape's, or the cells').
    pub true_area: f64,
}

/// One robot of a grid run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridRobotRecord {
    /// Robot id.
    pub id: usize,
    /// Cell centres flown through, metres, in the region's frame (cell `[r, c]` is at
    /// `(c·s, −r·s)`; add the drift times the time for the fixed frame); only the start when
    /// paths were not recorded.
    pub path: Vec<Point>,
    /// The cells (row, col) in the order visited.
    pub cells: Vec<Cell>,
    /// When each cell of `cells` was reached, seconds.
    pub times: Vec<f64>,
    /// Its scans.
    pub scans: Vec<ScanRecord>,
    /// When it finished (back at the start), seconds.
    pub finish_time: f64,
    /// Batteries swapped.
    pub battery_swaps: u32,
}

/// `"metrics"` of a grid run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridMetrics {
    /// Scans, moves, metres flown in the fixed frame, and the time split into its terms (all
    /// robots). `time` is the exploration time: when the last robot is back (Problem 1).
    #[serde(flatten)]
    pub totals: RunTotals,
    /// Region cells some robot stood on.
    pub visited_cells: usize,
    /// Their area, m² (DESIGN.md's `covered_area`).
    pub covered_area: f64,
    /// `visited_cells / cells`.
    pub coverage: f64,
    /// Whether every robot ended on the start cell.
    pub all_home: bool,
    /// Cells the map marks as region (when a map was built).
    pub mapped_cells: Option<usize>,
    /// Intersection over union of the mapped cells against the true region (section 7's
    /// figure; when a map was built).
    pub iou: Option<f64>,
    /// C_out and C_in of section 5 (for a region given as a shape).
    pub c_out: Option<usize>,
    /// Cells of the outer approximation lying wholly inside the shape.
    pub c_in: Option<usize>,
}

/// `"bounds"` of a grid run: the paper's bounds beside its time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridBoundsRecord {
    /// All the bounds.
    #[serde(flatten)]
    pub bounds: GridBounds,
    /// Whether the time is within Lemma 1 (null when scans or moves cost time, which the
    /// paper's model does not have, or when batteries were swapped).
    pub within_lemma1: Option<bool>,
    /// The time over Lemma 2's lower bound on the optimum: an upper estimate of the
    /// competitive ratio (the optimum is at least that bound).
    pub competitive_ratio: Option<f64>,
    /// The start's eccentricity in the region (4-neighbour steps to the farthest cell), for
    /// comparison with `d_max`, the depth of the tree built (which Lemma 1 uses, as the paper
    /// defines it; the tree can be deeper than shortest paths).
    pub eccentricity: usize,
}

/// A whole grid run record (DESIGN.md's fields, plus `cells`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridRunRecord {
    /// `"stopscan-run/1"`.
    pub format: String,
    /// The region.
    pub environment: GridEnvironmentInfo,
    /// The strategy and its parameters.
    pub strategy: StrategyInfo,
    /// The cost model (its speed is S_r).
    pub cost_model: CostModel,
    /// The sensor.
    pub sensor: serde_json::Value,
    /// One record per robot.
    pub robots: Vec<GridRobotRecord>,
    /// The metrics.
    pub metrics: GridMetrics,
    /// Bounds.
    pub bounds: GridBoundsRecord,
    /// C.
    pub cells: usize,
    /// Why robots gave up, if any did.
    pub failures: Vec<String>,
    /// The seed.
    pub seed: u64,
    /// The library version.
    pub stopscan_version: String,
}

impl GridRunRecord {
    /// The record of a finished (or stopped) mission in `world`.
    pub fn new(world: &GridWorld, mission: &Mission, seed: u64) -> Self {
        let roi = world.roi();
        let cost = mission.plan.cost;
        let tm = world.time_model(&cost);
        let s = roi.cell_size();
        let centre = |c: Cell| [f64::from(c[1]) * s, -f64::from(c[0]) * s];
        let home = mission.plan.search.map_or(roi.start(), |x| x.launch);
        let swaps = mission.swaps();
        let robots: Vec<GridRobotRecord> = mission
            .team
            .robots
            .iter()
            .enumerate()
            .map(|(i, r)| GridRobotRecord {
                id: i,
                path: r.path.iter().map(|&c| centre(c)).collect(),
                cells: r.path.clone(),
                times: crate::sim::grid::arrival_times(r, &tm, &cost),
                scans: r
                    .scan_places
                    .iter()
                    .zip(&r.scan_times)
                    .map(|(&c, &t)| ScanRecord { at: centre(c), time: t })
                    .collect(),
                finish_time: r.clock,
                battery_swaps: swaps.get(i).copied().unwrap_or(0),
            })
            .collect();
        let tally = mission.team.tally();
        let time = mission.team.makespan();
        let visited = world.visited().len();
        let mapped = mission.plan.map.then(|| mission.marks.positive());
        let counts = roi.approximation_counts();
        let bounds = GridBounds::of_world(world, mission.plan.robots, &cost);
        let paper_model = cost.scan_time == 0.0
            && cost.move_time == 0.0
            && swaps.iter().all(|&w| w == 0)
            && mission.plan.search.is_none();
        Self {
            format: "stopscan-run/1".into(),
            environment: GridEnvironmentInfo {
                name: roi.name().into(),
                cells: roi.len(),
                cell_size: s,
                bounds: roi.bounds(),
                start: roi.start(),
                drift: world.drift(),
                true_area: roi.true_area(),
            },
            strategy: StrategyInfo {
                name: crate::strategy::grid::ALGORITHM_1.name.into(),
                params: serde_json::json!({
                    "robots": mission.plan.robots,
                    "battery_s": mission.plan.battery_s,
                    "search": mission.plan.search,
                }),
            },
            cost_model: cost,
            sensor: serde_json::to_value(world.sensor()).unwrap_or_default(),
            robots,
            metrics: GridMetrics {
                totals: RunTotals::new(&tally, time, &cost.price(&tally)),
                visited_cells: visited,
                covered_area: visited as f64 * s * s,
                coverage: visited as f64 / roi.len() as f64,
                all_home: mission.team.robots.iter().all(|r| r.done && r.at == home),
                mapped_cells: mapped.as_ref().map(Vec::len),
                iou: mapped.as_ref().map(|m| roi.iou(m)),
                c_out: counts.map(|c| c.0),
                c_in: counts.map(|c| c.1),
            },
            bounds: GridBoundsRecord {
                within_lemma1: paper_model
                    .then_some(time <= bounds.lemma1_upper * (1.0 + SAME_VALUE_REL)),
                competitive_ratio: (bounds.lemma2_lower > 0.0).then(|| time / bounds.lemma2_lower),
                eccentricity: roi.distances().values().copied().max().unwrap_or(0) as usize,
                bounds,
            },
            cells: roi.len(),
            failures: mission.failures(),
            seed,
            stopscan_version: crate::VERSION.into(),
        }
    }
}
