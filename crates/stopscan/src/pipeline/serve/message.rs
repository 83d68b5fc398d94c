//! The messages of protocol `stopscan/1` (see `docs/protocol.md`): what a robot sends, what
//! stopscan answers, and how a line of text becomes a request with every problem named by its
//! field.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::protocol::corner::{LastStep, Route, Stop};
use crate::protocol::grid::{Cell, Frame};
use crate::protocol::laser::{LaserScan, Pose};
use crate::protocol::{MoveFailure, RunTotals, Tally};
use crate::sensing::icp::Alignment;
use crate::sensing::ingest::Cleaning;
use crate::strategy::corner::ExprecReading;
use crate::strategy::polygon::Skipped;

/// The protocol's name and version, in every reply and in the journal's header.
pub const PROTOCOL: &str = "stopscan/1";

/// The longest request line read, bytes: a 100,000-beam scan written out in full is about
/// 2.5 MB.
pub const MAX_LINE: usize = 8 << 20;

/// A problem with a request: the field it is in (a path such as `scan.ranges[3]`; absent when
/// the line is not a JSON object at all) and what is wrong.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, thiserror::Error)]
#[error("{}{message}", field.as_ref().map(|f| format!("field `{f}`: ")).unwrap_or_default())]
pub struct ProtocolError {
    /// The field.
    pub field: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl ProtocolError {
    /// A problem with `field`.
    pub fn field(field: impl Into<String>, message: impl Into<String>) -> Self {
        Self { field: Some(field.into()), message: message.into() }
    }
}

/// Which problem family a session runs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Family {
    /// Exploring an unknown floor from laser scans (the polygon strategies).
    #[default]
    Polygon,
    /// Looking around a corner for a target behind it (the corner strategies).
    Corner,
    /// A team of robots mapping a region of interest cell by cell (Algorithm 1 of the ROI
    /// paper), on a grid that may drift.
    Roi,
}

impl Family {
    /// The family's name in the protocol.
    pub fn name(self) -> &'static str {
        match self {
            Self::Polygon => "polygon",
            Self::Corner => "corner",
            Self::Roi => "roi",
        }
    }
}

/// The cost model of a session, as sent.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CostIn {
    /// Seconds per scan.
    pub scan_time: f64,
    /// Seconds per move.
    #[serde(default)]
    pub move_time: f64,
    /// Metres per second.
    pub speed: f64,
}

/// The robot's body.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotIn {
    /// A disc of this radius, metres.
    #[serde(default)]
    pub radius: Option<f64>,
    /// A convex polygon around the reference point, metres (instead of `radius`).
    #[serde(default)]
    pub footprint: Option<Vec<[f64; 2]>>,
}

/// The laser and the window rule.
#[derive(Debug, Clone, Copy, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SensorIn {
    /// Range noise, metres (standard deviation).
    #[serde(default)]
    pub sigma: Option<f64>,
    /// The range strategies plan with, metres (absent: each scan's `range_max` shapes what
    /// is seen, and planning assumes no limit).
    #[serde(default)]
    pub range: Option<f64>,
    /// Beams per revolution, for the window rule.
    #[serde(default)]
    pub beams: Option<u32>,
    /// The smallest feature the sensor resolves, metres.
    #[serde(default)]
    pub min_feature: Option<f64>,
    /// The shortest window worth a trip, metres.
    #[serde(default)]
    pub min_window: Option<f64>,
}

/// The corner search's geometry and belief.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CornerIn {
    /// Distance from the robot to the corner, metres.
    pub distance: f64,
    /// The belief about the hidden edge's angle (`stopscan corner`'s spec: `uniform:0,90`).
    #[serde(default)]
    pub belief: Option<String>,
    /// How the robot drives between stops (UNIREC and EXPREC).
    #[serde(default)]
    pub route: Option<Route>,
    /// How the last step is charged.
    #[serde(default)]
    pub last_step: Option<LastStep>,
    /// Which EXPREC.
    #[serde(default)]
    pub exprec: Option<ExprecReading>,
    /// The MDP policies' stop spacing, degrees.
    #[serde(default)]
    pub mdp_step_degrees: Option<f64>,
}

/// The region's drift, as sent.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriftIn {
    /// S_p, metres per second.
    pub speed: f64,
    /// Degrees counter-clockwise from the grid's +x axis (the start pose's heading).
    #[serde(default)]
    pub heading_deg: f64,
}

/// A lawn-mowing search box, in cells relative to the start cell.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SearchIn {
    /// The box's smallest row and column.
    pub min: Cell,
    /// Its largest row and column.
    pub max: Cell,
}

