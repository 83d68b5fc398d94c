//! One exploration of a polygon environment, as `stopscan explore --env FILE` and the main job
//! run it: load the environment, run the strategy (streaming the event trace), compute the
//! offline references, and build the run record and the scene.
//!
//! ```no_run
//! use stopscan::pipeline::explore::{ExploreOptions, explore_file};
//! let run = explore_file("office.geojson".as_ref(), None, &ExploreOptions::default(), &mut |_| {})?;
//! println!("{} scans", run.record.metrics.totals.scans);
//! # Ok::<(), stopscan::pipeline::explore::ExploreError>(())
//! ```

use std::path::{Path, PathBuf};

use super::{InvalidParameter, Progress};
use crate::algorithm::visibility::VisibilityError;
use crate::io::ros_map::RosMapOptions;
use crate::io::{Environment, LoadError};
use crate::kernel::{Num, Point};
use crate::offline::polygon::{OfflineError, ReferenceLimits};
use crate::protocol::polygon::{Footprint, PolygonObservation, RobotSetup, Sensor};
use crate::protocol::{Action, CostModel, Feedback};
use crate::run_record::{RobotInfo, RunRecord, SensorInfo};
use crate::sim::lidar::{LidarRun, LidarSetup};
use crate::sim::polygon::{PolygonSimError, Reframe};
use crate::sim::{Fanout, JsonLinesTrace, Observer};
use crate::strategy::UnknownStrategy;
use crate::world::polygon::{PolygonWorld, WorldError};

/// The built-in office floor of the main job (`stopscan generate office --size 6 --desks 16`),
/// as GeoJSON with its start.
pub const OFFICE_GEOJSON: &str = include_str!("../../../../fixtures/office.geojson");

/// The longest budget a reference stage may be given: a day.
pub const MAX_BUDGET_SECONDS: f64 = 86_400.0;

/// How to explore (and, for [`super::sweep`], how to sweep: `seed` and `trace` are not used
/// there, and `strategy` may be `all`).
#[derive(Debug, Clone, PartialEq)]
pub struct ExploreOptions {
    /// The polygon registry's name of the strategy.
    pub strategy: String,
    /// The cost model every run is priced with.
    pub cost: CostModel,
    /// The sensor range (metres), if limited.
    pub range: Option<f64>,
    /// The robot's footprint (a point: the paper's model).
    pub footprint: Footprint,
    /// The sensor's beams per revolution (`None`: continuous).
    pub beams: Option<u32>,
    /// The smallest feature the sensor resolves, metres.
    pub min_feature: f64,
    /// The shortest window worth a trip, metres (`None`: [`default_min_window`]).
    pub min_window: Option<f64>,
    /// The smallest enclosed pocket worth a trip, as a share of the area seen (`None`:
    /// [`default_min_pocket`]).
    pub min_pocket: Option<f64>,
    /// The largest pocket the rule may leave, square metres ([`DEFAULT_POCKET_CAP`]).
    pub pocket_cap: f64,
    /// The most the pockets the rule leaves may hold in all, as a share of the area seen
    /// ([`DEFAULT_POCKET_BUDGET`]).
    pub pocket_budget: f64,
    /// The budgets of the offline references.
    pub limits: ReferenceLimits,
    /// The seed recorded in the run record.
    pub seed: u64,
    /// Where to stream the event trace (JSON lines), if anywhere.
    pub trace: Option<PathBuf>,
    /// Drive from simulated raw laser scans with this lidar (`None`: the exact sensor).
    pub lidar: Option<crate::world::lidar::Lidar>,
    /// Odometry's drift with [`ExploreOptions::lidar`]: position error per metre driven.
    pub odometry_drift: f64,
    /// With [`ExploreOptions::lidar`]: the relay rule's threshold
    /// ([`LidarSetup::relay`], metres; 0 never relays).
    pub relay: f64,
    /// ROS maps: the boundary simplification tolerance in metres
    /// ([`crate::io::ros_map::RosMapOptions::simplify`]; `None`: the loader's default, 1.5
    /// cells). Other formats are read as they are.
    pub simplify: Option<f64>,
    /// Stop the run after this many scans, done or not (`None`: only the simulator's own
    /// limits); a run stopped so is recorded with the reason, as a run cut short.
    pub max_scans: Option<u64>,
}

impl Default for ExploreOptions {
    /// The paper's algorithm, the default cost model, an unlimited sensor, the default
    /// budgets, seed 0, no trace, the default map simplification.
    fn default() -> Self {
        Self {
            strategy: "depth_first".into(),
            cost: CostModel::default(),
            range: None,
            footprint: Footprint::Point,
            beams: None,
            min_feature: 0.0,
            min_window: None,
            min_pocket: None,
            pocket_cap: DEFAULT_POCKET_CAP,
            pocket_budget: DEFAULT_POCKET_BUDGET,
            limits: ReferenceLimits::default(),
            seed: 0,
            trace: None,
            simplify: None,
            lidar: None,
            odometry_drift: 0.0,
            relay: crate::sim::lidar::RELAY,
            max_scans: None,
        }
    }
}

