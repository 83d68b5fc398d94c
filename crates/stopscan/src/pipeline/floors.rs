//! `stopscan bench floors`: every polygon strategy, side by side, on real occupancy maps and
//! generated office floors, for a robot with a footprint, a range-limited sensor and a cost
//! model that makes scans expensive (by default a 0.2 m robot, 20 m lidar, 30 s per scan,
//! 0.5 m/s): scans, mission time, coverage of what the robot can see at all, unreachable
//! area, and the certified ratio against the lower bounds, per map and in total.
//!
//! Each run goes through [`super::explore::explore`], as `stopscan explore` runs it, so its
//! numbers are those of the run record. The offline greedy reference (in the configuration
//! space, with the same sensor) is computed once per map.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::explore::{ExploreError, ExploreOptions, explore};
use crate::io::Environment;
use crate::offline::polygon::ReferenceLimits;
use crate::protocol::CostModel;
use crate::protocol::polygon::Footprint;
use crate::render::{LineChart, Series};

/// How to run the benchmark.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorsOptions {
    /// A folder searched (one level of subfolders too) for ROS map `.yaml` files.
    pub data: Option<PathBuf>,
    /// Generated office floors added to the maps.
    pub offices: usize,
    /// The seed of the office floors.
    pub seed: u64,
    /// The strategies, in order.
    pub strategies: Vec<String>,
    /// The robot.
    pub footprint: Footprint,
    /// The sensor's range, metres.
    pub range: f64,
    /// The cost model.
    pub cost: CostModel,
    /// Seconds for each run's lower bounds.
    pub bounds_seconds: f64,
}

impl Default for FloorsOptions {
    /// The setting: a 0.2 m robot, 20 m range, 30 s per scan, 0.5 m/s, every
    /// strategy but `range_limited` (the paper's boundary follower, for short ranges), twelve
    /// offices.
    fn default() -> Self {
        Self {
            data: None,
            offices: 12,
            seed: 0,
            strategies: [
                "depth_first",
                "nearest_frontier",
                "greedy_nbv",
                "explore_lite",
                "cost_aware",
            ]
            .map(String::from)
            .to_vec(),
            footprint: Footprint::Disc { radius: 0.2 },
            range: 20.0,
            cost: CostModel { scan_time: 30.0, move_time: 0.0, speed: 0.5 },
            bounds_seconds: 2.0,
        }
    }
}

/// One run of the benchmark.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorRun {
    /// The strategy.
    pub strategy: String,
    /// Scans.
    pub scans: u64,
    /// Mission time, seconds.
    pub time: f64,
    /// Metres driven.
    pub distance: f64,
    /// Covered area over free area.
    pub coverage: f64,
    /// Covered area over the area visible from the reachable configuration space.
    pub coverage_of_reachable: f64,
    /// Free area no reachable viewpoint was found to see, m².
    pub unreachable_area: f64,
    /// Covered area over the area visible from the reachable configuration space inside the
    /// robot's body space (where its body can be).
    pub coverage_of_body_space: f64,
    /// Area visible from the reachable configuration space that no scan covered, in crevices
    /// narrower than the robot (outside its body space), m².
    pub unseen_in_crevices: f64,
    /// The lower bound on the time of any exploration that sees as much, seconds.
    pub time_lower: f64,
    /// `time / time_lower`.
    pub certified_ratio: Option<f64>,
    /// Wall-clock seconds of the exploration itself (the simulation, before the offline
    /// measurements).
    pub explore_seconds: f64,
    /// Why the run failed, if it did.
    pub error: Option<String>,
}

/// One map of the benchmark.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorMap {
    /// Its name.
    pub name: String,
    /// Vertices of its free space.
    pub vertices: usize,
    /// Free area, m².
    pub free_area: f64,
    /// Views of the offline greedy reference in the configuration space, same sensor.
    pub greedy_reference: Option<usize>,
    /// One run per strategy.
    pub runs: Vec<FloorRun>,
}

/// A strategy's totals over the maps.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorTotal {
    /// The strategy.
    pub strategy: String,
    /// Scans.
    pub scans: u64,
    /// Mission time, seconds.
    pub time: f64,
    /// The lowest coverage of the reachable-visible area over the maps.
    pub min_coverage_of_reachable: f64,
    /// The lowest coverage of the reachable-visible area inside the body space.
    pub min_coverage_of_body_space: f64,
    /// Runs that failed.
    pub failures: usize,
}

/// The benchmark's report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FloorsReport {
    /// `"stopscan-floors/1"`.
    pub format: String,
    /// The robot.
    pub footprint: Footprint,
    /// The range, metres.
    pub range: f64,
    /// The cost model.
    pub cost_model: CostModel,
    /// Per map.
    pub maps: Vec<FloorMap>,
    /// Per strategy, over all maps.
    pub totals: Vec<FloorTotal>,
    /// The library version.
    pub stopscan_version: String,
}

