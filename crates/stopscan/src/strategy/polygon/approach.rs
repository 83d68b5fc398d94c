//! Approaches with clearance inside one view's region: when no straight move from the view's
//! viewpoint keeps a robot's clearance on the way to any viewpoint for a window (a door seen
//! at a slant: the straight line grazes its jamb), a short polyline that bends around the
//! region's reflex vertices may.
//!
//! The region is what the scan saw, so a path that keeps clearance `c` from its whole
//! boundary (walls, windows and range arcs alike) keeps the robot's footprint in seen free
//! space. The search is a visibility graph over points stepped off the region's reflex
//! vertices along their interior bisectors (where shortest paths with clearance bend), a
//! bounded number of them (those nearest the straight line the robot cannot drive), searched
//! with Dijkstra's algorithm (`pathfinding`).

use super::known::{keeps_clear, keeps_clear_leaving};
use crate::kernel::{Point, RingSide, ring_side};

/// How many reflex vertices of the region (those nearest the blocked straight line) lend
/// their stepped-off points to the graph: enough to bend around a door's two jambs and a
/// corner before it, few enough that the graph stays small on pixel-jagged maps.
const MAX_CORNERS: usize = 24;

/// How far from its reflex vertex each graph point stands, in multiples of the clearance.
const STEPS: [f64; 2] = [1.25, 2.5];

/// How far from a reflex vertex a graph point also stands, in multiples of the clearance, where
/// the first of [`STEPS`] along its bisector is not clear.
const TIGHT_STEP: f64 = 1.05;

/// The turns from a reflex vertex's bisector tried for its graph point, radians, in order:
/// the bisector, then 15°, 30°, 45°, 60° and 75° to either side. At a reflex vertex the free
/// wedge spans more than 90° to each side of the bisector, so every turn starts into it.
const ASIDE: [f64; 11] = {
    let d = std::f64::consts::PI / 12.0;
    [0.0, d, -d, 2.0 * d, -2.0 * d, 3.0 * d, -3.0 * d, 4.0 * d, -4.0 * d, 5.0 * d, -5.0 * d]
};

/// The region (an outer ring, counter-clockwise, and its holes, clockwise: the region lies
/// left of every ring) and the clearance a path keeps in it.
pub(super) struct Approach<'a> {
    rings: Vec<&'a [Point]>,
    c: f64,
    /// Whether a path's first leg may keep less than `c` when the robot stands nearer than
    /// `c` to the boundary ([`keeps_clear_leaving`]: raw scans, where the drift or a scan's
    /// alignment may put it there).
    leaving: bool,
}

/// A path found: the waypoints strictly between the start and the goal, and the goal's index
/// among the goals given.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Path {
    pub(super) via: Vec<Point>,
    pub(super) goal: usize,
}

/// Whether `p` lies strictly inside the region with outer ring `rings[0]` and holes
/// `rings[1..]`.
pub(super) fn holds<R: AsRef<[Point]>>(rings: &[R], p: Point) -> bool {
    let Some((outer, holes)) = rings.split_first() else { return false };
    ring_side(outer.as_ref(), p) == RingSide::Inside
        && holes.iter().all(|h| ring_side(h.as_ref(), p) == RingSide::Outside)
}

impl<'a> Approach<'a> {
    /// Paths inside `polygon` (a view's region, counter-clockwise) keeping `c > 0` from its
    /// boundary.
    pub(super) fn new(polygon: &'a [Point], c: f64) -> Self {
        Self { rings: vec![polygon], c, leaving: false }
    }

    /// Paths inside the region with outer ring `shape[0]` (counter-clockwise) and holes
    /// `shape[1..]` (clockwise), keeping `c > 0` from every ring: the union of several
    /// views' regions.
    pub(super) fn with_holes(shape: &'a [Vec<Point>], c: f64) -> Self {
        Self { rings: shape.iter().map(Vec::as_slice).collect(), c, leaving: false }
    }

    /// These paths, with a first leg that may keep less than the clearance when the start
    /// does ([`Approach::leaving`]) if `leaving`.
    #[must_use]
    pub(super) fn leaving(self, leaving: bool) -> Self {
        Self { leaving, ..self }
    }

    /// Whether the first leg `a b` of a path from `a` keeps the clearance: as
    /// [`Approach::clear`], or, when the robot at `a` stands nearer than the clearance to the
    /// boundary and the first leg may leave it so ([`Approach::leaving`]), keeping 99% of
    /// what it has there ([`keeps_clear_leaving`]).
    fn clear_leaving(&self, a: Point, b: Point) -> bool {
        if !self.leaving {
            return self.clear(a, b);
        }
        self.rings.iter().all(|r| keeps_clear_leaving(r, a, b, self.c))
    }