/// How much the strategies' planning clearance grows over the robot's on raw scans: walls
/// read from noisy scans, and a pose known only to ICP's precision, put the true walls up to
/// this much nearer than planned (3σ of the range noise plus a pose error of a few
/// centimetres after alignment).
pub fn planning_margin(sigma: f64) -> f64 {
    0.05 + sigma
}

/// The robot as strategies plan with it on raw scans from a sensor with range noise `sigma`:
/// its clearance grown by [`planning_margin`] (a disc), and a window part closed where another
/// scan saw a wall along it within that margin ([`Sensor::wall_tolerance`]).
///
/// # Panics
/// Never: the clearance and the margin are finite and not negative.
pub fn raw_scan_planning(setup: &RobotSetup, sigma: f64) -> RobotSetup {
    let margin = planning_margin(sigma);
    RobotSetup {
        cost: setup.cost,
        footprint: Footprint::disc(setup.footprint.clearance() + margin)
            .expect("a finite clearance and margin"),
        sensor: Sensor { wall_tolerance: margin, ..setup.sensor },
    }
}

/// The default of the window rule's `min_window`: a window narrower than the robot, or no
/// longer than two cells of the occupancy map it was traced from (a pixel step of a wall
/// with its rounding), is not worth a trip. 0 for a point robot on a polygon input: every
/// window counts, as in the paper.
pub fn default_min_window(footprint: &Footprint, cell_size: Option<f64>) -> f64 {
    footprint.width().max(cell_size.map_or(0.0, |c| 2.0 * c))
}

/// The default cap on the pockets the rule may leave: 2 m², about a desk with the space
/// around it (`bench floors`: 12,268 s for `cost_aware` with it, 12,058 s without).
pub const DEFAULT_POCKET_CAP: f64 = 2.0;

/// The default budget of the pockets the window rule leaves, in all: 1% of the area seen.
/// Each pocket is counted at its hole's area, obstacle included, so what they hide is less.
///
/// Measured with `bench floors` (budgets of 0.5%, 1% and 1.5%) and on 600 runs from raw scans
/// (five strategies × office, depot, warehouse × seeds 1 to 40; README, "A budget for the
/// pockets"). Without a budget, the pockets each below 0.5% added up on `depot` from raw
/// scans: 6 of its 200 runs saw less than 99% of the area visible from the reachable region;
/// with 1% none did, and on `bench floors` the lowest coverage rose from 99.22% to 99.38%.
/// At 0.5% `cost_aware` lost its lead over `explore_lite` (0.763 × its mission time, the
/// issue asks 0.75).
pub const DEFAULT_POCKET_BUDGET: f64 = 0.01;

/// The default of the window rule's `min_pocket`: where the window rule applies by default
/// (a robot with a footprint, or an occupancy map), a pocket of unseen space enclosed by what
/// was seen and smaller than 0.5% of the area seen so far is not worth a trip; 0 for a point
/// robot on a polygon input (every pocket counts, as in the paper).
///
/// 0.5% was measured with `bench floors` (0.5%, 0.75% and 1%): at 0.75% and above, `depot`,
/// whose shelves and pillars leave many pockets, fell below 99% coverage for some
/// strategies; at 0.5% every strategy kept at least 99.2% of the area visible from the
/// reachable region on every map. The share alone let whole small rooms go on willow-full
/// (0.5% of 2,000 m² is 10 m²): hence the cap, [`DEFAULT_POCKET_CAP`].
pub fn default_min_pocket(footprint: &Footprint, cell_size: Option<f64>) -> f64 {
    if footprint.is_point() && cell_size.is_none() { 0.0 } else { 0.005 }
}

impl ExploreOptions {
    /// The robot as strategies are told about it, in `env` (whose cell size sets the default
    /// window rule).
    pub fn robot(&self, env: &Environment) -> RobotSetup {
        self.robot_for(env.cell_size)
    }

    /// The robot as [`ExploreOptions::robot`] makes it, for a map of `cell_size` (an
    /// occupancy map's cell, metres; `None` for a polygon): what a strategy driven outside the
    /// simulator (a Python driver) is built for.
    pub fn robot_for(&self, cell_size: Option<f64>) -> RobotSetup {
        RobotSetup {
            cost: self.cost,
            footprint: self.footprint.clone(),
            sensor: Sensor {
                range: self.sensor_range(),
                beams: self.beams.or(self.lidar.map(|l| l.beams as u32)),
                min_feature: self.min_feature,
                min_window: self
                    .min_window
                    .unwrap_or_else(|| default_min_window(&self.footprint, cell_size)),
                min_pocket: self
                    .min_pocket
                    .unwrap_or_else(|| default_min_pocket(&self.footprint, cell_size)),
                pocket_cap: self.pocket_cap,
                pocket_budget: Some(self.pocket_budget),
                wall_tolerance: self.lidar.map_or(0.0, |l| planning_margin(l.sigma)),
            },
        }
    }

