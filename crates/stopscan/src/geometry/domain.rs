//! A polygon with holes, validated once when it is built.
//!
//! Conventions: ring 0 is the outer boundary, stored counter-clockwise; rings 1.. are holes,
//! stored clockwise. Walking any ring, the free space is on the left. Rings are not closed
//! (the last vertex connects back to the first).
//!
//! A hole that touches the boundary or another hole (shares even one point) is rejected with
//! a typed error ([`InvalidEnvironment::RingsTouch`]): such a domain pinches free space into
//! pieces that meet at a point, which visibility and shortest paths would have to treat
//! specially; splitting or merging the rings is the caller's explicit choice.

use serde::{Deserialize, Serialize};

use crate::kernel::{self, Point, RingSide};

/// An edge of the domain: ring `ring`, from vertex `index` to vertex `index + 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct EdgeId {
    /// The ring (0 = outer boundary).
    pub ring: u32,
    /// The edge's first vertex in the ring.
    pub index: u32,
}

/// Why an environment was rejected. Every variant names the ring and the vertex or edge.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidEnvironment {
    /// The environment has no rings at all.
    #[error("the environment has no boundary ring")]
    Empty,
    /// A ring has fewer than three distinct vertices.
    #[error("ring {ring} has {count} vertices; a ring needs at least 3")]
    TooFewVertices {
        /// The ring.
        ring: usize,
        /// How many it has.
        count: usize,
    },
    /// A coordinate is NaN or infinite.
    #[error("ring {ring}, vertex {index}: coordinate {} is not finite", crate::kernel::Num(*.value))]
    NonFiniteCoord {
        /// The ring.
        ring: usize,
        /// The vertex.
        index: usize,
        /// The value.
        value: f64,
    },
    /// A coordinate is outside the range where the exact predicates are guaranteed
    /// (|x| in [2^-142, 2^201], or 0). Rescale the input (metres are fine).
    #[error(
        "ring {ring}, vertex {index}: coordinate {} is outside the exact range [2^-142, 2^201]",
        crate::kernel::Num(*.value)
    )]
    OutOfRange {
        /// The ring.
        ring: usize,
        /// The vertex.
        index: usize,
        /// The value.
        value: f64,
    },
    /// Two consecutive vertices are equal (a zero-length edge). Remove the repeat.
    #[error("ring {ring}, vertex {index} repeats the previous vertex (zero-length edge)")]
    RepeatedVertex {
        /// The ring.
        ring: usize,
        /// The vertex.
        index: usize,
    },
    /// The ring crosses or touches itself (edges `a` and `b`).
    #[error(
        "ring {ring} is not simple: edge {a} (from vertex {a}) meets edge {b} (from vertex {b})"
    )]
    SelfIntersection {
        /// The ring.
        ring: usize,
        /// One edge.
        a: usize,
        /// The other edge.
        b: usize,
    },
    /// The ring's area is zero (all vertices collinear).
    #[error("ring {ring} has zero area")]
    Degenerate {
        /// The ring.
        ring: usize,
    },
    /// Two rings cross or touch: ring `ring_a` edge `a` meets ring `ring_b` edge `b`.
    #[error(
        "ring {ring_a} edge {a} meets ring {ring_b} edge {b}: holes must lie strictly inside the boundary and not touch each other"
    )]
    RingsTouch {
        /// First ring.
        ring_a: usize,
        /// Its edge.
        a: usize,
        /// Second ring.
        ring_b: usize,
        /// Its edge.
        b: usize,
    },
    /// A hole lies outside the outer boundary.
    #[error("hole ring {ring} (vertex 0 at {at:?}) lies outside the outer boundary")]
    HoleOutside {
        /// The hole.
        ring: usize,
        /// Its first vertex.
        at: Point,
    },
    /// A hole lies inside another hole.
    #[error("hole ring {ring} lies inside hole ring {other}")]
    NestedHole {
        /// The inner hole.
        ring: usize,
        /// The hole around it.
        other: usize,
    },
}

/// Where a point lies relative to the domain's closed free space.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Location {
    /// In the open free space.
    Interior,
    /// On an edge or vertex of a ring.
    Boundary,
    /// Outside the boundary or inside a hole.
    Outside,
}

