//! A robot with a footprint (issue 12): every move keeps the robot in the free space,
//! checked here from the definition (the distance from every driven segment to every
//! boundary edge), independently of the configuration space the world builds; a corridor
//! narrower than the robot is never entered and what lies beyond it is reported apart.

use stopscan::generate::{Instance, comb, office, pillar_forest, star};
use stopscan::geometry::{Domain, segments_distance};
use stopscan::kernel::Point;
use stopscan::protocol::CostModel;
use stopscan::protocol::polygon::{Footprint, RobotSetup, Sensor};
use stopscan::sim::NoObserver;
use stopscan::sim::polygon::run;
use stopscan::strategy::polygon::{REGISTRY, build_for};
use stopscan::world::polygon::PolygonWorld;

/// The least distance from the polyline to the domain's boundary (brute force).
fn clearance_of(path: &[Point], d: &Domain) -> f64 {
    let mut best = f64::INFINITY;
    for w in path.windows(2) {
        for ring in d.rings() {
            for i in 0..ring.len() {
                let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
                best = best.min(segments_distance(w[0], w[1], a, b));
            }
        }
    }
    best
}

fn setup(radius: f64) -> RobotSetup {
    RobotSetup {
        cost: CostModel::default(),
        footprint: Footprint::disc(radius).unwrap(),
        sensor: Sensor { min_window: 2.0 * radius, ..Sensor::default() },
    }
}

/// Every strategy on `inst` with a disc robot: the run ends normally, and the path keeps
/// the radius from every wall.
fn check(inst: &Instance, radius: f64, what: &str) {
    let s = setup(radius);
    let Ok(world) = PolygonWorld::with_robot(inst.domain.clone(), Some(20.0), &s.footprint, None)
    else {
        return; // the footprint fits nowhere: nothing to drive
    };
    let start = world.reach().unwrap().start();
    for name in REGISTRY.names() {
        let mut strategy = build_for(name, &s).unwrap();
        let r = run(&world, start, &s.cost, strategy.as_mut(), &mut NoObserver)
            .unwrap_or_else(|e| panic!("{what} / {name}: {e}"));
        if r.path.len() >= 2 {
            let c = clearance_of(&r.path, &inst.domain);
            assert!(c >= radius * (1.0 - 1e-9), "{what} / {name}: clearance {c} < {radius}");
        }
        assert!(r.tally.scans >= 1);
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(16))]

    #[test]
    fn paths_keep_the_robot_off_the_walls(kind in 0usize..4, seed in 0u64..1000, r in 0.05..0.4f64) {
        let inst = match kind {
            0 => office(1 + (seed % 4) as usize, (seed % 7) as usize, seed).unwrap(),
            1 => pillar_forest(20.0, 14.0, 1 + (seed % 10) as usize, seed).unwrap(),
            2 => comb(1 + (seed % 5) as usize).unwrap(),
            _ => star(3 + (seed % 6) as usize).unwrap(),
        };
        check(&inst, r, "generated");
    }
}

#[test]
fn a_corridor_narrower_than_the_robot_is_never_entered() {
    // A 6 × 4 room; from its right wall a 0.3 m wide, 3 m long corridor leads to a 3 × 3
    // room. A robot of radius 0.2 (0.4 m wide) cannot pass it.
    let outer = vec![
        [0.0, 0.0],
        [6.0, 0.0],
        [6.0, 1.85],
        [9.0, 1.85],
        [9.0, 0.5],
        [12.0, 0.5],
        [12.0, 3.5],
        [9.0, 3.5],
        [9.0, 2.15],
        [6.0, 2.15],
        [6.0, 4.0],
        [0.0, 4.0],
    ];
    let d = Domain::new(outer, vec![]).unwrap();
    let s = setup(0.2);
    let world = PolygonWorld::with_robot(d.clone(), None, &s.footprint, Some([1.0, 2.0])).unwrap();
    for name in ["depth_first", "nearest_frontier", "greedy_nbv", "cost_aware"] {
        let mut strategy = build_for(name, &s).unwrap();
        let r = run(&world, [1.0, 2.0], &s.cost, strategy.as_mut(), &mut NoObserver).unwrap();
        assert!(r.path.iter().all(|p| p[0] < 6.0), "{name} entered the corridor: {:?}", r.path);
    }
    // The far room is reported as out of reach: the configuration space ends at the room.
    let reach = world.reach().unwrap();
    assert!(reach.domain().rings().iter().flatten().all(|p| p[0] < 6.0));
    let samples = stopscan::offline::polygon::reach::reachable_samples(&world);
    let seen = stopscan::offline::polygon::reach::visible_from(&world, &samples, &[]);
    let lost = stopscan::offline::polygon::reach::unreachable_area(&world, &seen);
    // The far room (9 m²) is mostly hidden; the corridor is seen down its length.
    assert!(lost > 5.0 && lost <= 9.0 + 0.9, "{lost}");
}

#[test]
fn a_start_too_close_to_a_wall_is_refused_with_the_reason() {
    let d = Domain::new(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]], vec![]).unwrap();
    let e = PolygonWorld::with_robot(d, None, &Footprint::disc(0.5).unwrap(), Some([0.2, 2.0]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("does not fit at the start (0.2, 2)"), "{e}");
}
