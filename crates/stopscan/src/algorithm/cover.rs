//! Which parts of a segment have a polygon on one side: the exact "is this window explored"
//! test of online exploration.
//!
//! A window of a visibility region is explored when the free space just beyond it is seen by
//! some other region. Point samples miss slivers, and points pushed a fixed distance past the
//! window land inside obstacles near its ends. Instead, [`side_cover`] classifies every point
//! `x` of the segment by the *limit*: `x` is covered by a polygon when `x + εn` lies in it for
//! all small enough `ε > 0`, with `n` the normal toward the chosen side. The segment is cut at
//! every point where the polygon's boundary meets it (side tests exact, cut parameters
//! rounded once), and each piece is classified once: by an exact point-in-polygon test at its
//! middle, or, where the piece runs along a polygon edge, by the side the polygon lies on.

use crate::algorithm::visibility::{BoundaryPiece, VisibilityRegion};
use crate::geometry::{segment_distance, signed_area_of};
use crate::kernel::{Point, RingSide, magnitude, orient_sign, ring_side, rounding};

/// Parameter intervals `[t0, t1] ⊂ [0, 1]`, sorted and disjoint.
pub type Intervals = Vec<[f64; 2]>;

/// Gaps between covered intervals shorter than this (in segment parameter) are closed: they
/// come from rounding, where the constructed vertices of different polygons (rays meeting
/// walls, each rounded once) meet the segment at what is one point in exact arithmetic. Far
/// from the origin the rounding grows with the coordinates, and [`tolerance`] raises the
/// threshold to [`rounding`] of them.
pub const GAP_TOLERANCE: f64 = 1e-9;

/// How far (in lengths of the segment) a probe steps off a segment when rounding put it on an
/// edge of the polygon: at least this, and more than [`rounding`] of the coordinates.
const SIDE_STEP: f64 = 1e-9;

/// The parts of the segment `a b` (as parameter intervals, appended to `out`) along which the
/// segment `p q` runs within `tol`: where `p q` lies in the band of half-width `tol` around
/// the line of `a b`, projected onto `a b`.
pub fn band_cover(a: Point, b: Point, p: Point, q: Point, tol: f64, out: &mut Intervals) {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len = dx.hypot(dy);
    if len.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
        || tol.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater)
    {
        return;
    }
    let (ux, uy) = (dx / len, dy / len);
    // Signed distances of p and q from the line, and their parameters along it.
    let side = |x: Point| ux * (x[1] - a[1]) - uy * (x[0] - a[0]);
    let along = |x: Point| (ux * (x[0] - a[0]) + uy * (x[1] - a[1])) / len;
    let (dp, dq) = (side(p), side(q));
    // The part of p q (s in [0, 1]) with |dp + s (dq − dp)| <= tol.
    let (mut s0, mut s1) = (0.0f64, 1.0f64);
    let dd = dq - dp;
    if dd.abs() < f64::MIN_POSITIVE {
        if dp.abs() > tol {
            return;
        }
    } else {
        let (e0, e1) = ((-tol - dp) / dd, (tol - dp) / dd);
        s0 = s0.max(e0.min(e1));
        s1 = s1.min(e0.max(e1));
        if s0 > s1 {
            return;
        }
    }
    let at = |s: f64| [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])];
    let (t0, t1) = (along(at(s0)), along(at(s1)));
    let (t0, t1) = (t0.min(t1).max(0.0), t0.max(t1).min(1.0));
    if t0 < t1 {
        out.push([t0, t1]);
    }
}

