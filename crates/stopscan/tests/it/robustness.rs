//! Inputs that used to hang: starts on walls and vertices, georeferenced coordinates, and
//! strategies that stop making progress.

use stopscan::algorithm::cover::open_windows;
use stopscan::generate::{Instance, comb, office, pillar_forest, spiral, star};
use stopscan::geometry::{Domain, Frame, Location};
use stopscan::io::Environment;
use stopscan::kernel::Point;
use stopscan::protocol::{Action, CostModel};
use stopscan::sim::polygon::{PolygonRun, run};
use stopscan::sim::{NoObserver, SimError};
use stopscan::strategy::polygon::{PolygonFeedback, PolygonStrategy, REGISTRY, by_name};
use stopscan::world::polygon::PolygonWorld;

fn explore(world: &PolygonWorld, start: Point, strategy: &str) -> PolygonRun {
    let cost = CostModel::default();
    let mut s = by_name(strategy, &cost).unwrap();
    run(world, start, &cost, s.as_mut(), &mut NoObserver)
        .unwrap_or_else(|e| panic!("{strategy} from {start:?}: {e}"))
}

/// Complete: no window of the union left open, and nothing unseen by exact point tests.
fn assert_complete(world: &PolygonWorld, run: &PolygonRun, label: &str) {
    let d = world.domain();
    let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
    let open = open_windows(&regions, |p| d.locate(p) == Location::Interior);
    assert_eq!(open, 0, "{label}: windows left open");
    let polys: Vec<_> = regions.iter().map(|r| r.polygon.clone()).collect();
    let u = stopscan::algorithm::cover::uncovered_area(d, &polys);
    assert!(u <= 1e-9 * d.area(), "{label}: {u} m² unseen");
    for w in run.path.windows(2) {
        assert!(world.can_move(w[0], w[1]), "{label}: illegal move {w:?}");
    }
}

/// What a strategy's run must reach: complete for the paper's algorithms and the window
/// baselines; `explore_lite` leaves frontiers shorter than its `min_frontier_size` (0.5 m)
/// unvisited by design, so it is held to legal moves and 99% of the free area.
fn assert_explored(world: &PolygonWorld, run: &PolygonRun, strategy: &str, label: &str) {
    if strategy != "explore_lite" {
        return assert_complete(world, run, label);
    }
    for w in run.path.windows(2) {
        assert!(world.can_move(w[0], w[1]), "{label}: illegal move {w:?}");
    }
    let polys: Vec<_> = run.scans.iter().map(|s| s.region.polygon.clone()).collect();
    let seen = stopscan::algorithm::region::Region::union_all(&polys).area();
    let d = world.domain().area();
    assert!(seen >= 0.99 * d, "{label}: {seen} m² of {d} seen");
}

/// Every vertex of every ring, and the middle of every axis-parallel edge (exact there).
fn boundary_points(d: &Domain) -> Vec<Point> {
    let mut out = Vec::new();
    for ring in d.rings() {
        for (i, &p) in ring.iter().enumerate() {
            out.push(p);
            let q = ring[(i + 1) % ring.len()];
            if p[0] == q[0] || p[1] == q[1] {
                out.push([0.5 * (p[0] + q[0]), 0.5 * (p[1] + q[1])]);
            }
        }
    }
    out
}

