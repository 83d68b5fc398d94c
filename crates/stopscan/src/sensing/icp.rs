//! Point-to-line ICP: aligns a scan's returns to the walls already seen, so that odometry's
//! drift does not pile up from stop to stop.
//!
//! Each iteration pairs every return (placed by the current pose) with the nearest wall
//! segment within a gate that shrinks from iteration to iteration, when its foot falls on the
//! segment and the segment runs as the return's own surface does (the normal of the wall its
//! scan fitted through it, within [`NORMAL_AGREEMENT`]; a return at a corner pairs with
//! either wall), and solves the linearised least squares for a small rigid motion about the
//! robot: minimise `Σ w · (n · (R(dθ)(q − c) + c + d − a))²` (Huber weights `w`). Written here:
//! no maintained Rust crate does 2D point-to-line ICP.
//!
//! **Degenerate geometry.** The normal equations' matrix, with the rotation scaled by the
//! returns' spread about the robot so that all three axes are in metres, has an eigenvalue
//! near zero along a motion the walls do not constrain (along a featureless corridor; or a
//! shift coupled with a turn, as about the centre of a round pillar seen alone). Only
//! the well-constrained directions are corrected; along the others the pose stays where
//! odometry put it, and the result says so. A result with too few pairs, a large residual, an
//! implausible correction, or one that puts many returns beyond walls already mapped (a
//! beam cannot pass through a wall: [`WallMap::crossings`]) is rejected as a whole: odometry
//! is kept.
//!
//! **Refinement.** A kept alignment is refined against the same walls fitted finer
//! ([`refine`]): lines fitted at three σ through walls traced from a grid tilt across its
//! steps, and place scans centimetres off; the coarse walls find the place, the fine ones
//! settle it.

use crate::geometry::segment_distance;
use crate::kernel::{Point, orient_sign};
use crate::protocol::laser::{Pose, wrap};

/// ICP's settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct IcpParams {
    /// The pairing gate at the first iteration, metres.
    pub gate_start: f64,
    /// The smallest gate, metres (reached by shrinking 30% per iteration).
    pub gate_end: f64,
    /// The Huber threshold, metres: residuals beyond it weigh less.
    pub huber: f64,
    /// At most this many iterations.
    pub max_iterations: usize,
    /// Fewest pairs for a correction.
    pub min_pairs: usize,
    /// A direction is degenerate when its eigenvalue is below this share of the largest.
    pub degenerate_ratio: f64,
    /// The largest correction accepted: metres.
    pub max_shift: f64,
    /// The largest correction accepted: radians.
    pub max_turn: f64,
    /// The largest root-mean-square residual accepted, metres.
    pub max_rms: f64,
    /// The range noise the residuals are weighed by, metres (at least 1 cm is used).
    pub sigma: f64,
    /// How far around the guess [`align`] searches, at most, when its alignment sees through
    /// walls in part, metres; 0 searches nowhere (matches to a single stop's walls, where
    /// another place along them is found as readily).
    #[serde(default = "default_search_span")]
    pub search_span: f64,
}

fn default_search_span() -> f64 {
    SEARCH_SPAN
}

impl Default for IcpParams {
    fn default() -> Self {
        Self {
            gate_start: 1.5,
            gate_end: 0.15,
            huber: 0.05,
            max_iterations: 60,
            min_pairs: 20,
            degenerate_ratio: 0.005,
            max_shift: 1.0,
            max_turn: 20f64.to_radians(),
            max_rms: 0.1,
            sigma: 0.02,
            search_span: SEARCH_SPAN,
        }
    }
}

/// What ICP did.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Alignment {
    /// The pose it started from (odometry).
    pub guess: Pose,
    /// The pose it settled on (the guess when it fell back).
    pub pose: Pose,
    /// Pairs of return and wall at the end.
    pub pairs: usize,
    /// Their root-mean-square residual, metres.
    pub rms: f64,
    /// Iterations run.
    pub iterations: usize,
    /// Whether the steps fell below the convergence threshold.
    pub converged: bool,
    /// The unconstrained direction of motion (a unit vector in the map frame), when the walls
    /// left one: the pose was not corrected along it.
    pub degenerate: Option<Point>,
    /// Whether the whole correction was rejected and odometry kept (too few pairs, a large
    /// residual or an implausible correction), and why.
    pub fallback: Option<Fallback>,
    /// How many returns, placed where ICP settled (before any fallback), lie beyond a wall
    /// of the map ([`WallMap::crossings`]).
    #[serde(default)]
    pub crossings: usize,
}

impl Alignment {
    /// The correction applied: how far the pose moved, metres, and turned, radians.
    pub fn correction(&self) -> (f64, f64) {
        (
            (self.pose.x - self.guess.x).hypot(self.pose.y - self.guess.y),
            wrap(self.pose.theta - self.guess.theta),
        )
    }
}

/// Why ICP kept odometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Fallback {
    /// Fewer pairs than [`IcpParams::min_pairs`] (nothing known yet, or nothing near).
    TooFewPairs,
    /// The residual stayed above [`IcpParams::max_rms`].
    PoorFit,
    /// The correction went beyond [`IcpParams::max_shift`] or [`IcpParams::max_turn`].
    Implausible,
    /// Placed where ICP settled, more returns would lie beyond walls of the map than on them
    /// ([`MAX_CROSSINGS`]): the scan slid onto a wall pattern that is not where it stands.
    SeesThroughWalls,
}

/// The walls seen so far, indexed by a uniform grid for nearest-segment queries.
#[derive(Debug, Clone, Default)]
pub struct WallMap {
    segments: Vec<[Point; 2]>,
    /// Whether each segment is a wall seen (not a bridge across a gap between returns, which
    /// may be a door): only walls stop a beam in [`WallMap::crossings`].
    solid: Vec<bool>,
    /// The stop each segment was seen from ([`NO_OWNER`] when none was given): an alignment
    /// to the map is an alignment to the stops whose walls it paired with.
    owner: Vec<u32>,
    cells: rustc_hash::FxHashMap<(i64, i64), Vec<u32>>,
}

/// The owner of a segment added without one ([`WallMap::extend`], [`WallMap::extend_bridges`]).
pub const NO_OWNER: u32 = u32::MAX;

/// A return pairs only with a wall whose normal and its own surface's normal (from the wall
/// its scan fitted through it) agree to within this cosine, 30°. Without it, returns on a
/// shelf's side paired with a line another stop had fitted across the shelf's corner from
/// far away: on the depot, the second stop's alignment settled 0.13 to 0.18 m off along
/// the hall, where nothing else constrained it. On the 20,215 stops of the 600 raw-scan
/// runs (replayed through the mapper alone, same poses and odometry), the stops beyond 0.1 m
/// fell from 12.0% to 10.4%, and with [`MIN_WALL_RETURNS`](super::ingest::MIN_WALL_RETURNS)
/// to 9.1% (those beyond 0.5 m from 466 to 148). From 20° to 45° it did about as well.
pub const NORMAL_AGREEMENT: f64 = 0.866;

/// The wall map's cell side, metres.
const CELL: f64 = 1.0;

fn cell_of(p: Point) -> (i64, i64) {
    ((p[0] / CELL).floor() as i64, (p[1] / CELL).floor() as i64)
}

/// Calls `f(cell, leave)` for the grid's cells along the segment `a → b`, in order, where
/// `leave` is the segment's parameter (0 at `a`, 1 at `b`) at which it leaves the cell
/// (Amanatides and Woo's traversal), until `f` returns true.
fn walk_cells(a: Point, b: Point, mut f: impl FnMut((i64, i64), f64) -> bool) {
    let (mut i, mut j) = cell_of(a);
    let end = cell_of(b);
    let d = [b[0] - a[0], b[1] - a[1]];
    // The ray parameter at the next cell border per axis.
    let next = |c: i64, o: f64, v: f64| {
        if v > 0.0 {
            ((c + 1) as f64 * CELL - o) / v
        } else if v < 0.0 {
            (c as f64 * CELL - o) / v
        } else {
            f64::INFINITY
        }
    };
    let (mut tx, mut ty) = (next(i, a[0], d[0]), next(j, a[1], d[1]));
    let (sx, sy) = (CELL / d[0].abs(), CELL / d[1].abs());
    let steps = (end.0 - i).abs() + (end.1 - j).abs();
    for _ in 0..=steps {
        if f((i, j), tx.min(ty).min(1.0)) || (i, j) == end {
            return;
        }
        if tx < ty {
            i += d[0].signum() as i64;
            tx += sx;
        } else {
            j += d[1].signum() as i64;
            ty += sy;
        }
    }
}

impl WallMap {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// How many segments it holds.
    pub fn len(&self) -> usize {
        self.segments.len()
    }

    /// Whether it holds none.
    pub fn is_empty(&self) -> bool {
        self.segments.is_empty()
    }

    /// Adds wall segments (degenerate and non-finite ones are skipped).
    pub fn extend(&mut self, walls: &[[Point; 2]]) {
        self.push(walls, true, NO_OWNER);
    }

    /// Adds bridges: segments across gaps between returns on one wall line, evidence of the
    /// line for matching but not of a wall (a beam may pass through one).
    pub fn extend_bridges(&mut self, bridges: &[[Point; 2]]) {
        self.push(bridges, false, NO_OWNER);
    }

    fn push(&mut self, walls: &[[Point; 2]], solid: bool, owner: u32) {
        for w in walls {
            let len = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
            if !(len.is_finite() && len > 1e-9) {
                continue;
            }
            let id = self.segments.len() as u32;
            self.segments.push(*w);
            self.solid.push(solid);
            self.owner.push(owner);
            let (a, b) = (cell_of(w[0]), cell_of(w[1]));
            // Every cell the segment's box covers (walls are short, from one scan each).
            for i in a.0.min(b.0)..=a.0.max(b.0) {
                for j in a.1.min(b.1)..=a.1.max(b.1) {
                    if segment_distance(
                        [(i as f64 + 0.5) * CELL, (j as f64 + 0.5) * CELL],
                        w[0],
                        w[1],
                    ) <= CELL
                    {
                        self.cells.entry((i, j)).or_default().push(id);
                    }
                }
            }
        }
    }

