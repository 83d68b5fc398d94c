//! The grid world: a region of interest (ROI) made of unit cells, static or translating, and
//! the sensors that tell a robot hovering over a cell whether it and its four neighbours belong
//! to the region (Sung and Tokekar, sections 3–5 and 7).

pub mod camera;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::geometry::{Domain, signed_area_of};
use crate::kernel::Point;
use crate::protocol::grid::{
    Cell, CellMap, CellSet, Frame, GridContext, GridObservation, NeighbourState, Record,
    VertexState, neighbour,
};
use crate::protocol::{CostModel, grid::TimeModel};
use crate::sim::{Arena, Leg};

/// Bit `k` of a bitmap.
fn bit(bits: &[u64], k: usize) -> bool {
    bits[k / 64] >> (k % 64) & 1 == 1
}

/// Sets bit `k` of a bitmap.
fn set_bit(bits: &mut [u64], k: usize) {
    bits[k / 64] |= 1 << (k % 64);
}

/// Why a region of interest was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidRoi {
    /// No cell belongs to the region.
    #[error("the region has no cells")]
    Empty,
    /// The start cell is not a region cell.
    #[error("the start cell (row {}, col {}) is not a region cell", .0[0], .0[1])]
    StartOutside(Cell),
    /// Some cell cannot be reached from the start through 4-neighbours.
    #[error(
        "the region is not 4-connected: cell (row {}, col {}) cannot be reached from the start ({reached} of {total} cells can)",
        .cell[0], .cell[1]
    )]
    Disconnected {
        /// A cell that cannot be reached.
        cell: Cell,
        /// How many can.
        reached: usize,
        /// How many there are.
        total: usize,
    },
    /// The cell size is not a positive finite number of metres.
    #[error("the cell size must be a positive number of metres, got {}", crate::kernel::Num(*.0))]
    CellSize(f64),
}

/// A region of interest: a 4-connected set of unit cells with a start cell, and, when it comes
/// from an arbitrary shape, that shape (for the camera and for IoU).
#[derive(Debug, Clone)]
pub struct GridRoi {
    name: String,
    cells: Vec<Cell>,
    start: Cell,
    min: Cell,
    max: Cell,
    bits: Vec<u64>,
    cell_size: f64,
    shape: Option<Domain>,
}

impl GridRoi {
    /// Validates a cell set: not empty, the start in it, every cell 4-connected to the start.
    ///
    /// # Errors
    /// [`InvalidRoi`] naming the problem and a cell where it is.
    pub fn new(
        name: impl Into<String>,
        cells: impl IntoIterator<Item = Cell>,
        start: Cell,
        cell_size: f64,
    ) -> Result<Self, InvalidRoi> {
        if !(cell_size.is_finite() && cell_size > 0.0) {
            return Err(InvalidRoi::CellSize(cell_size));
        }
        let mut cells: Vec<Cell> = cells.into_iter().collect();
        cells.sort_unstable();
        cells.dedup();
        if cells.is_empty() {
            return Err(InvalidRoi::Empty);
        }
        let mut min = cells[0];
        let mut max = cells[0];
        for c in &cells {
            for k in 0..2 {
                min[k] = min[k].min(c[k]);
                max[k] = max[k].max(c[k]);
            }
        }
        let w = (max[1] - min[1] + 1) as usize;
        let h = (max[0] - min[0] + 1) as usize;
        let mut roi = Self {
            name: name.into(),
            cells,
            start,
            min,
            max,
            bits: vec![0; (w * h).div_ceil(64)],
            cell_size,
            shape: None,
        };
        for i in 0..roi.cells.len() {
            let k = roi.index(roi.cells[i]).unwrap_or(0);
            set_bit(&mut roi.bits, k);
        }
        if !roi.contains(start) {
            return Err(InvalidRoi::StartOutside(start));
        }
        // 4-connectivity: a flood fill over the bitmap.
        let mut seen = vec![0u64; roi.bits.len()];
        let mut stack = vec![start];
        let mut reached = 0;
        while let Some(c) = stack.pop() {
            let Some(k) = roi.index(c) else { continue };
            if bit(&seen, k) || !roi.contains(c) {
                continue;
            }
            set_bit(&mut seen, k);
            reached += 1;
            stack.extend((0..4).map(|i| neighbour(c, i)));
        }
        if reached < roi.cells.len() {
            let cell = roi
                .cells
                .iter()
                .copied()
                .find(|&c| roi.index(c).is_some_and(|k| !bit(&seen, k)))
                .unwrap_or(start);
            return Err(InvalidRoi::Disconnected { cell, reached, total: roi.cells.len() });
        }
        Ok(roi)
    }

