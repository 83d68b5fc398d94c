//! Criterion benchmark of polygon exploration: the paper's depth-first algorithm on a
//! 1,524-vertex office floor (88 rooms, desks), world preprocessing included.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use stopscan::generate::office;
use stopscan::protocol::CostModel;
use stopscan::sim::NoObserver;
use stopscan::sim::polygon::run;
use stopscan::strategy::polygon::DepthFirst;
use stopscan::world::polygon::PolygonWorld;

fn explore_office(c: &mut Criterion) {
    let inst = office(40, 220, 1).unwrap();
    let mut g = c.benchmark_group("explore");
    g.sample_size(20);
    g.bench_function(format!("depth_first/office_v={}", inst.domain.vertex_count()), |b| {
        b.iter(|| {
            let world = PolygonWorld::new(inst.domain.clone()).unwrap();
            let r = run(
                &world,
                inst.start,
                &CostModel::default(),
                &mut DepthFirst::new(),
                &mut NoObserver,
            )
            .unwrap();
            black_box(r.tally.scans)
        });
    });
    g.finish();
}

criterion_group!(benches, explore_office);
criterion_main!(benches);