    /// On raw scans ([`ExploreOptions::lidar`]): the robot as strategies plan with it
    /// ([`raw_scan_planning`]) and the simulated robot's setup (gaps on a wall line shorter
    /// than the window rule's minimum, and at least 0.4 m, are read as wall); else the robot
    /// as it is.
    pub fn raw_scan_setup(&self, setup: &RobotSetup) -> (RobotSetup, Option<LidarSetup>) {
        let Some(l) = self.lidar else { return (setup.clone(), None) };
        let mut s = LidarSetup::new(l, self.odometry_drift, self.seed);
        s.ingest = s.ingest.bridging(setup.sensor.min_window);
        s.relay = self.relay;
        (raw_scan_planning(setup, l.sigma), Some(s))
    }

    /// The sensor's range: the lidar's with raw scans, else [`ExploreOptions::range`].
    pub fn sensor_range(&self) -> Option<f64> {
        self.lidar.map_or(self.range, |l| Some(l.range_max))
    }

    /// The sensor's parameters are finite and not negative, and a beam count is positive.
    ///
    /// # Errors
    /// [`ExploreError::Parameter`] naming the first that is not.
    pub fn check_sensor(&self) -> Result<(), ExploreError> {
        let nonneg = |name: &'static str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(())
            } else {
                Err(InvalidParameter::new(name, "be a finite number of metres >= 0", &Num(v)))
            }
        };
        nonneg("min_feature", self.min_feature)?;
        if let Some(w) = self.min_window {
            nonneg("min_window", w)?;
        }
        if let Some(s) = self.min_pocket
            && !(0.0..=1.0).contains(&s)
        {
            return Err(InvalidParameter::new(
                "min_pocket",
                "be a share of the area seen, in [0, 1]",
                &Num(s),
            )
            .into());
        }
        if !(0.0..=1.0).contains(&self.pocket_budget) {
            return Err(InvalidParameter::new(
                "pocket_budget",
                "be a share of the area seen, in [0, 1]",
                &Num(self.pocket_budget),
            )
            .into());
        }
        if !(self.pocket_cap.is_finite() && self.pocket_cap >= 0.0) {
            return Err(InvalidParameter::new(
                "pocket_cap",
                "be a finite number of square metres >= 0",
                &Num(self.pocket_cap),
            )
            .into());
        }
        if self.beams == Some(0) {
            return Err(InvalidParameter::new("beams", "be at least 1", &0).into());
        }
        if !(self.odometry_drift.is_finite() && (0.0..=0.5).contains(&self.odometry_drift)) {
            return Err(InvalidParameter::new(
                "odometry_drift",
                "be a share of the distance driven, in [0, 0.5]",
                &Num(self.odometry_drift),
            )
            .into());
        }
        nonneg("relay", self.relay)?;
        if self.odometry_drift > 0.0 && self.lidar.is_none() {
            return Err(InvalidParameter::new(
                "odometry_drift",
                "come with raw scans (--sensor lidar): the exact sensor has no odometry",
                &Num(self.odometry_drift),
            )
            .into());
        }
        if let (Some(l), Some(r)) = (self.lidar, self.range)
            && r != l.range_max
        {
            return Err(InvalidParameter::new(
                "range",
                format!(
                    "equal the lidar's max ({}) with --sensor lidar, or be left out",
                    Num(l.range_max)
                ),
                &Num(r),
            )
            .into());
        }
        Ok(())
    }
}

/// A finished exploration (or one the simulator ended early, see `failure`).
#[derive(Debug, Clone)]
pub struct Exploration {
    /// The run record (`error` set when the run was ended early).
    pub record: RunRecord,
    /// The scene: domain, regions seen, path and numbered scans, as SVG.
    pub svg: String,
    /// What the browser replay is drawn from ([`Exploration::report`]).
    pub replay: crate::render::PolygonReplay,
    /// Why the run was ended before the strategy was done (in the input's coordinates); the
    /// record is then the run so far, and not measured against the greedy reference or the
    /// optimum.
    pub failure: Option<PolygonSimError>,
}

impl Exploration {
    /// `report.html`: the run replayed step by step in the browser, beside its metrics,
    /// bounds and certified ratio ([`crate::render::polygon_report`]).
    pub fn report(&self) -> String {
        crate::render::polygon_report(&self.replay, &self.record)
    }

    /// The run as an MCAP recording for Foxglove ([`crate::render::polygon_mcap`]).
    ///
    /// # Errors
    /// [`crate::render::McapError`] if the recording cannot be made.
    pub fn mcap(&self) -> Result<Vec<u8>, crate::render::McapError> {
        crate::render::polygon_mcap(&self.replay, &self.record)
    }
}

