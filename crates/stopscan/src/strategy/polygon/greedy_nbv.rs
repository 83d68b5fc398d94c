//! Greedy next-best-view: after each scan, go to the candidate viewpoint with the most
//! predicted new area per second of cost, under the run's [`CostModel`], and scan.
//!
//! Candidates are the viewpoints of the paper's algorithm, one per unexplored window (the
//! middle of its first uncovered part, see [`super::known`]), so the comparison with
//! `depth_first` and `nearest_frontier` is about the choice only. The cost of a candidate is
//! what the cost model charges for getting there along the tree of moves and scanning:
//! `move_time · moves + distance / speed + scan_time`.
//!
//! Before a scan nobody knows the area behind a window. The prediction used here (stated in
//! the strategy's output as `gain`) is the half-disc on the window's uncovered length `ℓ`,
//! `π ℓ² / 8`: the usual optimistic frontier estimate, which grows with the opening and
//! needs no knowledge of the world. Ties go to the earlier view and window, so runs are
//! deterministic.

use serde::{Deserialize, Serialize};

use super::known::{Known, Target};
use super::{PolygonFeedback, PolygonStrategy};
use crate::kernel::Point;
use crate::protocol::{Action, CostModel};

/// Greedy next-best-view. Its whole state is serialisable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GreedyNbv {
    cost: CostModel,
    known: Known,
    current: Option<usize>,
    target_parent: Option<usize>,
}

impl GreedyNbv {
    /// A fresh strategy that prices candidates with `cost`.
    pub fn new(cost: CostModel) -> Self {
        Self { cost, known: Known::default(), current: None, target_parent: None }
    }

    fn plan(&mut self) -> Action<Point> {
        let Some(cur) = self.current else { return Action::Done };
        let mut best: Option<(f64, usize, Target)> = None;
        for v in 0..self.known.views.len() {
            if self.known.views[v].explored {
                continue;
            }
            let mut any = false;
            for k in 0..self.known.views[v].windows_len() {
                let Some((t, open)) = self.known.window_target(v, k) else { continue };
                any = true;
                let (pts, len) = self.known.route(cur, v);
                let at = self.known.views[v].at;
                let dist = len + (t.at[0] - at[0]).hypot(t.at[1] - at[1]);
                let moves = pts.len() + 1;
                let secs = self.cost.move_time * moves as f64
                    + dist / self.cost.speed
                    + self.cost.scan_time;
                let gain = std::f64::consts::PI * open * open / 8.0;
                let rate = gain / secs.max(f64::MIN_POSITIVE);
                if best.as_ref().is_none_or(|b| rate > b.0) {
                    best = Some((rate, v, t));
                }
            }
            self.known.views[v].explored = !any;
        }
        let Some((_, v, t)) = best else { return Action::Done };
        let (pts, _) = self.known.route(cur, v);
        self.target_parent = Some(v);
        self.known.go(pts, t)
    }
}

impl PolygonStrategy for GreedyNbv {
    fn name(&self) -> &'static str {
        "greedy_nbv"
    }

    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point> {
        match feedback {
            PolygonFeedback::Start(_) => Action::Scan,
            PolygonFeedback::Arrived => self.known.next_move(),
            PolygonFeedback::Scanned(obs) => {
                let v = self.known.add(obs, self.target_parent);
                self.current = Some(v);
                self.plan()
            }
        }
    }
}
