//! The constrained Delaunay triangulation of a [`Domain`]'s free space (spade), stored as
//! compact triangle arrays for the visibility expansion.

use spade::handles::FixedVertexHandle;
use spade::{
    ConstrainedDelaunayTriangulation, HasPosition, HierarchyHintGenerator, Point2,
    PositionInTriangulation, Triangulation,
};

use crate::geometry::{Domain, EdgeId};
use crate::kernel::{Point, orient_sign};

/// "No triangle": the other side of a domain edge.
pub const NONE: u32 = u32::MAX;

/// In [`Cell::adj`], marks a side that is a domain edge; the low bits are the edge's ring.
pub(crate) const WALL: u32 = 1 << 31;

/// The most triangles a mesh may have: [`Cell::adj`] packs a neighbour's index with the
/// shared side's number (2 bits) below [`WALL`]. (A polygon with holes has at least n − 2
/// triangles for n vertices, so vertex indices stay below [`WALL`] too.)
const MAX_TRIANGLES: usize = 1 << 29;

/// One triangle as the triangular expansion reads it, 24 bytes: per side `k` (opposite
/// corner `k`), what lies across it and the far corner there. Side `k` leads to cell
/// `adj[k] >> 2` through that triangle's side `adj[k] & 3`, whose opposite corner is
/// `coords[opp[k]]`; when `adj[k]` has the [`WALL`] bit, side `k` is the domain edge
/// `EdgeId { ring: adj[k] & !WALL, index: opp[k] }`, so a piece of the region is named
/// without reading anything else.
///
/// With the far corner here, one expansion step needs the next triangle's cell and the far
/// corner's coordinates, and both addresses are known at once, so the two loads overlap
/// instead of waiting for each other.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cell {
    /// Across each side: neighbour and mirror side, or the domain edge.
    pub(crate) adj: [u32; 3],
    /// The corner of the neighbour opposite the shared side, as an index into
    /// [`Mesh::coords`] (at a domain edge: the edge's index in its ring).
    pub(crate) opp: [u32; 3],
}

/// A uniform grid over the mesh's bounding box naming, for each grid cell, a triangle near it
/// (its [`Cell`], and its corners as indices into [`Mesh::coords`]): where
/// [`Mesh::locate`]'s walk starts.
/// About two triangles per cell, so walks are a few steps long.
#[derive(Debug, Default)]
struct Grid {
    lo: Point,
    /// Cells per unit length, on each axis.
    scale: [f64; 2],
    side: [usize; 2],
    starts: Vec<GridStart>,
    /// Steps before a walk gives up (a visibility walk can circle in a constrained
    /// triangulation).
    max_steps: usize,
}

#[derive(Debug, Clone, Copy)]
struct GridStart {
    /// The triangle's index in [`Mesh::cells`].
    cell: u32,
    /// Its corners, as indices into [`Mesh::coords`].
    c: [u32; 3],
}

