//! Polygon exploration with the paper's depth-first algorithm: the r + 1 bound, coverage,
//! legal moves and determinism on generated instances.

use rand::{RngExt, SeedableRng};
use stopscan::algorithm::cover::open_windows;
use stopscan::algorithm::region::Region;
use stopscan::generate::{Instance, comb, office, pillar_forest, spiral, star};
use stopscan::geometry::Location;
use stopscan::kernel::{RingSide, ring_side};
use stopscan::protocol::CostModel;
use stopscan::sim::NoObserver;
use stopscan::sim::polygon::{PolygonRun, run};
use stopscan::strategy::polygon::{DepthFirst, by_name};
use stopscan::world::polygon::PolygonWorld;

fn explore(inst: &Instance) -> (PolygonWorld, PolygonRun) {
    let world = PolygonWorld::new(inst.domain.clone()).unwrap();
    let r = run(&world, inst.start, &CostModel::default(), &mut DepthFirst::new(), &mut NoObserver)
        .unwrap();
    (world, r)
}

fn check(inst: &Instance, label: &str) -> PolygonRun {
    let (world, run) = explore(inst);
    let d = world.domain();
    let r = d.reflex_vertices().len() as u64;
    assert!(run.tally.scans <= r + 1, "{label}: {} scans > r + 1 = {}", run.tally.scans, r + 1);
    // Coverage: the union of the scans is the free space.
    let polys: Vec<_> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
    let covered = Region::union_all(&polys).area();
    assert!(
        (covered - d.area()).abs() <= 1e-7 * d.area(),
        "{label}: covered {covered} of {}",
        d.area()
    );
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    let [lo, hi] = d.bounds();
    for _ in 0..400 {
        let p = [rng.random_range(lo[0]..hi[0]), rng.random_range(lo[1]..hi[1])];
        if d.locate(p) == Location::Interior {
            assert!(
                polys.iter().any(|poly| ring_side(poly, p) != RingSide::Outside),
                "{label}: {p:?} never seen"
            );
        }
    }
    // Every segment driven lies in the free space (the simulator refuses others; check again).
    for w in run.path.windows(2) {
        assert!(world.can_move(w[0], w[1]), "{label}: {w:?}");
    }
    // The area no scan covers, confirmed by exact point tests: none.
    let u = stopscan::algorithm::cover::uncovered_area(d, &polys);
    assert!(u <= 1e-9 * d.area(), "{label}: {u} m² uncovered");
    // The exact certificate: every window of every scan is looked through by another.
    let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
    assert_eq!(
        open_windows(&regions, |p| d.locate(p) == Location::Interior),
        0,
        "{label}: windows left open"
    );
    run
}

/// A room with a side corridor whose wall is in line with the start: the ray down the wall
/// grazes it edge-on. It must be an edge of the region, not a window (a window there has only
/// the inside of the wall behind it, and an explorer would try to look through it forever).
#[test]
fn a_wall_in_line_with_the_start_is_an_edge_not_a_window() {
    let outer = vec![
        [0.0, 0.0],
        [2.0, 0.0],
        [2.0, 1.0],
        [5.0, 1.0],
        [5.0, 2.0],
        [3.0, 2.0],
        [3.0, 5.0],
        [0.0, 5.0],
    ];
    let domain = stopscan::geometry::Domain::new(outer, vec![]).unwrap();
    let vis = stopscan::algorithm::visibility::Visibility::new(domain.clone()).unwrap();
    let region = vis.query([2.0, 4.0]).unwrap();
    for w in region.windows() {
        let (a, b) = w.ends();
        assert!(!(a[0] == 2.0 && b[0] == 2.0), "edge-on wall reported as window {w:?}");
    }
    let inst = Instance { domain, start: [2.0, 4.0] };
    let run = check(&inst, "wall in line");
    assert!(run.tally.scans <= 2, "{} scans", run.tally.scans);
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(48))]

    /// Coverage (area and certificate), legal moves and r + 1 from random starts, many of
    /// them on the integer grid the generators use, so in line with walls and vertices.
    #[test]
    fn exploration_holds_from_any_start(kind in 0usize..4, seed in 0u64..1000, sx in 0.0..1.0f64, sy in 0.0..1.0f64, snap in proptest::prelude::any::<bool>()) {
        let inst = match kind {
            0 => office(1 + (seed % 6) as usize, (seed % 9) as usize, seed).unwrap(),
            1 => pillar_forest(30.0, 20.0, 1 + (seed % 12) as usize, seed).unwrap(),
            2 => comb(1 + (seed % 6) as usize).unwrap(),
            _ => star(3 + (seed % 7) as usize).unwrap(),
        };
        let [lo, hi] = inst.domain.bounds();
        let mut p = [lo[0] + sx * (hi[0] - lo[0]), lo[1] + sy * (hi[1] - lo[1])];
        if snap {
            p = [p[0].round(), p[1].round()];
        }
        if inst.domain.locate(p) == Location::Interior {
            check(&Instance { domain: inst.domain.clone(), start: p }, "random start");
        }
    }
}