    /// Adds the parts of `walls` and `bridges` ([`WallMap::extend_bridges`]) the map does not
    /// hold yet: each is cut into pieces of at most `piece` metres, and a piece is skipped
    /// when a segment of the same orientation runs within `tol` of its middle. A wall seen
    /// again from a pose that is a little off would otherwise stand in the map twice, and
    /// later scans would align to either copy. The pieces added are `owner`'s
    /// ([`information_by_owner`]).
    pub fn extend_unseen(
        &mut self,
        walls: &[[Point; 2]],
        bridges: &[[Point; 2]],
        piece: f64,
        tol: f64,
        owner: u32,
    ) {
        let (walls, bridges) = (self.unseen(walls, piece, tol), self.unseen(bridges, piece, tol));
        self.push(&walls, true, owner);
        self.push(&bridges, false, owner);
    }

    /// The pieces of `walls` (at most `piece` long) that no segment of the map holds.
    fn unseen(&self, walls: &[[Point; 2]], piece: f64, tol: f64) -> Vec<[Point; 2]> {
        let mut fresh = Vec::new();
        for w in walls {
            let (dx, dy) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
            let len = dx.hypot(dy);
            if !(len.is_finite() && len > 1e-9) {
                continue;
            }
            let k = (len / piece).ceil().max(1.0) as usize;
            let at = |t: f64| [w[0][0] + t * dx, w[0][1] + t * dy];
            for i in 0..k {
                let (a, b) = (at(i as f64 / k as f64), at((i + 1) as f64 / k as f64));
                let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
                if !self.holds(m, [dx / len, dy / len], tol) {
                    fresh.push([a, b]);
                }
            }
        }
        fresh
    }

    /// Whether a segment running along `dir` (a unit vector) passes within `tol` of `m`.
    fn holds(&self, m: Point, dir: Point, tol: f64) -> bool {
        let (lo, hi) = (cell_of([m[0] - tol, m[1] - tol]), cell_of([m[0] + tol, m[1] + tol]));
        (lo.0..=hi.0).any(|i| {
            (lo.1..=hi.1).any(|j| {
                self.cells.get(&(i, j)).is_some_and(|ids| {
                    ids.iter().any(|&id| {
                        let [a, b] = self.segments[id as usize];
                        let (ex, ey) = (b[0] - a[0], b[1] - a[1]);
                        let l = ex.hypot(ey);
                        (ex * dir[0] + ey * dir[1]) / l > 0.9 && segment_distance(m, a, b) <= tol
                    })
                })
            })
        })
    }

    /// How many of `points` (returns in the map frame, seen from `eye`) the map says cannot
    /// be: the beam from `eye` to the return, short of its last `margin` metres, crosses a
    /// wall of the map, short of the wall's last `margin` metres at either end (a fitted wall
    /// may overhang its corner a little). Bridges stop no beam. A scan placed where it was
    /// taken sees through no wall; one slid onto a neighbouring wall pattern (the next shelf,
    /// a door's other jamb) or turned by a few degrees sees through many.
    pub fn crossings(
        &self,
        eye: Point,
        points: impl IntoIterator<Item = Point>,
        margin: f64,
    ) -> usize {
        points
            .into_iter()
            .filter(|&q| {
                let (dx, dy) = (q[0] - eye[0], q[1] - eye[1]);
                let r = dx.hypot(dy);
                r > margin && {
                    let k = 1.0 - margin / r;
                    self.crosses_wall(eye, [eye[0] + k * dx, eye[1] + k * dy], margin)
                }
            })
            .count()
    }

    /// Whether the segment `a → b` properly crosses a wall of the map (not within `margin` of
    /// the wall's ends).
    fn crosses_wall(&self, a: Point, b: Point, margin: f64) -> bool {
        let mut crossed = false;
        walk_cells(a, b, |cell, _| {
            crossed = self.cells.get(&cell).is_some_and(|ids| {
                ids.iter().any(|&id| self.solid[id as usize] && self.wall_crosses(id, a, b, margin))
            });
            crossed
        });
        crossed
    }

    /// Where a beam from `eye` toward `to` first meets a wall of the map (bridges stop no
    /// beam), short of `to`: the point and the wall's unit normal on the side the beam came
    /// from.
    pub fn first_hit(&self, eye: Point, to: Point) -> Option<(Point, Point)> {
        let d = [to[0] - eye[0], to[1] - eye[1]];
        let mut best: Option<(f64, Point)> = None;
        walk_cells(eye, to, |cell, leave| {
            for &id in self.cells.get(&cell).into_iter().flatten() {
                if !self.solid[id as usize] {
                    continue;
                }
                let [p, q] = self.segments[id as usize];
                let e = [q[0] - p[0], q[1] - p[1]];
                let den = d[0] * e[1] - d[1] * e[0];
                if den == 0.0 {
                    continue;
                }
                let w = [p[0] - eye[0], p[1] - eye[1]];
                let (t, u) = ((w[0] * e[1] - w[1] * e[0]) / den, (w[0] * d[1] - w[1] * d[0]) / den);
                if (0.0..=1.0).contains(&t)
                    && (0.0..=1.0).contains(&u)
                    && best.is_none_or(|b| t < b.0)
                {
                    let l = e[0].hypot(e[1]);
                    let n = if den > 0.0 { [-e[1] / l, e[0] / l] } else { [e[1] / l, -e[0] / l] };
                    best = Some((t, n));
                }
            }
            // A wall met in this cell may cross the beam beyond it; one met before the
            // beam leaves the cell is the first.
            best.is_some_and(|b| b.0 <= leave)
        });
        best.map(|(t, n)| ([eye[0] + t * d[0], eye[1] + t * d[1]], n))
    }

    /// Whether wall `id`, short of `margin` at either end, properly crosses `a → b`.
    fn wall_crosses(&self, id: u32, a: Point, b: Point, margin: f64) -> bool {
        let [p, q] = self.segments[id as usize];
        let (ex, ey) = (q[0] - p[0], q[1] - p[1]);
        let l = ex.hypot(ey);
        if l <= 2.0 * margin {
            return false;
        }
        let (ux, uy) = (ex / l * margin, ey / l * margin);
        let (p, q) = ([p[0] + ux, p[1] + uy], [q[0] - ux, q[1] - uy]);
        orient_sign(a, b, p) * orient_sign(a, b, q) < 0
            && orient_sign(p, q, a) * orient_sign(p, q, b) < 0
    }

    /// The nearest segment to `q` within `gate` whose foot from `q` falls inside it, whose
    /// free side faces the scanner at `eye` (a return lies on a face the scanner sees: the
    /// back face of a thin wall is never its match), and whose normal agrees with `normal`
    /// (the return's own surface, when known) within [`NORMAL_AGREEMENT`]: its unit normal
    /// and a point on it.
    fn nearest(
        &self,
        q: Point,
        eye: Point,
        gate: f64,
        normal: Option<Point>,
    ) -> Option<(Point, Point, f64, u32)> {
        let (lo, hi) = (cell_of([q[0] - gate, q[1] - gate]), cell_of([q[0] + gate, q[1] + gate]));
        let mut best: Option<(Point, Point, f64, u32)> = None;
        for i in lo.0..=hi.0 {
            for j in lo.1..=hi.1 {
                let Some(ids) = self.cells.get(&(i, j)) else { continue };
                for &id in ids {
                    let [a, b] = self.segments[id as usize];
                    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                    // Walls run counter-clockwise around the scan that saw them: free space
                    // on their left.
                    if dx * (eye[1] - a[1]) - dy * (eye[0] - a[0]) <= 0.0 {
                        continue;
                    }
                    let l2 = dx * dx + dy * dy;
                    let t = ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / l2;
                    if !(0.0..=1.0).contains(&t) {
                        continue;
                    }
                    let l = l2.sqrt();
                    let n = [-dy / l, dx / l];
                    if normal.is_some_and(|m| (m[0] * n[0] + m[1] * n[1]).abs() < NORMAL_AGREEMENT)
                    {
                        continue;
                    }
                    let d = ((q[0] - a[0]) * n[0] + (q[1] - a[1]) * n[1]).abs();
                    if d <= gate && best.is_none_or(|b| d < b.2) {
                        best = Some((n, a, d, id));
                    }
                }
            }
        }
        best
    }
}

/// How far odometry's pose may be off, one standard deviation: metres per axis and radians.
/// ICP weighs its pairs against this prior, so that along a direction the walls barely
/// constrain, odometry prevails.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Prior {
    /// Position, metres per axis.
    pub position: f64,
    /// Heading, radians.
    pub heading: f64,
}

/// The heading offsets of the restarts tried when an alignment from the guess is not
/// convincing (it fell back or did not converge), radians: a large heading error can pair
/// returns with the wrong walls, and a start a few degrees off may find the right ones.
const RESTART_TURNS: [f64; 2] = [0.1, -0.1];

/// A correction beyond this many of odometry's standard deviations is suspect: ICP may have
/// slid to a neighbouring wall pattern (a door's jambs, a shelf). Restarts are tried, and
/// one within the prior wins over one beyond it.
const SURPRISE: f64 = 4.0;