#[test]
fn every_strategy_explores_from_a_start_on_a_wall_or_a_vertex() {
    let instances: Vec<(&str, Instance)> = vec![
        ("spiral", spiral(4).unwrap()),
        ("star", star(5).unwrap()),
        ("comb", comb(3).unwrap()),
        ("forest", pillar_forest(30.0, 20.0, 4, 3).unwrap()),
        ("office", office(2, 3, 1).unwrap()),
    ];
    for (name, inst) in &instances {
        let world = PolygonWorld::new(inst.domain.clone()).unwrap();
        let ranged = PolygonWorld::with_range(inst.domain.clone(), Some(6.0)).unwrap();
        let r = inst.domain.reflex_vertices().len() as u64;
        let points = boundary_points(&inst.domain);
        // Every boundary point for the paper's algorithm, a sample for the others.
        for (k, &p) in points.iter().enumerate() {
            assert_ne!(inst.domain.locate(p), Location::Outside);
            let label = format!("{name} from {p:?}");
            let df = explore(&world, p, "depth_first");
            assert!(df.tally.scans <= r + 1, "{label}: {} scans > r + 1", df.tally.scans);
            assert_complete(&world, &df, &label);
            if k % 7 == 0 {
                for strategy in REGISTRY.names() {
                    let w = if strategy == "range_limited" { &ranged } else { &world };
                    let run = explore(w, p, strategy);
                    assert_explored(w, &run, strategy, &format!("{label}, {strategy}"));
                }
            }
        }
    }
}

/// The turtlebot map of the repository, written with its origin moved.
fn ros_map_at(dir: &std::path::Path, origin: [f64; 2]) -> Environment {
    let fixtures = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/ros-maps");
    let image = fixtures.join("turtlebot3_world.pgm").canonicalize().unwrap();
    let yaml = dir.join(format!("map_{}_{}.yaml", origin[0], origin[1]));
    std::fs::write(
        &yaml,
        format!(
            "image: {}\nresolution: 0.05\norigin: [{:e}, {:e}, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
            image.display(),
            origin[0],
            origin[1]
        ),
    )
    .unwrap();
    stopscan::io::read_environment(&yaml).unwrap()
}