#[test]
fn spirals_need_exactly_r_plus_one_views() {
    for turns in 1..10 {
        let run = check(&spiral(turns).unwrap(), "spiral");
        assert_eq!(run.tally.scans, turns as u64 + 1, "spiral with {turns} turns");
    }
}

#[test]
fn stars_combs_and_forests_stay_within_r_plus_one() {
    for k in [3, 5, 9] {
        check(&star(k).unwrap(), "star");
    }
    for t in [1, 2, 5, 8] {
        check(&comb(t).unwrap(), "comb");
    }
    for seed in 0..12 {
        check(&pillar_forest(30.0, 20.0, 2 + seed as usize, seed).unwrap(), "forest");
    }
    for (rooms, desks) in [(1, 0), (2, 3), (5, 12), (10, 40)] {
        check(&office(rooms, desks, rooms as u64).unwrap(), "office");
    }
}

#[test]
fn the_same_instance_gives_the_same_run() {
    let inst = pillar_forest(30.0, 20.0, 10, 4).unwrap();
    let (_, a) = explore(&inst);
    let (_, b) = explore(&inst);
    assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&b).unwrap());
}

#[test]
fn a_thousand_vertex_office_floor() {
    let inst = office(40, 220, 1).unwrap();
    assert!(inst.domain.vertex_count() >= 1000);
    let run = check(&inst, "office 1000");
    assert!(run.tally.scans >= 80, "every room needs a view: {}", run.tally.scans);
}

#[test]
fn baselines_cover_everything_with_legal_moves() {
    let cases = vec![
        spiral(6).unwrap(),
        star(7).unwrap(),
        comb(4).unwrap(),
        office(4, 8, 2).unwrap(),
        pillar_forest(30.0, 20.0, 9, 5).unwrap(),
    ];
    for (inst, name) in
        cases.into_iter().flat_map(|i| [(i.clone(), "nearest_frontier"), (i, "greedy_nbv")])
    {
        let world = PolygonWorld::new(inst.domain.clone()).unwrap();
        let mut s = by_name(name, &CostModel::default()).unwrap();
        let run =
            run(&world, inst.start, &CostModel::default(), s.as_mut(), &mut NoObserver).unwrap();
        let polys: Vec<_> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
        let covered = Region::union_all(&polys).area();
        let d = world.domain();
        assert!((covered - d.area()).abs() <= 1e-7 * d.area(), "covered {covered} of {}", d.area());
        for w in run.path.windows(2) {
            assert!(world.can_move(w[0], w[1]));
        }
        let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
        assert_eq!(open_windows(&regions, |p| d.locate(p) == Location::Interior), 0, "{name}");
    }
}

