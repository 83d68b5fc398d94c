//! Greedy next-best-view: after each scan, go to the candidate viewpoint with the most
//! predicted new area per second of cost, under the run's [`CostModel`], and scan.
//!
//! Candidates are the viewpoints of the paper's algorithm, one per unexplored window (the
//! middle of its first uncovered part, see [`super::known`]), so the comparison with
//! `depth_first` and `nearest_frontier` is about the choice only. The cost of a candidate is
//! what the cost model charges for getting there along the tree of moves and scanning:
//! `move_time · moves + distance / speed + scan_time`. (On raw scans with a footprint the
//! trip is driven along the shortest way through what was seen instead,
//! [`Known::go_route`]; it is priced as before, so the choice is the same.)
//!
//! Before a scan nobody knows the area behind a window. The prediction used here (stated in
//! the strategy's output as `gain`) is the half-disc on the window's uncovered length `ℓ`,
//! `π ℓ² / 8`: the usual optimistic frontier estimate, which grows with the opening and
//! needs no knowledge of the world. Ties go to the earlier view and window, so runs are
//! deterministic.

use serde::{Deserialize, Serialize};

use super::known::{self, Known, Target};
use super::{PolygonFeedback, PolygonStrategy};
use crate::kernel::Point;
use crate::protocol::polygon::RobotSetup;
use crate::protocol::{Action, CostModel};

/// Greedy next-best-view. Its whole state is serialisable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GreedyNbv {
    cost: CostModel,
    known: Known,
}

impl GreedyNbv {
    /// A fresh strategy that prices candidates with `cost`.
    pub fn new(cost: CostModel) -> Self {
        Self { cost, known: Known::default() }
    }

    /// A fresh strategy for a robot with a footprint and a sensor rule ([`RobotSetup`]),
    /// pricing with its cost model.
    pub fn for_robot(setup: &RobotSetup) -> Self {
        Self { cost: setup.cost, known: Known::for_robot(setup) }
    }

    /// After the scan that became view `cur`: the candidate with the most predicted area per
    /// second.
    fn plan(&mut self, cur: usize) -> Action<Point> {
        let mut best: Option<(f64, Target)> = None;
        for v in 0..self.known.views.len() {
            if self.known.views[v].explored {
                continue;
            }
            let route = self.known.route(cur, v);
            let mut any = false;
            for k in 0..self.known.views[v].windows_len() {
                let Some((t, open)) = self.known.window_target(v, k) else { continue };
                any = true;
                let (steps, len) = self.known.trip_to(cur, &t, &route);
                let dist = len + self.known.approach_length(&t);
                let moves = steps + t.via.len() + 1;
                let secs = self.cost.move_time * moves as f64
                    + dist / self.cost.speed
                    + self.cost.scan_time;
                let gain = std::f64::consts::PI * open * open / 8.0;
                let rate = gain / secs.max(f64::MIN_POSITIVE);
                if best.as_ref().is_none_or(|b| rate > b.0) {
                    best = Some((rate, t));
                }
            }
            self.known.views[v].explored = !any;
        }
        let Some((_, t)) = best else { return Action::Done };
        self.known.go_from(cur, t)
    }
}

impl PolygonStrategy for GreedyNbv {
    fn name(&self) -> &'static str {
        "greedy_nbv"
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
