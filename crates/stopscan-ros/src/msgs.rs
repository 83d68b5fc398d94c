//! The ROS 2 messages the node speaks, defined by hand with their fields in `.msg` order (CDR
//! has no field names: the order is the format). ROS's `float32`, `float64`, `string` and
//! `T[]` are `f32`, `f64`, `String` and `Vec<T>`; a fixed `float64[36]` is two halves, since
//! serde derives arrays of at most 32 elements (CDR writes fixed arrays without a length, so
//! the halves are the same bytes).

use ros2_client::Message;
use ros2_client::builtin_interfaces::{Duration, Time};
use serde::{Deserialize, Serialize};

/// `std_msgs/Header`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Header {
    /// Time stamp.
    pub stamp: Time,
    /// The frame of the data.
    pub frame_id: String,
}

impl Header {
    /// A header stamped now, in `frame`.
    pub fn now(frame: &str) -> Self {
        Self { stamp: Time::now(), frame_id: frame.into() }
    }
}

/// `geometry_msgs/Point`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
}

/// `geometry_msgs/Quaternion`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Quaternion {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
    /// w.
    pub w: f64,
}

/// `geometry_msgs/Pose`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position.
    pub position: Point,
    /// Orientation.
    pub orientation: Quaternion,
}

impl Pose {
    /// A planar pose: `(x, y)` and heading `yaw` (radians) about z.
    pub fn planar(x: f64, y: f64, yaw: f64) -> Self {
        let (s, c) = (0.5 * yaw).sin_cos();
        Self {
            position: Point { x, y, z: 0.0 },
            orientation: Quaternion { x: 0.0, y: 0.0, z: s, w: c },
        }
    }

    /// The heading about z, radians.
    pub fn yaw(&self) -> f64 {
        let q = self.orientation;
        (2.0 * (q.w * q.z + q.x * q.y)).atan2(1.0 - 2.0 * (q.y * q.y + q.z * q.z))
    }

    /// The planar pose, as the protocol's.
    pub fn to_protocol(&self) -> stopscan::protocol::laser::Pose {
        stopscan::protocol::laser::Pose::new([self.position.x, self.position.y], self.yaw())
    }
}

/// `geometry_msgs/PoseStamped`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoseStamped {
    /// Header.
    pub header: Header,
    /// Pose.
    pub pose: Pose,
}

impl Message for PoseStamped {}

/// A `float64[36]` covariance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Covariance(pub [f64; 18], pub [f64; 18]);

impl Default for Covariance {
    fn default() -> Self {
        Self([0.0; 18], [0.0; 18])
    }
}

/// `geometry_msgs/PoseWithCovariance`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoseWithCovariance {
    /// Pose.
    pub pose: Pose,
    /// Its covariance, row-major (x, y, z, rotations about x, y, z).
    pub covariance: Covariance,
}

/// `geometry_msgs/Vector3`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Vector3 {
    /// x.
    pub x: f64,
    /// y.
    pub y: f64,
    /// z.
    pub z: f64,
}

/// `geometry_msgs/Twist`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Twist {
    /// Linear velocity.
    pub linear: Vector3,
    /// Angular velocity.
    pub angular: Vector3,
}

/// `geometry_msgs/TwistWithCovariance`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwistWithCovariance {
    /// Twist.
    pub twist: Twist,
    /// Its covariance.
    pub covariance: Covariance,
}

/// `nav_msgs/Odometry`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Odometry {
    /// Header (the odometry frame).
    pub header: Header,
    /// The robot's frame.
    pub child_frame_id: String,
    /// The robot's pose in the odometry frame.
    pub pose: PoseWithCovariance,
    /// Its velocity.
    pub twist: TwistWithCovariance,
}

/// `sensor_msgs/LaserScan`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LaserScan {
    /// Header (the scanner's frame).
    pub header: Header,
    /// First beam's angle, radians.
    pub angle_min: f32,
    /// Last beam's angle, radians.
    pub angle_max: f32,
    /// Angle between beams, radians.
    pub angle_increment: f32,
    /// Time between measurements, seconds.
    pub time_increment: f32,
    /// Time between scans, seconds.
    pub scan_time: f32,
    /// Nearest valid range, metres.
    pub range_min: f32,
    /// Farthest valid range, metres.
    pub range_max: f32,
    /// Ranges (REP 117).
    pub ranges: Vec<f32>,
    /// Intensities.
    pub intensities: Vec<f32>,
}

