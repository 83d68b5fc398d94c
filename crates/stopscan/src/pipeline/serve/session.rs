//! One robot's session: the strategy, what has been mapped, and what the robot was last asked
//! to do. Every request either moves the session one step (and gets its reply) or is refused
//! with an error that leaves it unchanged.

use super::message::{
    CornerIn, DoneReason, FailedIn, Family, Localised, Order, ProtocolError, ReplyBody, Request,
    ScanIn, StartIn, Summary,
};
use super::roi::{Outcome, RoiRun};
use crate::geometry::Frame;
use crate::kernel::{Num, Point};
use crate::pipeline::explore::{
    DEFAULT_POCKET_BUDGET, DEFAULT_POCKET_CAP, default_min_pocket, raw_scan_planning,
};
use crate::protocol::corner::{AngleDistribution, CornerObservation, CornerSetup, Stop};
use crate::protocol::laser::{InvalidScan, Pose};
use crate::protocol::polygon::{Footprint, RobotSetup, Sensor};
use crate::protocol::{Action, CostModel, Feedback, RunTotals, Tally};
use crate::sensing::ingest::IngestError;
use crate::sensing::mapper::{MAX_RELAYS, Mapper, MapperParams, RELAY};
use crate::sim::lidar::HEADING_DRIFT;
use crate::strategy::corner::registry::{self, BuildOptions};
use crate::strategy::corner::{CornerFeedback, CornerStrategy, StopListStrategy};
use crate::strategy::polygon::{self, PolygonStrategy};

/// The polygon family's default strategy (as `explore`'s).
pub const DEFAULT_POLYGON_STRATEGY: &str = "depth_first";
/// The corner family's default strategy.
pub const DEFAULT_CORNER_STRATEGY: &str = "exprec";
/// The range noise assumed when the start does not give it, metres.
pub const DEFAULT_SIGMA: f64 = 0.02;
/// Odometry's drift assumed when the start does not give it, per metre driven.
pub const DEFAULT_DRIFT: f64 = 0.01;
/// The corner belief assumed when the start does not give it.
pub const DEFAULT_BELIEF: &str = "uniform:0,180";

/// What the session waits for.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Expect {
    /// `start`.
    Start,
    /// `scan` (after a scan request).
    Scan,
    /// `arrived` or `move_failed` (after a goal).
    Move,
    /// A report from any robot of the team that has an order out.
    Team,
    /// Nothing: the session is over.
    Over(DoneReason),
}

/// A session.
pub struct Session {
    expect: Expect,
    max_scans: u64,
    run: Option<Run>,
}

/// A session's run: one robot, or a team.
enum Run {
    One(One),
    Team(Box<RoiRun>),
}

/// One robot's run.
enum One {
    Polygon(Box<PolygonRun>),
    Corner(Box<CornerRun>),
}

/// What a session does first.
enum Begin {
    /// One robot's action.
    Action(Action<Point>),
    /// A team's orders.
    Orders(Vec<Order>),
}

impl std::fmt::Debug for Session {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Session").field("expect", &self.expect).finish_non_exhaustive()
    }
}

/// The odometry bookkeeping every family shares: the pose last reported and the tally.
#[derive(Debug, Clone, Copy)]
pub(super) struct Odometry {
    last: Pose,
    pub(super) tally: Tally,
    /// Metres driven since the last scan.
    since_scan: f64,
}

impl Odometry {
    pub(super) fn new(start: Pose) -> Self {
        Self { last: start, tally: Tally::default(), since_scan: 0.0 }
    }

    /// The robot reports `pose` after a move: the metres since the last report join the
    /// tally (a move that went nowhere is not counted).
    pub(super) fn moved(&mut self, pose: Pose) {
        let d = (pose.x - self.last.x).hypot(pose.y - self.last.y);
        if d > 0.0 {
            self.tally.moves += 1;
            self.tally.distance += d;
            self.since_scan += d;
        }
        self.last = pose;
    }
}

