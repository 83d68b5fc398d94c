//! Multi-robot exploration of an unknown region of interest (Sung and Tokekar): Algorithm 1,
//! the recursive depth-first search of a binary tree of cells with the robots split as equally
//! as possible, and the two layers the field experiment needed around it: a lawn-mowing search
//! until the region is first seen, and a battery that forces a return, a swap and a resume.
//!
//! # Communication
//! Robots learn from one another only through the vertex they stand on. Robots standing on
//! the same vertex at the same time act together: each learns who the others are (to split the
//! group). Each vertex also keeps the record that robots left on it (its parent, its children
//! and their states): the bookkeeping devices of Brass et al. and Das et al., which the paper
//! cites. Nobody has the whole tree: a robot reads one record, the one under it. Without the
//! records, two robots in neighbouring branches would each explore the other's cells (their
//! branches touch wherever the region has a cycle) and the Lemma 1 bound would not hold; with
//! them, a robot that reaches a cell already claimed from another vertex learns it there and
//! goes back (Algorithm 1's cycle test, lines 9–11), which costs one edge each way.

mod battery;
mod dfs;
mod search;

pub use battery::Battery;
pub use dfs::RecursiveDfs;
pub use search::LawnMower;

use crate::protocol::grid::{Cell, GridContext, GridObservation, Record};
use crate::protocol::{Action, Feedback};

/// What the driver tells a grid strategy before asking for its next action.
pub type GridFeedback = Feedback<Cell, GridObservation>;

/// An online grid-exploration strategy: one robot of a team.
pub trait GridStrategy {
    /// The registry name.
    fn name(&self) -> &str;
    /// The next action: fly straight to a cell, scan (observe the cell below and its four
    /// neighbours), or done.
    fn act(&mut self, feedback: &GridFeedback, context: &GridContext) -> Action<Cell>;
    /// What the robot leaves on the cell it stands on after its last action.
    fn note(&mut self) -> Option<&Record>;
    /// What the robot tells the others as it arrives, before anyone acts: the state of the
    /// child it comes back from.
    fn report(&mut self, feedback: &GridFeedback) -> Option<Record>;
}

/// The strategy of one robot of a mission: Algorithm 1, inside an optional search, inside an
/// optional battery.
pub type MissionRobot = Battery<LawnMower<RecursiveDfs>>;

/// `(name, summary)` of the grid strategies.
pub const REGISTRY: &[(&str, &str)] = &[(
    "recursive_dfs",
    "Algorithm 1: multi-robot recursive depth-first search over a binary tree of cells",
)];
