//! The occupancy raster of what the views saw, [`Raster`]: free where a view's region holds
//! a cell whole, occupied where a wall touches it, unknown elsewhere. explore_lite's frontier
//! search and cost_aware's predicted gain both read it.

use serde::{Deserialize, Serialize};

use std::collections::VecDeque;

use super::known::{keeps_clear, keeps_clear_leaving, reaches};
use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::Point;

/// The largest side of the raster, cells (around the start).
pub const MAX_SIDE_CELLS: i64 = 16384;

/// The hair by which the rasteriser grows every boundary segment, relative to the magnitude
/// of the coordinates seen (at least 1): far above the rounding of the regions' coordinates.
const HAIR_REL: f64 = 1e-9;

/// Cells added on each side when the raster grows, so that it is not re-allocated at every
/// view.
const GROWTH_PAD: i64 = 64;

/// Cells this close to the box's edge are never free: the neighbours of free cells, of
/// frontier cells and of theirs all lie in the box, so the searches index them unchecked.
pub(super) const MARGIN: usize = 3;

/// The 4-neighbours, then the diagonal ones.
pub(super) const NEIGHBOURS: [[i64; 2]; 8] =
    [[-1, 0], [1, 0], [0, -1], [0, 1], [-1, -1], [-1, 1], [1, -1], [1, 1]];

/// A cell's state: nothing known of it.
pub(super) const UNKNOWN: u8 = 0;
/// A cell's state: its closed square lies in a view's region.
pub(super) const FREE: u8 = 1;
/// A cell's state: a wall touches it.
pub(super) const OCCUPIED: u8 = 2;
/// A cell's state: unknown, but a wall seen beside it is assumed to run on through it (for
/// predictions only; a view that holds it makes it free).
pub(super) const ASSUMED: u8 = 3;
/// The bits of a cell that hold its state.
pub(super) const STATE: u8 = 3;
/// The bit of a cell that says it is safe for the robot.
pub(super) const SAFE: u8 = 4;

/// The occupancy raster: a box of cells `[x·res, (x+1)·res] × [y·res, (y+1)·res]` for
/// integer `x`, `y`, each with its state (unknown, free, occupied) and whether it is safe.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(super) struct Raster {
    pub(super) res: f64,
    /// The magnitude of the coordinates seen (at least 1).
    pub(super) scale: f64,
    /// The cell of the first viewpoint: the raster stays within [`MAX_SIDE_CELLS`] around it.
    pub(super) anchor: Option<[i64; 2]>,
    /// The box's lower-left cell.
    pub(super) origin: [i64; 2],
    /// Its width and height, cells.
    pub(super) size: [usize; 2],
    /// State bits and the safe bit, row by row from the bottom (run-length coded in JSON).
    #[serde(with = "runs")]
    pub(super) cells: Vec<u8>,
}

impl Raster {
    pub(super) fn new(res: f64) -> Self {
        Self { res, scale: 1.0, anchor: None, origin: [0, 0], size: [0, 0], cells: Vec::new() }
    }

    /// The hair boundary segments are grown by.
    pub(super) fn hair(&self) -> f64 {
        HAIR_REL * self.scale
    }

    pub(super) fn cell_of(&self, p: Point) -> [i64; 2] {
        [(p[0] / self.res).floor() as i64, (p[1] / self.res).floor() as i64]
    }

    pub(super) fn centre(&self, c: [i64; 2]) -> Point {
        [(c[0] as f64 + 0.5) * self.res, (c[1] as f64 + 0.5) * self.res]
    }

    /// The local index of a cell, if it is in the box.
    pub(super) fn local(&self, c: [i64; 2]) -> Option<usize> {
        let (x, y) = (c[0] - self.origin[0], c[1] - self.origin[1]);
        (x >= 0 && y >= 0 && (x as usize) < self.size[0] && (y as usize) < self.size[1])
            .then(|| y as usize * self.size[0] + x as usize)
    }

    pub(super) fn global(&self, i: usize) -> [i64; 2] {
        let w = self.size[0];
        [self.origin[0] + (i % w) as i64, self.origin[1] + (i / w) as i64]
    }

    pub(super) fn state(&self, c: [i64; 2]) -> u8 {
        self.local(c).map_or(UNKNOWN, |i| self.cells[i] & STATE)
    }

    pub(super) fn is_safe(&self, c: [i64; 2]) -> bool {
        self.local(c).is_some_and(|i| self.cells[i] & SAFE != 0)
    }

    /// Whether every cell the supercover of `a b` touches is safe.
    pub(super) fn segment_is_safe(&self, a: Point, b: Point) -> bool {
        supercover(self.res, a, b, self.hair(), |c| self.is_safe(c))
    }

