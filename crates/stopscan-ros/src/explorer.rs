//! The explorer node: ROS topics and nav2's action on one side, a stopscan session
//! ([`stopscan::pipeline::serve::Server`]) on the other. Each step of the session becomes ROS
//! traffic:
//! - a scan request waits until the robot has stopped (the goal succeeded), then takes the
//!   second `/scan` message to arrive (the first may have begun while the robot moved) and
//!   the latest `/odom` pose;
//! - a goal is published on `explore/next_scan_pose` and, with nav2, sent to
//!   `navigate_to_pose`: success is an arrival; a rejected goal is `blocked`, an aborted or
//!   cancelled one `aborted`, one past `--goal-timeout` is cancelled and `timed_out`. In the
//!   publish-only mode the node waits for `/odom` to come within `--tolerance` of the goal;
//! - done publishes `complete` (and, with `--return-home`, drives back to the start:
//!   `returning`, then `returned`).
//!
//! `explore/resume` (`std_msgs/Bool`) pauses (false) and resumes (true) between steps.

use std::path::PathBuf;
use std::time::{Duration, Instant};

use anyhow::{Context as _, bail};
use ros2_client::action::GoalStatusEnum;
use ros2_client::{
    ActionTypeName, MessageTypeName, Name, Node, NodeName, NodeOptions, Publisher, ServiceMapping,
    Subscription, action,
};
use serde_json::{Value, json};
use stopscan::pipeline::serve::{ServeOptions, Server};

use crate::msgs::{
    BoolMsg, Header, LaserScan, NavigateFeedback, NavigateGoal, NavigateResult, Odometry, Pose,
    PoseStamped, StringMsg,
};

/// How goals reach the robot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Drive {
    /// Through nav2's `navigate_to_pose` action.
    Nav2,
    /// Only published on `explore/next_scan_pose`; the node waits for the robot to get there.
    PublishOnly,
}

/// How the explorer runs.
#[derive(Debug, Clone)]
pub struct ExplorerOptions {
    /// DDS domain.
    pub domain: u16,
    /// Keep DDS traffic on the loopback interface.
    pub localhost: bool,
    /// The `start` message's set-up (strategy, cost, robot, sensor, odometry drift).
    pub setup: serde_json::Map<String, Value>,
    /// How goals reach the robot.
    pub drive: Drive,
    /// Send goals in the map frame (`map_goal`, for a robot that localises itself) instead of
    /// the odometry frame.
    pub map_goals: bool,
    /// The frame goals are stamped in.
    pub frame_id: String,
    /// A new journal.
    pub journal: Option<PathBuf>,
    /// A journal to resume.
    pub resume: Option<PathBuf>,
    /// The longest a goal may take.
    pub goal_timeout: Duration,
    /// Publish-only mode: how near the goal counts as there, metres.
    pub tolerance: f64,
    /// Drive back to the start when done.
    pub return_home: bool,
    /// The scan limit.
    pub max_scans: u64,
    /// The longest to wait for the first `/scan`, `/odom` and the nav2 server.
    pub wait: Duration,
}

/// The ROS side: subscriptions, publishers and the action client, and the latest messages.
struct Ros {
    node: Node,
    scans: Subscription<LaserScan>,
    odoms: Subscription<Odometry>,
    resume: Subscription<BoolMsg>,
    status: Publisher<StringMsg>,
    next: Publisher<PoseStamped>,
    nav: action::ActionClient<NavigateGoal, NavigateResult, NavigateFeedback>,
    scan: Option<LaserScan>,
    scan_count: u64,
    odom: Option<Pose>,
    paused: bool,
}

const POLL: Duration = Duration::from_millis(5);

