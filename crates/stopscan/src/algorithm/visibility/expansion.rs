//! Triangular expansion (Bungiu, Hemmer, Hershberger, Huang, Kröller) over the constrained
//! triangulation, with exact predicates.
//!
//! From the triangle(s) around the viewpoint `q`, each triangle side is entered with a view
//! cone bounded by two rays from `q` through *input vertices* (the right bound `R` and the left
//! bound `L`). Entering a side, the opposite vertex `c` of the next triangle either lies inside
//! the cone (split into `(R, c)` and `(c, L)`), or on or beyond one bound (continue through the
//! one sub-side the cone still sees). Every decision is `orient(q, bound, c)` on input points,
//! so it is exact. At a domain edge the cone is clipped to the edge: an end is the edge's own
//! vertex when the bound passes through it (exact), otherwise the ray–edge intersection (the
//! only constructed points; they are output, never tested). A depth-first stack, right part
//! first, emits the pieces in counter-clockwise order; a gap between consecutive pieces lies on
//! one ray from `q` and is a window.

use super::{BoundaryPiece, VisibilityError, VisibilityRegion};
use crate::algorithm::triangulation::{Mesh, MeshLocation, NONE};
use crate::kernel::{Point, on_segment, orient_sign};

/// Reusable buffers for [`expand`].
#[derive(Debug, Default, Clone)]
pub struct Scratch {
    stack: Vec<(u32, u8, u32, u32)>,
    starts: Vec<(u32, u8, u32, u32)>,
    pieces: Vec<Piece>,
}

#[derive(Debug, Clone, Copy)]
struct Piece {
    from: Point,
    to: Point,
    edge_start: u32,
    full: bool,
}

/// Computes the visibility region of `q` into `out`.
///
/// # Errors
/// [`VisibilityError::Outside`] if `q` is not in the closed free space.
pub fn expand(
    mesh: &Mesh,
    q: Point,
    scratch: &mut Scratch,
    out: &mut VisibilityRegion,
) -> Result<(), VisibilityError> {
    out.viewpoint = q;
    out.polygon.clear();
    out.boundary.clear();
    scratch.pieces.clear();
    let tri = &mesh.tri;
    let pts = mesh.points();
    scratch.starts.clear();
    let starts = &mut scratch.starts;
    let push_start = |t: u32, k: u8, starts: &mut Vec<(u32, u8, u32, u32)>| {
        let v = tri[t as usize];
        starts.push((t, k, v[(k as usize + 1) % 3], v[(k as usize + 2) % 3]));
    };
    // Pieces along the domain edges through q itself (boundary queries), before/after.
    let mut lead: Option<Piece> = None;
    let mut tail: Option<Piece> = None;
    match mesh.locate(q) {
        MeshLocation::Outside => return Err(VisibilityError::Outside(q[0], q[1])),
        MeshLocation::Face(t) => {
            for k in [2, 0, 1] {
                push_start(t, k, starts);
            }
        }
        MeshLocation::InnerEdge(t, s) => {
            let u = mesh.nbr[t as usize][s as usize];
            let m = mesh.mirror[t as usize][s as usize];
            push_start(t, (s + 1) % 3, starts);
            push_start(t, (s + 2) % 3, starts);
            push_start(u, (m + 1) % 3, starts);
            push_start(u, (m + 2) % 3, starts);
        }
        MeshLocation::BoundaryEdge(t, s) => {
            let v = tri[t as usize];
            let (a, b) = (v[(s as usize + 1) % 3], v[(s as usize + 2) % 3]);
            lead = Some(Piece { from: q, to: pts[b as usize], edge_start: a, full: false });
            push_start(t, (s + 1) % 3, starts);
            push_start(t, (s + 2) % 3, starts);
            tail = Some(Piece { from: pts[a as usize], to: q, edge_start: a, full: false });
        }
        MeshLocation::Vertex(v) => {
            let (mut t, mut i) = mesh.vertex_fan[v as usize];
            let next = tri[t as usize][(i as usize + 1) % 3];
            lead = Some(Piece { from: q, to: pts[next as usize], edge_start: v, full: true });
            loop {
                push_start(t, i, starts);
                let side = (i as usize + 1) % 3;
                let u = mesh.nbr[t as usize][side];
                if u == NONE {
                    let prev = tri[t as usize][(i as usize + 2) % 3];
                    tail = Some(Piece {
                        from: pts[prev as usize],
                        to: q,
                        edge_start: prev,
                        full: true,
                    });
                    break;
                }
                t = u;
                i = tri[u as usize].iter().position(|&w| w == v).unwrap_or(0) as u8;
            }
        }
    }
    if let Some(p) = lead {
        scratch.pieces.push(p);
    }
    for k in 0..scratch.starts.len() {
        let s = scratch.starts[k];
        run(mesh, q, s, &mut scratch.stack, &mut scratch.pieces);
    }
    if let Some(p) = tail {
        scratch.pieces.push(p);
    }
    assemble(mesh, q, &scratch.pieces, out);
    Ok(())
}