impl FloorsReport {
    /// Mission time per map, one line per strategy (maps in the report's order on x).
    pub fn chart(&self) -> LineChart {
        let series = self
            .totals
            .iter()
            .map(|t| {
                let pts = self
                    .maps
                    .iter()
                    .enumerate()
                    .filter_map(|(i, m)| {
                        m.runs
                            .iter()
                            .find(|r| r.strategy == t.strategy && r.error.is_none())
                            .map(|r| ((i + 1) as f64, r.time))
                    })
                    .collect();
                Series::line(&t.strategy, pts).with_markers()
            })
            .collect();
        LineChart {
            title: "Mission time per floor plan".into(),
            subtitle: format!(
                "robot clearance {:.2} m, range {} m, {} s per scan, {} m/s; maps: {}",
                self.footprint.clearance(),
                self.range,
                self.cost_model.scan_time,
                self.cost_model.speed,
                self.maps.iter().map(|m| m.name.as_str()).collect::<Vec<_>>().join(", ")
            ),
            x_label: "floor plan (in the order listed)".into(),
            y_label: "mission time (s)".into(),
            series,
        }
    }
}

/// What the benchmark is doing.
#[derive(Debug, Clone, PartialEq)]
pub enum FloorsEvent {
    /// The runs to do.
    Started {
        /// How many.
        runs: u64,
    },
    /// One run finished.
    RunDone {
        /// The map.
        map: String,
        /// The strategy.
        strategy: String,
    },
}

/// The ROS map `.yaml` files in `dir` and its subfolders (one level), sorted.
///
/// # Errors
/// [`ExploreError::ReadDir`] if `dir` cannot be read.
pub fn map_files(dir: &Path) -> Result<Vec<PathBuf>, ExploreError> {
    let read = |d: &Path| -> Result<Vec<PathBuf>, ExploreError> {
        let mut v: Vec<PathBuf> = std::fs::read_dir(d)
            .map_err(|source| ExploreError::ReadDir { path: d.to_path_buf(), source })?
            .filter_map(Result::ok)
            .map(|e| e.path())
            .collect();
        v.sort();
        Ok(v)
    };
    let mut out = Vec::new();
    for p in read(dir)? {
        if p.is_dir() {
            out.extend(read(&p)?.into_iter().filter(|q| is_yaml(q)));
        } else if is_yaml(&p) {
            out.push(p);
        }
    }
    Ok(out)
}

fn is_yaml(p: &Path) -> bool {
    p.extension().and_then(|e| e.to_str()).is_some_and(|e| matches!(e, "yaml" | "yml"))
}

/// Runs the benchmark: every strategy on every map of `options.data` and on
/// `options.offices` generated office floors. `on` hears each finished run.
///
/// # Errors
/// [`ExploreError`] if the data folder cannot be read, a map does not load, or a strategy
/// is unknown. A run that fails is reported in its row, not as an error.
pub fn floors(
    options: &FloorsOptions,
    on: &mut dyn FnMut(FloorsEvent),
) -> Result<FloorsReport, ExploreError> {
    for s in &options.strategies {
        crate::strategy::polygon::REGISTRY.get(s)?;
    }
    let inputs = inputs(options)?;
    on(FloorsEvent::Started { runs: (inputs.len() * options.strategies.len()) as u64 });
    let mut maps = Vec::new();
    for (name, env) in &inputs {
        let mut runs = Vec::new();
        let mut greedy = None;
        for strategy in &options.strategies {
            runs.push(run_one(name, env, strategy, options));
            if greedy.is_none() {
                greedy = greedy_reference(env, options);
            }
            on(FloorsEvent::RunDone { map: name.clone(), strategy: strategy.clone() });
        }
        maps.push(FloorMap {
            name: name.clone(),
            vertices: env.domain.vertex_count(),
            free_area: env.domain.area(),
            greedy_reference: greedy,
            runs,
        });
    }
    let totals = options
        .strategies
        .iter()
        .map(|s| {
            let runs: Vec<&FloorRun> =
                maps.iter().flat_map(|m| m.runs.iter().filter(|r| &r.strategy == s)).collect();
            FloorTotal {
                strategy: s.clone(),
                scans: runs.iter().map(|r| r.scans).sum(),
                time: runs.iter().map(|r| r.time).sum(),
                min_coverage_of_reachable: runs
                    .iter()
                    .map(|r| r.coverage_of_reachable)
                    .fold(f64::INFINITY, f64::min),
                min_coverage_of_body_space: runs
                    .iter()
                    .map(|r| r.coverage_of_body_space)
                    .fold(f64::INFINITY, f64::min),
                failures: runs.iter().filter(|r| r.error.is_some()).count(),
            }
        })
        .collect();
    Ok(FloorsReport {
        format: "stopscan-floors/1".into(),
        footprint: options.footprint.clone(),
        range: options.range,
        cost_model: options.cost,
        maps,
        totals,
        stopscan_version: crate::VERSION.into(),
    })
}

