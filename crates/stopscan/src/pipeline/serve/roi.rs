//! A team's session (family `roi`): every robot of a team that maps a region of interest cell
//! by cell (Algorithm 1 of the ROI paper, with the field experiment's optional search) reports
//! through one connection, by index, and gets its orders back.
//!
//! # Meetings
//! In the simulator robots meet when they stand on the same cell at the same instant. A
//! server has no clock of its own, so it holds a meeting when the robots it sent off together
//! (one order, to the same cell, or the same scan) have all reported: those standing on the
//! same cell then meet, as they would have in the simulator had they flown the same leg at the
//! same speed. Robots that reach a cell separately do not wait for one another; they learn of
//! each other only through the records on the cells, which is all Algorithm 1 needs (the
//! paper's robots are asynchronous).
//!
//! # Frames and time
//! Cell `[0, 0]` is centred on the team's start pose and the grid's axes are the pose's: `+x`
//! along its heading is the columns' direction, rows grow towards `−y`. A drifting region
//! moves at `speed` towards `heading_deg` in that frame. A goal names its cell, the cell's
//! centre in the region's frame (`map_goal`), and where that centre will be in the odometry
//! frame when the robot gets there (`goal`, at `eta` on the team's clock, predicted by the
//! time model). Robots report the team's clock with `time`; a drifting region needs it, a
//! static one does not (the server then keeps the time model's clock).

use super::message::{
    DoneReason, FailedIn, Family, Order, OrderKind, ProtocolError, Request, RoiIn, ScanIn, StartIn,
    Summary, TeamSummary,
};
use super::session::Odometry;
use crate::kernel::Num;
use crate::protocol::grid::{Cell, CellSet, GridObservation, Marks, TimeModel};
use crate::protocol::laser::Pose;
use crate::protocol::{Action, CostModel, Feedback, RunTotals, Tally};
use crate::sim::confer;
use crate::sim::grid::{MAX_FRAMES, MissionPlan, Search};
use crate::strategy::grid::{GridFeedback, GridStrategy, MissionRobot};
use crate::strategy::polygon::MAX_MOVE_FAILURES;
use crate::world::grid::Blackboard;

/// The team's start cell (and the search's launch cell).
const HOME: Cell = [0, 0];

/// The largest search box side, in cells.
const MAX_SEARCH_SIDE: i64 = 1 << 20;

/// The largest cell, metres (ten kilometres): goals stay finite in every frame.
const MAX_CELL_SIZE: f64 = 1e4;

/// The fastest drift, metres per second.
const MAX_DRIFT_SPEED: f64 = 1e3;

/// The latest team clock, seconds (about 31 years).
const MAX_TIME: f64 = 1e9;

/// What a robot of the team is doing.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Task {
    /// Flying to a cell.
    Moving(Cell),
    /// Scanning.
    Scanning,
    /// Reported; waits for the robots sent off with it.
    Ready,
    /// Done.
    Done,
}

/// One robot of the team.
#[derive(Debug, Clone)]
struct Member {
    at: Cell,
    feedback: GridFeedback,
    task: Task,
    /// The robots sent off together share a flight.
    flight: u64,
    odometry: Odometry,
    /// Failed moves in a row.
    failures: u32,
    /// The team's clock at its last report, or when its last order was given.
    clock: f64,
    /// When the time model expects its report (for a static region, whose robots need not
    /// report the clock).
    due: f64,
}

/// A team's session.
pub(super) struct RoiRun {
    robots: Vec<MissionRobot>,
    members: Vec<Member>,
    board: Blackboard,
    marks: Marks,
    visited: CellSet,
    cost: CostModel,
    times: TimeModel,
    /// The region's frame (cell `[0, 0]`'s centre and the grid's axes) at time 0, in the
    /// odometry frame.
    origin: Pose,
    flights: u64,
}

/// What a report leads to.
pub(super) enum Outcome {
    /// Orders (possibly none).
    Orders(Vec<Order>),
    /// The session ends.
    Over(DoneReason),
}