    /// Whether the straight move `a b` keeps the clearance from every edge
    /// ([`keeps_clear`]).
    pub(super) fn clear(&self, a: Point, b: Point) -> bool {
        self.rings.iter().all(|r| keeps_clear(r, a, b, self.c))
    }

    /// Whether `p` lies inside the region with the clearance around it.
    pub(super) fn clear_point(&self, p: Point) -> bool {
        holds(&self.rings, p) && self.clear(p, p)
    }

    /// Points stepped off the region's reflex vertices into it (along each vertex's interior
    /// bisector, or turned from it by [`ASIDE`] where the bisector's point is not clear, by
    /// [`STEPS`] times the clearance, and by [`TIGHT_STEP`] too where the bisector's first
    /// point is not clear), from the [`MAX_CORNERS`] vertices nearest the segment `near`, that
    /// keep the clearance themselves. Deterministic: ties keep the region's vertex order.
    pub(super) fn corners(&self, near: [Point; 2]) -> Vec<Point> {
        // Reflex vertices of every ring (the region lies left of each), by ring and index.
        let mut reflex: Vec<(f64, usize, usize)> = Vec::new();
        for (k, poly) in self.rings.iter().enumerate() {
            let n = poly.len();
            if n < 3 {
                continue;
            }
            reflex.extend(
                (0..n)
                    .filter(|&i| {
                        let (p, q, r) = (poly[(i + n - 1) % n], poly[i], poly[(i + 1) % n]);
                        crate::kernel::orient_sign(p, q, r) < 0
                    })
                    .map(|i| (crate::geometry::segment_distance(poly[i], near[0], near[1]), k, i)),
            );
        }
        reflex.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).then(a.2.cmp(&b.2)));
        reflex.truncate(MAX_CORNERS);
        let mut out = Vec::new();
        for &(_, k, i) in &reflex {
            let poly = self.rings[k];
            let n = poly.len();
            let (p, q, r) = (poly[(i + n - 1) % n], poly[i], poly[(i + 1) % n]);
            let unit = |d: [f64; 2]| {
                let l = d[0].hypot(d[1]);
                if l > 0.0 { [d[0] / l, d[1] / l] } else { [0.0, 0.0] }
            };
            // Interior normals of the two edges (left of a counter-clockwise ring); their sum
            // halves the (reflex) interior angle.
            let e1 = unit([q[0] - p[0], q[1] - p[1]]);
            let e2 = unit([r[0] - q[0], r[1] - q[1]]);
            let b = unit([-e1[1] - e2[1], e1[0] + e2[0]]);
            if b == [0.0, 0.0] {
                continue;
            }
            // The point `k` clearances from the vertex, turned by `a` from the bisector.
            let at = |k: f64, a: f64| {
                let (s, c) = a.sin_cos();
                let d = [c * b[0] - s * b[1], s * b[0] + c * b[1]];
                [q[0] + k * self.c * d[0], q[1] + k * self.c * d[1]]
            };
            // Along the bisector or, where that comes too near another wall (a jamb close to
            // the opposite wall), turned from it by [`ASIDE`]: the first that keeps the
            // clearance.
            let step = |k: f64| ASIDE.iter().map(|&a| at(k, a)).find(|&z| self.clear_point(z));
            // Beside such a jamb, also a point just beyond the clearance: the nearest the
            // robot comes to the vertex, from where it looks past it the farthest.
            let tight = (!self.clear_point(at(STEPS[0], 0.0))).then_some(TIGHT_STEP);
            out.extend(tight.into_iter().chain(STEPS).filter_map(step));
        }
        out
    }

    /// The shortest path from `from` through `corners` to one of `goals` keeping the
    /// clearance, for the first goal (in the order given) that has one; `None` if none does.
    /// Goals are ends only: no path passes through one.
    pub(super) fn path(&self, from: Point, corners: &[Point], goals: &[Point]) -> Option<Path> {
        let nodes: Vec<Point> = std::iter::once(from)
            .chain(corners.iter().copied())
            .chain(goals.iter().copied())
            .collect();
        let first_goal = 1 + corners.len();
        let open: Vec<bool> = goals.iter().map(|&g| self.clear_point(g)).collect();
        // Integer costs for Dijkstra: lengths in units of 1e-12 of the region's magnitude
        // (every length fits in a u64, whatever the coordinates' scale).
        let outer = self.rings.first().copied().unwrap_or_default();
        let unit = 1e12 / crate::kernel::magnitude(outer).max(f64::MIN_POSITIVE);
        let cost = |a: Point, b: Point| ((a[0] - b[0]).hypot(a[1] - b[1]) * unit).round() as u64;
        let reached = pathfinding::directed::dijkstra::dijkstra_all(&0usize, |&u| {
            let a = nodes[u];
            let mut next = Vec::new();
            if u < first_goal {
                for (v, &b) in nodes.iter().enumerate().skip(1) {
                    let clear =
                        |a, b| if u == 0 { self.clear_leaving(a, b) } else { self.clear(a, b) };
                    if v != u && (v < first_goal || open[v - first_goal]) && clear(a, b) {
                        next.push((v, cost(a, b)));
                    }
                }
            }
            next
        });
        let g = (0..goals.len()).find(|&g| reached.contains_key(&(first_goal + g)))?;
        let mut via = Vec::new();
        let mut at = reached[&(first_goal + g)].0;
        while at != 0 {
            via.push(nodes[at]);
            at = reached[&at].0;
        }
        via.reverse();
        Some(Path { via, goal: g })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two rooms joined by a door 1 m wide in a wall 0.2 m thick, as one counter-clockwise
    /// ring: the lower room 0 ≤ x ≤ 4, 0 ≤ y ≤ 4; the door 1.5 ≤ x ≤ 2.5 at 4 ≤ y ≤ 4.2;
    /// the upper room above.
    fn two_rooms() -> Vec<Point> {
        vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [2.5, 4.0],
            [2.5, 4.2],
            [4.0, 4.2],
            [4.0, 8.2],
            [0.0, 8.2],
            [0.0, 4.2],
            [1.5, 4.2],
            [1.5, 4.0],
            [0.0, 4.0],
        ]
    }

    #[test]
    fn a_slanted_door_is_passed_by_bending_at_its_jambs() {
        let poly = two_rooms();
        let a = Approach::new(&poly, 0.3);
        // From the lower room's right to the upper room's right: the straight line runs into
        // the wall beside the door.
        let (from, goal) = ([3.5, 0.5], [3.5, 7.5]);
        assert!(a.clear_point(from) && a.clear_point(goal));
        assert!(!a.clear(from, goal));
        let corners = a.corners([from, goal]);
        let p = a.path(from, &corners, &[goal]).expect("a path through the door");
        assert_eq!(p.goal, 0);
        assert!(!p.via.is_empty());
        // Every leg keeps the clearance, checked from the definition.
        let pts: Vec<Point> =
            std::iter::once(from).chain(p.via.iter().copied()).chain([goal]).collect();
        assert!(legs_keep_clear(std::slice::from_ref(&poly), &pts, 0.3), "{pts:?}");
        // No longer than a detour through the door's middle with a metre to spare.
        let length: f64 =
            pts.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).sum();
        let mid = [2.0, 4.1];
        let detour =
            (mid[0] - from[0]).hypot(mid[1] - from[1]) + (goal[0] - mid[0]).hypot(goal[1] - mid[1]);
        assert!(length <= detour + 1.0, "{length}");
    }

    /// Whether every leg of the polyline `pts` keeps `c` from every edge of `rings`, checked
    /// from the definition on 101 points of each leg.
    fn legs_keep_clear(rings: &[Vec<Point>], pts: &[Point], c: f64) -> bool {
        pts.windows(2).all(|w| {
            (0..=100).all(|s| {
                let t = f64::from(s) / 100.0;
                let x = [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])];
                rings.iter().all(|r| {
                    (0..r.len()).all(|i| {
                        crate::geometry::segment_distance(x, r[i], r[(i + 1) % r.len()]) >= c - 1e-9
                    })
                })
            })
        })
    }

    #[test]
    fn a_pillar_in_a_region_with_holes_is_passed_around() {
        // A 10 m square (counter-clockwise) with a 2 m pillar at its middle (clockwise).
        let shape = vec![
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![[4.0, 4.0], [4.0, 6.0], [6.0, 6.0], [6.0, 4.0]],
        ];
        let a = Approach::with_holes(&shape, 0.3);
        let (from, goal) = ([1.0, 5.0], [9.0, 5.0]);
        assert!(!a.clear(from, goal), "the straight line crosses the pillar");
        assert!(!a.clear_point([5.0, 5.0]), "inside the pillar is not in the region");
        let corners = a.corners([from, goal]);
        let p = a.path(from, &corners, &[goal]).expect("a path around the pillar");
        let pts: Vec<Point> =
            std::iter::once(from).chain(p.via.iter().copied()).chain([goal]).collect();
        assert!(p.via.len() >= 2);
        assert!(legs_keep_clear(&shape, &pts, 0.3), "{pts:?}");
    }

    #[test]
    fn a_start_nearer_than_the_clearance_to_a_jamb_is_left_on_raw_scans() {
        let poly = two_rooms();
        // The robot stands in the door, 0.25 m from its right jamb's corner (2.5, 4): the
        // drift or an alignment put it there. The goal is in the upper room's right.
        let (from, goal) = ([2.25, 4.0], [3.5, 7.5]);
        let own = crate::geometry::segment_distance(from, [2.5, 4.0], [2.5, 4.2]);
        assert!((own - 0.25).abs() < 1e-12);
        let a = Approach::new(&poly, 0.3);
        let corners = a.corners([from, goal]);
        // Holding the whole clearance from the start, no path leaves it.
        assert_eq!(a.path(from, &corners, &[goal]), None);
        let a = a.leaving(true);
        let p = a.path(from, &corners, &[goal]).expect("a path out of the door");
        let pts: Vec<Point> =
            std::iter::once(from).chain(p.via.iter().copied()).chain([goal]).collect();
        // The first leg keeps 99% of what the robot has where it stands; every later leg
        // keeps the whole clearance (checked from the definition).
        assert!(legs_keep_clear(std::slice::from_ref(&poly), &pts[..2], 0.99 * own), "{pts:?}");
        assert!(legs_keep_clear(std::slice::from_ref(&poly), &pts[1..], 0.3), "{pts:?}");
    }

    #[test]
    fn a_door_narrower_than_the_robot_has_no_path() {
        let poly = two_rooms();
        // A clearance of 0.55 m: the 1 m door is too narrow.
        let a = Approach::new(&poly, 0.55);
        let (from, goal) = ([1.0, 1.0], [3.0, 7.0]);
        let corners = a.corners([from, goal]);
        assert_eq!(a.path(from, &corners, &[goal]), None);
    }

    #[test]
    fn the_first_goal_with_a_path_is_taken() {
        let poly = two_rooms();
        let a = Approach::new(&poly, 0.3);
        let from = [0.5, 0.5];
        // The first goal is outside the region, the second is within reach.
        let goals = [[5.0, 5.0], [3.5, 7.5]];
        let corners = a.corners([from, goals[1]]);
        assert_eq!(a.path(from, &corners, &goals).map(|p| p.goal), Some(1));
    }

    #[test]
    fn a_jamb_close_to_the_opposite_wall_still_has_a_graph_point() {
        // A room (0 ≤ x ≤ 1) and, behind a thin jamb whose tip is at (1, 1.2), a second room
        // reached through a gap 0.15 m high under the top wall (y = 1.35): too narrow for a
        // robot keeping 0.1 m. Along the tip's bisector the points 1.25 and 2.5 clearances
        // out come within 0.1 m of the top wall; turned from it, one is clear, and so is one
        // just beyond the clearance, from where the robot looks past the tip.
        let poly = vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.2],
            [1.05, 1.2],
            [1.05, 0.8],
            [3.0, 0.8],
            [3.0, 1.35],
            [0.0, 1.35],
        ];
        let c = 0.1;
        let a = Approach::new(&poly, c);
        let tip = [1.0, 1.2];
        let corners = a.corners([[0.5, 0.5], tip]);
        let near: Vec<Point> = corners
            .iter()
            .copied()
            .filter(|z| (z[0] - tip[0]).hypot(z[1] - tip[1]) <= 1.3 * c)
            .collect();
        assert!(!near.is_empty(), "no graph point beside the tip: {corners:?}");
        for z in &corners {
            // Clear from the definition: inside, and at least c from every edge.
            assert!(z[0] > 0.0 && z[0] < 3.0 && z[1] > 0.0 && z[1] < 1.35);
            let n = poly.len();
            let d = (0..n)
                .map(|i| crate::geometry::segment_distance(*z, poly[i], poly[(i + 1) % n]))
                .fold(f64::INFINITY, f64::min);
            assert!(d >= c, "{z:?} is {d} from the walls");
        }
        // The robot gets there from the room.
        assert!(a.path([0.5, 0.5], &corners, &near).is_some());
    }
}
