//! A robot with a footprint (issue 12): every move keeps the robot in the free space,
//! checked here from the definition (the distance from every driven segment to every
//! boundary edge), independently of the configuration space the world builds; a corridor
//! narrower than the robot is never entered and what lies beyond it is reported apart.

use stopscan::generate::{Instance, comb, office, pillar_forest, star};
use stopscan::geometry::{Domain, Location, segments_distance};
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

/// A case the property test once found: a window passing nearer the viewpoint than the
/// clearance must not let a move keep less (that relaxation is for raw scans only).
#[test]
fn an_office_case_keeps_the_clearance_near_a_window() {
    let seed = 714;
    let inst = office(1 + (seed % 4) as usize, (seed % 7) as usize, seed).unwrap();
    check(&inst, 0.348_787_253_784_284_43, "office 714");
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
fn the_body_space_leaves_out_crevices_narrower_than_the_robot() {
    // A 4 × 4 room with a slot 0.2 m wide and 1.5 m deep off its top wall: a robot 0.4 m
    // wide reaches the whole room with its body (less a hair in each corner), and not the slot.
    let outer = vec![
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [2.1, 4.0],
        [2.1, 5.5],
        [1.9, 5.5],
        [1.9, 4.0],
        [0.0, 4.0],
    ];
    let d = Domain::new(outer, vec![]).unwrap();
    let r = 0.2;
    let world =
        PolygonWorld::with_robot(d.clone(), None, &Footprint::disc(r).unwrap(), Some([2.0, 2.0]))
            .unwrap();
    let body = stopscan::offline::polygon::reach::body_space(&world).unwrap();
    // From the definition: a grid point is in the body space when a point within r of it
    // (sampled on rings around it) keeps r from every wall.
    let step = 0.05;
    let (mut inside, mut mismatched) = (0usize, 0usize);
    for i in 0..80 {
        for j in 0..110 {
            let q = [(f64::from(i) + 0.5) * step, (f64::from(j) + 0.5) * step];
            if d.locate(q) != Location::Interior {
                continue;
            }
            let fits = (0..=10).any(|k| {
                let rho = r * f64::from(k) / 10.0;
                (0..64).any(|a| {
                    let t = std::f64::consts::TAU * f64::from(a) / 64.0;
                    let p = [q[0] + rho * t.cos(), q[1] + rho * t.sin()];
                    d.locate(p) == Location::Interior && wall_distance(&d, p) >= r
                })
            });
            if fits {
                inside += 1;
                assert!(q[1] < 4.05, "the slot at {q:?} counted as body space");
            }
            if fits != body.contains(q) {
                mismatched += 1;
            }
        }
    }
    // Only grid points within a sample's spacing of the body space's edge may disagree.
    assert!(mismatched * 100 < inside, "{mismatched} of {inside} grid points disagree");
    let brute = inside as f64 * step * step;
    let a = body.area();
    assert!((a - brute).abs() < 0.02 * brute, "body space {a} m², brute force {brute} m²");
    // The room less a sliver in each corner (r² − πr²/4 each), and nothing of the slot.
    let room = 16.0 - 4.0 * r * r * (1.0 - std::f64::consts::FRAC_PI_4);
    assert!(a > room - 1e-3 && a < room + 0.01, "{a}");
}

#[test]
fn a_start_too_close_to_a_wall_is_refused_with_the_reason() {
    let d = Domain::new(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]], vec![]).unwrap();
    let e = PolygonWorld::with_robot(d, None, &Footprint::disc(0.5).unwrap(), Some([0.2, 2.0]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("does not fit at the start (0.2, 2)"), "{e}");
}

/// Whether `a` sees `b` in `d`: the segment crosses no boundary edge and its middle is free
/// (brute force, from the definition).
fn sees(d: &Domain, a: Point, b: Point) -> bool {
    let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
    d.locate(mid) == Location::Interior
        && d.rings().iter().all(|ring| {
            (0..ring.len()).all(|i| {
                let (p, q) = (ring[i], ring[(i + 1) % ring.len()]);
                !stopscan::kernel::segments_intersect(a, b, p, q)
                    || stopscan::kernel::on_segment(p, q, b)
                    || stopscan::kernel::on_segment(p, q, a)
            })
        })
}

