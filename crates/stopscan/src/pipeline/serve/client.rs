//! A simulated robot that speaks the protocol: it answers each reply of `stopscan serve`
//! with its next request, driving a [`SimRobot`] (noisy lidar, drifting odometry, a navigation
//! stack that refuses goals it cannot reach). The tests, `stopscan bench serve` and the ROS
//! node's fake robot drive the server with it.

use serde_json::{Value, json};

use super::message::PROTOCOL;
use crate::kernel::Point;
use crate::sim::lidar::SimRobot;

/// The robot side of a session.
#[derive(Debug)]
pub struct SimClient<'a> {
    robot: SimRobot<'a>,
    seq: u64,
    setup: serde_json::Map<String, Value>,
    /// Where each scan was truly taken.
    pub truth: Vec<Point>,
    /// Moves that failed.
    pub failures: u64,
}

impl<'a> SimClient<'a> {
    /// A client for `robot`; `setup` holds the `start` message's fields besides `protocol`,
    /// `seq`, `type` and `pose` (strategy, cost, robot, sensor, …).
    pub fn new(robot: SimRobot<'a>, setup: serde_json::Map<String, Value>) -> Self {
        Self { robot, seq: 0, setup, truth: Vec::new(), failures: 0 }
    }

    /// The robot.
    pub fn robot(&self) -> &SimRobot<'a> {
        &self.robot
    }

    /// The `start` request.
    pub fn start(&self) -> String {
        let mut m = self.setup.clone();
        m.insert("protocol".into(), PROTOCOL.into());
        m.insert("seq".into(), 0.into());
        m.insert("type".into(), "start".into());
        m.insert("pose".into(), json!(self.robot.odometry()));
        Value::Object(m).to_string()
    }

    /// The request that answers `reply`; `Ok(None)` once the session is done.
    ///
    /// # Errors
    /// The reply, when it is an error or not a reply this client expects.
    pub fn answer(&mut self, reply: &Value) -> Result<Option<String>, String> {
        if reply["protocol"] != PROTOCOL || reply["seq"] != self.seq {
            return Err(format!("unexpected reply to step {}: {reply}", self.seq));
        }
        self.seq += 1;
        let seq = self.seq;
        let request = match reply["type"].as_str() {
            Some("scan") => {
                let scan = self.robot.scan();
                self.truth.push(self.robot.truth().at());
                json!({"seq": seq, "type": "scan", "pose": self.robot.odometry(), "scan": scan})
            }
            Some("goal") => {
                let g = &reply["goal"];
                let (Some(x), Some(y)) = (g["x"].as_f64(), g["y"].as_f64()) else {
                    return Err(format!("a goal without a position: {reply}"));
                };
                let drive = self.robot.drive([x, y]);
                let pose = self.robot.odometry();
                match drive.failed {
                    None => json!({"seq": seq, "type": "arrived", "pose": pose}),
                    Some(reason) => {
                        self.failures += 1;
                        json!({"seq": seq, "type": "move_failed", "pose": pose, "reason": reason})
                    }
                }
            }
            Some("done") => return Ok(None),
            _ => return Err(format!("unexpected reply: {reply}")),
        };
        Ok(Some(request.to_string()))
    }
}
