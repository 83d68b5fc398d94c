//! Successive scans into observations in one map frame: each scan is read ([`ingest`]),
//! aligned by ICP to the walls of the scans before it, and its walls join the map.
//!
//! The first scan defines the map frame's walls; it is placed where odometry says. A scan ICP
//! could not align (a [`Fallback`](super::icp::Fallback)) is placed by odometry and informs
//! the strategy, but its walls stay out of the map: put in the wrong place, they would pull
//! every later alignment.

use serde::{Deserialize, Serialize};

use super::icp::{self, Alignment, IcpParams, Prior, WallMap};
use super::ingest::{Cleaning, IngestError, IngestParams, ingest};
use crate::kernel::Point;
use crate::protocol::laser::{LaserScan, Pose};
use crate::protocol::polygon::PolygonObservation;

/// The wall map keeps walls in pieces of at most this length, metres.
pub const MAP_PIECE: f64 = 0.5;

/// A wall piece within this distance of a mapped wall of the same orientation is that wall,
/// seen again, metres: it is not added twice.
pub const MAP_SAME_WALL: f64 = 0.3;

/// The smallest prior standard deviations ICP is given: 1 cm and 0.002 rad, so that a short
/// move does not pin the alignment to odometry.
const MIN_PRIOR: Prior = Prior { position: 0.01, heading: 0.002 };

/// The smallest correction ICP may not make, metres: a wall seen again within
/// [`MAP_SAME_WALL`] is the same wall.
pub const MIN_PLAUSIBLE_SHIFT: f64 = MAP_SAME_WALL;

/// The smallest turn ICP may not make, radians (3°).
pub const MIN_PLAUSIBLE_TURN: f64 = 0.052;

/// How scans are read and aligned, and how far odometry drifts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MapperParams {
    /// How scans are read.
    pub ingest: IngestParams,
    /// How scans are aligned.
    pub icp: IcpParams,
    /// Odometry's drift: the standard deviation of the position error per metre driven (per
    /// axis), and `heading_drift` radians per metre for the heading.
    pub drift: f64,
    /// The heading's drift per metre driven, radians.
    pub heading_drift: f64,
}

impl MapperParams {
    /// The defaults for a sensor with range noise `sigma` on odometry that drifts `drift`
    /// metres per metre (per axis) and `heading_drift` radians per metre.
    pub fn for_sensor(sigma: f64, drift: f64, heading_drift: f64) -> Self {
        Self {
            ingest: IngestParams::for_noise(sigma),
            icp: IcpParams { huber: (3.0 * sigma).max(0.02), sigma, ..IcpParams::default() },
            drift,
            heading_drift,
        }
    }
}

/// One scan, read and placed.
#[derive(Debug, Clone, PartialEq)]
pub struct Reading {
    /// The region seen, in the map frame.
    pub observation: PolygonObservation,
    /// The pose the scan was placed at: ICP's, or odometry's when it could not align.
    pub estimate: Pose,
    /// What ICP did (none for the first scan: nothing was known).
    pub alignment: Option<Alignment>,
    /// What cleaning did.
    pub cleaning: Cleaning,
}

/// The walls seen so far, and how new scans are read against them.
#[derive(Debug, Clone)]
pub struct Mapper {
    params: MapperParams,
    map: WallMap,
}

impl Mapper {
    /// An empty map.
    pub fn new(params: MapperParams) -> Self {
        Self { params, map: WallMap::new() }
    }

    /// The parameters.
    pub fn params(&self) -> &MapperParams {
        &self.params
    }

    /// Reads `scan`, taken where odometry says `odometry` (map frame) after driving
    /// `driven` metres since the last scan; aligns it and adds its walls to the map.
    ///
    /// # Errors
    /// [`IngestError`] for an invalid scan or pose, or a scan with no valid return.
    pub fn read(
        &mut self,
        scan: &LaserScan,
        odometry: &Pose,
        driven: f64,
    ) -> Result<Reading, IngestError> {
        if !odometry.is_finite() {
            return Err(IngestError::Pose(*odometry));
        }
        let p = &self.params;
        // Read in the scanner's frame, aligned, then placed at the estimate.
        let local = ingest(scan, &Pose::default(), &p.ingest)?;
        let prior = Prior {
            position: (p.drift * driven).max(MIN_PRIOR.position),
            heading: (p.heading_drift * driven).max(MIN_PRIOR.heading),
        };
        // A correction is plausible within three standard deviations of how far odometry may
        // be off: its position error, and the heading error made on the way turning every
        // metre after it (about `heading_drift · d² / 2` across the direction of travel, for a
        // trip of several legs between scans). Never less than a mapped wall's own tolerance.
        let heading = p.heading_drift * driven;
        let reach = (p.drift * driven).hypot(heading * driven / 2.0);
        let icp = IcpParams {
            max_shift: (3.0 * std::f64::consts::SQRT_2 * reach).max(MIN_PLAUSIBLE_SHIFT),
            max_turn: (3.0 * heading).max(MIN_PLAUSIBLE_TURN),
            ..p.icp
        };
        let alignment = (!self.map.is_empty())
            .then(|| icp::align(&local.points, odometry, Some(prior), &self.map, &icp));
        let estimate = alignment.as_ref().map_or(*odometry, |a| a.pose);
        let place = |q: Point| estimate.apply(q);
        if alignment.as_ref().is_none_or(|a| a.fallback.is_none()) {
            let walls: Vec<[Point; 2]> = local
                .walls
                .iter()
                .chain(&local.bridges)
                .map(|w| [place(w[0]), place(w[1])])
                .collect();
            self.map.extend_unseen(&walls, MAP_PIECE, MAP_SAME_WALL);
        }
        Ok(Reading {
            observation: local.observation.mapped(place),
            estimate,
            alignment,
            cleaning: local.cleaning,
        })
    }
}
