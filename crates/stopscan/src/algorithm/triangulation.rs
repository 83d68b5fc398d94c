//! The constrained Delaunay triangulation of a [`Domain`]'s free space (spade), stored as
//! compact triangle arrays for the visibility expansion.

use spade::handles::FixedVertexHandle;
use spade::{
    ConstrainedDelaunayTriangulation, HasPosition, HierarchyHintGenerator, Point2,
    PositionInTriangulation, Triangulation,
};

use crate::geometry::{Domain, EdgeId};
use crate::kernel::Point;

/// "No triangle": the other side of a domain edge.
pub const NONE: u32 = u32::MAX;

#[derive(Debug, Clone, Copy)]
struct Vertex {
    pos: Point2<f64>,
    id: u32,
}

impl HasPosition for Vertex {
    type Scalar = f64;
    fn position(&self) -> Point2<f64> {
        self.pos
    }
}

type Cdt = ConstrainedDelaunayTriangulation<Vertex, (), (), (), HierarchyHintGenerator<f64>>;

/// Why a triangulation could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum TriangulationError {
    /// spade refused a vertex (out of its range); a validated domain never triggers this.
    #[error("the triangulation rejected a vertex: {0}")]
    Insertion(String),
}

/// Where a point lies in the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshLocation {
    /// Inside triangle `t`.
    Face(u32),
    /// On the side `side` of triangle `t` shared with another free-space triangle.
    InnerEdge(u32, u8),
    /// On the interior of the domain edge that is side `side` of triangle `t`.
    BoundaryEdge(u32, u8),
    /// On the domain vertex `v`.
    Vertex(u32),
    /// Outside the free space.
    Outside,
}

/// The free space triangulated: vertices are the domain's (ring order, concatenated),
/// triangles are counter-clockwise, and side `k` of a triangle is the edge opposite its
/// vertex `k`.
#[derive(Debug)]
pub struct Mesh {
    points: Vec<Point>,
    ring_start: Vec<u32>,
    /// `tri[t] = [v0, v1, v2]`, counter-clockwise.
    pub(crate) tri: Vec<[u32; 3]>,
    /// `nbr[t][k]`: the triangle across side `k`, or [`NONE`] at a domain edge.
    pub(crate) nbr: Vec<[u32; 3]>,
    /// `mirror[t][k]`: which side of `nbr[t][k]` is the shared one.
    pub(crate) mirror: Vec<[u8; 3]>,
    /// For each vertex, a triangle `t` and index `i` with `tri[t][i] = v` and the domain edge
    /// `v → next(v)` as the triangle's edge `tri[t][i] → tri[t][i+1]`.
    pub(crate) vertex_fan: Vec<(u32, u8)>,
    face_map: Vec<u32>,
    cdt: Cdt,
}

impl Mesh {
    /// Triangulates a domain.
    ///
    /// # Errors
    /// [`TriangulationError`] if spade rejects the input (never for a validated domain).
    ///
    /// # Complexity
    /// O(n log n) time (spade's bulk loader), O(n) space.
    pub fn new(domain: &Domain) -> Result<Self, TriangulationError> {
        let mut points = Vec::with_capacity(domain.vertex_count());
        let mut ring_start = Vec::with_capacity(domain.rings().len() + 1);
        let mut edges = Vec::with_capacity(domain.vertex_count());
        for ring in domain.rings() {
            let base = points.len();
            ring_start.push(base as u32);
            for (i, p) in ring.iter().enumerate() {
                points.push(*p);
                edges.push([base + i, base + (i + 1) % ring.len()]);
            }
        }
        ring_start.push(points.len() as u32);
        let verts: Vec<Vertex> = points
            .iter()
            .enumerate()
            .map(|(i, p)| Vertex { pos: Point2::new(p[0], p[1]), id: i as u32 })
            .collect();
        let cdt = Cdt::bulk_load_cdt(verts, edges)
            .map_err(|e| TriangulationError::Insertion(format!("{e:?}")))?;
        let mut mesh = Self {
            points,
            ring_start,
            tri: Vec::new(),
            nbr: Vec::new(),
            mirror: Vec::new(),
            vertex_fan: Vec::new(),
            face_map: Vec::new(),
            cdt,
        };
        mesh.classify();
        Ok(mesh)
    }