/// Why an exploration (or a sweep) could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExploreError {
    /// The sensor range (`range`) is not a finite positive number of metres, or a reference
    /// budget (`optimum_seconds`, `bounds_seconds`) is not between 0 and
    /// [`MAX_BUDGET_SECONDS`].
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// `range_limited` was asked for without a range.
    #[error(
        "range_limited needs a sensor range (metres); for an unlimited range the paper's algorithm is depth_first"
    )]
    RangeNeeded,
    /// The strategy is not in the registry (a sweep also accepts `all`).
    #[error(transparent)]
    Strategy(#[from] UnknownStrategy),
    /// The start lies outside the free space (input coordinates).
    #[error("the start ({}, {}) is outside the free space", Num(.0[0]), Num(.0[1]))]
    StartOutside(Point),
    /// A lidar run (`--sensor lidar`) starts on a wall (input coordinates): the beams that
    /// leave the free space there would meet no wall, and read as open space beyond it.
    #[error(
        "the start ({}, {}) lies on a wall: a lidar scans from inside the free space (give a start off the boundary)",
        Num(.0[0]),
        Num(.0[1])
    )]
    StartOnWall(Point),
    /// The robot's footprint fits nowhere, or not at the start (input coordinates).
    #[error(transparent)]
    World(#[from] WorldError),
    /// The environment file does not load.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// The free space could not be preprocessed.
    #[error(transparent)]
    Visibility(#[from] VisibilityError),
    /// An offline reference failed.
    #[error(transparent)]
    Offline(#[from] OfflineError),
    /// The event trace could not be written.
    #[error("cannot write {}", .path.display())]
    Trace {
        /// The trace file.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// A sweep's folder could not be read.
    #[error("cannot read {}", .path.display())]
    ReadDir {
        /// The folder.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// A sweep's folder holds no environment file.
    #[error("{} holds no environment files (.geojson, .wkt, .pol, .yaml, .txt)", .0.display())]
    NoFiles(PathBuf),
    /// A folder sweep was given a robot (a footprint or a window rule): sweeps run the paper's
    /// point robot with an ideal sensor only.
    #[error(
        "a folder sweep runs a point robot with an ideal sensor; {0} applies to one environment (explore --env FILE) or to bench floors --data DIR"
    )]
    RobotInSweep(&'static str),
    /// A folder sweep was given a scan limit: its rows are whole runs, each measured against
    /// the paper's bounds.
    #[error(
        "a folder sweep runs every strategy to its end; --max-scans applies to one environment (explore --env FILE)"
    )]
    LimitInSweep,
}

/// The range is a finite positive distance, and `range_limited`, named explicitly, has one
/// (the paper's algorithm for an unlimited sensor is `depth_first`).
///
/// # Errors
/// [`ExploreError::Parameter`] (`range`) or [`ExploreError::RangeNeeded`].
pub fn check_range(strategy: &str, range: Option<f64>) -> Result<(), ExploreError> {
    if let Some(r) = range
        && !(r.is_finite() && r > 0.0)
    {
        return Err(
            InvalidParameter::new("range", "be a positive number of metres", &Num(r)).into()
        );
    }
    if strategy == "range_limited" && range.is_none() {
        return Err(ExploreError::RangeNeeded);
    }
    Ok(())
}

/// A map simplification tolerance, if given, is a finite non-negative number of metres.
///
/// # Errors
/// [`ExploreError::Parameter`] (`simplify`).
pub fn check_simplify(simplify: Option<f64>) -> Result<(), ExploreError> {
    if let Some(t) = simplify
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(InvalidParameter::new(
            "simplify",
            "be a finite non-negative number of metres",
            &Num(t),
        )
        .into());
    }
    Ok(())
}

/// The reference budgets are between 0 and [`MAX_BUDGET_SECONDS`].
///
/// # Errors
/// [`ExploreError::Parameter`] naming the first budget that is not.
pub fn check_budgets(limits: &ReferenceLimits) -> Result<(), ExploreError> {
    for (name, value) in
        [("optimum_seconds", limits.optimum_seconds), ("bounds_seconds", limits.bounds_seconds)]
    {
        if !(value.is_finite() && (0.0..=MAX_BUDGET_SECONDS).contains(&value)) {
            return Err(
                InvalidParameter::new(name, "be between 0 and 86400 seconds", &value).into()
            );
        }
    }
    Ok(())
}

/// Explores the environment in `path` (any format [`crate::io::read_environment`] reads),
/// from `start` (input coordinates) or the file's default start
/// ([`crate::io::sweep::default_start`]). The run is named after the file's stem. A ROS map
/// is read with `start` (the free region containing it is kept, and the simplification
/// keeps it inside) and `options.simplify`.
///
/// # Errors
/// [`ExploreError`]: bad options, a file that does not load, a start outside the free space,
/// a trace that cannot be written, or an offline reference that fails. A run the simulator
/// ends early is not an error: see [`Exploration::failure`].
pub fn explore_file(
    path: &Path,
    start: Option<Point>,
    options: &ExploreOptions,
    progress: Progress,
) -> Result<Exploration, ExploreError> {
    check_range(&options.strategy, options.sensor_range())?;
    options.check_sensor()?;
    check_simplify(options.simplify)?;
    let map = RosMapOptions { start, simplify: options.simplify, ..RosMapOptions::default() };
    let env = crate::io::read_environment_with(path, &map)?;
    let start = start.map(|s| env.frame.to_local(s));
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("environment");
    explore(name, &env, start, options, progress)
}

