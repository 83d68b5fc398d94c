//! Range-limited visibility: the paper's restricted visibility polygon, the part of the
//! visibility region within distance `R` of the viewpoint.
//!
//! The full region is star-shaped from `q`, so each boundary piece is clipped to the disk on
//! its own; where the boundary runs beyond `R`, the clipped region follows the circle, which
//! is kept exact as an [`RangePiece::Arc`]. The exact area adds, for straight pieces, the
//! triangle `½·(a − q)×(b − q)`, and for arcs the sector `½·R²·Δθ`. For boolean operations,
//! [`RangeRegion::to_polygon`] replaces each arc by inscribed chords whose sagitta is at most a
//! stated tolerance, so the polygon lies within that distance of the exact region.

use serde::{Deserialize, Serialize};

use super::{BoundaryPiece, VisibilityRegion};
use crate::kernel::Point;

/// The smallest arc tolerance [`RangeRegion::to_polygon`] honours, relative to the radius
/// (1e-9·R: 70,250 chords for a full circle). Below about 1.1e-16·R, `acos(1 − t/R)` is 0 and
/// the chord count would be infinite.
pub const MIN_ARC_TOLERANCE: f64 = 1e-9;

/// A boundary piece of a range-limited region.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(untagged)]
pub enum RangePiece {
    /// A straight piece (edge, partial edge or window), clipped to the disk.
    Straight(BoundaryPiece),
    /// An arc of the range circle, counter-clockwise.
    Arc(Arc),
}

/// An arc of the circle of radius `radius` around `center`, counter-clockwise from `from`
/// to `to` (a full circle when `sweep` is 2π).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename = "arc")]
pub struct Arc {
    /// Start point on the circle.
    pub from: Point,
    /// End point on the circle.
    pub to: Point,
    /// The viewpoint.
    pub center: Point,
    /// The range.
    pub radius: f64,
    /// The swept angle in (0, 2π].
    pub sweep: f64,
}

/// A range-limited visibility region with exact arcs.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RangeRegion {
    /// The viewpoint.
    pub viewpoint: Point,
    /// The range `R`.
    pub radius: f64,
    /// Boundary pieces, counter-clockwise.
    pub boundary: Vec<RangePiece>,
}

impl RangeRegion {
    /// The same region with every point moved by `f` (a change of frame: a translation, so
    /// radii and angles stay).
    #[must_use]
    pub fn mapped(&self, f: impl Fn(Point) -> Point) -> Self {
        Self {
            viewpoint: f(self.viewpoint),
            radius: self.radius,
            boundary: self
                .boundary
                .iter()
                .map(|p| match p {
                    RangePiece::Straight(b) => RangePiece::Straight(b.mapped(&f)),
                    RangePiece::Arc(a) => RangePiece::Arc(Arc {
                        from: f(a.from),
                        to: f(a.to),
                        center: f(a.center),
                        ..*a
                    }),
                })
                .collect(),
        }
    }

    /// The exact area.
    pub fn area(&self) -> f64 {
        let q = self.viewpoint;
        self.boundary
            .iter()
            .map(|p| match p {
                RangePiece::Straight(b) => {
                    let (a, c) = b.ends();
                    0.5 * ((a[0] - q[0]) * (c[1] - q[1]) - (c[0] - q[0]) * (a[1] - q[1]))
                }
                RangePiece::Arc(a) => 0.5 * a.radius * a.radius * a.sweep,
            })
            .sum()
    }

    /// A polygon within `tolerance` of the exact region: arcs become inscribed chords with
    /// sagitta `R·(1 − cos(Δ/2)) ≤ tolerance`, but never finer than [`MIN_ARC_TOLERANCE`]`·R`
    /// (chords of at least 8.9e-5 rad: at most 70,250 vertices for a full circle), so that a
    /// tiny tolerance cannot ask for unbounded output.
    pub fn to_polygon(&self, tolerance: f64) -> Vec<Point> {
        let mut out: Vec<Point> = Vec::new();
        let push = |out: &mut Vec<Point>, p: Point| {
            if out.last() != Some(&p) {
                out.push(p);
            }
        };
        for piece in &self.boundary {
            match piece {
                RangePiece::Straight(b) => {
                    let (a, c) = b.ends();
                    push(&mut out, a);
                    push(&mut out, c);
                }
                RangePiece::Arc(a) => {
                    let max_step = if tolerance > 0.0 && tolerance < a.radius {
                        2.0 * (1.0 - tolerance.max(MIN_ARC_TOLERANCE * a.radius) / a.radius).acos()
                    } else {
                        std::f64::consts::FRAC_PI_2
                    };
                    let n = ((a.sweep / max_step).ceil() as usize).max(1);
                    let start = (a.from[1] - a.center[1]).atan2(a.from[0] - a.center[0]);
                    push(&mut out, a.from);
                    for k in 1..n {
                        let t = start + a.sweep * k as f64 / n as f64;
                        push(
                            &mut out,
                            [a.center[0] + a.radius * t.cos(), a.center[1] + a.radius * t.sin()],
                        );
                    }
                    push(&mut out, a.to);
                }
            }
        }
        if out.len() > 1 && out.first() == out.last() {
            out.pop();
        }
        out
    }

