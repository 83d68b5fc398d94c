//! Driving a team of grid robots against a grid world: a mission, whose whole state (the team
//! loop, every robot's strategy, the records left on the cells) is plain data that can be
//! written after every step and resumed.

use serde::{Deserialize, Serialize};

use super::{Agent, Arena, Flow, Leg, Meeting, NoObserver, Observer, Recording, SimError, Team};
use crate::kernel::tolerance::SAME_VALUE_REL;
use crate::protocol::grid::{
    Cell, CellMap, GridContext, GridObservation, Marks, Record, SIDES, sorted_map,
};
use crate::protocol::{Action, CostModel};
use crate::strategy::grid::{
    ALGORITHM_1, Battery, GridFeedback, GridStrategy, LawnMower, MissionRobot,
};
use crate::world::grid::{Blackboard, GridWorld};

/// A grid world as the loop sees it: moves priced by the drift, scans by its sensor, the
/// records on the cells as the robots' only medium besides meeting.
impl Meeting for GridWorld {
    type Place = Cell;
    type Observation = GridObservation;
    type Context = GridContext;
    type Note = Record;

    fn meet(&mut self, at: &Cell, _clock: f64, group: &[usize]) -> GridContext {
        self.arrive(*at, group)
    }

    fn leave(&mut self, at: &Cell, note: Record) {
        self.write(*at, note);
    }
}

/// A board of records with nobody's world behind it: the meeting place of robots that report
/// over a protocol (the server learns the region only from their scans).
impl Meeting for Blackboard {
    type Place = Cell;
    type Observation = GridObservation;
    type Context = GridContext;
    type Note = Record;

    fn meet(&mut self, at: &Cell, _clock: f64, group: &[usize]) -> GridContext {
        self.context(*at, group)
    }

    fn leave(&mut self, at: &Cell, note: Record) {
        self.write(*at, note);
    }
}

impl Arena for GridWorld {
    fn travel(&self, from: &Cell, to: &Cell, _clock: f64, cost: &CostModel) -> Option<Leg> {
        let step = [to[0] - from[0], to[1] - from[1]];
        let seconds = match SIDES.iter().position(|&d| d == step) {
            // One cell: the four unit times, computed once per robot speed.
            Some(i) => self.unit_seconds(cost)[i]?,
            None => self.time_model(cost).seconds(*from, *to)?,
        };
        Some(Leg { metres: seconds * cost.speed, seconds })
    }

    fn scan(&mut self, robot: usize, at: &Cell, clock: f64) -> Option<GridObservation> {
        Some(GridObservation { cell: *at, frames: self.sense(robot, *at, clock) })
    }
}

impl<
    S: GridStrategy,
    W: Meeting<Place = Cell, Observation = GridObservation, Context = GridContext, Note = Record>,
> Agent<W> for S
{
    fn name(&self) -> &str {
        GridStrategy::name(self)
    }
    fn act(&mut self, feedback: &GridFeedback, context: &GridContext) -> Action<Cell> {
        GridStrategy::act(self, feedback, context)
    }
    fn note(&mut self) -> Option<&Record> {
        GridStrategy::note(self)
    }
    fn report(&mut self, feedback: &GridFeedback) -> Option<Record> {
        GridStrategy::report(self, feedback)
    }
}

/// How a mission is flown.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MissionPlan {
    /// R, the number of robots.
    pub robots: usize,
    /// Scan time, per-move time and S_r (the robot speed).
    pub cost: CostModel,
    /// Flight seconds per battery (`None`: unlimited).
    pub battery_s: Option<f64>,
    /// A lawn-mowing search first: the launch cell and the box (min and max cells) known to
    /// contain part of the region. `None`: the robots start on the region's start cell.
    pub search: Option<Search>,
    /// Whether to build the map from every scan's vote ([`Marks`]: conservative marking).
    pub map: bool,
}

impl MissionPlan {
    /// The strategy of robot `i` (its index in the team) flying under `times`: Algorithm 1,
    /// inside the plan's search (if any), inside its battery (if any).
    pub fn robot(&self, i: usize, times: crate::protocol::grid::TimeModel) -> MissionRobot {
        let dfs = (ALGORITHM_1.build)(i);
        let searched = match self.search {
            Some(s) => LawnMower::sweep(dfs, s.min, s.max),
            None => LawnMower::none(dfs),
        };
        Battery::new(searched, self.battery_s, times, self.cost.scan_time, self.cost.move_time)
    }
}

/// The field experiment's search: launch cell and box.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Search {
    /// Where the robots take off (and land at the end).
    pub launch: Cell,
    /// The box's smallest row and column.
    pub min: Cell,
    /// Its largest row and column.
    pub max: Cell,
}