struct PolygonRun {
    strategy: Box<dyn PolygonStrategy + Send>,
    cost: CostModel,
    mapper: Mapper,
    odometry: Odometry,
    /// The map frame from the odometry frame, both moved by `local`: the local map frame
    /// from the local odometry frame.
    correction: Pose,
    /// Where the frames the mapper and the strategy compute in lie in the map frame and in the
    /// odometry frame: [`Frame::near`] the start, the identity within 512 m of the origin.
    /// Odometry far from its origin (a georeferenced frame, say) would otherwise scale the
    /// strategies' tolerances (made relative to the coordinates' magnitude) far beyond a map's.
    local: Frame,
    /// Relays ([`Mapper::relay`]): the threshold, metres (0 never).
    relay: f64,
    /// The last scan's beams and `range_max`: the lidar a relay's prediction casts.
    lidar: Option<(usize, f64)>,
    /// Relays since the strategy's last scan.
    relays: usize,
    /// While the robot drives to a relay or scans there: the strategy's move it stopped on
    /// the way of, to be driven after the relay's scan.
    resume: Option<Point>,
}

struct CornerRun {
    strategy: StopListStrategy,
    setup: CornerSetup,
    /// The corner frame (the robot's start, facing the corner) in the odometry frame.
    frame: Pose,
    odometry: Odometry,
    /// The stop the robot stands at, radians.
    angle: f64,
    /// The stop it was sent to.
    target: Option<Stop>,
}

impl Session {
    /// A session that waits for `start` and ends after `max_scans` scans.
    pub fn new(max_scans: u64) -> Self {
        Self { expect: Expect::Start, max_scans, run: None }
    }

    /// Whether the session is over, and why.
    pub fn over(&self) -> Option<DoneReason> {
        match self.expect {
            Expect::Over(r) => Some(r),
            _ => None,
        }
    }

    /// One step: the reply to `request`, and localisation for a polygon scan.
    ///
    /// # Errors
    /// [`ProtocolError`] for a request out of order or with invalid contents; the session is
    /// unchanged.
    ///
    /// # Panics
    /// Never: every request but `start` is refused before the session has started.
    pub fn step(
        &mut self,
        request: &Request,
    ) -> Result<(ReplyBody, Option<Localised>), ProtocolError> {
        let out_of_order = |expected: &str| {
            Err(ProtocolError::field(
                "type",
                format!("expected {expected}, got {:?}", request.kind()),
            ))
        };
        if matches!(self.run, Some(Run::One(_))) && !matches!(self.expect, Expect::Over(_)) {
            single(request)?;
        }
        match (self.expect, request) {
            (Expect::Over(reason), _) => Err(ProtocolError::field(
                "type",
                format!(
                    "the session is over ({}); start a new server for a new session",
                    serde_json::to_value(reason).expect("a name")
                ),
            )),
            (Expect::Start, Request::Start(s)) => {
                let (run, begin) = Run::start(s)?;
                self.run = Some(run);
                match begin {
                    Begin::Action(action) => Ok((self.answer(action, false), None)),
                    Begin::Orders(orders) => Ok((self.orders(Outcome::Orders(orders)), None)),
                }
            }
            (Expect::Start, _) => out_of_order("\"start\""),
            (_, Request::Start(_)) => Err(ProtocolError::field(
                "type",
                "the session has started already; one server runs one session",
            )),
            (_, Request::Found(p) | Request::Stop(p)) => {
                match self.run.as_mut().expect("started") {
                    Run::Team(team) => team.ending(request)?,
                    Run::One(run) => {
                        check_pose("pose", &p.pose)?;
                        run.odometry().moved(p.pose);
                    }
                }
                let reason = if matches!(request, Request::Found(_)) {
                    DoneReason::Found
                } else {
                    DoneReason::Stopped
                };
                Ok((self.finish(reason), None))
            }
            (Expect::Team, _) => {
                let outcome = self.team().report(request)?;
                Ok((self.orders(outcome), None))
            }
            (Expect::Move, Request::Arrived(p)) => {
                check_pose("pose", &p.pose)?;
                let action = self.one().arrived(p.pose);
                Ok((self.answer(action, false), None))
            }
            (Expect::Move, Request::MoveFailed(f)) => {
                check_pose("pose", &f.pose)?;
                match self.one().failed(f) {
                    Some(action) => Ok((self.answer(action, true), None)),
                    None => Ok((self.finish(DoneReason::Blocked), None)),
                }
            }
            (Expect::Move, _) => out_of_order("\"arrived\" or \"move_failed\" (a goal is out)"),
            (Expect::Scan, Request::Scan(s)) => {
                check_pose("pose", &s.pose)?;
                let (action, localised) = self.one().scanned(s)?;
                if matches!(action, Action::Scan) {
                    return Ok((self.finish(DoneReason::NoProgress), localised));
                }
                Ok((self.answer(action, false), localised))
            }
            (Expect::Scan, _) => out_of_order("\"scan\" (a scan was asked for)"),
        }
    }

