//! The offline references, checked against independent code written from their definitions:
//! lower bounds that no run beats and that hold point by point, and the exact optimum against
//! a brute force over the same candidates.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use stopscan::algorithm::shortest_path::segment_is_free;
use stopscan::algorithm::visibility::Visibility;
use stopscan::generate::{Instance, comb, office, pillar_forest, spiral, star};
use stopscan::geometry::{Domain, Location};
use stopscan::kernel::Point;
use stopscan::offline::polygon::{OptimumStatus, Solver, lower_bounds, optimum};
use stopscan::protocol::CostModel;
use stopscan::sim::NoObserver;
use stopscan::sim::polygon::run;
use stopscan::strategy::polygon::{REGISTRY, by_name};
use stopscan::world::polygon::PolygonWorld;

/// Points to test "seen from here" at: a grid over the domain, its vertices, and the edges'
/// middles (viewpoints on the boundary count: visibility is in the closed free space).
fn samples(d: &Domain, n: usize) -> Vec<Point> {
    let [lo, hi] = d.bounds();
    let mut out = Vec::new();
    for i in 0..=n {
        for j in 0..=n {
            let p = [
                lo[0] + (hi[0] - lo[0]) * i as f64 / n as f64,
                lo[1] + (hi[1] - lo[1]) * j as f64 / n as f64,
            ];
            if d.locate(p) != Location::Outside {
                out.push(p);
            }
        }
    }
    for ring in d.rings() {
        for (k, &p) in ring.iter().enumerate() {
            let q = ring[(k + 1) % ring.len()];
            out.push(p);
            out.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
        }
    }
    out
}

fn instances() -> Vec<(&'static str, Instance)> {
    vec![
        ("spiral 4", spiral(4).unwrap()),
        ("spiral 7", spiral(7).unwrap()),
        ("star 6", star(6).unwrap()),
        ("comb 4", comb(4).unwrap()),
        ("forest", pillar_forest(30.0, 20.0, 5, 2).unwrap()),
        ("office", office(3, 4, 5).unwrap()),
    ]
}

/// The certificate of the bounds, point by point: from no sample point does a viewpoint see
/// two packing witnesses or more than weight 1 of the fractional packing, and the start sees
/// none of them. "Sees" is decided by an exact walk of the segment through the triangulation,
/// not by the visibility regions the bounds were computed from.
#[test]
fn the_lower_bounds_hold_point_by_point() {
    for (name, inst) in instances() {
        let vis = Visibility::new(inst.domain.clone()).unwrap();
        let lb = lower_bounds(
            &vis,
            inst.start,
            None,
            &stopscan::offline::polygon::bounds::Budget::default(),
        )
        .unwrap();
        assert!(lb.complete, "{name}");
        assert_eq!(lb.packing, lb.packing_points.len());
        assert!(lb.views > lb.packing, "{name}: {lb:?}");
        let mesh = vis.mesh();
        let sees = |g: Point, w: Point| segment_is_free(mesh, g, w);
        for &w in lb.packing_points.iter().chain(lb.lp_weights.iter().map(|w| &w.at)) {
            assert!(!sees(inst.start, w), "{name}: the start sees witness {w:?}");
        }
        let total: f64 = lb.lp_weights.iter().map(|w| w.weight).sum();
        if let Some(lp) = lb.lp {
            assert!((lp - total).abs() < 1e-9, "{name}");
            assert!(lb.views > (lp - 1e-9).ceil() as usize);
        }
        for g in samples(&inst.domain, 60) {
            let two = lb.packing_points.iter().filter(|&&w| sees(g, w)).count();
            assert!(two <= 1, "{name}: {g:?} sees {two} packing witnesses");
            let depth: f64 = lb.lp_weights.iter().filter(|w| sees(g, w.at)).map(|w| w.weight).sum();
            assert!(depth <= 1.0 + 1e-9, "{name}: {g:?} sees weight {depth}");
        }
    }
}