impl LaserScan {
    /// The scan as the protocol's.
    pub fn to_protocol(&self) -> stopscan::protocol::laser::LaserScan {
        stopscan::protocol::laser::LaserScan {
            angle_min: f64::from(self.angle_min),
            angle_increment: f64::from(self.angle_increment),
            range_min: f64::from(self.range_min),
            range_max: f64::from(self.range_max),
            ranges: self.ranges.iter().map(|&r| f64::from(r)).collect(),
        }
    }

    /// A protocol scan as a ROS message, stamped now in `frame`.
    pub fn from_protocol(s: &stopscan::protocol::laser::LaserScan, frame: &str) -> Self {
        let n = s.ranges.len().saturating_sub(1) as f64;
        Self {
            header: Header::now(frame),
            angle_min: s.angle_min as f32,
            angle_max: (s.angle_min + n * s.angle_increment) as f32,
            angle_increment: s.angle_increment as f32,
            time_increment: 0.0,
            scan_time: 0.1,
            range_min: s.range_min as f32,
            range_max: s.range_max as f32,
            ranges: s.ranges.iter().map(|&r| r as f32).collect(),
            intensities: Vec::new(),
        }
    }
}

/// `std_msgs/String`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StringMsg {
    /// The text.
    pub data: String,
}

/// `std_msgs/Bool`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BoolMsg {
    /// The value.
    pub data: bool,
}

/// `nav2_msgs/action/NavigateToPose`'s goal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NavigateGoal {
    /// Where to go.
    pub pose: PoseStamped,
    /// A behaviour tree to use instead of the default (empty: the default).
    pub behavior_tree: String,
}

impl Message for NavigateGoal {}

/// `nav2_msgs/action/NavigateToPose`'s result on Jazzy: an error code (0: none) and message.
#[cfg(not(feature = "humble"))]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NavigateResult {
    /// 0: no error.
    pub error_code: u16,
    /// What went wrong.
    pub error_msg: String,
}

#[cfg(not(feature = "humble"))]
impl NavigateResult {
    /// A result: success, or a failure and why.
    pub fn new(failure: Option<&str>) -> Self {
        Self { error_code: u16::from(failure.is_some()), error_msg: failure.unwrap_or("").into() }
    }
}

/// `nav2_msgs/action/NavigateToPose`'s result on Humble: `std_msgs/Empty`, which DDS carries as
/// one byte.
#[cfg(feature = "humble")]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NavigateResult {
    /// `std_msgs/Empty`'s placeholder member.
    pub structure_needs_at_least_one_member: u8,
}

#[cfg(feature = "humble")]
impl NavigateResult {
    /// A result (Humble's carries nothing: the goal's status tells success from failure).
    pub fn new(_failure: Option<&str>) -> Self {
        Self { structure_needs_at_least_one_member: 0 }
    }
}

impl Message for NavigateResult {}

/// `nav2_msgs/action/NavigateToPose`'s feedback (the same on Humble and Jazzy).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct NavigateFeedback {
    /// Where the robot is.
    pub current_pose: PoseStamped,
    /// Time since the goal began.
    pub navigation_time: Duration,
    /// Time left, estimated.
    pub estimated_time_remaining: Duration,
    /// Recoveries so far.
    pub number_of_recoveries: i16,
    /// Metres left.
    pub distance_remaining: f32,
}

impl Message for NavigateFeedback {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_planar_pose_keeps_its_heading() {
        for yaw in [-3.0, -1.0, 0.0, 0.5, 3.1] {
            let p = Pose::planar(1.0, 2.0, yaw);
            assert!((p.yaw() - yaw).abs() < 1e-12, "{yaw}");
        }
    }

    #[test]
    fn a_scan_survives_the_ros_message() {
        let s = stopscan::protocol::laser::LaserScan {
            angle_min: -1.0,
            angle_increment: 0.5,
            range_min: 0.1,
            range_max: 10.0,
            ranges: vec![1.0, f64::NAN, f64::INFINITY, 2.5, f64::NEG_INFINITY],
        };
        let back = LaserScan::from_protocol(&s, "laser").to_protocol();
        assert_eq!(back.ranges.len(), 5);
        assert!(back.ranges[1].is_nan() && back.ranges[2] == f64::INFINITY);
        assert_eq!(back.ranges[4], f64::NEG_INFINITY);
        assert_eq!((back.range_min as f32, back.range_max), (0.1, 10.0));
    }
}