    fn index(&self, c: Cell) -> Option<usize> {
        if c[0] < self.min[0] || c[0] > self.max[0] || c[1] < self.min[1] || c[1] > self.max[1] {
            return None;
        }
        let w = (self.max[1] - self.min[1] + 1) as usize;
        Some((c[0] - self.min[0]) as usize * w + (c[1] - self.min[1]) as usize)
    }

    /// Whether `c` is a region cell.
    pub fn contains(&self, c: Cell) -> bool {
        self.index(c).is_some_and(|k| bit(&self.bits, k))
    }

    /// The name (file stem or generator).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The cells, sorted.
    pub fn cells(&self) -> &[Cell] {
        &self.cells
    }

    /// C, the number of cells.
    pub fn len(&self) -> usize {
        self.cells.len()
    }

    /// Never true: a region has at least one cell.
    pub fn is_empty(&self) -> bool {
        self.cells.is_empty()
    }

    /// The start cell.
    pub fn start(&self) -> Cell {
        self.start
    }

    /// The smallest and largest row and column.
    pub fn bounds(&self) -> [Cell; 2] {
        [self.min, self.max]
    }

    /// The side of a cell, metres.
    pub fn cell_size(&self) -> f64 {
        self.cell_size
    }

    /// The arbitrary shape this grid approximates from outside, if any (metres, in the grid's
    /// frame: cell `[r, c]` is the square centred at `(c·s, −r·s)`).
    pub fn shape(&self) -> Option<&Domain> {
        self.shape.as_ref()
    }

    /// The grid distance (4-neighbour steps inside the region) of every cell from the start.
    pub fn distances(&self) -> CellMap<u32> {
        let mut d = CellMap::default();
        d.insert(self.start, 0);
        let mut queue = std::collections::VecDeque::from([self.start]);
        while let Some(c) = queue.pop_front() {
            let dc = d[&c];
            for i in 0..4 {
                let n = neighbour(c, i);
                if self.contains(n) && !d.contains_key(&n) {
                    d.insert(n, dc + 1);
                    queue.push_back(n);
                }
            }
        }
        d
    }

    /// A random region like the paper's (Fig. 7 (a)): `count` cells grown from the start cell
    /// `[0, 0]` by adding, at every step, a cell drawn uniformly from those 4-adjacent to the
    /// region (Eden growth). The same seed gives the same region.
    ///
    /// # Errors
    /// [`InvalidRoi::Empty`] for `count` = 0.
    pub fn random(count: usize, seed: u64) -> Result<Self, InvalidRoi> {
        if count == 0 {
            return Err(InvalidRoi::Empty);
        }
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut inside = CellSet::default();
        let mut seen = CellSet::default();
        let mut frontier: Vec<Cell> = vec![[0, 0]];
        seen.insert([0, 0]);
        while inside.len() < count {
            let k = rng.random_range(0..frontier.len());
            let c = frontier.swap_remove(k);
            inside.insert(c);
            for i in 0..4 {
                let n = neighbour(c, i);
                if seen.insert(n) {
                    frontier.push(n);
                }
            }
        }
        Self::new(format!("random-{count}-seed{seed}"), inside, [0, 0], 1.0)
    }

