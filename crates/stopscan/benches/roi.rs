//! Multi-robot ROI exploration: a random region of 10^6 cells explored by 64 robots (the
//! issue's figure: at most 1 s), and one Fig. 7 point (100 regions of 120 cells, 20 robots).
//! Each workload is checked once before it is timed (every cell visited, every robot home,
//! the time within Lemma 1's bound), and every timed run must end at the same time.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use stopscan::offline::grid::GridBounds;
use stopscan::protocol::CostModel;
use stopscan::sim::Recording;
use stopscan::sim::grid::{Mission, explore};
use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};

/// Explores `roi` with `robots` robots; returns the world explored and the mission.
fn run(roi: &GridRoi, drift: Drift, robots: usize, cost: CostModel) -> (GridWorld, Mission) {
    let mut w = GridWorld::new(roi.clone(), drift, GridSensor::Ideal, 1);
    let m = explore(&mut w, robots, cost, Recording::NONE).unwrap();
    (w, m)
}

/// The checks of a finished run: every cell visited, every robot back at the start, the time
/// within Lemma 1's upper bound. Returns the time.
fn checked(roi: &GridRoi, drift: Drift, robots: usize, cost: CostModel) -> f64 {
    let (w, m) = run(roi, drift, robots, cost);
    assert_eq!(w.visited().len(), roi.len(), "every cell visited");
    assert!(m.team.robots.iter().all(|r| r.done && r.at == roi.start()), "every robot home");
    let time = m.team.makespan();
    let bound = GridBounds::of_world(&w, robots, &cost).lemma1_upper;
    assert!(time <= bound, "time {time} above Lemma 1's {bound}");
    time
}

fn roi(c: &mut Criterion) {
    let cost = CostModel::new(0.0, 0.0, 1.0).unwrap();
    let big = GridRoi::random(1_000_000, 1).unwrap();
    let time = checked(&big, Drift::default(), 64, cost);
    let mut g = c.benchmark_group("roi");
    g.sample_size(10);
    g.bench_function("explore 10^6 cells, 64 robots", |b| {
        b.iter(|| {
            let t = run(&big, Drift::default(), 64, cost).1.team.makespan();
            assert_eq!(t, time);
            black_box(t)
        });
    });
    let small: Vec<GridRoi> = (0..100).map(|s| GridRoi::random(120, s).unwrap()).collect();
    let drift = Drift { speed: 0.4, heading_deg: 90.0 };
    let total: f64 = small.iter().map(|r| checked(r, drift, 20, cost)).sum();
    g.bench_function("fig 7 point: 100 regions of 120 cells, 20 robots, drifting", |b| {
        b.iter(|| {
            let t: f64 = small.iter().map(|r| run(r, drift, 20, cost).1.team.makespan()).sum();
            assert_eq!(t, total);
            black_box(t)
        });
    });
    g.finish();
}

criterion_group!(benches, roi);
criterion_main!(benches);