#[test]
fn a_georeferenced_ros_map_explores_exactly_as_at_its_usual_origin() {
    let dir = std::env::temp_dir().join(format!("stopscan-frames-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = ros_map_at(&dir, [-10.0, -10.0]);
    let world = PolygonWorld::new(base.domain.clone()).unwrap();
    let start = world.interior_point();
    let cost = CostModel::default();
    let reference: Vec<PolygonRun> =
        ["depth_first", "nearest_frontier"].iter().map(|s| explore(&world, start, s)).collect();
    for origin in [[4.5e6, 5.3e6], [1e8, 1e8], [1e15, 0.0], [1e15, 1e15], [1e16, 1e16]] {
        let env = ros_map_at(&dir, origin);
        // The map is traced in its grid's frame: the same domain at every origin.
        assert_eq!(env.domain, base.domain, "origin {origin:?}");
        assert_eq!(env.frame, Frame::at(origin));
        let w = PolygonWorld::new(env.domain.clone()).unwrap();
        for (s, want) in ["depth_first", "nearest_frontier"].iter().zip(&reference) {
            let got = explore(&w, start, s);
            assert_eq!(got.path, want.path, "{s} at origin {origin:?}");
            assert_eq!(cost.price(&got.tally), cost.price(&want.tally));
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_georeferenced_polygon_is_moved_exactly_and_explored_completely() {
    let inst = office(3, 4, 2).unwrap();
    for off in [4.5e6, 1e10, 1e12] {
        // Coordinates that are representable after the shift, as a surveyed map's are.
        let rings: Vec<Vec<Point>> = inst
            .domain
            .rings()
            .iter()
            .map(|r| r.iter().map(|p| [p[0] + off, p[1] - off]).collect())
            .collect();
        let (outer, holes) = rings.split_first().unwrap();
        let shifted = Domain::new(outer.clone(), holes.to_vec()).unwrap();
        let start = [inst.start[0] + off, inst.start[1] - off];
        let env = Environment::new(shifted.clone()).with_start(Some(start)).localised().unwrap();
        assert!(!env.frame.is_identity());
        // Exact: back in the input's frame, every vertex is the input's.
        for (a, b) in env.domain.rings().iter().zip(shifted.rings()) {
            let back: Vec<Point> = a.iter().map(|&p| env.frame.to_input(p)).collect();
            assert_eq!(&back, b);
        }
        for s in REGISTRY.names() {
            let range = (s == "range_limited").then_some(5.0);
            let w = PolygonWorld::with_range(env.domain.clone(), range).unwrap();
            let run = explore(&w, env.start.unwrap(), s);
            assert_explored(&w, &run, s, &format!("{s}, offset {off}"));
        }
    }
}

/// A strategy that scans where it stands forever.
struct Stubborn;

impl PolygonStrategy for Stubborn {
    fn name(&self) -> &'static str {
        "stubborn"
    }
    fn act(&mut self, _feedback: &PolygonFeedback) -> Action<Point> {
        Action::Scan
    }
}

/// A strategy that drives back and forth between two points, scanning at each.
struct Pendulum(usize);

impl PolygonStrategy for Pendulum {
    fn name(&self) -> &'static str {
        "pendulum"
    }
    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point> {
        self.0 += 1;
        match feedback {
            PolygonFeedback::Arrived
            | PolygonFeedback::Start { .. }
            | PolygonFeedback::MoveFailed { .. } => Action::Scan,
            PolygonFeedback::Scanned(_) => {
                Action::MoveTo { to: if self.0 % 4 == 2 { [3.0, 1.0] } else { [1.0, 1.0] } }
            }
        }
    }
}

#[test]
fn the_loop_ends_a_strategy_that_stops_making_progress_and_keeps_the_run_so_far() {
    let d = Domain::new(vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]], vec![]).unwrap();
    let world = PolygonWorld::new(d).unwrap();
    let cost = CostModel::default();
    let e = run(&world, [1.0, 1.0], &cost, &mut Stubborn, &mut NoObserver).unwrap_err();
    assert!(matches!(e.error, SimError::NoProgress { earlier: 1, scans: 1, .. }), "{e}");
    assert_eq!(e.partial.tally.scans, 1);
    assert!(e.to_string().contains("nothing new"), "{e}");
    let e = run(&world, [1.0, 1.0], &cost, &mut Pendulum(0), &mut NoObserver).unwrap_err();
    assert!(matches!(e.error, SimError::NoProgress { at: [1.0, 1.0], earlier: 1, scans: 2, .. }));
    assert_eq!(e.partial.tally.scans, 2);
    assert_eq!(e.partial.path, vec![[1.0, 1.0], [3.0, 1.0], [1.0, 1.0]]);
}

/// What a strategy asked for when driven by hand ([`drive_office`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum Step {
    /// A scan, and whether it came right after a failed move.
    Scan { after_failure: bool },
    /// A move to a goal, and whether it failed.
    Move { to: Point, failed: bool },
}

/// Drives `DepthFirst` with a 0.2 m disc on an office floor by hand, for at most `limit`
/// actions: each goal is reached at once unless `fails(goal, steps so far)` says the move
/// fails without the robot moving (as a goal that odometry's drift put inside an obstacle
/// does). Returns the steps, whether the strategy said it was done, what it skipped, and
/// the robot's setup.
fn drive_office(
    limit: usize,
    mut fails: impl FnMut(Point, &[Step]) -> bool,
) -> (Vec<Step>, bool, stopscan::strategy::polygon::Skipped, stopscan::protocol::polygon::RobotSetup)
{
    use stopscan::algorithm::visibility::Visibility;
    use stopscan::protocol::polygon::{Footprint, PolygonObservation, RobotSetup};
    use stopscan::protocol::{Feedback, MoveFailure};
    use stopscan::strategy::polygon::DepthFirst;
    let inst = office(3, 0, 1).unwrap();
    let vis = Visibility::new(inst.domain).unwrap();
    let setup = RobotSetup { footprint: Footprint::disc(0.2).unwrap(), ..RobotSetup::default() };
    let mut s = DepthFirst::for_robot(&setup);
    let mut here = inst.start;
    let mut fb: PolygonFeedback = Feedback::Start { at: here };
    let mut steps = Vec::new();
    for _ in 0..limit {
        let after_failure = matches!(fb, Feedback::MoveFailed { .. });
        match s.act(&fb) {
            Action::Scan => {
                steps.push(Step::Scan { after_failure });
                fb = Feedback::Scanned(PolygonObservation::new(here, vis.query(here).unwrap()));
            }
            Action::MoveTo { to } => {
                let failed = fails(to, &steps);
                steps.push(Step::Move { to, failed });
                fb = if failed {
                    Feedback::MoveFailed { at: here, reason: MoveFailure::Blocked }
                } else {
                    here = to;
                    Feedback::Arrived
                };
            }
            Action::Done => return (steps, true, s.skipped(), setup),
        }
    }
    (steps, false, s.skipped(), setup)
}

