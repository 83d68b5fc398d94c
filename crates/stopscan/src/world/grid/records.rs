//! The records robots leave on the cells, packed: 11 bytes a cell, dense over the region's
//! bounding box, with an overflow map for records that do not pack and for cells beyond it.

use super::GridRoi;
use crate::protocol::grid::{Cell, CellMap, NeighbourState, Record, VertexState, neighbour};

/// A record packed into 11 bytes: parents and children are always 4-neighbours, so each is a
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
pub(super) struct Boards {
    min: Cell,
    width: usize,
    height: usize,
    dense: Vec<Packed>,
    sparse: CellMap<Record>,
}

impl Boards {
    pub(super) fn new(roi: &GridRoi) -> Self {
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

    /// Boards with no dense part: every record in the hash map.
    pub(super) fn unbounded() -> Self {
        Self { min: [0, 0], width: 0, height: 0, dense: Vec::new(), sparse: CellMap::default() }
    }

    fn index(&self, c: Cell) -> Option<usize> {
        let (r, k) = (c[0] - self.min[0], c[1] - self.min[1]);
        (r >= 0 && k >= 0 && (r as usize) < self.height && (k as usize) < self.width)
            .then(|| r as usize * self.width + k as usize)
    }

    pub(super) fn get(&self, c: Cell) -> Record {
        match self.index(c) {
            Some(i) if self.dense[i].flags & OVERFLOW == 0 => self.dense[i].unpack(c),
            _ => self.sparse.get(&c).copied().unwrap_or_default(),
        }
    }

    /// What a neighbour learns of `c`: whether it is in the tree, its parent and its state
    /// (read from the packed record, without unpacking the rest).
    pub(super) fn tree_state(&self, c: Cell) -> NeighbourState {
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

    pub(super) fn set(&mut self, c: Cell, r: Record) {
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

    pub(super) fn update(&mut self, c: Cell, f: impl FnOnce(&mut Record)) {
        let mut r = self.get(c);
        f(&mut r);
        self.set(c, r);
    }

    pub(super) fn records(&self) -> CellMap<Record> {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn roi() -> GridRoi {
        GridRoi::new("l", [[0, 0], [0, 1], [1, 1]], [0, 0], 1.0).unwrap()
    }

    /// A record with every field in use: parent and children on 4-neighbours of `c`.
    fn full(c: Cell) -> Record {
        Record {
            parent: Some(neighbour(c, 0)),
            root: false,
            scanned: true,
            children: [Some(neighbour(c, 1)), Some(neighbour(c, 2)), None, Some(neighbour(c, 3))],
            child_states: [
                VertexState::Explored,
                VertexState::UnderExploration,
                VertexState::Unexplored,
                VertexState::Pruned,
            ],
            state: VertexState::UnderExploration,
        }
    }

    #[test]
    fn neighbour_records_pack_and_unpack_unchanged() {
        let c = [3, -2];
        assert_eq!(Packed::pack(c, &full(c)).unwrap().unpack(c), full(c));
        let root = Record { root: true, ..Record::default() };
        assert_eq!(Packed::pack(c, &root).unwrap().unpack(c), root);
        // A blank record packs to the blank cell, which `records` leaves out.
        assert_eq!(Packed::pack(c, &Record::default()).unwrap(), Packed::default());
        assert_eq!(std::mem::size_of::<Packed>(), 11, "the documented size");
    }

    #[test]
    fn records_that_do_not_pack_overflow_and_come_back() {
        let mut b = Boards::new(&roi());
        let c = [0, 1];
        let i = b.index(c).unwrap();
        // A parent two cells away is no side: the record goes to the overflow map.
        let far = Record { parent: Some([0, 3]), scanned: true, ..Record::default() };
        assert!(Packed::pack(c, &far).is_none());
        b.set(c, far);
        assert_ne!(b.dense[i].flags & OVERFLOW, 0);
        assert_eq!(b.get(c), far);
        assert_eq!(
            b.tree_state(c),
            NeighbourState { in_tree: true, parent: Some([0, 3]), state: VertexState::Unexplored }
        );
        assert_eq!(b.records().get(&c), Some(&far));
        // Updating it keeps it in the overflow map.
        b.update(c, |r| r.state = VertexState::Explored);
        assert_eq!(b.get(c).state, VertexState::Explored);
        assert_eq!(b.sparse.len(), 1);
        // A record that packs again leaves the overflow map.
        b.set(c, full(c));
        assert_eq!(b.dense[i].flags & OVERFLOW, 0);
        assert!(b.sparse.is_empty());
        assert_eq!(b.get(c), full(c));
        assert_eq!(b.records().len(), 1);
    }

    #[test]
    fn cells_beyond_the_box_live_in_the_sparse_map() {
        let mut b = Boards::new(&roi());
        // The box has a margin of one cell around the region.
        assert!(b.index([-1, -1]).is_some() && b.index([2, 2]).is_some());
        assert!(b.index([5, 5]).is_none() && b.index([-2, 0]).is_none());
        b.set([5, 5], full([5, 5]));
        assert_eq!(b.get([5, 5]), full([5, 5]));
        b.update([5, 5], |r| r.state = VertexState::Explored);
        assert_eq!(b.get([5, 5]).state, VertexState::Explored);
        assert!(b.tree_state([5, 5]).in_tree);
        // Untouched cells read blank and are not listed.
        assert_eq!(b.get([0, 0]), Record::default());
        assert_eq!(b.tree_state([0, 0]), NeighbourState::default());
        assert_eq!(b.records().keys().copied().collect::<Vec<_>>(), [[5, 5]]);
    }
}