/// A valid polygon with holes. Once built, it is simple, correctly oriented, and its holes
/// lie strictly inside the boundary and apart from each other.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Domain {
    rings: Vec<Vec<Point>>,
}

impl Domain {
    /// Validates and normalises an outer ring and its holes (any orientation, not closed; a
    /// repeated closing vertex is dropped).
    ///
    /// # Errors
    /// [`InvalidEnvironment`] naming the first problem found.
    ///
    /// # Complexity
    /// O(n·k) with k the number of edges sharing a grid cell (about O(n) for ordinary maps),
    /// plus O(h·n) for hole containment.
    ///
    /// # Example
    /// A 10 m × 10 m room given clockwise, with a 2 m × 2 m pillar; then a bow tie.
    /// ```
    /// use stopscan::geometry::{Domain, InvalidEnvironment};
    ///
    /// let room = vec![[0.0, 0.0], [0.0, 10.0], [10.0, 10.0], [10.0, 0.0]];
    /// let pillar = vec![[4.0, 4.0], [6.0, 4.0], [6.0, 6.0], [4.0, 6.0]];
    /// let d = Domain::new(room, vec![pillar])?;
    /// assert_eq!(d.area(), 96.0);
    /// // The outer ring is turned counter-clockwise, the hole clockwise.
    /// assert_eq!(d.outer(), [[10.0, 0.0], [10.0, 10.0], [0.0, 10.0], [0.0, 0.0]]);
    /// assert_eq!(d.holes()[0], [[4.0, 6.0], [6.0, 6.0], [6.0, 4.0], [4.0, 4.0]]);
    /// // Every corner of the pillar is a reflex vertex of the free space: (ring, index).
    /// assert_eq!(d.reflex_vertices(), [(1, 0), (1, 1), (1, 2), (1, 3)]);
    ///
    /// let bow_tie = vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]];
    /// let err = Domain::new(bow_tie, vec![]).unwrap_err();
    /// assert_eq!(err, InvalidEnvironment::SelfIntersection { ring: 0, a: 0, b: 2 });
    /// assert_eq!(
    ///     err.to_string(),
    ///     "ring 0 is not simple: edge 0 (from vertex 0) meets edge 2 (from vertex 2)"
    /// );
    /// # Ok::<(), InvalidEnvironment>(())
    /// ```
    pub fn new(outer: Vec<Point>, holes: Vec<Vec<Point>>) -> Result<Self, InvalidEnvironment> {
        let mut rings = Vec::with_capacity(holes.len() + 1);
        rings.push(outer);
        rings.extend(holes);
        for (r, ring) in rings.iter_mut().enumerate() {
            if ring.len() > 1 && ring.first() == ring.last() {
                ring.pop();
            }
            check_ring(r, ring)?;
        }
        check_intersections(&rings)?;
        for (r, ring) in rings.iter_mut().enumerate() {
            // Outer counter-clockwise, holes clockwise: free space on the left. Decided exactly:
            // a float area can have the wrong sign on slivers with huge coordinates.
            let turn = ring_orientation(ring);
            if turn == 0 {
                return Err(InvalidEnvironment::Degenerate { ring: r });
            }
            if (r == 0) != (turn > 0) {
                ring.reverse();
            }
        }
        for h in 1..rings.len() {
            let at = rings[h][0];
            if kernel::ring_side(&rings[0], at) != RingSide::Inside {
                return Err(InvalidEnvironment::HoleOutside { ring: h, at });
            }
            for (o, other) in rings.iter().enumerate().skip(1) {
                if o != h && kernel::ring_side(other, at) == RingSide::Inside {
                    return Err(InvalidEnvironment::NestedHole { ring: h, other: o });
                }
            }
        }
        Ok(Self { rings })
    }

    /// All rings: the outer boundary first, then the holes.
    pub fn rings(&self) -> &[Vec<Point>] {
        &self.rings
    }

    /// The outer boundary (counter-clockwise).
    pub fn outer(&self) -> &[Point] {
        &self.rings[0]
    }

