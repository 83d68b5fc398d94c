//! Exact predicates. This is the only module that calls `robust`; everything else asks it
//! for an [`Orientation`] or composes its answers, never a raw floating-point sign.
//!
//! Inputs must lie in the range where Shewchuk's adaptive predicates are exact
//! ([`MIN_ABS`] ≤ |x| ≤ [`MAX_ABS`], or 0); `geometry::Domain` validates that once.

use robust::Coord;

pub mod tolerance;

/// A point of the plane.
pub type Point = [f64; 2];

/// Smallest non-zero magnitude accepted (as spade does: 2^-142).
pub const MIN_ABS: f64 = 1.793_662_034_335_766e-43;
/// Largest magnitude accepted (as spade does: 2^201).
pub const MAX_ABS: f64 = 3.213_876_088_517_98e60;

/// A number as people read it in messages: Rust's shortest round-trip decimal for ordinary
/// magnitudes (`0.25`, `-3`, `1500000`), scientific notation outside [1e-6, 1e16) (`1e300`,
/// `-2.5e-12`), so that a user's `1e300` is echoed as `1e300` and not as 301 digits.
///
/// # Example
/// ```
/// use stopscan::kernel::Num;
/// assert_eq!(Num(1e300).to_string(), "1e300");
/// assert_eq!(Num(0.25).to_string(), "0.25");
/// assert_eq!(Num(-1e-9).to_string(), "-1e-9");
/// assert_eq!(Num(f64::NAN).to_string(), "NaN");
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl std::fmt::Display for Num {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-6..1e16).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// Which side of a directed line a point lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Orientation {
    /// Left of `a → b` (counter-clockwise turn).
    CounterClockwise,
    /// Right of `a → b` (clockwise turn).
    Clockwise,
    /// On the line through `a` and `b`.
    Collinear,
}

impl Orientation {
    /// +1, -1 or 0.
    pub fn sign(self) -> i8 {
        match self {
            Self::CounterClockwise => 1,
            Self::Clockwise => -1,
            Self::Collinear => 0,
        }
    }
}

/// The exact orientation of `c` relative to the directed line `a → b`.
#[inline]
pub fn orient(a: Point, b: Point, c: Point) -> Orientation {
    let d = orient_value(a, b, c);
    if d > 0.0 {
        Orientation::CounterClockwise
    } else if d < 0.0 {
        Orientation::Clockwise
    } else {
        Orientation::Collinear
    }
}

/// The exact sign of the orientation as -1, 0 or +1 (for hot loops).
#[inline]
pub fn orient_sign(a: Point, b: Point, c: Point) -> i8 {
    let d = orient_value(a, b, c);
    i8::from(d > 0.0) - i8::from(d < 0.0)
}

#[inline]
fn orient_value(a: Point, b: Point, c: Point) -> f64 {
    robust::orient2d(
        Coord { x: a[0], y: a[1] },
        Coord { x: b[0], y: b[1] },
        Coord { x: c[0], y: c[1] },
    )
}

/// How far a point constructed in floating point (a ray meeting a wall, a cut along a segment)
/// may lie from its exact position when the coordinates involved are at most `scale` in
/// magnitude: 64 units in the last place of `scale`. Every tolerance of the strategies and
/// the window tests is at least this, so they stay meaningful whatever the coordinates' origin
/// (a map in UTM coordinates, say, rounds its constructed points a million times coarser than
/// the same map near the origin).
pub fn rounding(scale: f64) -> f64 {
    64.0 * f64::EPSILON * scale
}

/// The largest coordinate magnitude of `points` (the scale for [`rounding`]).
pub fn magnitude<'a>(points: impl IntoIterator<Item = &'a Point>) -> f64 {
    points.into_iter().flatten().fold(0.0, |m, v| m.max(v.abs()))
}

/// Whether a coordinate is finite and in the predicates' exact range.
pub fn coordinate_is_safe(v: f64) -> bool {
    v.is_finite() && (v == 0.0 || (MIN_ABS..=MAX_ABS).contains(&v.abs()))
}

