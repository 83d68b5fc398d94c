//! Criterion benchmark of polygon exploration: the paper's depth-first algorithm on a
//! 1,524-vertex office floor (88 rooms, desks), world preprocessing included. The run is
//! checked before it is timed (within the paper's r + 1 scans, no window left open) and each
//! timed run must take the same number of scans.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use stopscan::algorithm::cover::open_windows;
use stopscan::generate::office;
use stopscan::geometry::Location;
use stopscan::protocol::CostModel;
use stopscan::sim::NoObserver;
use stopscan::sim::polygon::run;
use stopscan::strategy::polygon::DepthFirst;
use stopscan::world::polygon::PolygonWorld;

fn explore_office(c: &mut Criterion) {
    let inst = office(40, 220, 1).unwrap();
    let explore = || {
        let world = PolygonWorld::new(inst.domain.clone()).unwrap();
        run(&world, inst.start, &CostModel::default(), &mut DepthFirst::new(), &mut NoObserver)
            .unwrap()
    };
    let first = explore();
    let regions: Vec<_> = first.scans.iter().map(|s| s.region.clone()).collect();
    let reflex = inst.domain.reflex_vertices().len();
    assert!(first.tally.scans as usize <= reflex + 1, "{} scans, r = {reflex}", first.tally.scans);
    assert_eq!(open_windows(&regions, |p| inst.domain.locate(p) == Location::Interior), 0);
    let scans = first.tally.scans;
    let mut g = c.benchmark_group("explore");
    g.sample_size(20);
    g.bench_function(format!("depth_first/office_v={}", inst.domain.vertex_count()), |b| {
        b.iter(|| {
            let r = explore();
            assert_eq!(r.tally.scans, scans);
            black_box(r.tally.scans)
        });
    });
    g.finish();
}

criterion_group!(benches, explore_office);
criterion_main!(benches);
