//! The field experiment's first mode: sweep a bounding box that is known to contain part of
//! the region, lawn-mower fashion, until the region is first seen; then the inner strategy
//! (Algorithm 1) starts from the first region cell, and when it is done the robot flies back to
//! where it was launched.

use serde::{Deserialize, Serialize};

use super::{GridFeedback, GridStrategy};
use crate::protocol::Action;
use crate::protocol::grid::{Cell, GridContext, Record, neighbour};

#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
enum Phase {
    /// Sweeping; the index of the next lawn cell.
    Search(usize),
    /// Flying to the first region cell seen from the sweep.
    Entering,
    /// The inner strategy runs.
    Inner,
    /// Flying back to the launch cell.
    Homing,
    /// Finished.
    Done,
}

/// The lawn of a box of cells from `min` to `max` (inclusive): lanes three cells apart, the
/// first one row in from the top (each pass sees its own row and the rows either side), the
/// last no further than the box's last row, alternating east and west. Cells are computed from
/// their index, so a lawn takes no memory whatever the box.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
struct Lawn {
    min: Cell,
    max: Cell,
}

impl Lawn {
    /// Lanes and cells per lane.
    fn shape(self) -> (i64, i64) {
        let rows = i64::from(self.max[0]) - i64::from(self.min[0]);
        // Lane k lies on row min + 1 + 3k (capped at max); the last is the first at or below
        // max − 1.
        let lanes = ((rows - 2).max(0) + 2) / 3 + 1;
        (lanes, i64::from(self.max[1]) - i64::from(self.min[1]) + 1)
    }

    /// The `i`-th cell of the sweep, if the sweep has that many.
    fn cell(self, i: usize) -> Option<Cell> {
        let (lanes, width) = self.shape();
        let i = i64::try_from(i).ok()?;
        let lane = i / width;
        if lane >= lanes {
            return None;
        }
        let row = (i64::from(self.min[0]) + 1 + 3 * lane).min(i64::from(self.max[0]));
        let pos = i % width;
        let col =
            if lane % 2 == 0 { i64::from(self.min[1]) + pos } else { i64::from(self.max[1]) - pos };
        Some([row as i32, col as i32])
    }
}

/// A lawn-mowing search around an inner strategy. With no box, it passes everything through.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LawnMower<S> {
    inner: S,
    /// A fresh inner strategy, for a new start after a false alarm.
    fresh: Option<Box<S>>,
    lawn: Option<Lawn>,
    /// The next lawn cell when the search goes on.
    resume_at: usize,
    /// Whether the region was confirmed below the robot since the inner strategy started.
    confirmed: bool,
    phase: Phase,
    launch: Option<Cell>,
    entry: Option<Cell>,
    /// Whether the sweep ended without seeing the region.
    pub not_found: bool,
}

impl<S> LawnMower<S> {
    /// No search: the robot starts on the region.
    pub fn none(inner: S) -> Self {
        Self {
            inner,
            fresh: None,
            lawn: None,
            resume_at: 0,
            confirmed: true,
            phase: Phase::Inner,
            launch: None,
            entry: None,
            not_found: false,
        }
    }

    /// Sweep the box of cells from `min` to `max` (inclusive): lanes three cells apart
    /// (each pass sees its own row and the rows either side), alternating in direction.
    pub fn sweep(inner: S, min: Cell, max: Cell) -> Self
    where
        S: Clone,
    {
        Self {
            fresh: Some(Box::new(inner.clone())),
            inner,
            lawn: Some(Lawn { min, max }),
            resume_at: 0,
            confirmed: false,
            phase: Phase::Search(0),
            launch: None,
            entry: None,
            not_found: false,
        }
    }

    /// The inner strategy.
    pub fn inner(&self) -> &S {
        &self.inner
    }

    /// Whether the robot is still searching for the region.
    pub fn searching(&self) -> bool {
        matches!(self.phase, Phase::Search(_) | Phase::Entering)
    }

    fn next_lawn_cell(&mut self, i: usize) -> Action<Cell> {
        if let Some(c) = self.lawn.and_then(|l| l.cell(i)) {
            self.phase = Phase::Search(i + 1);
            Action::MoveTo { to: c }
        } else {
            self.not_found = true;
            self.home()
        }
    }

    fn after_inner(&mut self, a: Action<Cell>) -> Action<Cell> {
        match a {
            Action::Done
                if self.launch.is_some() && self.launch != self.entry && self.lawn.is_some() =>
            {
                self.home()
            }
            Action::Done => {
                self.phase = Phase::Done;
                Action::Done
            }
            a => a,
        }
    }

