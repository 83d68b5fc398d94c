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
use crate::protocol::laser::{LaserScan, Pose, wrap};
use crate::protocol::polygon::PolygonObservation;
use crate::protocol::{Action, CostModel, Feedback, MoveFailure, Tally};
use crate::sensing::icp::{Alignment, IcpParams};
use crate::sensing::ingest::{Cleaning, IngestParams};
use crate::sensing::mapper::{Mapper, MapperParams};
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
    /// Relays ([`Mapper::relay`]): when a scan where a trip ends is predicted not to be
    /// placed by ICP along some direction, and odometry over the trip may be off by more
    /// than this (one standard deviation, metres), the robot stops on the way where a scan
    /// can be placed, and scans to place itself. 0 never relays.
    #[serde(default = "default_relay")]
    pub relay: f64,
}

fn default_relay() -> f64 {
    RELAY
}

pub use crate::sensing::mapper::{MAX_RELAYS, RELAY};

impl LidarSetup {
    /// A setup for `lidar` and `drift`, reading scans with the lidar's noise, seeded.
    pub fn new(lidar: Lidar, drift: f64, seed: u64) -> Self {
        let m = MapperParams::for_sensor(lidar.sigma, drift, HEADING_DRIFT * drift);
        Self { lidar, drift, ingest: m.ingest, icp: m.icp, seed, relay: RELAY }
    }

