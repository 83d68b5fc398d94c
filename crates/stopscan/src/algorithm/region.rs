//! Regions for coverage bookkeeping: union, difference, intersection and area of many
//! polygons, by i_overlay; and the clipping of one ring to a box ([`clip_to_box`],
//! Sutherland–Hodgman).
//!
//! i_overlay snaps coordinates to an integer grid over the operands' bounding box (31 bits a
//! side), so results are exact up to about 5e-10 of the extent; areas carry that relative
//! precision. A union of many polygons is merged as a balanced tree of pairwise unions
//! (`union_all`); `benches/visibility.rs` measures it against one overlay of everything and
//! against a left fold.

use i_overlay::core::fill_rule::FillRule;
use i_overlay::core::overlay_rule::OverlayRule;
use i_overlay::float::overlay::FloatOverlay;
use serde::{Deserialize, Serialize};

use crate::geometry::Domain;
use crate::kernel::Point;

/// A set of polygons with holes: each shape is an outer ring (counter-clockwise) followed by
/// its holes (clockwise).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Region {
    /// The shapes.
    pub shapes: Vec<Vec<Vec<Point>>>,
}

impl Region {
    /// The empty region.
    pub fn empty() -> Self {
        Self::default()
    }

    /// One simple polygon (either orientation).
    pub fn polygon(ring: &[Point]) -> Self {
        Self::overlay_all(&[ring.to_vec()])
    }

    /// The free space of a domain.
    pub fn of_domain(d: &Domain) -> Self {
        Self { shapes: vec![d.rings().to_vec()] }
    }

    /// The union of many simple polygons, merged as a balanced binary tree of pairwise
    /// unions. Visibility regions overlap heavily; one overlay of all of them must resolve
    /// every mutual crossing at once, and is several times slower (`benches/visibility.rs`,
    /// `region_union_*`).
    ///
    /// # Complexity
    /// O(log m) rounds of pairwise overlays for m polygons.
    pub fn union_all(polygons: &[Vec<Point>]) -> Self {
        let mut layer: Vec<Region> =
            polygons.iter().filter(|p| p.len() >= 3).map(|p| Self::polygon(p)).collect();
        while layer.len() > 1 {
            layer = layer
                .chunks(2)
                .map(|c| if c.len() == 2 { c[0].union(&c[1]) } else { c[0].clone() })
                .collect();
        }
        layer.pop().unwrap_or_default()
    }

    /// The union of many simple polygons in one overlay (the alternative `union_all` is
    /// measured against).
    ///
    /// # Complexity
    /// O((n + k) log n) for n edges in all and k crossings.
    pub fn overlay_all(polygons: &[Vec<Point>]) -> Self {
        if polygons.is_empty() {
            return Self::empty();
        }
        let subj: Vec<Vec<Point>> =
            polygons.iter().filter(|p| p.len() >= 3).map(|p| oriented(p)).collect();
        let shapes =
            FloatOverlay::with_subj(&subj).overlay(OverlayRule::Subject, FillRule::NonZero);
        Self { shapes }
    }

    fn op(&self, other: &Self, rule: OverlayRule) -> Self {
        let a: Vec<Vec<Point>> = self.shapes.iter().flatten().cloned().collect();
        let b: Vec<Vec<Point>> = other.shapes.iter().flatten().cloned().collect();
        if a.is_empty() && b.is_empty() {
            return Self::empty();
        }
        let shapes = FloatOverlay::with_subj_and_clip(&a, &b).overlay(rule, FillRule::NonZero);
        Self { shapes }
    }

    /// `self ∪ other`.
    #[must_use]
    pub fn union(&self, other: &Self) -> Self {
        self.op(other, OverlayRule::Union)
    }

    /// `self ∖ other`.
    #[must_use]
    pub fn difference(&self, other: &Self) -> Self {
        self.op(other, OverlayRule::Difference)
    }

    /// `self ∩ other`.
    #[must_use]
    pub fn intersection(&self, other: &Self) -> Self {
        self.op(other, OverlayRule::Intersect)
    }

    /// The area (holes subtracted).
    pub fn area(&self) -> f64 {
        self.shapes
            .iter()
            .flatten()
            .filter(|r| r.len() >= 3)
            .map(|r| crate::geometry::signed_area_of(r))
            .sum::<f64>()
            .abs()
    }

    /// Whether `p` lies inside the region (inside a shape's outer ring and in none of its
    /// holes; points on a ring count as inside).
    pub fn contains(&self, p: Point) -> bool {
        use crate::kernel::{RingSide, ring_side};
        self.shapes.iter().any(|s| {
            s.first().is_some_and(|o| ring_side(o, p) != RingSide::Outside)
                && s[1..].iter().all(|h| ring_side(h, p) != RingSide::Inside)
        })
    }