    /// Grows the box to hold the cells `lo..=hi` (within [`MAX_SIDE_CELLS`] around the
    /// anchor), with a margin.
    pub(super) fn ensure(&mut self, lo: [i64; 2], hi: [i64; 2]) {
        let Some(anchor) = self.anchor else { return };
        let half = MAX_SIDE_CELLS / 2;
        let clip = |v: i64, k: usize| v.clamp(anchor[k] - half, anchor[k] + half - 1);
        let (lo, hi) = ([clip(lo[0], 0), clip(lo[1], 1)], [clip(hi[0], 0), clip(hi[1], 1)]);
        let end = |k: usize| self.origin[k] + self.size[k] as i64 - 1;
        if !self.cells.is_empty() && (0..2).all(|k| lo[k] >= self.origin[k] && hi[k] <= end(k)) {
            return;
        }
        let (mut nlo, mut nhi) =
            ([lo[0] - GROWTH_PAD, lo[1] - GROWTH_PAD], [hi[0] + GROWTH_PAD, hi[1] + GROWTH_PAD]);
        if !self.cells.is_empty() {
            for k in 0..2 {
                nlo[k] = nlo[k].min(self.origin[k]);
                nhi[k] = nhi[k].max(end(k));
            }
        }
        let (nlo, nhi) = ([clip(nlo[0], 0), clip(nlo[1], 1)], [clip(nhi[0], 0), clip(nhi[1], 1)]);
        let size = [(nhi[0] - nlo[0] + 1) as usize, (nhi[1] - nlo[1] + 1) as usize];
        let mut cells = vec![UNKNOWN; size[0] * size[1]];
        for y in 0..self.size[1] {
            let gy = self.origin[1] + y as i64;
            let from = y * self.size[0];
            let to = (gy - nlo[1]) as usize * size[0] + (self.origin[0] - nlo[0]) as usize;
            cells[to..to + self.size[0]].copy_from_slice(&self.cells[from..from + self.size[0]]);
        }
        self.origin = nlo;
        self.size = size;
        self.cells = cells;
    }

    /// Rasterises one view; returns the box of cells whose state may have changed.
    pub(super) fn add_view(
        &mut self,
        polygon: &[Point],
        pieces: &[BoundaryPiece],
        at: Point,
    ) -> Option<([i64; 2], [i64; 2])> {
        if polygon.len() < 3 {
            return None;
        }
        let eps = self.hair();
        if self.anchor.is_none() {
            self.anchor = Some(self.cell_of(at));
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in polygon.iter().chain(std::iter::once(&at)) {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        let (clo, chi) =
            (self.cell_of([lo[0] - eps, lo[1] - eps]), self.cell_of([hi[0] + eps, hi[1] + eps]));
        let (clo, chi) = ([clo[0] - 1, clo[1] - 1], [chi[0] + 1, chi[1] + 1]);
        self.ensure(clo, chi);
        // Clip the box to the raster (it may be capped).
        let end =
            [self.origin[0] + self.size[0] as i64 - 1, self.origin[1] + self.size[1] as i64 - 1];
        let blo = [clo[0].max(self.origin[0]), clo[1].max(self.origin[1])];
        let bhi = [chi[0].min(end[0]), chi[1].min(end[1])];
        if blo[0] > bhi[0] || blo[1] > bhi[1] {
            return None;
        }
        let bw = (bhi[0] - blo[0] + 1) as usize;
        let bh = (bhi[1] - blo[1] + 1) as usize;
        let in_box = |c: [i64; 2]| {
            (c[0] >= blo[0] && c[0] <= bhi[0] && c[1] >= blo[1] && c[1] <= bhi[1])
                .then(|| (c[1] - blo[1]) as usize * bw + (c[0] - blo[0]) as usize)
        };
        // Cells the region's boundary touches: never free by this view.
        let mut touched = vec![false; bw * bh];
        let n = polygon.len();
        for i in 0..n {
            supercover(self.res, polygon[i], polygon[(i + 1) % n], eps, |c| {
                if let Some(j) = in_box(c) {
                    touched[j] = true;
                }
                true
            });
        }
        // Cells a wall touches: occupied.
        for piece in pieces {
            if let BoundaryPiece::Edge { from, to, .. }
            | BoundaryPiece::Partial { from, to, .. }
            | BoundaryPiece::Wall { from, to } = *piece
            {
                supercover(self.res, from, to, eps, |c| {
                    if let Some(j) = self.local(c) {
                        self.cells[j] = (self.cells[j] & !STATE) | OCCUPIED;
                    }
                    true
                });
            }
        }
        // Cells whose centre is inside (scanline at the centres' heights) and that the boundary
        // does not touch: free.
        let mut crossings: Vec<(i64, f64)> = Vec::new();
        for i in 0..n {
            let (p, q) = (polygon[i], polygon[(i + 1) % n]);
            if p[1] == q[1] {
                continue;
            }
            let (ylo, yhi) = (p[1].min(q[1]), p[1].max(q[1]));
            // Rows whose centre height y satisfies ylo <= y < yhi (half-open, as a crossing
            // number must be).
            let first = ((ylo / self.res - 0.5).ceil() as i64).max(blo[1]);
            let last = bhi[1];
            for row in first..=last {
                let y = (row as f64 + 0.5) * self.res;
                if y >= yhi {
                    break;
                }
                if y < ylo {
                    continue;
                }
                crossings.push((row, p[0] + (y - p[1]) * (q[0] - p[0]) / (q[1] - p[1])));
            }
        }
        crossings.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
        for run in crossings.chunk_by(|a, b| a.0 == b.0) {
            let row = run[0].0;
            for pair in run.chunks_exact(2) {
                let (x0, x1) = (pair[0].1, pair[1].1);
                let first = ((x0 / self.res - 0.5).floor() as i64).max(blo[0]);
                let last = ((x1 / self.res - 0.5).ceil() as i64).min(bhi[0]);
                for x in first..=last {
                    let cx = (x as f64 + 0.5) * self.res;
                    if cx <= x0 || cx >= x1 || in_box([x, row]).is_some_and(|j| touched[j]) {
                        continue;
                    }
                    if let Some(j) = self.local([x, row])
                        && matches!(self.cells[j] & STATE, UNKNOWN | ASSUMED)
                        && self.inner(j)
                    {
                        self.cells[j] = (self.cells[j] & !STATE) | FREE;
                    }
                }
            }
        }
        Some((blo, bhi))
    }

    /// Recomputes the safe bit of the cells within `k` of the box `lo..=hi`: safe when every
    /// cell within `k` (Chebyshev) is free.
    pub(super) fn update_safe(&mut self, lo: [i64; 2], hi: [i64; 2], k: i64) {
        if self.cells.is_empty() {
            return;
        }
        let end =
            [self.origin[0] + self.size[0] as i64 - 1, self.origin[1] + self.size[1] as i64 - 1];
        let tlo = [(lo[0] - k).max(self.origin[0]), (lo[1] - k).max(self.origin[1])];
        let thi = [(hi[0] + k).min(end[0]), (hi[1] + k).min(end[1])];
        if tlo[0] > thi[0] || tlo[1] > thi[1] {
            return;
        }
        // Prefix sums of "not free" over the targets grown by k (cells outside count).
        let slo = [tlo[0] - k, tlo[1] - k];
        let sw = (thi[0] - tlo[0] + 1 + 2 * k) as usize;
        let sh = (thi[1] - tlo[1] + 1 + 2 * k) as usize;
        let mut sum = vec![0u32; (sw + 1) * (sh + 1)];
        for y in 0..sh {
            let mut row = 0u32;
            for x in 0..sw {
                let c = [slo[0] + x as i64, slo[1] + y as i64];
                row += u32::from(self.state(c) != FREE);
                sum[(y + 1) * (sw + 1) + x + 1] = sum[y * (sw + 1) + x + 1] + row;
            }
        }
        let d = (2 * k + 1) as usize;
        for y in tlo[1]..=thi[1] {
            for x in tlo[0]..=thi[0] {
                let (sx, sy) = ((x - tlo[0]) as usize, (y - tlo[1]) as usize);
                let blocked = sum[(sy + d) * (sw + 1) + sx + d] + sum[sy * (sw + 1) + sx]
                    - sum[sy * (sw + 1) + sx + d]
                    - sum[(sy + d) * (sw + 1) + sx];
                if let Some(i) = self.local([x, y]) {
                    self.cells[i] =
                        if blocked == 0 { self.cells[i] | SAFE } else { self.cells[i] & !SAFE };
                }
            }
        }
    }

    pub(super) fn update_safe_everywhere(&mut self, k: i64) {
        if self.cells.is_empty() {
            return;
        }
        let end =
            [self.origin[0] + self.size[0] as i64 - 1, self.origin[1] + self.size[1] as i64 - 1];
        self.update_safe(self.origin, end, k);
    }

    /// Whether a local index is at least [`MARGIN`] cells from the box's edge.
    pub(super) fn inner(&self, i: usize) -> bool {
        let [w, h] = self.size;
        let (x, y) = (i % w, i / w);
        x >= MARGIN && y >= MARGIN && x + MARGIN < w && y + MARGIN < h
    }

    /// The local index offsets of [`NEIGHBOURS`], for cells away from the box's edge.
    pub(super) fn offsets(&self) -> [isize; 8] {
        let w = self.size[0] as isize;
        NEIGHBOURS.map(|[dx, dy]| dx as isize + dy as isize * w)
    }

    /// The 4- and 8-neighbourhoods of a local index (within the box).
    pub(super) fn neighbours(&self, i: usize, eight: bool) -> impl Iterator<Item = usize> + use<> {
        let [w, h] = self.size;
        let (x, y) = ((i % w) as i64, (i / w) as i64);
        NEIGHBOURS.into_iter().take(if eight { 8 } else { 4 }).filter_map(move |d| {
            let (nx, ny) = (x + d[0], y + d[1]);
            (nx >= 0 && ny >= 0 && (nx as usize) < w && (ny as usize) < h)
                .then(|| ny as usize * w + nx as usize)
        })
    }
}

/// How far (cells, Chebyshev) from its own cell the robot looks for a safe cell to drive to
/// straight when its own cell is not safe.
const MAX_ENTRY_CELLS: i64 = 64;

/// Path cost of an orthogonal step (a diagonal one costs [`DIAGONAL`]): a cell's side is
/// `STEP` units.
pub(super) const STEP: u64 = 1000;
/// Path cost of a diagonal step.
pub(super) const DIAGONAL: u64 = 1414;

/// A first step of a trip: from the robot to the cell with this local index.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Entry {
    pub(super) cell: usize,
    pub(super) cost: u64,
    /// Reached straight through the robot's region (the robot's cell is not safe).
    pub(super) direct: bool,
}

/// Paths through safe cells: every cell a move's supercover touches is safe, so the robot's
/// footprint stays in cells seen free.
impl Raster {
    /// The A* cost of a straight step.
    pub(super) fn step_cost(&self, a: Point, b: Point) -> u64 {
        ((b[0] - a[0]).hypot(b[1] - a[1]) / self.res * STEP as f64).round() as u64
    }

