//! The polygon world: the true environment, hidden from strategies, its sensor, and where a
//! robot with a footprint can be (its configuration space).

use crate::algorithm::cover;
use crate::algorithm::region::{Region, configuration_space};
use crate::algorithm::shortest_path::segment_is_free;
use crate::algorithm::visibility::{Visibility, VisibilityError};
use crate::geometry::Domain;
use crate::kernel::{Point, RingSide, magnitude, ring_side};
use crate::protocol::polygon::{Footprint, PolygonObservation};

/// The ground truth of one exploration instance.
#[derive(Debug)]
pub struct PolygonWorld {
    vis: Visibility,
    range: Option<f64>,
    reach: Option<Reach>,
}

/// Where a robot with a footprint can be: the component of the configuration space that
/// holds its start. Scans still see the whole free space; moves must stay in here.
#[derive(Debug)]
pub struct Reach {
    footprint: Footprint,
    cspace: Visibility,
    start: Point,
    components: usize,
}

impl Reach {
    /// The footprint.
    pub fn footprint(&self) -> &Footprint {
        &self.footprint
    }

    /// The reachable configuration space (its component holding the start).
    pub fn domain(&self) -> &Domain {
        self.cspace.domain()
    }

    /// The configuration space's triangulation (for exact move checks and sampling).
    pub fn mesh(&self) -> &crate::algorithm::triangulation::Mesh {
        self.cspace.mesh()
    }

    /// The start the component was chosen by.
    pub fn start(&self) -> Point {
        self.start
    }

    /// How many components the whole configuration space has (the others are out of reach).
    pub fn components(&self) -> usize {
        self.components
    }
}

/// Why a world for a robot with a footprint could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WorldError {
    /// The free space could not be preprocessed.
    #[error(transparent)]
    Visibility(#[from] VisibilityError),
    /// The footprint fits nowhere.
    #[error("the robot's footprint (clearance {clearance:.3} m) fits nowhere in the free space")]
    NoRoom {
        /// The footprint's clearance, metres.
        clearance: f64,
    },
    /// The footprint does not fit at the start.
    #[error(
        "the robot's footprint (clearance {clearance:.3} m) does not fit at the start ({}, {}): it is too close to an obstacle; move the start or shrink the robot",
        crate::kernel::Num(start[0]), crate::kernel::Num(start[1])
    )]
    StartBlocked {
        /// The start.
        start: Point,
        /// The footprint's clearance, metres.
        clearance: f64,
    },
    /// The configuration space's component at the start is not a valid domain (the overlay's
    /// output touches itself).
    #[error("the configuration space at the start could not be built: {0}")]
    ConfigurationSpace(String),
}

impl PolygonWorld {
    /// Preprocesses a domain for sensing.
    ///
    /// # Errors
    /// [`VisibilityError`] if it cannot be triangulated (never for a valid domain).
    pub fn new(domain: Domain) -> Result<Self, VisibilityError> {
        Ok(Self { vis: Visibility::new(domain)?, range: None, reach: None })
    }

    /// Preprocesses a domain for a sensor that sees only within `range` metres (the paper's
    /// restricted visibility polygons); `None` sees without limit.
    ///
    /// # Errors
    /// [`VisibilityError`] if it cannot be triangulated (never for a valid domain).
    pub fn with_range(domain: Domain, range: Option<f64>) -> Result<Self, VisibilityError> {
        Ok(Self { vis: Visibility::new(domain)?, range, reach: None })
    }

