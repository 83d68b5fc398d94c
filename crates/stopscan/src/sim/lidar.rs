//! Driving a polygon strategy from raw laser scans: a simulated robot with a noisy lidar and
//! drifting odometry, read through the [`sensing`](crate::sensing) pipeline.
//!
//! The strategy plans in the map frame the robot believes in (its start is the origin of
//! that belief). Each step:
//! - **Move.** The robot drives until odometry says it reached the goal; its true motion
//!   differs by a random error that grows with the distance (`drift · d` metres, standard
//!   deviation per axis, and [`HEADING_DRIFT`]` · drift · d` radians of heading). The true move is checked
//!   exactly against the configuration space: where the straight move would leave
//!   it, the navigation stack drives a short way round (and is charged for it), or stops
//!   where the way is blocked; a goal the drift puts against a wall is reached as near as the
//!   footprint allows. Odometry measures any shortfall.
//! - **Scan.** The lidar scans from the true pose; the scan is read at the pose odometry
//!   believes, aligned by ICP to the walls of earlier scans, and the corrected pose becomes
//!   the robot's belief. The strategy gets the region read from the scan.
//!
//! The run is measured on the ground truth: the exact visibility regions from where the scans
//! were truly taken, along the path truly driven ([`LidarRun::truth`]), with the pose error at
//! every stop.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use super::polygon::{PolygonRun, PolygonSimError};
use super::{Observer, SimError};
use crate::algorithm::shortest_path::PathPlanner;
use crate::kernel::Point;
use crate::protocol::laser::{Pose, wrap};
use crate::protocol::polygon::PolygonObservation;
use crate::protocol::{Action, CostModel, Feedback, Tally};
use crate::sensing::icp::{self, Alignment, IcpParams, WallMap};
use crate::sensing::ingest::{Cleaning, IngestParams, ingest};
use crate::strategy::polygon::PolygonStrategy;
use crate::world::lidar::{Lidar, Walls, gaussian};
use crate::world::polygon::PolygonWorld;

/// How the simulated robot senses and drifts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LidarSetup {
    /// The lidar.
    pub lidar: Lidar,
    /// Odometry's drift: the standard deviation of the position error per metre driven (per
    /// axis); [`HEADING_DRIFT`] times it in radians per metre for the heading.
    pub drift: f64,
    /// How scans are read.
    pub ingest: IngestParams,
    /// How scans are aligned.
    pub icp: IcpParams,
    /// The seed of the lidar's noise and the odometry's drift.
    pub seed: u64,
}

impl LidarSetup {
    /// A setup for `lidar` and `drift`, reading scans with the lidar's noise, seeded.
    pub fn new(lidar: Lidar, drift: f64, seed: u64) -> Self {
        Self {
            lidar,
            drift,
            ingest: IngestParams::for_noise(lidar.sigma),
            icp: IcpParams {
                huber: (3.0 * lidar.sigma).max(0.02),
                sigma: lidar.sigma,
                ..IcpParams::default()
            },
            seed,
        }
    }
}

/// One stop: where the robot truly was, what odometry said, what ICP made of it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Stop {
    /// The true pose.
    pub truth: Pose,
    /// The pose by odometry, before the scan was aligned.
    pub odometry: Pose,
    /// The pose believed after alignment.
    pub estimate: Pose,
    /// `|estimate − truth|`, metres.
    pub position_error: f64,
    /// The heading error after alignment, radians.
    pub heading_error: f64,
    /// What ICP did (none at the first stop: nothing was known).
    pub alignment: Option<Alignment>,
    /// What cleaning did to the scan.
    pub cleaning: Cleaning,
}

/// A run from raw scans.
#[derive(Debug, Clone, PartialEq)]
pub struct LidarRun {
    /// The run on the ground truth: the path truly driven and the exact regions seen from
    /// where the scans were truly taken (what the metrics measure).
    pub truth: PolygonRun,
    /// The path as the robot believed it (the strategy's goals, and each stop's estimate).
    pub believed_path: Vec<Point>,
    /// The regions read from the scans, as the strategy got them.
    pub observations: Vec<PolygonObservation>,
    /// Every stop.
    pub stops: Vec<Stop>,
}

/// A raw-scan run that was cut short, with the run until then.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{error}")]
pub struct LidarRunError {
    /// Why.
    pub error: PolygonSimError,
    /// The run until then.
    pub partial: Box<LidarRun>,
}

/// The heading's drift per metre, in radians, as a share of the position's drift per metre:
/// with 1% drift, 0.001 rad (0.06°) per metre, so that over a trip the heading adds about as
/// much position error as the drift itself (a robot with a gyro).
pub const HEADING_DRIFT: f64 = 0.1;

/// How far short of a goal the simulated robot may stop when the goal lies against a wall,
/// metres; farther, the goal is refused.
pub const STOP_SHORT: f64 = 0.5;

