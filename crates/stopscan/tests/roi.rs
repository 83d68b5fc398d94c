//! Multi-robot exploration of a region of interest: every run is replayed independently and
//! checked against the paper's invariants (every cell visited, everyone home, within Lemma 1).

use proptest::prelude::*;
use stopscan::offline::grid::{GridBounds, tree_depth};
use stopscan::protocol::CostModel;
use stopscan::protocol::grid::{CellSet, TimeModel};
use stopscan::sim::Recording;
use stopscan::sim::grid::{Mission, explore};
use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};

/// Replays a finished mission from its paths alone and checks it.
fn check(world: &GridWorld, m: &Mission) -> (f64, GridBounds) {
    let roi = world.roi();
    let cost = m.plan.cost;
    let tm: TimeModel = world.time_model(&cost);
    let mut visited = CellSet::default();
    let mut makespan: f64 = 0.0;
    for (i, r) in m.team.robots.iter().enumerate() {
        assert!(r.done, "robot {i} did not finish");
        assert_eq!(*r.path.last().unwrap(), roi.start(), "robot {i} did not return to the start");
        let mut t = 0.0;
        for w in r.path.windows(2) {
            // Each flight is between two cells of the region (or hovers in place).
            assert!(roi.contains(w[1]), "robot {i} flew to {:?}, outside the region", w[1]);
            t += cost.move_time + tm.seconds(w[0], w[1]).unwrap();
        }
        t += r.tally.scans as f64 * cost.scan_time;
        assert!(
            (t - r.clock).abs() <= 1e-9 * t.max(1.0),
            "robot {i}: replayed {t}, reported {}",
            r.clock
        );
        visited.extend(r.path.iter().copied());
        makespan = makespan.max(t);
    }
    for c in roi.cells() {
        assert!(visited.contains(c), "cell {c:?} was never visited");
    }
    let b =
        GridBounds::new(roi.len(), roi.bounds(), tree_depth(&world.records()), m.plan.robots, tm);
    assert!(
        makespan <= b.lemma1_upper * (1.0 + 1e-12),
        "time {makespan} exceeds Lemma 1's {} (C = {}, R = {}, d_max = {})",
        b.lemma1_upper,
        roi.len(),
        m.plan.robots,
        b.d_max
    );
    if let Some(b8) = b.bound8_single {
        assert!(makespan <= b8 * (1.0 + 1e-12), "single robot: {makespan} > (8) {b8}");
    }
    (makespan, b)
}

fn run(cells: usize, seed: u64, robots: usize, drift: Drift, speed: f64) -> (f64, GridBounds) {
    let roi = GridRoi::random(cells, seed).unwrap();
    let mut world = GridWorld::new(roi, drift, GridSensor::Ideal, seed);
    let cost = CostModel::new(0.0, 0.0, speed).unwrap();
    let m = explore(&mut world, robots, cost, Recording::PATHS).unwrap();
    check(&world, &m)
}

#[test]
fn one_robot_is_depth_first_search() {
    // One robot on a static region: every tree edge twice, 2(C − 1) cells of flight.
    for seed in 0..20 {
        let (t, _) = run(60, seed, 1, Drift::default(), 1.0);
        assert_eq!(t, 118.0, "seed {seed}");
    }
}

#[test]
fn a_line_is_split_nowhere() {
    let roi = GridRoi::new("line", (0..10).map(|c| [0, c]), [0, 0], 1.0).unwrap();
    let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, 0);
    let m =
        explore(&mut world, 4, CostModel::new(0.0, 0.0, 1.0).unwrap(), Recording::PATHS).unwrap();
    let (t, _) = check(&world, &m);
    assert_eq!(t, 18.0);
}

#[test]
fn a_fork_splits_the_team() {
    // A plus shape from the centre: four arms of 5; the root has 4 children (a dummy vertex
    // joins two of them). 4 robots: each arm gets one robot.
    let mut cells = vec![[0, 0]];
    for k in 1..=5 {
        cells.extend([[-k, 0], [k, 0], [0, k], [0, -k]]);
    }
    let roi = GridRoi::new("plus", cells, [0, 0], 1.0).unwrap();
    let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, 0);
    let m =
        explore(&mut world, 4, CostModel::new(0.0, 0.0, 1.0).unwrap(), Recording::PATHS).unwrap();
    let (t, b) = check(&world, &m);
    // The binary vertex sends 2 robots to the first arm and 1 to each of the next two (the
    // dummy vertices); the fourth arm waits for the first team back: 10 + 10.
    assert_eq!(t, 20.0);
    assert!(t <= b.lemma1_upper);
}