    /// Marks free-space faces by parity (crossing a domain edge toggles inside/outside,
    /// starting outside at the convex hull) and builds the triangle arrays.
    fn classify(&mut self) {
        let nf = self.cdt.num_all_faces();
        let mut state = vec![0u8; nf]; // 0 unknown, 1 outside, 2 inside
        let mut stack = Vec::new();
        for e in self.cdt.convex_hull() {
            let inner = e.rev().face();
            let s = if e.is_constraint_edge() { 2 } else { 1 };
            if state[inner.fix().index()] == 0 {
                state[inner.fix().index()] = s;
                stack.push(inner.fix());
            }
        }
        while let Some(f) = stack.pop() {
            let s = state[f.index()];
            let Some(face) = self.cdt.face(f).as_inner() else { continue };
            for e in face.adjacent_edges() {
                let g = e.rev().face();
                if g.is_outer() || state[g.fix().index()] != 0 {
                    continue;
                }
                let t = if e.is_constraint_edge() { 3 - s } else { s };
                state[g.fix().index()] = t;
                stack.push(g.fix());
            }
        }
        self.face_map = vec![NONE; nf];
        for face in self.cdt.inner_faces() {
            if state[face.fix().index()] == 2 {
                self.face_map[face.fix().index()] = self.tri.len() as u32;
                let v = face.vertices().map(|h| h.data().id);
                self.tri.push(v);
            }
        }
        let n = self.tri.len();
        self.nbr = vec![[NONE; 3]; n];
        self.mirror = vec![[0; 3]; n];
        self.vertex_fan = vec![(NONE, 0); self.points.len()];
        for face in self.cdt.inner_faces() {
            let t = self.face_map[face.fix().index()];
            if t == NONE {
                continue;
            }
            let v = self.tri[t as usize];
            // spade's adjacent_edges()[k] runs from vertices()[k] to vertices()[k+1]: our
            // side (k + 2) % 3.
            for (k, e) in face.adjacent_edges().iter().enumerate() {
                let side = (k + 2) % 3;
                if e.is_constraint_edge() {
                    self.vertex_fan[v[k] as usize] = (t, k as u8);
                    continue;
                }
                let g = e.rev().face();
                let u = g.as_inner().map_or(NONE, |h| self.face_map[h.index()]);
                self.nbr[t as usize][side] = u;
                if u != NONE {
                    let w = self.tri[u as usize];
                    // The shared edge in u runs v[k+1] → v[k]; its side is opposite the third vertex.
                    let m = (0..3).find(|&j| w[j] != v[k] && w[j] != v[(k + 1) % 3]).unwrap_or(0);
                    self.mirror[t as usize][side] = m as u8;
                }
            }
        }
    }

    /// Vertex coordinates.
    pub fn points(&self) -> &[Point] {
        &self.points
    }

    /// Number of free-space triangles.
    pub fn triangles(&self) -> usize {
        self.tri.len()
    }

    /// The free-space triangles' corners (indices into [`Mesh::points`], counter-clockwise).
    pub fn triangle_corners(&self) -> &[[u32; 3]] {
        &self.tri
    }

    /// The domain edge starting at vertex `v` (to the next vertex of its ring).
    pub fn edge_of(&self, v: u32) -> EdgeId {
        let ring = self.ring_start.partition_point(|&s| s <= v) - 1;
        EdgeId { ring: ring as u32, index: v - self.ring_start[ring] }
    }

    /// The vertex after `v` in its ring.
    pub(crate) fn ring_next(&self, v: u32) -> u32 {
        let ring = self.ring_start.partition_point(|&s| s <= v) - 1;
        let (s, e) = (self.ring_start[ring], self.ring_start[ring + 1]);
        if v + 1 == e { s } else { v + 1 }
    }

