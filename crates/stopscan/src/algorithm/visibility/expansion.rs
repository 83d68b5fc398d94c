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
use crate::algorithm::shortest_path::walk;
use crate::algorithm::triangulation::{Mesh, MeshLocation, NONE, WALL};
use crate::geometry::EdgeId;
use crate::kernel::{Point, orient_sign};

/// Reusable buffers for [`expand`].
#[derive(Debug, Default, Clone)]
pub struct Scratch {
    /// Whether a vertex was met exactly on a cone's bounding ray (only then can a gap hold
    /// domain edges seen edge-on, and gaps are walked).
    collinear: bool,
    stack: Vec<Cone>,
    starts: Vec<Cone>,
    pieces: Vec<Piece>,
    /// The vertices met along a gap ([`gap`]).
    stops: Vec<(Point, Option<u32>)>,
}

/// A triangle side `er → el` (counter-clockwise in the triangle being left), entered with the
/// view cone from the right bound `r` to the left bound `l` (input vertices, all four as
/// indices into [`Mesh::coords`]). It carries the side's entry of the triangle's [`Cell`]
/// (what lies across, and the far corner there), read when the cone was made, so a step's
/// two reads from memory (the far corner, the next cell) are both addressed by the cone.
#[derive(Debug, Clone, Copy)]
struct Cone {
    r: u32,
    l: u32,
    er: u32,
    el: u32,
    across: u32,
    opp: u32,
}

