//! Offline references for polygon exploration: what a robot that knew the map could do, and
//! what no robot can do better than.
//!
//! The paper's offline problem (its conditions 1–3) is the art gallery problem with one more
//! constraint: every viewpoint after the first is seen from an earlier one, and the first is
//! the start. Here:
//!
//! - [`bounds`]: lower bounds on the views, the distance and the time of *any* exploration,
//!   with viewpoints anywhere (witnesses with disjoint visibility regions, a fractional
//!   packing made valid, the area a range-limited scan can see, the distance to the farthest
//!   witness's region). They certify `time / time_lower` as an upper bound on a run's
//!   competitive ratio;
//! - [`greedy`]: a valid viewpoint set, as an upper *reference* (not a bound): from the start,
//!   repeatedly add the candidate seen from a chosen one that sees the most area not yet
//!   covered;
//! - [`reach`]: what a robot with a footprint can see at all (the free space seen from its
//!   reachable configuration space), for the unreachable area beside its runs;
//! - [`optimum`](mod@optimum): the exact minimum over the same candidates by integer
//!   programming, within a time budget (the best set found and the best proven lower bound
//!   when it runs out).
//!
//! **Candidates** are the start, every vertex of the domain (a guard on a vertex, seen in the
//! closed free space; a robot stands a hair inside) and the centroid of every triangle of the
//! free space's constrained Delaunay triangulation (so that, for instance, the kernel of a
//! star is among them). Vertex guards alone always suffice: each triangle is seen whole from
//! each of its corners. The exact minimum is exact *over these candidates*; a point guard
//! elsewhere can occasionally do better, which the output says, and which is why the
//! certified ratio is taken against [`bounds`] and not against it.
//!
//! **Witnesses**: coverage is required at the centroid of every triangle of the free space
//! (weighted by its area), and a solution is then checked exactly with
//! [`cover::open_windows`]. Where a window of the chosen regions is left open (its probe
//! point lies in the free space), a witness is added there and the problem is solved again,
//! until the certificate holds (the usual iterative scheme for art gallery problems).

pub mod bounds;
pub mod optimum;
pub mod reach;

pub use bounds::{LowerBounds, WeightedWitness, lower_bounds};
pub use optimum::{OptimumReport, OptimumStatus, Solver};

use std::collections::HashMap;

use std::time::{Duration, Instant};

use serde::{Deserialize, Serialize};

use crate::algorithm::cover;
use crate::algorithm::visibility::{Visibility, VisibilityError, VisibilityRegion};
use crate::geometry::{Domain, Location};
use crate::kernel::{Point, RingSide, ring_side};

/// The weight of a witness added beyond a window a solution leaves open, as a fraction of the
/// free area: next to nothing, as the coverage it stands for is a sliver, but not zero.
const CERTIFICATE_WITNESS_WEIGHT: f64 = 1e-9;

/// A set of viewpoints found offline.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ViewSet {
    /// The viewpoints, the start first, each seen from an earlier one.
    pub viewpoints: Vec<Point>,
    /// Whether the exact coverage certificate holds (no window of the union left open).
    pub certified: bool,
}

/// Why an offline reference could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OfflineError {
    /// The domain could not be preprocessed, or the start is outside it.
    #[error(transparent)]
    Visibility(#[from] VisibilityError),
    /// The integer program failed (time limit, or a solver error).
    #[error("integer program: {0}")]
    Solver(String),
}

/// The bound of the paper's Lemma 4 on the views of the range-limited algorithm:
/// `⌊8·Area / (3R²)⌋ + ⌊Perimeter / R⌋ + r + h + 1`.
///
/// The extracted text prints the first term as "8 3 Area(P) / 3 3 R2": the "3"s between
/// factors are the PDF's multiplication signs, and the proof fixes the term — grid squares
/// with diagonal √3R/2 have side √3R/(2√2) and area 3R²/8, so at most 8·Area/(3R²) of them
/// lie inside P.
pub fn lemma4_bound(domain: &Domain, range: f64) -> usize {
    let perimeter: f64 = domain
        .rings()
        .iter()
        .map(|ring| {
            (0..ring.len())
                .map(|i| {
                    let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                    (b[0] - a[0]).hypot(b[1] - a[1])
                })
                .sum::<f64>()
        })
        .sum();
    let squares = (8.0 * domain.area() / (3.0 * range * range)).floor() as usize;
    let boundary = (perimeter / range).floor() as usize;
    squares + boundary + domain.reflex_vertices().len() + domain.holes().len() + 1
}

