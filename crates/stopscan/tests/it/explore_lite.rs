//! `explore_lite`: the explore_lite-style frontier explorer completes on the built-in office
//! and on generated floors, for a point robot and a disc, with every move legal, high
//! coverage for the point robot, and the same run twice.

use stopscan::algorithm::region::Region;
use stopscan::generate::{Instance, comb, spiral};
use stopscan::geometry::Domain;
use stopscan::kernel::Point;
use stopscan::protocol::CostModel;
use stopscan::protocol::polygon::{Footprint, RobotSetup};
use stopscan::sim::NoObserver;
use stopscan::sim::polygon::{PolygonRun, run};
use stopscan::strategy::polygon::{ExploreLite, build_for};
use stopscan::world::polygon::PolygonWorld;

fn office() -> Instance {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/office.geojson");
    let env = stopscan::io::read_environment(&path).unwrap();
    let world = PolygonWorld::new(env.domain.clone()).unwrap();
    let start = env.start.unwrap_or_else(|| world.interior_point());
    Instance { domain: env.domain, start }
}

/// The instances: the office fixture, a spiral and a comb.
fn instances() -> Vec<(&'static str, Instance)> {
    vec![("office", office()), ("spiral", spiral(6).unwrap()), ("comb", comb(5).unwrap())]
}

/// Runs explore_lite for `footprint` from `start` (the world's own start for a footprint
/// when `start` lacks room); returns the world and the run.
fn explore(domain: &Domain, start: Point, footprint: &Footprint) -> (PolygonWorld, PolygonRun) {
    let world = PolygonWorld::with_robot(domain.clone(), None, footprint, Some(start))
        .or_else(|_| PolygonWorld::with_robot(domain.clone(), None, footprint, None))
        .unwrap();
    let start = world.reach().map_or(start, stopscan::world::polygon::Reach::start);
    let setup = RobotSetup { footprint: footprint.clone(), ..RobotSetup::default() };
    let cost = CostModel::default();
    let mut s = build_for("explore_lite", &setup).unwrap();
    let r = run(&world, start, &cost, s.as_mut(), &mut NoObserver)
        .unwrap_or_else(|e| panic!("explore_lite from {start:?}: {e}"));
    (world, r)
}

/// The share of the free area the scans saw: the union of their regions over the domain's
/// area, computed apart from the strategy.
fn coverage(world: &PolygonWorld, run: &PolygonRun) -> f64 {
    let polys: Vec<_> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
    Region::union_all(&polys).area() / world.domain().area()
}

#[test]
fn a_point_robot_covers_almost_everything_with_legal_moves() {
    for (name, inst) in instances() {
        let (world, run) = explore(&inst.domain, inst.start, &Footprint::Point);
        for w in run.path.windows(2) {
            assert!(world.can_move(w[0], w[1]), "{name}: illegal move {w:?}");
        }
        let c = coverage(&world, &run);
        assert!(c >= 0.99, "{name}: coverage {c} after {} scans", run.tally.scans);
        assert!(!run.interrupted);
    }
}

#[test]
fn a_disc_robot_keeps_its_clearance_and_explores() {
    let disc = Footprint::disc(0.2).unwrap();
    for (name, inst) in instances() {
        let (world, run) = explore(&inst.domain, inst.start, &disc);
        assert!(world.reach().is_some());
        for w in run.path.windows(2) {
            assert!(world.can_move(w[0], w[1]), "{name}: illegal move {w:?}");
        }
        // The disc passes every door and corridor of these floors (1 m and wider): it sees
        // nearly all of them too, from a little farther back.
        let c = coverage(&world, &run);
        assert!(c >= 0.99, "{name}: coverage {c} after {} scans", run.tally.scans);
        assert!(run.tally.scans >= 2, "{name}: it moved");
    }
}

#[test]
fn other_footprints_and_a_range_never_end_a_run_with_an_error() {
    use stopscan::generate::{office, pillar_forest, star};
    let rectangle =
        Footprint::convex(vec![[0.3, 0.2], [-0.3, 0.2], [-0.3, -0.2], [0.3, -0.2]]).unwrap();
    let footprints = [rectangle, Footprint::disc(0.35).unwrap()];
    let instances =
        [pillar_forest(30.0, 20.0, 6, 1).unwrap(), office(3, 4, 5).unwrap(), star(5).unwrap()];
    for inst in &instances {
        for fp in &footprints {
            for range in [None, Some(3.0)] {
                let world =
                    PolygonWorld::with_robot(inst.domain.clone(), range, fp, Some(inst.start))
                        .or_else(|_| PolygonWorld::with_robot(inst.domain.clone(), range, fp, None))
                        .unwrap();
                let start =
                    world.reach().map_or(inst.start, stopscan::world::polygon::Reach::start);
                let setup = RobotSetup { footprint: fp.clone(), ..RobotSetup::default() };
                let mut s = ExploreLite::for_robot(&setup);
                let r = run(&world, start, &CostModel::default(), &mut s, &mut NoObserver);
                let r = r.unwrap_or_else(|e| panic!("{fp:?}, range {range:?}: {e}"));
                assert!(r.tally.scans >= 1);
            }
        }
    }
}

#[test]
fn the_same_instance_gives_the_same_run() {
    for footprint in [Footprint::Point, Footprint::disc(0.2).unwrap()] {
        let inst = office();
        let (_, a) = explore(&inst.domain, inst.start, &footprint);
        let (_, b) = explore(&inst.domain, inst.start, &footprint);
        assert_eq!(a.path, b.path);
        assert_eq!(serde_json::to_string(&a).unwrap(), serde_json::to_string(&b).unwrap());
    }
}

#[test]
fn its_state_round_trips_through_json_mid_run() {
    use stopscan::protocol::Action;
    use stopscan::strategy::polygon::{PolygonFeedback, PolygonStrategy};
    let inst = comb(3).unwrap();
    let world = PolygonWorld::new(inst.domain.clone()).unwrap();
    let mut s = ExploreLite::for_robot(&RobotSetup::default());
    assert_eq!(s.act(&PolygonFeedback::Start { at: inst.start }), Action::Scan);
    let obs = world.scan(inst.start).unwrap();
    let a = s.act(&PolygonFeedback::Scanned(obs));
    assert!(matches!(a, Action::MoveTo { .. }), "{a:?}");
    let json = serde_json::to_string(&s).unwrap();
    let mut back: ExploreLite = serde_json::from_str(&json).unwrap();
    assert_eq!(back, s);
    assert_eq!(back.act(&PolygonFeedback::Arrived), s.act(&PolygonFeedback::Arrived));
}