/// The main job: the paper's algorithm on the built-in office floor ([`OFFICE_GEOJSON`]),
/// with the exact optimum left out (the office's 164 vertices are beyond what it proves
/// within a few seconds, and a search cut short by the clock would make the result depend on
/// the machine).
///
/// # Errors
/// As [`explore`].
pub fn office(seed: u64, progress: Progress) -> Result<Exploration, ExploreError> {
    let env = crate::io::text_formats::parse_geojson(OFFICE_GEOJSON, "built-in office floor")?;
    let options = ExploreOptions {
        limits: ReferenceLimits { optimum_max_vertices: 100, ..ReferenceLimits::default() },
        seed,
        ..ExploreOptions::default()
    };
    explore("office (built-in)", &env, None, &options, progress)
}

/// Counts scans and metres for the progress line, and stops the run at the scan limit.
struct Counter<'a, 'p> {
    progress: &'a mut Progress<'p>,
    scans: u64,
    metres: f64,
    /// [`ExploreOptions::max_scans`].
    limit: Option<u64>,
    /// Whether the run was stopped at the limit.
    stopped: bool,
}

impl<'a, 'p> Counter<'a, 'p> {
    fn new(progress: &'a mut Progress<'p>, limit: Option<u64>) -> Self {
        Self { progress, scans: 0, metres: 0.0, limit, stopped: false }
    }
}

impl<O> Observer<Point, O> for Counter<'_, '_> {
    fn on_move(&mut self, _robot: usize, _to: &Point, metres: f64) -> std::ops::ControlFlow<()> {
        self.metres += metres;
        std::ops::ControlFlow::Continue(())
    }
    fn on_scan(&mut self, _robot: usize, _at: &Point, _o: &O) -> std::ops::ControlFlow<()> {
        self.scans += 1;
        (self.progress)(&format!("{} scans, {:.1} m", self.scans, self.metres));
        if self.limit.is_some_and(|n| self.scans >= n) {
            self.stopped = true;
            return std::ops::ControlFlow::Break(());
        }
        std::ops::ControlFlow::Continue(())
    }
}