    /// Preprocesses a domain for a robot with a footprint: scans see the whole free space,
    /// within `range`; moves must stay in the configuration space's component that holds
    /// `start` (checked exactly against it). Without a start, the largest component is used,
    /// and [`Reach::start`] is a point inside it. A point footprint gives [`Self::with_range`].
    ///
    /// # Errors
    /// [`WorldError`]: the footprint fits nowhere or not at the start, or the domain cannot be
    /// triangulated.
    pub fn with_robot(
        domain: Domain,
        range: Option<f64>,
        footprint: &Footprint,
        start: Option<Point>,
    ) -> Result<Self, WorldError> {
        let Some(shape) = footprint.polygon() else {
            return Ok(Self::with_range(domain, range)?);
        };
        let clearance = footprint.clearance();
        // Grown a little beyond the overlay's snapping (about 5e-10 of the extent), so that
        // the space lies inside the exact one.
        let margin = 1e-8 * magnitude(domain.rings().iter().flatten()).max(1.0);
        let region = configuration_space(&domain, &shape, margin);
        let components = region.shapes.len();
        let pick = match start {
            Some(s) => region
                .shapes
                .iter()
                .position(|sh| {
                    ring_side(&sh[0], s) != RingSide::Outside
                        && sh[1..].iter().all(|h| ring_side(h, s) != RingSide::Inside)
                })
                .ok_or(WorldError::StartBlocked { start: s, clearance })?,
            None => (0..components)
                .max_by(|&a, &b| {
                    let area = |i: usize| Region { shapes: vec![region.shapes[i].clone()] }.area();
                    area(a).total_cmp(&area(b)).then(b.cmp(&a))
                })
                .ok_or(WorldError::NoRoom { clearance })?,
        };
        let mut rings = region.shapes[pick].clone();
        let outer = rings.remove(0);
        let cspace = Domain::new(outer, rings)
            .map_err(|e| WorldError::ConfigurationSpace(e.to_string()))
            .and_then(|d| Ok(Visibility::new(d)?))?;
        let start = match start {
            Some(s) => {
                // Strategies keep the planning clearance from all they have not seen free; the
                // start must have it too, or no first move could be planned.
                let need = footprint.planning_clearance(magnitude(domain.rings().iter().flatten()));
                if domain.boundary_distance(s) < need {
                    return Err(WorldError::StartBlocked { start: s, clearance: need });
                }
                s
            }
            None => roomiest_centroid(&cspace, &domain),
        };
        Ok(Self {
            vis: Visibility::new(domain)?,
            range,
            reach: Some(Reach { footprint: footprint.clone(), cspace, start, components }),
        })
    }

    /// Where the robot can be, when it has a footprint.
    pub fn reach(&self) -> Option<&Reach> {
        self.reach.as_ref()
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
        Ok(PolygonObservation::new(at, region))
    }

    /// A point strictly inside the free space (the centroid of a triangle of the mesh), for
    /// environments that name no start.
    pub fn interior_point(&self) -> Point {
        interior_point(&self.vis)
    }

    /// Where the robot's reference point may move: the reachable configuration space with a
    /// footprint, else the free space (for planning paths in the true world).
    pub fn moves(&self) -> &Visibility {
        self.reach.as_ref().map_or(&self.vis, |r| &r.cspace)
    }

    /// The point where a robot heading for `p` can stop: `p` itself when it lies in
    /// [`moves`](Self::moves), else the nearest point inside it, if within `within` metres
    /// (a local planner stops short of a wall the goal lies against); `None` beyond.
    pub fn nearest_place(&self, p: Point, within: f64) -> Option<Point> {
        use crate::geometry::Location;
        let d = self.moves().domain();
        if d.locate(p) == Location::Interior {
            return Some(p);
        }
        let mut best: Option<(f64, Point)> = None;
        for ring in d.rings() {
            let n = ring.len();
            for i in 0..n {
                let (a, b) = (ring[i], ring[(i + 1) % n]);
                let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                let l2 = dx * dx + dy * dy;
                let t = (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / l2).clamp(0.0, 1.0);
                let f = [a[0] + t * dx, a[1] + t * dy];
                let dist = (p[0] - f[0]).hypot(p[1] - f[1]);
                if dist <= within && best.is_none_or(|b| dist < b.0) {
                    // Rings keep the space on their left: step a millimetre in.
                    let l = l2.sqrt();
                    best = Some((dist, [f[0] - 1e-3 * dy / l, f[1] + 1e-3 * dx / l]));
                }
            }
        }
        best.map(|b| b.1).filter(|q| d.locate(*q) == Location::Interior)
    }

    /// Whether a straight move stays in the closed free space, or with a footprint in the
    /// reachable configuration space (exact against its polygon).
    pub fn can_move(&self, from: Point, to: Point) -> bool {
        let mesh = self.reach.as_ref().map_or(self.vis.mesh(), |r| r.cspace.mesh());
        segment_is_free(mesh, from, to)
    }
}

/// The centroid of a triangle of `cspace` farthest from the boundary of `domain` (the first
/// on ties): a start with room around it.
fn roomiest_centroid(cspace: &Visibility, domain: &Domain) -> Point {
    let m = cspace.mesh();
    let mut best = (f64::NEG_INFINITY, interior_point(cspace));
    for t in &m.tri {
        let p = t.map(|i| m.points()[i as usize]);
        let c = [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0];
        let d = domain.boundary_distance(c);
        if d > best.0 {
            best = (d, c);
        }
    }
    best.1
}

/// The centroid of the first triangle of a preprocessed domain.
fn interior_point(vis: &Visibility) -> Point {
    let m = vis.mesh();
    let t = m.tri.first().copied().unwrap_or([0, 0, 0]);
    let p = t.map(|i| m.points()[i as usize]);
    [(p[0][0] + p[1][0] + p[2][0]) / 3.0, (p[0][1] + p[1][1] + p[2][1]) / 3.0]
}