/// Runs `name` with a sensor of range `range` and checks the range-limited figures: coverage
/// ≥ 1 − 1e-6, no frontier left open, every move legal, and the paper's Lemma 4 bound.
fn check_range(inst: &Instance, name: &str, range: f64) -> PolygonRun {
    use stopscan::offline::polygon::lemma4_bound;
    let world = PolygonWorld::with_range(inst.domain.clone(), Some(range)).unwrap();
    let mut s = by_name(name, &CostModel::default()).unwrap();
    let run = run(&world, inst.start, &CostModel::default(), s.as_mut(), &mut NoObserver).unwrap();
    let d = world.domain();
    let polys: Vec<_> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
    let covered = Region::union_all(&polys).area();
    assert!(
        covered >= (1.0 - 1e-6) * d.area(),
        "{name} R={range}: covered {covered} of {}",
        d.area()
    );
    let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
    assert_eq!(
        open_windows(&regions, |p| d.locate(p) == Location::Interior),
        0,
        "{name} R={range}"
    );
    for w in run.path.windows(2) {
        assert!(world.can_move(w[0], w[1]), "{name} R={range}: {w:?}");
    }
    let bound = lemma4_bound(d, range) as u64;
    assert!(
        run.tally.scans <= bound,
        "{name} R={range}: {} scans > Lemma 4's {bound}",
        run.tally.scans
    );
    // The certified lower bounds hold for the run: every scan sees at most a disc, and
    // witnesses the start does not see need scans and travel.
    let lower = stopscan::offline::polygon::lower_bounds(
        world.visibility(),
        inst.start,
        Some(range),
        &stopscan::offline::polygon::bounds::Budget::default(),
    )
    .unwrap();
    assert!(lower.area >= 1 && lower.views >= lower.area);
    assert!(
        run.tally.scans >= lower.views as u64,
        "{name} R={range}: {} scans < {lower:?}",
        run.tally.scans
    );
    assert!(
        run.tally.distance >= lower.travel,
        "{name} R={range}: {} m < {lower:?}",
        run.tally.distance
    );
    run
}

#[test]
fn range_limited_exploration_covers_within_lemma_4() {
    let cases = vec![
        spiral(3).unwrap(),
        comb(3).unwrap(),
        office(3, 4, 7).unwrap(),
        pillar_forest(30.0, 20.0, 6, 3).unwrap(),
    ];
    for inst in &cases {
        for name in ["range_limited", "depth_first", "nearest_frontier"] {
            for range in [2.5, 6.0] {
                check_range(inst, name, range);
            }
        }
    }
}

/// In an empty room much larger than the range, the range-limited algorithm crosses open
/// space on arcs (Steps 2 and 6) and follows the walls (Step 4).
#[test]
fn range_limited_follows_the_walls_of_a_large_room() {
    let outer = vec![[0.0, 0.0], [20.0, 0.0], [20.0, 12.0], [0.0, 12.0]];
    let domain = stopscan::geometry::Domain::new(outer, vec![]).unwrap();
    let run = check_range(&Instance { domain, start: [10.0, 6.0] }, "range_limited", 3.0);
    // Some viewpoints stand at the walls (a hair inside), as the paper's boundary walk does.
    let at_wall = run
        .scans
        .iter()
        .filter(|s| {
            let [x, y] = s.at;
            x.min(20.0 - x).min(y).min(12.0 - y) < 1e-3
        })
        .count();
    assert!(at_wall >= 4, "{at_wall} scans at a wall");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(24))]

    #[test]
    fn range_limited_holds_on_random_instances(kind in 0usize..3, seed in 0u64..500, range in 1.5..8.0f64) {
        let inst = match kind {
            0 => office(1 + (seed % 4) as usize, (seed % 6) as usize, seed).unwrap(),
            1 => pillar_forest(30.0, 20.0, 1 + (seed % 8) as usize, seed).unwrap(),
            _ => comb(1 + (seed % 4) as usize).unwrap(),
        };
        check_range(&inst, "range_limited", range);
    }
}