/// Whether `p` lies on the closed segment `a b` (exact).
pub fn on_segment(a: Point, b: Point, p: Point) -> bool {
    orient_sign(a, b, p) == 0
        && p[0] >= a[0].min(b[0])
        && p[0] <= a[0].max(b[0])
        && p[1] >= a[1].min(b[1])
        && p[1] <= a[1].max(b[1])
}

/// Whether the closed segments `a b` and `c d` share at least one point (exact).
pub fn segments_intersect(a: Point, b: Point, c: Point, d: Point) -> bool {
    let (o1, o2) = (orient_sign(a, b, c), orient_sign(a, b, d));
    let (o3, o4) = (orient_sign(c, d, a), orient_sign(c, d, b));
    if o1 * o2 < 0 && o3 * o4 < 0 {
        return true;
    }
    (o1 == 0 && on_segment(a, b, c))
        || (o2 == 0 && on_segment(a, b, d))
        || (o3 == 0 && on_segment(c, d, a))
        || (o4 == 0 && on_segment(c, d, b))
}

/// Where a point lies relative to a closed polygon ring.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RingSide {
    /// Strictly inside.
    Inside,
    /// On an edge or a vertex.
    Boundary,
    /// Strictly outside.
    Outside,
}

/// Exact point-in-ring test (crossing number with exact side tests), any orientation.
///
/// # Complexity
/// O(n).
pub fn ring_side(ring: &[Point], p: Point) -> RingSide {
    let n = ring.len();
    let mut inside = false;
    for i in 0..n {
        let (a, b) = (ring[i], ring[(i + 1) % n]);
        if on_segment(a, b, p) {
            return RingSide::Boundary;
        }
        // Half-open rule on y: the edge counts when it straddles the horizontal line at p.
        if (a[1] > p[1]) != (b[1] > p[1]) {
            // p is left of the upward edge ⇔ the rightward ray crosses it.
            let s = orient_sign(a, b, p);
            let upward = b[1] > a[1];
            if (upward && s > 0) || (!upward && s < 0) {
                inside = !inside;
            }
        }
    }
    if inside { RingSide::Inside } else { RingSide::Outside }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_is_exact_on_near_collinear_points() {
        // A classic failure of naive arithmetic: points almost on a line.
        let a = [0.5, 0.5];
        let b = [12.0, 12.0];
        let c = [24.0, 24.0];
        assert_eq!(orient(a, b, c), Orientation::Collinear);
        let c2 = [24.0, 24.000_000_000_000_004];
        assert_eq!(orient(a, b, c2), Orientation::CounterClockwise);
    }

    #[test]
    fn segments() {
        assert!(segments_intersect([0.0, 0.0], [2.0, 2.0], [0.0, 2.0], [2.0, 0.0]));
        assert!(segments_intersect([0.0, 0.0], [2.0, 0.0], [2.0, 0.0], [3.0, 1.0]));
        assert!(segments_intersect([0.0, 0.0], [2.0, 0.0], [1.0, 0.0], [3.0, 0.0]));
        assert!(!segments_intersect([0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]));
        assert!(!segments_intersect([0.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.4, 0.6]));
    }

    #[test]
    fn ring_sides() {
        let sq = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        assert_eq!(ring_side(&sq, [1.0, 1.0]), RingSide::Inside);
        assert_eq!(ring_side(&sq, [2.0, 1.0]), RingSide::Boundary);
        assert_eq!(ring_side(&sq, [0.0, 0.0]), RingSide::Boundary);
        assert_eq!(ring_side(&sq, [3.0, 1.0]), RingSide::Outside);
        assert_eq!(ring_side(&sq, [1.0, 2.5]), RingSide::Outside);
        // A vertex at the query's height.
        let tri = [[0.0, 0.0], [4.0, 1.0], [0.0, 2.0]];
        assert_eq!(ring_side(&tri, [1.0, 1.0]), RingSide::Inside);
        assert_eq!(ring_side(&tri, [5.0, 1.0]), RingSide::Outside);
    }

    #[test]
    fn safe_range() {
        assert!(coordinate_is_safe(0.0) && coordinate_is_safe(1e10) && coordinate_is_safe(-3.5));
        assert!(
            !coordinate_is_safe(f64::NAN)
                && !coordinate_is_safe(1e300)
                && !coordinate_is_safe(1e-300)
        );
    }
}
