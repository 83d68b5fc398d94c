//! The polygon world: the true environment, hidden from strategies, and its sensor.

use crate::algorithm::shortest_path::segment_is_free;
use crate::algorithm::visibility::{Visibility, VisibilityError};
use crate::geometry::Domain;
use crate::kernel::Point;
use crate::protocol::polygon::PolygonObservation;

/// The ground truth of one exploration instance.
#[derive(Debug)]
pub struct PolygonWorld {
    vis: Visibility,
}

impl PolygonWorld {
    /// Preprocesses a domain for sensing.
    ///
    /// # Errors
    /// [`VisibilityError`] if it cannot be triangulated (never for a valid domain).
    pub fn new(domain: Domain) -> Result<Self, VisibilityError> {
        Ok(Self { vis: Visibility::new(domain)? })
    }

    /// The domain (for the simulator and the metrics; strategies never get it).
    pub fn domain(&self) -> &Domain {
        self.vis.domain()
    }

    /// The sensor: a full visibility scan from `at`.
    ///
    /// # Errors
    /// [`VisibilityError::Outside`] if `at` is not in the free space.
    pub fn scan(&self, at: Point) -> Result<PolygonObservation, VisibilityError> {
        Ok(PolygonObservation { at, region: self.vis.query(at)? })
    }

    /// A point strictly inside the free space (the centroid of a triangle of the mesh), for
    /// environments that name no start.
    pub fn interior_point(&self) -> Point {
        let m = self.vis.mesh();
        let t = m.tri.first().copied().unwrap_or([0, 0, 0]);
        let p = t.map(|i| m.points()[i as usize]);
        [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0]
    }

    /// Whether a straight move stays in the closed free space (exact).
    pub fn can_move(&self, from: Point, to: Point) -> bool {
        segment_is_free(self.vis.mesh(), from, to)
    }
}
