//! Multi-robot exploration of a region of interest: every run is replayed independently and
//! checked against the paper's invariants (every cell visited, everyone home, within Lemma 1).

use proptest::prelude::*;
use stopscan::geometry::Domain;
use stopscan::io::grid::{GridOptions, read_roi};
use stopscan::offline::grid::GridBounds;
use stopscan::protocol::CostModel;
use stopscan::protocol::grid::{CellSet, TimeModel};
use stopscan::sim::grid::{Mission, MissionPlan, Search, explore};
use stopscan::sim::{NoObserver, Recording};
use stopscan::world::grid::camera::CameraModel;
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
    let b = GridBounds::of_world(world, m.plan.robots, &cost);
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

fn plan(robots: usize, battery_s: Option<f64>, search: Option<Search>) -> MissionPlan {
    MissionPlan {
        robots,
        cost: CostModel::new(0.0, 0.0, 1.0).unwrap(),
        battery_s,
        search,
        map: true,
    }
}

/// A mission written out mid-way and read back carries on exactly as if never stopped.
#[test]
fn a_saved_mission_resumes_exactly() {
    let roi = GridRoi::random(300, 5).unwrap();
    let drift = Drift { speed: 0.3, heading_deg: 200.0 };
    let fresh = || GridWorld::new(roi.clone(), drift, GridSensor::Ideal, 5);
    let mut whole_world = fresh();
    let mut whole = Mission::new(&whole_world, plan(5, Some(90.0), None), Recording::ALL).unwrap();
    whole.run(&mut whole_world, &mut NoObserver, 1_000_000).unwrap();
    for cut in [1, 17, 250] {
        let mut world = fresh();
        let mut m = Mission::new(&world, plan(5, Some(90.0), None), Recording::ALL).unwrap();
        for _ in 0..cut {
            m.step(&mut world, &mut NoObserver).unwrap();
        }
        m.snapshot(&world);
        let text = serde_json::to_string(&m).unwrap();
        let mut back: Mission = serde_json::from_str(&text).unwrap();
        let mut world = back.restore(fresh());
        back.run(&mut world, &mut NoObserver, 1_000_000).unwrap();
        back.snapshot(&world);
        let mut w = whole.clone();
        w.snapshot(&whole_world);
        assert_eq!(back.team.robots, w.team.robots, "cut at {cut}");
        assert_eq!(back.boards, w.boards, "cut at {cut}");
        assert_eq!(back.marks, w.marks, "cut at {cut}");
        assert_eq!(serde_json::to_string(&back).unwrap(), serde_json::to_string(&w).unwrap());
    }
}

/// With a battery, every flight between two swaps fits in it, and the mission still covers
/// every cell and ends at home.
#[test]
fn batteries_force_swaps_but_not_gaps() {
    for (seed, robots, battery) in [(1u64, 1usize, 60.0), (2, 4, 45.0), (3, 3, 200.0)] {
        let roi = GridRoi::random(400, seed).unwrap();
        let mut world = GridWorld::new(
            roi.clone(),
            Drift { speed: 0.2, heading_deg: 0.0 },
            GridSensor::Ideal,
            seed,
        );
        let mut m =
            Mission::new(&world, plan(robots, Some(battery), None), Recording::PATHS).unwrap();
        m.run(&mut world, &mut NoObserver, 10_000_000).unwrap();
        assert!(m.failures().is_empty(), "{:?}", m.failures());
        assert!(m.swaps().iter().sum::<u32>() > 0, "a {battery} s battery needs swaps");
        assert_eq!(world.visited().len(), roi.len());
        let tm = world.time_model(&m.plan.cost);
        for (i, r) in m.team.robots.iter().enumerate() {
            assert_eq!(r.at, roi.start());
            // Flight time between visits home never exceeds the battery.
            let mut flight = 0.0;
            for w in r.path.windows(2) {
                flight += tm.seconds(w[0], w[1]).unwrap();
                assert!(flight <= battery + 1e-9, "robot {i} flew {flight} s on one battery");
                if w[1] == roi.start() {
                    flight = 0.0;
                }
            }
        }
    }
}

