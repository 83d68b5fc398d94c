//! Shortest paths in the free space: a visibility graph of the reflex vertices, searched
//! with A*.
//!
//! A shortest path bends only at reflex vertices, and only where it wraps around them: a
//! graph edge `u v` is kept when the segment lies in the closed free space and is tangent at
//! both ends (each end's two ring neighbours lie on one side of the line). Whether a segment
//! lies in the closed free space is decided by walking it through the triangulation with
//! exact orientation tests; where it passes exactly through a domain vertex, it must leave
//! through that vertex's closed free wedge. Grazing a vertex or running along an edge is
//! allowed (the closed free space, as for visibility).
//!
//! The search is hand-written (a binary heap over `f64` lengths with `total_cmp`): the
//! graph crates want integer or `Ord` costs.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use serde::{Deserialize, Serialize};

use crate::algorithm::triangulation::{Mesh, MeshLocation, NONE};
use crate::algorithm::visibility::Visibility;
use crate::kernel::{Point, orient_sign};

/// Whether the closed segment `a b` lies in the closed free space of the mesh (exact).
///
/// # Complexity
/// O(triangles crossed).
pub fn segment_is_free(mesh: &Mesh, a: Point, b: Point) -> bool {
    walk(mesh, a, b, |_| {})
}

/// [`segment_is_free`], calling `on_vertex` with every domain vertex the segment passes
/// exactly through strictly after `a`, in order (the walk goes on from each).
pub(crate) fn walk(mesh: &Mesh, a: Point, b: Point, mut on_vertex: impl FnMut(u32)) -> bool {
    let pts = mesh.points();
    let tri = &mesh.tri;
    let mut t = match mesh.locate(a) {
        MeshLocation::Outside => return false,
        _ if a == b => return true,
        MeshLocation::Face(t) => t,
        MeshLocation::InnerEdge(t, s) | MeshLocation::BoundaryEdge(t, s) => {
            let v = tri[t as usize];
            let (p, q) =
                (pts[v[(s as usize + 1) % 3] as usize], pts[v[(s as usize + 2) % 3] as usize]);
            if orient_sign(p, q, b) >= 0 {
                t
            } else {
                match mesh.nbr[t as usize][s as usize] {
                    NONE => return false,
                    u => u,
                }
            }
        }
        MeshLocation::Vertex(v) => match fan_triangle(mesh, v, b) {
            Some(t) => t,
            None => return false,
        },
    };
    let mut a = a;
    for _ in 0..=3 * mesh.triangles() + 3 {
        let v = tri[t as usize];
        let p = v.map(|i| pts[i as usize]);
        if (0..3).all(|k| orient_sign(p[(k + 1) % 3], p[(k + 2) % 3], b) >= 0) {
            return true;
        }
        let s = p.map(|x| orient_sign(a, b, x));
        // The line passes exactly through a vertex ahead of a: continue from that vertex.
        let ahead = |x: Point| (x[0] - a[0]) * (b[0] - a[0]) + (x[1] - a[1]) * (b[1] - a[1]) > 0.0;
        if let Some(k) = (0..3).find(|&k| s[k] == 0 && p[k] != a && ahead(p[k])) {
            a = p[k];
            on_vertex(v[k]);
            match fan_triangle(mesh, v[k], b) {
                Some(u) => {
                    t = u;
                    continue;
                }
                None => return false,
            }
        }
        // Otherwise it leaves through the side whose start is right of the line and end left.
        let Some(k) = (0..3).find(|&k| s[(k + 1) % 3] < 0 && s[(k + 2) % 3] > 0) else {
            return false;
        };
        match mesh.nbr[t as usize][k] {
            NONE => return false,
            u => t = u,
        }
    }
    false
}

/// The free-space triangle around domain vertex `v` whose closed wedge contains the
/// direction towards `b`, if any.
fn fan_triangle(mesh: &Mesh, v: u32, b: Point) -> Option<u32> {
    let pts = mesh.points();
    let pv = pts[v as usize];
    let (mut t, mut i) = mesh.vertex_fan[v as usize];
    for _ in 0..mesh.triangles() {
        let w = mesh.tri[t as usize];
        let (p1, p2) =
            (pts[w[(i as usize + 1) % 3] as usize], pts[w[(i as usize + 2) % 3] as usize]);
        if orient_sign(pv, p1, b) >= 0 && orient_sign(pv, p2, b) <= 0 {
            return Some(t);
        }
        let u = mesh.nbr[t as usize][(i as usize + 1) % 3];
        if u == NONE {
            return None;
        }
        t = u;
        i = mesh.tri[u as usize].iter().position(|&x| x == v)? as u8;
    }
    None
}

/// A path and its length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Path {
    /// From the start to the goal; every segment lies in the closed free space.
    pub points: Vec<Point>,
    /// Euclidean length.
    pub length: f64,
}

/// The visibility graph of a domain's reflex vertices, built once.
#[derive(Debug)]
pub struct PathPlanner<'a> {
    vis: &'a Visibility,
    /// Reflex vertices: mesh vertex id, position, and its two ring neighbours.
    nodes: Vec<(u32, Point, Point, Point)>,
    adj: Vec<Vec<(u32, f64)>>,
}