    /// Locates a point exactly.
    pub fn locate(&self, p: Point) -> MeshLocation {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return MeshLocation::Outside;
        }
        match self.cdt.locate(Point2::new(p[0], p[1])) {
            PositionInTriangulation::OnFace(f) => match self.face_map[f.index()] {
                NONE => MeshLocation::Outside,
                t => MeshLocation::Face(t),
            },
            PositionInTriangulation::OnVertex(v) => self.vertex_location(v),
            PositionInTriangulation::OnEdge(e) => {
                let e = self.cdt.directed_edge(e);
                let (f1, f2) = (e.face().as_inner(), e.rev().face().as_inner());
                let t1 = f1.map_or(NONE, |f| self.face_map[f.index()]);
                let t2 = f2.map_or(NONE, |f| self.face_map[f.index()]);
                let (t, other) = if t1 == NONE { (t2, t1) } else { (t1, t2) };
                if t == NONE {
                    return MeshLocation::Outside;
                }
                let (a, b) = (e.from().data().id, e.to().data().id);
                let w = self.tri[t as usize];
                let side = (0..3).find(|&j| w[j] != a && w[j] != b).unwrap_or(0) as u8;
                if other == NONE {
                    MeshLocation::BoundaryEdge(t, side)
                } else {
                    MeshLocation::InnerEdge(t, side)
                }
            }
            PositionInTriangulation::OutsideOfConvexHull(_)
            | PositionInTriangulation::NoTriangulation => MeshLocation::Outside,
        }
    }

    fn vertex_location(&self, v: FixedVertexHandle) -> MeshLocation {
        let id = self.cdt.vertex(v).data().id;
        MeshLocation::Vertex(id)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ring(x: f64, y: f64, s: f64) -> Vec<Point> {
        vec![[x, y], [x + s, y], [x + s, y + s], [x, y + s]]
    }

    #[test]
    fn free_space_area_is_preserved() {
        let d = Domain::new(ring(0.0, 0.0, 10.0), vec![ring(2.0, 2.0, 2.0), ring(6.0, 5.0, 3.0)])
            .unwrap();
        let m = Mesh::new(&d).unwrap();
        let area: f64 = m
            .tri
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| m.points[i as usize]);
                0.5 * ((b[0] - a[0]) * (c[1] - a[1]) - (c[0] - a[0]) * (b[1] - a[1]))
            })
            .sum();
        assert!((area - d.area()).abs() < 1e-9, "{area} vs {}", d.area());
        // Neighbours are symmetric.
        for t in 0..m.triangles() {
            for k in 0..3 {
                let u = m.nbr[t][k];
                if u != NONE {
                    assert_eq!(m.nbr[u as usize][m.mirror[t][k] as usize], t as u32);
                    // Side k is the edge opposite vertex k: both its ends are in the neighbour.
                    let (a, b) = (m.tri[t][(k + 1) % 3], m.tri[t][(k + 2) % 3]);
                    assert!(m.tri[u as usize].contains(&a) && m.tri[u as usize].contains(&b));
                    assert!(!m.tri[u as usize].contains(&m.tri[t][k]));
                }
            }
        }
        // The fan entry of v holds the domain edge v → next(v) as a triangle edge.
        for (v, &(t, i)) in m.vertex_fan.iter().enumerate() {
            let e = m.edge_of(v as u32);
            let ring = &d.rings()[e.ring as usize];
            let next = ring[(e.index as usize + 1) % ring.len()];
            let tri = m.tri[t as usize];
            assert_eq!(tri[i as usize], v as u32);
            assert_eq!(m.points[tri[(i as usize + 1) % 3] as usize], next);
        }
    }

    #[test]
    fn locations() {
        let d = Domain::new(ring(0.0, 0.0, 10.0), vec![ring(2.0, 2.0, 2.0)]).unwrap();
        let m = Mesh::new(&d).unwrap();
        assert!(matches!(
            m.locate([5.0, 7.0]),
            MeshLocation::Face(_) | MeshLocation::InnerEdge(..)
        ));
        assert_eq!(m.locate([3.0, 3.0]), MeshLocation::Outside);
        assert_eq!(m.locate([11.0, 3.0]), MeshLocation::Outside);
        assert!(matches!(m.locate([0.0, 0.0]), MeshLocation::Vertex(0)));
        assert!(matches!(m.locate([5.0, 0.0]), MeshLocation::BoundaryEdge(..)));
        assert_eq!(m.edge_of(5), EdgeId { ring: 1, index: 1 });
    }
}