/// Aligns `points` (returns in the scanner's frame, with their surfaces' `normals` in the
/// same frame where known: [`Ingested::normals`](super::ingest::Ingested::normals); an empty
/// slice pairs every return with any wall) to `map`, starting from `guess` (the
/// scanner's pose by odometry, in the map frame), weighed against odometry's `prior` when
/// given. When the alignment from the guess falls back, does not converge, corrects the
/// guess by more than four of the prior's standard deviations, or puts many returns beyond
/// walls ([`SUSPECT_CROSSINGS`]), it is tried again
/// from the guess turned by ±0.1 rad and shifted by 1.5 standard deviations along each axis
/// (the prior stays on the guess), and the best is kept: one that did not fall back and is
/// within the prior, then one that sees through walls in part (the fewest per pair first),
/// then odometry (a fallback), then a surprising one (when every start
/// ends beyond the prior, they agree); among equals, one that converged, then the smallest
/// residual. On 1,000 office scan pairs with seed 2, the shifted starts and the surprise
/// raised convergence from 98.5% to 99.0%: three alignments had slid 0.8 m to a
/// neighbouring door's jambs, eight times the prior's deviation.
///
/// When the first alignment sees through walls in part and no restart did better, the
/// guess itself may be metres off (a long drive whose heading drifted), and a wide gate
/// slid the scan onto the next aisle's shelves. Starts on a grid around the guess, out to
/// three of the prior's deviations (at most [`IcpParams::search_span`], in at most four steps each way
/// and steps of at least a third of [`IcpParams::gate_start`]), each with a gate of one step
/// (at least twice [`IcpParams::gate_end`]), look for an alignment that does not; one found
/// within the square is kept even beyond the prior. An alignment beyond the prior that sees
/// through walls in part is refused, and odometry kept ([`Fallback::SeesThroughWalls`]).
pub fn align(
    points: &[Point],
    normals: &[Option<Point>],
    guess: &Pose,
    prior: Option<Prior>,
    map: &WallMap,
    params: &IcpParams,
) -> Alignment {
    // How many of odometry's standard deviations the correction is (0 without a prior).
    let surprise = |a: &Alignment| {
        prior.map_or(0.0, |p| {
            let (shift, turn) = a.correction();
            (shift / p.position.max(1e-9)).max(turn.abs() / p.heading.max(1e-12))
        })
    };
    // The gate starts wide enough for odometry's error at three standard deviations.
    let gate = prior.map_or(params.gate_start, |p| {
        params.gate_start.max(3.0 * p.position + 3.0 * p.heading * 10.0).min(3.0)
    });
    let first = align_from(points, normals, guess, guess, prior, [map, map], params, gate);
    if first.fallback.is_none()
        && first.converged
        && surprise(&first) <= SURPRISE
        && !first.sees_through_walls_in_part()
    {
        return first;
    }
    let rank = |a: &Alignment| {
        let class = match (a.fallback.is_some(), surprise(a) > SURPRISE) {
            (false, false) if a.sees_through_walls_in_part() => 1,
            (false, false) => 0,
            (true, _) => 2,
            (false, true) => 3,
        };
        let against = if class == 1 { -a.support() } else { 0.0 };
        (class, against, !a.converged, a.rms)
    };
    let better = |a: &Alignment, b: &Alignment| {
        rank(a).partial_cmp(&rank(b)) == Some(std::cmp::Ordering::Less)
    };
    let mut best = first;
    let shifts = prior.map_or(0.0, |p| 1.5 * p.position);
    let starts =
        RESTART_TURNS.iter().map(|&turn| Pose { theta: wrap(guess.theta + turn), ..*guess }).chain(
            [[1.0, 0.0], [-1.0, 0.0], [0.0, 1.0], [0.0, -1.0]]
                .into_iter()
                .filter(|_| shifts > 0.0)
                .map(|[dx, dy]| Pose {
                    x: guess.x + shifts * dx,
                    y: guess.y + shifts * dy,
                    ..*guess
                }),
        );
    for start in starts {
        let a = align_from(points, normals, guess, &start, prior, [map, map], params, gate);
        if better(&a, &best) {
            best = a;
        }
    }
    let Some(p) = prior.filter(|_| {
        params.search_span > 0.0 && first.sees_through_walls_in_part() && rank(&best).0 > 0
    }) else {
        return odometry_unless_trusted(best, surprise(&best) > SURPRISE);
    };
    let span = (3.0 * (p.position + p.heading * 10.0)).min(params.search_span);
    let step = (span / SEARCH_STEPS as f64).max(params.gate_start / 3.0);
    let n = (span / step).floor() as i32;
    // A start lies within `step / √2` of any place in the square: a gate of one step finds
    // the walls from there, where a wider one lets the scan slide again.
    let reach = step.max(2.0 * params.gate_end);
    // The restarts' best competes when it did not fall back and is within the prior.
    let mut best_inside = rank(&best).0 <= 1;
    for i in -n..=n {
        for j in -n..=n {
            if i == 0 && j == 0 {
                continue;
            }
            let start = Pose {
                x: guess.x + f64::from(i) * step,
                y: guess.y + f64::from(j) * step,
                ..*guess
            };
            let a = align_from(points, normals, guess, &start, prior, [map, map], params, reach);
            // Within the searched square an alignment is not surprising: the search is for
            // guesses off by more than the prior says. Among those that did not fall back,
            // the one the most returns support wins.
            let (shift, _) = a.correction();
            let inside = a.fallback.is_none() && shift <= span * std::f64::consts::SQRT_2;
            if inside && (!best_inside || a.support() > best.support()) {
                (best, best_inside) = (a, true);
            }
        }
    }
    let surprising = !best_inside && surprise(&best) > SURPRISE;
    odometry_unless_trusted(best, surprising)
}

/// How far a refinement ([`refine`]) may move an alignment, metres: it corrects the tilt of
/// lines fitted through a grid's steps, centimetres, not a wrong match.
pub const REFINE_SHIFT: f64 = 0.15;

/// How far a refinement may turn an alignment, radians (about 1.4°).
pub const REFINE_TURN: f64 = 0.025;

/// The pairing gate a refinement starts from, and ends at, metres.
const REFINE_GATE: [f64; 2] = [0.2, 0.05];

/// `coarse`, an alignment of `points` by [`align`] to the walls `walls`, refined against
/// `fine` (the same stops' walls fitted at [`IngestParams::fine_split`](super::ingest::IngestParams::fine_split),
/// with the returns' `normals` from that fit): ICP again with a gate narrowing from 0.2 m to
/// 5 cm and no prior, from `coarse`'s pose when it was kept, or from odometry's (its guess)
/// when it was implausible. The result is returned when it converged without falling back
/// (at least [`IcpParams::min_pairs`] pairs, a residual within [`IcpParams::max_rms`]) within
/// [`REFINE_SHIFT`] and [`REFINE_TURN`] of where it started; its crossings are counted
/// against `walls`, since a fine piece a few returns long stops no beam
/// ([`WallMap::crossings`] spares the ends of every wall).
///
/// Why: walls traced from an occupancy grid have steps of a cell. A line fitted at three σ
/// cuts through them, tilted toward the side its scan saw more of, and a scan aligned to such
/// lines is placed off by as much: depot's second stop (`cost_aware`, seed 11, 13 m from
/// the first) by 0.098 m with σ = 2 cm, by 0.003 m refined. Matched to the fine pieces alone
/// (from odometry, with the wide gate), alignments after long drives fell back or slid more
/// often (the README's raw-scan section). Refined from a coarse alignment they start within
/// centimetres. Coarse walls of stops placed by refinement no longer agree with each other
/// to the centimetre, and a scan can settle where their offsets agree, beyond what odometry
/// allows: refining from odometry then found the place (on the 720 runs of the grid, ICP's
/// fallbacks 156 → 18; 94 before refinement).
pub fn refine(
    points: &[Point],
    normals: &[Option<Point>],
    coarse: &Alignment,
    [fine, walls]: [&WallMap; 2],
    params: &IcpParams,
) -> Option<Alignment> {
    // An alignment the coarse walls put beyond what odometry allows is refined from
    // odometry's pose instead: coarse walls of stops placed by refinement need not agree
    // with each other to the centimetre, and a scan can settle where their offsets agree.
    let start = match coarse.fallback {
        None => coarse.pose,
        Some(Fallback::Implausible) => coarse.guess,
        Some(_) => return None,
    };
    if fine.is_empty() {
        return None;
    }
    let p = IcpParams {
        gate_start: REFINE_GATE[0],
        gate_end: REFINE_GATE[1],
        max_shift: REFINE_SHIFT,
        max_turn: REFINE_TURN,
        ..*params
    };
    // The fine pieces stop no beam: at the ends of pieces a few returns long, the test
    // for returns beyond walls spares all of them.
    let none = WallMap::new();
    let mut a = align_from(points, normals, &start, &start, None, [fine, &none], &p, p.gate_start);
    if a.fallback.is_some() || !a.converged {
        return None;
    }
    let placing = a.pose.placing();
    let margin = CROSSING_MARGIN.max(5.0 * params.sigma);
    a.crossings = walls.crossings(a.pose.at(), points.iter().map(|&q| placing.apply(q)), margin);
    Some(Alignment { guess: coarse.guess, degenerate: a.degenerate.or(coarse.degenerate), ..a })
}

/// `a`, or odometry's pose when `a` is beyond the prior and sees through walls in part: two
/// signs that the scan slid onto a wall pattern that is not where it stands.
fn odometry_unless_trusted(mut a: Alignment, surprising: bool) -> Alignment {
    if surprising && a.fallback.is_none() && a.sees_through_walls_in_part() {
        a.fallback = Some(Fallback::SeesThroughWalls);
        a.pose = a.guess;
    }
    a
}