/// The depth-first expansion from one start cone, appending pieces in CCW order.
#[inline]
fn run(
    mesh: &Mesh,
    q: Point,
    start: (u32, u8, u32, u32),
    stack: &mut Vec<(u32, u8, u32, u32)>,
    pieces: &mut Vec<Piece>,
) {
    let (tri, nbr, mirror, pts) = (&mesh.tri, &mesh.nbr, &mesh.mirror, mesh.points());
    stack.push(start);
    while let Some((t, k, r, l)) = stack.pop() {
        let tv = tri[t as usize];
        let n = nbr[t as usize][k as usize];
        if n == NONE {
            let (er, el) = (tv[(k as usize + 1) % 3], tv[(k as usize + 2) % 3]);
            let (pr, pl) = (pts[r as usize], pts[l as usize]);
            let (per, pel) = (pts[er as usize], pts[el as usize]);
            let full_r = r == er || orient_sign(q, pr, per) == 0;
            let full_l = l == el || orient_sign(q, pl, pel) == 0;
            let from = if full_r { per } else { ray_hit(q, pr, per, pel) };
            let to = if full_l { pel } else { ray_hit(q, pl, per, pel) };
            pieces.push(Piece { from, to, edge_start: er, full: full_r && full_l });
            continue;
        }
        let m = mirror[t as usize][k as usize] as usize;
        let c = tri[n as usize][m];
        let pc = pts[c as usize];
        let sr = orient_sign(q, pts[r as usize], pc);
        if sr <= 0 {
            // c on or right of R: only the left sub-side (c, e_l) is seen.
            stack.push((n, ((m + 2) % 3) as u8, r, l));
            continue;
        }
        let sl = orient_sign(q, pts[l as usize], pc);
        if sl >= 0 {
            // c on or left of L: only the right sub-side (e_r, c) is seen.
            stack.push((n, ((m + 1) % 3) as u8, r, l));
        } else {
            stack.push((n, ((m + 2) % 3) as u8, c, l));
            stack.push((n, ((m + 1) % 3) as u8, r, c));
        }
    }
}

/// Where the ray from `q` through `through` meets the line through `a` and `b`.
#[inline]
fn ray_hit(q: Point, through: Point, a: Point, b: Point) -> Point {
    let (dx, dy) = (through[0] - q[0], through[1] - q[1]);
    let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
    let den = dx * ey - dy * ex;
    let t = ((a[0] - q[0]) * ey - (a[1] - q[1]) * ex) / den;
    [q[0] + t * dx, q[1] + t * dy]
}

fn assemble(mesh: &Mesh, q: Point, pieces: &[Piece], out: &mut VisibilityRegion) {
    let n = pieces.len();
    let pts = mesh.points();
    for (i, p) in pieces.iter().enumerate() {
        let edge = mesh.edge_of(p.edge_start);
        if out.polygon.last() != Some(&p.from) {
            out.polygon.push(p.from);
        }
        if p.to != p.from {
            out.polygon.push(p.to);
        }
        out.boundary.push(if p.full {
            BoundaryPiece::Edge { from: p.from, to: p.to, edge }
        } else {
            BoundaryPiece::Partial { from: p.from, to: p.to, edge }
        });
        let np = &pieces[(i + 1) % n];
        if np.from != p.to {
            // Which ends of the gap are domain vertices (a piece ends exactly on its edge's
            // vertex or at a constructed point).
            let end = mesh.ring_next(p.edge_start);
            let va = (pts[end as usize] == p.to).then_some(end);
            let vb = (pts[np.edge_start as usize] == np.from).then_some(np.edge_start);
            gap(mesh, q, (p.to, va), (np.from, vb), out);
        }
    }
    if out.polygon.len() > 1 && out.polygon.first() == out.polygon.last() {
        out.polygon.pop();
    }
}

/// Labels the gap from `a` to `b` (on one ray from `q`) between two consecutive pieces.
///
/// Domain edges collinear with the ray are seen edge-on and never entered by the expansion, so
/// they show up inside gaps: those parts are edges, grazed, and only what is left between them
/// is a window. Without this an edge seen edge-on would be reported as a window whose far
/// side is outside the domain, and an explorer would try to look through it forever.
fn gap(
    mesh: &Mesh,
    q: Point,
    (a, va): (Point, Option<u32>),
    (b, vb): (Point, Option<u32>),
    out: &mut VisibilityRegion,
) {
    let pts = mesh.points();
    let edge_between = |v: u32, w: u32| {
        if mesh.ring_next(v) == w { mesh.edge_of(v) } else { mesh.edge_of(w) }
    };
    // Follow collinear domain edges from one end toward the other.
    let walk = |mut at: (Point, Option<u32>), goal: Point| {
        let mut steps = Vec::new();
        let mut last = None;
        while let Some(v) = at.1 {
            if at.0 == goal {
                break;
            }
            let next = [mesh.ring_next(v), mesh.ring_prev(v)].into_iter().find(|&w| {
                Some(w) != last
                    && pts[w as usize] != at.0
                    && on_segment(at.0, goal, pts[w as usize])
            });
            let Some(w) = next else { break };
            steps.push((at.0, pts[w as usize], edge_between(v, w)));
            last = Some(v);
            at = (pts[w as usize], Some(w));
        }
        (steps, at.0)
    };
    let (front, mid_a) = walk((a, va), b);
    let (back, mid_b) = if mid_a == b { (Vec::new(), b) } else { walk((b, vb), mid_a) };
    for &(from, to, edge) in &front {
        out.boundary.push(BoundaryPiece::Edge { from, to, edge });
    }
    if mid_a != mid_b {
        let d = |x: Point| (x[0] - q[0]).powi(2) + (x[1] - q[1]).powi(2);
        let (reflex, far) = if d(mid_a) <= d(mid_b) { (mid_a, mid_b) } else { (mid_b, mid_a) };
        out.boundary.push(BoundaryPiece::Window { from: mid_a, to: mid_b, reflex, far });
    }
    for &(to, from, edge) in back.iter().rev() {
        out.boundary.push(BoundaryPiece::Edge { from, to, edge });
    }
}
