//! `serve --mcap FILE`: a session recorded for Foxglove, step by step, with the same
//! Foxglove schemas as the simulator's recordings ([`crate::render::mcap`]).
//!
//! The protocol carries no clock for one robot, so a session's time is its mission time under
//! its cost model, priced from what the robot reports: a scan costs `scan_time`; a move costs
//! `move_time` plus the straight distance between the poses the robot reported before and
//! after it, over `speed`. A team's requests carry the team's clock (`time`), which is used
//! when given. Steps replayed from a journal (`--resume`) are recorded like live ones, so a
//! resumed session's recording is the whole session's.
//!
//! Topics: `/tf` (`odom → base_link`, or `odom → robot_<i>` for a team, at every pose the
//! robot reports; `map → odom` from every scan's localisation), `/lidar` (every laser scan,
//! in `map` where it was localised, else in `odom`), `/goal` (PosesInFrame: every goal, in
//! `odom`) and `/log` (every request and reply, in words).

use std::collections::BTreeMap;

use serde_json::json;

use super::message::{OrderKind, Reply, ReplyBody, Request};
use crate::protocol::CostModel;
use crate::protocol::laser::Pose;
use crate::render::mcap::{INFO, McapError, McapWriter, WARNING};
use crate::render::mcap::{frame_transform, laser_scan, log, pose, time};

/// What a session did, kept to be written as MCAP when it ends.
#[derive(Debug, Default)]
pub struct SessionRecording {
    steps: Vec<(Request, Reply)>,
}

impl SessionRecording {
    /// Keeps one step.
    pub fn push(&mut self, request: Request, reply: Reply) {
        self.steps.push((request, reply));
    }

    /// Steps kept.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// Whether no step was kept.
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// The recording, as MCAP bytes.
    ///
    /// # Errors
    /// [`McapError`] if the writer fails (only on a bug: it writes to memory).
    pub fn mcap(&self) -> Result<Vec<u8>, McapError> {
        let mut w = McapWriter::in_memory()?;
        let mut cost = CostModel::default();
        let mut meta = BTreeMap::new();
        meta.insert("stopscan_version".into(), env!("CARGO_PKG_VERSION").to_string());
        meta.insert("protocol".into(), super::PROTOCOL.to_string());
        meta.insert(
            "time_origin".into(),
            "0 s = the session's start; mission time under its cost model, priced from the poses the robot reported (a team's own clock where its requests give one)".into(),
        );
        if let Some((Request::Start(s), _)) = self.steps.first() {
            if let Some(c) = s.cost
                && let Ok(m) = CostModel::new(c.scan_time, c.move_time, c.speed)
            {
                cost = m;
            }
            meta.insert("family".into(), s.family.name().to_string());
            meta.insert("strategy".into(), s.strategy.clone().unwrap_or_default());
        }
        meta.insert("cost_model".into(), serde_json::to_string(&cost).unwrap_or_default());
        meta.insert("steps".into(), self.steps.len().to_string());
        w.metadata(meta)?;
        let mut clock = Clock { cost, now: 0.0, last: BTreeMap::new() };
        for (seq, (request, reply)) in self.steps.iter().enumerate() {
            let at = clock.before(request);
            let what = request_messages(&mut w, at, request, reply)?;
            let (level, answer) = reply_messages(&mut w, at, reply)?;
            w.write(
                "/log",
                "foxglove.Log",
                at,
                &log(at, level, &format!("step {seq}: {what}; {answer}")),
            )?;
            clock.after(reply);
        }
        w.bytes()
    }
}

