//! Criterion benchmarks of preprocessing, visibility queries and region unions.
//!
//! Uses `shared/bench/visibility/env_*.txt` when the shared folder sits beside the
//! repository, and a generated pillar forest otherwise.

use std::hint::black_box;
use std::path::PathBuf;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use stopscan::algorithm::region::Region;
use stopscan::algorithm::visibility::range::clip;
use stopscan::algorithm::visibility::{Visibility, VisibilityRegion, expansion};
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
        g.bench_with_input(BenchmarkId::new("preprocess", &name), &d, |b, d| {
            b.iter(|| black_box(Visibility::new(d.clone()).unwrap()));
        });
        let v = Visibility::new(d.clone()).unwrap();
        let mut s = expansion::Scratch::default();
        let mut r = VisibilityRegion::default();
        g.bench_function(BenchmarkId::new("1000_queries", &name), |b| {
            b.iter(|| {
                for &q in &qs {
                    v.query_into(q, &mut s, &mut r).unwrap();
                }
                black_box(&r);
            });
        });
        g.bench_function(BenchmarkId::new("1000_range_queries_r5", &name), |b| {
            b.iter(|| {
                for &q in &qs {
                    v.query_into(q, &mut s, &mut r).unwrap();
                    black_box(clip(&r, 5.0));
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
    let mut g = c.benchmark_group("region_union_of_100_visibility_regions");
    g.sample_size(10);
    g.bench_function("balanced_tree", |b| b.iter(|| black_box(Region::union_all(&polys).area())));
    g.bench_function("one_overlay", |b| b.iter(|| black_box(Region::overlay_all(&polys).area())));
    g.bench_function("pairwise_fold", |b| {
        b.iter(|| {
            let acc = polys.iter().fold(Region::empty(), |acc, p| acc.union(&Region::polygon(p)));
            black_box(acc.area())
        });
    });
    g.finish();
}

criterion_group!(benches, visibility, regions);
criterion_main!(benches);