/// `reproduce views-benchmarks` on the small shared benchmark polygons: every run within the
/// bound, complete, and the offline optimum computed. The `.pol` files may not be copied into
/// the repository, so the test is ignored by default and fails when run without them.
#[test]
#[ignore = "needs the AGP .pol benchmarks in ../shared/data/agp-polygons (not redistributable)"]
fn views_benchmarks_on_the_small_shared_polygons() {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    let dir = std::env::temp_dir().join(format!("stopscan-vb-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for f in [
        "agp-polygons/agp2009a-orthorand/random-20-1.pol",
        "agp-polygons/agp2009a-simplerand/randsimple-20-1.pol",
        "agp-polygons/agp2009a-rvk/randvon-20-1.pol",
    ] {
        let src = root.join(f);
        assert!(src.exists(), "{} is absent: run beside ../shared", src.display());
        std::fs::copy(&src, dir.join(src.file_name().unwrap())).unwrap();
    }
    let r = stopscan::experiment::reproduce_with_data("views-benchmarks", 0, 0, &dir).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let n = stopscan::strategy::polygon::REGISTRY.len();
    let scans: Vec<_> = r.rows.iter().filter(|row| row.paper.is_some()).collect();
    assert_eq!(scans.len(), 3 * n, "{:?}", r.rows);
    for row in &scans {
        assert!(row.ours <= row.paper.unwrap(), "{}: {} > {:?}", row.label, row.ours, row.paper);
    }
    assert_eq!(r.rows.iter().filter(|row| row.label.contains("offline optimum")).count(), 3);
    assert!(r.notes[0].starts_with(&format!("{} of {} runs", 3 * n, 3 * n)), "{}", r.notes[0]);
    // explore_lite leaves frontiers shorter than its min_frontier_size by design; every other
    // strategy's run is complete.
    let complete: usize = r.notes[1].split(' ').next().unwrap().parse().unwrap();
    assert!(complete >= 3 * (n - 1), "{}", r.notes[1]);
    assert!(r.notes[1].contains(&format!(" of {} runs complete", 3 * n)), "{}", r.notes[1]);
}

/// The visibility benchmark's random polygon with holes: within r + 1, nothing left open,
/// legal moves, from the file's first query point.
#[test]
#[ignore = "needs ../shared/bench/visibility/env_100.txt (no stated licence, not vendored)"]
fn the_shared_random_polygon_with_holes() {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/bench/visibility/env_100.txt");
    assert!(path.exists(), "{} is absent: run beside ../shared", path.display());
    let env = stopscan::io::read_environment(&path).unwrap();
    let start = env.queries[0];
    check(&Instance { domain: env.domain, start }, "env_100");
}

/// The replay's frontier history (what `report.html` highlights at each step) is, at every
/// step, what `open_windows` counts for the scans taken so far, and its tallies add up to the
/// run's: with and without a range limit, for several strategies and instances.
#[test]
fn frontier_history_is_open_windows_at_every_step() {
    use stopscan::algorithm::cover::frontier_history;
    let cases = [
        (office(3, 6, 1).unwrap(), None),
        (pillar_forest(30.0, 20.0, 9, 3).unwrap(), None),
        (spiral(5).unwrap(), Some(4.0)),
        (office(2, 4, 7).unwrap(), Some(3.0)),
    ];
    for (inst, range) in cases {
        for name in ["depth_first", "nearest_frontier"] {
            let name =
                if range.is_some() && name == "depth_first" { "range_limited" } else { name };
            let world = PolygonWorld::with_range(inst.domain.clone(), range).unwrap();
            let mut s = by_name(name, &CostModel::default()).unwrap();
            let r = run(&world, inst.start, &CostModel::default(), s.as_mut(), &mut NoObserver)
                .unwrap();
            let d = world.domain();
            let inside = |p| d.locate(p) == Location::Interior;
            let regions: Vec<_> = r.scans.iter().map(|s| s.region.clone()).collect();
            let history = frontier_history(&regions, inside);
            let mut opened = 0;
            for step in 1..=regions.len() {
                let at_step: usize = history
                    .iter()
                    .filter(|h| h.scan < step)
                    .filter_map(|h| h.open.iter().rev().find(|(s, _)| *s <= step))
                    .map(|(_, open)| open.len())
                    .sum();
                let want = open_windows(&regions[..step], inside);
                assert_eq!(at_step, want, "{name} R={range:?}: step {step}");
                opened = opened.max(at_step);
            }
            assert!(opened > 0, "{name}: some frontier was open at some step");
            // Entries come in step order, first when the frontier's scan is taken.
            for h in &history {
                assert_eq!(h.open[0].0, h.scan + 1);
                assert!(h.open.windows(2).all(|w| w[0].0 < w[1].0 && w[0].1 != w[1].1));
            }
            // Each scan's tally counts it, and the last is the run's.
            assert_eq!(r.scan_tallies.len(), regions.len());
            for (k, t) in r.scan_tallies.iter().enumerate() {
                assert_eq!(t.scans, k as u64 + 1);
            }
            assert_eq!(r.scan_tallies.last().unwrap().scans, r.tally.scans);
        }
    }
}
