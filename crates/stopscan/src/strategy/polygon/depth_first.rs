//! The paper's exploration algorithm (its Steps 1–8): a depth-first search over the
//! constructed edges (windows) of the visibility regions seen so far.
//!
//! After each scan the robot looks, from the deepest view down the search path, for a window
//! that is still unexplored: one whose far side is not yet covered by any region seen. The next
//! viewpoint is on that window, moved a millionth of the window's length into the seen side (the
//! paper's `z` on the constructed edge, inside the partially visible triangle `uvw`): it lies
//! inside the view's region, so the forward move is a straight segment in seen free space. When a view has no unexplored window
//! the search backs up to its parent, retracing the forward move (a backward move). The search
//! ends when the start view has none. The paper proves at most r + 1 scans.
//!
//! "Unexplored" is decided at 16 points along the window, each a millionth of the window's
//! length past it on the side away from the owning view: a window is explored when all are
//! covered by regions seen. The next viewpoint is placed at the first uncovered one (on the
//! seen side), and a scan there covers it, so every scan makes progress (the paper's
//! Corollary 1) and the search ends.

use serde::{Deserialize, Serialize};

use super::{PolygonFeedback, PolygonStrategy};
use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::{Point, RingSide, ring_side};
use crate::protocol::Action;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct View {
    at: Point,
    polygon: Vec<Point>,
    /// Bounding box `[min, max]` of the polygon.
    bounds: [Point; 2],
    /// Windows in the region's counter-clockwise order.
    windows: Vec<Window>,
}

/// A window and how far its exploration test has got. Samples only ever turn from unexplored
/// to explored, so the test resumes where it stopped: at sample `sample`, against the views
/// from index `checked` on.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct Window {
    from: Point,
    to: Point,
    sample: usize,
    checked: usize,
}

/// The depth-first exploration of the paper. Its whole state is serialisable.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct DepthFirst {
    views: Vec<View>,
    stack: Vec<usize>,
    route: Vec<Point>,
    started: bool,
}

impl DepthFirst {
    /// A fresh strategy.
    pub fn new() -> Self {
        Self::default()
    }

    /// Points along a window where "explored" is tested.
    const SAMPLES: usize = 16;

    /// The point at fraction `t` of the window, pushed `side` millionths of the window's
    /// length to its left (positive: the seen side) or right (negative: the unseen side).
    fn along(from: Point, to: Point, t: f64, side: f64) -> Point {
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let e = 1e-6 * side;
        [from[0] + t * dx - e * dy, from[1] + t * dy + e * dx]
    }

    /// Whether any of `views[from..]` covers `p`.
    fn covered_by(&self, from: usize, p: Point) -> bool {
        self.views[from..].iter().rev().any(|v| {
            p[0] >= v.bounds[0][0]
                && p[0] <= v.bounds[1][0]
                && p[1] >= v.bounds[0][1]
                && p[1] <= v.bounds[1][1]
                && ring_side(&v.polygon, p) != RingSide::Outside
        })
    }

    /// The next viewpoint for the first unexplored window of `view`: at the first of
    /// [`Self::SAMPLES`] points along it whose unseen side is not yet covered, moved a
    /// millionth of the window's length into the seen side (inside the view's region, so the
    /// straight move there is safe although the window's points are constructed).
    fn first_unexplored(&mut self, view: usize) -> Option<Point> {
        let n = self.views.len();
        for k in 0..self.views[view].windows.len() {
            loop {
                let w = &self.views[view].windows[k];
                if w.sample == Self::SAMPLES {
                    break;
                }
                let (f, t, u, from) =
                    (w.from, w.to, (w.sample as f64 + 0.5) / Self::SAMPLES as f64, w.checked);
                let covered = self.covered_by(from, Self::along(f, t, u, -1.0));
                let w = &mut self.views[view].windows[k];
                if covered {
                    w.sample += 1;
                    w.checked = 0;
                } else {
                    w.checked = n;
                    return Some(Self::along(f, t, u, 1.0));
                }
            }
        }
        None
    }

    /// Steps 3–6: find the next viewpoint from the deepest view with an unexplored window,
    /// retracing the search path back to it.
    fn plan(&mut self) -> Action<Point> {
        let mut route = Vec::new();
        loop {
            let Some(&top) = self.stack.last() else { return Action::Done };
            if let Some(z) = self.first_unexplored(top) {
                route.push(z);
                route.reverse();
                self.route = route;
                return self.next_move();
            }
            self.stack.pop();
            if let Some(&parent) = self.stack.last() {
                route.push(self.views[parent].at);
            }
        }
    }

    fn next_move(&mut self) -> Action<Point> {
        match self.route.pop() {
            Some(p) => Action::MoveTo { to: p },
            None => Action::Scan,
        }
    }
}

impl PolygonStrategy for DepthFirst {
    fn name(&self) -> &'static str {
        "depth_first"
    }

    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point> {
        match feedback {
            PolygonFeedback::Start(_) => {
                self.started = true;
                Action::Scan
            }
            PolygonFeedback::Arrived => self.next_move(),
            PolygonFeedback::Scanned(obs) => {
                let windows = obs
                    .region
                    .boundary
                    .iter()
                    .filter_map(|b| match *b {
                        BoundaryPiece::Window { from, to, .. } => {
                            Some(Window { from, to, sample: 0, checked: 0 })
                        }
                        _ => None,
                    })
                    .collect();
                let poly = &obs.region.polygon;
                let mut bounds = [[f64::MAX; 2], [f64::MIN; 2]];
                for p in poly {
                    bounds = [
                        [bounds[0][0].min(p[0]), bounds[0][1].min(p[1])],
                        [bounds[1][0].max(p[0]), bounds[1][1].max(p[1])],
                    ];
                }
                self.views.push(View { at: obs.at, polygon: poly.clone(), bounds, windows });
                self.stack.push(self.views.len() - 1);
                self.plan()
            }
        }
    }
}
