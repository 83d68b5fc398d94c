//! The stop-scan-plan-go loop. The simulator drives a strategy against a world, charges the
//! [`CostModel`](crate::protocol::CostModel) and pushes events to observers, which listen.
//!
//! - `team`: [`Team`], the one loop, with the [`Arena`] and [`Agent`] traits;
//! - [`polygon`]: one polygon robot in it ([`polygon::run`]);
//! - [`lidar`]: one polygon robot on raw laser scans, with drifting odometry ([`lidar::run`]);
//! - [`grid`]: grid missions that resume ([`grid::Mission`]), on `GridWorld` as an [`Arena`];
//! - [`corner`]: the corner Monte Carlo, with its own loop over hidden angles;
//! - here: the [`Observer`] trait, [`Fanout`] and [`JsonLinesTrace`].

pub mod corner;
pub mod grid;
pub mod lidar;
pub mod polygon;
mod team;

pub use team::{
    Agent, Arena, Flow, Leg, Meeting, MeetingFeedback, Recording, SimError, Spot, Team, Track,
    confer,
};

use std::ops::ControlFlow;

/// Listens to a run. Every hook has a no-op default; returning `Break` stops the run.
///
/// `P` is the family's place type, `O` its observation type; `robot` is the robot's index in
/// the team (always 0 for one robot).
pub trait Observer<P, O> {
    /// Robot `robot` drove to `to`, covering `metres`.
    fn on_move(&mut self, _robot: usize, _to: &P, _metres: f64) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// Robot `robot` scanned at `at` and observed `observation`.
    fn on_scan(&mut self, _robot: usize, _at: &P, _observation: &O) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
    /// The run ended.
    fn on_finish(&mut self, _tally: &crate::protocol::Tally) {}
}

/// An observer that ignores everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoObserver;

impl<P, O> Observer<P, O> for NoObserver {}

/// Several observers as one: every event goes to each in order; the run stops when any of
/// them asks to.
pub struct Fanout<'a, P, O>(pub Vec<&'a mut dyn Observer<P, O>>);

impl<P, O> Observer<P, O> for Fanout<'_, P, O> {
    fn on_move(&mut self, robot: usize, to: &P, metres: f64) -> ControlFlow<()> {
        let mut flow = ControlFlow::Continue(());
        for o in &mut self.0 {
            if o.on_move(robot, to, metres).is_break() {
                flow = ControlFlow::Break(());
            }
        }
        flow
    }
    fn on_scan(&mut self, robot: usize, at: &P, observation: &O) -> ControlFlow<()> {
        let mut flow = ControlFlow::Continue(());
        for o in &mut self.0 {
            if o.on_scan(robot, at, observation).is_break() {
                flow = ControlFlow::Break(());
            }
        }
        flow
    }
    fn on_finish(&mut self, tally: &crate::protocol::Tally) {
        for o in &mut self.0 {
            o.on_finish(tally);
        }
    }
}

/// The trace recorder: one JSON object per line and per event, written (and flushed) as it
/// happens, so a trace survives a crash up to its last event: `{"event":"move","robot":0,
/// "to":[x,y],"metres":m}`, `{"event":"scan","robot":0,"at":[x,y],"observation":{..}}`,
/// `{"event":"finish","tally":{..}}`. A write error stops the run and is kept in [`JsonLinesTrace::error`].
pub struct JsonLinesTrace<W: std::io::Write> {
    out: W,
    /// The first write error, if any.
    pub error: Option<std::io::Error>,
}

impl<W: std::io::Write> JsonLinesTrace<W> {
    /// A recorder writing to `out`.
    pub fn new(out: W) -> Self {
        Self { out, error: None }
    }

    fn line(&mut self, v: &serde_json::Value) -> ControlFlow<()> {
        let r = serde_json::to_writer(&mut self.out, v)
            .map_err(std::io::Error::from)
            .and_then(|()| self.out.write_all(b"\n"))
            .and_then(|()| self.out.flush());
        match r {
            Ok(()) => ControlFlow::Continue(()),
            Err(e) => {
                self.error.get_or_insert(e);
                ControlFlow::Break(())
            }
        }
    }
}

impl<P: serde::Serialize, O: serde::Serialize, W: std::io::Write> Observer<P, O>
    for JsonLinesTrace<W>
{
    fn on_move(&mut self, robot: usize, to: &P, metres: f64) -> ControlFlow<()> {
        self.line(&serde_json::json!({"event": "move", "robot": robot, "to": to, "metres": metres}))
    }
    fn on_scan(&mut self, robot: usize, at: &P, observation: &O) -> ControlFlow<()> {
        let v = serde_json::json!({"event": "scan", "robot": robot, "at": at, "observation": observation});
        self.line(&v)
    }
    fn on_finish(&mut self, tally: &crate::protocol::Tally) {
        let _ = self.line(&serde_json::json!({"event": "finish", "tally": tally}));
    }
}