    /// The one robot's run (the session expects a move or a scan, so it has started with one
    /// robot).
    fn one(&mut self) -> &mut One {
        match self.run.as_mut() {
            Some(Run::One(one)) => one,
            _ => unreachable!("only a one-robot session expects a move or a scan"),
        }
    }

    /// The team's run (the session expects team reports).
    fn team(&mut self) -> &mut RoiRun {
        match self.run.as_mut() {
            Some(Run::Team(team)) => team,
            _ => unreachable!("only a team session expects team reports"),
        }
    }

    /// The reply to the strategy's action; `failing` when it answers a failed move.
    fn answer(&mut self, action: Action<Point>, failing: bool) -> ReplyBody {
        let max_scans = self.max_scans;
        match action {
            Action::Scan if self.one().scans() >= max_scans => self.finish(DoneReason::Limit),
            Action::Scan => {
                self.expect = Expect::Scan;
                ReplyBody::Scan
            }
            Action::MoveTo { to } => {
                let to = self.one().relay_for(to).unwrap_or(to);
                let (goal, map_goal, stop) = self.one().goal(to);
                self.expect = Expect::Move;
                ReplyBody::Goal { goal, map_goal, stop }
            }
            Action::Done if failing => self.finish(DoneReason::Stuck),
            Action::Done => self.finish(DoneReason::Explored),
        }
    }

    /// The reply to a team's orders (or its end).
    fn orders(&mut self, outcome: Outcome) -> ReplyBody {
        let max_scans = self.max_scans;
        match outcome {
            Outcome::Orders(o) if RoiRun::asks_scan(&o) && self.team().scans() >= max_scans => {
                self.finish(DoneReason::Limit)
            }
            Outcome::Orders(orders) => {
                self.expect = Expect::Team;
                ReplyBody::Orders { orders }
            }
            Outcome::Over(reason) => self.finish(reason),
        }
    }

    fn finish(&mut self, reason: DoneReason) -> ReplyBody {
        self.expect = Expect::Over(reason);
        let summary = self.run.as_ref().expect("started").summary();
        ReplyBody::Done { reason, summary }
    }
}

/// A one-robot family's request names no robot of a team and no team clock.
fn single(request: &Request) -> Result<(), ProtocolError> {
    match request.team_fields() {
        Some((Some(r), _, _)) if r != 0 => Err(ProtocolError::field(
            "robot",
            "is for the roi family (a team); this session has one robot",
        )),
        Some((_, Some(_), _)) => Err(ProtocolError::field("time", "is for the roi family")),
        _ => Ok(()),
    }
}

/// The largest position coordinate a pose may have, metres. Doubles there are 1.2e-7 m apart,
/// fine enough for a robot's motion; far beyond it (1e16 m, say) a metre's drive does not
/// change the number at all, and a goal would be sent to where the robot stands.
pub(super) const MAX_COORDINATE: f64 = 1e9;

