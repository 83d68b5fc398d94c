//! Visibility regions of points in a polygon with holes.
//!
//! [`Visibility`] preprocesses a [`Domain`] once (a constrained Delaunay triangulation) and
//! answers queries by triangular expansion ([`expansion`]); [`sweep`] is an independent
//! angular-sweep algorithm used to check it.
//!
//! - [`expansion`]: the triangular expansion, which answers queries;
//! - [`range`]: the region clipped to a sensor's range, with exact arcs;
//! - [`sweep`]: an independent angular sweep and a brute-force point test, for the tests.
//!
//! # Convention for queries on the boundary
//! A point `p` is visible from `q` when the closed segment `qp` lies in the closed free space
//! (the domain with its boundary). A ray may therefore graze a vertex or run along an edge.
//! A query on a domain edge or vertex is valid: its region is the part of the closed free
//! space seen this way, and its polygon starts and ends at the query point, with the incident
//! boundary edge(s) as its first and last pieces. A query outside the closed free space is an
//! error.

pub mod expansion;
pub mod range;
pub mod sweep;

use serde::{Deserialize, Serialize};

use crate::algorithm::triangulation::{Mesh, TriangulationError};
use crate::geometry::{Domain, EdgeId};
use crate::kernel::Point;

/// One piece of a visibility region's boundary, in counter-clockwise order around the
/// viewpoint.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum BoundaryPiece {
    /// A whole domain edge.
    Edge {
        /// Start.
        from: Point,
        /// End.
        to: Point,
        /// Which edge.
        edge: EdgeId,
    },
    /// Part of a domain edge.
    Partial {
        /// Start.
        from: Point,
        /// End.
        to: Point,
        /// Which edge.
        edge: EdgeId,
    },
    /// A window: the paper's constructed edge, on the ray from the viewpoint through a reflex
    /// vertex to the point where the ray meets the boundary behind it.
    Window {
        /// Start.
        from: Point,
        /// End.
        to: Point,
        /// The reflex vertex (the end nearer the viewpoint).
        reflex: Point,
        /// The far end.
        far: Point,
    },
    /// A wall seen by a range sensor: a line fitted to its returns
    /// ([`crate::sensing`](../../sensing/index.html)'s scan ingestion). It names no domain
    /// edge: a real robot's scan has none.
    Wall {
        /// Start.
        from: Point,
        /// End.
        to: Point,
    },
    /// A chord of the range circle, in a range-limited region made polygonal
    /// ([`range::RangeRegion::to_region`]): the region ends here because of the range, and
    /// the free space may go on beyond.
    Frontier {
        /// Start.
        from: Point,
        /// End.
        to: Point,
    },
}

impl BoundaryPiece {
    /// Start and end.
    pub fn ends(&self) -> (Point, Point) {
        match *self {
            Self::Edge { from, to, .. }
            | Self::Partial { from, to, .. }
            | Self::Window { from, to, .. }
            | Self::Wall { from, to }
            | Self::Frontier { from, to } => (from, to),
        }
    }

    /// The same piece with every point moved by `f` (a change of frame).
    #[must_use]
    pub fn mapped(&self, f: impl Fn(Point) -> Point) -> Self {
        match *self {
            Self::Edge { from, to, edge } => Self::Edge { from: f(from), to: f(to), edge },
            Self::Partial { from, to, edge } => Self::Partial { from: f(from), to: f(to), edge },
            Self::Window { from, to, reflex, far } => {
                Self::Window { from: f(from), to: f(to), reflex: f(reflex), far: f(far) }
            }
            Self::Wall { from, to } => Self::Wall { from: f(from), to: f(to) },
            Self::Frontier { from, to } => Self::Frontier { from: f(from), to: f(to) },
        }
    }
}

/// The region of the free space seen from a viewpoint: a polygon, star-shaped from the
/// viewpoint, counter-clockwise, with labelled boundary pieces.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct VisibilityRegion {
    /// The viewpoint.
    pub viewpoint: Point,
    /// Polygon vertices, counter-clockwise (no repeated closing vertex).
    pub polygon: Vec<Point>,
    /// Boundary pieces, counter-clockwise, covering the polygon's boundary once.
    pub boundary: Vec<BoundaryPiece>,
}

impl VisibilityRegion {
    /// The area (shoelace, relative to the viewpoint).
    pub fn area(&self) -> f64 {
        polygon_area(self.viewpoint, &self.polygon)
    }

    /// The windows (constructed edges).
    pub fn windows(&self) -> impl Iterator<Item = &BoundaryPiece> {
        self.boundary.iter().filter(|b| matches!(b, BoundaryPiece::Window { .. }))
    }

    /// The same region with every point moved by `f` (a change of frame).
    #[must_use]
    pub fn mapped(&self, f: impl Fn(Point) -> Point) -> Self {
        Self {
            viewpoint: f(self.viewpoint),
            polygon: self.polygon.iter().map(|&p| f(p)).collect(),
            boundary: self.boundary.iter().map(|b| b.mapped(&f)).collect(),
        }
    }