/// Explores `env` from `start` (local frame; by default the file's start, else a point
/// inside the free space, or with a footprint the roomiest point of its configuration space)
/// and measures the run: the run record (in the input's coordinates), the scene, and the
/// event trace streamed to `options.trace`. `progress` hears the scans and metres so far,
/// then the offline stage being computed.
///
/// # Errors
/// As [`explore_file`].
pub fn explore(
    name: &str,
    env: &Environment,
    start: Option<Point>,
    options: &ExploreOptions,
    mut progress: Progress,
) -> Result<Exploration, ExploreError> {
    let o = options;
    check_range(&o.strategy, o.sensor_range())?;
    check_budgets(&o.limits)?;
    o.check_sensor()?;
    let setup = o.robot(env);
    let (plan, lidar) = o.raw_scan_setup(&setup);
    let mut strategy = crate::strategy::polygon::build_for(&o.strategy, &plan)?;
    let frame = env.frame;
    let start = start.or_else(|| env.default_start());
    if let Some(s) = start
        && env.domain.locate(s) == crate::geometry::Location::Outside
    {
        return Err(ExploreError::StartOutside(frame.to_input(s)));
    }
    let world =
        PolygonWorld::with_robot(env.domain.clone(), setup.sensor.range, &o.footprint, start)
            .map_err(|e| match e {
                WorldError::StartBlocked { start, clearance } => {
                    WorldError::StartBlocked { start: frame.to_input(start), clearance }
                }
                e => e,
            })?;
    let start = match (start, world.reach()) {
        (_, Some(r)) => r.start(),
        (Some(s), None) => s,
        (None, None) => world.interior_point(),
    };
    if world.scan(start).is_err() {
        return Err(ExploreError::StartOutside(frame.to_input(start)));
    }
    if lidar.is_some() && env.domain.locate(start) == crate::geometry::Location::Boundary {
        return Err(ExploreError::StartOnWall(frame.to_input(start)));
    }
    let mut counter = Counter::new(&mut progress, o.max_scans);
    let mut drive = |observer: &mut dyn Observer<Point, PolygonObservation>| {
        Driven::run(&world, start, &o.cost, strategy.as_mut(), lidar.as_ref(), observer)
    };
    let driven = match &o.trace {
        None => drive(&mut counter),
        Some(path) => {
            let cannot = |source| ExploreError::Trace { path: path.clone(), source };
            let file = std::fs::File::create(path).map_err(cannot)?;
            let mut trace = JsonLinesTrace::new(std::io::BufWriter::new(file));
            let driven = {
                let mut reframed = Reframe { inner: &mut trace, frame };
                let observers: Vec<&mut dyn Observer<Point, PolygonObservation>> =
                    vec![&mut reframed, &mut counter];
                let mut all = Fanout(observers);
                drive(&mut all)
            };
            if let Some(e) = trace.error {
                return Err(cannot(e));
            }
            driven
        }
    };
    let Driven { run, mut failure, raw } = driven;
    if counter.stopped && failure.is_none() {
        failure = cut_at_limit(strategy.as_mut(), &run, raw.as_ref(), counter.scans);
    }
    let failure = failure.map(|e| e.map_places(|p| frame.to_input(p)));
    // A run cut short is not measured against the offline references (they take time, and a
    // ratio of an unfinished run means nothing); its record says why it ended.
    let mut limits = if failure.is_some() { ReferenceLimits::BOUNDS_ONLY } else { o.limits };
    // A robot with a footprint or a window rule sets out to see only part of the free space:
    // the lower bounds then count witnesses in what the run saw (valid for any exploration
    // that sees as much), and the point robot's references over the whole space do not
    // apply; a footprint gets its own greedy reference.
    let partial = world.reach().is_some() || !setup.sensor.excludes_nothing();
    let seen = partial.then(|| {
        let polys: Vec<Vec<Point>> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
        crate::algorithm::region::Region::union_all(&polys)
    });
    if partial {
        limits.greedy_max_vertices = 0;
        limits.optimum_seconds = 0.0;
    }
    let mut refs = crate::offline::polygon::references_within(
        world.visibility(),
        start,
        setup.sensor.range,
        limits,
        seen.as_ref(),
        &mut |stage| progress(&format!("offline: {stage}")),
    )?;
    if world.reach().is_some() && failure.is_none() && o.limits.greedy_max_vertices > 0 {
        progress("offline: greedy reference in the configuration space");
        refs.greedy = Some(crate::offline::polygon::reach::greedy(&world, start));
    }
    let (svg, replay) = pictures(env, &world, &run, raw.as_ref());
    let mut record = RunRecord::polygon(name, &world, &o.strategy, &o.cost, &run, &refs, o.seed);
    record.sensor = SensorInfo::of(&setup.sensor, &strategy.skipped());
    // A footprint makes the run partial, so what it saw is at hand.
    if let (Some(reach), Some(seen)) = (world.reach(), seen.as_ref()) {
        progress("offline: the area visible from the reachable configuration space");
        let skipped = strategy.skipped();
        record.robot = Some(robot_info(&world, reach, &setup, &run, &record, &skipped, seen));
    }
    if let (Some(r), Some(l)) = (&raw, &lidar) {
        let margin = o.lidar.map_or(0.0, |l| planning_margin(l.sigma));
        record.raw_scans = Some(crate::run_record::RawScanInfo::of(r, l, margin));
    }
    let mut record = record.in_frame(&frame);
    record.error = failure.as_ref().map(ToString::to_string);
    Ok(Exploration { record, svg, replay, failure })
}

/// A run stopped at its scan limit after `scans` scans: cut short unless the strategy, told
/// of the last scan as it saw it (from raw scans, the region read from the scan), is done
/// (then the run is the unlimited one).
fn cut_at_limit(
    strategy: &mut dyn crate::strategy::polygon::PolygonStrategy,
    run: &crate::sim::polygon::PolygonRun,
    raw: Option<&LidarRun>,
    scans: u64,
) -> Option<PolygonSimError> {
    let last = raw.map_or(run.scans.last(), |r| r.observations.last()).cloned();
    let done =
        last.is_some_and(|obs| matches!(strategy.act(&Feedback::Scanned(obs)), Action::Done));
    (!done)
        .then(|| crate::sim::SimError::ScanLimit { strategy: strategy.name().to_string(), scans })
}

/// The scene (SVG) and the browser replay's data of `run` in `world` (on `env`'s domain).
fn pictures(
    env: &Environment,
    world: &PolygonWorld,
    run: &crate::sim::polygon::PolygonRun,
    raw: Option<&LidarRun>,
) -> (String, crate::render::PolygonReplay) {
    let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
    let cspace: Option<Vec<Vec<Vec<Point>>>> =
        world.reach().map(|r| vec![r.domain().rings().to_vec()]);
    let relays: Option<Vec<bool>> = raw.map(|r| r.stops.iter().map(|s| s.relay).collect());
    let svg = crate::render::exploration_svg(
        &env.domain,
        &regions,
        &run.path,
        crate::render::SceneExtras { cspace: cspace.as_deref(), relays: relays.as_deref() },
    );
    let replay = crate::render::PolygonReplay {
        domain: env.domain.clone(),
        cspace,
        regions,
        path: run.path.clone(),
        steps: run.scan_tallies.clone(),
        scan_times: run.scan_times.clone(),
        total: run.tally,
        raw: raw.map(|r| crate::render::RawReplay {
            laser: r.laser.clone(),
            truth: r.stops.iter().map(|s| s.truth).collect(),
            estimate: r.stops.iter().map(|s| s.estimate).collect(),
        }),
        frontiers: std::sync::OnceLock::new(),
    };
    (svg, replay)
}

