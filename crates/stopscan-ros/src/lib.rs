//! `stopscan-ros`: stopscan as a ROS 2 node, in pure Rust (ros2-client over RustDDS: no ROS
//! installation needed).
//!
//! - [`explorer`]: the node. It subscribes to `/scan` (`sensor_msgs/LaserScan`, best effort)
//!   and `/odom` (`nav_msgs/Odometry`), runs a stopscan session ([`stopscan::pipeline::serve`],
//!   journaled and resumable), and sends each goal through nav2's `navigate_to_pose` action,
//!   or only publishes it for a robot driven by other means. It publishes `explore/status`
//!   (`std_msgs/String`: started, paused, complete, returning, returned, failed; reliable,
//!   transient local) and `explore/next_scan_pose` (`geometry_msgs/PoseStamped`), and takes
//!   `explore/resume` (`std_msgs/Bool`) as a pause switch.
//! - [`fake_robot`]: a simulated robot for tests and demos: it plays nav2's action server and
//!   publishes the lidar and odometry of stopscan's simulated robot in a polygon world.
//! - [`msgs`]: the messages, defined by hand; the cargo features `humble` and `jazzy` choose
//!   nav2's `NavigateToPose` result.

pub mod explorer;
pub mod fake_robot;
pub mod msgs;

use ros2_client::dds::rustdds::DomainParticipantBuilder;
use ros2_client::qos::{Durability, History};
use ros2_client::{Context, QosProfile, action};

/// A ROS 2 context on DDS domain `domain`; with `localhost`, discovery and data stay on the
/// loopback interface.
///
/// # Errors
/// The DDS participant cannot be created.
pub fn context(domain: u16, localhost: bool) -> anyhow::Result<Context> {
    if !localhost {
        return Ok(Context::with_options(ros2_client::ContextOptions::new().domain_id(domain))?);
    }
    let dp = DomainParticipantBuilder::new(domain)
        .with_only_networks([std::net::Ipv4Addr::LOCALHOST])
        .build()?;
    Ok(Context::from_domain_participant(dp)?)
}

/// Sensor data: best effort, the last few (what `/scan` publishers offer, and what a reader
/// of a reliable `/odom` may ask for).
pub fn sensor_qos() -> QosProfile {
    QosProfile::subscription_default().history(History::KeepLast { depth: 5 })
}

/// A latched topic: reliable and transient local, so a late subscriber gets the last value
/// (`explore/status`, `explore/next_scan_pose`).
pub fn latched_qos() -> QosProfile {
    QosProfile::publisher_default()
        .durability(Durability::TransientLocal)
        .history(History::KeepLast { depth: 1 })
}

/// Reliable, volatile (`explore/resume`).
pub fn command_qos() -> QosProfile {
    QosProfile::publisher_default().history(History::KeepLast { depth: 10 })
}

/// An action's services and feedback: reliable, volatile, the last one.
fn service_qos() -> QosProfile {
    QosProfile::publisher_default()
        .durability(Durability::Volatile)
        .history(History::KeepLast { depth: 1 })
}

/// The QoS of nav2's action client side.
pub fn action_client_qos() -> action::ActionClientQosPolicies {
    let s = service_qos();
    action::ActionClientQosPolicies {
        goal_service: s.clone(),
        result_service: s.clone(),
        cancel_service: s.clone(),
        feedback_subscription: s.clone(),
        status_subscription: s.durability(Durability::TransientLocal),
    }
}

/// The QoS of nav2's action server side (status is transient local, as ROS clients ask).
pub fn action_server_qos() -> action::ActionServerQosPolicies {
    let s = service_qos();
    action::ActionServerQosPolicies {
        goal_service: s.clone(),
        result_service: s.clone(),
        cancel_service: s.clone(),
        feedback_publisher: s.clone(),
        status_publisher: s.durability(Durability::TransientLocal),
    }
}