impl RoiRun {
    /// A team at its start, and the first orders.
    pub(super) fn start(
        s: &StartIn,
        r: &RoiIn,
        cost: CostModel,
    ) -> Result<(Self, Vec<Order>), ProtocolError> {
        if s.strategy.as_deref().is_some_and(|n| n != "recursive_dfs") {
            return Err(ProtocolError::field(
                "strategy",
                "the roi family runs recursive_dfs (Algorithm 1); leave it out or name it",
            ));
        }
        if !(1..=super::message::MAX_TEAM).contains(&r.robots) {
            return Err(ProtocolError::field(
                "roi.robots",
                format!("must be 1 to {}, got {}", super::message::MAX_TEAM, r.robots),
            ));
        }
        let cell_size = r.cell_size.unwrap_or(1.0);
        if !(cell_size > 0.0 && cell_size <= MAX_CELL_SIZE) {
            return Err(ProtocolError::field(
                "roi.cell_size",
                format!(
                    "must be above 0 and at most {} metres, got {}",
                    Num(MAX_CELL_SIZE),
                    Num(cell_size)
                ),
            ));
        }
        let (drift_speed, heading_deg) = r.drift.map_or((0.0, 0.0), |d| (d.speed, d.heading_deg));
        if !(0.0..=MAX_DRIFT_SPEED).contains(&drift_speed) {
            return Err(ProtocolError::field(
                "roi.drift.speed",
                format!(
                    "must be at least 0 and at most {} m/s, got {}",
                    Num(MAX_DRIFT_SPEED),
                    Num(drift_speed)
                ),
            ));
        }
        if !heading_deg.is_finite() {
            return Err(ProtocolError::field("roi.drift.heading_deg", "must be finite"));
        }
        if cost.speed <= drift_speed {
            return Err(ProtocolError::field(
                "cost.speed",
                format!(
                    "the robots ({} m/s) must be faster than the region drifts ({} m/s)",
                    Num(cost.speed),
                    Num(drift_speed)
                ),
            ));
        }
        let search = match r.search {
            None => None,
            Some(b) => {
                for k in 0..2 {
                    let side = i64::from(b.max[k]) - i64::from(b.min[k]) + 1;
                    if !(1..=MAX_SEARCH_SIDE).contains(&side) {
                        return Err(ProtocolError::field(
                            "roi.search",
                            format!(
                                "min must not exceed max, and a side spans at most {MAX_SEARCH_SIDE} cells; got {:?} to {:?}",
                                b.min, b.max
                            ),
                        ));
                    }
                }
                Some(Search { launch: HOME, min: b.min, max: b.max })
            }
        };
        let times = TimeModel { robot_speed: cost.speed, drift_speed, heading_deg, cell_size };
        let plan = MissionPlan { robots: r.robots, cost, battery_s: None, search, map: true };
        let robots = (0..r.robots).map(|i| plan.robot(i, times)).collect();
        let mut board = Blackboard::unbounded();
        if search.is_none() {
            board.plant_root(HOME);
        }
        let member = Member {
            at: HOME,
            feedback: Feedback::Start { at: HOME },
            task: Task::Ready,
            flight: 0,
            odometry: Odometry::new(s.pose),
            failures: 0,
            clock: 0.0,
            due: 0.0,
        };
        let mut run = Self {
            robots,
            members: vec![member; r.robots],
            board,
            marks: Marks::default(),
            visited: std::iter::once(HOME).collect(),
            cost,
            times,
            origin: s.pose,
            flights: 1,
        };
        let orders = run.release(0);
        Ok((run, orders))
    }

    /// The team's scans so far.
    pub(super) fn scans(&self) -> u64 {
        self.members.iter().map(|m| m.odometry.tally.scans).sum()
    }

    /// Whether an order asks for a scan.
    pub(super) fn asks_scan(orders: &[Order]) -> bool {
        orders.iter().any(|o| matches!(o.what, OrderKind::Scan { .. }))
    }

