//! Exploration from raw laser scans: every polygon strategy, driven by a simulated noisy lidar
//! and drifting odometry, measured on the ground truth; the record's numbers checked against
//! an independent brute force.

use stopscan::io::Environment;
use stopscan::kernel::Point;
use stopscan::pipeline::explore::{ExploreOptions, explore};
use stopscan::protocol::CostModel;
use stopscan::protocol::laser::Pose;
use stopscan::protocol::polygon::Footprint;
use stopscan::world::lidar::Lidar;

#[path = "support/seen.rs"]
mod seen;
use seen::seen_share;

fn office(seed: u64) -> Environment {
    let inst = stopscan::generate::office(2, 3, seed).unwrap();
    let mut env = Environment::new(inst.domain);
    env.start = Some(inst.start);
    env
}

fn options(strategy: &str, seed: u64) -> ExploreOptions {
    ExploreOptions {
        strategy: strategy.into(),
        cost: CostModel::new(30.0, 0.0, 0.5).unwrap(),
        footprint: Footprint::disc(0.2).unwrap(),
        lidar: Some(Lidar::default()),
        odometry_drift: 0.01,
        seed,
        limits: stopscan::offline::polygon::ReferenceLimits {
            greedy_max_vertices: 0,
            optimum_seconds: 0.0,
            bounds_seconds: 0.0,
            ..Default::default()
        },
        ..ExploreOptions::default()
    }
}

#[test]
fn every_strategy_explores_an_office_from_raw_scans_and_the_record_is_true() {
    let env = office(4);
    for name in stopscan::strategy::polygon::REGISTRY.names() {
        let run = explore("office", &env, None, &options(name, 3), &mut |_| {}).unwrap();
        let r = &run.record;
        assert!(r.error.is_none(), "{name}: {:?}", r.error);
        let raw = r.raw_scans.as_ref().expect("a raw-scan record");
        let robot = r.robot.as_ref().unwrap();
        assert!(robot.coverage_of_reachable >= 0.99, "{name}: {}", robot.coverage_of_reachable);
        assert_eq!(raw.stops.len() as u64, r.metrics.totals.scans, "{name}");
        // Every stop's error is the distance between its estimate and its truth.
        for s in &raw.stops {
            let e = (s.estimate.x - s.truth.x).hypot(s.estimate.y - s.truth.y);
            assert!((e - s.position_error).abs() < 1e-12, "{name}");
        }
        let max = raw.stops.iter().map(|s| s.position_error).fold(0.0, f64::max);
        assert_eq!(max, raw.max_position_error);
        assert!(max <= 0.15, "{name}: pose error {max}");
        // The scans of the record stand where the robot truly was.
        let truth: Vec<Point> = raw.stops.iter().map(|s| [s.truth.x, s.truth.y]).collect();
        let at: Vec<Point> = r.robots[0].scans.iter().map(|s| s.at).collect();
        assert_eq!(at, truth, "{name}");
        // The coverage printed is the share of the free space seen from those stops, by a
        // brute force over a 10 cm grid (within the grid's resolution).
        let brute = seen_share(&env.domain, &truth, 20.0, 0.1);
        assert!(
            (brute - r.metrics.coverage).abs() < 0.01,
            "{name}: record {} brute {brute}",
            r.metrics.coverage
        );
    }
}

#[test]
fn the_same_seed_gives_the_same_run_and_another_seed_another() {
    let env = office(7);
    let json = |seed| {
        let run = explore("office", &env, None, &options("cost_aware", seed), &mut |_| {}).unwrap();
        serde_json::to_string(&run.record).unwrap()
    };
    let a = json(11);
    assert_eq!(a, json(11));
    assert_ne!(a, json(12));
}

#[test]
fn the_lidar_truth_and_the_belief_start_together() {
    let env = office(2);
    let run = explore("office", &env, None, &options("depth_first", 1), &mut |_| {}).unwrap();
    let raw = run.record.raw_scans.unwrap();
    let first = raw.stops[0];
    assert_eq!(first.truth, first.estimate);
    assert_eq!(first.truth, Pose::new(env.start.unwrap(), 0.0));
    assert!(first.alignment.is_none(), "nothing to align the first scan to");
}