/// The legs a simulated robot truly drives from `from` toward `goal`: straight when the move
/// stays in the space it may move in; else the shortest way round to the goal (or to the
/// nearest place within [`STOP_SHORT`] of it when the goal lies against a wall) when that is
/// at most 1.5 times the straight distance plus a metre; else straight toward the goal until
/// the way is blocked.
fn drive(world: &PolygonWorld, planner: &PathPlanner<'_>, from: Point, goal: Point) -> Vec<Point> {
    if world.can_move(from, goal) {
        return vec![from, goal];
    }
    let dist = |a: Point, b: Point| (b[0] - a[0]).hypot(b[1] - a[1]);
    if let Some(g) = world.nearest_place(goal, STOP_SHORT) {
        if world.can_move(from, g) {
            return vec![from, g];
        }
        if let Some(p) = planner.shortest_path(from, g)
            && p.length <= 1.5 * dist(from, g) + 1.0
        {
            return p.points;
        }
    }
    // Blocked on the way: the last free point of the straight move, a millimetre back.
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let at = |t: f64| [from[0] + t * (goal[0] - from[0]), from[1] + t * (goal[1] - from[1])];
    for _ in 0..48 {
        let mid = 0.5 * (lo + hi);
        if world.can_move(from, at(mid)) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let back = (lo - 1e-3 / dist(from, goal).max(1e-3)).max(0.0);
    vec![from, at(back)]
}

/// The wall map keeps walls in pieces of at most this length, metres.
pub const MAP_PIECE: f64 = 0.5;

/// A wall piece within this distance of a mapped wall of the same orientation is that wall,
/// seen again, metres: it is not added twice.
pub const MAP_SAME_WALL: f64 = 0.3;

/// The most scans a raw-scan run may take before it is cut short as making no progress.
pub const MAX_SCANS: u64 = 20_000;

/// Runs `strategy` in `world` from `start` on raw scans ([`LidarSetup`]), until it is done.
///
/// # Errors
/// [`LidarRunError`], with the run so far: a scan asked for where one already stood, or more
/// than [`MAX_SCANS`] scans.
pub fn run(
    world: &PolygonWorld,
    start: Point,
    cost: &CostModel,
    strategy: &mut dyn PolygonStrategy,
    setup: &LidarSetup,
    observer: &mut dyn Observer<Point, PolygonObservation>,
) -> Result<LidarRun, LidarRunError> {
    let mut robot = Robot::new(world, start, setup);
    let name = strategy.name().to_string();
    let mut feedback = Feedback::Start { at: start };
    let outcome = loop {
        match strategy.act(&feedback) {
            Action::Done => break Ok(()),
            Action::MoveTo { to } => {
                let (to, metres) = robot.drive_to(to);
                if observer.on_move(0, &to, metres).is_break() {
                    robot.out.truth.interrupted = true;
                    break Ok(());
                }
                feedback = Feedback::Arrived;
            }
            Action::Scan => {
                let observation = match robot.scan(&name, cost) {
                    Ok(o) => o,
                    Err(e) => break Err(e),
                };
                let at = observation.at;
                if observer.on_scan(0, &at, &observation).is_break() {
                    robot.out.truth.interrupted = true;
                    break Ok(());
                }
                feedback = Feedback::Scanned(observation);
            }
        }
    };
    let tally = robot.tally;
    let mut out = robot.out;
    out.truth.tally = tally;
    out.truth.time = cost.price(&tally);
    match outcome {
        Ok(()) => {
            observer.on_finish(&tally);
            Ok(out)
        }
        Err(error) => Err(LidarRunError { error, partial: Box::new(out) }),
    }
}

/// The simulated robot: its true and believed poses, its sensor and its wall map.
struct Robot<'a> {
    world: &'a PolygonWorld,
    walls: Walls,
    planner: PathPlanner<'a>,
    setup: &'a LidarSetup,
    rng: ChaCha8Rng,
    map: WallMap,
    truth: Pose,
    belief: Pose,
    tally: Tally,
    /// Metres driven since the last scan: how far odometry may have drifted.
    since_scan: f64,
    out: LidarRun,
}

impl<'a> Robot<'a> {
    fn new(world: &'a PolygonWorld, start: Point, setup: &'a LidarSetup) -> Self {
        let tally = Tally::default();
        Self {
            world,
            walls: Walls::of(world.domain()),
            planner: PathPlanner::new(world.moves()),
            setup,
            rng: ChaCha8Rng::seed_from_u64(setup.seed),
            map: WallMap::new(),
            truth: Pose::new(start, 0.0),
            belief: Pose::new(start, 0.0),
            tally,
            since_scan: 0.0,
            out: LidarRun {
                truth: PolygonRun {
                    tally,
                    time: crate::protocol::TimeBreakdown::default(),
                    path: vec![start],
                    scans: Vec::new(),
                    scan_times: Vec::new(),
                    interrupted: false,
                },
                believed_path: vec![start],
                observations: Vec::new(),
                stops: Vec::new(),
            },
        }
    }