    /// The same cells with another cell size (metres).
    ///
    /// # Errors
    /// [`InvalidRoi::CellSize`] if it is not a positive finite number.
    pub fn with_cell_size(mut self, cell_size: f64) -> Result<Self, InvalidRoi> {
        if !(cell_size.is_finite() && cell_size > 0.0) {
            return Err(InvalidRoi::CellSize(cell_size));
        }
        if let Some(shape) = &self.shape {
            // Scale the shape with the grid.
            let k = cell_size / self.cell_size;
            let rings: Vec<Vec<Point>> = shape
                .rings()
                .iter()
                .map(|r| r.iter().map(|p| [p[0] * k, p[1] * k]).collect())
                .collect();
            self.shape = Domain::new(rings[0].clone(), rings[1..].to_vec()).ok();
        }
        self.cell_size = cell_size;
        Ok(self)
    }

    /// The outer grid approximation of an arbitrary region (section 5): every cell whose
    /// square meets the shape's interior. The grid is placed as in the field experiment, with
    /// the centre of cell `[0, 0]` at `start` (the start must be inside the shape); cells are
    /// `cell_size` metres. Only the cells 4-connected to the start cell are kept (a fat region
    /// gives a connected approximation).
    ///
    /// # Errors
    /// [`InvalidRoi`] if the start is not inside the shape or the cell size is not positive.
    pub fn outer_approximation(
        name: impl Into<String>,
        shape: &Domain,
        start: Point,
        cell_size: f64,
    ) -> Result<Self, InvalidRoi> {
        if !(cell_size.is_finite() && cell_size > 0.0) {
            return Err(InvalidRoi::CellSize(cell_size));
        }
        // Move the shape into the grid frame: start at the origin.
        let moved: Vec<Vec<Point>> = shape
            .rings()
            .iter()
            .map(|r| r.iter().map(|p| [p[0] - start[0], p[1] - start[1]]).collect())
            .collect();
        let Ok(frame) = Domain::new(moved[0].clone(), moved[1..].to_vec()) else {
            return Err(InvalidRoi::Empty);
        };
        let [lo, hi] = frame.bounds();
        let s = cell_size;
        let cols = ((lo[0] / s - 0.5).floor() as i32)..=((hi[0] / s + 0.5).ceil() as i32);
        let rows = ((-hi[1] / s - 0.5).floor() as i32)..=((-lo[1] / s + 0.5).ceil() as i32);
        let mut cells = Vec::new();
        for r in rows {
            for c in cols.clone() {
                if cell_overlap(&frame, [r, c], s) > 0.0 {
                    cells.push([r, c]);
                }
            }
        }
        if !cells.contains(&[0, 0]) {
            return Err(InvalidRoi::StartOutside([0, 0]));
        }
        // Keep the component of the start.
        let all: CellSet = cells.iter().copied().collect();
        let mut keep = CellSet::default();
        let mut stack = vec![[0, 0]];
        keep.insert([0, 0]);
        while let Some(c) = stack.pop() {
            for i in 0..4 {
                let n = neighbour(c, i);
                if all.contains(&n) && keep.insert(n) {
                    stack.push(n);
                }
            }
        }
        let mut roi = Self::new(name, keep, [0, 0], cell_size)?;
        roi.shape = Some(frame);
        Ok(roi)
    }

    /// Section 5's counts for a region with a shape: `(C_out, C_in)`, the cells of the outer
    /// approximation and those lying wholly inside the shape. `None` for a plain cell region.
    pub fn approximation_counts(&self) -> Option<(usize, usize)> {
        let shape = self.shape.as_ref()?;
        let full = self.cell_size * self.cell_size;
        let inner = self
            .cells
            .iter()
            .filter(|&&c| {
                cell_overlap(shape, c, self.cell_size)
                    >= full * (1.0 - crate::kernel::tolerance::AREA_REL)
            })
            .count();
        Some((self.cells.len(), inner))
    }