    /// The safe 8-neighbours of a local index a move may step to (a diagonal only when both
    /// orthogonal cells are safe), with the step's cost. Safe cells are free, so they keep
    /// [`MARGIN`] from the box's edge and their neighbours are indexed unchecked.
    pub(super) fn safe_steps(&self, i: usize) -> impl Iterator<Item = (usize, u64)> + '_ {
        let w = self.size[0] as isize;
        let safe = move |o: isize| self.cells[i.wrapping_add_signed(o)] & SAFE != 0;
        NEIGHBOURS.into_iter().zip(self.offsets()).filter_map(move |([dx, dy], o)| {
            if !safe(o) {
                return None;
            }
            if dx != 0 && dy != 0 {
                (safe(dx as isize) && safe(dy as isize * w))
                    .then_some((i.wrapping_add_signed(o), DIAGONAL))
            } else {
                Some((i.wrapping_add_signed(o), STEP))
            }
        })
    }

    /// The safe cells reachable from the entries.
    pub(super) fn reachable(&self, entries: &[Entry]) -> Vec<bool> {
        let mut reach = vec![false; self.cells.len()];
        let mut q: VecDeque<usize> = VecDeque::new();
        for e in entries {
            if !reach[e.cell] {
                reach[e.cell] = true;
                q.push_back(e.cell);
            }
        }
        while let Some(i) = q.pop_front() {
            for (j, _) in self.safe_steps(i) {
                if !reach[j] {
                    reach[j] = true;
                    q.push_back(j);
                }
            }
        }
        reach
    }