    /// The region as a polygon with labelled pieces, arcs replaced by inscribed chords
    /// (sagitta at most `tolerance`) labelled [`BoundaryPiece::Frontier`]: what a
    /// range-limited scan hands an exploration strategy.
    pub fn to_region(&self, tolerance: f64) -> VisibilityRegion {
        let mut boundary = Vec::new();
        for piece in &self.boundary {
            match piece {
                RangePiece::Straight(b) => boundary.push(*b),
                RangePiece::Arc(a) => {
                    let one = RangeRegion {
                        viewpoint: self.viewpoint,
                        radius: self.radius,
                        boundary: vec![RangePiece::Arc(*a)],
                    };
                    let mut pts = one.to_polygon(tolerance);
                    if a.sweep >= std::f64::consts::TAU {
                        pts.push(pts[0]);
                    } else if pts.last() != Some(&a.to) {
                        pts.push(a.to);
                    }
                    for w in pts.windows(2) {
                        boundary.push(BoundaryPiece::Frontier { from: w[0], to: w[1] });
                    }
                }
            }
        }
        VisibilityRegion {
            viewpoint: self.viewpoint,
            polygon: self.to_polygon(tolerance),
            boundary,
        }
    }

    /// The arcs.
    pub fn arcs(&self) -> impl Iterator<Item = &Arc> {
        self.boundary.iter().filter_map(|p| if let RangePiece::Arc(a) = p { Some(a) } else { None })
    }
}

/// The part of `full` within distance `r` of its viewpoint.
///
/// # Complexity
/// O(k) for k boundary pieces.
pub fn clip(full: &VisibilityRegion, r: f64) -> RangeRegion {
    let q = full.viewpoint;
    let r2 = r * r;
    // Each piece clipped to the disk: (piece, entered, exited).
    let mut kept: Vec<(BoundaryPiece, bool, bool)> = Vec::new();
    for &b in &full.boundary {
        let (a, c) = b.ends();
        let (dx, dy) = (c[0] - a[0], c[1] - a[1]);
        let (fx, fy) = (a[0] - q[0], a[1] - q[1]);
        let (qa, qb, qc) = (dx * dx + dy * dy, 2.0 * (fx * dx + fy * dy), fx * fx + fy * fy - r2);
        let (t0, t1) = if qa == 0.0 {
            if qc <= 0.0 { (0.0, 1.0) } else { continue }
        } else {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc < 0.0 {
                continue;
            }
            let s = disc.sqrt();
            ((-qb - s) / (2.0 * qa), (-qb + s) / (2.0 * qa))
        };
        let (t0, t1) = (t0.max(0.0), t1.min(1.0));
        if t0 >= t1 {
            continue;
        }
        let at = |t: f64| {
            if t <= 0.0 {
                a
            } else if t >= 1.0 {
                c
            } else {
                [a[0] + t * dx, a[1] + t * dy]
            }
        };
        let (p0, p1) = (at(t0), at(t1));
        let clipped = t0 > 0.0 || t1 < 1.0;
        let piece = match b {
            BoundaryPiece::Edge { edge, .. } if clipped => {
                BoundaryPiece::Partial { from: p0, to: p1, edge }
            }
            BoundaryPiece::Edge { edge, .. } => BoundaryPiece::Edge { from: p0, to: p1, edge },
            BoundaryPiece::Partial { edge, .. } => {
                BoundaryPiece::Partial { from: p0, to: p1, edge }
            }
            BoundaryPiece::Window { .. } => {
                let d = |x: Point| (x[0] - q[0]).hypot(x[1] - q[1]);
                let (near, farp) = if d(p0) <= d(p1) { (p0, p1) } else { (p1, p0) };
                BoundaryPiece::Window { from: p0, to: p1, reflex: near, far: farp }
            }
            BoundaryPiece::Wall { .. } => BoundaryPiece::Wall { from: p0, to: p1 },
            BoundaryPiece::Frontier { .. } => BoundaryPiece::Frontier { from: p0, to: p1 },
        };
        kept.push((piece, t0 > 0.0, t1 < 1.0));
    }
    let mut boundary = Vec::with_capacity(kept.len() * 2);
    let angle = |p: Point| (p[1] - q[1]).atan2(p[0] - q[0]);
    let tau = std::f64::consts::TAU;
    if kept.is_empty() {
        // Nothing within range: the whole disk is visible.
        let p = [q[0] + r, q[1]];
        boundary.push(RangePiece::Arc(Arc { from: p, to: p, center: q, radius: r, sweep: tau }));
        return RangeRegion { viewpoint: q, radius: r, boundary };
    }
    let m = kept.len();
    for i in 0..m {
        let (piece, _, exited) = kept[i];
        boundary.push(RangePiece::Straight(piece));
        let (next, entered, _) = kept[(i + 1) % m];
        if exited || entered {
            let from = piece.ends().1;
            let to = next.ends().0;
            let mut sweep = (angle(to) - angle(from)).rem_euclid(tau);
            if sweep == 0.0 && m == 1 {
                sweep = tau;
            }
            if sweep > 0.0 {
                boundary.push(RangePiece::Arc(Arc { from, to, center: q, radius: r, sweep }));
            }
        }
    }
    RangeRegion { viewpoint: q, radius: r, boundary }
}