    /// Whether the region is empty.
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }
}

/// The configuration space of a convex footprint in a domain: the reference points `x` at
/// which the robot `x + F` lies in the closed free space. `footprint` is a convex polygon
/// around the reference point `[0, 0]`.
///
/// The robot at `x` meets a boundary edge `e` exactly when `x ∈ e ⊕ (−F)`, the convex hull of
/// the edge's ends minus the footprint's vertices; a whole obstacle inside the robot would
/// meet its edges too. So the configuration space is the free space less the union of one
/// convex hull per boundary edge (a Minkowski sum of the obstacles with the reflected
/// footprint). The hulls are grown by `margin` (metres, on top of the overlay's own
/// snapping), so that the result lies inside the exact configuration space.
///
/// # Complexity
/// One overlay of n hulls of at most 2k vertices, for n domain edges and a k-gon footprint.
pub fn configuration_space(domain: &Domain, footprint: &[Point], margin: f64) -> Region {
    let grown: Vec<Point> = footprint
        .iter()
        .map(|p| {
            let r = p[0].hypot(p[1]);
            let f = if r > 0.0 { (r + margin) / r } else { 1.0 };
            [-p[0] * f, -p[1] * f]
        })
        .collect();
    Region::of_domain(domain).difference(&Region::overlay_all(&edge_hulls(domain, &grown)))
}

/// The domain grown by a convex `shape` placed at each of its points (a Minkowski sum):
/// where a robot whose configuration space is `domain` can put its body, for its
/// footprint as `shape`.
///
/// # Complexity
/// One overlay of n hulls of at most 2k vertices, for n domain edges and a k-gon shape.
pub fn dilation(domain: &Domain, shape: &[Point]) -> Region {
    Region::of_domain(domain).union(&Region::overlay_all(&edge_hulls(domain, shape)))
}

/// The convex hull of each boundary edge of `domain` swept by `shape`.
fn edge_hulls(domain: &Domain, shape: &[Point]) -> Vec<Vec<Point>> {
    let mut hulls = Vec::new();
    for ring in domain.rings() {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            let pts: Vec<Point> = shape
                .iter()
                .flat_map(|f| [[a[0] + f[0], a[1] + f[1]], [b[0] + f[0], b[1] + f[1]]])
                .collect();
            hulls.push(convex_hull(pts));
        }
    }
    hulls
}

/// The convex hull (counter-clockwise, Andrew's monotone chain with exact orientation).
fn convex_hull(mut pts: Vec<Point>) -> Vec<Point> {
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup();
    if pts.len() < 3 {
        return pts;
    }
    let mut lower: Vec<Point> = Vec::new();
    for &p in &pts {
        while lower.len() >= 2
            && crate::kernel::orient_sign(lower[lower.len() - 2], lower[lower.len() - 1], p) <= 0
        {
            lower.pop();
        }
        lower.push(p);
    }
    let mut upper: Vec<Point> = Vec::new();
    for &p in pts.iter().rev() {
        while upper.len() >= 2
            && crate::kernel::orient_sign(upper[upper.len() - 2], upper[upper.len() - 1], p) <= 0
        {
            upper.pop();
        }
        upper.push(p);
    }
    lower.pop();
    upper.pop();
    lower.extend(upper);
    lower
}

/// Sutherland–Hodgman clipping of a ring against an axis-aligned box `[x0, y0, x1, y1]`:
/// the part of the ring's polygon inside the box, as one ring (empty, or fewer than three
/// points, when nothing is left). The result of a non-convex ring may have zero-width
/// bridges, which do not change its area; the grid family measures cell–polygon overlaps
/// with it (no overlay needed against one square).
///
/// # Complexity
/// O(n) time and space for a ring of n points (four passes, each adds at most one point per
/// edge it cuts).
pub fn clip_to_box(ring: &[Point], b: [f64; 4]) -> Vec<Point> {
    let mut pts = ring.to_vec();
    // (axis, bound, keep the side where the coordinate is >= bound?)
    for (axis, bound, keep_ge) in
        [(0, b[0], true), (0, b[2], false), (1, b[1], true), (1, b[3], false)]
    {
        if pts.is_empty() {
            break;
        }
        let inside = |p: &Point| if keep_ge { p[axis] >= bound } else { p[axis] <= bound };
        let mut out = Vec::with_capacity(pts.len() + 4);
        for i in 0..pts.len() {
            let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
            let (ip, iq) = (inside(&p), inside(&q));
            if ip {
                out.push(p);
            }
            if ip != iq {
                let t = (bound - p[axis]) / (q[axis] - p[axis]);
                let mut m = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                m[axis] = bound;
                out.push(m);
            }
        }
        pts = out;
    }
    pts
}