impl Grid {
    /// `coord_at[v]`: the index of vertex `v` in [`Mesh::coords`].
    fn new(mesh: &Mesh, coord_at: &[u32]) -> Self {
        let n = mesh.tri.len();
        if n == 0 {
            return Self::default();
        }
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &mesh.coords {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
        let (w, h) =
            ((hi[0] - lo[0]).max(f64::MIN_POSITIVE), (hi[1] - lo[1]).max(f64::MIN_POSITIVE));
        // Square cells, about n / 2 of them.
        let cell = (w * h / (n as f64 / 2.0).max(1.0)).sqrt();
        let side = [
            ((w / cell).ceil() as usize).clamp(1, 1 << 15),
            ((h / cell).ceil() as usize).clamp(1, 1 << 15),
        ];
        let scale = [side[0] as f64 / w, side[1] as f64 / h];
        let mut grid =
            Self { lo, scale, side, starts: Vec::new(), max_steps: 64 + 4 * (side[0] + side[1]) };
        // Each triangle claims the cell of its centroid (the first to come keeps it) ...
        let mut owner = vec![NONE; side[0] * side[1]];
        for (cell, &t) in mesh.cell_tri.iter().enumerate() {
            let c = mesh.tri[t as usize].map(|i| mesh.points[i as usize]);
            let centroid =
                [(c[0][0] + c[1][0] + c[2][0]) / 3.0, (c[0][1] + c[1][1] + c[2][1]) / 3.0];
            let g = grid.cell(centroid);
            if owner[g] == NONE {
                owner[g] = cell as u32;
            }
        }
        // ... and cells without one take a neighbour's, breadth first from the claimed ones.
        let mut queue: std::collections::VecDeque<usize> =
            (0..owner.len()).filter(|&g| owner[g] != NONE).collect();
        while let Some(g) = queue.pop_front() {
            let (x, y) = (g % side[0], g / side[0]);
            let next = [
                (x > 0).then(|| g - 1),
                (x + 1 < side[0]).then_some(g + 1),
                (y > 0).then(|| g - side[0]),
                (y + 1 < side[1]).then_some(g + side[0]),
            ];
            for h in next.into_iter().flatten() {
                if owner[h] == NONE {
                    owner[h] = owner[g];
                    queue.push_back(h);
                }
            }
        }
        grid.starts = owner
            .iter()
            .map(|&cell| {
                let t = mesh.cell_tri[cell as usize] as usize;
                GridStart { cell, c: mesh.tri[t].map(|i| coord_at[i as usize]) }
            })
            .collect();
        grid
    }

    /// The cell holding `p` (clamped to the grid).
    fn cell(&self, p: Point) -> usize {
        let x = (((p[0] - self.lo[0]) * self.scale[0]) as usize).min(self.side[0] - 1);
        let y = (((p[1] - self.lo[1]) * self.scale[1]) as usize).min(self.side[1] - 1);
        y * self.side[0] + x
    }

    /// Where a walk to `p` starts; `None` outside the bounding box (and for an empty mesh).
    fn start(&self, p: Point) -> Option<GridStart> {
        if self.starts.is_empty() {
            return None;
        }
        let (x, y) = ((p[0] - self.lo[0]) * self.scale[0], (p[1] - self.lo[1]) * self.scale[1]);
        if !(x >= 0.0 && y >= 0.0 && x <= self.side[0] as f64 && y <= self.side[1] as f64) {
            return None;
        }
        Some(self.starts[self.cell(p)])
    }
}

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
    /// More triangles than the compact mesh can number (2^29).
    #[error("the triangulation has {0} triangles, more than the 2^29 the mesh can hold")]
    TooLarge(usize),
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
    /// The triangles packed for the expansion ([`Cell`]), in the order of a Hilbert curve
    /// through their centroids, so that triangles near each other in the plane are near each
    /// other in memory (on large maps spade's face order scatters a walk's neighbours over
    /// megabytes). `cells[tri_cell[t]]` is triangle `t`; triangle numbers (locations,
    /// [`Mesh::triangle_corners`]) keep spade's order, so nothing outside the expansion
    /// sees the packing.
    pub(crate) cells: Vec<Cell>,
    /// `cell_tri[c]`: the triangle packed in cell `c`.
    cell_tri: Vec<u32>,
    /// `tri_cell[t]`: the cell of triangle `t`.
    pub(crate) tri_cell: Vec<u32>,
    /// The vertex coordinates again, numbered in the order the cells first use them, so that
    /// a triangle's corners lie near its neighbours' in memory.
    pub(crate) coords: Vec<Point>,
    /// `coords[coord_at[v]]` is vertex `v`'s position.
    pub(crate) coord_at: Vec<u32>,
    /// Where point location starts its walk ([`Grid`]).
    grid: Grid,
    face_map: Vec<u32>,
    cdt: Cdt,
}

/// The Hilbert curve's grid: 2^16 cells a side.
const HILBERT_SIDE: u32 = 1 << 16;