/// Appends to `out` the parameter intervals of segment `a → b` covered on its right side by
/// the closed polygon `poly` (any orientation, simple), in the limit sense of the module
/// documentation. `bounds` is the polygon's bounding box, for a quick rejection.
///
/// # Complexity
/// O(n log n) for a polygon of n vertices that meets the segment; O(1) when the boxes miss.
pub fn side_cover(a: Point, b: Point, poly: &[Point], bounds: [Point; 2], out: &mut Intervals) {
    let lo = [a[0].min(b[0]), a[1].min(b[1])];
    let hi = [a[0].max(b[0]), a[1].max(b[1])];
    if hi[0] < bounds[0][0] || lo[0] > bounds[1][0] || hi[1] < bounds[0][1] || lo[1] > bounds[1][1]
    {
        return;
    }
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    if len2 == 0.0 {
        return;
    }
    let param = |p: Point| ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2;
    let ccw = signed_area_of(poly) > 0.0;
    let n = poly.len();
    let mut cuts = vec![0.0, 1.0];
    // Pieces along polygon edges: (t0, t1, covered).
    let mut along: Vec<(f64, f64, bool)> = Vec::new();
    for i in 0..n {
        let (p, q) = (poly[i], poly[(i + 1) % n]);
        let (sp, sq) = (orient_sign(a, b, p), orient_sign(a, b, q));
        if sp == 0 && sq == 0 {
            let (t0, t1) = (param(p), param(q));
            let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(1.0));
            if lo < hi {
                cuts.extend([lo, hi]);
                // The polygon lies left of its edge when counter-clockwise. The right side of
                // a → b is covered when the polygon is on that side of the edge.
                let same_direction = (q[0] - p[0]) * dx + (q[1] - p[1]) * dy > 0.0;
                along.push((lo, hi, same_direction != ccw));
            }
            continue;
        }
        if sp == sq {
            continue;
        }
        // The edge meets the line of a → b; does it meet the segment?
        let (sa, sb) = (orient_sign(p, q, a), orient_sign(p, q, b));
        if sa == sb && sa != 0 {
            continue;
        }
        let t = if sp == 0 {
            param(p)
        } else if sq == 0 {
            param(q)
        } else {
            let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
            ((p[0] - a[0]) * ey - (p[1] - a[1]) * ex) / (dx * ey - dy * ex)
        };
        cuts.push(t.clamp(0.0, 1.0));
    }
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    let start = out.len();
    for w in cuts.windows(2) {
        let (t0, t1) = (w[0], w[1]);
        if t1 <= t0 {
            continue;
        }
        let tm = 0.5 * (t0 + t1);
        let covered = if let Some(&(_, _, c)) = along.iter().find(|s| s.0 <= tm && tm <= s.1) {
            c
        } else {
            let m = [a[0] + tm * dx, a[1] + tm * dy];
            match ring_side(poly, m) {
                RingSide::Inside => true,
                RingSide::Outside => false,
                // Rounding put the middle on an edge the segment crosses: step to the side, by
                // more than the rounding of the coordinates.
                RingSide::Boundary => {
                    let e = SIDE_STEP.max(4.0 * rounding(magnitude(&[a, b])) / len2.sqrt());
                    ring_side(poly, [m[0] + e * dy, m[1] - e * dx]) == RingSide::Inside
                }
            }
        };
        if covered {
            match out[start..].last_mut() {
                Some(last) if last[1] >= t0 => last[1] = t1,
                _ => out.push([t0, t1]),
            }
        }
    }
}

/// Sorts and merges intervals, closing gaps shorter than [`GAP_TOLERANCE`].
pub fn merge(iv: &mut Intervals) {
    iv.sort_by(|x, y| x[0].total_cmp(&y[0]));
    let mut out: Intervals = Vec::with_capacity(iv.len());
    for &[t0, t1] in iv.iter() {
        match out.last_mut() {
            Some(last) if t0 <= last[1] + GAP_TOLERANCE => last[1] = last[1].max(t1),
            _ => out.push([t0, t1]),
        }
    }
    *iv = out;
}

/// The first gap of merged intervals in `[0, 1]` longer than `tol`.
pub fn first_gap(iv: &[[f64; 2]], tol: f64) -> Option<[f64; 2]> {
    gaps(iv, tol).next()
}

/// The gaps of merged intervals in `[0, 1]` longer than `tol`.
pub fn gaps(iv: &[[f64; 2]], tol: f64) -> impl Iterator<Item = [f64; 2]> + '_ {
    let mut at = 0.0;
    iv.iter().chain(std::iter::once(&[1.0, 1.0])).filter_map(move |&[t0, t1]| {
        let gap = (t0 > at + tol).then_some([at, t0]);
        at = f64::max(at, t1);
        gap
    })
}

/// Parts of a frontier shorter than this many metres, for a range circle of radius R, times
/// R, are not worth a scan: range regions reach their strategies as polygons whose arcs are
/// chords with sagitta [`RANGE_CHORD_TOLERANCE`]·R, so where two circles cross, each chord
/// is left uncovered by the other's polygon over a length of a few sagittas. Those slivers
/// are sagitta-thin, so the area they leave is far below the 1e-6 coverage target.
pub const RANGE_GAP: f64 = 1e-3;

