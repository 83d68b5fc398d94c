//! The paper's exploration algorithm with range restriction (its second Steps 1–8): reach the
//! boundary of P through the open space, then follow the boundary from wall to wall, scanning
//! where a wall gives way to the unknown.
//!
//! How the paper's steps map onto what the robot knows (its scans, whose boundary pieces are
//! walls, windows, and range chords standing for the circular arcs):
//!
//! - **Steps 2 and 6** (only arcs, or arcs and marked edges, on the boundary of `CP`): go to
//!   an uncovered part of an arc (or window) of the most recent view that has one, and scan.
//! - **Step 3** (the robot is not at a wall, but walls are in sight): go to the furthest point
//!   of the current region on a wall where the wall gives way to unexplored space, and scan.
//! - **Step 4** (boundary following): from the wall the robot stands at, walk the current
//!   region's boundary counter-clockwise along walls to the first point where an unexplored
//!   arc or window starts; go there and scan. The paper's "arbitrarily close to the edge" is
//!   a millionth of the way toward the viewpoint.
//! - **Step 5** (a part `uu′` of a wall on the boundary of `CP`): go to any wall point of an
//!   earlier view where unexplored space starts (newest view first), and follow from there.
//! - **Marks** (Step 3c, 4c): an edge is marked once no unexplored arc or window touches it
//!   in any view; following stops at a marked edge's end, which is where the walk meets an
//!   explored frontier.
//! - **Steps 7–8**: the run ends when no arc or window of any view has unexplored space
//!   beyond it (the exact test of [`crate::algorithm::cover`]), that is, when the boundary of
//!   `CP` is all polygonal edges.
//!
//! Moves go straight within the region of the view a target belongs to, and between views
//! along the tree of moves, so every move is in seen free space (on raw scans with a
//! footprint, along the shortest way through the safe cells of a raster of what was seen,
//! [`Known::go_route`]). Without a range limit the
//! algorithm still works (it follows walls to the windows), but the paper's algorithm for
//! that case is `depth_first`.

use serde::{Deserialize, Serialize};

use super::known::{self, Known, Target};
use super::{PolygonFeedback, PolygonStrategy};
use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::Point;
use crate::protocol::Action;
use crate::protocol::polygon::RobotSetup;

/// The range-limited exploration of the paper. Its whole state is serialisable.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RangeLimited {
    known: Known,
    /// Whether the robot stands at a wall (boundary following, Steps 4–5).
    on_wall: bool,
    /// Whether the pending target is at a wall.
    target_on_wall: bool,
    /// Wall junctions already scanned at: a junction is visited once (a scan there that did
    /// not see past its frontier, say a window grazing a wall, would find the same junction
    /// in its own region).
    visited: Vec<Point>,
}

fn is_wall(b: &BoundaryPiece) -> bool {
    matches!(
        b,
        BoundaryPiece::Edge { .. } | BoundaryPiece::Partial { .. } | BoundaryPiece::Wall { .. }
    )
}

impl RangeLimited {
    /// A fresh strategy.
    pub fn new() -> Self {
        Self::default()
    }

    /// A fresh strategy for a robot with a footprint and a sensor rule ([`RobotSetup`]).
    pub fn for_robot(setup: &RobotSetup) -> Self {
        Self { known: Known::for_robot(setup), ..Self::default() }
    }

    /// Wall points of view `v` where an unexplored frontier starts: `(window, point, wall)`,
    /// with the wall piece's ends (counter-clockwise, the region on their left).
    fn junctions(&mut self, v: usize) -> Vec<(usize, Point, [Point; 2])> {
        let m = self.known.views[v].pieces.len();
        let mut out = Vec::new();
        for i in 0..m {
            let (a, b) = (self.known.views[v].pieces[i], self.known.views[v].pieces[(i + 1) % m]);
            let (piece, point, wall) = match (is_wall(&a), is_wall(&b)) {
                (true, false) => ((i + 1) % m, a.ends().1, a.ends()),
                (false, true) => (i, b.ends().0, b.ends()),
                _ => continue,
            };
            if let Some(k) = self.known.window_of_piece(v, piece)
                && !self.was_visited(v, point)
                && self.known.window_target(v, k).is_some()
            {
                out.push((k, point, [wall.0, wall.1]));
            }
        }
        out
    }