    /// How the robot's scans are read and aligned.
    pub fn mapper_params(&self) -> MapperParams {
        MapperParams {
            ingest: self.ingest,
            icp: self.icp,
            drift: self.drift,
            heading_drift: HEADING_DRIFT * self.drift,
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
    /// How many earlier stops the scan was matched to on its own and tied to in the pose
    /// graph (loop closures included).
    #[serde(default)]
    pub links: usize,
    /// How unsure the pose graph was of the stop's position when the scan was read: one
    /// standard deviation along its least sure direction, metres
    /// ([`Reading::placement`](crate::sensing::mapper::Reading::placement)).
    #[serde(default)]
    pub placement_sd: f64,
    /// What cleaning did to the scan.
    pub cleaning: Cleaning,
    /// A scan taken on the way to place the robot ([`LidarSetup::relay`]), not asked for by
    /// the strategy, which is not told of it.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub relay: bool,
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
    /// Every stop's scan as the lidar returned it, taken at the stop's true pose.
    pub laser: Vec<LaserScan>,
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

/// The legs a simulated robot truly drives from `from` toward `goal`, and whether it got
/// there: straight when the move stays in the space it may move in; else the shortest way
/// round to the goal (or to the nearest place within [`STOP_SHORT`] of it when the goal lies
/// against a wall) when that is at most 1.5 times the straight distance plus a metre; else
/// straight toward the goal until the way is blocked (a failed move). A goal with no place
/// within [`STOP_SHORT`] (inside an obstacle, or where the footprint does not fit) is
/// refused: the robot does not move.
fn drive(
    world: &PolygonWorld,
    planner: &PathPlanner<'_>,
    from: Point,
    goal: Point,
) -> (Vec<Point>, bool) {
    if world.can_move(from, goal) {
        return (vec![from, goal], true);
    }
    let dist = |a: Point, b: Point| (b[0] - a[0]).hypot(b[1] - a[1]);
    let Some(g) = world.nearest_place(goal, STOP_SHORT) else {
        return (vec![from], false);
    };
    if world.can_move(from, g) {
        return (vec![from, g], true);
    }
    if let Some(p) = planner.shortest_path(from, g)
        && p.length <= 1.5 * dist(from, g) + 1.0
    {
        return (p.points, true);
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
    (vec![from, at(back)], false)
}

/// The most scans a raw-scan run may take before it is cut short as making no progress.
pub const MAX_SCANS: u64 = 20_000;

/// A simulated robot in a polygon world: a true pose, an odometry pose that drifts from it,
/// and a lidar. It knows nothing of any map: it drives to goals given in its odometry frame
/// and scans where it truly stands. The simulator drives it, and so does a robot client of
/// `stopscan serve` in the tests.
#[derive(Debug)]
pub struct SimRobot<'a> {
    world: &'a PolygonWorld,
    walls: Walls,
    planner: PathPlanner<'a>,
    lidar: Lidar,
    drift: f64,
    rng: ChaCha8Rng,
    truth: Pose,
    odometry: Pose,
}

/// How a drive ended.
#[derive(Debug, Clone, PartialEq)]
pub struct Drive {
    /// The legs truly driven (the first point is where the robot stood).
    pub legs: Vec<Point>,
    /// Their length, metres.
    pub metres: f64,
    /// Why the robot did not reach the goal, if it did not.
    pub failed: Option<MoveFailure>,
}

impl<'a> SimRobot<'a> {
    /// A robot at `start`, heading 0, its odometry frame the world's; its lidar's noise and its
    /// odometry's drift seeded by `seed`.
    pub fn new(world: &'a PolygonWorld, start: Point, lidar: Lidar, drift: f64, seed: u64) -> Self {
        Self {
            world,
            walls: Walls::of(world.domain()),
            planner: PathPlanner::new(world.moves()),
            lidar,
            drift,
            rng: ChaCha8Rng::seed_from_u64(seed),
            truth: Pose::new(start, 0.0),
            odometry: Pose::new(start, 0.0),
        }
    }

    /// Where the robot truly is.
    pub fn truth(&self) -> Pose {
        self.truth
    }

    /// Where odometry says it is.
    pub fn odometry(&self) -> Pose {
        self.odometry
    }

    /// Sets the odometry pose (a localiser's correction).
    pub fn set_odometry(&mut self, pose: Pose) {
        self.odometry = pose;
    }

    /// Drives toward `goal` (odometry frame) as a navigation stack would, on drifting
    /// odometry: the true motion differs from the commanded one by a random error that grows
    /// with the distance ([`HEADING_DRIFT`]); the true move is checked exactly against the
    /// space the footprint may move in (straight, a short way round, or stopped where blocked;
    /// see the module notes); odometry measures any shortfall.
    ///
    /// # Panics
    /// Never: a drive's legs start where the robot stands.
    pub fn drive(&mut self, goal: Point) -> Drive {
        let odo = self.odometry;
        let d = (goal[0] - odo.x).hypot(goal[1] - odo.y);
        // The motion odometry reports, in the robot's frame, and the true one.
        let step = odo.inverse().compose(&Pose::new(goal, odo.theta));
        let s = self.drift * d;
        let rng = &mut self.rng;
        let (ex, ey, et) =
            (s * gaussian(rng), s * gaussian(rng), HEADING_DRIFT * s * gaussian(rng));
        let moved = Pose { x: step.x + ex, y: step.y + ey, theta: step.theta + et };
        let mut next = self.truth.compose(&moved);
        let (legs, reached) = drive(self.world, &self.planner, self.truth.at(), next.at());
        let stop = *legs.last().expect("a drive has an end");
        if legs.len() == 1 {
            // Refused: the robot did not move.
            return Drive { legs, metres: 0.0, failed: Some(MoveFailure::Blocked) };
        }
        let short = [stop[0] - next.x, stop[1] - next.y];
        let (sin, cos) = (odo.theta - next.theta).sin_cos();
        let to =
            [goal[0] + cos * short[0] - sin * short[1], goal[1] + sin * short[0] + cos * short[1]];
        (next.x, next.y) = (stop[0], stop[1]);
        let metres: f64 =
            legs.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).sum();
        self.truth = next;
        self.odometry = Pose::new(to, odo.theta);
        Drive { legs, metres, failed: (!reached).then_some(MoveFailure::Blocked) }
    }

    /// A scan from where the robot truly stands.
    pub fn scan(&mut self) -> LaserScan {
        self.lidar.scan(&self.walls, &self.truth, &mut self.rng)
    }
}

/// Runs `strategy` in `world` from `start` on raw scans ([`LidarSetup`]), until it is done.
///
/// # Errors
/// [`LidarRunError`], with the run so far: a scan asked for where one already stood (unless a
/// move failed since the last scan: the robot scans to place itself again), or more than
/// [`MAX_SCANS`] scans.
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
                if let Some(r) = robot.relay_on_the_way(to, &strategy.ahead()) {
                    let (at, metres, failed) = robot.drive_to(r);
                    if observer.on_move(0, &at, metres).is_break() {
                        robot.out.truth.interrupted = true;
                        break Ok(());
                    }
                    if failed.is_none()
                        && let Err(e) = robot.relay(&name, cost)
                    {
                        break Err(e);
                    }
                }
                let (at, metres, failed) = robot.drive_to(to);
                if observer.on_move(0, &at, metres).is_break() {
                    robot.out.truth.interrupted = true;
                    break Ok(());
                }
                feedback = match failed {
                    None => Feedback::Arrived,
                    Some(reason) => Feedback::MoveFailed { at, reason },
                };
            }
            Action::Scan => {
                robot.relays = 0;
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

/// The simulated robot, what it has mapped, and the run's record.
struct Robot<'a> {
    world: &'a PolygonWorld,
    sim: SimRobot<'a>,
    mapper: Mapper,
    tally: Tally,
    /// Metres driven since the last scan: how far odometry may have drifted.
    since_scan: f64,
    /// Whether a move failed since the last scan: a scan where one already stood then places
    /// the robot again (its belief drifted on the way there), and counts as progress.
    failed_since_scan: bool,
    /// Relays since the strategy's last scan.
    relays: usize,
    setup: &'a LidarSetup,
    out: LidarRun,
}

impl<'a> Robot<'a> {
    fn new(world: &'a PolygonWorld, start: Point, setup: &'a LidarSetup) -> Self {
        let tally = Tally::default();
        Self {
            world,
            sim: SimRobot::new(world, start, setup.lidar, setup.drift, setup.seed),
            mapper: Mapper::new(setup.mapper_params()),
            tally,
            since_scan: 0.0,
            failed_since_scan: false,
            relays: 0,
            setup,
            out: LidarRun {
                truth: PolygonRun {
                    tally,
                    time: crate::protocol::TimeBreakdown::default(),
                    path: vec![start],
                    scans: Vec::new(),
                    scan_times: Vec::new(),
                    scan_tallies: Vec::new(),
                    interrupted: false,
                },
                believed_path: vec![start],
                observations: Vec::new(),
                stops: Vec::new(),
                laser: Vec::new(),
            },
        }
    }