/// An alignment whose returns beyond mapped walls number at least [`MIN_CROSSINGS`] and this
/// share of its pairs is suspect (though not rejected below [`MAX_CROSSINGS`]): restarts and a
/// search around the guess are tried, and an alignment without them wins.
///
/// On the 600 raw-scan runs of the README (seeds 1 to 40), every alignment that moved a stop
/// from within 0.3 m of the truth to 1 m or more beyond it, but one, had 0.19 to 0.38
/// crossings per pair.
pub const SUSPECT_CROSSINGS: f64 = 0.1;

/// How far around the guess the search for an alignment that does not see through walls
/// reaches by default, metres at most ([`IcpParams::search_span`]), and in how many steps
/// each way.
pub const SEARCH_SPAN: f64 = 4.0;
const SEARCH_STEPS: usize = 4;

impl Alignment {
    /// How many returns support it: its pairs less twice the returns it puts beyond mapped
    /// walls (each contradicts it).
    pub fn support(&self) -> f64 {
        self.pairs as f64 - 2.0 * self.crossings as f64
    }

    /// Whether it puts many returns beyond mapped walls ([`SUSPECT_CROSSINGS`]).
    pub fn sees_through_walls_in_part(&self) -> bool {
        self.crossings >= MIN_CROSSINGS
            && self.crossings as f64 > SUSPECT_CROSSINGS * self.pairs as f64
    }
}

/// [`align`] from `start` (the prior, when given, stays on `guess`), with the pairing gate
/// starting at `gate`: returns paired with the walls of `map`, and counted beyond the walls
/// of `stop` ([`WallMap::crossings`]; the same map, but for a refinement).
#[allow(clippy::too_many_arguments)]
fn align_from(
    points: &[Point],
    normals: &[Option<Point>],
    guess: &Pose,
    start: &Pose,
    prior: Option<Prior>,
    [map, stop]: [&WallMap; 2],
    params: &IcpParams,
    gate: f64,
) -> Alignment {
    let mut pose = *start;
    let mut gate = gate;
    let mut out = Alignment {
        guess: *guess,
        pose: *guess,
        pairs: 0,
        rms: 0.0,
        iterations: 0,
        converged: false,
        degenerate: None,
        fallback: None,
        crossings: 0,
    };
    let lever = lever(points);
    let mut free: Option<[f64; 3]> = None;
    for it in 0..params.max_iterations {
        out.iterations = it + 1;
        let (mut h, mut g, pairs, sq) =
            normal_equations(points, normals, &pose, map, gate, params, lever);
        out.pairs = pairs;
        out.rms = if pairs > 0 { (sq / pairs as f64).sqrt() } else { 0.0 };
        if pairs < params.min_pairs {
            out.fallback = Some(Fallback::TooFewPairs);
            out.pose = *guess;
            return out;
        }
        if let Some(p) = prior {
            // Odometry's prior pulls toward the guess.
            let off = [guess.x - pose.x, guess.y - pose.y, wrap(guess.theta - pose.theta) * lever];
            let sd = [p.position, p.position, p.heading * lever];
            for (k, (o, d)) in off.iter().zip(sd).enumerate() {
                let w = 1.0 / d.max(1e-6).powi(2);
                h[k][k] += w;
                g[k] += w * o;
            }
        }
        let (step, weak) = solve(h, g, params.degenerate_ratio);
        // Report the free motion's shift (the motion odometry keeps).
        out.degenerate = weak.map(shift_of);
        free = weak;
        let (dx, dy, dth) = (step[0], step[1], step[2] / lever);
        // Rotate about the scanner's position, then shift.
        pose = Pose { x: pose.x + dx, y: pose.y + dy, theta: wrap(pose.theta + dth) };
        let small = dx.hypot(dy) < 1e-5 && dth.abs() < 1e-6;
        if small && gate <= params.gate_end {
            out.converged = true;
            break;
        }
        gate = (gate * 0.7).max(params.gate_end);
    }
    // Along the motion the walls leave free, the pose is odometry's: early iterations, with
    // a wide gate, may have pushed it there on pairs that were wrong. That motion may couple
    // a shift with a turn (a round pillar seen alone leaves the turn about its centre free),
    // so the whole correction's part along it is undone, turn included: undoing only its
    // shift would move the scanner off the walls along the turn the walls had fixed.
    if let Some(v) = free {
        let off = [pose.x - guess.x, pose.y - guess.y, wrap(pose.theta - guess.theta) * lever];
        let along = off[0] * v[0] + off[1] * v[1] + off[2] * v[2];
        pose.x -= along * v[0];
        pose.y -= along * v[1];
        pose.theta = wrap(pose.theta - along * v[2] / lever);
    }
    out.pose = pose;
    let margin = CROSSING_MARGIN.max(5.0 * params.sigma);
    let placing = pose.placing();
    out.crossings = stop.crossings(pose.at(), points.iter().map(|&q| placing.apply(q)), margin);
    let (shift, turn) = out.correction();
    if shift > params.max_shift || turn.abs() > params.max_turn {
        out.fallback = Some(Fallback::Implausible);
    } else if out.rms > params.max_rms {
        out.fallback = Some(Fallback::PoorFit);
    } else if out.crossings >= MIN_CROSSINGS
        && out.crossings as f64 > MAX_CROSSINGS * out.pairs as f64
    {
        out.fallback = Some(Fallback::SeesThroughWalls);
    }
    if out.fallback.is_some() {
        out.pose = *guess;
    }
    out
}

/// The returns' spread about the scanner (at least a metre): the lever that puts rotation in
/// metres.
fn lever(points: &[Point]) -> f64 {
    (points.iter().map(|p| p[0] * p[0] + p[1] * p[1]).sum::<f64>() / points.len().max(1) as f64)
        .sqrt()
        .max(1.0)
}

/// What an alignment of a scan not taken yet would rest on: [`predict`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Prediction {
    /// The returns predicted to pair with walls of the map.
    pub pairs: usize,
    /// The direction of motion those pairs would leave unconstrained, as
    /// [`Alignment::degenerate`], if any.
    pub degenerate: Option<Point>,
    /// The smallest eigenvalue of the normal equations' matrix as a share of the largest.
    pub weakest: f64,
}

impl Prediction {
    /// Whether ICP is predicted to place the scan: at least [`PREDICTION_MARGIN`] times
    /// [`IcpParams::min_pairs`] pairs, and the weakest direction at least that many times
    /// [`IcpParams::degenerate_ratio`] of the strongest. The margin stands for what the
    /// prediction cannot see: walls not mapped yet hide some of the walls predicted, and
    /// noise and dropouts thin the returns.
    pub fn places(&self, params: &IcpParams) -> bool {
        self.places_by(params, PREDICTION_MARGIN)
    }

    /// [`places`](Self::places) with another margin.
    pub fn places_by(&self, params: &IcpParams, margin: f64) -> bool {
        self.pairs as f64 >= margin * params.min_pairs as f64
            && self.weakest > margin * params.degenerate_ratio
    }
}

/// [`Prediction::places`]'s margin. On 54 raw-scan runs (the office, depot and warehouse;
/// `cost_aware`, `depth_first` and `explore_lite`; seeds 1 to 6), with a margin of 1 the
/// stops predicted not to be placed held 20 of the 49 alignments that were degenerate or
/// fell back, and the first stop beyond 0.1 m of 8 of the 20 runs that had one; with 4,
/// 31 and 15 (51 of 1,709 stops predicted not placed); with 6, 37 and 18 (72 stops).
pub const PREDICTION_MARGIN: f64 = 4.0;

/// Predicts how well a scan from `at` could be aligned to `map`: `beams` beams evenly
/// around, out to `range` metres, each returning from the first wall of the map it meets
/// (walls not mapped yet are not known to be there), paired and weighed as [`align`] pairs
/// returns, with the same test for a direction the pairs leave free. A robot that must stop
/// where its scan cannot be placed along some direction (the far end of a featureless
/// corridor, or of a hall it has seen only one side of) can stop on the way, where one can.
pub fn predict(
    map: &WallMap,
    occluders: &WallMap,
    at: Point,
    beams: usize,
    range: f64,
    params: &IcpParams,
) -> Prediction {
    let mut points = Vec::new();
    let mut normals = Vec::new();
    let dist = |q: Point| (q[0] - at[0]).hypot(q[1] - at[1]);
    for k in 0..beams {
        let a = std::f64::consts::TAU * k as f64 / beams as f64;
        let to = [at[0] + range * a.cos(), at[1] + range * a.sin()];
        if let Some((q, n)) = map.first_hit(at, to) {
            // A surface seen too sparsely for a wall, or a short gap between returns, may
            // hide the wall from here.
            if occluders.first_hit(at, q).is_some_and(|(o, _)| dist(o) < dist(q) - OCCLUDED) {
                continue;
            }
            points.push([q[0] - at[0], q[1] - at[1]]);
            normals.push(Some(n));
        }
    }
    let pose = Pose { x: at[0], y: at[1], theta: 0.0 };
    let lever = lever(&points);
    let (h, _, pairs, _) =
        normal_equations(&points, &normals, &pose, map, params.gate_end, params, lever);
    let eigen = jacobi_eigen(h);
    let vals = eigen.0;
    let (_, weak) = solve_eigen(eigen, [0.0; 3], params.degenerate_ratio);
    let top = vals.iter().copied().fold(0.0, f64::max);
    let weakest =
        if top > 0.0 { vals.iter().copied().fold(f64::INFINITY, f64::min) / top } else { 0.0 };
    Prediction { pairs, degenerate: weak.map(shift_of), weakest }
}

/// A predicted return is hidden when an occluder ([`predict`]) stands this much nearer
/// than its wall, metres.
pub const OCCLUDED: f64 = 0.1;

/// The shift of a free motion `(dx, dy, dθ·lever)` (mostly a shift: [`solve`]), as a unit
/// vector.
fn shift_of(v: [f64; 3]) -> Point {
    let t = v[0].hypot(v[1]);
    [v[0] / t, v[1] / t]
}