/// A pose must be finite, and its position within [`MAX_COORDINATE`] of the odometry
/// frame's origin.
pub(super) fn check_pose(field: &str, p: &Pose) -> Result<(), ProtocolError> {
    if !p.is_finite() {
        return Err(ProtocolError::field(
            field,
            format!("every coordinate must be finite, got {p:?}"),
        ));
    }
    for (axis, v) in [("x", p.x), ("y", p.y)] {
        if v.abs() > MAX_COORDINATE {
            return Err(ProtocolError::field(
                format!("{field}.{axis}"),
                format!(
                    "must lie within ±{} m of the odometry frame's origin, got {}",
                    Num(MAX_COORDINATE),
                    Num(v)
                ),
            ));
        }
    }
    Ok(())
}

/// A number must be finite and at least 0.
fn non_negative(field: &str, v: f64) -> Result<f64, ProtocolError> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(ProtocolError::field(field, format!("must be a finite number >= 0, got {}", Num(v))))
    }
}

impl Run {
    fn start(s: &StartIn) -> Result<(Self, Begin), ProtocolError> {
        check_pose("pose", &s.pose)?;
        let cost = match s.cost {
            None => CostModel::default(),
            Some(c) => CostModel::new(c.scan_time, c.move_time, c.speed)
                .map_err(|e| ProtocolError::field("cost", e.to_string()))?,
        };
        // What each family's set-up is made of; anything else is refused, named.
        let parts = [
            ("robot", s.robot.is_some(), Family::Polygon),
            ("sensor", s.sensor.is_some(), Family::Polygon),
            ("odometry_drift", s.odometry_drift.is_some(), Family::Polygon),
            ("relay", s.relay.is_some(), Family::Polygon),
            ("corner", s.corner.is_some(), Family::Corner),
            ("roi", s.roi.is_some(), Family::Roi),
        ];
        for (field, present, family) in parts {
            if present && family != s.family {
                return Err(ProtocolError::field(
                    field,
                    format!("is for the {} family", family.name()),
                ));
            }
        }
        match (s.family, &s.corner, &s.roi) {
            (Family::Polygon, _, _) => {
                let mut run = PolygonRun::new(s, cost)?;
                let action = run.strategy.act(&Feedback::Start { at: run.map_pose(s.pose).at() });
                Ok((Self::One(One::Polygon(Box::new(run))), Begin::Action(action)))
            }
            (Family::Corner, Some(corner), _) => {
                let mut run = CornerRun::new(s, corner, cost)?;
                let action = run.act(CornerFeedback::Start);
                Ok((Self::One(One::Corner(Box::new(run))), Begin::Action(action)))
            }
            (Family::Corner, None, _) => Err(ProtocolError::field(
                "corner",
                "missing: the corner family needs {\"distance\": D}",
            )),
            (Family::Roi, _, Some(roi)) => {
                let (run, orders) = RoiRun::start(s, roi, cost)?;
                Ok((Self::Team(Box::new(run)), Begin::Orders(orders)))
            }
            (Family::Roi, _, None) => {
                Err(ProtocolError::field("roi", "missing: the roi family needs {\"robots\": N}"))
            }
        }
    }

    fn summary(&self) -> Summary {
        match self {
            Self::One(one) => one.summary(),
            Self::Team(team) => team.summary(),
        }
    }
}

impl One {
    fn odometry(&mut self) -> &mut Odometry {
        match self {
            Self::Polygon(r) => &mut r.odometry,
            Self::Corner(r) => &mut r.odometry,
        }
    }

    fn scans(&self) -> u64 {
        match self {
            Self::Polygon(r) => r.odometry.tally.scans,
            Self::Corner(r) => r.odometry.tally.scans,
        }
    }

    fn arrived(&mut self, pose: Pose) -> Action<Point> {
        match self {
            Self::Polygon(r) => {
                r.odometry.moved(pose);
                if r.resume.is_some() {
                    // At a relay: its scan, of which the strategy is not told.
                    return Action::Scan;
                }
                r.strategy.act(&Feedback::Arrived)
            }
            Self::Corner(r) => {
                r.odometry.moved(pose);
                if let Some(t) = r.target.take() {
                    r.angle = t.angle.min(crate::protocol::corner::CORNER);
                }
                r.act(CornerFeedback::Arrived)
            }
        }
    }

