//! Driving a polygon strategy against a polygon world: one robot in the team loop.

use serde::{Deserialize, Serialize};

use super::{Agent, Arena, Flow, Leg, Meeting, Observer, SimError, Team};
use crate::kernel::Point;
use crate::protocol::polygon::PolygonObservation;
use crate::protocol::{Action, CostModel, Tally, TimeBreakdown};
use crate::strategy::polygon::{PolygonFeedback, PolygonStrategy};
use crate::world::polygon::PolygonWorld;

/// Why a polygon run was cut short.
pub type PolygonSimError = SimError<Point>;

/// A run that was cut short: why, and what was done until then (so that a caller can still
/// write the record so far).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{error}")]
pub struct PolygonRunError {
    /// Why.
    pub error: PolygonSimError,
    /// The run until then.
    pub partial: Box<PolygonRun>,
}

/// The record of one exploration run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PolygonRun {
    /// What was done.
    pub tally: Tally,
    /// Its price, term by term.
    pub time: TimeBreakdown,
    /// The polyline driven (starts at the start point).
    pub path: Vec<Point>,
    /// Every scan: where, and the region seen.
    pub scans: Vec<PolygonObservation>,
    /// When each scan began (seconds since the start, under the cost model).
    pub scan_times: Vec<f64>,
    /// The tally as each scan was taken, that scan counted.
    #[serde(default)]
    pub scan_tallies: Vec<Tally>,
    /// Whether an observer stopped the run before the strategy was done.
    pub interrupted: bool,
}

/// Passes events on to `inner` with every point moved from the local `frame` into the input's
/// coordinates: a trace or a display then speaks the input's coordinates.
pub struct Reframe<'a> {
    /// The observer that receives the moved events.
    pub inner: &'a mut dyn Observer<Point, PolygonObservation>,
    /// The frame the run's points are in.
    pub frame: crate::geometry::Frame,
}

impl Observer<Point, PolygonObservation> for Reframe<'_> {
    fn on_move(&mut self, robot: usize, to: &Point, metres: f64) -> std::ops::ControlFlow<()> {
        self.inner.on_move(robot, &self.frame.to_input(*to), metres)
    }
    fn on_scan(
        &mut self,
        robot: usize,
        at: &Point,
        observation: &PolygonObservation,
    ) -> std::ops::ControlFlow<()> {
        let f = |p| self.frame.to_input(p);
        self.inner.on_scan(robot, &f(*at), &observation.mapped(f))
    }
    fn on_finish(&mut self, tally: &Tally) {
        self.inner.on_finish(tally);
    }
}

/// A polygon world as the loop sees it: straight moves checked exactly, no communication.
struct PolygonArena<'a>(&'a PolygonWorld);

impl Meeting for PolygonArena<'_> {
    type Place = Point;
    type Observation = PolygonObservation;
    type Context = ();
    type Note = ();

    fn meet(&mut self, _at: &Point, _clock: f64, _group: &[usize]) {}
    fn leave(&mut self, _at: &Point, (): ()) {}
}

impl Arena for PolygonArena<'_> {
    fn travel(&self, from: &Point, to: &Point, _clock: f64, cost: &CostModel) -> Option<Leg> {
        self.0.can_move(*from, *to).then(|| {
            let metres = (to[0] - from[0]).hypot(to[1] - from[1]);
            Leg { metres, seconds: metres / cost.speed }
        })
    }
    fn scan(&mut self, _robot: usize, at: &Point, _clock: f64) -> Option<PolygonObservation> {
        self.0.scan(*at).ok()
    }
    fn is_static(&self) -> bool {
        true
    }
}

struct Driven<'a>(&'a mut dyn PolygonStrategy);

impl Agent<PolygonArena<'_>> for Driven<'_> {
    fn name(&self) -> &str {
        self.0.name()
    }
    fn act(&mut self, feedback: &PolygonFeedback, (): &()) -> Action<Point> {
        self.0.act(feedback)
    }
}

/// Runs `strategy` in `world` from `start` until it is done.
///
/// # Errors
/// [`PolygonRunError`], with the run so far, if the strategy asks for a move out of the free
/// space, asks to scan again where a scan already stood (it has stopped making progress: the
/// world is static, so it would see nothing new), or does not finish within a million steps.
pub fn run(
    world: &PolygonWorld,
    start: Point,
    cost: &CostModel,
    strategy: &mut dyn PolygonStrategy,
    observer: &mut dyn Observer<Point, PolygonObservation>,
) -> Result<PolygonRun, PolygonRunError> {
    const LIMIT: u64 = 1_000_000;
    let mut team = Team::new(vec![start], super::Recording::ALL);
    let mut agents = [Driven(strategy)];
    let flow = team.run(&mut PolygonArena(world), cost, &mut agents, observer, LIMIT);
    let r = team.robots.swap_remove(0);
    let run = PolygonRun {
        tally: r.tally,
        time: cost.price(&r.tally),
        path: r.path,
        scans: r.observations,
        scan_times: r.scan_times,
        scan_tallies: r.scan_tallies,
        interrupted: flow == Ok(Flow::Interrupted),
    };
    match flow {
        Ok(_) => Ok(run),
        Err(error) => Err(PolygonRunError { error, partial: Box::new(run) }),
    }
}
