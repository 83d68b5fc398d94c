//! Lower bounds that hold for every exploration of a domain, by any strategy, online or
//! offline, with viewpoints anywhere: what makes `time / time_lower` a certified upper bound
//! on a run's competitive ratio.
//!
//! **Witnesses.** Every point of the free space must be seen, so every point `w` forces a
//! viewpoint in its visibility region `V(w)` (visibility is symmetric), and a viewpoint sees
//! `w` only from there. The candidate witnesses are the centroids of the free space's
//! triangles and points just inside every convex corner (whose regions are small); those the
//! start sees are covered by the first scan and set aside.
//!
//! - **Packing**: witnesses whose regions are pairwise disjoint need one viewpoint each, so
//!   `views ≥ 1 + |packing|` (the start's scan sees none of them). Chosen greedily, smallest
//!   regions first.
//! - **Fractional packing** (the LP relaxation over a finite witness set, made valid):
//!   weights `y_w ≥ 0` with `Σ_{w : g ∈ V(w)} y_w ≤ 1` at *every* point `g` of the plane bound
//!   the views by `Σ y_w`. The LP is solved with the constraint at finitely many points, then
//!   its solution is checked at every vertex of the arrangement of the regions it uses (the
//!   regions are closed, so the weighted depth is largest at some arrangement vertex) and
//!   divided by the largest depth found, which makes it valid whatever points the LP saw.
//! - **Area** (with a range limit R): one scan sees at most `πR²`.
//! - **Travel**: the robot must reach `V(w)` for every witness `w` the start does not see.
//!   The geodesic distance to `V(w)` is at least `min_u geo(start, u) + |u V(w)|` over the
//!   start and the reflex vertices `u` (a shortest path to `V(w)` ends with a straight segment
//!   from its last bend), so the largest of these over the witnesses bounds the distance.
//!
//! Then `time ≥ scan_time·views + move_time·(views − 1) + travel/speed`: every scan but the
//! first is at a new place (the simulator refuses a scan where one stood), reached by a move.
//!
//! Computed regions are exact up to rounding (and, with a range, up to the chords replacing
//! arcs), so every test is made safe by a tolerance in the direction that can only weaken
//! the bound: regions count as apart only when separated by more than it, a region counts as
//! containing a point within it, distances are shortened by it.

use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::algorithm::cover::{RANGE_CHORD_TOLERANCE, bounds_of};
use crate::algorithm::region::Region;
use crate::algorithm::shortest_path::PathPlanner;
use crate::algorithm::visibility::{Visibility, VisibilityError, range::clip};
use crate::geometry::Location;
use crate::kernel::{Point, RingSide, magnitude, orient_sign, ring_side, rounding};
use crate::protocol::CostModel;

/// The lower bounds of one instance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LowerBounds {
    /// Views (scans) any complete exploration needs: the largest of the bounds below.
    pub views: usize,
    /// Which bound gave `views`.
    pub views_rule: String,
    /// Witnesses with pairwise disjoint regions that the start does not see.
    pub packing: usize,
    /// The valid fractional packing value over the witnesses the start does not see (views
    /// ≥ 1 + ⌈lp⌉), when computed.
    pub lp: Option<f64>,
    /// `⌈area / πR²⌉` with a range limit, else 1.
    pub area: usize,
    /// Metres any exploration must drive.
    pub travel: f64,
    /// The witness whose region is farthest from the start, if any.
    pub travel_witness: Option<Point>,
    /// Candidate witnesses examined.
    pub witnesses: usize,
    /// The packing's witnesses: no viewpoint sees two of them, and the start sees none.
    pub packing_points: Vec<Point>,
    /// The fractional packing behind `lp`, scaled to be valid: at every point of the plane,
    /// the weights of the witnesses seen from there sum to at most 1.
    pub lp_weights: Vec<WeightedWitness>,
    /// Whether every stage finished within the time budget (the bounds are valid either way,
    /// only weaker when cut short).
    pub complete: bool,
}

/// A witness point and its weight in a fractional packing. Run records store it as the
/// pair `[[x, y], weight]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(from = "(Point, f64)", into = "(Point, f64)")]
pub struct WeightedWitness {
    /// The witness.
    pub at: Point,
    /// Its weight, in [0, 1].
    pub weight: f64,
}

impl From<(Point, f64)> for WeightedWitness {
    fn from((at, weight): (Point, f64)) -> Self {
        Self { at, weight }
    }
}