/// A battery too small to reach the far side and come back is reported, not ignored.
#[test]
fn a_battery_too_small_is_a_failure() {
    let roi = GridRoi::new("line", (0..30).map(|c| [0, c]), [0, 0], 1.0).unwrap();
    let mut world = GridWorld::new(roi, Drift::default(), GridSensor::Ideal, 0);
    let mut m = Mission::new(&world, plan(1, Some(20.0), None), Recording::PATHS).unwrap();
    m.run(&mut world, &mut NoObserver, 1_000_000).unwrap();
    let f = m.failures();
    assert_eq!(f.len(), 1);
    assert!(f[0].contains("cannot reach cell (row 0, col 11)"), "{f:?}");
}

/// The lawn-mowing search finds a region that does not start under the robots, explores it,
/// and brings every robot back to the launch cell.
#[test]
fn search_then_explore_then_land() {
    let roi = GridRoi::random(120, 9).unwrap();
    let [lo, hi] = roi.bounds();
    let launch = [lo[0] - 6, lo[1] - 6];
    let search = Search { launch, min: [lo[0] - 6, lo[1] - 6], max: [hi[0] + 6, hi[1] + 6] };
    let mut world = GridWorld::without_root(roi.clone(), Drift::default(), GridSensor::Ideal, 9);
    let mut m = Mission::new(&world, plan(3, None, Some(search)), Recording::PATHS).unwrap();
    m.run(&mut world, &mut NoObserver, 1_000_000).unwrap();
    assert!(m.failures().is_empty(), "{:?}", m.failures());
    assert_eq!(world.visited().len(), roi.len(), "every region cell visited");
    assert!(m.team.robots.iter().all(|r| r.done && r.at == launch));
    assert_eq!(m.marks.positive(), roi.cells(), "the map is the region exactly");
}

/// The camera pipeline (noise, blur, shadows, glare, 3-of-5 votes) maps a region almost
/// exactly; conservative marking keeps every cell it ever saw as region.
#[test]
fn the_camera_pipeline_maps_the_region() {
    let roi = GridRoi::random(150, 4).unwrap();
    let sensor = GridSensor::Camera(CameraModel::default());
    let mut world = GridWorld::new(roi.clone(), Drift::default(), sensor, 4);
    let mut m = Mission::new(&world, plan(2, None, None), Recording::PATHS).unwrap();
    m.run(&mut world, &mut NoObserver, 1_000_000).unwrap();
    let mapped = m.marks.positive();
    let iou = roi.iou(&mapped);
    assert!(iou > 0.9, "IoU {iou}");
    assert!(m.team.robots.iter().all(|r| r.done && r.at == roi.start()));
}

/// Section 5: the outer approximation of fat shapes, with Lemma 3 (C_out ≤ 3 C_in + 6) and
/// the IoU of a complete map against the shape.
#[test]
fn outer_approximation_of_fat_shapes() {
    // An axis-aligned 4 × 3 rectangle on cell boundaries: outer = inner = 12 cells, IoU 1.
    let rect =
        Domain::new(vec![[-0.5, -0.5], [3.5, -0.5], [3.5, 2.5], [-0.5, 2.5]], vec![]).unwrap();
    let roi = GridRoi::outer_approximation("rect", &rect, [0.0, 0.0], 1.0).unwrap();
    assert_eq!(roi.approximation_counts(), Some((12, 12)));
    assert!((roi.iou(roi.cells()) - 1.0).abs() < 1e-12);
    // Shifted by a quarter cell: outer 5 × 4 = 20, inner 3 × 2 = 6.
    let roi = GridRoi::outer_approximation("shifted", &rect, [0.25, 0.25], 1.0).unwrap();
    assert_eq!(roi.approximation_counts(), Some((20, 6)));
    assert!((roi.iou(roi.cells()) - 12.0 / 20.0).abs() < 1e-12);
    // Rotated rectangles and discs of width at least one cell: Lemma 3 holds.
    for k in 0..24 {
        let a = f64::from(k) * 0.13;
        let (w, h) = (2.0 + f64::from(k % 5), 1.5 + f64::from(k % 3));
        let ring: Vec<[f64; 2]> = [(-w, -h), (w, -h), (w, h), (-w, h)]
            .iter()
            .map(|&(x, y)| {
                [x * a.cos() - y * a.sin() + 0.1 * f64::from(k), x * a.sin() + y * a.cos()]
            })
            .collect();
        let shape = Domain::new(ring, vec![]).unwrap();
        let roi =
            GridRoi::outer_approximation("r", &shape, [0.1 * f64::from(k), 0.0], 1.0).unwrap();
        let (out, inner) = roi.approximation_counts().unwrap();
        assert!(out <= 3 * inner + 6, "Lemma 3 fails: C_out {out}, C_in {inner}");
        assert!((roi.true_area() - 4.0 * w * h).abs() < 1e-9);
    }
}