/// The sagitta of the chords that replace arcs, relative to the range.
pub const RANGE_CHORD_TOLERANCE: f64 = 1e-4;

/// The gap tolerance (in the piece's own parameter) for a frontier piece of a region seen
/// from `viewpoint`: [`GAP_TOLERANCE`] for windows, [`RANGE_GAP`]·R for range chords, and for
/// both at least the [`rounding`] of the coordinates involved over the piece's length.
pub fn tolerance(viewpoint: Point, piece: &BoundaryPiece) -> f64 {
    let (from, to) = piece.ends();
    let len = (to[0] - from[0]).hypot(to[1] - from[1]);
    if len <= 0.0 {
        return 1.0;
    }
    let floor = GAP_TOLERANCE.max(rounding(magnitude(&[viewpoint, from, to])) / len);
    match *piece {
        BoundaryPiece::Frontier { .. } => {
            let r = (from[0] - viewpoint[0]).hypot(from[1] - viewpoint[1]);
            (RANGE_GAP * r / len).max(floor)
        }
        _ => floor,
    }
}

/// The uncovered parts of the frontiers (windows and range chords) of `regions` — parts of
/// their far side that no other region covers — whose probe point
/// ([`open_window_points`]) satisfies `inside`, normally "lies in the interior of the free
/// space". Zero certifies that the union of the regions is the whole connected free space
/// (the paper's Lemma 2: a point not seen would be reached from the viewpoints only by
/// crossing a frontier of the union), independently of area arithmetic. A part whose probe
/// falls outside the free space is a sliver against a wall, thinner there than a millionth
/// of the window's length (a window that runs along a wall within rounding).
///
/// # Complexity
/// O(w · k · n) for w frontiers, k regions of n vertices, with a bounding-box rejection first.
pub fn open_windows(regions: &[VisibilityRegion], inside: impl Fn(Point) -> bool) -> usize {
    open_window_points(regions).into_iter().filter(|&p| inside(p)).count()
}

/// A point just beyond the middle of every uncovered part of every window of `regions` (a
/// millionth of the window's length past it, and more than the coordinates' [`rounding`]):
/// points no region sees, or on the domain's boundary where a window grazes it. Used to
/// refine witness sets.
pub fn open_window_points(regions: &[VisibilityRegion]) -> Vec<Point> {
    let mut out = Vec::new();
    for_each_window(regions, |a, b, tol, iv| {
        out.extend(gaps(iv, tol).map(|g| gap_probe(a, b, g)));
    });
    out
}

/// The probe of the uncovered part `gap` of the frontier `a b` (its region to the left): a
/// millionth of the frontier's length beyond its middle, and more than the coordinates'
/// [`rounding`].
fn gap_probe(a: Point, b: Point, [g0, g1]: [f64; 2]) -> Point {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let e = 1e-6_f64.max(4.0 * rounding(magnitude(&[a, b])) / dx.hypot(dy));
    let t = 0.5 * (g0 + g1);
    [a[0] + t * dx + e * dy, a[1] + t * dy - e * dx]
}

/// One frontier of a sequence of scans, and how its open parts shrank as the scans after it
/// were taken: what a replay highlights as "left open" at each step.
#[derive(Debug, Clone, PartialEq)]
pub struct FrontierHistory {
    /// The index of the region (scan) the frontier belongs to.
    pub scan: usize,
    /// Its ends, counter-clockwise along that region's boundary.
    pub from: Point,
    /// See `from`.
    pub to: Point,
    /// A window (an occluding edge), not a range chord.
    pub window: bool,
    /// `(step, open)`, by increasing step: once `step` scans have been taken (and until the
    /// next entry's step), the parts `open` of the frontier (parameter intervals along
    /// `from → to`) are what no scan taken so far covers, counted as [`open_windows`] counts
    /// them. The first entry's step is `scan + 1`; an empty `open` means closed.
    pub open: Vec<(usize, Intervals)>,
}

