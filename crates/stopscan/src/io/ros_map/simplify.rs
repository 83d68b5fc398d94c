//! Topology-preserving simplification of a traced boundary within a Hausdorff tolerance.
//!
//! The vertices of every ring are removed greedily, the cheapest first: removing vertex `v`
//! joins its neighbours `p` and `n` by one edge, and costs the largest distance from that edge
//! to the *traced* vertices it replaces (Douglas–Peucker's error, in Visvalingam–Whyatt's
//! bottom-up order). Costs are distances in metres in the local frame, compared with the
//! tolerance in metres. A removal whose cost exceeds the tolerance is never made, which is the
//! Hausdorff bound: every traced vertex between `p` and `n` lies within the tolerance of the
//! edge `p n`, hence so does every traced point between them (the distance to a segment is
//! convex along each traced edge), and every point of `p n` lies within the tolerance of the
//! traced chain (the chain runs from `p` to `n`, so each point of `p n` is the projection of
//! one of its points, no farther away than the chain is from the segment).
//!
//! A removal is made only when the closed triangle `p v n` holds no other vertex of any ring
//! and no protected point (the start). In a valid set of rings (simple, apart from each other)
//! an edge that met that triangle would have to end inside it or cross `p v` or `v n`, so an
//! empty triangle is swept by the edge `p n` without touching anything: every removal keeps
//! the rings simple and apart, no hole crosses or leaves the outer ring, no ring drops below
//! three vertices (or to zero area), and a protected point keeps its side. A vertex is found in
//! the triangle through a uniform grid, visiting only the cells along the triangle's columns; a
//! removal blocked by a vertex is retried when that vertex goes.
//!
//! The triangle test is exact and runs on the grid corners in cells (whole numbers), not on
//! their coordinates in metres: `k · resolution` is rounded, so corners on one line of the grid
//! (a wall and the tip of a thin obstacle beside it, say) need not be collinear in metres, and
//! an exact test there would let an edge pass a hair beside a vertex it in truth runs through,
//! leaving a valid but needle-thin spike that later constructions cannot resolve. In whole
//! numbers a vertex is either on the new edge or at least `1/|p n|` cells from it, far beyond
//! the rounding of the final coordinates. The start, which is not a corner, is tested in
//! metres, where the result lives.
//!
//! Not geo's `simplify_vw_preserve`: its tolerance is a triangle's area, which bounds no
//! distance, its documentation warns that it may move a hole outside its shell and does not
//! guarantee a valid result, and geo would bring a second i_overlay (4.5) and rstar.
//!
//! Vertices are only removed, never moved or added: the result's vertices are traced vertices.
//! Ties in cost go to the lower vertex index, so the result is deterministic.
//!
//! Complexity: O(n log n) heap operations for n vertices; each removal walks the traced chain
//! it replaces and the grid cells under its triangle, both about the length of the new edge
//! over the cell size.

use std::collections::BinaryHeap;

use crate::algorithm::shortest_path::MinFirst;
use crate::geometry::segment_distance;
use crate::kernel::{Point, on_segment, orient_sign};

/// A ring of grid corners (cells) in metres.
pub(super) fn in_metres(ring: &[Point], resolution: f64) -> Vec<Point> {
    ring.iter().map(|p| [p[0] * resolution, p[1] * resolution]).collect()
}

/// The rings of grid corners `corners` (cells, whole numbers) simplified within `tol` metres,
/// in metres (local frame), keeping every point of `protect` (metres) on its side of every
/// ring. `corners` must be valid (as [`crate::geometry::Domain`] checks) for the guarantees of
/// the module to hold.
pub(super) fn simplify(
    corners: &[Vec<Point>],
    resolution: f64,
    tol: f64,
    protect: &[Point],
) -> Vec<Vec<Point>> {
    if tol.is_nan() || tol <= 0.0 {
        return corners.iter().map(|r| in_metres(r, resolution)).collect();
    }
    let mut s = State::new(corners, resolution, protect);
    let n = s.pts.len();
    let mut heap = BinaryHeap::with_capacity(n);
    for v in 0..n {
        if let Some(cost) = s.cost(v, tol) {
            heap.push(MinFirst(cost, (v as u32, 0)));
        }
    }
    // waiting[u]: vertices whose removal u blocked, retried when u goes.
    let mut waiting: Vec<Vec<u32>> = vec![Vec::new(); n];
    // Candidate removals, cheapest first, then the lowest vertex (and stamp).
    while let Some(MinFirst(_, (v, stamp))) = heap.pop() {
        let v = v as usize;
        if !s.alive[v] || stamp != s.stamp[v] || s.len[s.ring[v] as usize] <= 3 {
            continue;
        }
        match s.blocker(v) {
            Some(Blocker::Vertex(u)) => {
                waiting[u].push(v as u32);
                continue;
            }
            Some(Blocker::Fixed) => continue,
            None => {}
        }
        let (p, q) = (s.prev[v] as usize, s.next[v] as usize);
        s.remove(v);
        let retry = std::mem::take(&mut waiting[v]);
        for w in [p, q].into_iter().chain(retry.into_iter().map(|w| w as usize)) {
            if s.alive[w] {
                s.stamp[w] += 1;
                if let Some(cost) = s.cost(w, tol) {
                    heap.push(MinFirst(cost, (w as u32, s.stamp[w])));
                }
            }
        }
    }
    s.rings().iter().map(|r| in_metres(r, resolution)).collect()
}

