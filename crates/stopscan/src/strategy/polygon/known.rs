//! What a polygon strategy knows: the views it took, their windows, and the tree of moves
//! between them (each viewpoint was chosen inside the region of its parent view, so the
//! straight segment between them is known free space).

use serde::{Deserialize, Serialize};

use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::{Point, RingSide, ring_side};
use crate::protocol::Action;
use crate::protocol::polygon::PolygonObservation;

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct View {
    pub(super) at: Point,
    polygon: Vec<Point>,
    bounds: [Point; 2],
    windows: Vec<Window>,
    pub(super) parent: Option<usize>,
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

/// A next viewpoint and the window sample it is for.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub(super) struct Target {
    pub(super) at: Point,
    view: usize,
    window: usize,
    sample: usize,
}

/// The views taken so far.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct Known {
    pub(super) views: Vec<View>,
    /// The window sample the next scan is for.
    pending: Option<Target>,
    /// Waypoints still to drive, last first.
    route: Vec<Point>,
}

impl Known {
    /// Points along a window where "explored" is tested.
    const SAMPLES: usize = 16;

    /// Records a scan taken from inside the region of view `parent`; the target it was taken
    /// for counts as handled.
    pub(super) fn add(&mut self, obs: &PolygonObservation, parent: Option<usize>) -> usize {
        if let Some(t) = self.pending.take() {
            self.handled(t);
        }
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
        self.views.push(View { at: obs.at, polygon: poly.clone(), bounds, windows, parent });
        self.views.len() - 1
    }

    /// The point at fraction `t` of the window, pushed `side` millionths of the window's
    /// length to its left (positive: the seen side) or right (negative: the unseen side).
    fn along(from: Point, to: Point, t: f64, side: f64) -> Point {
        let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
        let e = 1e-6 * side;
        [from[0] + t * dx - e * dy, from[1] + t * dy + e * dx]
    }

    /// Whether any of `views[from..]` covers `p` (newest first, bounding boxes first).
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
    pub(super) fn next_target(&mut self, view: usize) -> Option<Target> {
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
                    return Some(Target {
                        at: Self::along(f, t, u, 1.0),
                        view,
                        window: k,
                        sample: w.sample,
                    });
                }
            }
        }
        None
    }

    /// Marks a target's window sample as handled once a scan was taken for it, covered or
    /// not: a point that scan cannot see (a hair inside an obstacle the window grazes) must
    /// not be tried again, so every scan makes progress and the exploration ends.
    fn handled(&mut self, t: Target) {
        let w = &mut self.views[t.view].windows[t.window];
        if w.sample <= t.sample {
            w.sample = t.sample + 1;
            w.checked = 0;
        }
    }

    /// Plans a trip: drive through `waypoints` (in order) to the target, then scan.
    pub(super) fn go(&mut self, mut waypoints: Vec<Point>, target: Target) -> Action<Point> {
        waypoints.push(target.at);
        waypoints.reverse();
        self.route = waypoints;
        self.pending = Some(target);
        self.next_move()
    }

    /// The next action of the planned trip: the next waypoint, or the scan at its end.
    pub(super) fn next_move(&mut self) -> Action<Point> {
        match self.route.pop() {
            Some(p) => Action::MoveTo { to: p },
            None => Action::Scan,
        }
    }

    /// The chain of views from `v` up to the root.
    fn ancestors(&self, mut v: usize) -> Vec<usize> {
        let mut out = vec![v];
        while let Some(p) = self.views[v].parent {
            out.push(p);
            v = p;
        }
        out
    }

    /// Waypoints from view `a`'s point to view `b`'s point along the tree of moves (every
    /// segment known free), with the length of that route.
    pub(super) fn route(&self, a: usize, b: usize) -> (Vec<Point>, f64) {
        let (up, down) = (self.ancestors(a), self.ancestors(b));
        let common = *up.iter().find(|x| down.contains(x)).unwrap_or(&a);
        let mut pts: Vec<Point> =
            up.iter().take_while(|&&x| x != common).skip(1).map(|&x| self.views[x].at).collect();
        if common != a {
            pts.push(self.views[common].at);
        }
        let tail: Vec<Point> =
            down.iter().take_while(|&&x| x != common).map(|&x| self.views[x].at).collect();
        pts.extend(tail.into_iter().rev());
        let mut len = 0.0;
        let mut prev = self.views[a].at;
        for p in &pts {
            len += (p[0] - prev[0]).hypot(p[1] - prev[1]);
            prev = *p;
        }
        (pts, len)
    }
}