/// The ROI team's set-up.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoiIn {
    /// How many robots (1 to [`MAX_TEAM`]).
    pub robots: usize,
    /// The side of a cell, metres (1 if absent).
    #[serde(default)]
    pub cell_size: Option<f64>,
    /// How the region moves (static if absent).
    #[serde(default)]
    pub drift: Option<DriftIn>,
    /// A lawn-mowing search first, when the team does not start over the region.
    #[serde(default)]
    pub search: Option<SearchIn>,
}

/// The largest team a session drives.
pub const MAX_TEAM: usize = 1024;

/// `start`: the session's set-up and where the robot stands.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartIn {
    /// The problem family.
    #[serde(default)]
    pub family: Family,
    /// The strategy's registry name (absent: the family's default).
    #[serde(default)]
    pub strategy: Option<String>,
    /// The robot's pose, in its odometry frame.
    pub pose: Pose,
    /// The cost model.
    #[serde(default)]
    pub cost: Option<CostIn>,
    /// The robot's body (polygon).
    #[serde(default)]
    pub robot: Option<RobotIn>,
    /// The sensor (polygon).
    #[serde(default)]
    pub sensor: Option<SensorIn>,
    /// Odometry's drift per metre driven (polygon).
    #[serde(default)]
    pub odometry_drift: Option<f64>,
    /// The relay rule's threshold, metres (polygon; 0 never relays):
    /// [`Mapper::relay`](crate::sensing::mapper::Mapper::relay).
    #[serde(default)]
    pub relay: Option<f64>,
    /// The corner search's set-up (corner).
    #[serde(default)]
    pub corner: Option<CornerIn>,
    /// The team's set-up (roi).
    #[serde(default)]
    pub roi: Option<RoiIn>,
}

/// `scan`: a scan and where odometry says it was taken.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScanIn {
    /// The pose, in the robot's odometry frame.
    pub pose: Pose,
    /// The laser scan (polygon).
    #[serde(default)]
    pub scan: Option<LaserScan>,
    /// The corner family's reading: the hidden edge's angle when it is seen, radians;
    /// `null` or absent while it is hidden.
    #[serde(default)]
    pub edge: Option<f64>,
    /// The roi family's reading: the camera frames taken over the cell.
    #[serde(default)]
    pub frames: Option<Vec<Frame>>,
    /// Which robot of a team (roi).
    #[serde(default)]
    pub robot: Option<usize>,
    /// The team's clock, seconds since the start (roi).
    #[serde(default)]
    pub time: Option<f64>,
}

impl ScanIn {
    /// Refuses a reading of another family than `family`'s: `scan` (polygon), `edge` (corner)
    /// or `frames` (roi).
    ///
    /// # Errors
    /// [`ProtocolError`] naming the reading and the family it is for.
    pub fn readings_for(&self, family: Family) -> Result<(), ProtocolError> {
        let readings = [
            ("scan", self.scan.is_some(), Family::Polygon),
            ("edge", self.edge.is_some(), Family::Corner),
            ("frames", self.frames.is_some(), Family::Roi),
        ];
        for (field, present, of) in readings {
            if present && of != family {
                return Err(ProtocolError::field(
                    field,
                    format!("is for the {} family", of.name()),
                ));
            }
        }
        Ok(())
    }
}

/// `arrived`, `found` or `stop`: where the robot stands.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PoseIn {
    /// The pose, in the robot's odometry frame.
    pub pose: Pose,
    /// Which robot of a team (roi).
    #[serde(default)]
    pub robot: Option<usize>,
    /// The team's clock, seconds since the start (roi).
    #[serde(default)]
    pub time: Option<f64>,
}

/// `move_failed`: where the robot stopped and why.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FailedIn {
    /// The pose, in the robot's odometry frame.
    pub pose: Pose,
    /// Why.
    pub reason: MoveFailure,
    /// Which robot of a team (roi).
    #[serde(default)]
    pub robot: Option<usize>,
    /// The team's clock, seconds since the start (roi).
    #[serde(default)]
    pub time: Option<f64>,
}

/// A request, by its `type`.
#[derive(Debug, Clone, PartialEq)]
pub enum Request {
    /// The session begins.
    Start(Box<StartIn>),
    /// The robot reached the goal.
    Arrived(PoseIn),
    /// The robot could not reach the goal.
    MoveFailed(FailedIn),
    /// The scan asked for.
    Scan(Box<ScanIn>),
    /// The robot found the target: the search ends.
    Found(PoseIn),
    /// The operator ends the session.
    Stop(PoseIn),
}