impl Ros {
    fn new(o: &ExplorerOptions) -> anyhow::Result<Self> {
        let ctx = crate::context(o.domain, o.localhost)?;
        let mut node = ctx.new_node(NodeName::new("/", "stopscan")?, NodeOptions::new())?;
        smol::spawn(node.spinner()?.spin()).detach();
        let topic = |node: &Node, ns: &str, name: &str, pkg: &str, ty: &str, qos| {
            node.create_topic(&Name::new(ns, name)?, MessageTypeName::new(pkg, ty), &qos)
                .map_err(anyhow::Error::from)
        };
        let t = topic(&node, "/", "scan", "sensor_msgs", "LaserScan", crate::sensor_qos())?;
        let scans = node.create_subscription(&t, None)?;
        let t = topic(&node, "/", "odom", "nav_msgs", "Odometry", crate::sensor_qos())?;
        let odoms = node.create_subscription(&t, None)?;
        let t = topic(&node, "/explore", "resume", "std_msgs", "Bool", crate::command_qos())?;
        let resume = node.create_subscription(&t, None)?;
        let t = topic(&node, "/explore", "status", "std_msgs", "String", crate::latched_qos())?;
        let status = node.create_publisher(&t, None)?;
        let t = topic(
            &node,
            "/explore",
            "next_scan_pose",
            "geometry_msgs",
            "PoseStamped",
            crate::latched_qos(),
        )?;
        let next = node.create_publisher(&t, None)?;
        let nav = node.create_action_client(
            ServiceMapping::Enhanced,
            &Name::new("/", "navigate_to_pose")?,
            &ActionTypeName::new("nav2_msgs", "NavigateToPose"),
            crate::action_client_qos(),
        )?;
        Ok(Self {
            node,
            scans,
            odoms,
            resume,
            status,
            next,
            nav,
            scan: None,
            scan_count: 0,
            odom: None,
            paused: false,
        })
    }

    /// Reads every message waiting.
    fn poll(&mut self) {
        while let Ok(Some((s, _))) = self.scans.take() {
            self.scan = Some(s);
            self.scan_count += 1;
        }
        while let Ok(Some((o, _))) = self.odoms.take() {
            self.odom = Some(o.pose.pose);
        }
        while let Ok(Some((b, _))) = self.resume.take() {
            self.paused = !b.data;
        }
    }

    /// Polls until `ready` holds, or `limit` passes.
    async fn until(&mut self, limit: Duration, ready: impl Fn(&Self) -> bool) -> bool {
        let t = Instant::now();
        loop {
            self.poll();
            if ready(self) {
                return true;
            }
            if t.elapsed() >= limit {
                return false;
            }
            smol::Timer::after(POLL).await;
        }
    }

    fn say(&self, status: &str) {
        eprintln!("explore/status: {status}");
        let _ = self.status.publish(StringMsg { data: status.into() });
    }

    /// Waits while paused.
    async fn unpaused(&mut self) {
        self.poll();
        if self.paused {
            self.say("paused");
            self.until(Duration::MAX, |r| !r.paused).await;
            self.say("started");
        }
    }

    fn odom(&self) -> Value {
        json!(self.odom.expect("odometry arrived").to_protocol())
    }

    /// A fresh scan: the second to arrive from now, with the odometry pose then.
    async fn fresh_scan(&mut self, limit: Duration) -> anyhow::Result<(Value, Value)> {
        self.poll();
        let want = self.scan_count + 2;
        if !self.until(limit, |r| r.scan_count >= want).await {
            bail!("no /scan message for {limit:?}");
        }
        let scan = self.scan.as_ref().expect("a scan arrived").to_protocol();
        Ok((json!(scan), self.odom()))
    }

    /// Drives to `goal`; the request's type and reason (for a failure).
    async fn drive(
        &mut self,
        goal: &stopscan::protocol::laser::Pose,
        o: &ExplorerOptions,
    ) -> (&'static str, Option<&'static str>) {
        let stamped = PoseStamped {
            header: Header::now(&o.frame_id),
            pose: Pose::planar(goal.x, goal.y, goal.theta),
        };
        let _ = self.next.publish(stamped.clone());
        if o.drive == Drive::PublishOnly {
            let near = |r: &Self| {
                r.odom.is_some_and(|p| {
                    (p.position.x - goal.x).hypot(p.position.y - goal.y) <= o.tolerance
                })
            };
            return if self.until(o.goal_timeout, near).await {
                ("arrived", None)
            } else {
                ("move_failed", Some("timed_out"))
            };
        }
        let request = NavigateGoal { pose: stamped, behavior_tree: String::new() };
        let limit = o.goal_timeout;
        let sent = async { Some(self.nav.async_send_goal(request).await) };
        let (id, response) = match smol::future::or(sent, expire(limit)).await {
            Some(Ok(r)) => r,
            Some(Err(e)) => {
                eprintln!("navigate_to_pose: the goal could not be sent: {e:?}");
                return ("move_failed", Some("aborted"));
            }
            None => return ("move_failed", Some("timed_out")),
        };
        if !response.accepted {
            return ("move_failed", Some("blocked"));
        }
        let result = async { Some(self.nav.async_request_result(id).await) };
        match smol::future::or(result, expire(limit)).await {
            Some(Ok((GoalStatusEnum::Succeeded, _))) => {
                // The pose after the move.
                let before = self.scan_count;
                let _ = self.until(Duration::from_secs(2), |r| r.scan_count > before).await;
                ("arrived", None)
            }
            Some(_) => ("move_failed", Some("aborted")),
            None => {
                let _ = self
                    .nav
                    .async_cancel_goal(id, ros2_client::builtin_interfaces::Time::ZERO)
                    .await;
                ("move_failed", Some("timed_out"))
            }
        }
    }
}