#[test]
fn random_regions_are_seeded_connected_and_sized() {
    for c in [1, 2, 7, 500] {
        let a = GridRoi::random(c, 3).unwrap();
        assert_eq!(a.len(), c);
        assert_eq!(a.cells(), GridRoi::random(c, 3).unwrap().cells());
        assert_eq!(a.distances().len(), c, "4-connected");
    }
    assert_ne!(GridRoi::random(50, 1).unwrap().cells(), GridRoi::random(50, 2).unwrap().cells());
    assert!(GridRoi::random(0, 1).is_err());
}

#[test]
fn masks_load_with_their_cell_size() {
    let dir = std::env::temp_dir().join(format!("stopscan-mask-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // A 6 × 4 P5 mask: a 4 × 2 white block; with 2-pixel cells, 2 × 1 cells.
    let mut px = vec![0u8; 24];
    for y in 1..3 {
        for x in 1..5 {
            px[y * 6 + x] = 255;
        }
    }
    let path = dir.join("m.pgm");
    let mut bytes = b"P5\n6 4\n255\n".to_vec();
    bytes.extend(&px);
    std::fs::write(&path, bytes).unwrap();
    let one = read_roi(&path, &GridOptions::default()).unwrap();
    assert_eq!(one.len(), 8);
    let two =
        read_roi(&path, &GridOptions { cell_px: 2, cell_size: 0.5, ..GridOptions::default() })
            .unwrap();
    // Outer approximation: every 2 × 2 block touching the white block.
    assert_eq!(two.cells(), &[[0, 0], [0, 1], [0, 2], [1, 0], [1, 1], [1, 2]]);
    assert_eq!(two.cell_size(), 0.5);
    // Inverted: the dark frame around the block is the region (16 cells, connected).
    let dark = read_roi(&path, &GridOptions { invert: true, ..GridOptions::default() }).unwrap();
    assert_eq!(dark.len(), 16);
    let e = read_roi(&path, &GridOptions { start: Some([9, 9]), ..GridOptions::default() })
        .unwrap_err();
    assert!(
        e.to_string().contains("m.pgm: the start cell (row 9, col 9) is not a region cell"),
        "{e}"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// Search, batteries and drift together: every cell visited, every robot back at the launch
    /// cell, no flight between two swaps longer than a battery.
    #[test]
    fn field_missions_cover_and_land(
        cells in 5usize..200,
        seed in 0u64..100_000,
        robots in 1usize..8,
        offset in 1i32..6,
        drift in 0.0f64..0.5,
        heading in 0u32..360,
    ) {
        let roi = GridRoi::random(cells, seed).unwrap();
        let [lo, hi] = roi.bounds();
        let launch = [lo[0] - offset, lo[1] - offset];
        let search = Search { launch, min: launch, max: [hi[0] + 1, hi[1] + 1] };
        let drift = Drift { speed: drift, heading_deg: f64::from(heading) };
        let mut world = GridWorld::without_root(roi.clone(), drift, GridSensor::Ideal, seed);
        // A battery that can reach the far corner of the box and come back, with margin.
        let tm = world.time_model(&CostModel::new(0.0, 0.0, 1.0).unwrap());
        let far = tm.seconds(launch, [hi[0] + 1, hi[1] + 1]).unwrap()
            .max(tm.seconds([hi[0] + 1, hi[1] + 1], launch).unwrap());
        let battery = 3.0 * far + 6.0;
        let mut m = Mission::new(&world, plan(robots, Some(battery), Some(search)), Recording::PATHS).unwrap();
        m.run(&mut world, &mut NoObserver, 10_000_000).unwrap();
        prop_assert!(m.failures().is_empty(), "{:?}", m.failures());
        prop_assert_eq!(world.visited().len(), roi.len());
        for r in &m.team.robots {
            prop_assert!(r.done && r.at == launch);
            let mut flight = 0.0;
            for w in r.path.windows(2) {
                flight += tm.seconds(w[0], w[1]).unwrap();
                prop_assert!(flight <= battery + 1e-9);
                if w[1] == launch {
                    flight = 0.0;
                }
            }
        }
    }
}
