//! Online exploration of unknown polygons with discrete visibility (Ghosh, Burdick,
//! Bhattacharya, Sarkar). Strategies are fed only observations: scans with their labelled
//! visibility regions.
//!
//! - `known`: what every polygon strategy knows (views, windows, the tree of moves) and the one
//!   feedback loop they share;
//! - `roads`: routes through the safe cells of a raster of the views (`cost_aware`'s trips,
//!   and every window strategy's on raw scans);
//! - `depth_first`: [`DepthFirst`], the paper's algorithm (at most r + 1 scans);
//! - `range_limited`: [`RangeLimited`], the paper's algorithm with a range restriction
//!   (Lemma 4);
//! - `nearest_frontier`: [`NearestFrontier`], the nearest open window by travel;
//! - `greedy_nbv`: [`GreedyNbv`], the most predicted area per second of cost;
//! - `explore_lite`: [`ExploreLite`], explore_lite's frontier explorer on an occupancy raster
//!   of what has been seen (the baseline ROS users run);
//! - `cost_aware`: [`CostAware`], stopscan's own: viewpoints on and off windows (room corners
//!   among them), weighed by the unknown area rays cast on a raster of what was seen predict
//!   they see, against travel and scan time;
//! - `raster`: the occupancy raster of the views that explore_lite plans on and cost_aware
//!   casts its rays on.

mod approach;
mod cost_aware;
mod depth_first;
mod explore_lite;
mod greedy_nbv;
mod known;
mod nearest_frontier;
mod range_limited;
mod raster;
mod roads;
mod trip;

pub use cost_aware::CostAware;
pub use depth_first::DepthFirst;
pub use explore_lite::{
    BLACKLIST_TOLERANCE_CELLS, ExploreLite, ExploreLiteParams, InvalidExploreLiteParams,
    MAX_SIDE_CELLS,
};
pub use greedy_nbv::GreedyNbv;
pub use known::{Placement, Skipped};
pub use nearest_frontier::NearestFrontier;
pub use range_limited::RangeLimited;
pub use trip::MAX_MOVE_FAILURES;

use super::{Entry, Registry, UnknownStrategy};
use crate::kernel::Point;
use crate::protocol::polygon::{PolygonObservation, RobotSetup};
use crate::protocol::{Action, CostModel, Feedback};

/// What the driver tells a polygon strategy before asking for its next action.
pub type PolygonFeedback = Feedback<Point, PolygonObservation>;

/// How a polygon registry entry builds its strategy: fresh, for a robot and a run priced by
/// its cost model (strategies that price their choices use it).
pub type PolygonBuild = fn(setup: &RobotSetup) -> Box<dyn PolygonStrategy + Send>;

/// Every polygon strategy, in display order: names, help text and construction.
pub const REGISTRY: Registry<PolygonBuild> = Registry::new(&[
    Entry {
        name: "depth_first",
        summary: "the paper's algorithm: depth-first over windows, at most r + 1 scans",
        build: |s| Box::new(DepthFirst::for_robot(s)),
    },
    Entry {
        name: "nearest_frontier",
        summary: "frontier-based (Yamauchi): the nearest unexplored window by travel",
        build: |s| Box::new(NearestFrontier::for_robot(s)),
    },
    Entry {
        name: "greedy_nbv",
        summary: "greedy next-best-view: most predicted new area per second of cost",
        build: |s| Box::new(GreedyNbv::for_robot(s)),
    },
    Entry {
        name: "explore_lite",
        summary: "explore_lite's frontier explorer (ROS): frontier clusters on an occupancy raster, largest first",
        build: |s| Box::new(ExploreLite::for_robot(s)),
    },
    Entry {
        name: "cost_aware",
        summary: "stopscan's own: the most predicted new area per second, viewpoints on and off windows, no goal churn",
        build: |s| Box::new(CostAware::for_robot(s)),
    },
    Entry {
        name: "range_limited",
        summary: "the paper's algorithm for a sensor range (needs one): open space, then boundary following",
        build: |s| Box::new(RangeLimited::for_robot(s)),
    },
]);

/// A fresh strategy by registry name, for a point robot with an ideal sensor (the paper's
/// model); `cost` is the cost model of the run (strategies that price their choices use it).
///
/// # Errors
/// [`UnknownStrategy`] listing the registered names.
pub fn build(
    name: &str,
    cost: &CostModel,
) -> Result<Box<dyn PolygonStrategy + Send>, UnknownStrategy> {
    build_for(name, &RobotSetup::point(*cost))
}

/// A fresh strategy by registry name for a robot with a footprint and a sensor
/// ([`RobotSetup`]).
///
/// # Errors
/// [`UnknownStrategy`] listing the registered names.
pub fn build_for(
    name: &str,
    setup: &RobotSetup,
) -> Result<Box<dyn PolygonStrategy + Send>, UnknownStrategy> {
    REGISTRY.get(name).map(|e| (e.build)(setup))
}

/// [`build`], `None` for an unknown name.
pub fn by_name(name: &str, cost: &CostModel) -> Option<Box<dyn PolygonStrategy + Send>> {
    build(name, cost).ok()
}

/// An online polygon-exploration strategy.
pub trait PolygonStrategy {
    /// The registry name.
    fn name(&self) -> &str;
    /// The next action: move in a straight line to a point, scan, or done.
    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point>;
    /// The windows closed without a visit so far, and why (none by default).
    fn skipped(&self) -> Skipped {
        Skipped::default()
    }
    /// After a [`Action::MoveTo`]: the waypoints the strategy means to drive after it, in
    /// order, the last being where it will scan; none when it will scan at the move's end
    /// or does not know yet. A driver that must place the robot on the way (a scan for
    /// localisation only: [`sim::lidar`](crate::sim::lidar)) reads where the trip ends.
    fn ahead(&self) -> Vec<Point> {
        Vec::new()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_builds_the_strategy_it_names() {
        for name in REGISTRY.names() {
            let s = build(name, &CostModel::default()).unwrap();
            assert_eq!(s.name(), name);
        }
        let e = build("warp", &CostModel::default()).err().unwrap();
        assert_eq!(
            e.to_string(),
            "unknown strategy \"warp\"; use one of: depth_first, nearest_frontier, greedy_nbv, explore_lite, cost_aware, range_limited"
        );
    }
}