    /// Where the region ends inside the free space: windows and range chords.
    pub fn frontiers(&self) -> impl Iterator<Item = &BoundaryPiece> {
        self.boundary
            .iter()
            .filter(|b| matches!(b, BoundaryPiece::Window { .. } | BoundaryPiece::Frontier { .. }))
    }
}

/// The area of a polygon given counter-clockwise, computed relative to `o` for precision.
pub fn polygon_area_of(o: Point, poly: &[Point]) -> f64 {
    polygon_area(o, poly)
}

pub(crate) fn polygon_area(o: Point, poly: &[Point]) -> f64 {
    let n = poly.len();
    let mut s = 0.0;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        s += (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]);
    }
    0.5 * s
}

/// Why a visibility query failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum VisibilityError {
    /// The viewpoint is outside the closed free space (outside the boundary, or inside a
    /// hole), or not finite.
    #[error("the viewpoint ({}, {}) is outside the free space", crate::kernel::Num(*.0), crate::kernel::Num(*.1))]
    Outside(f64, f64),
    /// The triangulation could not be built.
    #[error(transparent)]
    Triangulation(#[from] TriangulationError),
}

/// A domain preprocessed for visibility queries.
#[derive(Debug)]
pub struct Visibility {
    domain: Domain,
    mesh: Mesh,
}

impl Visibility {
    /// Preprocesses a domain (one triangulation).
    ///
    /// # Errors
    /// [`VisibilityError::Triangulation`] (never for a validated domain).
    ///
    /// # Complexity
    /// O(n log n) time, O(n) space.
    ///
    /// # Example
    /// An L-shaped room: seen from its bottom arm, the reflex corner (2, 2) hides part of the
    /// left arm behind one window.
    /// ```
    /// use stopscan::algorithm::visibility::{BoundaryPiece, Visibility};
    /// use stopscan::geometry::Domain;
    ///
    /// let l = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]];
    /// let vis = Visibility::new(Domain::new(l, vec![])?)?;
    /// let seen = vis.query([3.0, 1.0])?;
    /// // The bottom arm (8 m²) and the triangle (0, 2), (2, 2), (0, 4) of the left arm (2 m²).
    /// assert!((seen.area() - 10.0).abs() < 1e-12);
    /// let windows: Vec<&BoundaryPiece> = seen.windows().collect();
    /// assert!(matches!(
    ///     windows[..],
    ///     [BoundaryPiece::Window { reflex: [2.0, 2.0], far: [0.0, 4.0], .. }]
    /// ));
    /// // From the inner corner of the L, the whole room (12 m²) is in view.
    /// assert!((vis.query([1.0, 1.0])?.area() - 12.0).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn new(domain: Domain) -> Result<Self, VisibilityError> {
        let mesh = Mesh::new(&domain)?;
        Ok(Self { domain, mesh })
    }

    /// The domain.
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// The triangulation.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// The visibility region of `q` by triangular expansion.
    ///
    /// # Errors
    /// [`VisibilityError::Outside`] if `q` is not in the closed free space.
    ///
    /// # Complexity
    /// O(k) expected for output size k on ordinary maps, O(n·h) in the worst case, plus the
    /// point location.
    ///
    /// # Example
    /// ```
    /// use stopscan::geometry::Domain;
    /// use stopscan::algorithm::visibility::Visibility;
    /// let square = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 4.0], [0.0, 4.0]];
    /// let hole = vec![[1.0, 1.0], [1.0, 2.0], [2.0, 2.0], [2.0, 1.0]];
    /// let v = Visibility::new(Domain::new(square, vec![hole]).unwrap()).unwrap();
    /// let r = v.query([3.0, 3.0]).unwrap();
    /// assert!(r.area() < 16.0 - 1.0);
    /// assert_eq!(r.windows().count(), 2);
    /// ```
    pub fn query(&self, q: Point) -> Result<VisibilityRegion, VisibilityError> {
        let mut out = VisibilityRegion::default();
        self.query_into(q, &mut expansion::Scratch::default(), &mut out)?;
        Ok(out)
    }

    /// The range-limited region of `q` (the paper's restricted visibility polygon): the
    /// part of the visibility region within distance `range`, with exact arcs.
    ///
    /// # Errors
    /// [`VisibilityError::Outside`] if `q` is not in the closed free space.
    ///
    /// # Example
    /// ```
    /// use stopscan::geometry::Domain;
    /// use stopscan::algorithm::visibility::Visibility;
    /// let room = vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]];
    /// let v = Visibility::new(Domain::new(room, vec![]).unwrap()).unwrap();
    /// let r = v.query_range([5.0, 5.0], 1.0).unwrap();
    /// assert!((r.area() - std::f64::consts::PI).abs() < 1e-12);
    /// ```
    pub fn query_range(&self, q: Point, range: f64) -> Result<range::RangeRegion, VisibilityError> {
        Ok(range::clip(&self.query(q)?, range))
    }

    /// [`Visibility::query`] reusing buffers (for many queries).
    ///
    /// # Errors
    /// [`VisibilityError::Outside`] if `q` is not in the closed free space.
    pub fn query_into(
        &self,
        q: Point,
        scratch: &mut expansion::Scratch,
        out: &mut VisibilityRegion,
    ) -> Result<(), VisibilityError> {
        expansion::expand(&self.mesh, q, scratch, out)
    }
}