impl From<WeightedWitness> for (Point, f64) {
    fn from(w: WeightedWitness) -> Self {
        (w.at, w.weight)
    }
}

impl LowerBounds {
    /// The time any complete exploration takes under `cost`:
    /// `scan_time·views + move_time·(views − 1) + travel/speed`.
    pub fn time(&self, cost: &CostModel) -> f64 {
        let v = self.views as f64;
        cost.scan_time * v + cost.move_time * (v - 1.0).max(0.0) + self.travel / cost.speed
    }
}

/// A candidate witness and its region (closed; within `tol` of the exact one).
struct Witness {
    at: Point,
    poly: Vec<Point>,
    bbox: [Point; 2],
    area: f64,
}

/// Everything the bounds share: the witnesses the start does not see, the tolerance.
struct Setup {
    witnesses: Vec<Witness>,
    examined: usize,
    tol: f64,
    complete: bool,
}

/// The lower bounds for exploring `vis`'s domain from `start` with an optional range limit,
/// stopping each stage when `budget` runs out (the bounds stay valid, only weaker).
///
/// # Errors
/// [`VisibilityError`] if the start is outside the free space.
pub fn lower_bounds(
    vis: &Visibility,
    start: Point,
    range: Option<f64>,
    budget: &Budget,
) -> Result<LowerBounds, VisibilityError> {
    lower_bounds_within(vis, start, range, budget, None)
}

/// [`lower_bounds`] for any exploration that sees at least `within` (a part of the free
/// space: what a run with a footprint or a window rule set out to see): only witnesses in
/// `within` count, and `area / πR²` uses its area. Viewpoints may still lie anywhere, so the
/// bounds hold for any robot.
///
/// # Errors
/// [`VisibilityError`] if the start is outside the free space.
pub fn lower_bounds_within(
    vis: &Visibility,
    start: Point,
    range: Option<f64>,
    budget: &Budget,
    within: Option<&Region>,
) -> Result<LowerBounds, VisibilityError> {
    let d = vis.domain();
    let target_area = within.map_or_else(|| d.area(), Region::area);
    let area = match range {
        Some(r) if r > 0.0 && r.is_finite() => {
            ((target_area / (std::f64::consts::PI * r * r)).ceil() as usize).max(1)
        }
        _ => 1,
    };
    vis.query(start)?;
    let setup = witnesses(vis, start, range, budget, within)?;
    let packing = packing(&setup, budget);
    // Travel before the fractional packing: it is cheap and the time bound needs it; the
    // packing LP then has what is left of the budget.
    let (travel, travel_witness, travel_done) = travel(vis, start, &setup, budget);
    let beat = packing.len().max(area.saturating_sub(1));
    let fractional = fractional_packing(&setup, &packing, beat, budget);
    let lp = fractional.as_ref().map(|f| f.iter().map(|w| w.weight).sum::<f64>());
    let mut views = area;
    let mut views_rule = match range {
        Some(_) => format!("area / πR² = {area}"),
        None => "the start's scan".to_string(),
    };
    if 1 + packing.len() > views {
        views = 1 + packing.len();
        views_rule =
            format!("1 + {} witnesses with pairwise disjoint visibility regions", packing.len());
    }
    if let Some(v) = lp {
        let by_lp = 1 + (v - LP_TOLERANCE).ceil().max(0.0) as usize;
        if by_lp > views {
            views = by_lp;
            views_rule = format!("1 + ⌈{v:.3}⌉ (fractional packing of witnesses, LP)");
        }
    }
    Ok(LowerBounds {
        views,
        views_rule,
        packing: packing.len(),
        packing_points: packing.iter().map(|&k| setup.witnesses[k].at).collect(),
        lp_weights: fractional.unwrap_or_default(),
        lp,
        area,
        travel,
        travel_witness,
        witnesses: setup.examined,
        complete: setup.complete && travel_done && !budget.exhausted(),
    })
}

/// How long the lower bounds may work. A deadline cuts them where the machine's speed and
/// load put it; a number of steps cuts them at the same place on every machine (a step is
/// one check of the budget, made every few dozen witnesses, pairs or cells; the packing LP,
/// which has no step count, runs to its end). Either way the bounds stay valid, only weaker.
#[derive(Debug, Clone, Default)]
pub struct Budget {
    deadline: Option<Instant>,
    steps: Option<u64>,
    spent: std::cell::Cell<u64>,
}

impl Budget {
    /// Until `deadline` (none: no time limit).
    #[must_use]
    pub fn until(deadline: Option<Instant>) -> Self {
        Self { deadline, ..Self::default() }
    }