    /// The holes (clockwise).
    pub fn holes(&self) -> &[Vec<Point>] {
        &self.rings[1..]
    }

    /// Total number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.rings.iter().map(Vec::len).sum()
    }

    /// The endpoints of an edge.
    pub fn edge(&self, e: EdgeId) -> (Point, Point) {
        let ring = &self.rings[e.ring as usize];
        let i = e.index as usize;
        (ring[i], ring[(i + 1) % ring.len()])
    }

    /// The reflex vertices `(ring, index)`: interior angle above 180° (a right turn with the
    /// free space on the left). Collinear vertices are not reflex.
    pub fn reflex_vertices(&self) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (r, ring) in self.rings.iter().enumerate() {
            let n = ring.len();
            for i in 0..n {
                if kernel::orient_sign(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) < 0 {
                    out.push((r, i));
                }
            }
        }
        out
    }

    /// The area of the free space.
    pub fn area(&self) -> f64 {
        self.rings.iter().map(|r| signed_area(r)).sum()
    }

    /// The distance from `p` to the nearest edge of any ring.
    pub fn boundary_distance(&self, p: Point) -> f64 {
        self.rings
            .iter()
            .flat_map(|r| (0..r.len()).map(move |i| (r[i], r[(i + 1) % r.len()])))
            .map(|(a, b)| super::segment_distance(p, a, b))
            .fold(f64::INFINITY, f64::min)
    }

    /// Where `p` lies (exact).
    pub fn locate(&self, p: Point) -> Location {
        match kernel::ring_side(&self.rings[0], p) {
            RingSide::Outside => return Location::Outside,
            RingSide::Boundary => return Location::Boundary,
            RingSide::Inside => {}
        }
        for hole in self.holes() {
            match kernel::ring_side(hole, p) {
                RingSide::Inside => return Location::Outside,
                RingSide::Boundary => return Location::Boundary,
                RingSide::Outside => {}
            }
        }
        Location::Interior
    }

    /// The axis-aligned bounding box `[min, max]`.
    pub fn bounds(&self) -> [Point; 2] {
        let mut b = [[f64::MAX, f64::MAX], [f64::MIN, f64::MIN]];
        for p in &self.rings[0] {
            b[0] = [b[0][0].min(p[0]), b[0][1].min(p[1])];
            b[1] = [b[1][0].max(p[0]), b[1][1].max(p[1])];
        }
        b
    }
}

/// The exact orientation of a simple ring (+1 counter-clockwise, -1 clockwise, 0 degenerate):
/// the turn at its lexicographically smallest vertex, which is strictly convex on a simple,
/// non-degenerate ring.
pub(crate) fn ring_orientation(ring: &[Point]) -> i8 {
    let n = ring.len();
    let k = (0..n)
        .min_by(|&a, &b| ring[a][0].total_cmp(&ring[b][0]).then(ring[a][1].total_cmp(&ring[b][1])))
        .unwrap_or(0);
    kernel::orient_sign(ring[(k + n - 1) % n], ring[k], ring[(k + 1) % n])
}

/// Twice-free, shifted shoelace area (positive for counter-clockwise).
pub(crate) fn signed_area(ring: &[Point]) -> f64 {
    let Some(&o) = ring.first() else { return 0.0 };
    let mut s = 0.0;
    for i in 1..ring.len().saturating_sub(1) {
        let (a, b) = (ring[i], ring[i + 1]);
        s += (a[0] - o[0]) * (b[1] - o[1]) - (b[0] - o[0]) * (a[1] - o[1]);
    }
    0.5 * s
}

fn check_ring(r: usize, ring: &[Point]) -> Result<(), InvalidEnvironment> {
    for (i, p) in ring.iter().enumerate() {
        for &v in p {
            if !v.is_finite() {
                return Err(InvalidEnvironment::NonFiniteCoord { ring: r, index: i, value: v });
            }
            if !kernel::coordinate_is_safe(v) {
                return Err(InvalidEnvironment::OutOfRange { ring: r, index: i, value: v });
            }
        }
    }
    if ring.len() < 3 {
        return Err(InvalidEnvironment::TooFewVertices { ring: r, count: ring.len() });
    }
    for i in 0..ring.len() {
        if ring[i] == ring[(i + 1) % ring.len()] {
            return Err(InvalidEnvironment::RepeatedVertex {
                ring: r,
                index: (i + 1) % ring.len(),
            });
        }
    }
    Ok(())
}

