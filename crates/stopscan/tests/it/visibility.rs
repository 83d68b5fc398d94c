//! Visibility regions against independent oracles: the angular sweep, brute-force point
//! visibility, and the shared benchmark inputs when `../shared` is present.

use std::path::PathBuf;

use proptest::prelude::*;
use rand::{RngExt, SeedableRng};
use stopscan::algorithm::visibility::sweep::{is_visible, visible_area};
use stopscan::algorithm::visibility::{BoundaryPiece, Visibility};
use stopscan::geometry::{Domain, Location};
use stopscan::kernel::{Point, orient_sign};

/// A seeded pillar forest: a rectangle with disjoint random convex pillars.
fn forest(seed: u64, pillars: usize) -> Domain {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let (w, h) = (20.0, 14.0);
    let mut holes: Vec<Vec<Point>> = Vec::new();
    let mut boxes: Vec<[f64; 4]> = Vec::new();
    for _ in 0..pillars * 20 {
        if holes.len() == pillars {
            break;
        }
        let (cx, cy) = (rng.random_range(1.5..w - 1.5), rng.random_range(1.5..h - 1.5));
        let r = rng.random_range(0.3..1.2);
        let b = [cx - r, cy - r, cx + r, cy + r];
        if boxes.iter().any(|o| {
            b[0] < o[2] + 0.2 && o[0] < b[2] + 0.2 && b[1] < o[3] + 0.2 && o[1] < b[3] + 0.2
        }) {
            continue;
        }
        let k: i32 = rng.random_range(3..7);
        let start: f64 = rng.random_range(0.0..1.0);
        let ring: Vec<Point> = (0..k)
            .map(|i| {
                let a = std::f64::consts::TAU * (start + f64::from(i)) / f64::from(k);
                [cx + r * a.cos(), cy + r * a.sin()]
            })
            .collect();
        boxes.push(b);
        holes.push(ring);
    }
    Domain::new(vec![[0.0, 0.0], [w, 0.0], [w, h], [0.0, h]], holes).unwrap()
}

fn free_point(d: &Domain, rng: &mut impl rand::Rng) -> Point {
    let [lo, hi] = d.bounds();
    loop {
        let p = [rng.random_range(lo[0]..hi[0]), rng.random_range(lo[1]..hi[1])];
        if d.locate(p) == Location::Interior {
            return p;
        }
    }
}

/// Checks every invariant of one region.
fn check_region(v: &Visibility, q: Point, rng: &mut impl rand::Rng, samples: usize) {
    let d = v.domain();
    let r = v.query(q).unwrap();
    let area = r.area();
    assert!(area > 0.0 && area <= d.area() * (1.0 + 1e-12), "area {area}");
    // Star-shaped from q: every edge piece turns counter-clockwise around q (windows are
    // radial, checked below).
    for piece in r.boundary.iter().filter(|b| !matches!(b, BoundaryPiece::Window { .. })) {
        let (a, b) = piece.ends();
        if a != q && b != q {
            assert!(orient_sign(q, a, b) >= 0, "piece {piece:?} runs clockwise");
        }
    }
    // Pieces chain end to start.
    for i in 0..r.boundary.len() {
        let (_, end) = r.boundary[i].ends();
        let (start, _) = r.boundary[(i + 1) % r.boundary.len()].ends();
        assert_eq!(end, start);
    }
    // Windows lie on a ray from q through their reflex vertex, reflex vertex nearer.
    for w in r.windows() {
        if let BoundaryPiece::Window { reflex, far, .. } = *w {
            let (dr, df) =
                ((reflex[0] - q[0]).hypot(reflex[1] - q[1]), (far[0] - q[0]).hypot(far[1] - q[1]));
            assert!(dr <= df);
            let cross = (reflex[0] - q[0]) * (far[1] - q[1]) - (far[0] - q[0]) * (reflex[1] - q[1]);
            assert!(cross.abs() <= 1e-9 * dr * df.max(1.0), "window off its ray: {w:?}");
        }
    }
    // Sampled points: inside the polygon exactly when visible by brute force.
    for _ in 0..samples {
        let p = free_point(d, rng);
        let inside =
            stopscan::kernel::ring_side(&r.polygon, p) != stopscan::kernel::RingSide::Outside;
        assert_eq!(inside, is_visible(d, q, p), "q = {q:?}, p = {p:?}");
    }
}

#[test]
fn expansion_agrees_with_brute_force_on_random_forests() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    for seed in 0..20 {
        let d = forest(seed, 3 + seed as usize % 12);
        let v = Visibility::new(d.clone()).unwrap();
        for _ in 0..5 {
            let q = free_point(&d, &mut rng);
            check_region(&v, q, &mut rng, 60);
            let (a, b) = (v.query(q).unwrap().area(), visible_area(&d, q));
            assert!((a - b).abs() <= 1e-9 * b, "seed {seed} q {q:?}: expansion {a} vs sweep {b}");
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 48, rng_seed: proptest::test_runner::RngSeed::Fixed(3), ..ProptestConfig::default() })]

    #[test]
    fn expansion_equals_sweep(seed in 0u64..10_000, pillars in 1usize..20, qs in any::<u64>()) {
        let d = forest(seed, pillars);
        let v = Visibility::new(d.clone()).unwrap();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(qs);
        let q = free_point(&d, &mut rng);
        let (a, b) = (v.query(q).unwrap().area(), visible_area(&d, q));
        prop_assert!((a - b).abs() <= 1e-9 * b, "{a} vs {b}");
    }
}