impl Request {
    /// The robot and the clock a team's request names (`robot`, `time`), and its pose.
    pub fn team_fields(&self) -> Option<(Option<usize>, Option<f64>, Pose)> {
        match self {
            Self::Start(_) => None,
            Self::Arrived(p) | Self::Found(p) | Self::Stop(p) => Some((p.robot, p.time, p.pose)),
            Self::MoveFailed(f) => Some((f.robot, f.time, f.pose)),
            Self::Scan(s) => Some((s.robot, s.time, s.pose)),
        }
    }

    /// The request's `type`.
    pub fn kind(&self) -> &'static str {
        match self {
            Self::Start(_) => "start",
            Self::Arrived(_) => "arrived",
            Self::MoveFailed(_) => "move_failed",
            Self::Scan(_) => "scan",
            Self::Found(_) => "found",
            Self::Stop(_) => "stop",
        }
    }
}

/// A request read from a line: its sequence number, the request, and the line in canonical
/// form (for the journal, and to recognise a request sent again).
#[derive(Debug, Clone, PartialEq)]
pub struct Parsed {
    /// The robot's sequence number.
    pub seq: u64,
    /// The request.
    pub request: Request,
    /// The request as canonical JSON.
    pub canonical: String,
}

/// Reads one request line. The error carries the sequence number when it could be read.
///
/// # Errors
/// [`ProtocolError`] naming the field: not JSON, not an object, a missing or wrong
/// `protocol`, `seq` or `type`, or a field of the wrong type or unknown to the message.
pub fn parse(line: &str) -> Result<Parsed, (Option<u64>, ProtocolError)> {
    let value: Value = serde_json::from_str(line).map_err(|e| {
        (None, ProtocolError { field: None, message: format!("not valid JSON: {e}") })
    })?;
    let canonical = value.to_string();
    let Value::Object(mut map) = value else {
        return Err((None, ProtocolError { field: None, message: "not a JSON object".into() }));
    };
    let seq = match map.remove("seq") {
        Some(Value::Number(n)) if n.as_u64().is_some() => n.as_u64(),
        Some(other) => {
            return Err((
                None,
                ProtocolError::field("seq", format!("must be an integer >= 0, got {other}")),
            ));
        }
        None => return Err((None, ProtocolError::field("seq", "missing"))),
    };
    let fail = |e: ProtocolError| Err((seq, e));
    let kind = match map.remove("type") {
        Some(Value::String(s)) => s,
        Some(other) => {
            return fail(ProtocolError::field("type", format!("must be a string, got {other}")));
        }
        None => return fail(ProtocolError::field("type", "missing")),
    };
    match map.remove("protocol") {
        Some(Value::String(p)) if p == PROTOCOL => {}
        Some(other) => {
            return fail(ProtocolError::field(
                "protocol",
                format!("this server speaks {PROTOCOL:?}, got {other}"),
            ));
        }
        None if kind == "start" => {
            return fail(ProtocolError::field("protocol", format!("missing (use {PROTOCOL:?})")));
        }
        None => {}
    }
    let rest = Value::Object(map);
    let request = match kind.as_str() {
        "start" => Request::Start(Box::new(fields(rest).map_err(|e| (seq, e))?)),
        "arrived" => Request::Arrived(fields(rest).map_err(|e| (seq, e))?),
        "move_failed" => Request::MoveFailed(fields(rest).map_err(|e| (seq, e))?),
        "scan" => Request::Scan(Box::new(fields(rest).map_err(|e| (seq, e))?)),
        "found" => Request::Found(fields(rest).map_err(|e| (seq, e))?),
        "stop" => Request::Stop(fields(rest).map_err(|e| (seq, e))?),
        other => {
            return fail(ProtocolError::field(
                "type",
                format!(
                    "unknown message type {other:?}; use start, arrived, move_failed, scan, found or stop"
                ),
            ));
        }
    };
    Ok(Parsed { seq: seq.unwrap_or_default(), request, canonical })
}

/// The message's fields, each problem named by its path.
fn fields<T: DeserializeOwned>(value: Value) -> Result<T, ProtocolError> {
    serde_path_to_error::deserialize(value).map_err(|e| {
        let path = e.path().to_string();
        let message = e.inner().to_string();
        // A missing field is reported at its parent: name the field itself.
        let named = message.strip_prefix("missing field `").and_then(|m| m.split('`').next());
        let field = match (named, path.as_str()) {
            (Some(n), ".") => n.to_string(),
            (Some(n), p) => format!("{p}.{n}"),
            (None, p) => p.to_string(),
        };
        ProtocolError { field: Some(field), message }
    })
}