/// No run beats the bounds: every strategy, from several starts, takes at least the scans,
/// the metres and the time they promise; and the proven optimum over the candidates is at
/// least the bound on views (the bound holds for viewpoints anywhere).
#[test]
fn no_run_and_no_optimum_beats_the_lower_bounds() {
    let cost = CostModel::new(3.0, 0.5, 0.8).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(10);
    for (name, inst) in instances() {
        let world = PolygonWorld::new(inst.domain.clone()).unwrap();
        let [lo, hi] = inst.domain.bounds();
        let mut starts = vec![inst.start];
        while starts.len() < 3 {
            let p = [rng.random_range(lo[0]..hi[0]), rng.random_range(lo[1]..hi[1])];
            if inst.domain.locate(p) == Location::Interior {
                starts.push(p);
            }
        }
        for &s in &starts {
            let lb = lower_bounds(
                world.visibility(),
                s,
                None,
                &stopscan::offline::polygon::bounds::Budget::default(),
            )
            .unwrap();
            for strategy in REGISTRY.names().filter(|&n| n != "range_limited") {
                let mut st = by_name(strategy, &cost).unwrap();
                let r = run(&world, s, &cost, st.as_mut(), &mut NoObserver).unwrap();
                let label = format!("{name} from {s:?}, {strategy}");
                assert!(r.tally.scans >= lb.views as u64, "{label}: {} < {lb:?}", r.tally.scans);
                assert!(r.tally.distance >= lb.travel - 1e-9, "{label}: {} m", r.tally.distance);
                assert!(r.time.total() >= lb.time(&cost) - 1e-9, "{label}");
            }
            if s == inst.start {
                let o = optimum(world.visibility(), s, 30.0, Solver::Microlp).unwrap();
                if let Some(v) = o.views() {
                    assert!(v >= lb.views, "{name}: optimum {v} below the bound {}", lb.views);
                }
            }
        }
    }
}

/// The candidates of the exact optimum, rebuilt from their definition: the start, every
/// vertex and the centroid of every triangle of the free space.
fn candidates(vis: &Visibility, start: Point) -> Vec<Point> {
    let m = vis.mesh();
    let pts = m.points();
    let mut c = vec![start];
    c.extend(vis.domain().rings().iter().flatten().copied());
    c.extend(m.triangle_corners().iter().map(|t| {
        let [a, b, d] = t.map(|i| pts[i as usize]);
        [(a[0] + b[0] + d[0]) / 3.0, (a[1] + b[1] + d[1]) / 3.0]
    }));
    c
}

/// Calls `f` on every `k`-subset of `from..n` (ascending) until it returns true.
fn subsets(
    n: usize,
    k: usize,
    from: usize,
    cur: &mut Vec<usize>,
    f: &mut dyn FnMut(&[usize]) -> bool,
) -> bool {
    if cur.len() == k {
        return f(cur);
    }
    for i in from..n {
        cur.push(i);
        if subsets(n, k, i + 1, cur, f) {
            return true;
        }
        cur.pop();
    }
    false
}

/// The smallest number of candidates, the start among them, connected by mutual visibility
/// and seeing every sample point, by trying every set in order of size.
fn brute_force_minimum(vis: &Visibility, start: Point, max: usize) -> Option<usize> {
    let mesh = vis.mesh();
    let cands = candidates(vis, start);
    let pts: Vec<Point> = samples(vis.domain(), 40)
        .into_iter()
        .filter(|&p| vis.domain().locate(p) == Location::Interior)
        .collect();
    let sees: Vec<Vec<bool>> =
        cands.iter().map(|&c| pts.iter().map(|&p| segment_is_free(mesh, c, p)).collect()).collect();
    let link: Vec<Vec<bool>> = cands
        .iter()
        .map(|&a| cands.iter().map(|&b| segment_is_free(mesh, a, b)).collect())
        .collect();
    let n = cands.len();
    for k in 0..max {
        let mut ok = |rest: &[usize]| {
            let set: Vec<usize> = std::iter::once(0).chain(rest.iter().copied()).collect();
            let covered = (0..pts.len()).all(|p| set.iter().any(|&c| sees[c][p]));
            if !covered {
                return false;
            }
            let mut reached = vec![0usize];
            let mut i = 0;
            while i < reached.len() {
                for &c in &set {
                    if !reached.contains(&c) && link[reached[i]][c] {
                        reached.push(c);
                    }
                }
                i += 1;
            }
            reached.len() == set.len()
        };
        if subsets(n, k, 1, &mut Vec::new(), &mut ok) {
            return Some(k + 1);
        }
    }
    None
}

