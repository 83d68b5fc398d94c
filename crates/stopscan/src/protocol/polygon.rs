//! The polygon family: a robot in an unknown polygon with holes scans visibility regions.

use serde::{Deserialize, Serialize};

use crate::algorithm::visibility::VisibilityRegion;
use crate::kernel::Point;

/// What one scan returns: the region visible from where the robot stands, with labelled
/// boundary pieces (its windows are the paper's constructed edges).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PolygonObservation {
    /// Where the scan was taken.
    pub at: Point,
    /// The visibility region seen.
    pub region: VisibilityRegion,
}

impl PolygonObservation {
    /// The same observation with every point moved by `f` (a change of frame).
    #[must_use]
    pub fn mapped(&self, f: impl Fn(Point) -> Point) -> Self {
        Self { at: f(self.at), region: self.region.mapped(f) }
    }
}
