//! Nearest-frontier exploration (Yamauchi's frontier-based exploration, with the windows of
//! the regions seen as frontiers): after each scan, go to the closest point from which an
//! unexplored window can be looked through, travelling along the tree of moves, and scan.
//! (On raw scans with a footprint the trip to it is driven along the shortest way through
//! what was seen instead, [`Known::go_route`]; the choice, nearest along the tree, is the
//! same.)
//!
//! It shares the window bookkeeping of the paper's algorithm; only the choice of the next
//! window differs (the nearest by travel distance instead of depth first), so the two can be
//! compared on scans and on distance under one cost model.

use serde::{Deserialize, Serialize};

use super::known::{self, Known, Target};
use super::{PolygonFeedback, PolygonStrategy};
use crate::kernel::Point;
use crate::protocol::Action;
use crate::protocol::polygon::RobotSetup;

/// Nearest-frontier exploration. Its whole state is serialisable.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct NearestFrontier {
    known: Known,
}

impl NearestFrontier {
    /// A fresh strategy.
    pub fn new() -> Self {
        Self::default()
    }

    /// A fresh strategy for a robot with a footprint and a sensor rule ([`RobotSetup`]).
    pub fn for_robot(setup: &RobotSetup) -> Self {
        Self { known: Known::for_robot(setup) }
    }

    /// After the scan that became view `cur`: the unexplored window nearest by travel.
    fn plan(&mut self, cur: usize) -> Action<Point> {
        let mut best: Option<(f64, Target)> = None;
        for v in 0..self.known.views.len() {
            if let Some(t) = self.known.next_target(v) {
                let (_, len) = self.known.route(cur, t.base());
                let total = len + self.known.approach_length(&t);
                if best.as_ref().is_none_or(|b| total < b.0) {
                    best = Some((total, t));
                }
            }
        }
        let Some((_, t)) = best else { return Action::Done };
        self.known.go_from(cur, t)
    }
}

impl PolygonStrategy for NearestFrontier {
    fn name(&self) -> &'static str {
        "nearest_frontier"
    }

    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point> {
        known::act(self, feedback, |s| &mut s.known, Self::plan)
    }

    fn ahead(&self) -> Vec<Point> {
        self.known.ahead()
    }

    fn skipped(&self) -> super::Skipped {
        self.known.skipped
    }
}