/// The scans among `steps`, each with whether it came right after a failed move.
fn scans_of(steps: &[Step]) -> Vec<bool> {
    steps
        .iter()
        .filter_map(|s| match *s {
            Step::Scan { after_failure } => Some(after_failure),
            Step::Move { .. } => None,
        })
        .collect()
}

#[test]
fn moves_that_keep_failing_at_one_place_are_followed_by_a_scan_there() {
    // Every goal within 0.5 m of the first goal after the second scan fails: the belief
    // there is wrong, whatever the strategy plans.
    let mut blocked: Option<Point> = None;
    let (steps, done, skipped, _) = drive_office(2_000, |to, steps| {
        if blocked.is_none() && scans_of(steps).len() == 2 {
            blocked = Some(to);
        }
        blocked.is_some_and(|b| (b[0] - to[0]).hypot(b[1] - to[1]) <= 0.5)
    });
    let failures = steps.iter().filter(|s| matches!(s, Step::Move { failed: true, .. })).count();
    let scans = scans_of(&steps);
    let relocations = scans.iter().filter(|&&f| f).count();
    assert!(done, "the exploration ends");
    assert!(failures >= 3, "{failures} failures");
    assert!(relocations >= 1, "no scan after repeated failures at one place");
    // A scan that placed the robot again and did not cure the failures is not repeated
    // before a scan for a target: it would see the same.
    assert!(!scans.windows(2).any(|w| w[0] && w[1]), "two scans in a row to place the robot");
    // Each relocating scan follows failures that dropped targets.
    assert!(relocations <= skipped.move_failed, "{relocations} relocating scans");
}

#[test]
fn a_robot_that_can_drive_neither_on_nor_back_scans_where_it_is_stuck_and_goes_on() {
    // After the second scan every move fails, the way back too (odometry's drift put the
    // robot against a wall it believes it is clear of), until the robot scans where it
    // stands; `cured` says whether moves succeed again after that scan.
    for cured in [true, false] {
        let (steps, done, k, setup) = drive_office(20_000, |_, steps| {
            let scans = scans_of(steps);
            scans.len() >= 2 && !(cured && scans.contains(&true))
        });
        let scans = scans_of(&steps);
        let stuck = scans.contains(&true);
        assert!(done && stuck, "cured {cured}: the robot scans where it is stuck, and ends");
        assert_eq!(k.stuck_scans, 1, "cured {cured}");
        // Cured, it explores on to the end (the office's rooms take many scans); stuck again
        // where it scanned, it gives up, and says so.
        assert_eq!(k.gave_up, !cured, "cured {cured}");
        // The run record says so.
        let info = stopscan::run_record::SensorInfo::of(&setup.sensor, &k);
        assert_eq!(info.scans_where_stuck, Some(1));
        assert_eq!(info.gave_up, (!cured).then_some(true));
        if cured {
            assert!(scans.len() > 10, "{} scans", scans.len());
        } else {
            assert_eq!(scans.len(), 3);
        }
    }
}

