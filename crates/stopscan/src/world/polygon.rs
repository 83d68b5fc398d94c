//! The polygon world: the true environment, hidden from strategies, and its sensor.

use crate::algorithm::cover;
use crate::algorithm::shortest_path::segment_is_free;
use crate::algorithm::visibility::{Visibility, VisibilityError};
use crate::geometry::Domain;
use crate::kernel::Point;
use crate::protocol::polygon::PolygonObservation;

/// The ground truth of one exploration instance.
#[derive(Debug)]
pub struct PolygonWorld {
    vis: Visibility,
    range: Option<f64>,
}

impl PolygonWorld {
    /// Preprocesses a domain for sensing.
    ///
    /// # Errors
    /// [`VisibilityError`] if it cannot be triangulated (never for a valid domain).
    pub fn new(domain: Domain) -> Result<Self, VisibilityError> {
        Ok(Self { vis: Visibility::new(domain)?, range: None })
    }

    /// Preprocesses a domain for a sensor that sees only within `range` metres (the paper's
    /// restricted visibility polygons); `None` sees without limit.
    ///
    /// # Errors
    /// [`VisibilityError`] if it cannot be triangulated (never for a valid domain).
    pub fn with_range(domain: Domain, range: Option<f64>) -> Result<Self, VisibilityError> {
        Ok(Self { vis: Visibility::new(domain)?, range })
    }

    /// The preprocessed domain (for offline references; strategies never get it).
    pub fn visibility(&self) -> &Visibility {
        &self.vis
    }

    /// The sensor's range, if limited.
    pub fn range(&self) -> Option<f64> {
        self.range
    }

    /// The domain (for the simulator and the metrics; strategies never get it).
    pub fn domain(&self) -> &Domain {
        self.vis.domain()
    }

    /// The sensor: a visibility scan from `at`. With a range limit the region's arcs come as
    /// chords (sagitta [`cover::RANGE_CHORD_TOLERANCE`]·R) labelled as frontiers.
    ///
    /// # Errors
    /// [`VisibilityError::Outside`] if `at` is not in the free space.
    pub fn scan(&self, at: Point) -> Result<PolygonObservation, VisibilityError> {
        let region = match self.range {
            None => self.vis.query(at)?,
            Some(r) => self.vis.query_range(at, r)?.to_region(r * cover::RANGE_CHORD_TOLERANCE),
        };
        Ok(PolygonObservation { at, region })
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