    /// The cells a trip from `at` may start with, and how: the robot's own cell when it is
    /// safe and the move to its centre stays in safe cells; otherwise the safe cells nearby
    /// that a straight move through `view` (the region the robot stands in) reaches with the
    /// clearance `c` (`relaxed`: the robot may stand nearer a wall than `c`, and the move
    /// keeps 99% of what it has, [`keeps_clear_leaving`]). `k` is the inflation, cells.
    pub(super) fn entries(
        &self,
        at: Point,
        view: Option<&[Point]>,
        c: f64,
        k: i64,
        relaxed: bool,
    ) -> Vec<Entry> {
        let own = self.cell_of(at);
        if let Some(i) = self.local(own)
            && self.cells[i] & SAFE != 0
            && self.segment_is_safe(at, self.centre(own))
        {
            return vec![Entry {
                cell: i,
                cost: self.step_cost(at, self.centre(own)),
                direct: false,
            }];
        }
        let Some(polygon) = view else { return Vec::new() };
        // The box around the robot's cell grows until it holds a safe cell the robot can
        // drive to straight (a start in a corner or a narrow spike may be far from one).
        let mut reach = k + 3;
        loop {
            let mut out = Vec::new();
            for y in own[1] - reach..=own[1] + reach {
                for x in own[0] - reach..=own[0] + reach {
                    let Some(i) = self.local([x, y]) else { continue };
                    if self.cells[i] & SAFE == 0 {
                        continue;
                    }
                    let q = self.centre([x, y]);
                    if q != at
                        && reaches(polygon, at, q)
                        && (c == 0.0
                            || if relaxed {
                                keeps_clear_leaving(polygon, at, q, c)
                            } else {
                                keeps_clear(polygon, at, q, c)
                            })
                    {
                        out.push(Entry { cell: i, cost: self.step_cost(at, q), direct: true });
                    }
                }
            }
            if !out.is_empty() || reach >= MAX_ENTRY_CELLS {
                return out;
            }
            reach = (2 * reach).min(MAX_ENTRY_CELLS);
        }
    }

    /// The cost of the cheapest path through safe cells from the robot (through its entries)
    /// to every cell, in [`STEP`]s per cell side; `u64::MAX` where none leads (Dijkstra's
    /// algorithm over the whole raster).
    pub(super) fn distances(&self, entries: &[Entry]) -> Vec<u64> {
        use std::cmp::Reverse;
        let mut dist = vec![u64::MAX; self.cells.len()];
        let mut heap = std::collections::BinaryHeap::new();
        for e in entries {
            if e.cost < dist[e.cell] {
                dist[e.cell] = e.cost;
                heap.push(Reverse((e.cost, e.cell)));
            }
        }
        while let Some(Reverse((d, i))) = heap.pop() {
            if d > dist[i] {
                continue;
            }
            for (j, step) in self.safe_steps(i) {
                let nd = d + step;
                if nd < dist[j] {
                    dist[j] = nd;
                    heap.push(Reverse((nd, j)));
                }
            }
        }
        dist
    }

    /// A* over safe cells from the robot (through its entries) to the cell `goal`: the cell
    /// path, entry first.
    pub(super) fn astar(&self, entries: &[Entry], goal: usize) -> Option<Vec<usize>> {
        const ROBOT: usize = usize::MAX;
        let w = self.size[0];
        let (gx, gy) = ((goal % w) as i64, (goal / w) as i64);
        let h = |&i: &usize| -> u64 {
            if i == ROBOT {
                return 0;
            }
            let (dx, dy) =
                (((i % w) as i64 - gx).unsigned_abs(), ((i / w) as i64 - gy).unsigned_abs());
            let (lo, hi) = (dx.min(dy), dx.max(dy));
            STEP * hi + (DIAGONAL - STEP) * lo
        };
        let (path, _) = pathfinding::directed::astar::astar(
            &ROBOT,
            |&i: &usize| -> Vec<(usize, u64)> {
                if i == ROBOT {
                    entries.iter().map(|e| (e.cell, e.cost)).collect()
                } else {
                    self.safe_steps(i).collect()
                }
            },
            h,
            |&i| i == goal,
        )?;
        Some(path.into_iter().skip(1).collect())
    }

    /// Straight moves along a cell path from the robot at `at`: the first to the path's first
    /// cell when the entry goes there straight through the last scan's region; then from the
    /// anchor (the robot, or the last waypoint) to the farthest cell of the path, extending one
    /// cell at a time while every cell the move's supercover touches is safe. The last
    /// waypoint is the centre of the path's last cell. `None` if a move cannot be extended at
    /// all (never for a path of safe neighbours).
    pub(super) fn compress(
        &self,
        at: Point,
        entries: &[Entry],
        path: &[usize],
    ) -> Option<Vec<Point>> {
        let centre = |i: usize| self.centre(self.global(i));
        let first = *path.first()?;
        let mut out = Vec::new();
        let (mut anchor, mut next) = if entries.iter().any(|e| e.cell == first && e.direct) {
            out.push(centre(first));
            (centre(first), 1)
        } else if at == centre(first) {
            (at, 1)
        } else {
            (at, 0)
        };
        while next < path.len() {
            let mut best = None;
            for (j, &c) in path.iter().enumerate().skip(next) {
                if !self.segment_is_safe(anchor, centre(c)) {
                    break;
                }
                best = Some(j);
            }
            let j = best?;
            anchor = centre(path[j]);
            out.push(anchor);
            next = j + 1;
        }
        Some(out)
    }
}