/// Resolves to `None` after `limit`: the other side of a race with a timeout.
async fn expire<T>(limit: Duration) -> Option<T> {
    smol::Timer::after(limit).await;
    None
}

/// Runs the explorer to the end of its session: the final reply (`done`).
///
/// # Errors
/// No `/scan`, `/odom` or nav2 server within the wait, a journal that cannot be written, or
/// an error reply from the session.
pub fn run(o: &ExplorerOptions) -> anyhow::Result<Value> {
    smol::block_on(explore(o))
}

async fn explore(o: &ExplorerOptions) -> anyhow::Result<Value> {
    let options = ServeOptions { max_scans: o.max_scans, fsync: false, record: false };
    let mut server = match (&o.journal, &o.resume) {
        (_, Some(r)) => Server::resume(r, options)?,
        (Some(j), None) => Server::with_journal(j, options)?,
        (None, None) => Server::new(options),
    };
    let mut ros = Ros::new(o)?;
    eprintln!("waiting for /scan and /odom");
    if !ros.until(o.wait, |r| r.odom.is_some() && r.scan.is_some()).await {
        ros.say("failed");
        bail!("no /scan and /odom messages within {:?}", o.wait);
    }
    if o.drive == Drive::Nav2 {
        let found = smol::future::or(
            async {
                ros.nav.goal_client().wait_for_service(&ros.node).await;
                true
            },
            async {
                smol::Timer::after(o.wait).await;
                false
            },
        )
        .await;
        if !found {
            ros.say("failed");
            bail!("no navigate_to_pose action server within {:?}", o.wait);
        }
    }
    let start_pose = ros.odom.expect("odometry arrived");
    let mut reply: Value = if let Some(r) = server.last_reply() {
        serde_json::from_str(r)?
    } else {
        let mut m = o.setup.clone();
        m.insert("protocol".into(), "stopscan/1".into());
        m.insert("seq".into(), 0.into());
        m.insert("type".into(), "start".into());
        m.insert("pose".into(), ros.odom());
        serde_json::from_str(&server.handle(&Value::Object(m).to_string())?)?
    };
    ros.say("started");
    loop {
        let seq = server.steps();
        let request = match reply["type"].as_str() {
            Some("scan") => {
                ros.unpaused().await;
                let (scan, pose) = ros.fresh_scan(o.wait).await?;
                json!({"seq": seq, "type": "scan", "pose": pose, "scan": scan})
            }
            Some("goal") => {
                ros.unpaused().await;
                let key = if o.map_goals { "map_goal" } else { "goal" };
                let goal: stopscan::protocol::laser::Pose =
                    serde_json::from_value(reply[key].clone()).context("a goal without a pose")?;
                let (kind, reason) = ros.drive(&goal, o).await;
                ros.poll();
                let mut r = json!({"seq": seq, "type": kind, "pose": ros.odom()});
                if let Some(reason) = reason {
                    r["reason"] = reason.into();
                }
                r
            }
            Some("done") => break,
            _ => {
                ros.say("failed");
                bail!("the session answered {reply}");
            }
        };
        reply = serde_json::from_str(&server.handle(&request.to_string())?)?;
    }
    ros.say("complete");
    if o.return_home && o.drive == Drive::Nav2 {
        ros.say("returning");
        let home = start_pose.to_protocol();
        let (kind, _) = ros.drive(&home, &ExplorerOptions { map_goals: false, ..o.clone() }).await;
        ros.say(if kind == "arrived" { "returned" } else { "failed" });
    }
    // Let the latched status reach late subscribers' first match.
    smol::Timer::after(Duration::from_millis(200)).await;
    Ok(reply)
}