/// The upper bound the paper proves for its algorithm: r + 1 views (Theorem 1), or Lemma 4's
/// bound with a range limit, with the rule's name.
pub fn upper_bound(domain: &Domain, range: Option<f64>) -> (usize, &'static str) {
    match range {
        Some(r) => (lemma4_bound(domain, r), "Lemma 4: 8A/(3R^2) + P/R + r + h + 1"),
        None => (domain.reflex_vertices().len() + 1, "Theorem 1: r + 1"),
    }
}

/// Everything a run is measured against.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct References {
    /// Lower bounds on any exploration ([`bounds`]).
    pub lower: LowerBounds,
    /// The greedy upper reference, when computed.
    pub greedy: Option<ViewSet>,
    /// The exact minimum over the candidates, or how far the search got.
    pub optimum: OptimumReport,
}

/// Limits on the offline work for one run. Every stage has a time budget: when it runs out,
/// the stage reports what it has (bounds stay valid, only weaker; the optimum search reports
/// its best set and its best proven lower bound).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ReferenceLimits {
    /// Compute the greedy reference up to this many domain vertices.
    pub greedy_max_vertices: usize,
    /// Search for the exact optimum up to this many domain vertices.
    pub optimum_max_vertices: usize,
    /// Seconds for the exact optimum's search.
    pub optimum_seconds: f64,
    /// Branch-and-bound nodes for the exact optimum's search, when set (microlp only): a
    /// budget that does not depend on the machine, so results cut short by it are the same
    /// everywhere.
    pub optimum_nodes: Option<u64>,
    /// Seconds for the lower bounds.
    pub bounds_seconds: f64,
    /// Steps for the lower bounds, when set: a budget that does not depend on the machine
    /// or its load ([`bounds::Budget::steps`]), used instead of `bounds_seconds`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub bounds_steps: Option<u64>,
    /// The integer-programming solver.
    pub solver: Solver,
}

impl Default for ReferenceLimits {
    fn default() -> Self {
        Self {
            greedy_max_vertices: 1000,
            optimum_max_vertices: 400,
            optimum_seconds: 5.0,
            optimum_nodes: None,
            bounds_seconds: 5.0,
            bounds_steps: None,
            solver: Solver::default(),
        }
    }
}

impl ReferenceLimits {
    /// The lower bounds' budget: (seconds, steps), steps used when given.
    #[must_use]
    pub fn bounds(&self) -> (f64, Option<u64>) {
        (self.bounds_seconds, self.bounds_steps)
    }

    /// Only the lower bounds (within their default budget): no greedy reference, no optimum.
    pub const BOUNDS_ONLY: Self = Self {
        greedy_max_vertices: 0,
        optimum_max_vertices: 0,
        optimum_seconds: 0.0,
        optimum_nodes: None,
        bounds_seconds: 5.0,
        bounds_steps: None,
        solver: Solver::Microlp,
    };
}

/// A deadline `seconds` from now (none for an infinite budget).
pub fn deadline_in(seconds: f64) -> Option<Instant> {
    (seconds.is_finite() && seconds >= 0.0)
        .then(|| Instant::now() + Duration::from_secs_f64(seconds.min(1e9)))
}

/// What the offline work is doing, for a progress display.
pub type Progress<'a> = &'a mut dyn FnMut(&str);

/// The lower bounds always, the greedy reference and the exact optimum within `limits`
/// (references use full visibility, so with a range limit only the bounds are computed).
/// `progress` hears what is being computed.
///
/// # Errors
/// [`OfflineError`] if the start is outside the free space.
pub fn references(
    vis: &Visibility,
    start: Point,
    range: Option<f64>,
    limits: ReferenceLimits,
    progress: Progress,
) -> Result<References, OfflineError> {
    references_within(vis, start, range, limits, None, progress)
}