/// A `BinaryHeap` entry that pops the least cost first, ties to the least key; costs are
/// ordered totally (`f64::total_cmp`), and equality agrees with the order.
#[derive(Debug, Clone, Copy)]
pub(crate) struct MinFirst<K>(pub(crate) f64, pub(crate) K);

impl<K: Ord> PartialEq for MinFirst<K> {
    fn eq(&self, other: &Self) -> bool {
        self.cmp(other) == Ordering::Equal
    }
}

impl<K: Ord> Eq for MinFirst<K> {}

impl<K: Ord> PartialOrd for MinFirst<K> {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl<K: Ord> Ord for MinFirst<K> {
    /// Reversed, so that the max-heap pops the cheapest.
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then_with(|| other.1.cmp(&self.1))
    }
}

/// Whether the line from `u` (neighbours `p`, `n`) towards `x` is tangent at `u`.
fn tangent(u: Point, p: Point, n: Point, x: Point) -> bool {
    orient_sign(u, x, p) * orient_sign(u, x, n) >= 0
}

impl<'a> PathPlanner<'a> {
    /// Builds the reflex-vertex visibility graph.
    ///
    /// # Complexity
    /// O(r²) tangency tests and, for the tangent pairs, one exact walk each (r reflex
    /// vertices).
    pub fn new(vis: &'a Visibility) -> Self {
        let d = vis.domain();
        let mut nodes = Vec::new();
        let mut base = 0u32;
        let mut bases = Vec::new();
        for ring in d.rings() {
            bases.push(base);
            base += ring.len() as u32;
        }
        for (r, i) in d.reflex_vertices() {
            let ring = &d.rings()[r];
            let n = ring.len();
            nodes.push((bases[r] + i as u32, ring[i], ring[(i + n - 1) % n], ring[(i + 1) % n]));
        }
        let mut adj = vec![Vec::new(); nodes.len()];
        for i in 0..nodes.len() {
            for j in i + 1..nodes.len() {
                let (a, b) = (nodes[i], nodes[j]);
                if tangent(a.1, a.2, a.3, b.1)
                    && tangent(b.1, b.2, b.3, a.1)
                    && segment_is_free(vis.mesh(), a.1, b.1)
                {
                    let len = dist(a.1, b.1);
                    adj[i].push((j as u32, len));
                    adj[j].push((i as u32, len));
                }
            }
        }
        Self { vis, nodes, adj }
    }

    /// Number of graph edges.
    pub fn edges(&self) -> usize {
        self.adj.iter().map(Vec::len).sum::<usize>() / 2
    }

    /// The length of the shortest path from `s` to every reflex vertex that is a bend of some
    /// shortest path from `s` (exact for those; an upper bound for the others), with `s`
    /// itself at distance 0 first. A shortest path from `s` to anywhere ends with a straight
    /// segment from its last bend `u`, for which this length is exact, so `min_u (len(u) +
    /// |u x|)` over this list is the exact geodesic distance to any point `x` — and a lower
    /// bound on the distance to any set, taking `|u x|` as the straight distance to the set.
    ///
    /// # Complexity
    /// O(r) exact walks from `s`, then Dijkstra over the graph.
    pub fn distances_from(&self, s: Point) -> Vec<(Point, f64)> {
        let mesh = self.vis.mesh();
        let n = self.nodes.len();
        let mut g = vec![f64::INFINITY; n];
        let mut heap = BinaryHeap::new();
        if !matches!(mesh.locate(s), MeshLocation::Outside) {
            for (i, u) in self.nodes.iter().enumerate() {
                if segment_is_free(mesh, s, u.1) {
                    g[i] = dist(s, u.1);
                    heap.push(MinFirst(g[i], i as u32));
                }
            }
        }
        while let Some(MinFirst(d, k)) = heap.pop() {
            if d > g[k as usize] {
                continue;
            }
            for &(m, w) in &self.adj[k as usize] {
                if d + w < g[m as usize] {
                    g[m as usize] = d + w;
                    heap.push(MinFirst(d + w, m));
                }
            }
        }
        std::iter::once((s, 0.0))
            .chain((0..n).filter(|&i| g[i].is_finite()).map(|i| (self.nodes[i].1, g[i])))
            .collect()
    }

