//! Driving a corner strategy against a corner world.

use serde::{Deserialize, Serialize};

use super::Observer;
use crate::protocol::corner::{CornerObservation, Route, Stop};
use crate::protocol::{Action, Tally, TimeBreakdown};
use crate::strategy::corner::{CornerFeedback, CornerStrategy};
use crate::world::corner::CornerWorld;

/// Why a run was cut short.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CornerRunError {
    /// The strategy asked to move backwards along the circle.
    #[error("strategy {0} asked to move backwards along the circle")]
    Backwards(String),
    /// The strategy did not finish within the step limit.
    #[error("strategy {0} did not finish within {1} actions")]
    TooLong(String, usize),
    /// The strategy said it was done before seeing the edge.
    #[error("strategy {0} stopped before the edge was seen")]
    GaveUp(String),
}

/// The outcome of one corner run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CornerRun {
    /// What was done.
    pub tally: Tally,
    /// Its price, term by term.
    pub time: TimeBreakdown,
    /// Stop angles of the scans, in order.
    pub scans: Vec<f64>,
    /// Whether an observer stopped the run early.
    pub interrupted: bool,
}

/// Runs `strategy` in `world` until it is done; observers hear every move and scan.
///
/// # Errors
/// [`CornerRunError`] if the strategy misbehaves (moves backwards, never finishes, gives up).
pub fn run(
    world: &CornerWorld,
    strategy: &mut dyn CornerStrategy,
    observer: &mut dyn Observer<Stop, CornerObservation>,
) -> Result<CornerRun, CornerRunError> {
    const LIMIT: usize = 1_000_000;
    let mut tally = Tally::default();
    let mut at = 0.0;
    let mut scans = Vec::new();
    let mut feedback = CornerFeedback::Start;
    let mut seen = false;
    let mut interrupted = false;
    for _ in 0..LIMIT {
        match strategy.act(feedback) {
            Action::MoveTo { to } => {
                if to.angle < at {
                    return Err(CornerRunError::Backwards(strategy.name().into()));
                }
                let (reached, metres) = world.drive(at, &to);
                tally.moves += 1;
                tally.distance += metres;
                at = reached;
                feedback = CornerFeedback::Arrived;
                if observer.on_move(0, &Stop { angle: at, route: to.route }, metres).is_break() {
                    interrupted = true;
                    break;
                }
            }
            Action::Scan => {
                let obs = world.scan(at);
                tally.scans += 1;
                scans.push(at);
                seen = matches!(obs, CornerObservation::Seen { .. });
                feedback = CornerFeedback::Scanned(obs);
                if observer
                    .on_scan(0, &Stop { angle: at, route: Route::default() }, &obs)
                    .is_break()
                {
                    interrupted = true;
                    break;
                }
            }
            Action::Done => {
                if !seen {
                    return Err(CornerRunError::GaveUp(strategy.name().into()));
                }
                observer.on_finish(&tally);
                return Ok(CornerRun {
                    tally,
                    time: world.setup.cost.price(&tally),
                    scans,
                    interrupted,
                });
            }
        }
    }
    if interrupted {
        observer.on_finish(&tally);
        return Ok(CornerRun { tally, time: world.setup.cost.price(&tally), scans, interrupted });
    }
    Err(CornerRunError::TooLong(strategy.name().into(), LIMIT))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::CostModel;
    use crate::protocol::corner::{CornerSetup, LastStep, Route};
    use crate::sim::NoObserver;
    use crate::strategy::corner::unirec;

    #[test]
    fn run_matches_the_stop_list_cost() {
        let setup = CornerSetup::new(10.0, CostModel::new(2.0, 0.3, 0.5).unwrap()).unwrap();
        for last_step in [LastStep::Capped, LastStep::Nominal] {
            let list = unirec(0.1, Route::Arc, last_step).unwrap();
            let costs = list.costs(&setup);
            for theta in [0.05, 0.1, 0.15, 1.0, 1.55, 1.6, 3.0] {
                let world = CornerWorld { setup, theta, last_step };
                let mut s = list.clone().into_strategy("unirec");
                let r = run(&world, &mut s, &mut NoObserver).unwrap();
                let k = list.seen_at(theta);
                assert!(
                    (r.time.total() - costs[k]).abs() < 1e-9,
                    "θ={theta}: {} vs {}",
                    r.time.total(),
                    costs[k]
                );
                assert_eq!(r.tally.scans as usize, k + 1);
            }
        }
    }
}