    /// Drives toward `to` (map frame): where the robot believes it ended, the metres truly
    /// driven, and why it did not get there if it did not.
    fn drive_to(&mut self, to: Point) -> (Point, f64, Option<MoveFailure>) {
        let from = self.sim.odometry().at();
        let drive = self.sim.drive(to);
        let at = self.sim.odometry().at();
        self.since_scan += (at[0] - from[0]).hypot(at[1] - from[1]);
        self.failed_since_scan |= drive.failed.is_some();
        self.out.truth.path.extend_from_slice(&drive.legs[1..]);
        if drive.legs.len() > 1 {
            self.tally.moves += 1;
            self.tally.distance += drive.metres;
            self.out.believed_path.push(at);
        }
        (at, drive.metres, drive.failed)
    }

    /// Scans from the true pose, reads the scan at the belief, aligns it, and records the
    /// stop: the region the strategy is told of.
    fn scan(
        &mut self,
        name: &str,
        cost: &CostModel,
    ) -> Result<PolygonObservation, PolygonSimError> {
        let odometry = self.sim.odometry();
        let at = odometry.at();
        if !std::mem::take(&mut self.failed_since_scan)
            && let Some(k) = self.out.observations.iter().position(|o| o.at == at)
        {
            return Err(SimError::NoProgress {
                strategy: name.into(),
                robot: 0,
                at,
                earlier: k as u64 + 1,
                scans: self.tally.scans,
            });
        }
        let reading = self.read(name, cost, false)?;
        self.out.observations.push(reading.observation.clone());
        Ok(reading.observation)
    }

    /// Scans from the true pose, reads the scan at the belief and aligns it (the robot takes
    /// the aligned pose as its belief), and records the stop; refused beyond [`MAX_SCANS`].
    fn read(
        &mut self,
        name: &str,
        cost: &CostModel,
        relay: bool,
    ) -> Result<crate::sensing::mapper::Reading, PolygonSimError> {
        if self.tally.scans >= MAX_SCANS {
            return Err(SimError::TooLong(name.into(), MAX_SCANS));
        }
        let odometry = self.sim.odometry();
        let scan = self.sim.scan();
        let reading = self
            .mapper
            .read(&scan, &odometry, std::mem::take(&mut self.since_scan))
            .expect("the simulated lidar's scans and poses are valid");
        // The robot localises: its belief becomes the aligned pose.
        let belief = reading.estimate;
        self.sim.set_odometry(belief);
        self.out.truth.scan_times.push(cost.price(&self.tally).total());
        self.tally.scans += 1;
        self.out.truth.scan_tallies.push(self.tally);
        let truth = self.sim.truth();
        let exact = self.world.scan(truth.at()).expect("the true pose is in the free space");
        self.out.truth.scans.push(exact);
        self.out.stops.push(Stop {
            truth,
            odometry,
            estimate: belief,
            position_error: (belief.x - truth.x).hypot(belief.y - truth.y),
            heading_error: wrap(belief.theta - truth.theta),
            alignment: reading.alignment,
            links: reading.links,
            placement_sd: reading.placement,
            cleaning: reading.cleaning,
            relay,
        });
        if belief.at() != *self.out.believed_path.last().expect("starts with the start") {
            self.out.believed_path.push(belief.at());
        }
        self.out.laser.push(scan);
        Ok(reading)
    }

    /// A scan on the way, to place the robot ([`LidarSetup::relay`]): the strategy is not
    /// told of it.
    fn relay(&mut self, name: &str, cost: &CostModel) -> Result<(), PolygonSimError> {
        self.relays += 1;
        self.read(name, cost, true).map(drop)
    }

    /// Where on the move to `to` the robot should stop for a relay, if anywhere
    /// ([`Mapper::relay`], with the strategy's waypoints after the move).
    fn relay_on_the_way(&self, to: Point, ahead: &[Point]) -> Option<Point> {
        if self.setup.relay <= 0.0 || self.relays >= MAX_RELAYS || self.out.stops.is_empty() {
            return None;
        }
        let mut trip = vec![self.sim.odometry().at(), to];
        trip.extend_from_slice(ahead);
        let lidar = &self.setup.lidar;
        self.mapper.relay(&trip, self.since_scan, lidar.beams, lidar.range_max, self.setup.relay)
    }
}