    /// The shortest path from `s` to `t`, or `None` if either is outside the free space or
    /// they are not connected.
    ///
    /// # Complexity
    /// O(r) exact walks from each end, then A* over the graph.
    ///
    /// # Example
    /// Across the reflex corner (2, 2) of an L-shaped room: two legs of √3.25 m.
    /// ```
    /// use stopscan::algorithm::shortest_path::PathPlanner;
    /// use stopscan::algorithm::visibility::Visibility;
    /// use stopscan::geometry::Domain;
    ///
    /// let l = vec![[0.0, 0.0], [4.0, 0.0], [4.0, 2.0], [2.0, 2.0], [2.0, 4.0], [0.0, 4.0]];
    /// let vis = Visibility::new(Domain::new(l, vec![])?)?;
    /// let planner = PathPlanner::new(&vis);
    /// let path = planner.shortest_path([3.5, 1.0], [1.0, 3.5]).unwrap();
    /// assert_eq!(path.points, [[3.5, 1.0], [2.0, 2.0], [1.0, 3.5]]);
    /// assert!((path.length - 13f64.sqrt()).abs() < 1e-12);
    /// // A straight segment when one exists (here it grazes the corner), none from outside.
    /// assert_eq!(planner.shortest_path([3.0, 1.0], [1.0, 3.0]).unwrap().points.len(), 2);
    /// assert!(planner.shortest_path([3.0, 3.0], [1.0, 1.0]).is_none());
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn shortest_path(&self, s: Point, t: Point) -> Option<Path> {
        let mesh = self.vis.mesh();
        if matches!(mesh.locate(s), MeshLocation::Outside)
            || matches!(mesh.locate(t), MeshLocation::Outside)
        {
            return None;
        }
        if segment_is_free(mesh, s, t) {
            return Some(Path { points: vec![s, t], length: dist(s, t) });
        }
        let n = self.nodes.len();
        let (start, goal) = (n as u32, n as u32 + 1);
        let from_s: Vec<(u32, f64)> = (0..n)
            .filter(|&i| {
                let u = self.nodes[i];
                tangent(u.1, u.2, u.3, s) && segment_is_free(mesh, s, u.1)
            })
            .map(|i| (i as u32, dist(s, self.nodes[i].1)))
            .collect();
        let to_t: Vec<Option<f64>> = (0..n)
            .map(|i| {
                let u = self.nodes[i];
                (tangent(u.1, u.2, u.3, t) && segment_is_free(mesh, u.1, t)).then(|| dist(u.1, t))
            })
            .collect();
        let pos = |k: u32| {
            if k == start {
                s
            } else if k == goal {
                t
            } else {
                self.nodes[k as usize].1
            }
        };
        let mut g = vec![f64::INFINITY; n + 2];
        let mut prev = vec![u32::MAX; n + 2];
        let mut heap = BinaryHeap::new();
        g[start as usize] = 0.0;
        heap.push(MinFirst(dist(s, t), start));
        while let Some(MinFirst(_, k)) = heap.pop() {
            if k == goal {
                break;
            }
            let here = g[k as usize];
            let mut relax = |m: u32, w: f64, heap: &mut BinaryHeap<MinFirst<u32>>| {
                let c = here + w;
                if c < g[m as usize] {
                    g[m as usize] = c;
                    prev[m as usize] = k;
                    heap.push(MinFirst(c + dist(pos(m), t), m));
                }
            };
            if k == start {
                for &(m, w) in &from_s {
                    relax(m, w, &mut heap);
                }
                continue;
            }
            for &(m, w) in &self.adj[k as usize] {
                relax(m, w, &mut heap);
            }
            if let Some(w) = to_t[k as usize] {
                relax(goal, w, &mut heap);
            }
        }
        if !g[goal as usize].is_finite() {
            return None;
        }
        let mut points = vec![t];
        let mut k = prev[goal as usize];
        while k != start {
            points.push(pos(k));
            k = prev[k as usize];
        }
        points.push(s);
        points.reverse();
        Some(Path { points, length: g[goal as usize] })
    }
}

fn dist(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::Domain;

    #[test]
    fn around_a_pillar() {
        let d = Domain::new(
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
            vec![vec![[4.0, 2.0], [6.0, 2.0], [6.0, 8.0], [4.0, 8.0]]],
        )
        .unwrap();
        let v = Visibility::new(d).unwrap();
        let p = PathPlanner::new(&v);
        let path = p.shortest_path([2.0, 5.0], [8.0, 5.0]).unwrap();
        // Around the pillar's top or bottom corners: 2·sqrt(2² + 3²) + 2.
        let want = 2.0 * (4.0f64 + 9.0).sqrt() + 2.0;
        assert!((path.length - want).abs() < 1e-12, "{path:?}");
        assert_eq!(path.points.len(), 4);
        // Straight when visible; grazing along a wall is allowed.
        assert_eq!(p.shortest_path([1.0, 1.0], [9.0, 1.0]).unwrap().points.len(), 2);
        assert!(segment_is_free(v.mesh(), [4.0, 0.5], [4.0, 2.0]));
        assert!(segment_is_free(v.mesh(), [4.0, 2.0], [6.0, 2.0]), "along a hole's edge");
        assert!(!segment_is_free(v.mesh(), [4.0, 2.0], [6.0, 8.0]), "through the hole");
        assert!(!segment_is_free(v.mesh(), [2.0, 0.0], [8.0, 4.0]));
        assert!(segment_is_free(v.mesh(), [2.0, 0.0], [4.0, 2.0]), "to a corner");
        assert!(p.shortest_path([5.0, 5.0], [1.0, 1.0]).is_none(), "start inside the hole");
    }
}
