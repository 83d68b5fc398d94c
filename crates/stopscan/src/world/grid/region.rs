//! The region of interest and how it is built: validated from a cell set, grown at random
//! (Eden growth, as the paper's Fig. 7 (a)), or made from an arbitrary shape through its outer
//! grid approximation (section 5), with C_out, C_in and the IoU of a map against it.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use crate::algorithm::region::clip_to_box;
use crate::geometry::{Domain, signed_area_of};
use crate::kernel::Point;
use crate::protocol::grid::{Cell, CellMap, CellSet, neighbour};

/// Bit `k` of a bitmap.
pub(super) fn bit(bits: &[u64], k: usize) -> bool {
    bits[k / 64] >> (k % 64) & 1 == 1
}

/// Sets bit `k` of a bitmap.
pub(super) fn set_bit(bits: &mut [u64], k: usize) {
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

    /// The index of `c` in the bitmap over the bounding box, if it lies in that box.
    pub(super) fn index(&self, c: Cell) -> Option<usize> {
        if c[0] < self.min[0] || c[0] > self.max[0] || c[1] < self.min[1] || c[1] > self.max[1] {
            return None;
        }
        let w = (self.max[1] - self.min[1] + 1) as usize;
        Some((c[0] - self.min[0]) as usize * w + (c[1] - self.min[1]) as usize)
    }

    /// The number of words of a bitmap over the bounding box (one bit per cell).
    pub(super) fn bitmap_words(&self) -> usize {
        self.bits.len()
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