    /// Step 4: from the wall piece nearest the robot, walk counter-clockwise along walls to
    /// the first frontier; its start, if unexplored.
    fn follow(&mut self, v: usize) -> Option<(usize, Point, [Point; 2])> {
        let view = &self.known.views[v];
        let m = view.pieces.len();
        let at = view.at;
        let start = (0..m).filter(|&i| is_wall(&view.pieces[i])).min_by(|&i, &j| {
            let d = |k: usize| {
                let (a, b) = view.pieces[k].ends();
                crate::geometry::segment_distance(at, a, b)
            };
            d(i).total_cmp(&d(j))
        })?;
        let mut i = start;
        for _ in 0..m {
            let next = (i + 1) % m;
            if is_wall(&view.pieces[next]) {
                i = next;
                continue;
            }
            let (a, point) = view.pieces[i].ends();
            let k = self.known.window_of_piece(v, next)?;
            if self.was_visited(v, point) {
                return None;
            }
            return self.known.window_target(v, k).map(|_| (k, point, [a, point]));
        }
        None
    }

    /// Whether junction `p` of view `v` was scanned at already (within a millionth of its
    /// distance from the view's viewpoint, and at least the rounding of the coordinates).
    fn was_visited(&self, v: usize, p: Point) -> bool {
        let at = self.known.views[v].at;
        let tol = (1e-6 * (p[0] - at[0]).hypot(p[1] - at[1]))
            .max(4.0 * crate::kernel::rounding(crate::kernel::magnitude(&[at, p])));
        self.visited.iter().any(|q| (q[0] - p[0]).hypot(q[1] - p[1]) <= tol)
    }

    fn go_junction(
        &mut self,
        cur: usize,
        v: usize,
        (k, p, wall): (usize, Point, [Point; 2]),
    ) -> Option<Action<Point>> {
        // Off the wall, into the region (left of the wall piece): a robot driving along a
        // wall must not round onto its far side.
        let (dx, dy) = (wall[1][0] - wall[0][0], wall[1][1] - wall[0][1]);
        let len = dx.hypot(dy);
        let inward = if len > 0.0 { [-dy / len, dx / len] } else { [0.0, 0.0] };
        let t = self.known.target_near(v, k, p, inward)?;
        self.visited.push(p);
        Some(self.go_to(cur, t, true))
    }

    fn go_to(&mut self, cur: usize, t: Target, on_wall: bool) -> Action<Point> {
        self.target_on_wall = on_wall;
        self.known.go_from(cur, t)
    }

    /// After the scan that became view `cur` (taken where the last target was, so at a wall
    /// when that target was a wall junction).
    fn plan(&mut self, cur: usize) -> Action<Point> {
        self.on_wall = self.target_on_wall;
        // Step 4: boundary following from the wall the robot stands at.
        if self.on_wall
            && let Some(j) = self.follow(cur)
            && let Some(a) = self.go_junction(cur, cur, j)
        {
            return a;
        }
        // Step 3: the furthest wall point of the current region where the unknown starts.
        let at = self.known.views[cur].at;
        let far = self.junctions(cur).into_iter().max_by(|a, b| {
            let d = |p: Point| (p[0] - at[0]).hypot(p[1] - at[1]);
            d(a.1).total_cmp(&d(b.1))
        });
        if let Some(j) = far
            && let Some(a) = self.go_junction(cur, cur, j)
        {
            return a;
        }
        // Step 5: a wall point of an earlier view where the unknown starts, newest first.
        for v in (0..self.known.views.len()).rev() {
            if let Some(&j) = self.junctions(v).first()
                && let Some(a) = self.go_junction(cur, v, j)
            {
                return a;
            }
        }
        // Steps 2 and 6: only arcs (or windows) left: an unexplored one, newest view first.
        for v in (0..self.known.views.len()).rev() {
            if let Some(t) = self.known.next_target(v) {
                return self.go_to(cur, t, false);
            }
        }
        Action::Done
    }
}

impl PolygonStrategy for RangeLimited {
    fn name(&self) -> &'static str {
        "range_limited"
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
