//! The grid family (multi-robot exploration of an unknown region of interest, Sung and
//! Tokekar): robots hover over unit cells, look down, and learn whether the cell below and its
//! four neighbours belong to the region. Robots learn from one another only where they stand.

use std::collections::{HashMap, HashSet};
use std::hash::{BuildHasherDefault, Hasher};

use serde::{Deserialize, Serialize};

/// A cell `[row, col]`: rows grow southwards, columns eastwards. Cell `[r, c]` is the unit
/// square whose centre is at `x = c`, `y = -r` (in cells) in the region's own frame.
pub type Cell = [i32; 2];

/// The four neighbours in the order every grid strategy lists them: north, east, south, west.
pub const SIDES: [Cell; 4] = [[-1, 0], [0, 1], [1, 0], [0, -1]];

/// The neighbour of `c` on side `i` of [`SIDES`].
pub fn neighbour(c: Cell, i: usize) -> Cell {
    [c[0] + SIDES[i][0], c[1] + SIDES[i][1]]
}

/// Flight times over a region that may translate: the robots fly at `robot_speed` (S_r) in
/// the fixed frame while the region moves at `drift_speed` (S_p < S_r) towards `heading_deg`
/// (counter-clockwise from east, the grid's +x). Both are known to the robots (section 3).
///
/// To cross a displacement `d` of the region's frame, the robot's velocity `v` must satisfy
/// `v − u ∥ d` with `|v| = S_r`, `u` the drift; the relative speed along `d̂` is then
/// `−u·d̂ + sqrt((u·d̂)² + S_r² − S_p²)`: `S_r − S_p` downstream (the paper's worst case),
/// `S_r + S_p` upstream, `sqrt(S_r² − S_p²)` across.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TimeModel {
    /// S_r, m/s.
    pub robot_speed: f64,
    /// S_p, m/s (0 for a static region).
    pub drift_speed: f64,
    /// The drift's heading, degrees counter-clockwise from east.
    pub heading_deg: f64,
    /// The side of a cell, metres.
    pub cell_size: f64,
}

impl TimeModel {
    /// Seconds to fly straight from the centre of `from` to the centre of `to` (both in the
    /// region's frame); `None` when the robot is not faster than the region.
    pub fn seconds(&self, from: Cell, to: Cell) -> Option<f64> {
        if !(self.robot_speed > self.drift_speed && self.drift_speed >= 0.0) {
            return None;
        }
        if from == to {
            return Some(0.0);
        }
        let dx = f64::from(to[1] - from[1]) * self.cell_size;
        let dy = -f64::from(to[0] - from[0]) * self.cell_size;
        let len = dx.hypot(dy);
        let h = self.heading_deg.to_radians();
        let a = self.drift_speed * (h.cos() * dx + h.sin() * dy) / len;
        let rel = -a + (a * a + self.robot_speed.powi(2) - self.drift_speed.powi(2)).sqrt();
        Some(len / rel)
    }
}

/// A fast, deterministic hasher for cells (a multiply–rotate mix; not for untrusted keys).
#[derive(Debug, Default, Clone, Copy)]
pub struct CellHasher(u64);

impl Hasher for CellHasher {
    fn finish(&self) -> u64 {
        let x = self.0;
        (x ^ (x >> 29)).wrapping_mul(0xbf58_476d_1ce4_e5b9) ^ (x >> 32)
    }
    fn write(&mut self, bytes: &[u8]) {
        for chunk in bytes.chunks(8) {
            let mut w = [0u8; 8];
            w[..chunk.len()].copy_from_slice(chunk);
            self.write_u64(u64::from_le_bytes(w));
        }
    }
    fn write_u64(&mut self, v: u64) {
        self.0 = (self.0.rotate_left(5) ^ v).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    fn write_i32(&mut self, v: i32) {
        self.write_u64(u64::from(v as u32));
    }
    fn write_usize(&mut self, v: usize) {
        self.write_u64(v as u64);
    }
}

/// A hash map keyed by cells.
pub type CellMap<V> = HashMap<Cell, V, BuildHasherDefault<CellHasher>>;
/// A hash set of cells.
pub type CellSet = HashSet<Cell, BuildHasherDefault<CellHasher>>;

/// What one camera frame says: whether the cell below and each neighbour (in [`SIDES`]
/// order) belong to the region.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Frame {
    /// The cell below.
    pub centre: bool,
    /// North, east, south, west.
    pub sides: [bool; 4],
}

