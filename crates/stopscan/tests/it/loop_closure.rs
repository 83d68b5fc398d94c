//! Loop closure in the raw-scan pipeline: a stop that odometry misplaced along a corridor (ICP
//! cannot tell where along it) is moved when a later stop ties the map back to walls placed
//! well, and the walls it put in the map move with it.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use stopscan::geometry::Domain;
use stopscan::protocol::laser::Pose;
use stopscan::sensing::mapper::{Mapper, MapperParams};
use stopscan::world::lidar::{Lidar, Walls};

/// A 34 m corridor, 2 m wide, with a side corridor going off it at 3 m and at 25 m:
/// between them, a scanner of 8 m range sees two parallel walls and nothing along them. A
/// side corridor's walls tell where along the corridor a scanner stands; each is seen
/// only from the side it faces.
fn corridor() -> Walls {
    let d = Domain::new(
        vec![
            [0.0, 0.0],
            [34.0, 0.0],
            [34.0, 2.0],
            [27.0, 2.0],
            [27.0, 6.0],
            [25.0, 6.0],
            [25.0, 2.0],
            [5.0, 2.0],
            [5.0, 6.0],
            [3.0, 6.0],
            [3.0, 2.0],
            [0.0, 2.0],
        ],
        vec![],
    )
    .unwrap();
    Walls::of(&d)
}

/// A noise-free lidar of 720 beams reaching `range` metres.
fn exact_lidar(range: f64) -> Lidar {
    Lidar { beams: 720, range_min: 0.05, range_max: range, sigma: 0.0, dropout: 0.0, spurious: 0.0 }
}

fn error(a: &Pose, b: &Pose) -> f64 {
    (a.x - b.x).hypot(a.y - b.y)
}

#[test]
fn a_loop_closure_moves_the_stops_odometry_misplaced_along_a_corridor() {
    let walls = corridor();
    let lidar = exact_lidar(8.0);
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let mut mapper = Mapper::new(MapperParams::for_sensor(0.01, 0.02, 0.002));
    let at = |x: f64| Pose { x, y: 1.0, theta: 0.0 };
    // Stop 0 sees the first side corridor; stop 1 sees only the corridor, stop 2 the
    // corridor and the second side corridor. The robot reaches stop 1 by a 40 m detour,
    // and odometry overshoots by 0.3 m there; ICP cannot tell along the corridor. Stop 3
    // comes back to the first side corridor: a loop closure. The detour is the least sure
    // leg, so the graph puts the correction there.
    let truth = [at(6.5), at(14.0), at(21.0), at(7.5), at(20.0)];
    let overshoot = [0.0, 0.3, 0.0, 0.0, 0.0];
    let driven = [0.0, 40.0, 7.0, 13.5, 12.5];
    let mut reported: Vec<Pose> = Vec::new();
    for (k, t) in truth.iter().enumerate() {
        let scan = lidar.scan(&walls, t, &mut rng);
        let odometry = match reported.last() {
            None => *t,
            Some(prev) => {
                let step = truth[k - 1].inverse().compose(t);
                prev.compose(&Pose { x: step.x + overshoot[k], ..step })
            }
        };
        let reading = mapper.read(&scan, &odometry, driven[k]).unwrap();
        reported.push(reading.estimate);
        if k == 2 {
            // Before the loop closes, stops 1 and 2 are where odometry put them.
            assert!(error(&reading.estimate, t) > 0.2, "stop 2: {:?}", reading.estimate);
        }
        if k == 0 {
            assert_eq!(reading.placement, 0.0, "the first stop defines the map frame");
        }
        if k == 1 {
            // After a 40 m drive, ICP unable to tell where along the corridor: the graph
            // knows the stop only as well as odometry, 2% of 40 m along it.
            assert!(reading.placement > 0.4, "stop 1 spread {}", reading.placement);
        }
        if k == 3 {
            assert!(reading.links >= 1, "stop 3 matched to stop 0");
            assert!(reading.placement < 0.05, "stop 3 tied to stop 0: {}", reading.placement);
        }
    }
    // Stop 3 is placed by the first side corridor, and the graph moved stops 1 and 2 back with it.
    let now = mapper.poses();

    for k in 1..=3 {
        assert!(error(&now[k], &truth[k]) < 0.05, "stop {k} now {:?}", now[k]);
    }
    // Stop 4 sees the second side corridor, whose walls stop 2 put in the map 0.3 m off; they were
    // moved with stop 2, so the scan aligns to them where they are.
    assert!(error(&reported[4], &truth[4]) < 0.05, "stop 4 {:?}", reported[4]);
}

/// An L-shaped hall with a pillar: walls in every direction, so a scan's alignment is
/// determined, from a guess a metre or more off too.
fn hall() -> Walls {
    let d = Domain::new(
        vec![[0.0, 0.0], [12.0, 0.0], [12.0, 5.0], [7.0, 5.0], [7.0, 9.0], [0.0, 9.0]],
        vec![vec![[3.0, 3.0], [3.0, 4.0], [4.0, 4.0], [4.0, 3.0]]],
    )
    .unwrap();
    Walls::of(&d)
}

#[test]
fn a_robot_whose_corrections_were_refused_is_placed_again_once_its_drift_allows_it() {
    // The robot is 1.2 m off (it was misplaced before these stops) and drives 5 m between
    // stops. One leg's drift (2% a metre) cannot explain 1.2 m, so the first corrections are
    // refused as implausible and odometry is kept. But a stop that kept odometry corrected
    // nothing: the drift since the last kept alignment adds up, and once it can explain the
    // offset, the alignment is kept and the robot is where it is.
    let walls = hall();
    let lidar = exact_lidar(20.0);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut mapper = Mapper::new(MapperParams::for_sensor(0.01, 0.02, 0.002));
    let truth = [
        Pose { x: 2.0, y: 2.0, theta: 0.0 },
        Pose { x: 9.0, y: 2.5, theta: 0.3 },
        Pose { x: 5.0, y: 6.5, theta: -0.2 },
        Pose { x: 9.5, y: 1.5, theta: 0.1 },
        Pose { x: 2.0, y: 7.0, theta: 0.0 },
    ];
    let mut errors = Vec::new();
    let mut reported: Vec<Pose> = Vec::new();
    let mut refused = 0;
    for (k, t) in truth.iter().enumerate() {
        let scan = lidar.scan(&walls, t, &mut rng);
        // The first stop places the map; the robot then reaches stop 1 1.2 m off, and
        // odometry counts each later move from the pose reported for the stop before.
        let odometry = match k {
            0 => *t,
            1 => Pose { x: t.x + 0.9, y: t.y - 0.8, ..*t },
            _ => reported[k - 1].compose(&truth[k - 1].inverse().compose(t)),
        };
        let reading = mapper.read(&scan, &odometry, if k == 0 { 0.0 } else { 5.0 }).unwrap();
        if reading.alignment.as_ref().is_some_and(|a| a.fallback.is_some()) {
            refused += 1;
        }
        errors.push(error(&reading.estimate, t));
        reported.push(reading.estimate);
    }
    // One leg cannot explain the offset: the first stops after the map's are refused.
    assert!(errors[1] > 1.0 && errors[2] > 1.0 && refused >= 2, "{errors:?}");
    // Once the drift since the last kept alignment can, the robot is placed again, and
    // stays placed.
    assert!(errors[3] < 0.05 && errors[4] < 0.05, "{errors:?}");
}