/// Visits every cell whose closed square, grown by `eps` on every side, meets the closed
/// segment `a b` (rounding may add a cell or so more, never drop one by more than a fraction
/// of `eps`), row by row; stops as soon as `visit` returns false, and returns whether it never
/// did.
pub(super) fn supercover(
    res: f64,
    a: Point,
    b: Point,
    eps: f64,
    mut visit: impl FnMut([i64; 2]) -> bool,
) -> bool {
    let cell = |v: f64| (v / res).floor() as i64;
    let (ylo, yhi) = (a[1].min(b[1]), a[1].max(b[1]));
    for y in cell(ylo - eps)..=cell(yhi + eps) {
        let (x0, x1) = if a[1] == b[1] {
            (a[0].min(b[0]), a[0].max(b[0]))
        } else {
            let (band_lo, band_hi) = (y as f64 * res - eps, (y + 1) as f64 * res + eps);
            let t = |v: f64| ((v - a[1]) / (b[1] - a[1])).clamp(0.0, 1.0);
            let (xa, xb) = (a[0] + t(band_lo) * (b[0] - a[0]), a[0] + t(band_hi) * (b[0] - a[0]));
            (xa.min(xb), xa.max(xb))
        };
        for x in cell(x0 - eps)..=cell(x1 + eps) {
            if !visit([x, y]) {
                return false;
            }
        }
    }
    true
}

/// The raster's cells in JSON: `[value, count]` runs.
mod runs {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    pub(super) fn serialize<S: Serializer>(cells: &[u8], s: S) -> Result<S::Ok, S::Error> {
        let mut out: Vec<[u32; 2]> = Vec::new();
        for &c in cells {
            match out.last_mut() {
                Some(r) if r[0] == u32::from(c) => r[1] += 1,
                _ => out.push([u32::from(c), 1]),
            }
        }
        out.serialize(s)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<u8>, D::Error> {
        let runs: Vec<[u32; 2]> = Vec::deserialize(d)?;
        let mut out = Vec::new();
        for [v, n] in runs {
            let v = u8::try_from(v).map_err(serde::de::Error::custom)?;
            out.extend(std::iter::repeat_n(v, n as usize));
        }
        Ok(out)
    }
}

impl Raster {
    /// The area of unknown space seen from `z` along the rays whose angles `rays` marks
    /// (`rays[k]`: the ray at `k · 2π / rays.len()`), each out to `range` and through at most
    /// `depth` of unknown space (a ray stops at an occupied cell, a wall seen before, and at
    /// an assumed wall when `stops` says so; otherwise an assumed wall is unknown space). Each
    /// unknown cell a ray crosses counts the sector of the ray's angular width between where the
    /// ray enters and leaves it, so the sum estimates an area whatever the ray spacing. The
    /// cell `z` stands in is not a wall to its own rays.
    pub(super) fn unknown_area_seen(
        &self,
        z: Point,
        rays: &[bool],
        range: f64,
        depth: f64,
        limit: Option<[Point; 2]>,
        stops: Stops,
    ) -> f64 {
        let limit = limit.map(|[lo, hi]| [self.cell_of(lo), self.cell_of(hi)]);
        let n = rays.len();
        if n == 0 || !range.is_finite() || range <= 0.0 {
            return 0.0;
        }
        let dtheta = std::f64::consts::TAU / n as f64;
        let start = self.cell_of(z);
        let mut area = 0.0;
        for (k, _) in rays.iter().enumerate().filter(|(_, on)| **on) {
            let theta = k as f64 * dtheta;
            let (dx, dy) = (theta.cos(), theta.sin());
            area += dtheta * self.unknown_along(z, start, [dx, dy], (range, depth), limit, stops);
        }
        area
    }