/// The history of every frontier of `regions` taken in order ([`FrontierHistory`]): at each
/// step `s`, the frontiers of the first `s` regions and their parts that none of the other
/// first `s` regions covers, whose probe satisfies `inside`. At the last step they are exactly
/// the parts [`open_windows`] counts.
///
/// # Complexity
/// As [`open_windows`], plus a merge per region that covers part of a frontier.
pub fn frontier_history(
    regions: &[VisibilityRegion],
    inside: impl Fn(Point) -> bool,
) -> Vec<FrontierHistory> {
    let boxes: Vec<[Point; 2]> = regions.iter().map(|r| bounds_of(&r.polygon)).collect();
    let mut out = Vec::new();
    let mut part = Vec::new();
    for (i, r) in regions.iter().enumerate() {
        for w in r.frontiers() {
            let (a, b) = w.ends();
            let tol = tolerance(r.viewpoint, w);
            let open_now = |iv: &Intervals| -> Intervals {
                gaps(iv, tol).filter(|&g| inside(gap_probe(a, b, g))).collect()
            };
            let mut iv = Vec::new();
            for (j, o) in regions.iter().enumerate().take(i) {
                side_cover(a, b, &o.polygon, boxes[j], &mut iv);
            }
            merge(&mut iv);
            let mut open = vec![(i + 1, open_now(&iv))];
            for (j, o) in regions.iter().enumerate().skip(i + 1) {
                part.clear();
                side_cover(a, b, &o.polygon, boxes[j], &mut part);
                if part.is_empty() {
                    continue;
                }
                iv.extend_from_slice(&part);
                merge(&mut iv);
                let now = open_now(&iv);
                if open.last().is_some_and(|(_, before)| *before != now) {
                    open.push((j + 1, now));
                }
            }
            let window = matches!(w, BoundaryPiece::Window { .. });
            out.push(FrontierHistory { scan: i, from: a, to: b, window, open });
        }
    }
    out
}

/// Calls `f(from, to, tolerance, covered)` for every frontier (window or range chord) of every
/// region, with the merged parts of its far side that the other regions cover.
fn for_each_window(regions: &[VisibilityRegion], mut f: impl FnMut(Point, Point, f64, &Intervals)) {
    let boxes: Vec<[Point; 2]> = regions.iter().map(|r| bounds_of(&r.polygon)).collect();
    let mut iv = Vec::new();
    for (i, r) in regions.iter().enumerate() {
        for w in r.frontiers() {
            let (a, b) = w.ends();
            iv.clear();
            for (j, o) in regions.iter().enumerate() {
                if j != i {
                    side_cover(a, b, &o.polygon, boxes[j], &mut iv);
                }
            }
            merge(&mut iv);
            f(a, b, tolerance(r.viewpoint, w), &iv);
        }
    }
}

/// The area of the free space of `domain` that no polygon of `seen` covers, counting only
/// what is really uncovered.
///
/// `domain ∖ ∪ seen` is computed by i_overlay, whose integer grid (31 bits over the extent)
/// leaves slivers along boundaries that in exact arithmetic coincide: on a complete run they
/// add up to about 1e-9 of the area. Each piece of the difference is therefore probed at the
/// deepest of a few points stepped in from the middles of its longest edges, tested exactly
/// against the domain and every polygon; only pieces whose probe lies in the free space and
/// outside every polygon are counted, and a piece with no point deeper than 1e-7 of the
/// domain's extent (a sliver) is not. A sliver can also hang off a real gap, joined to it in
/// one piece (the overlay's ring runs out along a scan's edge and back): the deepest point
/// lies in the gap, not in the sliver, where a probe would be "seen" within the rounding and
/// drop the gap. A complete run measures 0; a real gap measures its area, to the overlay's
/// precision.
pub fn uncovered_area(domain: &crate::geometry::Domain, seen: &[Vec<Point>]) -> f64 {
    use crate::algorithm::region::Region;
    let union = Region::union_all(seen);
    uncovered_area_of(domain, &Region::of_domain(domain), seen, &union)
}

/// The area of `part` (a region of the free space of `domain`) that no polygon of `seen`
/// (whose union is `union`) covers, counting only what is really uncovered, as
/// [`uncovered_area`] does for the whole free space.
pub fn uncovered_area_of(
    domain: &crate::geometry::Domain,
    part: &crate::algorithm::region::Region,
    seen: &[Vec<Point>],
    union: &crate::algorithm::region::Region,
) -> f64 {
    use crate::geometry::Location;
    let diff = part.difference(union);
    let boxes: Vec<[Point; 2]> = seen.iter().map(|p| bounds_of(p)).collect();
    let covered = |p: Point| {
        seen.iter().zip(&boxes).any(|(poly, b)| {
            p[0] >= b[0][0]
                && p[0] <= b[1][0]
                && p[1] >= b[0][1]
                && p[1] <= b[1][1]
                && ring_side(poly, p) != RingSide::Outside
        })
    };
    let [lo, hi] = bounds_of(&domain.rings()[0]);
    let min_depth = MIN_PROBE_DEPTH * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let mut total = 0.0;
    for shape in &diff.shapes {
        let Some(outer) = shape.first().filter(|o| o.len() >= 3) else { continue };
        let area = signed_area_of(outer).abs()
            - shape[1..].iter().map(|h| signed_area_of(h).abs()).sum::<f64>();
        if area <= 0.0 {
            continue;
        }
        // A piece too thin to hold a probe point is not counted.
        if let Some(p) = probe(shape).filter(|&(_, depth)| depth > min_depth).map(|(p, _)| p)
            && domain.locate(p) == Location::Interior
            && !covered(p)
        {
            total += area;
        }
    }
    total
}