/// Counter-clockwise copy (i_overlay's non-zero rule counts windings).
fn oriented(ring: &[Point]) -> Vec<Point> {
    let mut r = ring.to_vec();
    if crate::geometry::signed_area_of(&r) < 0.0 {
        r.reverse();
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sq(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn union_difference_area() {
        let u = Region::union_all(&[sq(0.0, 0.0, 2.0), sq(1.0, 1.0, 2.0), sq(10.0, 10.0, 1.0)]);
        assert!((u.area() - (4.0 + 4.0 - 1.0 + 1.0)).abs() < 1e-9);
        let d =
            Region::polygon(&sq(0.0, 0.0, 4.0)).difference(&Region::polygon(&sq(1.0, 1.0, 1.0)));
        assert!((d.area() - 15.0).abs() < 1e-9);
        assert_eq!(d.shapes.len(), 1);
        assert_eq!(d.shapes[0].len(), 2, "one hole");
        let i =
            Region::polygon(&sq(0.0, 0.0, 2.0)).intersection(&Region::polygon(&sq(1.0, 1.0, 2.0)));
        assert!((i.area() - 1.0).abs() < 1e-9);
        assert!(Region::union_all(&[]).is_empty());
    }

    #[test]
    fn the_configuration_space_of_a_square_robot_in_a_room() {
        // A 10 × 6 room with a 2 × 2 pillar; a robot of half-width 0.5 (a square).
        let room = Domain::new(
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 6.0], [0.0, 6.0]],
            vec![vec![[4.0, 2.0], [4.0, 4.0], [6.0, 4.0], [6.0, 2.0]]],
        )
        .unwrap();
        let f = sq(-0.5, -0.5, 1.0);
        let c = configuration_space(&room, &f, 0.0);
        // The room shrinks to 9 × 5, the pillar grows to 3 × 3 (square corners stay square).
        assert!((c.area() - (45.0 - 9.0)).abs() < 1e-6, "{}", c.area());
        assert_eq!(c.shapes.len(), 1);
        assert_eq!(c.shapes[0].len(), 2);
        // A corridor narrower than the robot disappears from it.
        let corridor = Domain::new(
            vec![
                [0.0, 0.0],
                [4.0, 0.0],
                [4.0, 4.0],
                [6.0, 4.0],
                [6.0, 4.8],
                [4.0, 4.8],
                [4.0, 8.0],
                [0.0, 8.0],
            ],
            vec![],
        )
        .unwrap();
        let c = configuration_space(&corridor, &f, 0.0);
        assert!((c.area() - 3.0 * 7.0).abs() < 1e-6, "{}", c.area());
    }

    #[test]
    fn hulls_are_convex_and_counter_clockwise() {
        let h = convex_hull(vec![[0.0, 0.0], [2.0, 0.0], [1.0, 0.5], [2.0, 2.0], [0.0, 2.0]]);
        assert_eq!(h, vec![[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]]);
    }

    #[test]
    fn clipping_to_a_box_keeps_the_part_inside() {
        let area = |r: &[Point]| crate::geometry::signed_area_of(r).abs();
        // A square overlapping the box's corner: a quarter of it is inside.
        let c = clip_to_box(&sq(-1.0, -1.0, 2.0), [0.0, 0.0, 4.0, 4.0]);
        assert!((area(&c) - 1.0).abs() < 1e-12, "{c:?}");
        // Wholly inside: unchanged; wholly outside: nothing left.
        assert_eq!(clip_to_box(&sq(1.0, 1.0, 1.0), [0.0, 0.0, 4.0, 4.0]), sq(1.0, 1.0, 1.0));
        assert!(clip_to_box(&sq(5.0, 5.0, 1.0), [0.0, 0.0, 4.0, 4.0]).len() < 3);
        // A non-convex U whose arms both cross the box: the bridge between them has no area.
        let u = vec![
            [0.0, 0.0],
            [3.0, 0.0],
            [3.0, 3.0],
            [2.0, 3.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [1.0, 3.0],
            [0.0, 3.0],
        ];
        let c = clip_to_box(&u, [-1.0, 2.0, 4.0, 4.0]);
        assert!((area(&c) - 2.0).abs() < 1e-12, "{c:?}");
    }
}