    /// A failed move: the strategy's next action, or `None` when the family has no other
    /// way to go (the corner search's circle).
    fn failed(&mut self, f: &FailedIn) -> Option<Action<Point>> {
        match self {
            Self::Polygon(r) => {
                r.odometry.moved(f.pose);
                // A relay on the way that could not be reached: the strategy's move failed.
                r.resume = None;
                let at = r.map_pose(f.pose).at();
                Some(r.strategy.act(&Feedback::MoveFailed { at, reason: f.reason }))
            }
            Self::Corner(r) => {
                r.odometry.moved(f.pose);
                None
            }
        }
    }

    fn scanned(&mut self, s: &ScanIn) -> Result<(Action<Point>, Option<Localised>), ProtocolError> {
        match self {
            Self::Polygon(r) => r.scanned(s),
            Self::Corner(r) => r.scanned(s).map(|a| (a, None)),
        }
    }

    /// Where the robot should stop for a relay on the strategy's move to `to`, if anywhere
    /// ([`Mapper::relay`]); the move is driven after the relay's scan.
    fn relay_for(&mut self, to: Point) -> Option<Point> {
        let Self::Polygon(r) = self else { return None };
        let (beams, range) = r.lidar?;
        if r.relays >= MAX_RELAYS {
            return None;
        }
        let mut trip = vec![r.map_pose(r.odometry.last).at(), to];
        trip.extend(r.strategy.ahead());
        let at = r.mapper.relay(&trip, r.odometry.since_scan, beams, range, r.relay)?;
        r.resume = Some(to);
        Some(at)
    }

    /// The goal for a strategy's place: in the odometry frame, in the map frame, and the
    /// corner stop.
    fn goal(&self, to: Point) -> (Pose, Pose, Option<Stop>) {
        match self {
            Self::Polygon(r) => {
                let here = r.map_pose(r.odometry.last);
                let (dx, dy) = (to[0] - here.x, to[1] - here.y);
                let heading = if dx == 0.0 && dy == 0.0 { here.theta } else { dy.atan2(dx) };
                let map_goal = Pose::new(to, heading);
                let goal = r.correction.inverse().compose(&map_goal);
                (r.to_input(goal), r.to_input(map_goal), None)
            }
            Self::Corner(r) => {
                let stop = r.target.expect("a corner goal has its stop");
                let here = r.setup.position(r.angle);
                let (dx, dy) = (to[0] - here[0], to[1] - here[1]);
                let heading = if dx == 0.0 && dy == 0.0 { 0.0 } else { dy.atan2(dx) };
                let map_goal = Pose::new(to, heading);
                (r.frame.compose(&map_goal), map_goal, Some(stop))
            }
        }
    }

    fn summary(&self) -> Summary {
        let (strategy, tally, cost, windows) = match self {
            Self::Polygon(r) => (
                r.strategy.name().to_string(),
                r.odometry.tally,
                r.cost,
                Some(r.strategy.skipped()),
            ),
            Self::Corner(r) => {
                (r.strategy.name().to_string(), r.odometry.tally, r.setup.cost, None)
            }
        };
        let terms = cost.price(&tally);
        Summary {
            strategy,
            totals: RunTotals::new(&tally, terms.total(), &terms),
            windows,
            team: None,
        }
    }
}