/// The least distance from `p` to the domain's boundary (brute force).
fn wall_distance(d: &Domain, p: Point) -> f64 {
    clearance_of(&[p, p], d)
}

/// The share of free sample points (a `step` grid) seen from some reachable sample point that
/// some scan sees too: reachable points are free grid points (every `step`) at least `radius`
/// from every wall (the domain here is one room-and-door component, so all are connected).
fn brute_coverage(d: &Domain, radius: f64, scans: &[Point], step: f64) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in d.rings().iter().flatten() {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let grid = |s: f64| {
        let mut out = Vec::new();
        let mut y = lo[1] + 0.5 * s;
        while y < hi[1] {
            let mut x = lo[0] + 0.5 * s;
            while x < hi[0] {
                if d.locate([x, y]) == Location::Interior {
                    out.push([x, y]);
                }
                x += s;
            }
            y += s;
        }
        out
    };
    let reachable: Vec<Point> =
        grid(step).into_iter().filter(|&p| wall_distance(d, p) >= radius * 1.05).collect();
    let (mut visible, mut covered) = (0usize, 0usize);
    for p in grid(step) {
        if reachable.iter().any(|&q| sees(d, q, p)) {
            visible += 1;
            if scans.iter().any(|&s| sees(d, s, p)) {
                covered += 1;
            }
        }
    }
    covered as f64 / visible.max(1) as f64
}

/// Two 4 × 4 rooms, one above the other, joined by a door `x0 ≤ x ≤ x1` in a wall 0.2 m
/// thick (4 ≤ y ≤ 4.2).
fn two_rooms(x0: f64, x1: f64) -> Domain {
    let outer = vec![
        [0.0, 0.0],
        [4.0, 0.0],
        [4.0, 4.0],
        [x1, 4.0],
        [x1, 4.2],
        [4.0, 4.2],
        [4.0, 8.2],
        [0.0, 8.2],
        [0.0, 4.2],
        [x0, 4.2],
        [x0, 4.0],
        [0.0, 4.0],
    ];
    Domain::new(outer, vec![]).unwrap()
}

/// Every strategy with a 0.2 m robot from `start` in the lower of [`two_rooms`]: it keeps
/// the clearance, passes the door, and sees at least 99% of what its reachable region sees
/// (brute force on a 0.2 m grid).
fn every_strategy_passes_the_door(d: &Domain, start: Point) {
    let s = setup(0.2);
    let world = PolygonWorld::with_robot(d.clone(), None, &s.footprint, Some(start)).unwrap();
    for name in REGISTRY.names() {
        let mut strategy = build_for(name, &s).unwrap();
        let r = run(&world, start, &s.cost, strategy.as_mut(), &mut NoObserver)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let c = clearance_of(&r.path, d);
        assert!(c >= 0.2 * (1.0 - 1e-9), "{name}: clearance {c}");
        assert!(r.path.iter().any(|p| p[1] > 4.2), "{name} never passed the door: {:?}", r.path);
        let at: Vec<Point> = r.scans.iter().map(|o| o.at).collect();
        let cov = brute_coverage(d, 0.2, &at, 0.2);
        assert!(cov >= 0.99, "{name}: {cov} of what the reachable region sees, scans at {at:?}");
    }
}

#[test]
fn a_door_seen_at_a_slant_is_still_passed() {
    // The only door (0.8 m, for a robot 0.4 m wide) is near the right wall, and the robot
    // starts in the lower room's far corner: every window through the door is steep.
    every_strategy_passes_the_door(&two_rooms(3.0, 3.8), [0.4, 0.4]);
}

#[test]
fn a_door_with_a_few_centimetres_to_spare_is_passed_by_every_strategy() {
    // A door 0.45 m wide for a robot 0.4 m wide. An occupancy raster loses up to a cell on
    // each side of it to rounding (the explore_lite baseline at 0.025 m cells kept this door
    // closed until its cell size was fitted to the clearance).
    every_strategy_passes_the_door(&two_rooms(1.8125, 2.2625), [2.0, 2.0]);
}