/// The fractions of an edge's length by which [`probe`] steps inward from its middle.
const PROBE_STEPS: [f64; 8] = [0.25, 0.1, 0.03, 1e-2, 1e-3, 1e-6, 1e-9, 1e-12];

/// How many of a shape's longest edges (of all its rings) [`probe`] steps in from.
const PROBE_EDGES: usize = 64;

/// A piece of the difference counts only when a probe point lies deeper inside it than this
/// share of the domain's extent (its bounding box's diagonal): 1e-7, some 200 times the
/// overlay's grid step (2⁻³¹ of the extent).
const MIN_PROBE_DEPTH: f64 = 1e-7;

/// The deepest point strictly inside a shape (outer ring, then holes) among the middles of its
/// [`PROBE_EDGES`] longest edges stepped inward by each of [`PROBE_STEPS`] of the edge's
/// length, with its distance from the shape's boundary; `None` if none lies inside.
fn probe(shape: &[Vec<Point>]) -> Option<(Point, f64)> {
    let inside = |p: Point| {
        ring_side(&shape[0], p) == RingSide::Inside
            && shape[1..].iter().all(|h| ring_side(h, p) == RingSide::Outside)
    };
    let depth = |p: Point| {
        shape
            .iter()
            .flat_map(|r| {
                (0..r.len()).map(move |i| segment_distance(p, r[i], r[(i + 1) % r.len()]))
            })
            .fold(f64::INFINITY, f64::min)
    };
    // Every edge with the ring's inward side: left of a counter-clockwise outer ring, right of
    // a clockwise one, and the other way round for holes.
    let mut edges: Vec<(f64, Point, Point, bool)> = shape
        .iter()
        .enumerate()
        .flat_map(|(k, r)| {
            let left = (signed_area_of(r) > 0.0) == (k == 0);
            (0..r.len()).map(move |i| {
                let (a, b) = (r[i], r[(i + 1) % r.len()]);
                ((b[0] - a[0]).hypot(b[1] - a[1]), a, b, left)
            })
        })
        .collect();
    edges.sort_by(|x, y| y.0.total_cmp(&x.0));
    edges.truncate(PROBE_EDGES);
    let mut best: Option<(Point, f64)> = None;
    for (_, a, b, left) in edges {
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        for e in PROBE_STEPS {
            let s = if left { e } else { -e };
            let p = [m[0] - s * dy, m[1] + s * dx];
            if inside(p) {
                let d = depth(p);
                if best.is_none_or(|(_, b)| d > b) {
                    best = Some((p, d));
                }
                // A deeper step from this edge was inside: the shallower ones are not deeper.
                break;
            }
        }
    }
    best
}