#[test]
fn a_part_dropped_by_a_failed_move_is_tried_again_before_the_exploration_ends() {
    // The first goal after the second scan fails: once (a passing obstacle), or every time
    // (the way there is blocked for good).
    for always in [false, true] {
        let mut goal: Option<Point> = None;
        let mut failed = 0;
        let near = |a: Point, b: Point| (a[0] - b[0]).hypot(a[1] - b[1]) <= 0.5;
        let (steps, done, skipped, _) = drive_office(20_000, |to, steps| {
            if goal.is_none() && scans_of(steps).len() == 2 {
                goal = Some(to);
            }
            let fails = goal.is_some_and(|g| near(g, to)) && (always || failed == 0);
            failed += usize::from(fails);
            fails
        });
        let g = goal.expect("a goal after the second scan");
        assert!(done, "always {always}: the exploration ends");
        let fails: Vec<usize> = (0..steps.len())
            .filter(|&i| matches!(steps[i], Step::Move { failed: true, .. }))
            .collect();
        let (first, last) = (fails[0], fails[fails.len() - 1]);
        if always {
            // After the first failure the strategy went on elsewhere and scanned, and at what
            // would have been the end it tried the goal again; that failed too, the part was
            // dropped for good, and no scan came after.
            assert!(matches!(steps[last], Step::Move { to, .. } if near(to, g)));
            assert!(steps[first..last].iter().any(|s| matches!(s, Step::Scan { .. })));
            assert!(!steps[last..].iter().any(|s| matches!(s, Step::Scan { .. })));
            assert!(skipped.move_failed >= 1);
        } else {
            // Tried again, the part counts as dropped no more.
            assert_eq!(fails.len(), 1);
            assert_eq!(skipped.move_failed, 0, "the part was tried again");
        }
    }
}

#[test]
fn parts_still_dropped_at_the_end_get_a_scan_to_place_the_robot_again_and_one_more_try() {
    // Where each scan was taken: where the last move that got there ended (`None`: the start).
    fn scan_spots(steps: &[Step]) -> Vec<(usize, Option<Point>)> {
        let mut at = None;
        let mut out = Vec::new();
        for (i, s) in steps.iter().enumerate() {
            match *s {
                Step::Move { to, failed: false } => at = Some(to),
                Step::Move { .. } => {}
                Step::Scan { .. } => out.push((i, at)),
            }
        }
        out
    }
    // From the third scan on, odometry's drift puts every new goal of a trip of more than
    // two moves inside an obstacle in truth; the way back to where a scan was taken works.
    let mut failed_goals: Vec<Point> = Vec::new();
    let (steps, done, k, setup) = drive_office(20_000, |to, steps| {
        let spots = scan_spots(steps);
        let since = steps.iter().rev().take_while(|s| matches!(s, Step::Move { .. })).count();
        let back = spots.iter().any(|&(_, p)| p == Some(to));
        let fails = spots.len() >= 3 && since >= 2 && !back;
        if fails {
            failed_goals.push(to);
        }
        fails
    });
    assert!(done, "the exploration ends");
    assert!(!failed_goals.is_empty(), "no move failed: the test proves nothing");
    // One scan to place the robot again, at what would have been the end, and the run record
    // says so. It stood where an earlier scan was taken (the trip drove back there).
    assert_eq!(k.placed_again_scans, 1);
    let info = stopscan::run_record::SensorInfo::of(&setup.sensor, &k);
    assert_eq!(info.scans_to_place_again, Some(1));
    let spots = scan_spots(&steps);
    // (A scan right after failed moves is the other kind: three failures at one place.)
    let again: Vec<usize> = (0..spots.len())
        .filter(|&j| spots[j].1.is_some() && spots[..j].iter().any(|s| s.1 == spots[j].1))
        .map(|j| spots[j].0)
        .filter(|&i| matches!(steps[i], Step::Scan { after_failure: false }))
        .collect();
    assert_eq!(again.len(), 1, "scans where one was taken before: {again:?}");
    // After it, a goal that had failed was tried once more.
    assert!(
        steps[again[0]..]
            .iter()
            .any(|s| matches!(s, Step::Move { to, .. } if failed_goals.contains(to))),
        "no goal that failed was tried again after the scan"
    );
    // From the pose that scan gave, the parts dropped were reached: none is left dropped.
    assert_eq!(k.move_failed, 0);
}