    /// The robot a request names, checked, and its clock.
    fn reporter(&self, request: &Request) -> Result<(usize, f64), ProtocolError> {
        let (robot, time, pose) = request.team_fields().expect("not a start");
        let Some(i) = robot else {
            return Err(ProtocolError::field(
                "robot",
                "missing: every request of a team names its robot (0 to robots − 1)",
            ));
        };
        let Some(m) = self.members.get(i) else {
            return Err(ProtocolError::field(
                "robot",
                format!("the team has robots 0 to {}, got {i}", self.members.len() - 1),
            ));
        };
        super::session::check_pose("pose", &pose)?;
        let clock = match time {
            Some(t) if !(0.0..=MAX_TIME).contains(&t) => {
                return Err(ProtocolError::field(
                    "time",
                    format!("must be between 0 and {} seconds, got {}", Num(MAX_TIME), Num(t)),
                ));
            }
            Some(t) if t < m.clock => {
                return Err(ProtocolError::field(
                    "time",
                    format!("robot {i}'s clock went back: {} s after {} s", Num(t), Num(m.clock)),
                ));
            }
            Some(t) => t,
            None if self.times.drift_speed > 0.0 => {
                return Err(ProtocolError::field(
                    "time",
                    "missing: on a drifting region every report gives the team's clock",
                ));
            }
            None => m.due,
        };
        Ok((i, clock))
    }

    /// `found` or `stop` from one robot: it is checked and its odometry counted.
    pub(super) fn ending(&mut self, request: &Request) -> Result<(), ProtocolError> {
        let (i, clock) = self.reporter(request)?;
        let (_, _, pose) = request.team_fields().expect("not a start");
        let m = &mut self.members[i];
        m.odometry.moved(pose);
        m.clock = clock;
        Ok(())
    }

    /// One robot's report: `arrived`, `move_failed` or `scan`. The session is unchanged when
    /// it is refused.
    pub(super) fn report(&mut self, request: &Request) -> Result<Outcome, ProtocolError> {
        let (i, clock) = self.reporter(request)?;
        let m = &self.members[i];
        let expected = match m.task {
            Task::Moving(_) => "\"arrived\" or \"move_failed\" (a goal is out)",
            Task::Scanning => "\"scan\" (a scan was asked for)",
            Task::Ready => "nothing: it waits for the robots sent off with it",
            Task::Done => "nothing: it is done",
        };
        let out_of_order = || {
            ProtocolError::field(
                "type",
                format!("robot {i}: expected {expected}, got {:?}", request.kind()),
            )
        };
        let mut m = m.clone();
        match (m.task, request) {
            (Task::Moving(to), Request::Arrived(p)) => {
                m.odometry.moved(p.pose);
                m.at = to;
                m.feedback = Feedback::Arrived;
                m.failures = 0;
                self.visited.insert(to);
            }
            (Task::Moving(_), Request::MoveFailed(f)) => {
                let FailedIn { pose, reason, .. } = *f;
                m.odometry.moved(pose);
                m.feedback = Feedback::MoveFailed { at: m.at, reason };
                m.failures += 1;
                if m.failures >= MAX_MOVE_FAILURES {
                    m.clock = clock;
                    self.members[i] = m;
                    return Ok(Outcome::Over(DoneReason::Stuck));
                }
            }
            (Task::Scanning, Request::Scan(s)) => {
                let observation = observation(s, m.at)?;
                m.odometry.moved(s.pose);
                m.odometry.tally.scans += 1;
                self.marks.absorb(&observation);
                m.feedback = Feedback::Scanned(observation);
            }
            _ => return Err(out_of_order()),
        }
        m.task = Task::Ready;
        m.clock = clock;
        let flight = m.flight;
        self.members[i] = m;
        if self.members.iter().any(|o| o.flight == flight && o.task != Task::Ready) {
            return Ok(Outcome::Orders(Vec::new()));
        }
        let orders = self.release(flight);
        if self.members.iter().all(|m| m.task == Task::Done) {
            let not_found = self.robots.iter().any(|r| r.inner().not_found);
            return Ok(Outcome::Over(if not_found {
                DoneReason::NotFound
            } else {
                DoneReason::Explored
            }));
        }
        Ok(Outcome::Orders(orders))
    }