    /// Drives toward `to` (map frame) as the navigation stack would, on drifting odometry:
    /// where odometry says the robot ended, and the metres truly driven.
    fn drive_to(&mut self, to: Point) -> (Point, f64) {
        let belief = self.belief;
        let d = (to[0] - belief.x).hypot(to[1] - belief.y);
        self.since_scan += d;
        // The motion odometry reports, in the robot's frame, and the true one.
        let step = belief.inverse().compose(&Pose::new(to, belief.theta));
        let s = self.setup.drift * d;
        let rng = &mut self.rng;
        let (ex, ey, et) =
            (s * gaussian(rng), s * gaussian(rng), HEADING_DRIFT * s * gaussian(rng));
        let moved = Pose { x: step.x + ex, y: step.y + ey, theta: step.theta + et };
        let mut next = self.truth.compose(&moved);
        // Where the robot truly ends ([`drive`]); odometry measures any shortfall.
        let legs = drive(self.world, &self.planner, self.truth.at(), next.at());
        let stop = *legs.last().expect("a drive has an end");
        let short = [stop[0] - next.x, stop[1] - next.y];
        let (sin, cos) = (belief.theta - next.theta).sin_cos();
        let to = [to[0] + cos * short[0] - sin * short[1], to[1] + sin * short[0] + cos * short[1]];
        (next.x, next.y) = (stop[0], stop[1]);
        let metres: f64 =
            legs.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).sum();
        self.out.truth.path.extend_from_slice(&legs[1..]);
        self.tally.moves += 1;
        self.tally.distance += metres;
        self.truth = next;
        self.belief = Pose::new(to, belief.theta);
        self.out.believed_path.push(to);
        (to, metres)
    }

    /// Scans from the true pose, reads the scan at the belief, aligns it, and records the
    /// stop: the region the strategy is told of.
    fn scan(
        &mut self,
        name: &str,
        cost: &CostModel,
    ) -> Result<PolygonObservation, PolygonSimError> {
        let at = self.belief.at();
        if let Some(k) = self.out.observations.iter().position(|o| o.at == at) {
            return Err(SimError::NoProgress {
                strategy: name.into(),
                robot: 0,
                at,
                earlier: k as u64 + 1,
                scans: self.tally.scans,
            });
        }
        if self.tally.scans >= MAX_SCANS {
            return Err(SimError::TooLong(name.into(), MAX_SCANS));
        }
        let setup = self.setup;
        let scan = setup.lidar.scan(&self.walls, &self.truth, &mut self.rng);
        // Read in the scanner's frame, aligned, then placed at the belief.
        let local = ingest(&scan, &Pose::default(), &setup.ingest)
            .expect("the simulated lidar's scans are valid");
        let odometry = self.belief;
        let prior = icp::Prior {
            position: (setup.drift * self.since_scan).max(0.01),
            heading: (HEADING_DRIFT * setup.drift * self.since_scan).max(0.002),
        };
        self.since_scan = 0.0;
        let alignment = (!self.map.is_empty())
            .then(|| icp::align(&local.points, &odometry, Some(prior), &self.map, &setup.icp));
        if let Some(a) = &alignment {
            self.belief = a.pose;
        }
        let belief = self.belief;
        let place = |p: Point| belief.apply(p);
        // A scan that could not be aligned would put its walls in the wrong place: it informs
        // the strategy, not the map.
        if alignment.as_ref().is_none_or(|a| a.fallback.is_none()) {
            let walls: Vec<[Point; 2]> = local
                .walls
                .iter()
                .chain(&local.bridges)
                .map(|w| [place(w[0]), place(w[1])])
                .collect();
            self.map.extend_unseen(&walls, MAP_PIECE, MAP_SAME_WALL);
        }
        let observation = local.observation.mapped(place);
        self.out.truth.scan_times.push(cost.price(&self.tally).total());
        self.tally.scans += 1;
        let truth = self.truth;
        let exact = self.world.scan(truth.at()).expect("the true pose is in the free space");
        self.out.truth.scans.push(exact);
        self.out.stops.push(Stop {
            truth,
            odometry,
            estimate: belief,
            position_error: (belief.x - truth.x).hypot(belief.y - truth.y),
            heading_error: wrap(belief.theta - truth.theta),
            alignment,
            cleaning: local.cleaning,
        });
        if belief.at() != *self.out.believed_path.last().expect("starts with the start") {
            self.out.believed_path.push(belief.at());
        }
        self.out.observations.push(observation.clone());
        Ok(observation)
    }
}