    /// `steps` steps, whatever the time.
    #[must_use]
    pub fn steps(steps: u64) -> Self {
        Self { steps: Some(steps), ..Self::default() }
    }

    /// [`Budget::steps`] when `steps` is given, else `seconds` from now.
    #[must_use]
    pub fn of(seconds: f64, steps: Option<u64>) -> Self {
        steps.map_or_else(|| Self::until(super::deadline_in(seconds)), Self::steps)
    }

    /// The steps taken so far.
    #[must_use]
    pub fn spent(&self) -> u64 {
        self.spent.get()
    }

    /// Takes one step; whether the budget has run out.
    fn expired(&self) -> bool {
        self.spent.set(self.spent.get() + 1);
        self.exhausted()
    }

    /// Whether the budget has run out (without taking a step).
    fn exhausted(&self) -> bool {
        self.steps.is_some_and(|n| self.spent.get() > n)
            || self.deadline.is_some_and(|t| Instant::now() >= t)
    }
}

/// Candidate witness points: triangle centroids and points just inside convex corners.
fn witness_points(vis: &Visibility) -> Vec<Point> {
    let d = vis.domain();
    let m = vis.mesh();
    let pts = m.points();
    let mut out: Vec<Point> = m
        .tri
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| pts[i as usize]);
            [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0]
        })
        .collect();
    for ring in d.rings() {
        let n = ring.len();
        for i in 0..n {
            let (p, v, q) = (ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]);
            // Free space lies left of every ring: a left turn is a convex corner.
            if orient_sign(p, v, q) <= 0 {
                continue;
            }
            let unit = |a: Point| {
                let (x, y) = (a[0] - v[0], a[1] - v[1]);
                let l = x.hypot(y);
                [x / l, y / l]
            };
            let (u, w) = (unit(p), unit(q));
            let (bx, by) = (u[0] + w[0], u[1] + w[1]);
            let bl = bx.hypot(by);
            let step =
                1e-3 * (p[0] - v[0]).hypot(p[1] - v[1]).min((q[0] - v[0]).hypot(q[1] - v[1]));
            if bl > 0.0 {
                let c = [v[0] + step * bx / bl, v[1] + step * by / bl];
                if d.locate(c) == Location::Interior {
                    out.push(c);
                }
            }
        }
    }
    out
}

/// The witnesses the start does not see (by more than the tolerance), with their regions.
fn witnesses(
    vis: &Visibility,
    start: Point,
    range: Option<f64>,
    budget: &Budget,
    within: Option<&Region>,
) -> Result<Setup, VisibilityError> {
    let d = vis.domain();
    let [lo, hi] = d.bounds();
    let extent = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
    let sagitta = range.map_or(0.0, |r| r * RANGE_CHORD_TOLERANCE);
    let tol = NEAR_REL * extent + 16.0 * rounding(magnitude(&[lo, hi])) + 2.0 * sagitta;
    let mut points = witness_points(vis);
    if let Some(r) = within {
        points.retain(|&p| r.contains(p));
    }
    let mut out = Vec::new();
    let mut complete = true;
    let mut examined = 0;
    for (k, &w) in points.iter().enumerate() {
        if k % 64 == 0 && budget.expired() {
            complete = false;
            break;
        }
        examined += 1;
        let full = vis.query(w)?;
        let poly = match range {
            Some(r) => clip(&full, r).to_polygon(sagitta),
            None => full.polygon,
        };
        if poly.len() < 3 || near(&poly, bounds_of(&poly), start, tol) {
            continue;
        }
        let area = crate::algorithm::visibility::polygon_area_of(w, &poly).abs();
        out.push(Witness { at: w, bbox: bounds_of(&poly), poly, area });
    }
    out.sort_by(|a, b| a.area.total_cmp(&b.area).then(a.at[0].total_cmp(&b.at[0])));
    Ok(Setup { witnesses: out, examined, tol, complete })
}

/// Whether `p` lies in the closed polygon or within `tol` of it.
fn near(poly: &[Point], bbox: [Point; 2], p: Point, tol: f64) -> bool {
    if p[0] < bbox[0][0] - tol
        || p[0] > bbox[1][0] + tol
        || p[1] < bbox[0][1] - tol
        || p[1] > bbox[1][1] + tol
    {
        return false;
    }
    ring_side(poly, p) != RingSide::Outside || within(poly, p, tol)
}

