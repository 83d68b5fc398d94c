//! Online exploration of unknown polygons with discrete visibility (Ghosh, Burdick,
//! Bhattacharya, Sarkar). Strategies are fed only observations: scans with their labelled
//! visibility regions.

mod depth_first;

pub use depth_first::DepthFirst;

use serde::{Deserialize, Serialize};

use crate::kernel::Point;
use crate::protocol::Action;
use crate::protocol::polygon::PolygonObservation;

/// What the driver tells a polygon strategy before asking for its next action.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum PolygonFeedback {
    /// The run begins at the start point.
    Start(Point),
    /// The robot reached the point it asked for.
    Arrived,
    /// The scan it asked for.
    Scanned(PolygonObservation),
}

/// An online polygon-exploration strategy.
pub trait PolygonStrategy {
    /// The registry name.
    fn name(&self) -> &str;
    /// The next action: move in a straight line to a point, scan, or done.
    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point>;
}