    /// `∫ r dr` over the unknown stretches of the ray from `z` (in cell `start`) along the unit
    /// vector `d`, out to `range` and through at most `depth` of unknown space, stopping at the
    /// first cell after the start's that `stops` stops at (a grid walk, Amanatides and Woo).
    fn unknown_along(
        &self,
        z: Point,
        start: [i64; 2],
        d: [f64; 2],
        (range, depth): (f64, f64),
        limit: Option<[[i64; 2]; 2]>,
        stops: Stops,
    ) -> f64 {
        let res = self.res;
        let mut cell = start;
        let step = [if d[0] >= 0.0 { 1 } else { -1 }, if d[1] >= 0.0 { 1 } else { -1 }];
        // The ray parameter at the next vertical and horizontal cell boundary, and between two.
        let next = |k: usize| {
            if d[k] == 0.0 {
                f64::INFINITY
            } else {
                let edge = (cell[k] + i64::from(d[k] > 0.0)) as f64 * res;
                ((edge - z[k]) / d[k]).max(0.0)
            }
        };
        let mut t_max = [next(0), next(1)];
        let t_delta = [
            if d[0] == 0.0 { f64::INFINITY } else { res / d[0].abs() },
            if d[1] == 0.0 { f64::INFINITY } else { res / d[1].abs() },
        ];
        let (mut t, mut unknown, mut sum) = (0.0f64, 0.0f64, 0.0f64);
        loop {
            let state = self.state(cell);
            let stop = match stops {
                Stops::WallsAndAssumed => matches!(state, OCCUPIED | ASSUMED),
                Stops::Walls => state == OCCUPIED,
            };
            if stop && cell != start {
                return sum;
            }
            if let Some([lo, hi]) = limit
                && (cell[0] < lo[0] || cell[1] < lo[1] || cell[0] > hi[0] || cell[1] > hi[1])
            {
                return sum;
            }
            let axis = usize::from(t_max[1] < t_max[0]);
            let t_out = t_max[axis].min(range);
            // Assumed walls are unknown space where they do not stop the rays.
            if state == UNKNOWN || (state == ASSUMED && stops == Stops::Walls) {
                let t_end = t_out.min(t + (depth - unknown));
                sum += 0.5 * (t_end * t_end - t * t);
                unknown += t_end - t;
                if unknown >= depth {
                    return sum;
                }
            }
            if t_out >= range {
                return sum;
            }
            t = t_out;
            cell[axis] += step[axis];
            t_max[axis] += t_delta[axis];
        }
    }
}

/// The cell of a raster of the views, as a fraction of the length scale (the range, or
/// without one how far the first view reached): 10 cm at 20 m.
pub(super) const CELL: f64 = 1.0 / 200.0;

/// How far a ray of [`Raster::unknown_area_seen`] counts unknown space, as a fraction of the
/// length scale: 8 m at 20 m.
pub(super) const DEPTH: f64 = 0.4;

/// Rays per revolution of the predicted gain and of [`rays_through`].
pub(super) const RAYS: usize = 720;

/// Which of [`RAYS`] rays from `z` pass through the segments `gaps` (those with an end
/// within `range`): `rays[k]` for the ray at angle `k · 2π / RAYS`.
pub(super) fn rays_through(z: Point, gaps: &[[Point; 2]], range: f64) -> Vec<bool> {
    use std::f64::consts::{PI, TAU};
    let mut rays = vec![false; RAYS];
    let dtheta = TAU / RAYS as f64;
    let d = |p: Point| (p[0] - z[0]).hypot(p[1] - z[1]);
    for g in gaps.iter().filter(|g| d(g[0]).min(d(g[1])) <= range) {
        let a0 = (g[0][1] - z[1]).atan2(g[0][0] - z[0]);
        let a1 = (g[1][1] - z[1]).atan2(g[1][0] - z[0]);
        let mut sweep = a1 - a0;
        if sweep > PI {
            sweep -= TAU;
        } else if sweep < -PI {
            sweep += TAU;
        }
        let (a, sweep) = if sweep < 0.0 { (a1, -sweep) } else { (a0, sweep) };
        for k in (a / dtheta).ceil() as i64..=((a + sweep) / dtheta).floor() as i64 {
            rays[k.rem_euclid(RAYS as i64) as usize] = true;
        }
    }
    rays
}

/// Which cells stop a ray of [`Raster::unknown_area_seen`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Stops {
    /// Walls seen and walls assumed ([`Raster::assume_wall`]): the predicted gain.
    WallsAndAssumed,
    /// Walls seen only: whether anything unknown lies behind a window at all.
    Walls,
}

impl Raster {
    /// The area of the unknown space the segment `p q` opens onto, when it is a pocket: the
    /// unknown cells (assumed walls are unknown space) its line touches, and those reached
    /// from them through unknown cells (four neighbours), enclosed by cells seen free or
    /// walls seen, covering at most `cap` square metres (0 when the line touches no unknown
    /// cell: what it opens onto was seen). `None` when they cover more.
    pub(super) fn pocket_behind(&self, p: Point, q: Point, cap: f64) -> Option<f64> {
        let most = (cap / (self.res * self.res)).floor();
        if most.is_nan() || most < 0.0 {
            return None;
        }
        let most = most as usize;
        let open = |c: [i64; 2]| matches!(self.state(c), UNKNOWN | ASSUMED);
        let mut reached = rustc_hash::FxHashSet::default();
        let mut stack = Vec::new();
        supercover(self.res, p, q, self.hair(), |c| {
            if open(c) && reached.insert(c) {
                stack.push(c);
            }
            reached.len() <= most
        });
        while let Some(c) = stack.pop() {
            if reached.len() > most {
                return None;
            }
            for n in [[c[0] + 1, c[1]], [c[0] - 1, c[1]], [c[0], c[1] + 1], [c[0], c[1] - 1]] {
                if open(n) && reached.insert(n) {
                    stack.push(n);
                }
            }
        }
        (reached.len() <= most).then_some(reached.len() as f64 * self.res * self.res)
    }

    /// Makes the [`ASSUMED`] cells along `a b` unknown again (a view saw through them).
    pub(super) fn unassume(&mut self, a: Point, b: Point) {
        self.relabel_along(a, b, ASSUMED, UNKNOWN);
    }

    /// Marks the unknown cells along `a b` as [`ASSUMED`] walls.
    pub(super) fn assume_wall(&mut self, a: Point, b: Point) {
        self.relabel_along(a, b, UNKNOWN, ASSUMED);
    }