impl Search {
    /// The box's cells (as a float: a box may span more than `usize` on 32 bits).
    #[must_use]
    pub fn cells(&self) -> f64 {
        (f64::from(self.max[0]) - f64::from(self.min[0]) + 1.0)
            * (f64::from(self.max[1]) - f64::from(self.min[1]) + 1.0)
    }
}

/// Why a mission cannot start.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MissionError {
    /// No robots.
    #[error("a mission needs at least one robot")]
    NoRobots,
    /// The robots are not faster than the region.
    #[error(
        "the robot speed S_r = {} m/s must exceed the region's speed S_p = {} m/s",
        crate::kernel::Num(*.robot),
        crate::kernel::Num(*.region)
    )]
    TooSlow {
        /// S_r.
        robot: f64,
        /// S_p.
        region: f64,
    },
    /// The drift is not a finite, non-negative speed with a finite heading.
    #[error(
        "the region's speed must be finite and non-negative and its heading finite, got {} m/s at {}°",
        crate::kernel::Num(*.0),
        crate::kernel::Num(*.1)
    )]
    BadDrift(f64, f64),
    /// The camera takes no frames per scan, or more than [`MAX_FRAMES`]. Give 1 to 99 (the
    /// paper: 5, voted 3 of 5).
    #[error("the camera needs 1 to {MAX_FRAMES} frames per scan, got {0}")]
    Frames(usize),
    /// The battery is not a positive number of seconds.
    #[error("the battery must last a positive number of seconds, got {}", crate::kernel::Num(*.0))]
    BadBattery(f64),
}

/// The most frames per scan a camera mission takes (each frame is rendered and classified:
/// about 0.6 ms).
pub const MAX_FRAMES: usize = 99;

/// A mission in progress: everything needed to carry on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mission {
    /// How it is flown.
    pub plan: MissionPlan,
    /// The loop's state.
    pub team: Team<Cell, GridObservation>,
    /// Every robot's strategy.
    pub robots: Vec<MissionRobot>,
    /// The records on the cells (a copy of the world's, taken by [`Mission::snapshot`]).
    #[serde(with = "sorted_map")]
    pub boards: CellMap<Record>,
    /// The region cells robots have stood on (a copy of the world's count, taken by
    /// [`Mission::snapshot`]).
    pub visited: Vec<Cell>,
    /// The map so far, when the plan builds one.
    pub marks: Marks,
}

/// Absorbs every scan into the map, then passes events on.
struct Mapper<'a> {
    marks: Option<&'a mut Marks>,
    next: &'a mut dyn Observer<Cell, GridObservation>,
}

impl Observer<Cell, GridObservation> for Mapper<'_> {
    fn on_move(&mut self, robot: usize, to: &Cell, metres: f64) -> std::ops::ControlFlow<()> {
        self.next.on_move(robot, to, metres)
    }
    fn on_scan(
        &mut self,
        robot: usize,
        at: &Cell,
        o: &GridObservation,
    ) -> std::ops::ControlFlow<()> {
        if let Some(m) = self.marks.as_deref_mut() {
            m.absorb(o);
        }
        self.next.on_scan(robot, at, o)
    }
    fn on_finish(&mut self, tally: &crate::protocol::Tally) {
        self.next.on_finish(tally);
    }
}

impl Mission {
    /// A fresh mission in `world`.
    ///
    /// # Errors
    /// [`MissionError`] for no robots, robots no faster than the region, a bad drift or battery,
    /// or a camera with no frames.
    pub fn new(
        world: &GridWorld,
        plan: MissionPlan,
        recording: Recording,
    ) -> Result<Self, MissionError> {
        if plan.robots == 0 {
            return Err(MissionError::NoRobots);
        }
        if let crate::world::grid::GridSensor::Camera(c) = world.sensor()
            && !(1..=MAX_FRAMES).contains(&c.frames)
        {
            return Err(MissionError::Frames(c.frames));
        }
        let d = world.drift();
        if !(d.speed.is_finite() && d.speed >= 0.0 && d.heading_deg.is_finite()) {
            return Err(MissionError::BadDrift(d.speed, d.heading_deg));
        }
        if plan.cost.speed <= d.speed {
            return Err(MissionError::TooSlow { robot: plan.cost.speed, region: d.speed });
        }
        if let Some(b) = plan.battery_s
            && !(b.is_finite() && b > 0.0)
        {
            return Err(MissionError::BadBattery(b));
        }
        let times = world.time_model(&plan.cost);
        let start = plan.search.map_or(world.roi().start(), |s| s.launch);
        let robots = (0..plan.robots).map(|i| plan.robot(i, times)).collect();
        Ok(Self {
            team: Team::new(vec![start; plan.robots], recording),
            plan,
            robots,
            boards: CellMap::default(),
            visited: Vec::new(),
            marks: Marks::default(),
        })
    }

