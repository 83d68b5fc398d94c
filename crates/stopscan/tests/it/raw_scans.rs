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
        // Relays: counted, never the first stop, at most `MAX_RELAYS` in a row.
        assert_eq!(raw.relays, raw.stops.iter().filter(|s| s.relay).count(), "{name}");
        assert!(!raw.stops[0].relay, "{name}");
        let mut run = 0;
        for s in &raw.stops {
            run = if s.relay { run + 1 } else { 0 };
            assert!(run <= stopscan::sim::lidar::MAX_RELAYS, "{name}");
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

/// A relay's scan is placed wherever odometry may really have put the robot
/// ([`stopscan::sensing::mapper::RELAY_SPREAD`]). On the warehouse, `range_limited`'s first
/// trip runs 17 m from the start; its relay was put where the scan was predicted to be placed
/// from the believed pose, 0.35 m beside the end of the one wall that held it across the
/// aisle. The robot truly stood level with the wall's end and saw it edge-on: that relay was
/// placed 0.2 to 0.4 m off across the aisle, and the stops after it aligned to its walls.
#[test]
fn a_relay_stands_where_its_scan_is_placed_wherever_odometry_put_the_robot() {
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/ros-maps/warehouse.yaml");
    let env = stopscan::io::read_environment(&path).unwrap();
    for seed in [11, 12, 30] {
        let run =
            explore("warehouse", &env, None, &options("range_limited", seed), &mut |_| {}).unwrap();
        let raw = run.record.raw_scans.unwrap();
        assert!(raw.stops[1].relay, "seed {seed}: the first trip takes a relay");
        // The relay and the four stops after it, which align to its walls (later stops meet
        // other trips' troubles: seed 12's eighth stop follows two alignments that fell back).
        for (i, stop) in raw.stops.iter().take(6).enumerate() {
            assert!(stop.position_error <= 0.1, "seed {seed}, stop {i}: {} m", stop.position_error);
        }
    }
}

/// Drives a `serve` session in process with a simulated robot on depot (`range_limited`, 720
/// beams, 1% drift), `relay` in the start message when given: the largest distance between
/// where a scan was placed and where it was truly taken.
fn served_depot(seed: u64, relay: Option<f64>) -> f64 {
    use stopscan::pipeline::serve::client::SimClient;
    use stopscan::pipeline::serve::{ServeOptions, Server};
    use stopscan::sim::lidar::SimRobot;
    use stopscan::world::polygon::PolygonWorld;
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/ros-maps/depot.yaml");
    let env = stopscan::io::read_environment(&path).unwrap();
    let start = env.default_start();
    let disc = Footprint::disc(0.2).unwrap();
    let world = PolygonWorld::with_robot(env.domain, Some(20.0), &disc, start).unwrap();
    let start = world.reach().expect("a robot with a body").start();
    let mut setup = serde_json::json!({
        "strategy": "range_limited", "cost": {"scan_time": 30.0, "speed": 0.5},
        "robot": {"radius": 0.2}, "sensor": {"sigma": 0.02, "range": 20.0},
        "odometry_drift": 0.01,
    });
    if let Some(r) = relay {
        setup["relay"] = r.into();
    }
    let robot = SimRobot::new(&world, start, Lidar::default(), 0.01, seed);
    let mut client = SimClient::new(robot, setup.as_object().unwrap().clone());
    let mut server = Server::new(ServeOptions::default());
    let mut line = client.start();
    let mut placed = Vec::new();
    loop {
        let reply: serde_json::Value =
            serde_json::from_str(&server.handle(&line).unwrap()).unwrap();
        if let Some(p) = reply.get("localised") {
            placed.push([p["pose"]["x"].as_f64().unwrap(), p["pose"]["y"].as_f64().unwrap()]);
        }
        match client.answer(&reply).unwrap() {
            Some(next) => line = next,
            None => break,
        }
    }
    assert_eq!(placed.len(), client.truth.len());
    placed
        .iter()
        .zip(&client.truth)
        .map(|(p, t)| (p[0] - t[0]).hypot(p[1] - t[1]))
        .fold(0.0, f64::max)
}

/// `serve` takes relays as `explore --sensor lidar` does: on depot's first trip, along the
/// hall to where a scan cannot be placed along it, the server sends the robot to a relay on
/// the way and asks for its scan, and every scan is placed within 0.1 m; with `"relay": 0`
/// the second scan keeps odometry's 0.2 to 0.3 m error, and the stops after it align to its
/// walls. (`cost_aware` no longer makes that trip first: the window it went for was a sliver
/// along a wall, closed since window parts onto walls seen are.)
#[test]
fn serve_sends_the_robot_to_a_relay_where_a_trip_ends_beyond_what_icp_can_place() {
    for seed in [3, 4] {
        // Relays are the only difference between the two sessions.
        let on = served_depot(seed, None);
        let off = served_depot(seed, Some(0.0));
        assert!(on <= 0.1, "seed {seed}: {on} m with relays");
        assert!(off > 0.1, "seed {seed}: {off} m without");
    }
}

/// Walls traced from an occupancy grid have steps of a cell (5 cm on depot). A wall line
/// fitted at 3σ cuts through them, tilted toward the side its scan saw more of, and a scan
/// aligned to such lines is placed off by as much: depot's second stop of `cost_aware`
/// (seed 11), 13 m from the first, 0.1 m off. Refined against the walls fitted at 3 cm
/// ([`stopscan::sensing::icp::refine`]), it is placed within 3 cm for every lidar seed,
/// from 0.25 m and 1.2° of odometry error.
#[test]
fn a_scan_of_a_map_traced_from_a_grid_is_placed_within_centimetres() {
    use rand::SeedableRng;
    use stopscan::sensing::mapper::Mapper;
    use stopscan::sim::lidar::LidarSetup;
    use stopscan::world::lidar::Walls;
    let path = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/ros-maps/depot.yaml");
    let env = stopscan::io::read_environment(&path).unwrap();
    let walls = Walls::of(&env.domain);
    let lidar = Lidar::default();
    let first = Pose { x: 5.0124, y: 7.2028, theta: 0.0 };
    let second = Pose { x: 15.7170, y: 14.9954, theta: -0.0212 };
    let odometry = Pose { x: 15.6865, y: 14.7446, theta: 0.0 };
    let mut errors = Vec::new();
    for seed in 0..8 {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut mapper = Mapper::new(LidarSetup::new(lidar, 0.01, seed).mapper_params());
        mapper.read(&lidar.scan(&walls, &first, &mut rng), &first, 0.0).unwrap();
        let scan = lidar.scan(&walls, &second, &mut rng);
        let r = mapper.read(&scan, &odometry, 13.2).unwrap();
        errors.push((r.estimate.x - second.x).hypot(r.estimate.y - second.y));
    }
    assert!(errors.iter().all(|&e| e < 0.03), "{errors:?}");
}