    /// Gives the cells along `a b` (their supercover) in state `from` the state `to`.
    fn relabel_along(&mut self, a: Point, b: Point, from: u8, to: u8) {
        let mut cells = Vec::new();
        supercover(self.res, a, b, self.hair(), |c| {
            cells.push(c);
            true
        });
        for c in cells {
            if let Some(j) = self.local(c)
                && self.cells[j] & STATE == from
            {
                self.cells[j] = (self.cells[j] & !STATE) | to;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::EdgeId;

    /// The square `[-1, 1]²` seen from its middle, its right side a window (the rest walls).
    fn square_with_a_window() -> (Vec<Point>, Vec<BoundaryPiece>) {
        let polygon = vec![[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];
        let e = EdgeId { ring: 0, index: 0 };
        let pieces = (0..4)
            .map(|k| {
                let (from, to) = (polygon[k], polygon[(k + 1) % 4]);
                if k == 1 {
                    BoundaryPiece::Window { from, to, reflex: from, far: to }
                } else {
                    BoundaryPiece::Edge { from, to, edge: e }
                }
            })
            .collect();
        (polygon, pieces)
    }

    /// The area of the points `p` with `keep(p)`, counted on a grid of `h`: a brute force
    /// from the definition of what is seen.
    fn area_where(h: f64, lo: Point, hi: Point, keep: impl Fn(Point) -> bool) -> f64 {
        let (nx, ny) = (((hi[0] - lo[0]) / h) as i64, ((hi[1] - lo[1]) / h) as i64);
        let mut n = 0u64;
        for i in 0..nx {
            for j in 0..ny {
                let p = [lo[0] + (i as f64 + 0.5) * h, lo[1] + (j as f64 + 0.5) * h];
                n += u64::from(keep(p));
            }
        }
        n as f64 * h * h
    }

    #[test]
    fn an_unknown_plane_shows_a_disc_out_to_the_range_or_the_depth() {
        let r = Raster::new(0.1);
        let rays = vec![true; 720];
        let disc =
            r.unknown_area_seen([0.03, 0.07], &rays, 3.0, 10.0, None, Stops::WallsAndAssumed);
        assert!((disc - std::f64::consts::PI * 9.0).abs() < 1e-9, "{disc}");
        let shallow =
            r.unknown_area_seen([0.03, 0.07], &rays, 3.0, 2.0, None, Stops::WallsAndAssumed);
        assert!((shallow - std::f64::consts::PI * 4.0).abs() < 1e-9, "{shallow}");
        // Half the rays: half the disc.
        let half: Vec<bool> = (0..720).map(|k| k < 360).collect();
        let h = r.unknown_area_seen([0.0, 0.0], &half, 3.0, 10.0, None, Stops::WallsAndAssumed);
        assert!((h - std::f64::consts::PI * 4.5).abs() < 1e-9, "{h}");
    }

    #[test]
    fn a_window_shows_what_lies_beyond_it_and_walls_stop_the_rays() {
        let (polygon, pieces) = square_with_a_window();
        let mut r = Raster::new(0.05);
        r.add_view(&polygon, &pieces, [0.0, 0.0]);
        let rays = vec![true; 720];
        // Beyond the window, in its wedge, within the range: |y| ≤ x, x ≥ 1, r ≤ 3.
        let wedge = |p: Point| p[0] >= 1.0 && p[1].abs() <= p[0] && p[0].hypot(p[1]) <= 3.0;
        let want = area_where(0.005, [0.0, -3.0], [3.0, 3.0], wedge);
        let got = r.unknown_area_seen([0.0, 0.0], &rays, 3.0, 10.0, None, Stops::WallsAndAssumed);
        // Cells a wall touches stop the rays that pass through them: near the window's ends,
        // within a cell of its corners (√2 from the viewpoint), about `res` radians on each
        // side, at most `res · R²` of area. The cells the window runs through are unknown and
        // count: at most a cell's width along it more.
        let (res, r2) = (0.05, 9.0);
        let close = |got: f64, want: f64| got >= want - res * r2 && got <= want + res * 3.0;
        assert!(close(got, want), "{got} against {want}");
        // An assumed wall at x = 2 stops the rays there.
        r.assume_wall([2.0, -3.0], [2.0, 3.0]);
        let near = |p: Point| wedge(p) && p[0] <= 2.0;
        let want = area_where(0.005, [0.0, -3.0], [3.0, 3.0], near);
        let got = r.unknown_area_seen([0.0, 0.0], &rays, 3.0, 10.0, None, Stops::WallsAndAssumed);
        assert!(close(got, want), "{got} against {want}");
        // Not when only walls seen stop them.
        let all = r.unknown_area_seen([0.0, 0.0], &rays, 3.0, 10.0, None, Stops::Walls);
        let want_all = area_where(0.005, [0.0, -3.0], [3.0, 3.0], wedge);
        assert!(close(all, want_all), "{all} against {want_all}");
        // So does the limit box, and the depth of unknown space a ray may cross.
        let boxed = r.unknown_area_seen(
            [0.0, 0.0],
            &rays,
            3.0,
            10.0,
            Some([[-1.5, -1.5], [1.5, 1.5]]),
            Stops::WallsAndAssumed,
        );
        // The box ends at the cell holding x = 1.5.
        let want = area_where(0.005, [0.0, -3.0], [3.0, 3.0], |p| near(p) && p[0] <= 1.55);
        assert!(close(boxed, want), "{boxed} against {want}");
        let shallow =
            r.unknown_area_seen([0.0, 0.0], &rays, 3.0, 0.2, None, Stops::WallsAndAssumed);
        assert!(shallow < got && shallow > 0.0);
        // A ray from inside the room that meets only walls sees nothing.
        let left: Vec<bool> = (0..720).map(|k| (270..450).contains(&k)).collect();
        assert_eq!(
            r.unknown_area_seen([0.0, 0.0], &left, 3.0, 10.0, None, Stops::WallsAndAssumed),
            0.0
        );
    }

    #[test]
    fn a_sliver_in_front_of_a_wall_seen_opens_onto_nothing() {
        // Free cells in columns 0 to 4, a wall seen in column 5 from row 2 to row 9, unknown
        // beyond: the rays from (0.25, 0.55) through the segment x = 0.5, y from 0.3 to 0.8
        // (the region's edge, a cell in front of the wall) meet the wall before anything
        // unknown, assumed walls or not.
        let wall = |i: usize, j: usize| i == 5 && (2..=9).contains(&j);
        let cells: Vec<u8> = (0..144)
            .map(|k| match (k % 12, k / 12) {
                (i, j) if wall(i, j) => OCCUPIED,
                (i, _) if i < 5 => FREE,
                _ => UNKNOWN,
            })
            .collect();
        let r = raster_of(&cells);
        let (z, gap) = ([0.25, 0.55], [[0.5, 0.3], [0.5, 0.8]]);
        let rays = rays_through_gap(z, gap);
        for stops in [Stops::Walls, Stops::WallsAndAssumed] {
            assert_eq!(r.unknown_area_seen(z, &rays, 3.0, 10.0, None, stops), 0.0);
        }
        // Through a gap in the wall (rows 5 and 6 unknown), the space beyond shows.
        let holed: Vec<u8> = cells
            .iter()
            .enumerate()
            .map(|(k, &st)| if k % 12 == 5 && (5..=6).contains(&(k / 12)) { UNKNOWN } else { st })
            .collect();
        let seen = raster_of(&holed).unknown_area_seen(z, &rays, 3.0, 10.0, None, Stops::Walls);
        assert!(seen > 0.05, "{seen}");
    }

    /// The rays of 720 that pass through the segment `gap` seen from `z`, from the
    /// definition: those whose direction lies between the directions of its ends.
    fn rays_through_gap(z: Point, gap: [Point; 2]) -> Vec<bool> {
        let angle = |p: Point| (p[1] - z[1]).atan2(p[0] - z[0]);
        let (a, b) = (angle(gap[0]).min(angle(gap[1])), angle(gap[0]).max(angle(gap[1])));
        (0..720)
            .map(|k| {
                let t = std::f64::consts::TAU * f64::from(k) / 720.0;
                let t = if t > std::f64::consts::PI { t - std::f64::consts::TAU } else { t };
                (a..=b).contains(&t)
            })
            .collect()
    }

    /// A raster of `states` (row `j` of the grid at cells `(i, j)`, `0 ≤ i, j < 12`), cells
    /// of 0.1 m; outside it, everything is unknown.
    fn raster_of(states: &[u8]) -> Raster {
        let mut r = Raster::new(0.1);
        r.anchor = Some([0, 0]);
        r.ensure([0, 0], [11, 11]);
        for (k, &st) in states.iter().enumerate() {
            let j = r.local([(k % 12) as i64, (k / 12) as i64]).unwrap();
            r.cells[j] = st;
        }
        r
    }

    /// The pocket behind the cells `(col, from..=to)`, from the definition: the open cells
    /// (unknown or assumed) among them and every open cell joined to them by a chain of open
    /// cells side by side, found by growing the set until it stops changing. `None` when it
    /// reaches the grid's edge (beyond it the unknown goes on) or holds more than `most`.
    fn pocket_by_definition(
        states: &[u8],
        col: usize,
        rows: (usize, usize),
        most: usize,
    ) -> Option<usize> {
        let open = |i: usize, j: usize| matches!(states[j * 12 + i], UNKNOWN | ASSUMED);
        let mut inside = [[false; 12]; 12];
        for (j, cell) in inside[col].iter_mut().enumerate().take(rows.1 + 1).skip(rows.0) {
            *cell = open(col, j);
        }
        loop {
            let mut grew = false;
            for i in 0..12 {
                for j in 0..12 {
                    let next = (i > 0 && inside[i - 1][j])
                        || (i < 11 && inside[i + 1][j])
                        || (j > 0 && inside[i][j - 1])
                        || (j < 11 && inside[i][j + 1]);
                    if !inside[i][j] && open(i, j) && next {
                        inside[i][j] = true;
                        grew = true;
                    }
                }
            }
            if !grew {
                break;
            }
        }
        let edge = (0..12).any(|k| inside[0][k] || inside[11][k] || inside[k][0] || inside[k][11]);
        let n = inside.iter().flatten().filter(|&&b| b).count();
        (!edge && n <= most).then_some(n)
    }

    proptest::proptest! {
        #[test]
        fn a_pocket_is_the_unknown_space_a_segment_opens_onto_when_walls_enclose_it(
            cells in proptest::collection::vec(
                proptest::prop_oneof![
                    3 => proptest::strategy::Just(UNKNOWN),
                    2 => proptest::strategy::Just(FREE),
                    3 => proptest::strategy::Just(OCCUPIED),
                    1 => proptest::strategy::Just(ASSUMED),
                ],
                144,
            ),
            col in 0usize..12,
            a in 0usize..12,
            b in 0usize..12,
            most in 0usize..80,
        ) {
            let r = raster_of(&cells);
            let (lo, hi) = (a.min(b), a.max(b));
            // Through the cells' centres, so that the line touches exactly those cells.
            let x = (col as f64 + 0.5) * 0.1;
            let (p, q) = ([x, (lo as f64 + 0.5) * 0.1], [x, (hi as f64 + 0.5) * 0.1]);
            let cap = (most as f64 + 0.5) * 0.01;
            let got = r.pocket_behind(p, q, cap);
            let want = pocket_by_definition(&cells, col, (lo, hi), most);
            match (got, want) {
                (Some(area), Some(n)) => proptest::prop_assert!((area - n as f64 * 0.01).abs() < 1e-9),
                (None, None) => {}
                _ => proptest::prop_assert!(false, "{got:?} against {want:?} cells"),
            }
        }
    }

    #[test]
    fn a_view_that_holds_an_assumed_wall_frees_it() {
        let (polygon, pieces) = square_with_a_window();
        let mut r = Raster::new(0.1);
        r.assume_wall([0.0, -0.5], [0.0, 0.5]);
        r.add_view(&polygon, &pieces, [0.5, 0.5]);
        assert_eq!(r.state(r.cell_of([0.05, 0.05])), FREE);
    }
}