    /// The area of the true region, m² (the shape's, or the cells').
    pub fn true_area(&self) -> f64 {
        self.shape.as_ref().map_or(self.cells.len() as f64 * self.cell_size.powi(2), Domain::area)
    }

    /// Intersection over union of a set of mapped cells against the true region (the shape
    /// when there is one, else the region's cells).
    pub fn iou(&self, mapped: &[Cell]) -> f64 {
        let full = self.cell_size * self.cell_size;
        let mut mapped: Vec<Cell> = mapped.to_vec();
        mapped.sort_unstable();
        mapped.dedup();
        let inter: f64 = mapped
            .iter()
            .map(|&c| match &self.shape {
                Some(s) => cell_overlap(s, c, self.cell_size),
                None => f64::from(u8::from(self.contains(c))) * full,
            })
            .sum();
        let union = mapped.len() as f64 * full + self.true_area() - inter;
        if union > 0.0 { inter / union } else { 1.0 }
    }
}

/// The area of cell `c`'s square (side `s`, centred at `(c·s, −r·s)`) inside a domain.
fn cell_overlap(domain: &Domain, c: Cell, s: f64) -> f64 {
    let (x, y) = (f64::from(c[1]) * s, -f64::from(c[0]) * s);
    let b = [x - s / 2.0, y - s / 2.0, x + s / 2.0, y + s / 2.0];
    let [lo, hi] = domain.bounds();
    if hi[0] <= b[0] || lo[0] >= b[2] || hi[1] <= b[1] || lo[1] >= b[3] {
        return 0.0;
    }
    let mut a = 0.0;
    for (k, ring) in domain.rings().iter().enumerate() {
        let clipped = clip_to_box(ring, b);
        let part = if clipped.len() < 3 { 0.0 } else { signed_area_of(&clipped).abs() };
        a += if k == 0 { part } else { -part };
    }
    a.max(0.0)
}

/// Sutherland–Hodgman clipping of a ring against an axis-aligned box `[x0, y0, x1, y1]`. The
/// result of a non-convex ring may have zero-width bridges, which do not change its area.
fn clip_to_box(ring: &[Point], b: [f64; 4]) -> Vec<Point> {
    let mut pts = ring.to_vec();
    // (axis, bound, keep the side where the coordinate is >= bound?)
    for (axis, bound, keep_ge) in
        [(0, b[0], true), (0, b[2], false), (1, b[1], true), (1, b[3], false)]
    {
        if pts.is_empty() {
            break;
        }
        let inside = |p: &Point| if keep_ge { p[axis] >= bound } else { p[axis] <= bound };
        let mut out = Vec::with_capacity(pts.len() + 4);
        for i in 0..pts.len() {
            let (p, q) = (pts[i], pts[(i + 1) % pts.len()]);
            let (ip, iq) = (inside(&p), inside(&q));
            if ip {
                out.push(p);
            }
            if ip != iq {
                let t = (bound - p[axis]) / (q[axis] - p[axis]);
                let mut m = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
                m[axis] = bound;
                out.push(m);
            }
        }
        pts = out;
    }
    pts
}

/// How the region moves: translating at `speed` m/s towards `heading_deg` (degrees counter-
/// clockwise from east, the grid's +x), known to the robots (section 3). Speed 0 is static.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Drift {
    /// S_p, m/s.
    pub speed: f64,
    /// Heading, degrees counter-clockwise from east.
    pub heading_deg: f64,
}

/// The sensor of a grid world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum GridSensor {
    /// The paper's model: the robot knows exactly whether the cell below and its four
    /// neighbours are region cells (one frame per scan).
    Ideal,
    /// The field pipeline in simulation: a synthetic downward camera renders frames from the
    /// ground truth and the frame classifier decides (section 7).
    Camera(camera::CameraModel),
}