/// [`references`] for a run that set out to see only `within` (a footprint's reach, a
/// window rule): the lower bounds count witnesses there only
/// ([`bounds::lower_bounds_within`]); the greedy reference and the optimum are the full
/// problem's.
///
/// # Errors
/// [`OfflineError`] if the start is outside the free space.
pub fn references_within(
    vis: &Visibility,
    start: Point,
    range: Option<f64>,
    limits: ReferenceLimits,
    within: Option<&crate::algorithm::region::Region>,
    progress: Progress,
) -> Result<References, OfflineError> {
    let d = vis.domain();
    progress("lower bounds");
    let budget = bounds::Budget::of(limits.bounds_seconds, limits.bounds_steps);
    let lower = bounds::lower_bounds_within(vis, start, range, &budget, within)?;
    let n = d.vertex_count();
    let views = lower.views;
    let skipped = |why: String| OptimumReport::skipped(limits.solver, views, why);
    if range.is_some() {
        let why = "not computed with a range limit (the candidates' regions are unlimited)";
        return Ok(References { lower, greedy: None, optimum: skipped(why.into()) });
    }
    let mut problem = None;
    let mut greedy_set = None;
    if n <= limits.greedy_max_vertices {
        progress("greedy reference");
        let p = problem.insert(Problem::new(vis, start)?);
        greedy_set = Some(greedy_on(p)?);
    }
    let optimum = if n > limits.optimum_max_vertices {
        skipped(format!(
            "not attempted: {n} vertices, above the limit of {} (--optimum-max-vertices)",
            limits.optimum_max_vertices
        ))
    } else if limits.optimum_seconds <= 0.0 {
        skipped("not attempted: no time budget (--optimum-seconds 0)".into())
    } else {
        let p = match problem.as_mut() {
            Some(p) => p,
            None => problem.insert(Problem::new(vis, start)?),
        };
        let deadline = deadline_in(limits.optimum_seconds);
        let mut report = optimum::solve(
            p,
            lower.views,
            greedy_set.as_ref(),
            limits.solver,
            deadline,
            limits.optimum_nodes,
            progress,
        )?;
        report.budget_seconds = limits.optimum_seconds;
        report
    };
    Ok(References { lower, greedy: greedy_set.map(|g| g.set), optimum })
}

/// The candidates, the witnesses and who sees what.
struct Problem<'a> {
    vis: &'a Visibility,
    /// The start, the vertices, then triangle centroids.
    cands: Vec<Point>,
    /// Candidates that are points (the start and the centroids), with their indices.
    points: Vec<usize>,
    regions: Vec<VisibilityRegion>,
    /// `sees[c]`: the candidates candidate `c` sees (itself excluded), sorted.
    sees: Vec<Vec<usize>>,
    /// Witness points with weights (areas).
    witnesses: Vec<(Point, f64)>,
    /// `seen_by[w]`: the candidates that see witness `w`.
    seen_by: Vec<Vec<usize>>,
    vertex_index: HashMap<[u64; 2], usize>,
}

