//! Geometry with no robot concepts: the validated [`Domain`] (a polygon with holes).
//!
//! - `domain`: [`Domain`], validated once ([`InvalidEnvironment`]), and where a point lies
//!   ([`Location`]);
//! - `frame`: [`Frame`], the exact shift between the input's coordinates and the local frame;
//! - here: [`signed_area_of`], [`segment_distance`], [`segments_distance`] and
//!   [`fit_line`].

mod domain;
mod frame;

pub use crate::kernel::Point;
pub use domain::{Domain, EdgeId, InvalidEnvironment, Location};
pub use frame::Frame;

/// Where the ray from `o` along `u` first meets the closed segment `a b`, as the parameter `t`
/// of `o + t·u` (`t > 0`; a distance when `u` is a unit vector); `None` when it misses or
/// runs parallel to it. Floating point.
pub fn ray_segment(o: Point, u: Point, a: Point, b: Point) -> Option<f64> {
    let s = [b[0] - a[0], b[1] - a[1]];
    let den = u[0] * s[1] - u[1] * s[0];
    if den == 0.0 {
        return None;
    }
    let w = [a[0] - o[0], a[1] - o[1]];
    let t = (w[0] * s[1] - w[1] * s[0]) / den;
    let v = (w[0] * u[1] - w[1] * u[0]) / den;
    (t > 0.0 && (0.0..=1.0).contains(&v)).then_some(t)
}

/// The offset from the point of the closed segment `a b` nearest `p` to `p`.
fn offset_from_segment(p: Point, a: Point, b: Point) -> [f64; 2] {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    [p[0] - a[0] - t * dx, p[1] - a[1] - t * dy]
}

/// The distance from `p` to the closed segment `a b` (floating point).
pub fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let [ex, ey] = offset_from_segment(p, a, b);
    ex.hypot(ey)
}

/// The squared distance from `p` to the closed segment `a b` (floating point).
fn segment_distance_sq(p: Point, a: Point, b: Point) -> f64 {
    let [ex, ey] = offset_from_segment(p, a, b);
    ex * ex + ey * ey
}

/// Whether the closed segments `a b` and `c d` come closer than `r`: they meet (exact test),
/// or an end lies nearer than `r` to the other segment; never for `r <= 0`. It is
/// `segments_distance(a, b, c, d) < r` up to rounding, without square roots (the planner's
/// clearance test, called for every wall near every move it considers).
pub fn segments_closer_than(a: Point, b: Point, c: Point, d: Point, r: f64) -> bool {
    if r <= 0.0 || r.is_nan() {
        return false;
    }
    let r2 = r * r;
    segment_distance_sq(a, c, d) < r2
        || segment_distance_sq(b, c, d) < r2
        || segment_distance_sq(c, a, b) < r2
        || segment_distance_sq(d, a, b) < r2
        || crate::kernel::segments_intersect(a, b, c, d)
}

/// The distance between the closed segments `a b` and `c d`: 0 when they meet (exact test),
/// else the least of the four end-to-segment distances (floating point).
pub fn segments_distance(a: Point, b: Point, c: Point, d: Point) -> f64 {
    if crate::kernel::segments_intersect(a, b, c, d) {
        return 0.0;
    }
    segment_distance(a, c, d)
        .min(segment_distance(b, c, d))
        .min(segment_distance(c, a, b))
        .min(segment_distance(d, a, b))
}

/// The line through `points` by orthogonal regression (total least squares): their centroid
/// and the unit direction of most spread about it, at angle ½·atan2(2sxy, sxx − syy) (the x
/// axis when the points all coincide). Floating point; `points` must not be empty.
pub fn fit_line(points: &[Point]) -> (Point, Point) {
    let n = points.len() as f64;
    let (cx, cy) = points.iter().fold((0.0, 0.0), |s, p| (s.0 + p[0], s.1 + p[1]));
    let (cx, cy) = (cx / n, cy / n);
    let (mut sxx, mut syy, mut sxy) = (0.0, 0.0, 0.0);
    for p in points {
        let (dx, dy) = (p[0] - cx, p[1] - cy);
        sxx += dx * dx;
        syy += dy * dy;
        sxy += dx * dy;
    }
    let a = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    ([cx, cy], [a.cos(), a.sin()])
}

/// Signed area of a ring (positive when counter-clockwise).
pub fn signed_area_of(ring: &[Point]) -> f64 {
    domain::signed_area(ring)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn point() -> impl Strategy<Value = Point> {
        (-10.0..10.0f64, -10.0..10.0f64).prop_map(|(x, y)| [x, y])
    }

    proptest! {
        /// The squared test agrees with the distance it stands for, away from rounding at
        /// the threshold; crossing segments are closer than any positive r, and nothing is
        /// closer than 0.
        #[test]
        fn segments_closer_than_agrees_with_their_distance(
            a in point(), b in point(), c in point(), d in point(), r in 0.0..3.0f64,
        ) {
            let dist = segments_distance(a, b, c, d);
            prop_assume!((dist - r).abs() > 1e-9);
            prop_assert_eq!(segments_closer_than(a, b, c, d, r), dist < r);
            prop_assert!(!segments_closer_than(a, b, c, d, 0.0));
            if crate::kernel::segments_intersect(a, b, c, d) {
                prop_assert!(segments_closer_than(a, b, c, d, 1e-12));
            }
        }
    }
}