    fn home(&mut self) -> Action<Cell> {
        self.phase = Phase::Homing;
        match self.launch {
            Some(l) => Action::MoveTo { to: l },
            None => Action::Done,
        }
    }
}

impl<S: GridStrategy + Clone> GridStrategy for LawnMower<S> {
    fn name(&self) -> &str {
        self.inner.name()
    }

    fn act(&mut self, feedback: &GridFeedback, context: &GridContext) -> Action<Cell> {
        if let GridFeedback::Start { at: c } = feedback {
            self.launch.get_or_insert(*c);
        }
        match self.phase {
            Phase::Search(i) => match feedback {
                GridFeedback::Start { .. } | GridFeedback::Arrived => Action::Scan,
                // The sweep's cell cannot be reached: drop it and sweep on.
                GridFeedback::MoveFailed { .. } => self.next_lawn_cell(i),
                GridFeedback::Scanned(obs) => {
                    let vote = obs.vote();
                    self.resume_at = i;
                    if vote.centre {
                        self.phase = Phase::Inner;
                        self.entry = Some(obs.cell);
                        self.confirmed = true;
                        return self.inner.act(&GridFeedback::Start { at: obs.cell }, context);
                    }
                    if let Some(side) = vote.sides.iter().position(|&s| s) {
                        let to = neighbour(obs.cell, side);
                        self.phase = Phase::Entering;
                        self.entry = Some(to);
                        self.confirmed = false;
                        return Action::MoveTo { to };
                    }
                    self.next_lawn_cell(i)
                }
            },
            // The cell the vote pointed to cannot be reached: sweep on.
            Phase::Entering if matches!(feedback, GridFeedback::MoveFailed { .. }) => {
                self.next_lawn_cell(self.resume_at)
            }
            Phase::Entering => {
                self.phase = Phase::Inner;
                let entry = self.entry.unwrap_or_default();
                self.inner.act(&GridFeedback::Start { at: entry }, context)
            }
            Phase::Inner => {
                if let GridFeedback::Scanned(obs) = feedback {
                    self.confirmed |= obs.vote().centre;
                }
                match self.inner.act(feedback, context) {
                    // A false alarm: the cell entered was not region after all and nothing
                    // around it was. Sweep on with a fresh inner strategy.
                    Action::Done if !self.confirmed && self.fresh.is_some() => {
                        if let Some(f) = &self.fresh {
                            self.inner = S::clone(f);
                        }
                        self.next_lawn_cell(self.resume_at)
                    }
                    a => self.after_inner(a),
                }
            }
            Phase::Homing | Phase::Done => {
                self.phase = Phase::Done;
                Action::Done
            }
        }
    }
    fn report(&mut self, feedback: &GridFeedback) -> Option<Record> {
        if self.phase == Phase::Inner { self.inner.report(feedback) } else { None }
    }

    fn note(&mut self) -> Option<&Record> {
        if matches!(self.phase, Phase::Inner | Phase::Homing) { self.inner.note() } else { None }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The lawn as it was first written: every cell listed.
    fn listed(min: Cell, max: Cell) -> Vec<Cell> {
        let mut lawn = Vec::new();
        let mut r = min[0] + 1;
        let mut east = true;
        loop {
            let row = r.min(max[0]);
            let cols: Vec<i32> =
                if east { (min[1]..=max[1]).collect() } else { (min[1]..=max[1]).rev().collect() };
            lawn.extend(cols.into_iter().map(|c| [row, c]));
            if row >= max[0] - 1 {
                break;
            }
            r += 3;
            east = !east;
        }
        lawn
    }

    #[test]
    fn the_computed_lawn_is_the_listed_one() {
        for (r0, r1) in [(0, 0), (0, 1), (0, 2), (0, 3), (0, 4), (-5, 7), (-12, 0), (3, 20)] {
            for (c0, c1) in [(0, 0), (-3, 4), (2, 9)] {
                let (min, max) = ([r0, c0], [r1, c1]);
                let lawn = Lawn { min, max };
                let computed: Vec<Cell> = (0..).map_while(|i| lawn.cell(i)).collect();
                assert_eq!(computed, listed(min, max), "{min:?}..{max:?}");
            }
        }
        // A box far too large to list is still swept cell by cell.
        let huge = Lawn { min: [-1_000_000, -1_000_000], max: [1_000_000, 1_000_000] };
        assert_eq!(huge.cell(0), Some([-999_999, -1_000_000]));
        assert_eq!(huge.cell(2_000_001), Some([-999_996, 1_000_000]));
    }
}