/// What one scan returns: the frames taken over a cell (one for an ideal sensor, five in the
/// paper's field pipeline).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct GridObservation {
    /// The cell below.
    pub cell: Cell,
    /// The frames, in the order taken.
    pub frames: Vec<Frame>,
}

impl GridObservation {
    /// The vote over the frames: a cell is positive when more than half of them say so (3 of
    /// 5 in the paper's field experiment; 1 of 1 for a single frame).
    pub fn vote(&self) -> Frame {
        let n = self.frames.len();
        let majority = |count: usize| 2 * count > n;
        let mut v = Frame {
            centre: majority(self.frames.iter().filter(|f| f.centre).count()),
            sides: [false; 4],
        };
        for (i, s) in v.sides.iter_mut().enumerate() {
            *s = majority(self.frames.iter().filter(|f| f.sides[i]).count());
        }
        v
    }
}

/// A map built conservatively from votes (the paper's section 7): a cell once marked positive
/// is never reversed, and a later positive overrides an earlier negative.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Marks {
    /// Cell → marked as part of the region.
    #[serde(with = "sorted_map")]
    pub cells: CellMap<bool>,
}

impl Marks {
    /// Marks what one scan's vote says.
    pub fn absorb(&mut self, obs: &GridObservation) {
        let v = obs.vote();
        self.mark(obs.cell, v.centre);
        for (i, &s) in v.sides.iter().enumerate() {
            self.mark(neighbour(obs.cell, i), s);
        }
    }

    /// Marks one cell: positive wins over negative, whatever the order.
    pub fn mark(&mut self, c: Cell, positive: bool) {
        let m = self.cells.entry(c).or_insert(false);
        *m |= positive;
    }

    /// The cells marked positive, sorted.
    pub fn positive(&self) -> Vec<Cell> {
        let mut v: Vec<Cell> = self.cells.iter().filter(|e| *e.1).map(|e| *e.0).collect();
        v.sort_unstable();
        v
    }
}

/// The state of a vertex of the exploration tree (Algorithm 1), in the order it only ever
/// advances.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum VertexState {
    /// No robot has visited it.
    #[default]
    Unexplored,
    /// Visited, but some leaf below it is not.
    UnderExploration,
    /// It and everything below it are visited.
    Explored,
    /// Not a child here after all: a robot found it already in the tree under another parent
    /// (moving to it would have closed a cycle). Treated as explored.
    Pruned,
}

impl VertexState {
    /// Whether nothing is left to do below it.
    pub fn finished(self) -> bool {
        self >= VertexState::Explored
    }
}

/// What is known of one vertex of the tree: the record robots leave on the vertex and read
/// from it. Records only grow (states advance, a claim and a scan are written once), so
/// merging two of them never loses work.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Record {
    /// The parent this vertex was claimed from (`None` for the root, or not yet claimed).
    pub parent: Option<Cell>,
    /// Whether the vertex is the root.
    pub root: bool,
    /// Whether its neighbours have been observed (its children are known).
    pub scanned: bool,
    /// Its children (at most three, four at the root), kept binary with dummy vertices joined
    /// by edges of length 0 (Algorithm 1, line 16): the vertex has child slot 0 and a dummy
    /// vertex, the dummy has slot 1 and a second dummy, which has slots 2 and 3. A dummy with
    /// one open child is that child.
    pub children: [Option<Cell>; 4],
    /// The state of each child, as known here.
    pub child_states: [VertexState; 4],
    /// The vertex's own state.
    pub state: VertexState,
}

impl Record {
    /// What a robot coming back from `child` tells: its state (and nothing else).
    pub fn news(child: Cell, state: VertexState) -> Self {
        let mut r = Record::default();
        r.children[0] = Some(child);
        r.child_states[0] = state;
        r
    }

    /// Merges what another robot knows of the same vertex (children's states by cell).
    pub fn merge(&mut self, other: &Record) {
        if self.parent.is_none() {
            self.parent = other.parent;
        }
        self.root |= other.root;
        if !self.scanned && other.scanned {
            self.scanned = true;
            self.children = other.children;
        }
        for (c, &st) in other.children.iter().zip(&other.child_states) {
            if let Some(c) = c
                && let Some(k) = self.slot(*c)
            {
                self.child_states[k] = self.child_states[k].max(st);
            }
        }
        self.state = self.state.max(other.state);
    }