/// Runs every strategy on `inst` with a 0.2 m robot and a 20 m range from the roomiest
/// start, and asserts that each sees at least 99% of what its reachable region sees (brute
/// force on a `step` grid).
fn every_strategy_covers(inst: &Instance, step: f64, what: &str) {
    let s = setup(0.2);
    let world =
        PolygonWorld::with_robot(inst.domain.clone(), Some(20.0), &s.footprint, None).unwrap();
    let start = world.reach().unwrap().start();
    for name in REGISTRY.names() {
        let mut strategy = build_for(name, &s).unwrap();
        let r = run(&world, start, &s.cost, strategy.as_mut(), &mut NoObserver)
            .unwrap_or_else(|e| panic!("{what} / {name}: {e}"));
        let at: Vec<Point> = r.scans.iter().map(|o| o.at).collect();
        let cov = brute_coverage(&inst.domain, 0.2, &at, step);
        assert!(cov >= 0.99, "{what} / {name}: {cov}");
    }
}

#[test]
fn office_floors_are_covered_with_a_footprint() {
    for seed in [3u64, 8] {
        let inst = office(2, (seed % 4) as usize, seed).unwrap();
        every_strategy_covers(&inst, 0.25, &format!("office {seed}"));
    }
}

#[test]
fn space_bounded_only_by_windows_out_of_reach_is_still_visited() {
    // An office of 12 rooms with desks. Behind one desk lies space bounded by a window of
    // the view taken in the room (whose far side corridor views see, through the door) and
    // by windows of those corridor views, which no viewpoint in their own regions reaches
    // with the clearance. It is reached from the region of the view inside the room (the
    // nearest-frontier run left 1.5% of what the reachable region sees unseen there).
    every_strategy_covers(&office(4, 10, 106).unwrap(), 0.4, "office 106");
}

/// `cost_aware` drives between its scans along the shortest ways through what it has seen
/// (Dijkstra's algorithm over the safe cells of its raster of the views), not along the
/// tree of moves between viewpoints: over three office floors its path is within 12% of
/// the shortest paths between its consecutive scans in the true configuration space
/// (computed here by the exact reflex-vertex visibility graph). Along the tree of moves,
/// with its corners cut inside single views' regions, it was 15% longer (578 m against
/// 501 m; now 487 m against 449 m).
#[test]
fn cost_aware_drives_nearly_the_shortest_ways_between_its_scans() {
    use stopscan::algorithm::shortest_path::PathPlanner;
    let s = RobotSetup {
        cost: CostModel { scan_time: 30.0, move_time: 0.0, speed: 0.5 },
        sensor: Sensor { range: Some(20.0), ..setup(0.2).sensor },
        ..setup(0.2)
    };
    let (mut driven, mut shortest) = (0.0, 0.0);
    for seed in [2u64, 4, 9] {
        let rooms = 2 + (seed * 7 % 5) as usize;
        let inst = office(rooms, (seed * 13 % (3 * rooms as u64)) as usize, seed).unwrap();
        let world =
            PolygonWorld::with_robot(inst.domain.clone(), Some(20.0), &s.footprint, None).unwrap();
        let start = world.reach().unwrap().start();
        let mut strategy = build_for("cost_aware", &s).unwrap();
        let r = run(&world, start, &s.cost, strategy.as_mut(), &mut NoObserver).unwrap();
        let c = clearance_of(&r.path, &inst.domain);
        assert!(c >= 0.2 * (1.0 - 1e-9), "office {seed}: clearance {c}");
        driven +=
            r.path.windows(2).map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1])).sum::<f64>();
        let planner = PathPlanner::new(world.moves());
        for w in r.scans.windows(2) {
            shortest += planner.shortest_path(w[0].at, w[1].at).unwrap().length;
        }
    }
    assert!(driven <= 1.12 * shortest, "driven {driven:.1} m, shortest {shortest:.1} m");
}
