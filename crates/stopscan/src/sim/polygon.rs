//! Driving a polygon strategy against a polygon world: one robot in the team loop.

use serde::{Deserialize, Serialize};

use super::{Agent, Arena, Flow, Leg, Observer, SimError, Team};
use crate::kernel::Point;
use crate::protocol::polygon::PolygonObservation;
use crate::protocol::{Action, CostModel, Tally, TimeBreakdown};
use crate::strategy::polygon::{PolygonFeedback, PolygonStrategy};
use crate::world::polygon::PolygonWorld;

/// Why a polygon run was cut short.
pub type PolygonSimError = SimError<Point>;

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
    /// Whether an observer stopped the run before the strategy was done.
    pub interrupted: bool,
}

/// A polygon world as the loop sees it: straight moves checked exactly, no communication.
struct PolygonArena<'a>(&'a PolygonWorld);

impl Arena for PolygonArena<'_> {
    type Place = Point;
    type Observation = PolygonObservation;
    type Context = ();
    type Note = ();

    fn travel(&self, from: &Point, to: &Point, _clock: f64, cost: &CostModel) -> Option<Leg> {
        self.0.can_move(*from, *to).then(|| {
            let metres = (to[0] - from[0]).hypot(to[1] - from[1]);
            Leg { metres, seconds: metres / cost.speed }
        })
    }
    fn scan(&mut self, _robot: usize, at: &Point, _clock: f64) -> Option<PolygonObservation> {
        self.0.scan(*at).ok()
    }
    fn meet(&mut self, _at: &Point, _clock: f64, _group: &[usize]) {}
    fn leave(&mut self, _at: &Point, (): ()) {}
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
/// [`PolygonSimError`] if the strategy asks for a move out of the free space or never ends.
pub fn run(
    world: &PolygonWorld,
    start: Point,
    cost: &CostModel,
    strategy: &mut dyn PolygonStrategy,
    observer: &mut dyn Observer<Point, PolygonObservation>,
) -> Result<PolygonRun, PolygonSimError> {
    const LIMIT: u64 = 1_000_000;
    let mut team = Team::new(vec![start], super::Recording::ALL);
    let mut agents = [Driven(strategy)];
    let flow = team.run(&mut PolygonArena(world), cost, &mut agents, observer, LIMIT)?;
    let r = team.robots.swap_remove(0);
    Ok(PolygonRun {
        tally: r.tally,
        time: cost.price(&r.tally),
        path: r.path,
        scans: r.observations,
        scan_times: r.scan_times,
        interrupted: flow == Flow::Interrupted,
    })
}