/// The messages of one request (its poses, its scan); what it was, in words.
fn request_messages(
    w: &mut McapWriter,
    at: f64,
    request: &Request,
    reply: &Reply,
) -> Result<String, McapError> {
    // Every request reports where its robot stands: `odom → base_link` for one robot,
    // `odom → robot_<i>` for a team's.
    let (robot, p) = match request {
        Request::Start(s) => (None, s.pose),
        _ => request.team_fields().map(|(robot, _, p)| (robot, p)).unwrap_or_default(),
    };
    let child = robot.map_or("base_link".to_string(), |r| format!("robot_{r}"));
    w.write(
        "/tf",
        "foxglove.FrameTransform",
        at,
        &frame_transform("odom", &child, at, p.x, p.y, p.theta),
    )?;
    Ok(match request {
        Request::Start(s) => {
            format!("start: {} {}", s.family.name(), s.strategy.as_deref().unwrap_or(""))
        }
        Request::Scan(s) => {
            if let Some(scan) = &s.scan {
                let message = match &reply.localised {
                    Some(l) => {
                        let c = l.correction;
                        w.write(
                            "/tf",
                            "foxglove.FrameTransform",
                            at,
                            &frame_transform("map", "odom", at, c.x, c.y, c.theta),
                        )?;
                        laser_scan("map", at, &l.pose, scan)
                    }
                    None => laser_scan("odom", at, &p, scan),
                };
                w.write("/lidar", "foxglove.LaserScan", at, &message)?;
            }
            format!("scan at ({:.3}, {:.3}) in odom", p.x, p.y)
        }
        Request::Arrived(_) | Request::Found(_) | Request::Stop(_) => {
            format!("{} at ({:.3}, {:.3}) in odom", request.kind(), p.x, p.y)
        }
        Request::MoveFailed(f) => {
            format!("move failed ({}) at ({:.3}, {:.3}) in odom", f.reason.name(), p.x, p.y)
        }
    })
}

/// The messages of one reply (its goals); its level and what it said, in words.
fn reply_messages(w: &mut McapWriter, at: f64, reply: &Reply) -> Result<(u8, String), McapError> {
    Ok(match &reply.body {
        ReplyBody::Scan => (INFO, "scan here".to_string()),
        ReplyBody::Goal { goal, .. } => {
            w.write("/goal", "foxglove.PosesInFrame", at, &goal_message(at, &[*goal]))?;
            (INFO, format!("go to ({:.3}, {:.3}) in odom", goal.x, goal.y))
        }
        ReplyBody::Orders { orders } => {
            let goals: Vec<Pose> = orders
                .iter()
                .filter_map(|o| match &o.what {
                    OrderKind::Goal { goal, .. } => Some(*goal),
                    _ => None,
                })
                .collect();
            if !goals.is_empty() {
                w.write("/goal", "foxglove.PosesInFrame", at, &goal_message(at, &goals))?;
            }
            (INFO, format!("{} orders", orders.len()))
        }
        ReplyBody::Done { reason, summary } => (
            INFO,
            format!(
                "done ({}): {} scans, {:.3} m, {:.3} s",
                serde_json::to_string(reason).unwrap_or_default().trim_matches('"'),
                summary.totals.scans,
                summary.totals.distance,
                summary.totals.time
            ),
        ),
        ReplyBody::Error { message, .. } => (WARNING, format!("error: {message}")),
    })
}

fn goal_message(at: f64, goals: &[Pose]) -> serde_json::Value {
    let poses: Vec<_> = goals.iter().map(|g| pose(g.x, g.y, g.theta)).collect();
    json!({"timestamp": time(at), "frame_id": "odom", "poses": poses})
}

/// The session's time, priced from the robot's reports.
struct Clock {
    cost: CostModel,
    now: f64,
    /// Each robot's last reported pose.
    last: BTreeMap<Option<usize>, Pose>,
}

impl Clock {
    /// The time of `request`: a team's own clock when it gives one; else the time after the
    /// move that brought the robot from its last reported pose.
    fn before(&mut self, request: &Request) -> f64 {
        let Some((robot, time, p)) = request.team_fields() else {
            if let Request::Start(s) = request {
                self.last.insert(None, s.pose);
            }
            return self.now;
        };
        if let Some(t) = time.filter(|t| t.is_finite()) {
            self.now = self.now.max(t);
        } else if let Some(q) = self.last.get(&robot)
            && (q.x != p.x || q.y != p.y)
        {
            self.now += self.cost.move_time + (p.x - q.x).hypot(p.y - q.y) / self.cost.speed;
        }
        self.last.insert(robot, p);
        self.now
    }

    /// A reply that asks for a scan costs the scan's time.
    fn after(&mut self, reply: &Reply) {
        let scans = match &reply.body {
            ReplyBody::Scan => 1,
            ReplyBody::Orders { orders } => {
                usize::from(orders.iter().any(|o| matches!(o.what, OrderKind::Scan { .. })))
            }
            _ => 0,
        };
        self.now += self.cost.scan_time * scans as f64;
    }
}
