//! The stop-scan-plan-go loop. The simulator drives a strategy against a world, charges the
//! [`CostModel`](crate::protocol::CostModel) and pushes events to observers, which listen.

pub mod corner;
pub mod polygon;

use std::ops::ControlFlow;

/// Listens to a run. Every hook has a no-op default; returning `Break` stops the run.
///
/// `P` is the family's place type, `O` its observation type.
pub trait Observer<P, O> {
    /// The robot drove to `to`, covering `metres`.
    fn on_move(&mut self, _to: &P, _metres: f64) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// The robot scanned at `at` and observed `observation`.
    fn on_scan(&mut self, _at: &P, _observation: &O) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// The run ended.
    fn on_finish(&mut self, _tally: &crate::protocol::Tally) {}
}

/// An observer that ignores everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl<P, O> Observer<P, O> for NoObserver {}
