//! Multi-robot exploration of an unknown region of interest (Sung and Tokekar): Algorithm 1,
//! the recursive depth-first search of a binary tree of cells with the robots split as equally
//! as possible, and the two layers the field experiment needed around it: a lawn-mowing search
//! until the region is first seen, and a battery that forces a return, a swap and a resume.
//!
//! # Communication
//! Robots learn from one another only at the vertex they stand on. Robots standing on the same
//! vertex at the same time act together: each learns who the others are (to split the group)
//! and the news each brings back from below. Each vertex keeps the record that robots left on it
//! (its parent, its children and their states): the bookkeeping devices of Brass et al. and Das
//! et al., which the paper cites. At a vertex a robot also learns the state of the four
//! neighbouring cells (Algorithm 1, line 7: "communicate … to update the state of N(v)"): whether
//! each is in the tree, its parent and its state; the children it lists join the tree at once.
//! Nobody has the whole tree: a robot carries only its path back to the root. With meetings
//! alone, two robots in neighbouring branches would each explore the other's cells (branches
//! touch wherever the region has a cycle) and the Lemma 1 bound would not hold.
//!
//! - `dfs`: [`RecursiveDfs`], Algorithm 1;
//! - `search`: [`LawnMower`], the lawn-mowing search until the region is first seen;
//! - `battery`: [`Battery`]: return, swap and resume.

mod battery;
mod dfs;
mod search;

pub use battery::Battery;
pub use dfs::RecursiveDfs;
pub use search::LawnMower;

use super::{Entry, Registry};
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

/// How a grid registry entry builds the strategy of robot `robot` (its index in the team).
pub type GridBuild = fn(robot: usize) -> RecursiveDfs;

/// Algorithm 1, the grid family's strategy: every mission robot runs it (inside its search
/// and battery layers).
pub const ALGORITHM_1: Entry<GridBuild> = Entry {
    name: "recursive_dfs",
    summary: "Algorithm 1: multi-robot recursive depth-first search over a binary tree of cells",
    build: RecursiveDfs::new,
};

/// Every grid strategy: names, help text and construction.
pub const REGISTRY: Registry<GridBuild> = Registry::new(&[ALGORITHM_1]);