/// A beam must pass this far through a wall, metres, and a wall's ends are spared this much,
/// before the beam is said to cross it (at least five range deviations).
const CROSSING_MARGIN: f64 = 0.1;

/// An alignment is rejected when the returns it puts beyond walls of the map outnumber its
/// pairs times this ([`Fallback::SeesThroughWalls`])...
///
/// On 150 raw-scan runs (the office, depot and warehouse, five strategies, seeds 1 to 10),
/// while every earlier stop stood within 0.15 m of the truth, correct alignments had at most
/// 0.2 crossings per pair, and the three that slid 0.8 to 2 m from a good guess had 1.0 to
/// 1.2: a scan that mostly sees new space pairs its few returns near the map with the
/// wrong walls.
pub const MAX_CROSSINGS: f64 = 0.5;

/// ...and at least this many returns do: a handful of grazing beams prove nothing.
pub const MIN_CROSSINGS: usize = 20;

/// How sure an alignment of `points` (with `normals`, as in [`align`]) to `map` at `pose` is:
/// the information matrix (the normal equations' matrix, in `(x, y, θ)` of the map frame
/// with θ about the scanner) of the pairs within the final gate. Near zero along a direction the walls leave free.
pub fn information(
    points: &[Point],
    normals: &[Option<Point>],
    pose: &Pose,
    map: &WallMap,
    params: &IcpParams,
) -> [[f64; 3]; 3] {
    normal_equations(points, normals, pose, map, params.gate_end, params, 1.0).0
}

/// The information of the alignment of `points` to `map` at `pose`, as [`information`], split
/// by the stop whose walls each pair is with ([`WallMap::extend_unseen`]'s owner): for each
/// owner, its matrix and its pairs, in the order of owners. Summed over the owners it is
/// [`information`].
pub fn information_by_owner(
    points: &[Point],
    normals: &[Option<Point>],
    pose: &Pose,
    map: &WallMap,
    params: &IcpParams,
) -> Vec<(u32, [[f64; 3]; 3], usize)> {
    let mut by = std::collections::BTreeMap::<u32, ([[f64; 3]; 3], usize)>::new();
    for_each_pair(points, normals, pose, map, params.gate_end, params, 1.0, |owner, w, jac, _| {
        let (h, n) = by.entry(owner).or_insert(([[0.0; 3]; 3], 0));
        add_outer(h, w, &jac);
        *n += 1;
    });
    by.into_iter().map(|(owner, (h, n))| (owner, h, n)).collect()
}

/// The normal equations of the point-to-line residuals at `pose` (pairs within `gate`, Huber
/// weights, in units of the range noise), with the rotation scaled by `lever`: the matrix,
/// the right-hand side, the pairs and the sum of squared residuals.
fn normal_equations(
    points: &[Point],
    normals: &[Option<Point>],
    pose: &Pose,
    map: &WallMap,
    gate: f64,
    params: &IcpParams,
    lever: f64,
) -> ([[f64; 3]; 3], [f64; 3], usize, f64) {
    let mut h = [[0.0; 3]; 3];
    let mut g = [0.0; 3];
    let (mut pairs, mut sq) = (0usize, 0.0);
    for_each_pair(points, normals, pose, map, gate, params, lever, |_, w, jac, r| {
        add_outer(&mut h, w, &jac);
        for (gi, ji) in g.iter_mut().zip(jac) {
            *gi -= w * ji * r;
        }
        pairs += 1;
        sq += r * r;
    });
    (h, g, pairs, sq)
}

/// `h += w · jac jacᵀ`.
fn add_outer(h: &mut [[f64; 3]; 3], w: f64, jac: &[f64; 3]) {
    for (i, hi) in h.iter_mut().enumerate() {
        for (j, hij) in hi.iter_mut().enumerate() {
            *hij += w * jac[i] * jac[j];
        }
    }
}

/// Calls `f(owner, weight, jacobian, residual)` for every return of `points`, placed at
/// `pose`, that has a wall of `map` within `gate` ([`WallMap::nearest`]): the Huber weight
/// in units of the range noise, and the derivative of the point-to-line residual in
/// `(dx, dy, dθ·lever)` at zero.
fn for_each_pair(
    points: &[Point],
    normals: &[Option<Point>],
    pose: &Pose,
    map: &WallMap,
    gate: f64,
    params: &IcpParams,
    lever: f64,
    mut f: impl FnMut(u32, f64, [f64; 3], f64),
) {
    let c = pose.at();
    let placing = pose.placing();
    let w2 = 1.0 / params.sigma.max(0.01).powi(2);
    for (i, p) in points.iter().enumerate() {
        let q = placing.apply(*p);
        let normal = normals.get(i).copied().flatten().map(|m| placing.turn(m));
        let Some((n, a, _, id)) = map.nearest(q, c, gate, normal) else { continue };
        let r = n[0] * (q[0] - a[0]) + n[1] * (q[1] - a[1]);
        let w = w2 * if r.abs() <= params.huber { 1.0 } else { params.huber / r.abs() };
        let jac = [n[0], n[1], (n[0] * -(q[1] - c[1]) + n[1] * (q[0] - c[0])) / lever];
        f(map.owner[id as usize], w, jac, r);
    }
}

/// The step `h⁻¹ g` in the eigen-directions whose eigenvalue is above `ratio` of the
/// largest, and an unconstrained direction mostly a shift, if there is one, as
/// `(dx, dy, dθ·lever)` (unit).
fn solve(h: [[f64; 3]; 3], g: [f64; 3], ratio: f64) -> ([f64; 3], Option<[f64; 3]>) {
    solve_eigen(jacobi_eigen(h), g, ratio)
}

/// [`solve`] on the matrix's eigen-decomposition ([`jacobi_eigen`]).
fn solve_eigen(
    (vals, vecs): ([f64; 3], [[f64; 3]; 3]),
    g: [f64; 3],
    ratio: f64,
) -> ([f64; 3], Option<[f64; 3]>) {
    let top = vals.iter().copied().fold(0.0, f64::max);
    let mut step = [0.0; 3];
    let mut weak = None;
    for (k, &val) in vals.iter().enumerate() {
        let v = [vecs[0][k], vecs[1][k], vecs[2][k]];
        if val <= ratio * top {
            if v[0].hypot(v[1]) > 0.5 {
                weak = Some(v);
            }
            continue;
        }
        let coef = (v[0] * g[0] + v[1] * g[1] + v[2] * g[2]) / val;
        for (s, vi) in step.iter_mut().zip(v) {
            *s += coef * vi;
        }
    }
    (step, weak)
}