/// Every pair of edges that could meet is tested exactly; a uniform grid over the bounding
/// box keeps the candidate pairs near-linear in number.
fn check_intersections(rings: &[Vec<Point>]) -> Result<(), InvalidEnvironment> {
    let edges: Vec<(usize, usize)> = rings
        .iter()
        .enumerate()
        .flat_map(|(r, ring)| (0..ring.len()).map(move |i| (r, i)))
        .collect();
    let seg = |(r, i): (usize, usize)| (rings[r][i], rings[r][(i + 1) % rings[r].len()]);
    let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
    for ring in rings {
        for p in ring {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
    }
    let n = edges.len();
    let side = (n as f64).sqrt().ceil().max(1.0) as usize;
    let (w, h) = ((hi[0] - lo[0]).max(f64::MIN_POSITIVE), (hi[1] - lo[1]).max(f64::MIN_POSITIVE));
    let cell = |x: f64, y: f64| {
        let cx = (((x - lo[0]) / w) * side as f64).floor().clamp(0.0, (side - 1) as f64) as usize;
        let cy = (((y - lo[1]) / h) * side as f64).floor().clamp(0.0, (side - 1) as f64) as usize;
        (cx, cy)
    };
    let mut grid: Vec<Vec<u32>> = vec![Vec::new(); side * side];
    for (k, &e) in edges.iter().enumerate() {
        let (a, b) = seg(e);
        let (c0, c1) = (cell(a[0].min(b[0]), a[1].min(b[1])), cell(a[0].max(b[0]), a[1].max(b[1])));
        for cy in c0.1..=c1.1 {
            for cx in c0.0..=c1.0 {
                grid[cy * side + cx].push(k as u32);
            }
        }
    }
    let mut first: Option<(usize, usize)> = None;
    for bucket in &grid {
        for (x, &ka) in bucket.iter().enumerate() {
            for &kb in &bucket[x + 1..] {
                let (ea, eb) = (edges[ka as usize], edges[kb as usize]);
                if meets(rings, ea, eb, &seg) {
                    let pair = if ka < kb {
                        (ka as usize, kb as usize)
                    } else {
                        (kb as usize, ka as usize)
                    };
                    if first.is_none_or(|f| pair < f) {
                        first = Some(pair);
                    }
                }
            }
        }
    }
    match first {
        None => Ok(()),
        Some((ka, kb)) => {
            let ((ra, a), (rb, b)) = (edges[ka], edges[kb]);
            Err(if ra == rb {
                InvalidEnvironment::SelfIntersection { ring: ra, a, b }
            } else {
                InvalidEnvironment::RingsTouch { ring_a: ra, a, ring_b: rb, b }
            })
        }
    }
}

/// Whether two distinct edges meet other than at the vertex consecutive edges share.
fn meets(
    rings: &[Vec<Point>],
    (ra, a): (usize, usize),
    (rb, b): (usize, usize),
    seg: &impl Fn((usize, usize)) -> (Point, Point),
) -> bool {
    let (p0, p1) = seg((ra, a));
    let (q0, q1) = seg((rb, b));
    if ra == rb {
        let n = rings[ra].len();
        let next = |i: usize| (i + 1) % n;
        if next(a) == b || next(b) == a {
            // Consecutive: they share one vertex; they must not overlap beyond it.
            let (shared, pa, pb) = if next(a) == b { (p1, p0, q1) } else { (p0, p1, q0) };
            return kernel::orient_sign(pa, shared, pb) == 0
                && (kernel::on_segment(shared, pa, pb) || kernel::on_segment(shared, pb, pa));
        }
    }
    kernel::segments_intersect(p0, p1, q0, q1)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn normalises_orientation_and_counts_reflex_vertices() {
        let mut outer = square(0.0, 0.0, 10.0);
        outer.reverse();
        let d = Domain::new(outer, vec![square(2.0, 2.0, 2.0), square(6.0, 6.0, 1.0)]).unwrap();
        assert!(signed_area(d.outer()) > 0.0);
        assert!(d.holes().iter().all(|h| signed_area(h) < 0.0));
        assert!((d.area() - (100.0 - 4.0 - 1.0)).abs() < 1e-12);
        // Every hole corner is reflex for the free space; the square's corners are convex.
        assert_eq!(d.reflex_vertices().len(), 8);
        let l = Domain::new(
            vec![[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0], [1.0, 2.0], [0.0, 2.0]],
            vec![],
        )
        .unwrap();
        assert_eq!(l.reflex_vertices(), vec![(0, 3)]);
    }

    #[test]
    fn rejects_what_it_must() {
        let bow = vec![[0.0, 0.0], [2.0, 2.0], [2.0, 0.0], [0.0, 2.0]];
        assert!(matches!(
            Domain::new(bow, vec![]),
            Err(InvalidEnvironment::SelfIntersection { ring: 0, .. })
        ));
        let sq = square(0.0, 0.0, 10.0);
        assert!(matches!(
            Domain::new(sq.clone(), vec![square(20.0, 20.0, 1.0)]),
            Err(InvalidEnvironment::HoleOutside { ring: 1, .. })
        ));
        assert!(matches!(
            Domain::new(sq.clone(), vec![square(0.0, 2.0, 1.0)]),
            Err(InvalidEnvironment::RingsTouch { .. })
        ));
        assert!(matches!(
            Domain::new(sq.clone(), vec![square(2.0, 2.0, 2.0), square(4.0, 2.0, 1.0)]),
            Err(InvalidEnvironment::RingsTouch { .. })
        ));
        assert!(matches!(
            Domain::new(sq.clone(), vec![square(2.0, 2.0, 4.0), square(3.0, 3.0, 1.0)]),
            Err(InvalidEnvironment::NestedHole { .. })
        ));
        assert!(matches!(
            Domain::new(vec![[0.0, 0.0], [1.0, f64::NAN], [0.0, 1.0]], vec![]),
            Err(InvalidEnvironment::NonFiniteCoord { ring: 0, index: 1, .. })
        ));
        assert!(matches!(
            Domain::new(vec![[0.0, 0.0], [1.0, 0.0]], vec![]),
            Err(InvalidEnvironment::TooFewVertices { .. })
        ));
        assert!(matches!(
            Domain::new(vec![[0.0, 0.0], [1.0, 0.0], [1.0, 0.0], [0.0, 1.0]], vec![]),
            Err(InvalidEnvironment::RepeatedVertex { ring: 0, index: 2 })
        ));
        assert!(matches!(
            Domain::new(vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0]], vec![]),
            Err(InvalidEnvironment::Degenerate { ring: 0 }
                | InvalidEnvironment::SelfIntersection { ring: 0, .. })
        ));
        assert!(matches!(
            Domain::new(vec![[0.0, 0.0], [1e300, 0.0], [0.0, 1.0]], vec![]),
            Err(InvalidEnvironment::OutOfRange { .. })
        ));
        // Folding back along an edge (a spike).
        let spike = vec![
            [0.0, 0.0],
            [4.0, 0.0],
            [4.0, 4.0],
            [2.0, 4.0],
            [2.0, 6.0],
            [2.0, 5.0],
            [0.0, 4.0],
        ];
        assert!(Domain::new(spike, vec![]).is_err());
    }

    #[test]
    fn closed_rings_and_collinear_vertices_are_fine() {
        let mut ring = square(0.0, 0.0, 2.0);
        ring.insert(1, [1.0, 0.0]);
        ring.push([0.0, 0.0]);
        let d = Domain::new(ring, vec![]).unwrap();
        assert_eq!(d.vertex_count(), 5);
        assert!(d.reflex_vertices().is_empty());
        assert_eq!(d.locate([1.0, 1.0]), Location::Interior);
        assert_eq!(d.locate([1.0, 0.0]), Location::Boundary);
        assert_eq!(d.locate([3.0, 0.0]), Location::Outside);
    }
}