#[derive(Debug, Clone, Copy)]
struct Piece {
    from: Point,
    to: Point,
    /// The domain edge the piece lies on, with its ends' coordinates.
    edge: EdgeId,
    wall_from: Point,
    wall_to: Point,
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
    let push_start = |t: u32, k: u8, starts: &mut Vec<Cone>| {
        let (v, k) = (tri[t as usize], k as usize);
        let (er, el) =
            (mesh.coord_at[v[(k + 1) % 3] as usize], mesh.coord_at[v[(k + 2) % 3] as usize]);
        let cell = &mesh.cells[mesh.tri_cell[t as usize] as usize];
        starts.push(Cone { r: er, l: el, er, el, across: cell.adj[k], opp: cell.opp[k] });
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
            let edge = mesh.edge_of(a);
            let (wall_from, wall_to) = (pts[a as usize], pts[b as usize]);
            lead = Some(Piece { from: q, to: wall_to, edge, wall_from, wall_to, full: false });
            push_start(t, (s + 1) % 3, starts);
            push_start(t, (s + 2) % 3, starts);
            tail = Some(Piece { from: wall_from, to: q, edge, wall_from, wall_to, full: false });
        }
        MeshLocation::Vertex(v) => {
            let (mut t, mut i) = mesh.vertex_fan[v as usize];
            let next = tri[t as usize][(i as usize + 1) % 3];
            lead = Some(Piece {
                from: q,
                to: pts[next as usize],
                edge: mesh.edge_of(v),
                wall_from: q,
                wall_to: pts[next as usize],
                full: true,
            });
            loop {
                push_start(t, i, starts);
                let side = (i as usize + 1) % 3;
                let u = mesh.nbr[t as usize][side];
                if u == NONE {
                    let prev = tri[t as usize][(i as usize + 2) % 3];
                    tail = Some(Piece {
                        from: pts[prev as usize],
                        to: q,
                        edge: mesh.edge_of(prev),
                        wall_from: pts[prev as usize],
                        wall_to: q,
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
    scratch.collinear = false;
    for k in 0..scratch.starts.len() {
        let s = scratch.starts[k];
        scratch.collinear |= run(mesh, q, s, &mut scratch.stack, &mut scratch.pieces);
    }
    if let Some(p) = tail {
        scratch.pieces.push(p);
    }
    assemble(mesh, q, &scratch.pieces, scratch.collinear, &mut scratch.stops, out);
    Ok(())
}

/// The depth-first expansion from one start cone, appending pieces in CCW order. Returns
/// whether a vertex lay exactly on a bounding ray.
///
/// A step reads the far corner's coordinates and the next triangle's cell, both addressed by
/// the cone itself (the bounds' coordinates were read a step or more before: cached).
#[inline]
fn run(mesh: &Mesh, q: Point, start: Cone, stack: &mut Vec<Cone>, pieces: &mut Vec<Piece>) -> bool {
    let mut collinear = false;
    let (cells, coords) = (&mesh.cells, &mesh.coords);
    stack.push(start);
    while let Some(Cone { r, l, er, el, across, opp }) = stack.pop() {
        let (pr, pl) = (coords[r as usize], coords[l as usize]);
        if across & WALL != 0 {
            let edge = EdgeId { ring: across & !WALL, index: opp };
            let (per, pel) = (coords[er as usize], coords[el as usize]);
            let full_r = r == er || orient_sign(q, pr, per) == 0;
            let full_l = l == el || orient_sign(q, pl, pel) == 0;
            collinear |= (r != er && full_r) || (l != el && full_l);
            let from = if full_r { per } else { ray_hit(q, pr, per, pel) };
            let to = if full_l { pel } else { ray_hit(q, pl, per, pel) };
            let full = full_r && full_l;
            pieces.push(Piece { from, to, edge, wall_from: per, wall_to: pel, full });
            continue;
        }
        let (n, m) = ((across >> 2) as usize, (across & 3) as usize);
        let pc = coords[opp as usize];
        let cell = &cells[n];
        // The sub-sides (e_r, c) and (c, e_l): sides m + 1 and m + 2 of the next triangle.
        let (sub_r, sub_l) = ((m + 1) % 3, (m + 2) % 3);
        let right =
            |l: u32| Cone { r, l, er, el: opp, across: cell.adj[sub_r], opp: cell.opp[sub_r] };
        let left =
            |r: u32| Cone { r, l, er: opp, el, across: cell.adj[sub_l], opp: cell.opp[sub_l] };
        let sr = orient_sign(q, pr, pc);
        if sr == 0 {
            collinear = true;
        }
        if sr <= 0 {
            // c on or right of R: only the left sub-side (c, e_l) is seen.
            stack.push(left(r));
            continue;
        }
        let sl = orient_sign(q, pl, pc);
        collinear |= sl == 0;
        if sl >= 0 {
            // c on or left of L: only the right sub-side (e_r, c) is seen.
            stack.push(right(l));
        } else {
            stack.push(left(opp));
            stack.push(right(opp));
        }
    }
    collinear
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

fn assemble(
    mesh: &Mesh,
    q: Point,
    pieces: &[Piece],
    collinear: bool,
    stops: &mut Vec<(Point, Option<u32>)>,
    out: &mut VisibilityRegion,
) {
    let n = pieces.len();
    for (i, p) in pieces.iter().enumerate() {
        let edge = p.edge;
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
            let va = (p.wall_to == p.to).then(|| mesh.edge_end(p.edge));
            let vb = (np.wall_from == np.from).then(|| mesh.edge_start(np.edge));
            if collinear
                || va.zip(vb).is_some_and(|(v, w)| mesh.ring_next(w) == v || mesh.ring_next(v) == w)
            {
                gap(mesh, q, (p.to, va), (np.from, vb), stops, out);
            } else {
                window(q, p.to, np.from, out);
            }
        }
    }
    if out.polygon.len() > 1 && out.polygon.first() == out.polygon.last() {
        out.polygon.pop();
    }
}

/// Labels the gap from `a` to `b` (on one ray from `q`) between two consecutive pieces.
///
/// Domain edges collinear with the ray are seen edge-on and never entered by the expansion, so
/// they show up inside gaps: those parts are edges, grazed, and only the parts between them
/// are windows. Without this an edge seen edge-on would be reported as a window whose far
/// side is outside the domain, and an explorer would try to look through it forever. The
/// gap is walked through the mesh (exactly) to find the vertices on it.
fn gap(
    mesh: &Mesh,
    q: Point,
    (a, va): (Point, Option<u32>),
    (b, vb): (Point, Option<u32>),
    stops: &mut Vec<(Point, Option<u32>)>,
    out: &mut VisibilityRegion,
) {
    let pts = mesh.points();
    // Walk from an end that is a vertex: a constructed end may round to just outside.
    let backward = va.is_none() && vb.is_some();
    let (s, e) = if backward { ((b, vb), (a, va)) } else { ((a, va), (b, vb)) };
    stops.clear();
    stops.push(s);
    walk(mesh, s.0, e.0, |v| {
        if pts[v as usize] != e.0 {
            stops.push((pts[v as usize], Some(v)));
        }
    });
    stops.push(e);
    if backward {
        stops.reverse();
    }
    for s in stops.windows(2) {
        let ((p0, v0), (p1, v1)) = (s[0], s[1]);
        if p0 == p1 {
            continue;
        }
        match (v0, v1) {
            (Some(v), Some(w)) if mesh.ring_next(v) == w => {
                out.boundary.push(BoundaryPiece::Edge { from: p0, to: p1, edge: mesh.edge_of(v) });
            }
            (Some(v), Some(w)) if mesh.ring_next(w) == v => {
                out.boundary.push(BoundaryPiece::Edge { from: p0, to: p1, edge: mesh.edge_of(w) });
            }
            _ => window(q, p0, p1, out),
        }
    }
}

/// A window from `a` to `b` on a ray from `q`; the end nearer `q` is its reflex vertex.
fn window(q: Point, a: Point, b: Point, out: &mut VisibilityRegion) {
    let d = |x: Point| (x[0] - q[0]).powi(2) + (x[1] - q[1]).powi(2);
    let (reflex, far) = if d(a) <= d(b) { (a, b) } else { (b, a) };
    out.boundary.push(BoundaryPiece::Window { from: a, to: b, reflex, far });
}