#[test]
fn drifting_region_uses_relative_speeds() {
    for heading in [0.0, 90.0, 180.0, 270.0, 33.0] {
        for robots in [1, 3, 20] {
            run(150, 7, robots, Drift { speed: 0.4, heading_deg: heading }, 1.0);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]
    #[test]
    fn every_run_covers_returns_and_stays_within_lemma_1(
        cells in 1usize..400,
        seed in 0u64..1_000_000,
        robots in 1usize..=64,
        drifting in any::<bool>(),
        heading in 0u32..360,
        ratio in 1.2f64..8.0,
    ) {
        let drift = if drifting {
            Drift { speed: 1.0 / ratio, heading_deg: f64::from(heading) }
        } else {
            Drift::default()
        };
        run(cells, seed, robots, drift, 1.0);
    }
}

#[test]
#[ignore = "debugging aid"]
fn print_fork() {
    let mut cells = vec![[0, 0]];
    for k in 1..=5 {
        cells.extend([[-k, 0], [k, 0], [0, k], [0, -k]]);
    }
    let roi = GridRoi::new("plus", cells, [0, 0], 1.0).unwrap();
    let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, 0);
    let m =
        explore(&mut world, 4, CostModel::new(0.0, 0.0, 1.0).unwrap(), Recording::PATHS).unwrap();
    for r in &m.team.robots {
        eprintln!("{:?}", r.path);
    }
}

#[test]
#[ignore = "debugging aid"]
fn print_probes() {
    use stopscan::protocol::grid::VertexState;
    for seed in 0..40 {
        let roi = GridRoi::random(352, seed).unwrap();
        let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, seed);
        let m = explore(&mut world, 3, CostModel::new(0.0, 0.0, 1.0).unwrap(), Recording::PATHS)
            .unwrap();
        let probes: usize = world
            .records()
            .values()
            .map(|r| r.child_states.iter().filter(|s| **s == VertexState::Pruned).count())
            .sum();
        let tm = world.time_model(&m.plan.cost);
        let b = GridBounds::new(352, world.roi().bounds(), tree_depth(&world.records()), 3, tm);
        let moves: Vec<u64> = m.team.robots.iter().map(|r| r.tally.moves).collect();
        eprintln!(
            "seed {seed}: time {} bound {} dmax {} probes {probes} moves {moves:?}",
            m.team.makespan(),
            b.lemma1_upper,
            b.d_max
        );
    }
}

#[test]
#[ignore = "long stress run: cargo test --release --test roi stress -- --ignored"]
fn stress() {
    for seed in 0..3000u64 {
        let cells = 1 + (seed as usize * 7919) % 2000;
        let robots = 1 + (seed as usize * 31) % 64;
        let drift = if seed % 2 == 0 {
            Drift::default()
        } else {
            Drift { speed: 0.1 + (seed % 7) as f64 * 0.12, heading_deg: (seed * 37 % 360) as f64 }
        };
        run(cells, seed, robots, drift, 1.0);
    }
}

#[test]
#[ignore = "timing aid"]
fn million() {
    let t0 = std::time::Instant::now();
    let roi = GridRoi::random(1_000_000, 1).unwrap();
    let t1 = std::time::Instant::now();
    let robots = std::env::var("ROBOTS").map_or(64, |v| v.parse().unwrap());
    let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, 1);
    let rec = if std::env::var("SKIP_CHECK").is_ok() { Recording::NONE } else { Recording::PATHS };
    let m = explore(&mut world, robots, CostModel::new(0.0, 0.0, 1.0).unwrap(), rec).unwrap();
    let t2 = std::time::Instant::now();
    eprintln!(
        "gen {:?} sim {:?} steps {} makespan {} moves {}",
        t1 - t0,
        t2 - t1,
        m.team.steps,
        m.team.makespan(),
        m.team.tally().moves
    );
    eprintln!("dmax {}", tree_depth(&world.records()));
    if std::env::var("SKIP_CHECK").is_err() {
        check(&world, &m);
    }
}

#[test]
#[ignore = "experiment"]
fn order_experiment() {
    let mut total = 0.0;
    for seed in 0..12 {
        let roi = GridRoi::random(50_000, seed).unwrap();
        let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, seed);
        let m = explore(&mut world, 64, CostModel::new(0.0, 0.0, 1.0).unwrap(), Recording::NONE)
            .unwrap();
        total += m.team.makespan();
    }
    eprintln!("mean makespan {}", total / 12.0);
}