impl PolygonRun {
    fn new(s: &StartIn, cost: CostModel) -> Result<Self, ProtocolError> {
        let name = s.strategy.as_deref().unwrap_or(DEFAULT_POLYGON_STRATEGY);
        let robot = s.robot.clone().unwrap_or_default();
        let footprint = match (robot.radius, robot.footprint) {
            (Some(_), Some(_)) => {
                return Err(ProtocolError::field("robot", "give radius or footprint, not both"));
            }
            (Some(r), None) => Footprint::disc(r)
                .map_err(|e| ProtocolError::field("robot.radius", e.to_string()))?,
            (None, Some(v)) => Footprint::convex(v)
                .map_err(|e| ProtocolError::field("robot.footprint", e.to_string()))?,
            (None, None) => Footprint::Point,
        };
        let sensor = s.sensor.unwrap_or_default();
        let sigma = non_negative("sensor.sigma", sensor.sigma.unwrap_or(DEFAULT_SIGMA))?;
        let drift = non_negative("odometry_drift", s.odometry_drift.unwrap_or(DEFAULT_DRIFT))?;
        if drift > 0.5 {
            return Err(ProtocolError::field(
                "odometry_drift",
                format!("must be a share of the distance driven in [0, 0.5], got {}", Num(drift)),
            ));
        }
        let range = sensor.range.map(|r| non_negative("sensor.range", r)).transpose()?;
        if range == Some(0.0) {
            return Err(ProtocolError::field("sensor.range", "must be above 0"));
        }
        if sensor.beams == Some(0) {
            return Err(ProtocolError::field("sensor.beams", "must be at least 1"));
        }
        let min_window = match sensor.min_window {
            Some(w) => non_negative("sensor.min_window", w)?,
            None => footprint.width(),
        };
        let robot = RobotSetup {
            cost,
            sensor: Sensor {
                range,
                beams: sensor.beams,
                min_feature: non_negative("sensor.min_feature", sensor.min_feature.unwrap_or(0.0))?,
                min_window,
                min_pocket: default_min_pocket(&footprint, None),
                pocket_cap: DEFAULT_POCKET_CAP,
                pocket_budget: Some(DEFAULT_POCKET_BUDGET),
                wall_tolerance: 0.0,
            },
            footprint,
        };
        let setup = raw_scan_planning(&robot, sigma);
        let strategy = polygon::build_for(name, &setup)
            .map_err(|e| ProtocolError::field("strategy", e.to_string()))?;
        if name == "range_limited" && range.is_none() {
            return Err(ProtocolError::field(
                "sensor.range",
                "missing: range_limited needs the sensor's range",
            ));
        }
        let mut params = MapperParams::for_sensor(sigma, drift, HEADING_DRIFT * drift);
        params.ingest = params.ingest.bridging(min_window);
        let relay = non_negative("relay", s.relay.unwrap_or(RELAY))?;
        Ok(Self {
            strategy,
            cost,
            mapper: Mapper::new(params),
            odometry: Odometry::new(s.pose),
            correction: Pose::default(),
            local: Frame::near(s.pose.at()),
            relay,
            lidar: None,
            relays: 0,
            resume: None,
        })
    }

    /// A pose in the odometry frame, in the local map frame.
    fn map_pose(&self, odometry: Pose) -> Pose {
        let at = self.local.to_local(odometry.at());
        self.correction.compose(&Pose::new(at, odometry.theta))
    }

    /// A pose of a local frame in the input's frame (map or odometry).
    fn to_input(&self, local: Pose) -> Pose {
        Pose::new(self.local.to_input(local.at()), local.theta)
    }

