//! The grid world: a region of interest (ROI) made of unit cells, static or translating, and
//! the sensors that tell a robot hovering over a cell whether it and its four neighbours belong
//! to the region (Sung and Tokekar, sections 3–5 and 7).
//!
//! - [`region`]: the region itself, [`GridRoi`], and how it is built (cell sets, random
//!   growth, a shape's outer grid approximation);
//! - `records`: the records robots leave on the cells, packed 11 bytes a cell;
//! - [`camera`]: the synthetic downward camera of the field pipeline;
//! - here: [`GridWorld`], the ground truth of a mission (region, [`Drift`], [`GridSensor`],
//!   the records and the cells visited).

pub mod camera;
mod records;
pub mod region;

use serde::{Deserialize, Serialize};

use crate::protocol::grid::{Cell, CellMap, Frame, GridContext, Record, neighbour};
use crate::protocol::{CostModel, grid::TimeModel};
use records::Boards;
pub use region::{GridRoi, InvalidRoi};
use region::{bit, set_bit};

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

/// The ground truth of a grid mission and the records robots leave on the cells (the only way
/// they learn from one another besides meeting).
#[derive(Debug, Clone)]
pub struct GridWorld {
    roi: GridRoi,
    drift: Drift,
    sensor: GridSensor,
    seed: u64,
    unit_times: std::cell::Cell<Option<(f64, [Option<f64>; 4])>>,
    board: Blackboard,
    /// One bit per cell of the region's bounding box.
    visited: Vec<u64>,
}

impl GridWorld {
    /// A world whose root record is on the start cell.
    pub fn new(roi: GridRoi, drift: Drift, sensor: GridSensor, seed: u64) -> Self {
        let mut w = Self::without_root(roi, drift, sensor, seed);
        w.board.plant_root(w.roi.start());
        w
    }

    /// The same world, with its records replaced (to resume a mission).
    #[must_use]
    pub fn with_records(mut self, records: &CellMap<Record>) -> Self {
        self.board = Blackboard::over(&self.roi, records);
        self
    }

    /// Every record robots have left (cells nobody has touched have none).
    pub fn records(&self) -> CellMap<Record> {
        self.board.records()
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
        self.board.record(c)
    }

    /// A world with no root yet: a search must find the region first, and the first cell a
    /// robot reaches of it becomes the root (the field pipeline).
    pub fn without_root(roi: GridRoi, drift: Drift, sensor: GridSensor, seed: u64) -> Self {
        let board = Blackboard::over(&roi, &CellMap::default());
        let bits = roi.bitmap_words();
        Self {
            roi,
            drift,
            sensor,
            seed,
            unit_times: std::cell::Cell::default(),
            board,
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

    /// The seconds of a one-cell move towards each side (`None` where the drift makes it
    /// impossible), computed once per robot speed: the team loop prices a move at every step.
    pub(crate) fn unit_seconds(&self, cost: &CostModel) -> [Option<f64>; 4] {
        let tm = self.time_model(cost);
        let cached = self.unit_times.get().filter(|c| c.0 == cost.speed);
        if let Some((_, t)) = cached {
            t
        } else {
            let t = std::array::from_fn(|k| tm.seconds([0, 0], crate::protocol::grid::SIDES[k]));
            self.unit_times.set(Some((cost.speed, t)));
            t
        }
    }

    /// What the sensor of robot `robot` returns over cell `at` at time `clock`: the exact
    /// frame, or the camera's frames.
    pub(crate) fn sense(&self, robot: usize, at: Cell, clock: f64) -> Vec<Frame> {
        match &self.sensor {
            GridSensor::Ideal => vec![self.truth_frame(at)],
            GridSensor::Camera(model) => model.frames(&self.roi, at, self.seed, robot, clock),
        }
    }

    /// Robots `group` stand on `at`: the cell counts as visited, and they read its record and
    /// what the four neighbouring cells' records say of the tree.
    pub(crate) fn arrive(&mut self, at: Cell, group: &[usize]) -> GridContext {
        self.mark_visited(at);
        self.board.context(at, group)
    }

    /// A robot merges `note` into the record on `at` (see [`Blackboard::write`]).
    pub(crate) fn write(&mut self, at: Cell, note: Record) {
        self.board.write(at, note);
    }
}

/// The records robots leave on the cells: the only way they learn from one another besides
/// meeting. A [`GridWorld`] keeps one over its region; a server whose robots report over a
/// protocol keeps one over cells it learns of as they come ([`Blackboard::unbounded`]).
#[derive(Debug, Clone)]
pub struct Blackboard {
    boards: Boards,
}

impl Blackboard {
    /// A board for a region nobody knows yet: every record lives in a hash map.
    pub fn unbounded() -> Self {
        Self { boards: Boards::unbounded() }
    }

    /// A board packed over `roi`'s bounding box, holding `records`.
    fn over(roi: &GridRoi, records: &CellMap<Record>) -> Self {
        let mut boards = Boards::new(roi);
        for (c, r) in records {
            boards.set(*c, *r);
        }
        Self { boards }
    }

    /// Marks `c` as the root of the tree.
    pub fn plant_root(&mut self, c: Cell) {
        self.boards.update(c, |r| r.root = true);
    }

    /// The record on one cell (a blank one if nobody has touched it).
    pub fn record(&self, c: Cell) -> Record {
        self.boards.get(c)
    }

    /// Every record robots have left (cells nobody has touched have none).
    pub fn records(&self) -> CellMap<Record> {
        self.boards.records()
    }

    /// What robots `group` learn standing on `at`: its record and what the four neighbouring
    /// cells' records say of the tree.
    pub fn context(&self, at: Cell, group: &[usize]) -> GridContext {
        let record = self.boards.get(at);
        let neighbours = std::array::from_fn(|i| self.boards.tree_state(neighbour(at, i)));
        GridContext { record, neighbours, present: group.to_vec() }
    }

    /// A robot merges `note` into the record on `at`; the children a first scan lists join
    /// the tree.
    pub fn write(&mut self, at: Cell, note: Record) {
        let mut listed = false;
        self.boards.update(at, |record| {
            listed = note.scanned && !record.scanned;
            record.merge(&note);
        });
        if listed {
            // Children join the tree when they are listed (section 4.1: "added as children of
            // the present cell ... unless those cells have been previously added").
            for c in note.children.iter().flatten() {
                self.boards.update(*c, |r| {
                    if r.parent.is_none() && !r.root {
                        r.parent = Some(at);
                    }
                });
            }
        }
    }
}