/// The maps of `options.data` and the generated office floors, named.
fn inputs(options: &FloorsOptions) -> Result<Vec<(String, Environment)>, ExploreError> {
    let mut inputs: Vec<(String, Environment)> = Vec::new();
    if let Some(dir) = &options.data {
        let files = map_files(dir)?;
        if files.is_empty() {
            return Err(ExploreError::NoFiles(dir.clone()));
        }
        for f in files {
            let name = f.file_stem().and_then(|s| s.to_str()).unwrap_or("map").to_string();
            inputs.push((name, crate::io::read_environment(&f)?));
        }
    }
    for i in 0..options.offices {
        // Sizes and desks vary with the seed, as `bench explore` draws them.
        let seed = options.seed.wrapping_add(i as u64);
        let rooms = 2 + (seed.wrapping_mul(7) % 5) as usize;
        let desks = (seed.wrapping_mul(13) % (3 * rooms as u64)) as usize;
        let inst = crate::generate::office(rooms, desks, seed).map_err(|e| {
            ExploreError::Load(crate::io::LoadError::Invalid {
                file: format!("office-{i}"),
                source: e,
            })
        })?;
        // No start: the roomiest point of the configuration space, as on the maps.
        let env = Environment::new(inst.domain);
        inputs.push((format!("office-{i}"), env));
    }
    Ok(inputs)
}

/// One strategy on one map, as `stopscan explore` runs it.
fn run_one(name: &str, env: &Environment, strategy: &str, options: &FloorsOptions) -> FloorRun {
    let o = ExploreOptions {
        strategy: strategy.to_string(),
        cost: options.cost,
        range: Some(options.range),
        footprint: options.footprint.clone(),
        limits: ReferenceLimits {
            greedy_max_vertices: 0,
            optimum_seconds: 0.0,
            bounds_seconds: options.bounds_seconds,
            ..ReferenceLimits::default()
        },
        seed: options.seed,
        ..ExploreOptions::default()
    };
    let t0 = Instant::now();
    let mut explored: Option<f64> = None;
    let result = explore(name, env, None, &o, &mut |m: &str| {
        if explored.is_none() && m.starts_with("offline") {
            explored = Some(t0.elapsed().as_secs_f64());
        }
    });
    let explore_seconds = explored.unwrap_or_else(|| t0.elapsed().as_secs_f64());
    match result {
        Ok(x) => {
            let r = &x.record;
            let robot = r.robot.as_ref();
            FloorRun {
                strategy: strategy.to_string(),
                scans: r.metrics.totals.scans,
                time: r.metrics.totals.time,
                distance: r.metrics.totals.distance,
                coverage: r.metrics.coverage,
                coverage_of_reachable: robot
                    .map_or(r.metrics.coverage, |b| b.coverage_of_reachable),
                unreachable_area: robot.map_or(0.0, |b| b.unreachable_area),
                coverage_of_body_space: robot
                    .map_or(r.metrics.coverage, |b| b.coverage_of_body_space),
                unseen_in_crevices: robot.map_or(0.0, |b| b.unseen_in_crevices),
                time_lower: r.bounds.time_lower,
                certified_ratio: r.bounds.certified_ratio,
                explore_seconds,
                error: x.failure.map(|f| f.to_string()),
            }
        }
        Err(e) => FloorRun {
            strategy: strategy.to_string(),
            scans: 0,
            time: 0.0,
            distance: 0.0,
            coverage: 0.0,
            coverage_of_reachable: 0.0,
            unreachable_area: 0.0,
            coverage_of_body_space: 0.0,
            unseen_in_crevices: 0.0,
            time_lower: 0.0,
            certified_ratio: None,
            explore_seconds,
            error: Some(e.to_string()),
        },
    }
}

/// The greedy reference of a map in its configuration space, from the default start.
fn greedy_reference(env: &Environment, options: &FloorsOptions) -> Option<usize> {
    let world = crate::world::polygon::PolygonWorld::with_robot(
        env.domain.clone(),
        Some(options.range),
        &options.footprint,
        env.default_start(),
    )
    .ok()?;
    let start =
        world.reach().map_or_else(|| world.interior_point(), crate::world::polygon::Reach::start);
    let g = crate::offline::polygon::reach::greedy(&world, start);
    Some(g.viewpoints.len())
}