/// A record packed into 12 bytes: parents and children are always 4-neighbours, so each is a
/// side (1–4, 0 for none). Records that do not fit (which Algorithm 1 never writes) go to the
/// overflow map.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Packed {
    parent: u8,
    flags: u8,
    children: [u8; 4],
    states: [u8; 4],
    state: u8,
}

const ROOT: u8 = 1;
const SCANNED: u8 = 2;
const OVERFLOW: u8 = 4;

fn side_of(c: Cell, n: Cell) -> Option<u8> {
    let d = [n[0] - c[0], n[1] - c[1]];
    crate::protocol::grid::SIDES.iter().position(|&s| s == d).map(|i| i as u8 + 1)
}

fn state_code(s: VertexState) -> u8 {
    s as u8
}

fn state_of(b: u8) -> VertexState {
    match b {
        0 => VertexState::Unexplored,
        1 => VertexState::UnderExploration,
        2 => VertexState::Explored,
        _ => VertexState::Pruned,
    }
}

impl Packed {
    fn pack(c: Cell, r: &Record) -> Option<Self> {
        let mut p = Packed {
            flags: (u8::from(r.root) * ROOT) | (u8::from(r.scanned) * SCANNED),
            state: state_code(r.state),
            ..Packed::default()
        };
        if let Some(q) = r.parent {
            p.parent = side_of(c, q)?;
        }
        for k in 0..4 {
            if let Some(ch) = r.children[k] {
                p.children[k] = side_of(c, ch)?;
            }
            p.states[k] = state_code(r.child_states[k]);
        }
        Some(p)
    }

    fn unpack(self, c: Cell) -> Record {
        let at = |s: u8| (s > 0).then(|| neighbour(c, usize::from(s - 1)));
        Record {
            parent: at(self.parent),
            root: self.flags & ROOT != 0,
            scanned: self.flags & SCANNED != 0,
            children: self.children.map(at),
            child_states: self.states.map(state_of),
            state: state_of(self.state),
        }
    }
}

/// The records on the cells: packed and dense over the region's bounding box (with a margin
/// of one cell), in a hash map beyond it (cells a noisy sensor took for region cells).
#[derive(Debug, Clone)]
struct Boards {
    min: Cell,
    width: usize,
    height: usize,
    dense: Vec<Packed>,
    sparse: CellMap<Record>,
}

impl Boards {
    fn new(roi: &GridRoi) -> Self {
        let [lo, hi] = roi.bounds();
        let min = [lo[0] - 1, lo[1] - 1];
        let width = (hi[1] - lo[1] + 3) as usize;
        let height = (hi[0] - lo[0] + 3) as usize;
        Self {
            min,
            width,
            height,
            dense: vec![Packed::default(); width * height],
            sparse: CellMap::default(),
        }
    }

    fn index(&self, c: Cell) -> Option<usize> {
        let (r, k) = (c[0] - self.min[0], c[1] - self.min[1]);
        (r >= 0 && k >= 0 && (r as usize) < self.height && (k as usize) < self.width)
            .then(|| r as usize * self.width + k as usize)
    }

    fn get(&self, c: Cell) -> Record {
        match self.index(c) {
            Some(i) if self.dense[i].flags & OVERFLOW == 0 => self.dense[i].unpack(c),
            _ => self.sparse.get(&c).copied().unwrap_or_default(),
        }
    }

    /// What a neighbour learns of `c`: whether it is in the tree, its parent and its state
    /// (read from the packed record, without unpacking the rest).
    fn tree_state(&self, c: Cell) -> NeighbourState {
        let (parent, root, state) = match self.index(c) {
            Some(i) if self.dense[i].flags & OVERFLOW == 0 => {
                let p = self.dense[i];
                let parent = (p.parent > 0).then(|| neighbour(c, usize::from(p.parent - 1)));
                (parent, p.flags & ROOT != 0, state_of(p.state))
            }
            _ => {
                let r = self.sparse.get(&c).copied().unwrap_or_default();
                (r.parent, r.root, r.state)
            }
        };
        if root || parent.is_some() {
            NeighbourState { in_tree: true, parent, state }
        } else {
            NeighbourState::default()
        }
    }

