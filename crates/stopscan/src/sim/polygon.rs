//! Driving a polygon strategy against a polygon world.

use serde::{Deserialize, Serialize};

use super::Observer;
use crate::kernel::Point;
use crate::protocol::polygon::PolygonObservation;
use crate::protocol::{Action, CostModel, Tally, TimeBreakdown};
use crate::strategy::polygon::{PolygonFeedback, PolygonStrategy};
use crate::world::polygon::PolygonWorld;

/// Why a polygon run was cut short.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PolygonSimError {
    /// The strategy asked for a straight move that leaves the free space; the simulator
    /// refuses it.
    #[error(
        "strategy {strategy} asked to move from {from:?} to {to:?}, which leaves the free space"
    )]
    Blocked {
        /// The strategy.
        strategy: String,
        /// Where the robot was.
        from: Point,
        /// Where it wanted to go.
        to: Point,
    },
    /// The strategy did not finish within the action limit.
    #[error("strategy {0} did not finish within {1} actions")]
    TooLong(String, usize),
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
    /// Whether an observer stopped the run before the strategy was done.
    pub interrupted: bool,
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
    const LIMIT: usize = 1_000_000;
    let mut tally = Tally::default();
    let mut at = start;
    let mut path = vec![start];
    let mut scans = Vec::new();
    let mut scan_times = Vec::new();
    let mut elapsed = 0.0;
    let mut feedback = PolygonFeedback::Start(start);
    for _ in 0..LIMIT {
        match strategy.act(&feedback) {
            Action::MoveTo { to } => {
                if !world.can_move(at, to) {
                    return Err(PolygonSimError::Blocked {
                        strategy: strategy.name().into(),
                        from: at,
                        to,
                    });
                }
                let metres = (to[0] - at[0]).hypot(to[1] - at[1]);
                tally.moves += 1;
                tally.distance += metres;
                elapsed += cost.move_time + metres / cost.speed;
                at = to;
                path.push(to);
                feedback = PolygonFeedback::Arrived;
                if observer.on_move(&to, metres).is_break() {
                    return Ok(finish(observer, cost, tally, path, (scans, scan_times), true));
                }
            }
            Action::Scan => {
                let obs = world.scan(at).map_err(|_| PolygonSimError::Blocked {
                    strategy: strategy.name().into(),
                    from: at,
                    to: at,
                })?;
                tally.scans += 1;
                scan_times.push(elapsed);
                elapsed += cost.scan_time;
                let stop = observer.on_scan(&at, &obs).is_break();
                scans.push(obs.clone());
                feedback = PolygonFeedback::Scanned(obs);
                if stop {
                    return Ok(finish(observer, cost, tally, path, (scans, scan_times), true));
                }
            }
            Action::Done => {
                return Ok(finish(observer, cost, tally, path, (scans, scan_times), false));
            }
        }
    }
    Err(PolygonSimError::TooLong(strategy.name().into(), LIMIT))
}

fn finish(
    observer: &mut dyn Observer<Point, PolygonObservation>,
    cost: &CostModel,
    tally: Tally,
    path: Vec<Point>,
    (scans, scan_times): (Vec<PolygonObservation>, Vec<f64>),
    interrupted: bool,
) -> PolygonRun {
    observer.on_finish(&tally);
    PolygonRun { tally, time: cost.price(&tally), path, scans, scan_times, interrupted }
}