/// The exact optimum equals a brute force over the same candidates on small polygons (the
/// brute force checks coverage at sample points, so it can only find smaller sets; equality
/// means the optimum's exact certificate and the samples agree).
#[test]
fn the_optimum_matches_a_brute_force_over_the_candidates() {
    let small: Vec<(&str, Instance)> = vec![
        ("spiral 2", spiral(2).unwrap()),
        ("spiral 3", spiral(3).unwrap()),
        ("star 4", star(4).unwrap()),
        ("comb 2", comb(2).unwrap()),
    ];
    for (name, inst) in small {
        let vis = Visibility::new(inst.domain.clone()).unwrap();
        let o = optimum(&vis, inst.start, 60.0, Solver::Microlp).unwrap();
        assert_eq!(o.status, OptimumStatus::Proven, "{name}: {o:?}");
        let v = o.views().unwrap();
        assert_eq!(brute_force_minimum(&vis, inst.start, v + 1), Some(v), "{name}");
    }
}

/// Every built solver agrees with the strongest one. The reference (CBC, or HiGHS) must prove
/// every instance; each solver, microlp included, then either proves the same optimum or, cut
/// short by its budget (for microlp a node budget, the same on every machine), reports a proven
/// lower bound and an incumbent that bracket it. microlp must prove all but the largest.
#[cfg(any(feature = "cbc", feature = "highs"))]
#[test]
fn every_built_solver_proves_the_same_optimum() {
    use stopscan::offline::polygon::{ReferenceLimits, references};
    let strong = Solver::ALL
        .iter()
        .find(|(s, built)| *built && *s != Solver::Microlp)
        .map(|&(s, _)| s)
        .unwrap();
    for (name, inst) in instances() {
        let vis = Visibility::new(inst.domain.clone()).unwrap();
        let reference = optimum(&vis, inst.start, 600.0, strong).unwrap();
        assert_eq!(reference.status, OptimumStatus::Proven, "{name}, {}", strong.name());
        let v = reference.views().unwrap();
        for (solver, built) in Solver::ALL {
            if !built {
                continue;
            }
            let limits = ReferenceLimits {
                optimum_max_vertices: usize::MAX,
                optimum_seconds: 600.0,
                optimum_nodes: Some(2_000),
                solver,
                ..ReferenceLimits::default()
            };
            let o = references(&vis, inst.start, None, limits, &mut |_| {}).unwrap().optimum;
            let who = format!("{name}, {}", solver.name());
            match o.status {
                OptimumStatus::Proven => assert_eq!(o.views(), Some(v), "{who}"),
                OptimumStatus::BudgetReached => {
                    assert!(solver == Solver::Microlp && name == "office", "{who}: {o:?}");
                    assert!(o.lower <= v, "{who}: {o:?}");
                    assert!(
                        o.best.as_ref().is_none_or(|b| b.viewpoints.len() >= v),
                        "{who}: {o:?}"
                    );
                }
                OptimumStatus::Skipped => panic!("{who}: skipped: {o:?}"),
            }
        }
    }
}

/// A budget of steps cuts the lower bounds at the same place every time, whatever the load
/// (another thread computes the same bounds meanwhile): a cut run is marked incomplete and
/// stays below the whole computation, and a budget that covers the whole computation gives
/// exactly the unlimited bounds.
#[test]
fn a_budget_of_steps_cuts_the_bounds_at_the_same_place_every_time() {
    use stopscan::offline::polygon::bounds::Budget;
    let inst = stopscan::generate::pillar_forest(30.0, 20.0, 12, 8).unwrap();
    let vis = Visibility::new(inst.domain.clone()).unwrap();
    let whole = Budget::default();
    let full = lower_bounds(&vis, inst.start, None, &whole).unwrap();
    assert!(full.complete);
    let needed = whole.spent();
    for steps in [1, needed / 2, needed - 1] {
        let (a, b) = std::thread::scope(|s| {
            let busy = s.spawn(|| lower_bounds(&vis, inst.start, None, &Budget::default()));
            let a = lower_bounds(&vis, inst.start, None, &Budget::steps(steps)).unwrap();
            let b = lower_bounds(&vis, inst.start, None, &Budget::steps(steps)).unwrap();
            busy.join().unwrap().unwrap();
            (a, b)
        });
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "{steps} steps");
        assert!(!a.complete, "{steps} of {needed} steps");
        assert!(a.views <= full.views && a.travel <= full.travel + 1e-9, "{steps} steps");
    }
    let enough = lower_bounds(&vis, inst.start, None, &Budget::steps(needed)).unwrap();
    assert_eq!(format!("{enough:?}"), format!("{full:?}"));
}