    fn set(&mut self, c: Cell, r: Record) {
        match (self.index(c), Packed::pack(c, &r)) {
            (Some(i), Some(p)) => {
                if self.dense[i].flags & OVERFLOW != 0 {
                    self.sparse.remove(&c);
                }
                self.dense[i] = p;
            }
            (Some(i), None) => {
                self.dense[i].flags |= OVERFLOW;
                self.sparse.insert(c, r);
            }
            (None, _) => {
                self.sparse.insert(c, r);
            }
        }
    }

    fn update(&mut self, c: Cell, f: impl FnOnce(&mut Record)) {
        let mut r = self.get(c);
        f(&mut r);
        self.set(c, r);
    }

    fn records(&self) -> CellMap<Record> {
        let blank = Record::default();
        let mut m: CellMap<Record> =
            self.sparse.iter().filter(|e| *e.1 != blank).map(|(c, r)| (*c, *r)).collect();
        for (i, p) in self.dense.iter().enumerate() {
            if *p != Packed::default() && p.flags & OVERFLOW == 0 {
                let c =
                    [self.min[0] + (i / self.width) as i32, self.min[1] + (i % self.width) as i32];
                m.insert(c, p.unpack(c));
            }
        }
        m
    }
}

/// The ground truth of a grid mission and the records robots leave on the cells (the only way
/// they learn from one another besides meeting).
#[derive(Debug, Clone)]
pub struct GridWorld {
    roi: GridRoi,
    drift: Drift,
    sensor: GridSensor,
    seed: u64,
    unit_times: std::cell::Cell<Option<(f64, [Option<f64>; 4])>>,
    boards: Boards,
    /// One bit per cell of the region's bounding box.
    visited: Vec<u64>,
}

impl GridWorld {
    /// A world whose root record is on the start cell.
    pub fn new(roi: GridRoi, drift: Drift, sensor: GridSensor, seed: u64) -> Self {
        let mut w = Self::without_root(roi, drift, sensor, seed);
        w.boards.set(w.roi.start(), Record { root: true, ..Record::default() });
        w
    }

    /// The same world, with its records replaced (to resume a mission).
    #[must_use]
    pub fn with_records(mut self, records: &CellMap<Record>) -> Self {
        self.boards = Boards::new(&self.roi);
        for (c, r) in records {
            self.boards.set(*c, *r);
        }
        self
    }

    /// Every record robots have left (cells nobody has touched have none).
    pub fn records(&self) -> CellMap<Record> {
        self.boards.records()
    }

    /// The region cells some robot has stood on (the simulator's own count, independent of
    /// what robots wrote).
    pub fn visited(&self) -> Vec<Cell> {
        self.roi.cells().iter().copied().filter(|&c| self.was_visited(c)).collect()
    }

    /// Whether some robot has stood on region cell `c`.
    pub fn was_visited(&self, c: Cell) -> bool {
        self.roi.index(c).is_some_and(|k| bit(&self.visited, k))
    }

    /// Restores the visited cells (to resume a mission).
    #[must_use]
    pub fn with_visited(mut self, visited: impl IntoIterator<Item = Cell>) -> Self {
        for c in visited {
            self.mark_visited(c);
        }
        self
    }

    fn mark_visited(&mut self, c: Cell) {
        if let Some(k) = self.roi.index(c)
            && self.roi.contains(c)
        {
            set_bit(&mut self.visited, k);
        }
    }

    /// The record on one cell (a blank one if nobody has touched it).
    pub fn record(&self, c: Cell) -> Record {
        self.boards.get(c)
    }