    /// One step of the team loop (one group of robots, one action each).
    ///
    /// # Errors
    /// [`SimError`] if a strategy asks for something the world refuses.
    pub fn step(
        &mut self,
        world: &mut GridWorld,
        observer: &mut dyn Observer<Cell, GridObservation>,
    ) -> Result<Flow, SimError<Cell>> {
        let cost = self.plan.cost;
        let marks = self.plan.map.then_some(&mut self.marks);
        self.team.step(world, &cost, &mut self.robots, &mut Mapper { marks, next: observer })
    }

    /// Runs to the end.
    ///
    /// # Errors
    /// [`SimError`] if a strategy asks for something the world refuses, or the mission takes
    /// more than `limit` steps.
    pub fn run(
        &mut self,
        world: &mut GridWorld,
        observer: &mut dyn Observer<Cell, GridObservation>,
        limit: u64,
    ) -> Result<Flow, SimError<Cell>> {
        let cost = self.plan.cost;
        let marks = self.plan.map.then_some(&mut self.marks);
        self.team.run(world, &cost, &mut self.robots, &mut Mapper { marks, next: observer }, limit)
    }

    /// Copies the world's records into the mission, so that it can be written out.
    pub fn snapshot(&mut self, world: &GridWorld) {
        self.boards = world.records();
        self.visited = world.visited();
    }

    /// The world as this mission left it: `world` (rebuilt from the same region, drift,
    /// sensor and seed) with the mission's records and visited cells restored.
    pub fn restore(&self, world: GridWorld) -> GridWorld {
        world.with_records(&self.boards).with_visited(self.visited.iter().copied())
    }

    /// A generous cap on the steps of this mission in `world`, against a strategy that never
    /// ends: 64 steps per cell and robot, plus the search box four times over.
    pub fn step_limit(&self, world: &GridWorld) -> u64 {
        let cells = world.roi().len() as u64 + 64;
        let search = self.plan.search.map_or(0, |s| {
            let side = |k: usize| (i64::from(s.max[k]) - i64::from(s.min[k]) + 1).unsigned_abs();
            side(0).saturating_mul(side(1))
        });
        (64 * cells)
            .saturating_mul(self.plan.robots as u64 + 1)
            .saturating_add(search.saturating_mul(4))
    }

    /// Battery swaps per robot.
    pub fn swaps(&self) -> Vec<u32> {
        self.robots.iter().map(|r| r.swaps).collect()
    }

    /// Why robots gave up, if any did (a battery too small, or a search that found nothing).
    pub fn failures(&self) -> Vec<String> {
        let mut v: Vec<String> =
            self.robots.iter().filter_map(|r| r.failure.as_deref().map(String::from)).collect();
        if self.robots.iter().any(|r| r.inner().not_found) {
            v.push("the search box was swept without seeing the region".into());
        }
        v
    }
}

/// Runs a plain mission (no search, no battery) to the end: the paper's simulation.
///
/// # Errors
/// [`MissionError`] as in [`Mission::new`]; a [`SimError`] as a string otherwise.
pub fn explore(
    world: &mut GridWorld,
    robots: usize,
    cost: CostModel,
    recording: Recording,
) -> Result<Mission, GridRunError> {
    let plan = MissionPlan { robots, cost, battery_s: None, search: None, map: false };
    let mut m = Mission::new(world, plan, recording)?;
    let limit = m.step_limit(world);
    m.run(world, &mut NoObserver, limit)?;
    Ok(m)
}

/// Why a grid run failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum GridRunError {
    /// The mission could not start.
    #[error(transparent)]
    Mission(#[from] MissionError),
    /// The loop failed.
    #[error(transparent)]
    Sim(#[from] SimError<Cell>),
}

/// When robot `track` reached each place of its path, replayed from the time model and its
/// scans (the simulator's clock is not stored per place).
pub fn arrival_times(
    track: &super::Track<Cell, GridObservation>,
    times: &crate::protocol::grid::TimeModel,
    cost: &CostModel,
) -> Vec<f64> {
    let mut t = 0.0;
    let mut j = 0;
    let mut out = Vec::with_capacity(track.path.len());
    for (k, c) in track.path.iter().enumerate() {
        if k > 0 {
            t += cost.move_time + times.seconds(track.path[k - 1], *c).unwrap_or(f64::NAN);
        }
        out.push(t);
        // Scans taken here before the next move.
        // The same instant up to rounding (relative, and absolute in seconds near t = 0).
        while j < track.scan_times.len()
            && track.scan_times[j] <= t * (1.0 + SAME_VALUE_REL) + SAME_VALUE_REL
        {
            t += cost.scan_time;
            j += 1;
        }
    }
    out
}
