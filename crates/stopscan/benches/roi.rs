//! Multi-robot ROI exploration: a random region of 10^6 cells explored by 64 robots (the
//! issue's figure: at most 1 s), and one Fig. 7 point (100 regions of 120 cells, 20 robots).

use criterion::{Criterion, criterion_group, criterion_main};
use stopscan::protocol::CostModel;
use stopscan::sim::Recording;
use stopscan::sim::grid::explore;
use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};

fn roi(c: &mut Criterion) {
    let cost = CostModel::new(0.0, 0.0, 1.0).unwrap();
    let big = GridRoi::random(1_000_000, 1).unwrap();
    let mut g = c.benchmark_group("roi");
    g.sample_size(10);
    g.bench_function("explore 10^6 cells, 64 robots", |b| {
        b.iter(|| {
            let mut w = GridWorld::new(big.clone(), Drift::default(), GridSensor::Ideal, 1);
            explore(&mut w, 64, cost, Recording::NONE).unwrap().team.makespan()
        });
    });
    let small: Vec<GridRoi> = (0..100).map(|s| GridRoi::random(120, s).unwrap()).collect();
    g.bench_function("fig 7 point: 100 regions of 120 cells, 20 robots, drifting", |b| {
        b.iter(|| {
            small
                .iter()
                .map(|r| {
                    let d = Drift { speed: 0.4, heading_deg: 90.0 };
                    let mut w = GridWorld::new(r.clone(), d, GridSensor::Ideal, 1);
                    explore(&mut w, 20, cost, Recording::NONE).unwrap().team.makespan()
                })
                .sum::<f64>()
        });
    });
    g.finish();
}

criterion_group!(benches, roi);
criterion_main!(benches);