/// A file of the shared visibility benchmark beside the checkout; panics when it is absent
/// (the tests that need it are ignored by default, and must fail, not pass, without it).
fn shared(name: &str) -> PathBuf {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../../shared/bench/visibility")
        .join(name);
    assert!(p.exists(), "{} is absent: run beside ../shared, or without --ignored", p.display());
    p
}

// env_100.txt states no licence, so it is not copied into fixtures/.
#[test]
#[ignore = "needs ../shared/bench/visibility/env_100.txt (no stated licence, not vendored)"]
fn shared_benchmark_agrees_with_the_sweep() {
    let path = shared("env_100.txt");
    let env = stopscan::io::bench_format::read(&path).unwrap();
    let v = Visibility::new(env.domain.clone()).unwrap();
    for &q in &env.queries {
        let (a, b) = (v.query(q).unwrap().area(), visible_area(&env.domain, q));
        assert!((a - b).abs() <= 1e-9 * b, "q {q:?}: {a} vs {b}");
    }
}

#[test]
fn collinear_chains_and_rays_through_vertices() {
    // A comb whose teeth line up: rays from the viewpoint pass through several vertices.
    let outer =
        vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0], [6.0, 0.0], [6.0, 4.0], [0.0, 4.0]];
    let holes = vec![
        vec![[1.0, 1.0], [1.0, 2.0], [2.0, 2.0], [2.0, 1.0]],
        vec![[3.0, 1.0], [3.0, 2.0], [4.0, 2.0], [4.0, 1.0]],
    ];
    let d = Domain::new(outer, holes).unwrap();
    let v = Visibility::new(d.clone()).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
    // On the line y = 1 through four hole vertices, and y = 2 likewise.
    for q in [[0.5, 1.0], [0.5, 2.0], [5.0, 1.0], [0.5, 0.5], [5.5, 3.0]] {
        check_region(&v, q, &mut rng, 200);
        let (a, b) = (v.query(q).unwrap().area(), visible_area(&d, q));
        assert!((a - b).abs() <= 1e-9 * b, "q {q:?}: {a} vs {b}");
    }
}

#[test]
fn queries_on_vertices_and_edges() {
    let d = forest(7, 6);
    let v = Visibility::new(d.clone()).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
    let mut qs: Vec<Point> = d.rings().iter().flatten().copied().collect();
    for ring in d.rings() {
        for i in 0..ring.len() {
            let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
            qs.push([0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
        }
    }
    for q in qs {
        if d.locate(q) == Location::Outside {
            assert!(v.query(q).is_err(), "the mesh and the exact locator disagree at {q:?}");
            continue;
        }
        // A float midpoint of a slanted edge is usually not exactly on it; the exact locator
        // decides which convention applies.
        if d.locate(q) == Location::Boundary {
            assert_eq!(
                v.query(q).unwrap().polygon[0],
                q,
                "a boundary query starts its polygon at itself"
            );
        }
        check_region(&v, q, &mut rng, 40);
    }
}

#[test]
fn orthogonal_polygon_queries_on_vertices() {
    // CGAL's issue 6995: an orthogonal polygon, queries on its vertices.
    let outer = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]];
    let holes = vec![vec![[0.5, 0.5], [0.5, 1.0], [1.0, 1.0], [1.0, 0.5]]];
    let d = Domain::new(outer, holes).unwrap();
    let v = Visibility::new(d.clone()).unwrap();
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
    for &q in d.rings().iter().flatten() {
        check_region(&v, q, &mut rng, 300);
    }
}

#[test]
fn outside_is_an_error() {
    let d = forest(1, 3);
    let v = Visibility::new(d.clone()).unwrap();
    assert!(v.query([-1.0, 5.0]).is_err());
    assert!(v.query([f64::NAN, 5.0]).is_err());
    let c = d.holes()[0].iter().fold([0.0, 0.0], |s, p| [s[0] + p[0], s[1] + p[1]]);
    let n = d.holes()[0].len() as f64;
    assert!(v.query([c[0] / n, c[1] / n]).is_err());
}