/// The bounding box of a point set, `[min, max]`.
pub fn bounds_of(points: &[Point]) -> [Point; 2] {
    let mut b = [[f64::MAX; 2], [f64::MIN; 2]];
    for p in points {
        b = [[b[0][0].min(p[0]), b[0][1].min(p[1])], [b[1][0].max(p[0]), b[1][1].max(p[1])]];
    }
    b
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cover(a: Point, b: Point, poly: &[Point]) -> Intervals {
        let mut out = Vec::new();
        side_cover(a, b, poly, bounds_of(poly), &mut out);
        merge(&mut out);
        out
    }

    #[test]
    fn crossing_square_is_covered_in_its_middle() {
        let sq = [[1.0, -1.0], [3.0, -1.0], [3.0, 1.0], [1.0, 1.0]];
        assert_eq!(cover([0.0, 0.0], [4.0, 0.0], &sq), vec![[0.25, 0.75]]);
    }

    #[test]
    fn an_edge_along_the_segment_covers_only_its_own_side() {
        // The square lies below y = 0; the right side of (0,0) → (4,0) is below.
        let below = [[1.0, -1.0], [3.0, -1.0], [3.0, 0.0], [1.0, 0.0]];
        assert_eq!(cover([0.0, 0.0], [4.0, 0.0], &below), vec![[0.25, 0.75]]);
        let above = [[1.0, 0.0], [3.0, 0.0], [3.0, 1.0], [1.0, 1.0]];
        assert!(cover([0.0, 0.0], [4.0, 0.0], &above).is_empty());
        // The same polygon clockwise gives the same answer.
        let mut cw = below;
        cw.reverse();
        assert_eq!(cover([0.0, 0.0], [4.0, 0.0], &cw), vec![[0.25, 0.75]]);
    }

    #[test]
    fn touching_at_a_vertex_covers_nothing() {
        let tri = [[2.0, 0.0], [3.0, -1.0], [1.0, -1.0]];
        assert!(cover([0.0, 0.0], [4.0, 0.0], &tri).is_empty());
    }

    #[test]
    fn uncovered_area_counts_real_gaps_only() {
        let d = crate::geometry::Domain::new(
            vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]],
            vec![vec![[1.0, 1.0], [1.0, 1.5], [1.5, 1.5], [1.5, 1.0]]],
        )
        .unwrap();
        let left = vec![[0.0, 0.0], [2.0, 0.0], [2.0, 4.0], [0.0, 4.0]];
        let right = vec![[2.0, 0.0], [4.0, 0.0], [4.0, 4.0], [2.0, 4.0]];
        // Half seen: the other half is missing (the hole is not free space).
        let u = uncovered_area(&d, std::slice::from_ref(&left));
        assert!((u - 8.0).abs() < 1e-8, "{u}");
        // Both halves, meeting along x = 2: nothing, exactly.
        assert_eq!(uncovered_area(&d, &[left.clone(), right]), 0.0);
        // A thin real gap between two parts is counted.
        let far = vec![[2.001, 0.0], [4.0, 0.0], [4.0, 4.0], [2.001, 4.0]];
        let u = uncovered_area(&d, &[left, far]);
        assert!((u - 0.004).abs() < 1e-8, "{u}");
    }

    #[test]
    fn gaps_are_found_and_tiny_ones_closed() {
        let mut tiny = vec![[0.0, 0.5], [0.5 + 1e-11, 1.0]];
        merge(&mut tiny);
        assert_eq!(first_gap(&tiny, GAP_TOLERANCE), None);
        assert_eq!(first_gap(&[[0.0, 0.4], [0.6, 1.0]], GAP_TOLERANCE), Some([0.4, 0.6]));
        assert_eq!(first_gap(&[[0.0, 0.4], [0.6, 1.0]], 0.3), None);
        assert_eq!(first_gap(&[], GAP_TOLERANCE), Some([0.0, 1.0]));
        let mut iv = vec![[0.6, 1.0], [0.0, 0.3], [0.2, 0.61]];
        merge(&mut iv);
        assert_eq!(iv, vec![[0.0, 1.0]]);
    }
}
#[cfg(test)]
mod brute_force {
    use super::*;
    use rand::{RngExt, SeedableRng};
    #[test]
    fn side_cover_matches_point_tests_on_random_polygons() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        for it in 0..2000 {
            let n = rng.random_range(3..12);
            let mut poly: Vec<Point> = (0..n)
                .map(|k| {
                    let a = f64::from(k) / f64::from(n) * std::f64::consts::TAU;
                    let r = rng.random_range(1.0..5.0);
                    [r * a.cos(), r * a.sin()]
                })
                .collect();
            if it % 2 == 0 {
                poly.reverse();
            }
            let a = [rng.random_range(-6.0..6.0), rng.random_range(-6.0..6.0)];
            let b = [rng.random_range(-6.0..6.0), rng.random_range(-6.0..6.0)];
            let mut iv = Vec::new();
            side_cover(a, b, &poly, bounds_of(&poly), &mut iv);
            for k in 0..200 {
                let t = (f64::from(k) + 0.5) / 200.0;
                let m = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                let inside = ring_side(&poly, m) == RingSide::Inside;
                let got = iv.iter().any(|x| x[0] <= t && t <= x[1]);
                assert_eq!(inside, got, "it {it} t {t} poly {poly:?} a {a:?} b {b:?} iv {iv:?}");
            }
        }
    }
}