/// What keeps a vertex from being removed.
enum Blocker {
    /// A vertex of some ring lies in its triangle.
    Vertex(usize),
    /// A protected point, or a ring that would become degenerate.
    Fixed,
}

/// The rings as doubly linked lists over their traced vertices.
struct State<'a> {
    /// Every traced vertex, ring after ring, as a grid corner (cells; never changes).
    corners: Vec<Point>,
    /// The same in metres.
    pts: Vec<Point>,
    /// Ring `r` holds `first[r]..first[r + 1]`.
    first: Vec<usize>,
    ring: Vec<u32>,
    prev: Vec<u32>,
    next: Vec<u32>,
    alive: Vec<bool>,
    /// Bumped whenever a vertex's heap entry goes stale.
    stamp: Vec<u32>,
    /// Live vertices per ring.
    len: Vec<usize>,
    grid: Grid,
    protect: &'a [Point],
}

impl<'a> State<'a> {
    fn new(rings: &[Vec<Point>], resolution: f64, protect: &'a [Point]) -> Self {
        let mut first = vec![0];
        let (mut corners, mut ring, mut prev, mut next) = (vec![], vec![], vec![], vec![]);
        for (r, rg) in rings.iter().enumerate() {
            let base = corners.len();
            let m = rg.len();
            for (i, &c) in rg.iter().enumerate() {
                corners.push(c);
                ring.push(r as u32);
                prev.push((base + (i + m - 1) % m) as u32);
                next.push((base + (i + 1) % m) as u32);
            }
            first.push(corners.len());
        }
        let n = corners.len();
        let grid = Grid::new(&corners);
        Self {
            len: rings.iter().map(Vec::len).collect(),
            pts: in_metres(&corners, resolution),
            corners,
            first,
            ring,
            prev,
            next,
            alive: vec![true; n],
            stamp: vec![0; n],
            grid,
            protect,
        }
    }

    /// The Hausdorff cost of removing `v`: the farthest traced vertex between its neighbours
    /// from the edge that would join them; `None` above `tol` or when its ring is a triangle.
    fn cost(&self, v: usize, tol: f64) -> Option<f64> {
        let r = self.ring[v] as usize;
        if self.len[r] <= 3 {
            return None;
        }
        let (p, n) = (self.prev[v] as usize, self.next[v] as usize);
        let (a, b) = (self.pts[p], self.pts[n]);
        let (lo, hi) = (self.first[r], self.first[r + 1]);
        let mut worst = 0.0f64;
        let mut k = p;
        loop {
            k = if k + 1 == hi { lo } else { k + 1 };
            if k == n {
                return Some(worst);
            }
            let d = segment_distance(self.pts[k], a, b);
            if d > tol {
                return None;
            }
            worst = worst.max(d);
        }
    }

    /// What lies in the closed triangle of `v` and its neighbours, if anything; also refuses
    /// to turn a ring of four into a flat triangle.
    fn blocker(&self, v: usize) -> Option<Blocker> {
        let (p, n) = (self.prev[v] as usize, self.next[v] as usize);
        let t = [self.corners[p], self.corners[v], self.corners[n]];
        if self.len[self.ring[v] as usize] == 4
            && orient_sign(t[0], t[2], self.corners[self.next[n] as usize]) == 0
        {
            return Some(Blocker::Fixed);
        }
        let m = [self.pts[p], self.pts[v], self.pts[n]];
        if self.protect.iter().any(|&q| in_closed_triangle(m, q)) {
            return Some(Blocker::Fixed);
        }
        self.grid
            .find_in_triangle(t, |u| {
                u != p
                    && u != v
                    && u != n
                    && self.alive[u]
                    && in_closed_triangle(t, self.corners[u])
            })
            .map(Blocker::Vertex)
    }

    fn remove(&mut self, v: usize) {
        let (p, n) = (self.prev[v], self.next[v]);
        self.next[p as usize] = n;
        self.prev[n as usize] = p;
        self.alive[v] = false;
        self.len[self.ring[v] as usize] -= 1;
    }