/// Whether `p` lies within `tol` of the polygon's boundary (edges whose box, grown by `tol`,
/// misses `p` are skipped without measuring).
fn within(poly: &[Point], p: Point, tol: f64) -> bool {
    let n = poly.len();
    (0..n).any(|i| {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        p[0] >= a[0].min(b[0]) - tol
            && p[0] <= a[0].max(b[0]) + tol
            && p[1] >= a[1].min(b[1]) - tol
            && p[1] <= a[1].max(b[1]) + tol
            && crate::geometry::segment_distance(p, a, b) <= tol
    })
}

fn distance_to_boundary(poly: &[Point], p: Point) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| crate::geometry::segment_distance(p, poly[i], poly[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

/// The distance from `p` to the closed polygon (0 inside).
fn distance_to(poly: &[Point], p: Point) -> f64 {
    if ring_side(poly, p) == RingSide::Outside { distance_to_boundary(poly, p) } else { 0.0 }
}

fn boxes_overlap(a: [Point; 2], b: [Point; 2], tol: f64) -> bool {
    a[0][0] <= b[1][0] + tol
        && b[0][0] <= a[1][0] + tol
        && a[0][1] <= b[1][1] + tol
        && b[0][1] <= a[1][1] + tol
}

/// Whether two closed regions are separated by more than `tol` (so that the exact regions
/// are disjoint).
fn apart(a: &Witness, b: &Witness, tol: f64) -> bool {
    if !boxes_overlap(a.bbox, b.bbox, tol) {
        return true;
    }
    if a.poly.iter().any(|&p| near(&b.poly, b.bbox, p, tol))
        || b.poly.iter().any(|&p| near(&a.poly, a.bbox, p, tol))
    {
        return false;
    }
    // No vertex of either lies in or near the other: they meet only if two edges cross or
    // come close.
    let (na, nb) = (a.poly.len(), b.poly.len());
    for i in 0..na {
        let (p, q) = (a.poly[i], a.poly[(i + 1) % na]);
        let eb = bounds_of(&[p, q]);
        if !boxes_overlap(eb, b.bbox, tol) {
            continue;
        }
        for j in 0..nb {
            let (r, s) = (b.poly[j], b.poly[(j + 1) % nb]);
            if boxes_overlap(eb, bounds_of(&[r, s]), tol)
                && (crate::kernel::segments_intersect(p, q, r, s)
                    || crate::geometry::segment_distance(r, p, q) <= tol
                    || crate::geometry::segment_distance(s, p, q) <= tol
                    || crate::geometry::segment_distance(p, r, s) <= tol
                    || crate::geometry::segment_distance(q, r, s) <= tol)
            {
                return false;
            }
        }
    }
    true
}

/// Witnesses (indices into the setup) with pairwise disjoint regions: greedy, smallest
/// regions first.
fn packing(setup: &Setup, budget: &Budget) -> Vec<usize> {
    let mut chosen: Vec<usize> = Vec::new();
    for (k, w) in setup.witnesses.iter().enumerate() {
        if k % 16 == 0 && budget.expired() {
            break;
        }
        if chosen.iter().all(|&c| apart(&setup.witnesses[c], w, setup.tol)) {
            chosen.push(k);
        }
    }
    chosen
}

/// The most witnesses the fractional packing weighs (the smallest regions, and the packing).
const LP_WITNESSES: usize = 160;
/// Rounds of adding the most violated arrangement vertices as constraints.
const LP_ROUNDS: usize = 8;
/// Constraints added per round.
const LP_CUTS: usize = 400;
/// The precision of the packing LP's solution: a weight below it is zero, a depth within it of
/// 1 is 1, and a value within it above a whole number rounds up to that number.
const LP_TOLERANCE: f64 = 1e-9;
/// A point within this times the domain's diagonal of a witness's region (plus the
/// coordinates' rounding and the chords of a ranged scan) counts as in it: the regions are
/// constructed in floating point, and the bounds must hold for the exact ones.
const NEAR_REL: f64 = 1e-9;

/// The best valid fractional packing found (see the module documentation): witnesses and
/// their weights, already divided by the largest depth; `None` when none was found within the
/// budget.
///
/// It can only raise the bound on views when its value exceeds `beat` (the packing's size):
/// the relaxation's value only falls as constraints are added, so the rounds stop as soon as
/// its ceiling cannot beat `beat`, or cannot beat the valid value already found.
fn fractional_packing(
    setup: &Setup,
    packing: &[usize],
    beat: usize,
    budget: &Budget,
) -> Option<Vec<WeightedWitness>> {
    if setup.witnesses.is_empty() || budget.expired() {
        return None;
    }
    let mut ids: Vec<usize> = (0..setup.witnesses.len().min(LP_WITNESSES)).collect();
    ids.extend(packing.iter().copied().filter(|&k| k >= LP_WITNESSES));
    let ws: Vec<&Witness> = ids.iter().map(|&k| &setup.witnesses[k]).collect();
    let tol = setup.tol;
    let row = |g: Point| -> Vec<usize> {
        (0..ws.len()).filter(|&i| near(&ws[i].poly, ws[i].bbox, g, tol)).collect()
    };
    // Start with the constraint at every witness and every vertex of their regions.
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut seen_rows = std::collections::HashSet::new();
    let mut add = |r: Vec<usize>, rows: &mut Vec<Vec<usize>>| {
        if r.len() > 1 && seen_rows.insert(r.clone()) {
            rows.push(r);
        }
    };
    for w in &ws {
        add(row(w.at), &mut rows);
        for &p in &w.poly {
            add(row(p), &mut rows);
        }
    }
    let mut best: Option<(f64, Vec<WeightedWitness>)> = None;
    for _round in 0..LP_ROUNDS {
        if budget.expired() {
            break;
        }
        let y = solve_packing_lp(ws.len(), &rows, budget)?;
        let support: Vec<usize> = (0..ws.len()).filter(|&i| y[i] > LP_TOLERANCE).collect();
        let total: f64 = support.iter().map(|&i| y[i]).sum();
        let ceiling = |v: f64| (v - LP_TOLERANCE).ceil().max(0.0) as usize;
        let found = best.as_ref().map_or(0, |b| ceiling(b.0));
        if ceiling(total) <= beat.max(found) {
            break;
        }
        let (depth, worst) = arrangement_depths(&ws, &support, &y, tol, budget)?;
        let scale = depth.max(1.0);
        let value = total / scale;
        if best.as_ref().is_none_or(|b| value > b.0) {
            let weights = support
                .iter()
                .map(|&i| WeightedWitness { at: ws[i].at, weight: y[i] / scale })
                .collect();
            best = Some((value, weights));
        }
        if depth <= 1.0 + LP_TOLERANCE {
            break;
        }
        let before = rows.len();
        for g in worst.into_iter().take(LP_CUTS) {
            add(row(g), &mut rows);
        }
        if rows.len() == before {
            break;
        }
    }
    best.map(|b| b.1)
}

/// Maximise `Σ y` subject to `Σ_{i ∈ row} y_i ≤ 1` for every row, `0 ≤ y ≤ 1`.
fn solve_packing_lp(n: usize, rows: &[Vec<usize>], budget: &Budget) -> Option<Vec<f64>> {
    use microlp::{ComparisonOp, OptimizationDirection, Problem};
    let mut p = Problem::new(OptimizationDirection::Maximize);
    let y: Vec<_> = (0..n).map(|_| p.add_var(1.0, (0.0, 1.0))).collect();
    for r in rows {
        p.add_constraint(r.iter().map(|&i| (y[i], 1.0)).collect::<Vec<_>>(), ComparisonOp::Le, 1.0);
    }
    if let Some(t) = budget.deadline {
        p.set_time_limit(t.saturating_duration_since(Instant::now()));
    }
    let sol = p.solve().ok()?.into_solution().ok()?;
    Some(y.iter().map(|&v| sol.var_value(v).clamp(0.0, 1.0)).collect())
}

/// The largest weighted depth `Σ_{i : g near V_i} y_i` over every vertex of the arrangement of
/// the support's regions (their vertices and the crossings of their edges), and the vertices
/// deeper than 1, deepest first. `None` when the budget ran out (no valid depth then).
fn arrangement_depths(
    ws: &[&Witness],
    support: &[usize],
    y: &[f64],
    tol: f64,
    budget: &Budget,
) -> Option<(f64, Vec<Point>)> {
    let mut vertices: Vec<Point> =
        support.iter().flat_map(|&i| ws[i].poly.iter().copied()).collect();
    // Edge crossings, found through a uniform grid over the support's edges.
    let edges: Vec<(Point, Point)> = support
        .iter()
        .flat_map(|&i| {
            let p = &ws[i].poly;
            (0..p.len()).map(move |k| (p[k], p[(k + 1) % p.len()]))
        })
        .collect();
    let [lo, hi] = bounds_of(&vertices);
    let cells = (edges.len() as f64).sqrt().ceil().max(1.0);
    let (cw, ch) = (
        ((hi[0] - lo[0]) / cells).max(f64::MIN_POSITIVE),
        ((hi[1] - lo[1]) / cells).max(f64::MIN_POSITIVE),
    );
    let side = cells as usize;
    let cell = |v: f64, l: f64, w: f64| (((v - l) / w).floor().max(0.0) as usize).min(side - 1);
    let mut grid: Vec<Vec<usize>> = vec![Vec::new(); side * side];
    for (k, &(a, b)) in edges.iter().enumerate() {
        let (x0, x1) = (cell(a[0].min(b[0]), lo[0], cw), cell(a[0].max(b[0]), lo[0], cw));
        let (y0, y1) = (cell(a[1].min(b[1]), lo[1], ch), cell(a[1].max(b[1]), lo[1], ch));
        for gx in x0..=x1 {
            for gy in y0..=y1 {
                grid[gy * side + gx].push(k);
            }
        }
    }
    for (c, list) in grid.iter().enumerate() {
        if c % 256 == 0 && budget.expired() {
            return None;
        }
        for (x, &i) in list.iter().enumerate() {
            for &j in &list[x + 1..] {
                let ((a, b), (p, q)) = (edges[i], edges[j]);
                if !crate::kernel::segments_intersect(a, b, p, q) {
                    continue;
                }
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
                let den = dx * ey - dy * ex;
                if den != 0.0 {
                    let t = (((p[0] - a[0]) * ey - (p[1] - a[1]) * ex) / den).clamp(0.0, 1.0);
                    vertices.push([a[0] + t * dx, a[1] + t * dy]);
                }
            }
        }
    }
    // The weights of the boxes around a vertex bound its depth; visiting the vertices by that
    // bound, the deepest is found early and the rest, which cannot matter (no deeper than it,
    // and not above 1), are skipped.
    let mut order: Vec<(f64, Point)> = vertices
        .iter()
        .map(|&g| {
            let b =
                support.iter().filter(|&&i| boxes_overlap(ws[i].bbox, [g, g], tol)).map(|&i| y[i]);
            (b.sum(), g)
        })
        .collect();
    order.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut deep: Vec<(f64, Point)> = Vec::new();
    let mut max = 0.0_f64;
    for (k, &(bound, g)) in order.iter().enumerate() {
        if k % 1024 == 0 && budget.expired() {
            return None;
        }
        if bound <= max && bound <= 1.0 + LP_TOLERANCE {
            break;
        }
        let depth: f64 =
            support.iter().filter(|&&i| near(&ws[i].poly, ws[i].bbox, g, tol)).map(|&i| y[i]).sum();
        max = max.max(depth);
        if depth > 1.0 + LP_TOLERANCE {
            deep.push((depth, g));
        }
    }
    deep.sort_by(|a, b| b.0.total_cmp(&a.0));
    Some((max, deep.into_iter().map(|d| d.1).collect()))
}

/// The travel bound: the largest lower bound on the distance from the start to a witness's
/// region, and whether every witness was measured within the budget.
fn travel(
    vis: &Visibility,
    start: Point,
    setup: &Setup,
    budget: &Budget,
) -> (f64, Option<Point>, bool) {
    if setup.witnesses.is_empty() {
        return (0.0, None, true);
    }
    // Geodesic distances from the start to the reflex vertices (the start itself first).
    let mut hubs = PathPlanner::new(vis).distances_from(start);
    hubs.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut best = (0.0_f64, None);
    for (k, w) in setup.witnesses.iter().enumerate() {
        if k % 32 == 0 && budget.expired() {
            return (best.0, best.1, false);
        }
        let mut d = f64::INFINITY;
        for &(u, g) in &hubs {
            if g >= d {
                break;
            }
            // A cheap lower bound first: the distance to the region's box.
            let bx = (w.bbox[0][0] - u[0]).max(u[0] - w.bbox[1][0]).max(0.0);
            let by = (w.bbox[0][1] - u[1]).max(u[1] - w.bbox[1][1]).max(0.0);
            if g + bx.hypot(by) >= d {
                continue;
            }
            d = d.min(g + (distance_to(&w.poly, u) - setup.tol).max(0.0));
        }
        if d.is_finite() && d > best.0 {
            best = (d, Some(w.at));
        }
    }
    (best.0, best.1, true)
}