/// Eigenvalues and eigenvectors (as columns) of a symmetric 3×3 matrix, by cyclic Jacobi
/// rotations.
fn jacobi_eigen(mut a: [[f64; 3]; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for _ in 0..50 {
        let off = a[0][1].abs() + a[0][2].abs() + a[1][2].abs();
        let scale = a[0][0].abs() + a[1][1].abs() + a[2][2].abs();
        if off <= 1e-15 * scale.max(f64::MIN_POSITIVE) {
            break;
        }
        for (p, q) in [(0, 1), (0, 2), (1, 2)] {
            if a[p][q].abs() < f64::MIN_POSITIVE {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            let t = theta.signum() / (theta.abs() + (theta * theta + 1.0).sqrt());
            let t = if theta == 0.0 { 1.0 } else { t };
            let c = 1.0 / (t * t + 1.0).sqrt();
            let s = t * c;
            // A ← Jᵀ A J with J the rotation in the (p, q) plane.
            for row in &mut a {
                let (akp, akq) = (row[p], row[q]);
                row[p] = c * akp - s * akq;
                row[q] = s * akp + c * akq;
            }
            let (rp, rq) = (a[p], a[q]);
            for k in 0..3 {
                a[p][k] = c * rp[k] - s * rq[k];
                a[q][k] = s * rp[k] + c * rq[k];
            }
            for row in &mut v {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - s * vq;
                row[q] = s * vp + c * vq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Returns of a scanner at `truth` on the walls of a room (axis-aligned rectangle with a
    /// pillar), in the scanner's frame: every `step` metres along each wall it sees.
    fn room_walls() -> Vec<[Point; 2]> {
        vec![
            [[0.0, 0.0], [8.0, 0.0]],
            [[8.0, 0.0], [8.0, 5.0]],
            [[8.0, 5.0], [0.0, 5.0]],
            [[0.0, 5.0], [0.0, 0.0]],
            // The pillar's faces, with free space on their left as a scan gives them.
            [[4.0, 2.0], [3.0, 2.0]],
            [[4.0, 3.0], [4.0, 2.0]],
        ]
    }

    fn sample(walls: &[[Point; 2]], truth: &Pose, step: f64) -> Vec<Point> {
        let inv = truth.inverse();
        // The faces the scanner sees: it stands on their free (left) side.
        walls
            .iter()
            .filter(|w| {
                let (a, b) = (w[0], w[1]);
                (b[0] - a[0]) * (truth.y - a[1]) - (b[1] - a[1]) * (truth.x - a[0]) > 0.0
            })
            .flat_map(|w| {
                let len = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                let k = (len / step).ceil() as usize;
                (0..=k).map(move |i| {
                    let t = i as f64 / k as f64;
                    [w[0][0] + t * (w[1][0] - w[0][0]), w[0][1] + t * (w[1][1] - w[0][1])]
                })
            })
            .map(|p| inv.apply(p))
            .collect()
    }

    #[test]
    fn an_alignment_is_split_among_the_stops_whose_walls_it_pairs_with() {
        // Stop 3 saw the room's outer walls, stop 7 the pillar; the scanner sees both.
        let walls = room_walls();
        let (outer, pillar) = walls.split_at(4);
        let mut map = WallMap::new();
        map.extend_unseen(outer, &[], 0.5, 0.3, 3);
        map.extend_unseen(pillar, &[], 0.5, 0.3, 7);
        let truth = Pose { x: 6.0, y: 3.5, theta: 0.2 };
        let pts = sample(&walls, &truth, 0.05);
        let params = IcpParams::default();
        let split = information_by_owner(&pts, &[], &truth, &map, &params);
        assert_eq!(split.iter().map(|s| s.0).collect::<Vec<_>>(), vec![3, 7]);
        // Each owner's pairs are the returns on its walls (from the definition: a return
        // within the final gate of one of the owner's faces that the scanner sees, its foot
        // inside the face; `end` more than `end` from the face's ends, as a return exactly at
        // a corner may round off either face).
        let on = |ws: &[[Point; 2]], end: f64| {
            pts.iter()
                .map(|&p| truth.apply(p))
                .filter(|&q| {
                    ws.iter().any(|w| {
                        let (a, b) = (w[0], w[1]);
                        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
                        let t = ((q[0] - a[0]) * dx + (q[1] - a[1]) * dy) / (dx * dx + dy * dy);
                        let l = dx.hypot(dy);
                        dx * (truth.y - a[1]) - dy * (truth.x - a[0]) > 0.0
                            && t * l >= end
                            && (1.0 - t) * l >= end
                            && segment_distance(q, a, b) <= params.gate_end
                    })
                })
                .count()
        };
        for (k, ws) in [(0, outer), (1, pillar)] {
            let (inside, all) = (on(ws, 1e-6), on(ws, -1e-6));
            assert!(inside > 0 && inside <= split[k].2 && split[k].2 <= all, "{k}: {split:?}");
        }
        // The matrices add up to the whole alignment's information.
        let whole = information(&pts, &[], &truth, &map, &params);
        for (i, row) in whole.iter().enumerate() {
            for (j, &w) in row.iter().enumerate() {
                let sum = split[0].1[i][j] + split[1].1[i][j];
                assert!((sum - w).abs() <= 1e-9 * w.abs().max(1.0));
            }
        }
        // Walls added without an owner are nobody's.
        let mut plain = WallMap::new();
        plain.extend(&walls);
        let split = information_by_owner(&pts, &[], &truth, &plain, &params);
        assert_eq!(split.iter().map(|s| s.0).collect::<Vec<_>>(), vec![NO_OWNER]);
    }

    #[test]
    fn the_eigen_decomposition_rebuilds_the_matrix() {
        let a = [[4.0, 1.0, 0.5], [1.0, 3.0, -0.25], [0.5, -0.25, 0.01]];
        let (l, v) = jacobi_eigen(a);
        for i in 0..3 {
            for j in 0..3 {
                let r: f64 = (0..3).map(|k| v[i][k] * l[k] * v[j][k]).sum();
                assert!((r - a[i][j]).abs() < 1e-12, "{i}{j}");
            }
        }
    }

    #[test]
    fn a_room_is_aligned_from_a_wrong_guess() {
        let mut map = WallMap::new();
        map.extend(&room_walls());
        let truth = Pose { x: 2.0, y: 1.5, theta: 0.4 };
        let pts = sample(&room_walls(), &truth, 0.05);
        let guess = Pose { x: 2.25, y: 1.35, theta: 0.4 + 8f64.to_radians() };
        let a = align(&pts, &[], &guess, None, &map, &IcpParams::default());
        assert!(a.converged && a.fallback.is_none() && a.degenerate.is_none(), "{a:?}");
        assert!((a.pose.x - truth.x).abs() < 1e-6 && (a.pose.y - truth.y).abs() < 1e-6, "{a:?}");
        assert!((a.pose.theta - truth.theta).abs() < 1e-7, "{a:?}");
        let (shift, turn) = a.correction();
        assert!((shift - 0.25f64.hypot(0.15)).abs() < 1e-6);
        assert!((turn + 8f64.to_radians()).abs() < 1e-7);
    }

    #[test]
    fn a_surprising_alignment_is_kept_when_every_start_agrees() {
        // Odometry claims 2 cm and 1°; the guess is 0.25 m and 5° off, so the right
        // alignment is a dozen deviations away. Every start finds it: it is kept. (The scan
        // is cast, so that no return lies behind the pillar: beyond the prior, an alignment
        // that sees through walls in part is refused.)
        let mut map = WallMap::new();
        map.extend(&room_walls());
        let truth = Pose { x: 2.0, y: 1.5, theta: 0.4 };
        let pts = ray_cast(&room_walls(), &truth, 720, 20.0);
        let guess = Pose { x: 2.2, y: 1.35, theta: 0.4 + 5f64.to_radians() };
        let prior = Prior { position: 0.02, heading: 1f64.to_radians() };
        let a = align(&pts, &[], &guess, Some(prior), &map, &IcpParams::default());
        assert!(a.converged && a.fallback.is_none(), "{a:?}");
        assert!((a.pose.x - truth.x).abs() < 0.01 && (a.pose.y - truth.y).abs() < 0.01, "{a:?}");
        assert!((a.pose.theta - truth.theta).abs() < 0.2f64.to_radians(), "{a:?}");
    }

    #[test]
    fn a_featureless_corridor_keeps_odometry_along_it() {
        let walls = vec![[[-50.0, 0.0], [50.0, 0.0]], [[50.0, 2.0], [-50.0, 2.0]]];
        let mut map = WallMap::new();
        map.extend(&walls);
        let truth = Pose { x: 0.0, y: 1.0, theta: 0.0 };
        // Only what a 10 m scanner sees.
        let near: Vec<[Point; 2]> = vec![[[-10.0, 0.0], [10.0, 0.0]], [[10.0, 2.0], [-10.0, 2.0]]];
        let pts = sample(&near, &truth, 0.05);
        let guess = Pose { x: 0.3, y: 1.2, theta: 0.05 };
        let a = align(&pts, &[], &guess, None, &map, &IcpParams::default());
        let d = a.degenerate.expect("the corridor leaves x free");
        assert!(d[0].abs() > 0.99, "{d:?}");
        // Across the corridor and in heading, corrected; along it, odometry's x kept.
        assert!((a.pose.y - 1.0).abs() < 1e-4 && a.pose.theta.abs() < 1e-4, "{a:?}");
        assert!((a.pose.x - 0.3).abs() < 0.05, "{a:?}");
    }

    #[test]
    fn a_round_pillar_keeps_odometry_along_the_turn_about_its_centre() {
        // Seen alone, a round pillar cannot tell the scanner's turn about its centre: the
        // free motion is a shift across the sight line coupled with a turn. The distance to
        // the pillar is still corrected, and the returns land on it.
        let (c, r, n) = ([5.0, 0.0], 1.0, 64);
        let ring: Vec<Point> = (0..n)
            .map(|i| {
                // Clockwise: the free side of each face is outside the pillar.
                let a = -std::f64::consts::TAU * f64::from(i) / f64::from(n);
                [c[0] + r * a.cos(), c[1] + r * a.sin()]
            })
            .collect();
        let walls: Vec<[Point; 2]> =
            (0..ring.len()).map(|i| [ring[i], ring[(i + 1) % n as usize]]).collect();
        let mut map = WallMap::new();
        map.extend(&walls);
        let truth = Pose { x: 0.0, y: 0.0, theta: 0.0 };
        let pts = sample(&walls, &truth, 0.02);
        // Odometry: turned 0.03 rad about the centre (the free motion), 0.1 m too near, and
        // turned 0.05 rad more about the scanner (half free, half seen).
        let d = 0.03f64;
        let (s, co) = d.sin_cos();
        let guess = Pose { x: c[0] - 4.9 * co, y: c[1] - 4.9 * s, theta: d + 0.05 };
        let a = align(&pts, &[], &guess, None, &map, &IcpParams::default());
        assert!(a.degenerate.is_some() && a.fallback.is_none(), "{a:?}");
        // From the definition: every return, placed where ICP put the scanner, lies on the
        // pillar's faces (within the faces' own sag from the circle, and the solver's rest).
        let worst = pts
            .iter()
            .map(|&p| {
                let q = a.pose.apply(p);
                walls.iter().map(|w| segment_distance(q, w[0], w[1])).fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        assert!(worst < 0.005, "returns {worst} m off the pillar: {a:?}");
        // The distance to the centre is corrected, the scanner faces the centre as it did,
        // and the turn about the centre is between odometry's two turns.
        let dist = (a.pose.x - c[0]).hypot(a.pose.y - c[1]);
        assert!((dist - 5.0).abs() < 0.005, "{dist}: {a:?}");
        let bearing = (c[1] - a.pose.y).atan2(c[0] - a.pose.x);
        assert!((a.pose.theta - bearing).abs() < 0.002, "{bearing}: {a:?}");
        assert!(bearing > d - 0.002 && bearing < d + 0.052, "{bearing}: {a:?}");
    }

    #[test]
    fn a_return_pairs_only_with_a_wall_that_runs_as_its_surface_does() {
        // A line fitted across a corner from far away runs at 45°; the returns lie on a face
        // across the view (normal along x), where the line passes.
        let mut map = WallMap::new();
        map.extend(&[[[5.0, -0.5], [6.0, 0.5]]]);
        let pts: Vec<Point> = (-2..=2).map(|i| [5.5, 0.05 * f64::from(i)]).collect();
        let pairs = |normal: Option<Point>| {
            let normals = vec![normal; pts.len()];
            information_by_owner(&pts, &normals, &Pose::default(), &map, &IcpParams::default())
                .iter()
                .map(|o| o.2)
                .sum::<usize>()
        };
        // Without normals every return pairs (each within the final gate of the line).
        let gate = IcpParams::default().gate_end;
        let near = pts.iter().filter(|q| segment_distance(**q, [5.0, -0.5], [6.0, 0.5]) <= gate);
        assert_eq!(pairs(None), near.count());
        assert_eq!(pairs(None), 5);
        // Across the view, 45° from the line: none. Within 30° of it (either way round): all.
        assert_eq!(pairs(Some([1.0, 0.0])), 0);
        let (s, c) = 20f64.to_radians().sin_cos();
        let n = [std::f64::consts::FRAC_1_SQRT_2, -std::f64::consts::FRAC_1_SQRT_2];
        assert_eq!(pairs(Some([c * n[0] - s * n[1], s * n[0] + c * n[1]])), 5);
        assert_eq!(pairs(Some([-n[0], -n[1]])), 5);
        let (s, c) = 31f64.to_radians().sin_cos();
        assert_eq!(pairs(Some([c * n[0] - s * n[1], s * n[0] + c * n[1]])), 0);
        // The normals turn with the pose: seen by a scanner turned by 90°, the returns and
        // their normals are given turned back (the line's normal, turned back, is across it).
        let turned = Pose { theta: std::f64::consts::FRAC_PI_2, ..Pose::default() };
        let local: Vec<Point> = pts.iter().map(|q| [q[1], -q[0]]).collect();
        let normals = vec![Some([n[1], -n[0]]); local.len()];
        let n = information_by_owner(&local, &normals, &turned, &map, &IcpParams::default());
        assert_eq!(n.iter().map(|o| o.2).sum::<usize>(), 5);
    }

    #[test]
    fn nothing_known_keeps_odometry() {
        let pts = sample(&room_walls(), &Pose::default(), 0.1);
        let guess = Pose { x: 1.0, y: 1.0, theta: 0.0 };
        let a = align(&pts, &[], &guess, None, &WallMap::new(), &IcpParams::default());
        assert_eq!(a.fallback, Some(Fallback::TooFewPairs));
        assert_eq!(a.pose, guess);
    }

    /// Whether `c → d` properly crosses `a → b`, from the definition in floating point: each
    /// segment's ends lie strictly on opposite sides of the other's line.
    fn cross_brute(a: Point, b: Point, c: Point, d: Point) -> bool {
        let side = |p: Point, q: Point, r: Point| {
            ((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0])).signum()
        };
        side(a, b, c) * side(a, b, d) < 0.0 && side(c, d, a) * side(c, d, b) < 0.0
    }

    /// [`WallMap::crossings`] from its definition, every wall against every beam, no grid.
    fn crossings_brute(walls: &[([Point; 2], bool)], eye: Point, pts: &[Point], m: f64) -> usize {
        let shorten = |a: Point, b: Point, by_a: f64, by_b: f64| {
            let l = (b[0] - a[0]).hypot(b[1] - a[1]);
            let u = [(b[0] - a[0]) / l, (b[1] - a[1]) / l];
            [[a[0] + by_a * u[0], a[1] + by_a * u[1]], [b[0] - by_b * u[0], b[1] - by_b * u[1]]]
        };
        pts.iter()
            .filter(|&&q| {
                let r = (q[0] - eye[0]).hypot(q[1] - eye[1]);
                r > m && {
                    let [a, b] = shorten(eye, q, 0.0, m);
                    walls.iter().any(|&(w, solid)| {
                        let l = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                        solid && l > 2.0 * m && {
                            let [c, d] = shorten(w[0], w[1], m, m);
                            cross_brute(a, b, c, d)
                        }
                    })
                }
            })
            .count()
    }

    /// A hall of 30 × 20 m with eight shelves 1 m deep and 7 m long, 3.5 m apart, starting
    /// at y = 3, 6 or 9 m in turn: aisles that look alike but for where their shelves end.
    /// Walls run with free space on their left.
    fn shelves() -> Vec<[Point; 2]> {
        let mut walls = vec![
            [[0.0, 0.0], [30.0, 0.0]],
            [[30.0, 0.0], [30.0, 20.0]],
            [[30.0, 20.0], [0.0, 20.0]],
            [[0.0, 20.0], [0.0, 0.0]],
        ];
        for k in 0..8 {
            let (x0, x1) = (1.0 + 3.5 * f64::from(k), 2.0 + 3.5 * f64::from(k));
            let y0 = 3.0 + 3.0 * f64::from(k % 3);
            let y1 = y0 + 7.0;
            walls.extend([
                [[x0, y0], [x0, y1]],
                [[x0, y1], [x1, y1]],
                [[x1, y1], [x1, y0]],
                [[x1, y0], [x0, y0]],
            ]);
        }
        walls
    }

    /// The returns of a lidar at `truth` (`beams` per turn, `range` metres), in its frame:
    /// each beam's nearest wall crossing, from the definition.
    fn ray_cast(walls: &[[Point; 2]], truth: &Pose, beams: usize, range: f64) -> Vec<Point> {
        (0..beams)
            .filter_map(|i| {
                let rel = std::f64::consts::TAU * i as f64 / beams as f64;
                let (dy, dx) = (truth.theta + rel).sin_cos();
                let hit = walls
                    .iter()
                    .filter_map(|w| {
                        let (ex, ey) = (w[1][0] - w[0][0], w[1][1] - w[0][1]);
                        let den = dx * ey - dy * ex;
                        if den.abs() < 1e-12 {
                            return None;
                        }
                        let (ox, oy) = (w[0][0] - truth.x, w[0][1] - truth.y);
                        let t = (ox * ey - oy * ex) / den;
                        let u = (ox * dy - oy * dx) / den;
                        (t > 0.0 && (0.0..=1.0).contains(&u)).then_some(t)
                    })
                    .fold(f64::INFINITY, f64::min);
                (hit <= range).then(|| [hit * rel.cos(), hit * rel.sin()])
            })
            .collect()
    }

    #[test]
    fn a_guess_an_aisle_off_is_searched_around_until_no_return_sees_through_a_shelf() {
        // After a long drive the guess may be metres off, and a gate wide enough for that
        // slides the scan onto the next aisle: its shelves' faces fit, but beams that passed
        // a shelf's end now pass through a shelf. Two metres off, the restarts find the
        // right aisle; two and a half, beyond four of the prior's deviations, only the
        // search around the guess does.
        let walls = shelves();
        let mut map = WallMap::new();
        map.extend(&walls);
        let prior = Prior { position: 0.6, heading: 0.03 };
        // As the mapper allows after such a drive: three deviations' worth of correction.
        let params = IcpParams { max_shift: 4.5, max_turn: 0.1, ..IcpParams::default() };
        for (x, y, theta) in [(10.25, 10.0, 0.3), (17.25, 5.0, 2.0)] {
            let truth = Pose { x, y, theta };
            let pts = ray_cast(&walls, &truth, 720, 20.0);
            let off = |a: &Alignment| (a.pose.x - x).hypot(a.pose.y - y);
            for dx in [-2.5, -2.0, 2.0, 2.5] {
                for dy in [-1.0, 0.0, 1.0] {
                    let guess = Pose { x: x + dx, y: y + dy, theta: theta + 0.02 };
                    let a = align(&pts, &[], &guess, Some(prior), &map, &params);
                    assert!(
                        off(&a) < 0.05 && a.fallback.is_none(),
                        "{truth:?} from {guess:?}: {a:?}"
                    );
                    assert_eq!(a.crossings, 0, "{a:?}");
                    let restarts = IcpParams { search_span: 0.0, ..params };
                    let restarted = align(&pts, &[], &guess, Some(prior), &map, &restarts);
                    if f64::abs(dx) > 2.2 {
                        assert!(off(&restarted) > 1.0, "{guess:?}: {restarted:?}");
                    }
                }
            }
        }
    }

    /// The room without its pillar, and its wall map: every return sampled in it is seen.
    fn bare_room() -> (Vec<[Point; 2]>, WallMap) {
        let room = room_walls()[..4].to_vec();
        let mut map = WallMap::new();
        map.extend(&room);
        (room, map)
    }

    #[test]
    fn a_scan_where_it_was_taken_sees_through_no_wall() {
        let (room, map) = bare_room();
        let truth = Pose { x: 2.0, y: 1.5, theta: 0.4 };
        let pts = sample(&room, &truth, 0.05);
        let at = |p: &Pose| pts.iter().map(|&q| p.apply(q)).collect::<Vec<_>>();
        assert_eq!(map.crossings(truth.at(), at(&truth), 0.1), 0);
        // Slid 0.4 m to the right: the returns of the right wall (5 m long, every 5 cm) lie
        // beyond it; turned by 4°, the far corners' returns do.
        let slid = Pose { x: 2.4, ..truth };
        let n = map.crossings(slid.at(), at(&slid), 0.1);
        assert!(n >= 90, "{n}");
        let turned = Pose { theta: truth.theta + 4f64.to_radians(), ..truth };
        assert!(map.crossings(turned.at(), at(&turned), 0.1) > 0);
    }

    #[test]
    fn an_alignment_that_sees_through_walls_keeps_odometry() {
        // The room is mapped; the scan holds its walls (every 0.2 m) and returns 4 m beyond
        // its right wall, which no scan taken inside the room could have. Beyond-wall returns
        // past half the pairs reject the alignment; fewer leave it.
        let (room, map) = bare_room();
        let truth = Pose { x: 2.0, y: 1.5, theta: 0.0 };
        let inside = sample(&room, &truth, 0.2);
        let guess = Pose { x: 2.1, y: 1.45, theta: 0.02 };
        let beyond = |n: usize| {
            (0..n).map(move |i| [10.0, -1.2 + 3.6 * i as f64 / n as f64]).collect::<Vec<_>>()
        };
        let a = align(&inside, &[], &guess, None, &map, &IcpParams::default());
        assert!(a.fallback.is_none() && a.crossings == 0, "{a:?}");
        let few = [inside.clone(), beyond(a.pairs / 4)].concat();
        let b = align(&few, &[], &guess, None, &map, &IcpParams::default());
        assert!(b.fallback.is_none() && b.crossings == a.pairs / 4, "{b:?}");
        assert!((b.pose.x - truth.x).abs() < 1e-6 && (b.pose.y - truth.y).abs() < 1e-6, "{b:?}");
        let many = [inside, beyond(a.pairs)].concat();
        let c = align(&many, &[], &guess, None, &map, &IcpParams::default());
        assert_eq!(c.fallback, Some(Fallback::SeesThroughWalls), "{c:?}");
        assert_eq!(c.pose, guess);
        assert!(c.crossings as f64 > MAX_CROSSINGS * c.pairs as f64, "{c:?}");
    }

    #[test]
    fn a_bridge_stops_no_beam() {
        // A return 1 m beyond a line seen as a gap (a door): no crossing; as a wall, one.
        let line = [[[5.0, -2.0], [5.0, 2.0]]];
        let mut bridged = WallMap::new();
        bridged.extend_bridges(&line);
        assert_eq!(bridged.crossings([0.0, 0.0], [[6.0, 0.0]], 0.1), 0);
        let mut walled = WallMap::new();
        walled.extend(&line);
        assert_eq!(walled.crossings([0.0, 0.0], [[6.0, 0.0]], 0.1), 1);
        // A return on the wall itself, or within the margin beyond it, crosses nothing; so
        // does a beam past the wall's end within the margin.
        assert_eq!(walled.crossings([0.0, 0.0], [[5.0, 0.0], [5.08, 0.0]], 0.1), 0);
        assert_eq!(walled.crossings([0.0, 0.0], [[6.0, 2.34]], 0.1), 0);
        assert_eq!(walled.crossings([0.0, 0.0], [[6.0, 2.2]], 0.1), 1);
    }

    /// A room's walls as a scan from inside gives them (free space on their left), and a
    /// corridor's two long walls.
    fn closed_room() -> Vec<[Point; 2]> {
        vec![
            [[0.0, 0.0], [8.0, 0.0]],
            [[8.0, 0.0], [8.0, 5.0]],
            [[8.0, 5.0], [0.0, 5.0]],
            [[0.0, 5.0], [0.0, 0.0]],
        ]
    }

    #[test]
    fn a_scan_in_a_room_is_predicted_placed_and_one_in_a_corridor_is_not() {
        let params = IcpParams::default();
        let mut room = WallMap::new();
        room.extend(&closed_room());
        let p = predict(&room, &WallMap::new(), [3.0, 2.0], 720, 20.0, &params);
        assert!(p.places(&params) && p.degenerate.is_none(), "{p:?}");
        // Every beam meets a wall, and every return pairs.
        assert_eq!(p.pairs, 720, "{p:?}");
        // A corridor 40 m long seen without its ends: nothing fixes a shift along it.
        let mut corridor = WallMap::new();
        corridor.extend(&[[[0.0, 0.0], [40.0, 0.0]], [[40.0, 2.0], [0.0, 2.0]]]);
        let c = predict(&corridor, &WallMap::new(), [20.0, 1.0], 720, 20.0, &params);
        assert!(!c.places(&params), "{c:?}");
        let along = c.degenerate.expect("a direction left free");
        assert!(along[0].abs() > 0.99, "{along:?}");
        // Out of range of every wall, or with no wall at all: no pairs.
        assert_eq!(predict(&room, &WallMap::new(), [3.0, 2.0], 360, 1.0, &params).pairs, 0);
        assert_eq!(
            predict(&WallMap::new(), &WallMap::new(), [3.0, 2.0], 360, 20.0, &params).pairs,
            0
        );
        // The back of a wall (seen from the side it was not seen from) pairs with nothing.
        assert_eq!(predict(&room, &WallMap::new(), [3.0, -2.0], 720, 20.0, &params).pairs, 0);
    }

    #[test]
    fn walls_behind_an_occluder_are_not_predicted_to_pair() {
        let params = IcpParams::default();
        let mut room = WallMap::new();
        room.extend(&closed_room());
        let mut screen = WallMap::new();
        screen.extend(&[[[5.0, 0.5], [5.0, 4.5]]]);
        let at = [3.0, 2.0];
        let p = predict(&room, &screen, at, 720, 20.0, &params);
        // From the definition: a beam's first wall of the room, and whether it crosses the
        // screen more than `OCCLUDED` before it.
        let hidden = (0..720u32)
            .filter(|&k| {
                let a = std::f64::consts::TAU * f64::from(k) / 720.0;
                let (c, s) = (a.cos(), a.sin());
                let mut wall = f64::INFINITY;
                for (t, ok) in [
                    ((8.0 - at[0]) / c, c > 0.0),
                    ((0.0 - at[0]) / c, c < 0.0),
                    ((5.0 - at[1]) / s, s > 0.0),
                    ((0.0 - at[1]) / s, s < 0.0),
                ] {
                    if ok && t < wall {
                        wall = t;
                    }
                }
                let t = (5.0 - at[0]) / c;
                let y = at[1] + t * s;
                c > 0.0 && (0.5..=4.5).contains(&y) && t < wall - OCCLUDED
            })
            .count();
        assert!(hidden > 100, "{hidden}");
        assert_eq!(p.pairs, 720 - hidden, "{p:?}");
        // The left wall and the right wall's corners still fix the pose.
        assert!(p.degenerate.is_none(), "{p:?}");
        // A screen beyond every wall hides nothing.
        let mut far = WallMap::new();
        far.extend(&[[[9.0, -1.0], [9.0, 6.0]]]);
        assert_eq!(predict(&room, &far, at, 720, 20.0, &params).pairs, 720);
    }

    /// A wall as proptest draws it: a start, a run, and whether it is solid (or a bridge).
    type RandomWall = ((f64, f64), (f64, f64), bool);

    /// A wall map of proptest's walls, and the walls.
    fn random_map(walls: Vec<RandomWall>) -> (WallMap, Vec<([Point; 2], bool)>) {
        let walls: Vec<([Point; 2], bool)> = walls
            .into_iter()
            .map(|((x, y), (dx, dy), solid)| ([[x, y], [x + dx, y + dy]], solid))
            .collect();
        let mut map = WallMap::new();
        for &(w, solid) in &walls {
            if solid { map.extend(&[w]) } else { map.extend_bridges(&[w]) }
        }
        (map, walls)
    }

    proptest::proptest! {
        /// The grid walk finds exactly the crossings of every wall against every beam.
        #[test]
        fn crossings_match_a_brute_force(
            walls in proptest::collection::vec(
                ((-12.0..12.0f64, -12.0..12.0f64), (-6.0..6.0f64, -6.0..6.0f64), proptest::bool::ANY),
                0..25,
            ),
            eye in (-12.0..12.0f64, -12.0..12.0f64),
            pts in proptest::collection::vec((-15.0..15.0f64, -15.0..15.0f64), 1..60),
            margin in 0.0..0.3f64,
        ) {
            let (map, walls) = random_map(walls);
            let eye = [eye.0, eye.1];
            let pts: Vec<Point> = pts.into_iter().map(|(x, y)| [x, y]).collect();
            proptest::prop_assert_eq!(
                map.crossings(eye, pts.iter().copied(), margin),
                crossings_brute(&walls, eye, &pts, margin)
            );
        }

        /// A beam's first wall is the nearest of the solid walls it meets, by the grid walk
        /// as by trying every wall; its normal faces the beam.
        #[test]
        fn first_hit_matches_a_brute_force(
            walls in proptest::collection::vec(
                ((-12.0..12.0f64, -12.0..12.0f64), (-6.0..6.0f64, -6.0..6.0f64), proptest::bool::ANY),
                0..25,
            ),
            eye in (-12.0..12.0f64, -12.0..12.0f64),
            to in (-25.0..25.0f64, -25.0..25.0f64),
        ) {
            let (map, walls) = random_map(walls);
            let solid: Vec<[Point; 2]> = walls.iter().filter(|w| w.1).map(|w| w.0).collect();
            let (eye, to) = ([eye.0, eye.1], [to.0, to.1]);
            // From the definition: the beam's parameter where it meets each wall.
            let brute = solid
                .iter()
                .filter_map(|&[p, q]| {
                    let (d, e) = ([to[0] - eye[0], to[1] - eye[1]], [q[0] - p[0], q[1] - p[1]]);
                    let den = d[0] * e[1] - d[1] * e[0];
                    if den.abs() < 1e-12 { return None }
                    let w = [p[0] - eye[0], p[1] - eye[1]];
                    let t = (w[0] * e[1] - w[1] * e[0]) / den;
                    let u = (w[0] * d[1] - w[1] * d[0]) / den;
                    ((0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&u)).then_some(t)
                })
                .fold(None::<f64>, |m, t| Some(m.map_or(t, |m| m.min(t))));
            let hit = map.first_hit(eye, to);
            proptest::prop_assert_eq!(hit.is_some(), brute.is_some());
            if let (Some((q, n)), Some(t)) = (hit, brute) {
                let len = (to[0] - eye[0]).hypot(to[1] - eye[1]);
                let r = (q[0] - eye[0]).hypot(q[1] - eye[1]);
                proptest::prop_assert!((r - t * len).abs() < 1e-9, "{} {}", r, t * len);
                proptest::prop_assert!(n[0] * (to[0] - eye[0]) + n[1] * (to[1] - eye[1]) <= 0.0);
                proptest::prop_assert!((n[0].hypot(n[1]) - 1.0).abs() < 1e-12);
            }
        }
    }
}