/// A run as the simulator ended it: the run (on the ground truth for raw scans), why it was
/// cut short, and the raw-scan run when there was one.
struct Driven {
    run: crate::sim::polygon::PolygonRun,
    failure: Option<crate::sim::polygon::PolygonSimError>,
    raw: Option<LidarRun>,
}

impl Driven {
    /// Runs `strategy` with the exact sensor, or on raw scans with `lidar`.
    fn run(
        world: &PolygonWorld,
        start: Point,
        cost: &CostModel,
        strategy: &mut dyn crate::strategy::polygon::PolygonStrategy,
        lidar: Option<&LidarSetup>,
        observer: &mut dyn Observer<Point, PolygonObservation>,
    ) -> Self {
        match lidar {
            None => match crate::sim::polygon::run(world, start, cost, strategy, observer) {
                Ok(run) => Self { run, failure: None, raw: None },
                Err(e) => Self { run: *e.partial, failure: Some(e.error), raw: None },
            },
            Some(l) => match crate::sim::lidar::run(world, start, cost, strategy, l, observer) {
                Ok(r) => Self { run: r.truth.clone(), failure: None, raw: Some(r) },
                Err(e) => Self {
                    run: e.partial.truth.clone(),
                    failure: Some(e.error),
                    raw: Some(*e.partial),
                },
            },
        }
    }
}