/// The position of cell `(x, y)` along the Hilbert curve through a `HILBERT_SIDE`² grid.
fn hilbert_index(mut x: u32, mut y: u32) -> u64 {
    let mut d = 0u64;
    let mut s = HILBERT_SIDE / 2;
    while s > 0 {
        let rx = u32::from(x & s != 0);
        let ry = u32::from(y & s != 0);
        d += u64::from(s) * u64::from(s) * u64::from((3 * rx) ^ ry);
        // Rotate the quadrant so the curve's pieces join.
        if ry == 0 {
            if rx == 1 {
                x = HILBERT_SIDE - 1 - x;
                y = HILBERT_SIDE - 1 - y;
            }
            std::mem::swap(&mut x, &mut y);
        }
        s /= 2;
    }
    d
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
            cells: Vec::new(),
            cell_tri: Vec::new(),
            tri_cell: Vec::new(),
            coords: Vec::new(),
            coord_at: Vec::new(),
            grid: Grid::default(),
            face_map: Vec::new(),
            cdt,
        };
        mesh.classify();
        if mesh.tri.len() > MAX_TRIANGLES {
            return Err(TriangulationError::TooLarge(mesh.tri.len()));
        }
        mesh.coord_at = mesh.pack();
        mesh.grid = Grid::new(&mesh, &mesh.coord_at);
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

    /// The order of the cells: the triangles sorted by the Hilbert index of their centroids
    /// (ties by triangle number, so deterministic).
    fn hilbert_order(&self) -> Vec<u32> {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in &self.points {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
        let side = f64::from(HILBERT_SIDE - 1);
        let scale = [
            side / (hi[0] - lo[0]).max(f64::MIN_POSITIVE),
            side / (hi[1] - lo[1]).max(f64::MIN_POSITIVE),
        ];
        let mut keys: Vec<(u64, u32)> = self
            .tri
            .iter()
            .enumerate()
            .map(|(t, v)| {
                let c = v.map(|i| self.points[i as usize]);
                let cell = |a: usize| {
                    let x = (c[0][a] + c[1][a] + c[2][a]) / 3.0;
                    ((x - lo[a]) * scale[a]).clamp(0.0, side) as u32
                };
                (hilbert_index(cell(0), cell(1)), t as u32)
            })
            .collect();
        keys.sort_unstable();
        keys.into_iter().map(|(_, t)| t).collect()
    }

    /// Builds [`Mesh::cells`] and [`Mesh::coords`] from the triangle arrays;
    /// returns each vertex's index in `coords`.
    fn pack(&mut self) -> Vec<u32> {
        self.cell_tri = self.hilbert_order();
        self.tri_cell = vec![NONE; self.tri.len()];
        for (c, &t) in self.cell_tri.iter().enumerate() {
            self.tri_cell[t as usize] = c as u32;
        }
        // Coordinates in the order the cells first use them.
        let mut at = vec![NONE; self.points.len()];
        self.coords = Vec::with_capacity(self.points.len());
        for &t in &self.cell_tri {
            for &i in &self.tri[t as usize] {
                if at[i as usize] == NONE {
                    at[i as usize] = self.coords.len() as u32;
                    self.coords.push(self.points[i as usize]);
                }
            }
        }
        self.cells = Vec::with_capacity(self.tri.len());
        for &t in &self.cell_tri {
            let t = t as usize;
            let v = self.tri[t];
            let (mut adj, mut opp) = ([0; 3], [0; 3]);
            for k in 0..3 {
                match self.nbr[t][k] {
                    NONE => {
                        let e = self.edge_of(v[(k + 1) % 3]);
                        adj[k] = WALL | e.ring;
                        opp[k] = e.index;
                    }
                    u => {
                        let m = self.mirror[t][k];
                        adj[k] = (self.tri_cell[u as usize] << 2) | u32::from(m);
                        opp[k] = at[self.tri[u as usize][m as usize] as usize];
                    }
                }
            }
            self.cells.push(Cell { adj, opp });
        }
        at
    }

    /// The first vertex of a domain edge.
    pub(crate) fn edge_start(&self, e: EdgeId) -> u32 {
        self.ring_start[e.ring as usize] + e.index
    }

    /// The last vertex of a domain edge (the next of its ring).
    pub(crate) fn edge_end(&self, e: EdgeId) -> u32 {
        let (s, end) = (self.ring_start[e.ring as usize], self.ring_start[e.ring as usize + 1]);
        if s + e.index + 1 == end { s } else { s + e.index + 1 }
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
    ///
    /// A point strictly inside a triangle is found by a short walk from the triangle the
    /// mesh's uniform grid names for its cell; on an edge or a vertex, or when the walk meets a
    /// domain edge, spade's hierarchy locates it (the same answers, spade picks which triangle names
    /// an inner edge).
    pub fn locate(&self, p: Point) -> MeshLocation {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return MeshLocation::Outside;
        }
        if let Some(t) = self.walk_to(p) {
            return MeshLocation::Face(t);
        }
        self.locate_spade(p)
    }

    /// The triangle that holds `p` strictly inside, found by a visibility walk from the grid's
    /// start triangle; `None` when `p` is on an edge or vertex, or the walk meets a domain
    /// edge or runs long.
    fn walk_to(&self, p: Point) -> Option<u32> {
        let start = self.grid.start(p)?;
        let (mut t, mut c) = (start.cell, start.c.map(|i| self.coords[i as usize]));
        for step in 0..self.grid.max_steps {
            let o = [
                orient_sign(c[1], c[2], p),
                orient_sign(c[2], c[0], p),
                orient_sign(c[0], c[1], p),
            ];
            if o == [1, 1, 1] {
                return Some(self.cell_tri[t as usize]);
            }
            // Leave through a side with p strictly beyond it (starting the search at a side
            // that changes with the step, so the walk cannot circle), never through a wall.
            let cell = &self.cells[t as usize];
            let k =
                (0..3).map(|j| (j + step) % 3).find(|&k| o[k] < 0 && cell.adj[k] & WALL == 0)?;
            let (n, m) = (cell.adj[k] >> 2, (cell.adj[k] & 3) as usize);
            let mut d = [[0.0; 2]; 3];
            d[m] = self.coords[cell.opp[k] as usize];
            d[(m + 1) % 3] = c[(k + 2) % 3];
            d[(m + 2) % 3] = c[(k + 1) % 3];
            (t, c) = (n, d);
        }
        None
    }

    /// [`Mesh::locate`] through spade's point location.
    fn locate_spade(&self, p: Point) -> MeshLocation {
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
    fn packed_cells_hilbert_order_and_grid_walk() {
        let d = Domain::new(ring(0.0, 0.0, 10.0), vec![ring(2.0, 2.0, 2.0), ring(6.0, 5.0, 3.0)])
            .unwrap();
        let m = Mesh::new(&d).unwrap();
        // The cells say what the arrays say.
        for t in 0..m.triangles() {
            let cell = m.cells[m.tri_cell[t] as usize];
            assert_eq!(m.cell_tri[m.tri_cell[t] as usize] as usize, t);
            for k in 0..3 {
                let (a, o) = (cell.adj[k], cell.opp[k]);
                match m.nbr[t][k] {
                    NONE => {
                        let e = EdgeId { ring: a & !WALL, index: o };
                        assert_ne!(a & WALL, 0);
                        assert_eq!(e, m.edge_of(m.tri[t][(k + 1) % 3]));
                        assert_eq!(m.edge_start(e), m.tri[t][(k + 1) % 3]);
                        assert_eq!(m.edge_end(e), m.tri[t][(k + 2) % 3]);
                    }
                    u => {
                        let j = m.mirror[t][k];
                        assert_eq!(a, (m.tri_cell[u as usize] << 2) | u32::from(j));
                        let far = m.tri[u as usize][j as usize];
                        assert_eq!(m.coords[o as usize], m.points[far as usize]);
                    }
                }
            }
        }
        for (v, &i) in m.coord_at.iter().enumerate() {
            assert_eq!(m.coords[i as usize], m.points[v]);
        }
        // The cells' order is deterministic (and a permutation, checked above).
        let again = Mesh::new(&d).unwrap();
        assert_eq!((&m.tri, &m.cell_tri, &m.coords), (&again.tri, &again.cell_tri, &again.coords));
        // The grid walk locates exactly as spade does, on vertices, edges, in holes and
        // outside; and it answers most interior points itself.
        let mut walked = 0;
        for i in -2..=42 {
            for j in -2..=42 {
                let p = [f64::from(i) * 0.25, f64::from(j) * 0.25 + 0.01 * f64::from(i % 3)];
                assert_eq!(m.locate(p), m.locate_spade(p), "at {p:?}");
                walked += usize::from(m.walk_to(p).is_some());
            }
        }
        assert!(walked > 1000, "{walked}");
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
