//! Online exploration of unknown polygons with discrete visibility (Ghosh, Burdick,
//! Bhattacharya, Sarkar). Strategies are fed only observations: scans with their labelled
//! visibility regions.
//!
//! - `known`: what every polygon strategy knows (views, windows, the tree of moves) and the one
//!   feedback loop they share;
//! - `depth_first`: [`DepthFirst`], the paper's algorithm (at most r + 1 scans);
//! - `range_limited`: [`RangeLimited`], the paper's algorithm with a range restriction
//!   (Lemma 4);
//! - `nearest_frontier`: [`NearestFrontier`], the nearest open window by travel;
//! - `greedy_nbv`: [`GreedyNbv`], the most predicted area per second of cost.

mod depth_first;
mod greedy_nbv;
mod known;
mod nearest_frontier;
mod range_limited;

pub use depth_first::DepthFirst;
pub use greedy_nbv::GreedyNbv;
pub use known::Placement;
pub use nearest_frontier::NearestFrontier;
pub use range_limited::RangeLimited;

use crate::kernel::Point;
use crate::protocol::polygon::PolygonObservation;
use crate::protocol::{Action, CostModel, Feedback};

/// What the driver tells a polygon strategy before asking for its next action.
pub type PolygonFeedback = Feedback<Point, PolygonObservation>;

/// `(name, summary)` of every polygon strategy, in display order.
pub const REGISTRY: &[(&str, &str)] = &[
    ("depth_first", "the paper's algorithm: depth-first over windows, at most r + 1 scans"),
    ("nearest_frontier", "frontier-based (Yamauchi): the nearest unexplored window by travel"),
    ("greedy_nbv", "greedy next-best-view: most predicted new area per second of cost"),
    ("range_limited", "the paper's range-limited algorithm: open space, then boundary following"),
];

/// A fresh strategy by registry name; `cost` is the cost model of the run (strategies that
/// price their choices use it).
pub fn by_name(name: &str, cost: &CostModel) -> Option<Box<dyn PolygonStrategy + Send>> {
    match name {
        "depth_first" => Some(Box::new(DepthFirst::new())),
        "nearest_frontier" => Some(Box::new(NearestFrontier::new())),
        "greedy_nbv" => Some(Box::new(GreedyNbv::new(*cost))),
        "range_limited" => Some(Box::new(RangeLimited::new())),
        _ => None,
    }
}

/// An online polygon-exploration strategy.
pub trait PolygonStrategy {
    /// The registry name.
    fn name(&self) -> &str;
    /// The next action: move in a straight line to a point, scan, or done.
    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point>;
}