    /// The live vertices of each ring, in order from its first live traced vertex.
    fn rings(&self) -> Vec<Vec<Point>> {
        (0..self.len.len())
            .map(|r| {
                let Some(start) = (self.first[r]..self.first[r + 1]).find(|&k| self.alive[k])
                else {
                    return Vec::new();
                };
                let mut out = Vec::with_capacity(self.len[r]);
                let mut k = start;
                loop {
                    out.push(self.corners[k]);
                    k = self.next[k] as usize;
                    if k == start {
                        return out;
                    }
                }
            })
            .collect()
    }
}

/// Whether `q` lies in the closed triangle `t` (a segment when `t` is flat), exactly.
fn in_closed_triangle(t: [Point; 3], q: Point) -> bool {
    let [a, b, c] = t;
    let o = orient_sign(a, b, c);
    if o == 0 {
        // Flat: `b` lies between `a` and `c` (the rings are valid), so the triangle is `a c`.
        return on_segment(a, c, q);
    }
    orient_sign(a, b, q) * o >= 0 && orient_sign(b, c, q) * o >= 0 && orient_sign(c, a, q) * o >= 0
}

/// A uniform grid of vertex indices over their bounding box (bucketed once, in index order).
struct Grid {
    lo: Point,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Cell `k` holds `items[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    items: Vec<u32>,
}

impl Grid {
    /// About one cell per vertex.
    fn new(pts: &[Point]) -> Self {
        let (mut lo, mut hi) = ([f64::MAX; 2], [f64::MIN; 2]);
        for p in pts {
            lo = [lo[0].min(p[0]), lo[1].min(p[1])];
            hi = [hi[0].max(p[0]), hi[1].max(p[1])];
        }
        let (w, h) = ((hi[0] - lo[0]).max(0.0), (hi[1] - lo[1]).max(0.0));
        let n = pts.len().max(1) as f64;
        let cell = (w * h / n).sqrt().max(w.max(h) / n).max(f64::MIN_POSITIVE);
        let nx = ((w / cell).floor() as usize + 1).min(pts.len() + 1);
        let ny = ((h / cell).floor() as usize + 1).min(pts.len() + 1);
        let mut g = Self { lo, cell, nx, ny, start: vec![0; nx * ny + 1], items: Vec::new() };
        let keys: Vec<usize> = pts.iter().map(|p| g.row(p[1]) * nx + g.col(p[0])).collect();
        for &k in &keys {
            g.start[k + 1] += 1;
        }
        for k in 0..nx * ny {
            g.start[k + 1] += g.start[k];
        }
        let mut fill = g.start.clone();
        g.items = vec![0; pts.len()];
        for (i, &k) in keys.iter().enumerate() {
            g.items[fill[k] as usize] = i as u32;
            fill[k] += 1;
        }
        g
    }

    fn col(&self, x: f64) -> usize {
        (((x - self.lo[0]) / self.cell).floor().max(0.0) as usize).min(self.nx - 1)
    }

    fn row(&self, y: f64) -> usize {
        (((y - self.lo[1]) / self.cell).floor().max(0.0) as usize).min(self.ny - 1)
    }

    /// The first vertex (in cell order) under the triangle `t` for which `hit` holds. Visits the
    /// columns the triangle spans and, in each, the rows of the triangle's extent over the
    /// column widened by half a cell, plus one row either side: a superset of the cells any
    /// point of the closed triangle falls in, whatever the rounding (`col` and `row` are
    /// monotone).
    fn find_in_triangle(&self, t: [Point; 3], mut hit: impl FnMut(usize) -> bool) -> Option<usize> {
        let x0 = t[0][0].min(t[1][0]).min(t[2][0]);
        let x1 = t[0][0].max(t[1][0]).max(t[2][0]);
        for cx in self.col(x0)..=self.col(x1) {
            let sx0 = self.lo[0] + (cx as f64 - 0.5) * self.cell;
            let sx1 = self.lo[0] + (cx as f64 + 1.5) * self.cell;
            let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
            for (p, q) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                let (l, r) = if p[0] <= q[0] { (p, q) } else { (q, p) };
                let (cl, cr) = (l[0].max(sx0), r[0].min(sx1));
                if cl > cr {
                    continue;
                }
                if r[0] > l[0] {
                    for x in [cl, cr] {
                        let y = l[1] + (r[1] - l[1]) * ((x - l[0]) / (r[0] - l[0]));
                        y0 = y0.min(y);
                        y1 = y1.max(y);
                    }
                } else {
                    y0 = y0.min(l[1]).min(r[1]);
                    y1 = y1.max(l[1]).max(r[1]);
                }
            }
            if y0 > y1 {
                continue;
            }
            let (r0, r1) = (self.row(y0).saturating_sub(1), (self.row(y1) + 1).min(self.ny - 1));
            for cy in r0..=r1 {
                let k = cy * self.nx + cx;
                for &i in &self.items[self.start[k] as usize..self.start[k + 1] as usize] {
                    if hit(i as usize) {
                        return Some(i as usize);
                    }
                }
            }
        }
        None
    }
}