#[test]
fn range_limited_regions_match_the_sweep_and_brute_force() {
    use stopscan::algorithm::visibility::sweep::visible_area_within;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(21);
    for seed in 0..15 {
        let d = forest(100 + seed, 2 + seed as usize % 10);
        let v = Visibility::new(d.clone()).unwrap();
        for _ in 0..4 {
            let q = free_point(&d, &mut rng);
            let r = rng.random_range(0.2..12.0);
            let region = v.query_range(q, r).unwrap();
            let (a, b) = (region.area(), visible_area_within(&d, q, r));
            assert!((a - b).abs() <= 1e-9 * b, "seed {seed} q {q:?} R {r}: {a} vs {b}");
            assert!(a <= std::f64::consts::PI * r * r * (1.0 + 1e-12));
            assert!(a <= v.query(q).unwrap().area() * (1.0 + 1e-12));
            // The polygonal approximation is within its tolerance: points well inside the disk
            // are classified like the exact region.
            let tol = 1e-6 * r;
            let poly = region.to_polygon(tol);
            let approx = stopscan::algorithm::visibility::polygon_area_of(q, &poly);
            assert!(
                b - approx >= -1e-9 * b
                    && b - approx <= tol * 2.0 * std::f64::consts::PI * r + 1e-9 * b
            );
            for _ in 0..40 {
                let p = free_point(&d, &mut rng);
                let dist = (p[0] - q[0]).hypot(p[1] - q[1]);
                if (dist - r).abs() < 1e-3 * r {
                    continue;
                }
                let inside =
                    stopscan::kernel::ring_side(&poly, p) != stopscan::kernel::RingSide::Outside;
                assert_eq!(inside, dist < r && is_visible(&d, q, p), "q {q:?} p {p:?} R {r}");
            }
        }
    }
    // Nothing within range: the whole disk.
    let d = forest(3, 2);
    let v = Visibility::new(d.clone()).unwrap();
    let q = free_point(&d, &mut rng);
    let r = v.query_range(q, 1e-3).unwrap();
    assert!((r.area() - std::f64::consts::PI * 1e-6).abs() < 1e-15);
}

#[test]
fn regions_seen_from_all_vertices_cover_the_free_space() {
    use stopscan::algorithm::region::Region;
    for seed in 0..6 {
        let d = forest(200 + seed, 4 + seed as usize);
        let v = Visibility::new(d.clone()).unwrap();
        let polys: Vec<Vec<Point>> =
            d.rings().iter().flatten().map(|&p| v.query(p).unwrap().polygon).collect();
        let covered = Region::union_all(&polys);
        assert!(
            (covered.area() - d.area()).abs() <= 1e-7 * d.area(),
            "seed {seed}: {} vs {}",
            covered.area(),
            d.area()
        );
        let missing = Region::of_domain(&d).difference(&covered);
        assert!(missing.area() <= 1e-7 * d.area(), "uncovered {}", missing.area());
    }
}

#[test]
fn shortest_paths_match_a_dijkstra_over_all_vertices() {
    use stopscan::algorithm::shortest_path::PathPlanner;
    use stopscan::kernel::{RingSide, ring_side};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(77);
    for seed in 0..8 {
        let d = forest(300 + seed, 3 + seed as usize);
        let v = Visibility::new(d.clone()).unwrap();
        let planner = PathPlanner::new(&v);
        let verts: Vec<Point> = d.rings().iter().flatten().copied().collect();
        for _ in 0..4 {
            let (s, t) = (free_point(&d, &mut rng), free_point(&d, &mut rng));
            let path = planner.shortest_path(s, t).unwrap();
            // Every segment stays in the free space (sampled), and the path is connected.
            assert_eq!(path.points.first(), Some(&s));
            assert_eq!(path.points.last(), Some(&t));
            for w in path.points.windows(2) {
                for k in 0..=50 {
                    let u = f64::from(k) / 50.0;
                    let p = [w[0][0] + u * (w[1][0] - w[0][0]), w[0][1] + u * (w[1][1] - w[0][1])];
                    assert_ne!(
                        d.locate(p),
                        Location::Outside,
                        "segment {w:?} leaves the free space at {p:?}"
                    );
                }
            }
            // Oracle: Dijkstra over s, t and all vertices; u sees x when x lies in u's region.
            let mut nodes = vec![s, t];
            nodes.extend(&verts);
            let regions: Vec<Vec<Point>> =
                nodes.iter().map(|&p| v.query(p).unwrap().polygon).collect();
            let n = nodes.len();
            let mut g = vec![f64::INFINITY; n];
            let mut done = vec![false; n];
            g[0] = 0.0;
            for _ in 0..n {
                let Some(k) = (0..n).filter(|&k| !done[k]).min_by(|&a, &b| g[a].total_cmp(&g[b]))
                else {
                    break;
                };
                done[k] = true;
                for m in 0..n {
                    if !done[m] && ring_side(&regions[k], nodes[m]) != RingSide::Outside {
                        let c = g[k] + (nodes[k][0] - nodes[m][0]).hypot(nodes[k][1] - nodes[m][1]);
                        if c < g[m] {
                            g[m] = c;
                        }
                    }
                }
            }
            assert!(
                (path.length - g[1]).abs() <= 1e-9 * g[1],
                "seed {seed}: planner {} vs oracle {}",
                path.length,
                g[1]
            );
        }
    }
}