impl<'a> Problem<'a> {
    fn new(vis: &'a Visibility, start: Point) -> Result<Self, OfflineError> {
        let d = vis.domain();
        let m = vis.mesh();
        let pts = m.points();
        let tris: Vec<(Point, f64)> = m
            .tri
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| pts[i as usize]);
                let centroid = [(a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0];
                let area =
                    0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1])).abs();
                (centroid, area)
            })
            .collect();
        let mut cands = vec![start];
        cands.extend(d.rings().iter().flatten().copied());
        let mut vertex_index = HashMap::new();
        for (i, p) in cands.iter().enumerate().skip(1) {
            vertex_index.entry(key(*p)).or_insert(i);
        }
        let mut points = vec![0];
        points.extend(cands.len()..cands.len() + tris.len());
        cands.extend(tris.iter().map(|t| t.0));
        let regions = cands.iter().map(|&c| vis.query(c)).collect::<Result<Vec<_>, _>>()?;
        let mut p = Self {
            vis,
            cands,
            points,
            regions,
            sees: Vec::new(),
            witnesses: Vec::new(),
            seen_by: Vec::new(),
            vertex_index,
        };
        p.sees = (0..p.cands.len()).map(|c| p.seen_from_region(&p.regions[c], Some(c))).collect();
        for (w, weight) in tris {
            p.add_witness(w, weight)?;
        }
        Ok(p)
    }

    /// The candidates a region sees: the vertices on its boundary (every vertex seen lies on
    /// it) and the point candidates inside it (closed).
    fn seen_from_region(&self, r: &VisibilityRegion, own: Option<usize>) -> Vec<usize> {
        let mut out: Vec<usize> = r
            .boundary
            .iter()
            .flat_map(|b| {
                let (a, c) = b.ends();
                [a, c]
            })
            .filter_map(|q| self.vertex_index.get(&key(q)).copied())
            .collect();
        let [lo, hi] = cover::bounds_of(&r.polygon);
        for &c in &self.points {
            let q = self.cands[c];
            if q[0] >= lo[0]
                && q[0] <= hi[0]
                && q[1] >= lo[1]
                && q[1] <= hi[1]
                && ring_side(&r.polygon, q) != RingSide::Outside
            {
                out.push(c);
            }
        }
        out.sort_unstable();
        out.dedup();
        out.retain(|&c| Some(c) != own);
        out
    }

    fn add_witness(&mut self, w: Point, weight: f64) -> Result<(), OfflineError> {
        let r = self.vis.query(w)?;
        let by = self.seen_from_region(&r, None);
        self.witnesses.push((w, weight));
        self.seen_by.push(by);
        Ok(())
    }

    /// Checks a solution exactly; adds a witness beyond every open window part. Returns
    /// whether the solution was complete.
    fn certify(&mut self, chosen: &[usize]) -> Result<bool, OfflineError> {
        let regions: Vec<VisibilityRegion> =
            chosen.iter().map(|&c| self.regions[c].clone()).collect();
        let d = self.vis.domain();
        let mut added = 0;
        for p in cover::open_window_points(&regions) {
            if d.locate(p) == Location::Interior {
                self.add_witness(p, CERTIFICATE_WITNESS_WEIGHT * d.area())?;
                added += 1;
            }
        }
        Ok(added == 0)
    }

    fn view_set(&self, chosen: &[usize], certified: bool) -> ViewSet {
        let (order, _) = self.reach(chosen);
        ViewSet { viewpoints: order.into_iter().map(|c| self.cands[c]).collect(), certified }
    }

    /// The chosen candidates reachable from the start through chosen ones, breadth first (so
    /// each is seen by an earlier one), and the chosen ones that are not.
    fn reach(&self, chosen: &[usize]) -> (Vec<usize>, Vec<usize>) {
        let mut inset = vec![false; self.cands.len()];
        for &c in chosen {
            inset[c] = true;
        }
        let mut out = vec![0];
        let mut done = vec![false; self.cands.len()];
        done[0] = true;
        let mut k = 0;
        while k < out.len() {
            for &n in &self.sees[out[k]] {
                if inset[n] && !done[n] {
                    done[n] = true;
                    out.push(n);
                }
            }
            k += 1;
        }
        let rest = chosen.iter().copied().filter(|&c| !done[c]).collect();
        (out, rest)
    }
}

fn key(p: Point) -> [u64; 2] {
    [p[0].to_bits(), p[1].to_bits()]
}

/// The greedy upper reference: a certified viewpoint set, each seen from an earlier one.
///
/// # Errors
/// [`OfflineError::Visibility`] if the start is outside the free space.
///
/// # Complexity
/// O(n) visibility queries for the candidates and witnesses, then O(k · n · w) for k views.
pub fn greedy(vis: &Visibility, start: Point) -> Result<ViewSet, OfflineError> {
    Ok(greedy_on(&mut Problem::new(vis, start)?)?.set)
}

/// The exact minimum over the candidates (see [`optimum`](mod@optimum)) within `seconds`, with
/// the greedy reference as the first incumbent and the geometric lower bounds as the first
/// bound.
///
/// # Errors
/// [`OfflineError`] if the start is outside the free space or the solver fails.
pub fn optimum(
    vis: &Visibility,
    start: Point,
    seconds: f64,
    solver: Solver,
) -> Result<OptimumReport, OfflineError> {
    let lower = lower_bounds(vis, start, None, &bounds::Budget::until(deadline_in(seconds)))?;
    let mut p = Problem::new(vis, start)?;
    let g = greedy_on(&mut p)?;
    let mut report = optimum::solve(
        &mut p,
        lower.views,
        Some(&g),
        solver,
        deadline_in(seconds),
        None,
        &mut |_| {},
    )?;
    report.budget_seconds = seconds;
    Ok(report)
}

/// A greedy set: the viewpoints and the candidates they are.
struct Greedy {
    set: ViewSet,
    chosen: Vec<usize>,
}

fn greedy_on(p: &mut Problem) -> Result<Greedy, OfflineError> {
    greedy_from(p, &[0])
}

