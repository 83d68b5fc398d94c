//! The paper's exploration algorithm (its Steps 1–8): a depth-first search over the
//! constructed edges (windows) of the visibility regions seen so far.
//!
//! After each scan the robot looks, from the deepest view down the search path, for a window
//! that is still unexplored: one whose far side is not yet covered by any region seen. The next
//! viewpoint is on that window (the paper's `z` on the constructed edge, inside the partially
//! visible triangle `uvw`), in the middle of its first uncovered part, moved a hair toward the
//! view's viewpoint so that it lies inside the view's region and the forward move is a
//! straight segment in seen free space. When a view has no unexplored window the search backs
//! up to its parent, retracing the forward move (a backward move). The search ends when the
//! start view has none. The paper proves at most r + 1 scans.
//!
//! "Unexplored" is decided exactly, not by samples: the parts of a window whose far side lies
//! in another region are cut out at the points where that region's boundary meets the window
//! ([`crate::algorithm::cover`]). A scan taken for an uncovered part marks that part handled
//! even if it could not see it, so every scan makes progress (the paper's Corollary 1) and
//! the search ends.

use serde::{Deserialize, Serialize};

use super::known::{self, Known, Placement};
use super::{PolygonFeedback, PolygonStrategy};
use crate::kernel::Point;
use crate::protocol::Action;
use crate::protocol::polygon::RobotSetup;

/// The depth-first exploration of the paper. Its whole state is serialisable.
///
/// # Example
/// An L-shaped room explored from its bottom arm: the first scan leaves one window, at the
/// reflex corner; the second, taken on that window, sees the rest. The paper's bound, r + 1
/// scans for r reflex vertices, is met.
/// ```
/// use stopscan::algorithm::region::Region;
/// use stopscan::geometry::Domain;
/// use stopscan::protocol::CostModel;
/// use stopscan::sim::NoObserver;
/// use stopscan::sim::polygon::run;
/// use stopscan::strategy::polygon::DepthFirst;
/// use stopscan::world::polygon::PolygonWorld;
///
/// let l = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]];
/// let world = PolygonWorld::new(Domain::new(l, vec![])?)?;
/// let cost = CostModel::default(); // 1 s per scan, 1 m/s
/// let r = run(&world, [3.0, 1.0], &cost, &mut DepthFirst::new(), &mut NoObserver)?;
/// assert_eq!(r.tally.scans, 2);
/// assert_eq!(r.tally.moves, 1);
/// // The second viewpoint lies on the window (2, 2)–(0, 4), a hair inside the first view.
/// let [x, y] = r.path[1];
/// assert!((x - 1.0).abs() < 1e-5 && (y - 3.0).abs() < 1e-5);
/// assert!((r.time.total() - (2.0 + 8f64.sqrt())).abs() < 1e-5);
/// // Together the two scans cover the whole room (12 m²).
/// let seen: Vec<_> = r.scans.iter().map(|s| s.region.polygon.clone()).collect();
/// assert!((Region::union_all(&seen).area() - 12.0).abs() < 1e-9);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct DepthFirst {
    known: Known,
    stack: Vec<usize>,
}

impl DepthFirst {
    /// A fresh strategy.
    pub fn new() -> Self {
        Self::default()
    }

    /// A fresh strategy for a robot with a footprint and a sensor rule
    /// ([`RobotSetup`]): the paper's algorithm, with every viewpoint moved off its window far
    /// enough for the footprint and short windows closed by the rule.
    pub fn for_robot(setup: &RobotSetup) -> Self {
        Self { known: Known::for_robot(setup), ..Self::default() }
    }

    /// A fresh strategy that places each viewpoint by `placement` on its window.
    pub fn with_placement(placement: Placement) -> Self {
        let mut s = Self::default();
        s.known.placement = placement;
        s
    }

    /// Steps 2–6 after the scan that became view `v`: push it on the search path, then find
    /// the next viewpoint from the deepest view with an unexplored window, retracing the
    /// search path back to it.
    fn plan(&mut self, v: usize) -> Action<Point> {
        self.stack.push(v);
        let mut route = Vec::new();
        // The view whose viewpoint the route planned so far ends at.
        let mut here = v;
        loop {
            let Some(&top) = self.stack.last() else {
                // With a footprint, a window part closed as out of reach is opened again when
                // a later view holds its near side (`Known`'s deferred parts), possibly after
                // the search has backed up past its view: the search then starts again from
                // the first view with an open part. (A point robot never defers a part.)
                let n = self.known.views.len();
                let Some(u) = (0..n).find(|&u| self.known.next_target(u).is_some()) else {
                    return Action::Done;
                };
                route.extend(self.known.route(here, u).0);
                here = u;
                self.stack.push(u);
                continue;
            };
            if let Some(t) = self.known.next_target(top) {
                if t.base() != top {
                    route.extend(self.known.route(top, t.base()).0);
                }
                return self.known.go_route(v, route, t);
            }
            self.stack.pop();
            if let Some(&next) = self.stack.last() {
                // The search path is the tree of moves: back the way the robot came (to the
                // view below on the stack, which is the parent unless the scan's trip started
                // from another view, see `Target::base`). On raw scans the robot drives the
                // shortest way through what was seen to the next target instead
                // (`Known::go_route`); the search is the same.
                route.extend(self.known.route(top, next).0);
                here = next;
            }
        }
    }
}

impl PolygonStrategy for DepthFirst {
    fn name(&self) -> &'static str {
        "depth_first"
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