    /// The slot of child `c`, if it is one.
    pub fn slot(&self, c: Cell) -> Option<usize> {
        self.children.iter().position(|&x| x == Some(c))
    }
}

/// What a robot learns of a neighbouring cell at a vertex (Algorithm 1, line 7: "communicate
/// … to update the state of N(v)").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct NeighbourState {
    /// Whether the cell is in the tree already (claimed, or the root).
    pub in_tree: bool,
    /// The vertex it was claimed from.
    pub parent: Option<Cell>,
    /// Its state.
    pub state: VertexState,
}

/// What a robot learns where it stands: the vertex's record (with any claim made by the group
/// that just arrived), the state of its four neighbours, and the robots standing there with it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct GridContext {
    /// The record of the vertex.
    pub record: Record,
    /// The four neighbours, in [`SIDES`] order.
    pub neighbours: [NeighbourState; 4],
    /// The robots that stand here now and act together, by index, ascending.
    pub present: Vec<usize>,
}

/// Serialises a cell-keyed map as a list sorted by cell, so that the same state always gives
/// the same bytes whatever the map's history.
pub mod sorted_map {
    use super::{Cell, CellMap};
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    /// Writes the map as `[[cell, value], ...]` sorted by cell.
    ///
    /// # Errors
    /// The serialiser's.
    pub fn serialize<V: Serialize, S: Serializer>(m: &CellMap<V>, s: S) -> Result<S::Ok, S::Error> {
        let mut v: Vec<(&Cell, &V)> = m.iter().collect();
        v.sort_unstable_by_key(|e| *e.0);
        v.serialize(s)
    }

    /// Reads what [`serialize`] wrote.
    ///
    /// # Errors
    /// The deserialiser's.
    pub fn deserialize<'de, V: Deserialize<'de>, D: Deserializer<'de>>(
        d: D,
    ) -> Result<CellMap<V>, D::Error> {
        let v: Vec<(Cell, V)> = Vec::deserialize(d)?;
        Ok(v.into_iter().collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn relative_speeds() {
        let tm = TimeModel { robot_speed: 2.5, drift_speed: 1.0, heading_deg: 0.0, cell_size: 1.0 };
        // Downstream (east, with the drift): S_r − S_p; upstream: S_r + S_p; across: sqrt.
        assert!((tm.seconds([0, 0], [0, 1]).unwrap() - 1.0 / 1.5).abs() < 1e-12);
        assert!((tm.seconds([0, 0], [0, -1]).unwrap() - 1.0 / 3.5).abs() < 1e-12);
        assert!((tm.seconds([0, 0], [1, 0]).unwrap() - 1.0 / 5.25f64.sqrt()).abs() < 1e-12);
        let slow = TimeModel { robot_speed: 1.0, drift_speed: 1.0, ..tm };
        assert_eq!(slow.seconds([0, 0], [0, 1]), None);
    }

    #[test]
    fn three_of_five_vote() {
        let yes = Frame { centre: true, sides: [true, false, true, false] };
        let no = Frame::default();
        let obs = GridObservation { cell: [0, 0], frames: vec![yes, yes, no, yes, no] };
        assert_eq!(obs.vote(), yes);
        let obs = GridObservation { cell: [0, 0], frames: vec![yes, yes, no, no, no] };
        assert_eq!(obs.vote(), no);
    }

    #[test]
    fn marks_are_conservative() {
        let mut m = Marks::default();
        m.mark([1, 1], true);
        m.mark([1, 1], false);
        m.mark([2, 2], false);
        m.mark([2, 2], true);
        m.mark([3, 3], false);
        assert_eq!(m.positive(), vec![[1, 1], [2, 2]]);
    }

    #[test]
    fn records_only_grow() {
        let mut a = Record { parent: Some([0, 0]), ..Record::default() };
        let mut b = Record {
            parent: Some([5, 5]),
            scanned: true,
            children: [Some([1, 1]), None, None, None],
            child_states: [
                VertexState::Explored,
                VertexState::Unexplored,
                VertexState::Unexplored,
                VertexState::Unexplored,
            ],
            state: VertexState::UnderExploration,
            root: false,
        };
        a.merge(&b);
        assert_eq!(a.parent, Some([0, 0]), "the first claim stays");
        assert_eq!(a.child_states[0], VertexState::Explored);
        b.child_states[0] = VertexState::UnderExploration;
        a.merge(&b);
        assert_eq!(a.child_states[0], VertexState::Explored, "a state never goes back");
    }
}
