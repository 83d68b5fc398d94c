//! `stopscan-ros`: the stopscan explorer as a ROS 2 node, and a fake robot to try it with.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Duration;

use clap::{Parser, Subcommand};
use serde_json::json;
use stopscan_ros::explorer::{self, Drive, ExplorerOptions};
use stopscan_ros::fake_robot::{self, FakeRobotOptions};

#[derive(Debug, Parser)]
#[command(name = "stopscan-ros", version, about = "stopscan as a ROS 2 node (pure Rust)")]
struct Cli {
    /// DDS domain (ROS_DOMAIN_ID).
    #[arg(long, global = true, default_value_t = 0)]
    domain: u16,
    /// Keep DDS discovery and data on the loopback interface (ROS_LOCALHOST_ONLY).
    #[arg(long, global = true)]
    localhost: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Explore: /scan and /odom in, nav2 navigate_to_pose goals out; explore/status,
    /// explore/next_scan_pose and the explore/resume switch.
    Explore(ExploreArgs),
    /// A simulated robot in an environment file: nav2's action server, /scan and /odom.
    FakeRobot(FakeArgs),
}

#[derive(Debug, clap::Args)]
struct ExploreArgs {
    /// The polygon strategy (as `stopscan explore --strategy`).
    #[arg(long, default_value = "cost_aware")]
    strategy: String,
    /// The robot's radius, metres.
    #[arg(long, default_value_t = 0.2)]
    robot_radius: f64,
    /// Seconds per scan.
    #[arg(long, default_value_t = 30.0)]
    scan_time: f64,
    /// Metres per second.
    #[arg(long, default_value_t = 0.5)]
    speed: f64,
    /// The lidar's range noise, metres.
    #[arg(long, default_value_t = 0.02)]
    sigma: f64,
    /// Odometry's drift per metre driven.
    #[arg(long, default_value_t = 0.01)]
    odometry_drift: f64,
    /// Relays: when the scan where a trip ends is predicted not to be placed by scan matching
    /// and odometry may be off there by more than M metres (one standard deviation), the
    /// robot is first sent to a place on the way where a scan can be placed, and scans there.
    /// 0 never relays.
    #[arg(long, value_name = "M", default_value_t = stopscan::sensing::mapper::RELAY)]
    relay: f64,
    /// Only publish the next scan pose (the robot is driven by other means) instead of sending
    /// nav2 goals.
    #[arg(long)]
    publish_only: bool,
    /// Send goals in the map frame (for a robot that localises itself) instead of the
    /// odometry frame.
    #[arg(long)]
    map_goals: bool,
    /// The frame goals are stamped in.
    #[arg(long, default_value = "odom")]
    frame_id: String,
    /// Seconds a goal may take.
    #[arg(long, default_value_t = 300.0)]
    goal_timeout: f64,
    /// With --publish-only: how near the goal counts as there, metres.
    #[arg(long, default_value_t = 0.25)]
    tolerance: f64,
    /// Drive back to the start when done.
    #[arg(long)]
    return_home: bool,
    /// Journal the session here (for --resume).
    #[arg(long, conflicts_with = "resume")]
    journal: Option<PathBuf>,
    /// Go on from this journal.
    #[arg(long)]
    resume: Option<PathBuf>,
    /// The most scans.
    #[arg(long, default_value_t = 20_000)]
    max_scans: u64,
    /// Seconds to wait for /scan, /odom and the nav2 server.
    #[arg(long, default_value_t = 60.0)]
    wait: f64,
    /// Write the final reply (done, with the summary) here as JSON.
    #[arg(long)]
    out: Option<PathBuf>,
}

#[derive(Debug, clap::Args)]
struct FakeArgs {
    /// The environment (GeoJSON with a start, WKT, .pol, ROS map).
    #[arg(long)]
    env: PathBuf,
    /// The robot's radius, metres.
    #[arg(long, default_value_t = 0.2)]
    robot_radius: f64,
    /// The lidar: `lidar[:beams=720,max=20,sigma=0.02,dropout=0.01,spurious=0,min=0.05]`.
    #[arg(long, default_value = "lidar")]
    sensor: String,
    /// Odometry's drift per metre driven.
    #[arg(long, default_value_t = 0.01)]
    odometry_drift: f64,
    /// Seed of the noise and the drift.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Scans and odometry messages per second.
    #[arg(long, default_value_t = 20.0)]
    rate: f64,
}

fn seconds(name: &str, s: f64) -> anyhow::Result<Duration> {
    Duration::try_from_secs_f64(s)
        .map_err(|_| anyhow::anyhow!("--{name} must be seconds >= 0, got {s}"))
}

fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Explore(a) => {
            let setup = json!({
                "strategy": a.strategy,
                "cost": {"scan_time": a.scan_time, "speed": a.speed},
                "robot": {"radius": a.robot_radius},
                "sensor": {"sigma": a.sigma},
                "odometry_drift": a.odometry_drift,
                "relay": a.relay,
            });
            let o = ExplorerOptions {
                domain: cli.domain,
                localhost: cli.localhost,
                setup: setup.as_object().expect("an object").clone(),
                drive: if a.publish_only { Drive::PublishOnly } else { Drive::Nav2 },
                map_goals: a.map_goals,
                frame_id: a.frame_id,
                journal: a.journal,
                resume: a.resume,
                goal_timeout: seconds("goal-timeout", a.goal_timeout)?,
                tolerance: a.tolerance,
                return_home: a.return_home,
                max_scans: a.max_scans,
                wait: seconds("wait", a.wait)?,
            };
            let done = explorer::run(&o)?;
            let text = serde_json::to_string_pretty(&done)?;
            match a.out {
                Some(p) => std::fs::write(&p, text + "\n")
                    .map_err(|e| anyhow::anyhow!("cannot write {}: {e}", p.display()))?,
                None => println!("{text}"),
            }
            Ok(())
        }
        Command::FakeRobot(a) => match fake_robot::run(&FakeRobotOptions {
            domain: cli.domain,
            localhost: cli.localhost,
            env: a.env,
            radius: a.robot_radius,
            lidar: a.sensor.parse().map_err(|e| anyhow::anyhow!("--sensor: {e}"))?,
            drift: a.odometry_drift,
            seed: a.seed,
            rate: a.rate,
        })? {},
    }
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}