    /// A world with no root yet: a search must find the region first, and the first cell a
    /// robot reaches of it becomes the root (the field pipeline).
    pub fn without_root(roi: GridRoi, drift: Drift, sensor: GridSensor, seed: u64) -> Self {
        let boards = Boards::new(&roi);
        let bits = roi.bits.len();
        Self {
            roi,
            drift,
            sensor,
            seed,
            unit_times: std::cell::Cell::default(),
            boards,
            visited: vec![0; bits],
        }
    }

    /// The region (for the simulator and the metrics; strategies never get it).
    pub fn roi(&self) -> &GridRoi {
        &self.roi
    }

    /// The drift.
    pub fn drift(&self) -> Drift {
        self.drift
    }

    /// The sensor.
    pub fn sensor(&self) -> &GridSensor {
        &self.sensor
    }

    /// The time model robots of speed `cost.speed` share with this world.
    pub fn time_model(&self, cost: &CostModel) -> TimeModel {
        TimeModel {
            robot_speed: cost.speed,
            drift_speed: self.drift.speed,
            heading_deg: self.drift.heading_deg,
            cell_size: self.roi.cell_size(),
        }
    }

    /// The exact frame over cell `c`.
    pub fn truth_frame(&self, c: Cell) -> Frame {
        let mut f = Frame { centre: self.roi.contains(c), sides: [false; 4] };
        for (i, s) in f.sides.iter_mut().enumerate() {
            *s = self.roi.contains(neighbour(c, i));
        }
        f
    }
}

impl Arena for GridWorld {
    type Place = Cell;
    type Observation = GridObservation;
    type Context = GridContext;
    type Note = Record;

    fn travel(&self, from: &Cell, to: &Cell, _clock: f64, cost: &CostModel) -> Option<Leg> {
        let tm = self.time_model(cost);
        let step = [to[0] - from[0], to[1] - from[1]];
        let seconds = match crate::protocol::grid::SIDES.iter().position(|&d| d == step) {
            // One cell: the four unit times, computed once per robot speed.
            Some(i) => {
                let cached = self.unit_times.get().filter(|c| c.0 == cost.speed);
                let t = if let Some((_, t)) = cached {
                    t
                } else {
                    let t = std::array::from_fn(|k| {
                        tm.seconds([0, 0], crate::protocol::grid::SIDES[k])
                    });
                    self.unit_times.set(Some((cost.speed, t)));
                    t
                };
                t[i]?
            }
            None => tm.seconds(*from, *to)?,
        };
        Some(Leg { metres: seconds * cost.speed, seconds })
    }

    fn scan(&mut self, robot: usize, at: &Cell, clock: f64) -> Option<GridObservation> {
        let frames = match &self.sensor {
            GridSensor::Ideal => vec![self.truth_frame(*at)],
            GridSensor::Camera(model) => model.frames(&self.roi, *at, self.seed, robot, clock),
        };
        Some(GridObservation { cell: *at, frames })
    }

    fn meet(&mut self, at: &Cell, _clock: f64, group: &[usize]) -> GridContext {
        let present = group.to_vec();
        self.mark_visited(*at);
        let record = self.boards.get(*at);
        let neighbours = std::array::from_fn(|i| self.boards.tree_state(neighbour(*at, i)));
        GridContext { record, neighbours, present }
    }

    fn leave(&mut self, at: &Cell, note: Record) {
        let mut listed = false;
        self.boards.update(*at, |record| {
            listed = note.scanned && !record.scanned;
            record.merge(&note);
        });
        if listed {
            // Children join the tree when they are listed (section 4.1: "added as children of
            // the present cell ... unless those cells have been previously added").
            for c in note.children.iter().flatten() {
                self.boards.update(*c, |r| {
                    if r.parent.is_none() && !r.root {
                        r.parent = Some(*at);
                    }
                });
            }
        }
    }
}
