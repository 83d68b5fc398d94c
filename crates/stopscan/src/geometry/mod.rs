//! Geometry with no robot concepts: the validated [`Domain`] (a polygon with holes).
//!
//! - `domain`: [`Domain`], validated once ([`InvalidEnvironment`]), and where a point lies
//!   ([`Location`]);
//! - `frame`: [`Frame`], the exact shift between the input's coordinates and the local frame;
//! - here: [`signed_area_of`], [`segment_distance`] and [`segments_distance`].

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

/// The distance from `p` to the closed segment `a b` (floating point).
pub fn segment_distance(p: Point, a: Point, b: Point) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let l2 = dx * dx + dy * dy;
    let t = if l2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
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

/// Signed area of a ring (positive when counter-clockwise).
pub fn signed_area_of(ring: &[Point]) -> f64 {
    domain::signed_area(ring)
}
