//! An independent visibility algorithm for checking [`super::expansion`]: an angular sweep
//! around the viewpoint over all edges, with no triangulation.
//!
//! The directions of all vertices cut the full turn around `q` into angular intervals; inside
//! one interval the nearest edge along every ray is the same, so the region's part there is
//! the triangle between `q` and that edge, clipped to the interval's two rays. The nearest
//! edge is found by testing the interval's middle ray against every edge: O(n) per interval,
//! O(n²) in all. Slow and simple on purpose.

use crate::geometry::{Domain, Location};
use crate::kernel::{Point, orient_sign};

/// The area visible from a point `q` in the open free space.
///
/// # Complexity
/// O(n²) time, O(n) space.
pub fn visible_area(domain: &Domain, q: Point) -> f64 {
    visible_area_within(domain, q, f64::INFINITY)
}

/// The area visible from `q` within distance `range`: each angular interval is split where
/// its nearest edge crosses the circle, and each part is a triangle or a circular sector.
///
/// # Complexity
/// O(n²) time, O(n) space.
pub fn visible_area_within(domain: &Domain, q: Point, range: f64) -> f64 {
    let edges: Vec<(Point, Point)> = domain
        .rings()
        .iter()
        .flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
        .collect();
    let mut angles: Vec<f64> =
        domain.rings().iter().flatten().map(|p| (p[1] - q[1]).atan2(p[0] - q[0])).collect();
    angles.sort_by(f64::total_cmp);
    angles.dedup();
    let tau = std::f64::consts::TAU;
    let mut area = 0.0;
    for i in 0..angles.len() {
        let a0 = angles[i];
        let a1 = if i + 1 < angles.len() { angles[i + 1] } else { angles[0] + tau };
        if a1 - a0 <= 0.0 {
            continue;
        }
        let mid = 0.5 * (a0 + a1);
        let d = [mid.cos(), mid.sin()];
        let mut best: Option<(f64, Point, Point)> = None;
        for &(p0, p1) in &edges {
            if let Some(t) = crate::geometry::ray_segment(q, d, p0, p1)
                && best.is_none_or(|b| t < b.0)
            {
                best = Some((t, p0, p1));
            }
        }
        let Some((_, p0, p1)) = best else { continue };
        let mut cuts = vec![a0, a1];
        if range.is_finite() {
            for t in circle_line(q, range, p0, p1) {
                let mut a = t;
                while a < a0 {
                    a += tau;
                }
                if a > a0 && a < a1 {
                    cuts.push(a);
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        for w in cuts.windows(2) {
            let (b0, b1) = (w[0], w[1]);
            let m = 0.5 * (b0 + b1);
            let hm = ray_line(q, [m.cos(), m.sin()], p0, p1);
            if (hm[0] - q[0]).hypot(hm[1] - q[1]) <= range {
                let h0 = ray_line(q, [b0.cos(), b0.sin()], p0, p1);
                let h1 = ray_line(q, [b1.cos(), b1.sin()], p0, p1);
                area += 0.5 * ((h0[0] - q[0]) * (h1[1] - q[1]) - (h1[0] - q[0]) * (h0[1] - q[1]));
            } else {
                area += 0.5 * range * range * (b1 - b0);
            }
        }
    }
    area
}

/// Angles (around `q`) where the line through `a`, `b` meets the circle of radius `r`.
fn circle_line(q: Point, r: f64, a: Point, b: Point) -> Vec<f64> {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let (fx, fy) = (a[0] - q[0], a[1] - q[1]);
    let (qa, qb, qc) = (dx * dx + dy * dy, 2.0 * (fx * dx + fy * dy), fx * fx + fy * fy - r * r);
    let disc = qb * qb - 4.0 * qa * qc;
    if qa == 0.0 || disc < 0.0 {
        return vec![];
    }
    let s = disc.sqrt();
    [(-qb - s) / (2.0 * qa), (-qb + s) / (2.0 * qa)]
        .iter()
        .map(|t| (fy + t * dy).atan2(fx + t * dx))
        .collect()
}

fn ray_line(q: Point, d: Point, a: Point, b: Point) -> Point {
    let e = [b[0] - a[0], b[1] - a[1]];
    let den = d[0] * e[1] - d[1] * e[0];
    let t = ((a[0] - q[0]) * e[1] - (a[1] - q[1]) * e[0]) / den;
    [q[0] + t * d[0], q[1] + t * d[1]]
}

/// Whether `p` is visible from `q` by brute force, for points in general position (the
/// segment meets no vertex except possibly at `q`): `p` and the segment's midpoint lie in the
/// closed free space and no edge crosses the segment properly.
///
/// # Complexity
/// O(n).
pub fn is_visible(domain: &Domain, q: Point, p: Point) -> bool {
    if domain.locate(p) == Location::Outside {
        return false;
    }
    let mid = [0.5 * (q[0] + p[0]), 0.5 * (q[1] + p[1])];
    if domain.locate(mid) == Location::Outside {
        return false;
    }
    for r in domain.rings() {
        for i in 0..r.len() {
            let (a, b) = (r[i], r[(i + 1) % r.len()]);
            let (o1, o2) = (orient_sign(q, p, a), orient_sign(q, p, b));
            let (o3, o4) = (orient_sign(a, b, q), orient_sign(a, b, p));
            if o1 * o2 < 0 && o3 * o4 < 0 {
                return false;
            }
        }
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn convex_room_sees_everything() {
        let d = Domain::new(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]], vec![]).unwrap();
        assert!((visible_area(&d, [1.0, 1.0]) - 12.0).abs() < 1e-12);
        assert!(is_visible(&d, [1.0, 1.0], [3.9, 2.9]));
    }

    #[test]
    fn a_pillar_casts_a_shadow() {
        let d = Domain::new(
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![vec![[4.0, 4.0], [6.0, 4.0], [6.0, 6.0], [4.0, 6.0]]],
        )
        .unwrap();
        let a = visible_area(&d, [1.0, 5.0]);
        assert!(a < 96.0 && a > 50.0);
        assert!(!is_visible(&d, [1.0, 5.0], [9.0, 5.0]));
        assert!(is_visible(&d, [1.0, 5.0], [9.0, 9.5]));
    }
}