/// The greedy completion of `initial` (the start and candidates connected to it): candidates
/// seen from a chosen one are added, most uncovered area first, until the set is certified
/// complete.
fn greedy_from(p: &mut Problem, initial: &[usize]) -> Result<Greedy, OfflineError> {
    let nc = p.cands.len();
    let mut chosen = initial.to_vec();
    let mut is_chosen = vec![false; nc];
    let mut eligible = vec![false; nc];
    for &c in &chosen {
        is_chosen[c] = true;
        for &n in &p.sees[c] {
            eligible[n] = true;
        }
    }
    // Witnesses each candidate sees, and which witnesses are covered; both grow as witnesses
    // are added by the certificate.
    let mut sees_w: Vec<Vec<usize>> = vec![Vec::new(); nc];
    let mut covered: Vec<bool> = Vec::new();
    let mut known = 0;
    for _round in 0..64 {
        for w in known..p.witnesses.len() {
            covered.push(p.seen_by[w].iter().any(|&c| is_chosen[c]));
            for &c in &p.seen_by[w] {
                sees_w[c].push(w);
            }
        }
        known = p.witnesses.len();
        let mut gain: Vec<f64> = (0..nc)
            .map(|c| sees_w[c].iter().filter(|&&w| !covered[w]).map(|&w| p.witnesses[w].1).sum())
            .collect();
        let mut count: Vec<usize> =
            (0..nc).map(|c| sees_w[c].iter().filter(|&&w| !covered[w]).count()).collect();
        loop {
            let best = (0..nc)
                .filter(|&c| eligible[c] && !is_chosen[c] && count[c] > 0)
                .max_by(|&a, &b| gain[a].total_cmp(&gain[b]).then(b.cmp(&a)));
            let Some(c) = best else { break };
            chosen.push(c);
            is_chosen[c] = true;
            for &n in &p.sees[c] {
                eligible[n] = true;
            }
            for &w in &sees_w[c] {
                if !covered[w] {
                    covered[w] = true;
                    for &o in &p.seen_by[w] {
                        gain[o] -= p.witnesses[w].1;
                        count[o] -= 1;
                    }
                }
            }
        }
        if p.certify(&chosen)? {
            return Ok(Greedy { set: p.view_set(&chosen, true), chosen });
        }
    }
    Ok(Greedy { set: p.view_set(&chosen, false), chosen })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{spiral, star};

    fn proven(v: &Visibility, start: Point) -> usize {
        let o = optimum(v, start, 60.0, Solver::Microlp).unwrap();
        assert_eq!(o.status, OptimumStatus::Proven, "{o:?}");
        assert!(o.best.as_ref().unwrap().certified);
        o.views().unwrap()
    }

    #[test]
    fn a_convex_room_needs_one_view() {
        let d = Domain::new(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]], vec![]).unwrap();
        let v = Visibility::new(d).unwrap();
        let g = greedy(&v, [1.0, 1.0]).unwrap();
        assert_eq!(g.viewpoints.len(), 1);
        assert!(g.certified);
        assert_eq!(proven(&v, [1.0, 1.0]), 1);
    }

    #[test]
    fn the_star_needs_two_and_the_spiral_r_plus_one() {
        // The paper's Fig. 11: the start and the star point.
        let s = star(5).unwrap();
        let v = Visibility::new(s.domain.clone()).unwrap();
        assert_eq!(proven(&v, s.start), 2);
        // The paper's Fig. 9: no algorithm does better than r + 1 on the spiral.
        for turns in 1..4 {
            let sp = spiral(turns).unwrap();
            let v = Visibility::new(sp.domain.clone()).unwrap();
            assert_eq!(proven(&v, sp.start), turns + 1, "spiral {turns}");
            let g = greedy(&v, sp.start).unwrap();
            assert!(g.certified && g.viewpoints.len() > turns);
        }
    }

    #[test]
    fn a_zero_budget_reports_the_greedy_set_and_the_bounds() {
        let sp = spiral(6).unwrap();
        let v = Visibility::new(sp.domain.clone()).unwrap();
        let o = optimum(&v, sp.start, 0.0, Solver::Microlp).unwrap();
        assert_eq!(o.status, OptimumStatus::BudgetReached);
        assert!(o.views().is_none());
        let best = o.best.as_ref().unwrap().viewpoints.len();
        assert!(o.lower <= best && o.gap() == Some(best - o.lower), "{o:?}");
    }
}