/// The footprint's part of the run record: the configuration space, what can be seen from
/// it ([`crate::offline::polygon::reach`]) and what the run covered of that (`covered`: the
/// union of its scans' regions).
fn robot_info(
    world: &PolygonWorld,
    reach: &crate::world::polygon::Reach,
    setup: &RobotSetup,
    run: &crate::sim::polygon::PolygonRun,
    record: &RunRecord,
    skipped: &crate::strategy::polygon::Skipped,
    covered: &crate::algorithm::region::Region,
) -> RobotInfo {
    use crate::offline::polygon::reach as r;
    let seen: Vec<Vec<Point>> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
    let visible = r::visible_from(world, &r::reachable_samples(world), &seen);
    let visible_area = visible.area();
    let body = r::body_space(world).unwrap_or_else(crate::algorithm::region::Region::empty);
    let visible_body = visible.intersection(&body);
    let visible_body_area = visible_body.area();
    // What no scan saw, in the visible area (as the coverage counts it) and in its part where
    // the body fits (the same exact test of each uncovered piece); the rest is in crevices.
    let unseen = (visible_area - record.metrics.covered_area).max(0.0);
    let unseen_body =
        crate::algorithm::cover::uncovered_area_of(world.domain(), &visible_body, &seen, covered);
    let scale = crate::kernel::magnitude(world.domain().rings().iter().flatten());
    RobotInfo {
        footprint: setup.footprint.clone(),
        clearance: setup.footprint.planning_clearance(scale),
        configuration_space_rule: format!(
            "free space minus the Minkowski sum of its boundary with the reflected footprint ({})",
            match &setup.footprint {
                Footprint::Disc { .. } => format!(
                    "a disc as the circumscribed {}-gon, so the space is conservative by at most 0.5% of the radius",
                    crate::protocol::polygon::DISC_SIDES
                ),
                _ => "the convex polygon at a fixed heading".into(),
            }
        ),
        reachable_configuration_space_area: reach.domain().area(),
        configuration_space_components: reach.components(),
        visible_from_reachable_area: visible_area,
        unreachable_area: r::unreachable_area(world, &visible),
        coverage_of_reachable: if visible_area > 0.0 {
            (record.metrics.covered_area / visible_area).min(1.0)
        } else {
            1.0
        },
        windows_out_of_reach: skipped.out_of_reach,
        body_space_area: body.area(),
        coverage_of_body_space: if visible_body_area > 0.0 {
            (1.0 - unseen_body / visible_body_area).clamp(0.0, 1.0)
        } else {
            1.0
        },
        unseen_in_crevices: (unseen - unseen_body).max(0.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_are_checked_before_any_work() {
        let o = ExploreOptions { range: Some(-1.0), ..ExploreOptions::default() };
        let e = explore_file(Path::new("/no/such/file"), None, &o, &mut |_| {}).unwrap_err();
        assert_eq!(e.to_string(), "range must be a positive number of metres, got -1");
        let o = ExploreOptions { strategy: "range_limited".into(), ..ExploreOptions::default() };
        let e = explore_file(Path::new("/no/such/file"), None, &o, &mut |_| {}).unwrap_err();
        assert!(matches!(e, ExploreError::RangeNeeded), "{e}");
        let limits = ReferenceLimits { bounds_seconds: f64::NAN, ..ReferenceLimits::default() };
        let e = check_budgets(&limits).unwrap_err().to_string();
        assert_eq!(e, "bounds_seconds must be between 0 and 86400 seconds, got NaN");
        for bad in [-0.5, f64::NAN, f64::INFINITY] {
            let o = ExploreOptions { simplify: Some(bad), ..ExploreOptions::default() };
            let e = explore_file(Path::new("/no/such/file"), None, &o, &mut |_| {}).unwrap_err();
            assert!(
                e.to_string().starts_with("simplify must be a finite non-negative number"),
                "{e}"
            );
        }
    }

    #[test]
    fn a_start_outside_is_an_error_in_input_coordinates() {
        let env = crate::io::text_formats::parse_geojson(OFFICE_GEOJSON, "office").unwrap();
        let e =
            explore("office", &env, Some([-1e3, -1e3]), &ExploreOptions::default(), &mut |_| {})
                .unwrap_err();
        assert_eq!(e.to_string(), "the start (-1000, -1000) is outside the free space");
        let o = ExploreOptions { strategy: "warp".into(), ..ExploreOptions::default() };
        let e = explore("office", &env, Some([0.0, 0.0]), &o, &mut |_| {}).unwrap_err();
        assert!(matches!(e, ExploreError::Strategy(_)), "{e}");
    }

    #[test]
    fn a_lidar_run_on_a_wall_is_an_error_and_the_exact_sensor_runs() {
        // The office's outer corner (0, 0) and a point on its west wall: from there, the
        // beams that leave the free space meet no wall. The exact sensor sees from there.
        let env = crate::io::text_formats::parse_geojson(OFFICE_GEOJSON, "office").unwrap();
        let lidar = ExploreOptions {
            lidar: Some(crate::world::lidar::Lidar::default()),
            ..ExploreOptions::default()
        };
        for at in [[0.0, 0.0], [0.0, 2.0]] {
            let e = explore("office", &env, Some(at), &lidar, &mut |_| {}).unwrap_err();
            assert!(matches!(e, ExploreError::StartOnWall(p) if p == at), "{e}");
            assert!(e.to_string().contains("lies on a wall"), "{e}");
            let exact = ExploreOptions { max_scans: Some(2), ..ExploreOptions::default() };
            assert!(explore("office", &env, Some(at), &exact, &mut |_| {}).is_ok());
        }
        // Just inside, it runs (two scans are enough to tell).
        let short = ExploreOptions { max_scans: Some(2), ..lidar };
        assert!(explore("office", &env, Some([0.5, 0.5]), &short, &mut |_| {}).is_ok());
    }

    #[test]
    fn a_scan_limit_cuts_the_run_short_unless_the_strategy_is_done_there() {
        // A small generated office: two rooms a side along a corridor.
        let inst = crate::generate::office(2, 0, 0).unwrap();
        let geo = crate::io::text_formats::to_geojson(&inst.domain, Some(inst.start));
        let env = crate::io::text_formats::parse_geojson(&geo.to_string(), "office-2").unwrap();
        let run = |max_scans: Option<u64>, lidar: bool| {
            let o = ExploreOptions {
                strategy: "cost_aware".into(),
                range: Some(20.0),
                footprint: Footprint::disc(0.2).unwrap(),
                limits: ReferenceLimits { bounds_seconds: 0.0, ..ReferenceLimits::BOUNDS_ONLY },
                lidar: lidar.then(crate::world::lidar::Lidar::default),
                max_scans,
                ..ExploreOptions::default()
            };
            explore("office", &env, None, &o, &mut |_| {}).unwrap()
        };
        for lidar in [false, true] {
            let whole = run(None, lidar);
            assert!(whole.failure.is_none(), "{:?}", whole.failure);
            let n = whole.record.metrics.totals.scans;
            assert!(n >= 3, "{n} scans");
            // Stopped before the end: cut short after exactly the limit, and said so.
            let cut = run(Some(n - 1), lidar);
            assert_eq!(cut.record.metrics.totals.scans, n - 1);
            let e = cut.failure.expect("cut short").to_string();
            assert!(e.contains(&format!("scan limit ({} scans, --max-scans)", n - 1)), "{e}");
            assert_eq!(cut.record.error.as_deref(), Some(e.as_str()));
            // A limit the run just reaches, or (exact sensor) one beyond it, changes nothing.
            for limit in if lidar { vec![n] } else { vec![n, n + 5] } {
                let same = run(Some(limit), lidar);
                assert!(same.failure.is_none(), "{limit}: {:?}", same.failure);
                assert_eq!(same.record.metrics, whole.record.metrics, "{limit}");
                assert_eq!(same.record.sensor, whole.record.sensor, "{limit}");
            }
        }
    }
}