    fn scanned(&mut self, s: &ScanIn) -> Result<(Action<Point>, Option<Localised>), ProtocolError> {
        s.readings_for(Family::Polygon)?;
        let Some(scan) = &s.scan else {
            return Err(ProtocolError::field(
                "scan",
                "missing: the polygon family reads laser scans",
            ));
        };
        let guess = self.map_pose(s.pose);
        let mut odometry = self.odometry;
        odometry.moved(s.pose);
        // The mapper checks the scan before it changes anything, and the session changes only
        // after it: a refused scan leaves the session as it was.
        let reading = self.mapper.read(scan, &guess, odometry.since_scan).map_err(|e| match e {
            IngestError::Scan(InvalidScan::Field { field, problem }) => {
                ProtocolError::field(format!("scan.{field}"), problem)
            }
            other => ProtocolError::field("scan", other.to_string()),
        })?;
        self.odometry = odometry;
        self.odometry.since_scan = 0.0;
        self.odometry.tally.scans += 1;
        let odometry = Pose::new(self.local.to_local(s.pose.at()), s.pose.theta);
        self.correction = reading.estimate.compose(&odometry.inverse());
        let estimate = self.to_input(reading.estimate);
        self.lidar = Some((scan.ranges.len(), scan.range_max));
        let action = if let Some(to) = self.resume.take() {
            // A relay's scan places the robot; the strategy's move goes on.
            self.relays += 1;
            Action::MoveTo { to }
        } else {
            self.relays = 0;
            self.strategy.act(&Feedback::Scanned(reading.observation))
        };
        let alignment = reading.alignment.map(|mut a| {
            (a.guess, a.pose) = (self.to_input(a.guess), self.to_input(a.pose));
            a
        });
        let localised = Localised {
            pose: estimate,
            correction: estimate.compose(&s.pose.inverse()),
            alignment,
            placement_sd: reading.placement,
            cleaning: reading.cleaning,
        };
        Ok((action, Some(localised)))
    }
}

impl CornerRun {
    fn new(s: &StartIn, c: &CornerIn, cost: CostModel) -> Result<Self, ProtocolError> {
        let name = s.strategy.as_deref().unwrap_or(DEFAULT_CORNER_STRATEGY);
        let setup = CornerSetup::new(c.distance, cost)
            .map_err(|e| ProtocolError::field("corner.distance", e.to_string()))?;
        let spec = c.belief.as_deref().unwrap_or(DEFAULT_BELIEF);
        if spec.starts_with("histogram:") || spec.starts_with("observed:") {
            return Err(ProtocolError::field(
                "corner.belief",
                "beliefs read from files are not accepted over the protocol; give uniform, normal or mix",
            ));
        }
        let belief = AngleDistribution::parse(spec)
            .map_err(|e| ProtocolError::field("corner.belief", e.to_string()))?;
        let mut options = BuildOptions::default();
        options.route = c.route.unwrap_or(options.route);
        options.last_step = c.last_step.unwrap_or(options.last_step);
        options.exprec = c.exprec.unwrap_or(options.exprec);
        if let Some(d) = c.mdp_step_degrees {
            if !(d.is_finite() && d > 0.0 && d <= 90.0) {
                return Err(ProtocolError::field(
                    "corner.mdp_step_degrees",
                    format!("must be in (0, 90], got {}", Num(d)),
                ));
            }
            options.mdp_step = d.to_radians();
        }
        let list = registry::build(name, &setup, &belief, &options)
            .map_err(|e| ProtocolError::field("strategy", e.to_string()))?;
        Ok(Self {
            strategy: list.into_strategy(name),
            setup,
            frame: s.pose,
            odometry: Odometry::new(s.pose),
            angle: 0.0,
            target: None,
        })
    }

    /// The strategy's action, its stop as a point of the corner frame.
    fn act(&mut self, feedback: CornerFeedback) -> Action<Point> {
        match self.strategy.act(feedback) {
            Action::MoveTo { to } => {
                self.target = Some(to);
                Action::MoveTo {
                    to: self.setup.position(to.angle.min(crate::protocol::corner::CORNER)),
                }
            }
            Action::Scan => Action::Scan,
            Action::Done => Action::Done,
        }
    }

    fn scanned(&mut self, s: &ScanIn) -> Result<Action<Point>, ProtocolError> {
        s.readings_for(Family::Corner)?;
        let observation = match s.edge {
            None => CornerObservation::Hidden,
            Some(theta) if theta.is_finite() && theta >= 0.0 => CornerObservation::Seen { theta },
            Some(theta) => {
                return Err(ProtocolError::field(
                    "edge",
                    format!("must be an angle >= 0 in radians, got {}", Num(theta)),
                ));
            }
        };
        self.odometry.moved(s.pose);
        self.odometry.tally.scans += 1;
        Ok(self.act(CornerFeedback::Scanned(observation)))
    }
}