    /// Holds the meetings of flight `flight` (its robots have all reported): the robots on
    /// the same cell meet, in the order of their lowest index, and each gets its order.
    fn release(&mut self, flight: u64) -> Vec<Order> {
        let mut waiting: Vec<usize> = (0..self.members.len())
            .filter(|&i| self.members[i].flight == flight && self.members[i].task == Task::Ready)
            .collect();
        let mut orders = Vec::new();
        while let Some(&first) = waiting.first() {
            let at = self.members[first].at;
            let (group, rest): (Vec<usize>, Vec<usize>) =
                waiting.iter().partition(|&&i| self.members[i].at == at);
            waiting = rest;
            let clock = group.iter().map(|&i| self.members[i].clock).fold(0.0, f64::max);
            let members = &self.members;
            let actions = confer(
                &mut self.board,
                &mut self.robots,
                |i| &members[i].feedback,
                &at,
                clock,
                &group,
            );
            // One flight per distinct action of the group: robots sent to the same cell (or
            // scanning together) meet again when they have all reported.
            let mut sent: Vec<(Action<Cell>, u64)> = Vec::new();
            for (&i, action) in group.iter().zip(actions) {
                let flight = if let Some(&(_, f)) = sent.iter().find(|(a, _)| *a == action) {
                    f
                } else {
                    self.flights += 1;
                    sent.push((action, self.flights));
                    self.flights
                };
                orders.push(self.order(i, action, flight, clock));
            }
        }
        orders
    }

    /// Robot `i`'s order for `action`, in flight `flight`, at time `clock`.
    fn order(&mut self, i: usize, action: Action<Cell>, flight: u64, clock: f64) -> Order {
        let m = &mut self.members[i];
        m.flight = flight;
        m.clock = clock;
        let what = match action {
            Action::Scan => {
                m.task = Task::Scanning;
                m.due = clock + self.cost.scan_time;
                OrderKind::Scan { cell: m.at }
            }
            Action::MoveTo { to } => {
                m.task = Task::Moving(to);
                let seconds = self.times.seconds(m.at, to).unwrap_or(f64::INFINITY);
                let eta = if m.at == to { clock } else { clock + self.cost.move_time + seconds };
                m.due = eta;
                let map_goal = self.centre(to, 0.0);
                let goal = self.origin.compose(&self.centre(to, eta));
                OrderKind::Goal { cell: to, goal, map_goal, eta }
            }
            Action::Done => {
                m.task = Task::Done;
                m.due = clock;
                OrderKind::Done { cell: m.at }
            }
        };
        Order { robot: i, what }
    }

    /// Cell `c`'s centre at time `t`, in the region's frame at time 0 (the grid's own frame
    /// moved by the drift), heading along the grid's `+x`.
    fn centre(&self, c: Cell, t: f64) -> Pose {
        let h = self.times.heading_deg.to_radians();
        let s = self.times.drift_speed * t;
        let x = f64::from(c[1]) * self.times.cell_size + s * h.cos();
        let y = -f64::from(c[0]) * self.times.cell_size + s * h.sin();
        Pose { x, y, theta: 0.0 }
    }

    /// What the team did and mapped.
    pub(super) fn summary(&self) -> Summary {
        let per_robot: Vec<Tally> = self.members.iter().map(|m| m.odometry.tally).collect();
        let tally = per_robot.iter().fold(Tally::default(), |mut t, r| {
            t.scans += r.scans;
            t.moves += r.moves;
            t.distance += r.distance;
            t
        });
        let terms = self.cost.price(&tally);
        let makespan = self.members.iter().map(|m| m.clock).fold(0.0, f64::max);
        Summary {
            strategy: GridStrategy::name(&self.robots[0]).to_string(),
            totals: RunTotals::new(&tally, makespan, &terms),
            windows: None,
            team: Some(TeamSummary {
                robots: self.members.len(),
                per_robot,
                cells_visited: self.visited.len(),
                map: self.marks.positive(),
            }),
        }
    }
}

/// A team scan's frames, checked, as the observation of the cell the robot stands on.
fn observation(s: &ScanIn, at: Cell) -> Result<GridObservation, ProtocolError> {
    s.readings_for(Family::Roi)?;
    let Some(frames) = &s.frames else {
        return Err(ProtocolError::field(
            "frames",
            "missing: the roi family reports the camera frames over the cell",
        ));
    };
    if !(1..=MAX_FRAMES).contains(&frames.len()) {
        return Err(ProtocolError::field(
            "frames",
            format!("give 1 to {MAX_FRAMES} frames, got {}", frames.len()),
        ));
    }
    Ok(GridObservation { cell: at, frames: frames.clone() })
}
