//! A robot for tests and demos, over ROS 2: stopscan's simulated robot
//! ([`stopscan::sim::lidar::SimRobot`]: a noisy lidar, drifting odometry, a navigation stack
//! that refuses goals the footprint cannot reach) in a polygon world, playing nav2's
//! `navigate_to_pose` action server and publishing `/scan` (best effort) and `/odom` at a
//! fixed rate. A goal succeeds when the robot gets there, and is aborted when the way is
//! blocked.

use std::cell::RefCell;
use std::path::PathBuf;
use std::rc::Rc;
use std::time::Duration;

use anyhow::Context as _;
use ros2_client::action::{AsyncActionServer, GoalEndStatus};
use ros2_client::{ActionTypeName, MessageTypeName, Name, NodeName, NodeOptions, ServiceMapping};
use stopscan::protocol::polygon::Footprint;
use stopscan::sim::lidar::SimRobot;
use stopscan::world::lidar::Lidar;
use stopscan::world::polygon::PolygonWorld;

use crate::msgs::{
    Covariance, Header, LaserScan, NavigateFeedback, NavigateGoal, NavigateResult, Odometry, Pose,
    PoseWithCovariance, TwistWithCovariance,
};

/// The simulated robot's set-up.
#[derive(Debug, Clone)]
pub struct FakeRobotOptions {
    /// DDS domain.
    pub domain: u16,
    /// Keep DDS traffic on the loopback interface.
    pub localhost: bool,
    /// The environment file (any format `stopscan explore` reads).
    pub env: PathBuf,
    /// The robot's radius, metres.
    pub radius: f64,
    /// The lidar.
    pub lidar: Lidar,
    /// Odometry's drift per metre.
    pub drift: f64,
    /// The seed of the noise and the drift.
    pub seed: u64,
    /// Scans and odometry per second.
    pub rate: f64,
}

/// Runs the robot until the process is stopped (it never returns `Ok`).
///
/// # Errors
/// The environment does not load, the footprint does not fit at its start, or DDS fails.
pub fn run(o: &FakeRobotOptions) -> anyhow::Result<std::convert::Infallible> {
    let env = stopscan::io::read_environment(&o.env)?;
    let start = env.start.with_context(|| format!("{}: no start", o.env.display()))?;
    let footprint = Footprint::disc(o.radius)?;
    let world = PolygonWorld::with_robot(env.domain, None, &footprint, Some(start))?;
    // The robot borrows the world for as long as the process runs.
    let world: &'static PolygonWorld = Box::leak(Box::new(world));
    let start = world.reach().map_or(start, stopscan::world::polygon::Reach::start);
    let robot = Rc::new(RefCell::new(SimRobot::new(world, start, o.lidar, o.drift, o.seed)));

    let ctx = crate::context(o.domain, o.localhost)?;
    let mut node = ctx.new_node(NodeName::new("/", "fake_robot")?, NodeOptions::new())?;
    let scan_topic = node.create_topic(
        &Name::new("/", "scan")?,
        MessageTypeName::new("sensor_msgs", "LaserScan"),
        &crate::sensor_qos(),
    )?;
    let scans = node.create_publisher::<LaserScan>(&scan_topic, None)?;
    let odom_topic = node.create_topic(
        &Name::new("/", "odom")?,
        MessageTypeName::new("nav_msgs", "Odometry"),
        &crate::sensor_qos(),
    )?;
    let odoms = node.create_publisher::<Odometry>(&odom_topic, None)?;
    let nav = AsyncActionServer::new(
        node.create_action_server::<NavigateGoal, NavigateResult, NavigateFeedback>(
            ServiceMapping::Enhanced,
            &Name::new("/", "navigate_to_pose")?,
            &ActionTypeName::new("nav2_msgs", "NavigateToPose"),
            crate::action_server_qos(),
        )?,
    );
    let odometry = |r: &SimRobot<'_>| {
        let p = r.odometry();
        Odometry {
            header: Header::now("odom"),
            child_frame_id: "base_link".into(),
            pose: PoseWithCovariance {
                pose: Pose::planar(p.x, p.y, p.theta),
                covariance: Covariance::default(),
            },
            twist: TwistWithCovariance {
                twist: crate::msgs::Twist::default(),
                covariance: Covariance::default(),
            },
        }
    };
    let period = Duration::from_secs_f64(1.0 / o.rate.max(0.1));
    let ex = smol::LocalExecutor::new();
    let sensing = {
        let robot = robot.clone();
        ex.spawn(async move {
            loop {
                let (scan, odom) = {
                    let mut r = robot.borrow_mut();
                    (r.scan(), odometry(&r))
                };
                let _ = odoms.publish(odom);
                let _ = scans.publish(LaserScan::from_protocol(&scan, "base_link"));
                smol::Timer::after(period).await;
            }
        })
    };
    let serving = ex.spawn(async move {
        loop {
            let Ok(handle) = nav.receive_new_goal().await else { continue };
            let Some(goal) = nav.get_new_goal(handle.clone()) else { continue };
            let Ok(accepted) = nav.accept_goal(handle).await else { continue };
            let Ok(executing) = nav.start_executing_goal(accepted).await else { continue };
            let p = goal.pose.pose.position;
            let failed = robot.borrow_mut().drive([p.x, p.y]).failed;
            let (status, result) = match failed {
                None => (GoalEndStatus::Succeeded, NavigateResult::new(None)),
                Some(why) => (GoalEndStatus::Aborted, NavigateResult::new(Some(why.name()))),
            };
            let _ = nav.send_result_response(executing, status, result).await;
        }
    });
    eprintln!("fake robot at ({:.3}, {:.3}) in {}", start[0], start[1], o.env.display());
    // Both tasks loop for ever: the robot runs until the process is stopped.
    sensing.detach();
    smol::block_on(ex.run(serving))
}
