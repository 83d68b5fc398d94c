//! Criterion benchmarks of preprocessing, visibility queries and region unions.
//!
//! Uses `shared/bench/visibility/env_*.txt` when the shared folder sits beside the
//! repository, and a generated pillar forest otherwise. Each checks what it computes: the
//! triangulation has the n + 2h − 2 triangles of a polygon with h holes, the first queries
//! agree with the independent angular sweep, every region lies within the free space (and a
//! ranged one within the range's disk), and the three ways of uniting regions give one area.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use stopscan::algorithm::region::Region;
use stopscan::algorithm::visibility::range::clip;
use stopscan::algorithm::visibility::{Visibility, VisibilityRegion, expansion, sweep};
use stopscan::geometry::Domain;
use stopscan::kernel::Point;

fn inputs() -> Vec<(String, Domain, Vec<Point>)> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/bench/visibility");
    let mut out = Vec::new();
    for name in ["env_1k", "env_10k", "env_100k"] {
        if let Ok(e) = stopscan::io::bench_format::read(&dir.join(format!("{name}.txt"))) {
            out.push((name.to_string(), e.domain, e.queries));
        }
    }
    if out.is_empty() {
        // A grid of square pillars.
        let n = 30;
        let holes = (0..n * n)
            .map(|k| {
                let (x, y) = (f64::from(k % n) * 3.0 + 1.0, f64::from(k / n) * 3.0 + 1.0);
                vec![[x, y], [x, y + 1.0], [x + 1.0, y + 1.0], [x + 1.0, y]]
            })
            .collect();
        let s = f64::from(n) * 3.0;
        let d = Domain::new(vec![[0.0, 0.0], [s, 0.0], [s, s], [0.0, s]], holes).unwrap();
        let q = (0..1000)
            .map(|i| [0.5 + f64::from(i % 30) * 3.0, 0.5 + f64::from(i / 30 % 30) * 3.0])
            .collect();
        out.push(("grid_3600".into(), d, q));
    }
    out
}

fn visibility(c: &mut Criterion) {
    let mut g = c.benchmark_group("visibility");
    g.sample_size(10);
    for (name, d, qs) in inputs() {
        // A triangulation of a polygon with h holes and n vertices in all, without extra
        // points, has n + 2h − 2 triangles.
        let triangles = d.vertex_count() + 2 * d.holes().len() - 2;
        g.bench_with_input(BenchmarkId::new("preprocess", &name), &d, |b, d| {
            b.iter(|| {
                let v = Visibility::new(d.clone()).unwrap();
                assert_eq!(v.mesh().triangles(), triangles);
                black_box(v)
            });
        });
        let v = Visibility::new(d.clone()).unwrap();
        // The expansion against the independent O(n²) angular sweep, on as many queries as
        // 10^8 steps of the sweep afford (20 at most; none on 100,000 vertices).
        let checked = (100_000_000 / d.vertex_count().pow(2).max(1)).min(20);
        for &q in qs.iter().take(checked) {
            let (fast, slow) = (v.query(q).unwrap().area(), sweep::visible_area(&d, q));
            assert!((fast - slow).abs() <= 1e-9 * slow, "{name} at {q:?}: {fast} vs {slow}");
        }
        let free = d.area() * (1.0 + 1e-9);
        let mut s = expansion::Scratch::default();
        let mut r = VisibilityRegion::default();
        g.bench_function(BenchmarkId::new("1000_queries", &name), |b| {
            b.iter(|| {
                for &q in &qs {
                    v.query_into(q, &mut s, &mut r).unwrap();
                    assert!(r.area() <= free, "{name} at {q:?}");
                }
                black_box(&r);
            });
        });
        let disk = std::f64::consts::PI * 25.0 * (1.0 + 1e-9);
        g.bench_function(BenchmarkId::new("1000_range_queries_r5", &name), |b| {
            b.iter(|| {
                for &q in &qs {
                    v.query_into(q, &mut s, &mut r).unwrap();
                    let ranged = clip(&r, 5.0);
                    assert!(ranged.area() <= disk.min(r.area() * (1.0 + 1e-9)), "{name} at {q:?}");
                    black_box(ranged);
                }
            });
        });
    }
    g.finish();
}

fn regions(c: &mut Criterion) {
    let (_, d, qs) = inputs().remove(0);
    let v = Visibility::new(d).unwrap();
    let polys: Vec<Vec<Point>> =
        qs.iter().take(100).map(|&q| v.query(q).unwrap().polygon).collect();
    // The three ways must agree on the area of the union, which lies within the free space
    // and covers the largest single region. i_overlay snaps to an integer grid, and the three
    // orders of operations snap differently: they agree to about 1e-8 of the area.
    let want = Region::union_all(&polys).area();
    let largest = polys.iter().map(|p| Region::polygon(p).area()).fold(0.0, f64::max);
    assert!(want <= v.domain().area() * (1.0 + 1e-6) && want >= largest * (1.0 - 1e-6));
    let same = move |area: f64| {
        assert!((area - want).abs() <= 1e-6 * want, "{area} vs {want}");
        area
    };
    let mut g = c.benchmark_group("region_union_of_100_visibility_regions");
    g.sample_size(10);
    g.bench_function("balanced_tree", |b| {
        b.iter(|| black_box(same(Region::union_all(&polys).area())));
    });
    g.bench_function("one_overlay", |b| {
        b.iter(|| black_box(same(Region::overlay_all(&polys).area())));
    });
    g.bench_function("pairwise_fold", |b| {
        b.iter(|| {
            let acc = polys.iter().fold(Region::empty(), |acc, p| acc.union(&Region::polygon(p)));
            black_box(same(acc.area()))
        });
    });
    g.finish();
}

criterion_group!(benches, visibility, regions);
criterion_main!(benches);