/// What stopscan answers.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ReplyBody {
    /// Take a scan where the robot stands.
    Scan,
    /// Drive to this pose.
    Goal {
        /// The goal in the robot's odometry frame (what to drive to).
        goal: Pose,
        /// The same goal in the map frame (the frame of the first scan, corrected by scan
        /// matching since).
        map_goal: Pose,
        /// The corner family's stop: its angle on the circle and the route there.
        #[serde(skip_serializing_if = "Option::is_none")]
        stop: Option<Stop>,
    },
    /// The session is over.
    Done {
        /// Why.
        reason: DoneReason,
        /// What was done.
        summary: Summary,
    },
    /// What each robot of a team does next (roi): orders for the robots whose turn it is,
    /// none while the robot that reported waits for the others sent with it.
    Orders {
        /// The orders, by robot.
        orders: Vec<Order>,
    },
    /// The request was refused; the session is unchanged.
    Error {
        /// The field at fault (absent for a line that is not a JSON object).
        field: Option<String>,
        /// What is wrong.
        message: String,
    },
}

/// An order to one robot of a team.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Order {
    /// The robot.
    pub robot: usize,
    /// What it does.
    #[serde(flatten)]
    pub what: OrderKind,
}

/// What one robot of a team is told to do.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum OrderKind {
    /// Take a scan over the cell it stands on.
    Scan {
        /// The cell.
        cell: Cell,
    },
    /// Fly to a cell.
    Goal {
        /// The cell, `[row, col]` (rows grow against the grid's +y).
        cell: Cell,
        /// Where the cell's centre will be on arrival, in the odometry frame.
        goal: Pose,
        /// The cell's centre in the region's own frame (cell `[0, 0]` at the start pose).
        map_goal: Pose,
        /// When it arrives, seconds on the team's clock, as the time model predicts (the
        /// time `goal` is computed for).
        eta: f64,
    },
    /// Nothing more: it is home (or gave up).
    Done {
        /// The cell it ends on.
        cell: Cell,
    },
}

/// Why a session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DoneReason {
    /// The strategy finished: everything worth a trip was seen (polygon), or the edge was
    /// seen (corner).
    Explored,
    /// The robot reported that it found the target.
    Found,
    /// The robot (or its operator) stopped the session.
    Stopped,
    /// Moves kept failing: the robot could not even drive back the way it came.
    Stuck,
    /// The strategy asked for a scan where the robot had just scanned.
    NoProgress,
    /// The scan limit (`--max-scans`) was reached.
    Limit,
    /// A corner search's move failed: the circle around the corner is blocked, and the
    /// search has no other way to go.
    Blocked,
    /// A team's search box was swept without seeing the region (roi).
    NotFound,
}

/// What a session did.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// The strategy.
    pub strategy: String,
    /// Scans, moves, distance (by odometry) and time, term by term.
    #[serde(flatten)]
    pub totals: RunTotals,
    /// Windows closed without a visit, and why (polygon).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub windows: Option<Skipped>,
    /// What the team mapped (roi).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub team: Option<TeamSummary>,
}

/// What a team did and mapped.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TeamSummary {
    /// The robots.
    pub robots: usize,
    /// Scans, moves and distance (by odometry) of each robot.
    pub per_robot: Vec<Tally>,
    /// Cells some robot stood on (arrived at, or started on).
    pub cells_visited: usize,
    /// The map: every cell some scan's vote marked as part of the region, sorted (a cell once
    /// marked stays marked).
    pub map: Vec<Cell>,
}

/// How a scan was placed: sent with the reply to every polygon `scan`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Localised {
    /// The pose the scan was placed at, map frame.
    pub pose: Pose,
    /// The map frame from the robot's odometry frame: `map = correction ∘ odometry`.
    pub correction: Pose,
    /// What scan matching did (absent for the first scan).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub alignment: Option<Alignment>,
    /// How unsure the pose is: one standard deviation of the position along its least sure
    /// direction, metres, as the pose graph holds it (0 for the first scan, which defines
    /// the map frame).
    pub placement_sd: f64,
    /// What cleaning did to the scan.
    pub cleaning: Cleaning,
}

/// A reply line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Reply {
    /// [`PROTOCOL`].
    pub protocol: &'static str,
    /// The request's sequence number (absent when it could not be read).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub seq: Option<u64>,
    /// What to do.
    #[serde(flatten)]
    pub body: ReplyBody,
    /// How the scan was placed (replies to a polygon `scan`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub localised: Option<Localised>,
}

impl Reply {
    /// The reply as one line of JSON (no newline).
    ///
    /// # Panics
    /// Never: a reply holds only strings, finite numbers and maps with string keys.
    pub fn to_line(&self) -> String {
        serde_json::to_string(self).expect("replies serialise")
    }

    /// An error reply.
    pub fn error(seq: Option<u64>, e: ProtocolError) -> Self {
        Self {
            protocol: PROTOCOL,
            seq,
            body: ReplyBody::Error { field: e.field, message: e.message },
            localised: None,
        }
    }
}
