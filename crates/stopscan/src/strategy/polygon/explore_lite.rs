//! An explore_lite-style frontier explorer, [`ExploreLite`]: the baseline ROS users run today.
//! How it works, its defaults, what it inherits from explore_lite and where it departs from it
//! are documented on the type, where the public documentation shows them.

use std::collections::{BTreeSet, VecDeque};

use serde::{Deserialize, Serialize};

use super::known;
use super::trip::{Next, Trip};
use super::{PolygonFeedback, PolygonStrategy};
use crate::algorithm::visibility::BoundaryPiece;
use crate::kernel::{Point, magnitude};
use crate::protocol::Action;
use crate::protocol::polygon::{Footprint, PolygonObservation, RobotSetup};

pub use super::raster::MAX_SIDE_CELLS;
use super::raster::{ASSUMED, DIAGONAL, Entry, FREE, OCCUPIED, Raster, STATE, STEP, UNKNOWN};

/// explore_lite's blacklist tolerance: a goal within this many cells of a blacklisted point,
/// in both coordinates, is blacklisted too (`Explore::goalOnBlacklist`).
pub const BLACKLIST_TOLERANCE_CELLS: f64 = 5.0;

/// After this many failed moves with no scan between, the robot scans where it stands to
/// place itself again (see the departures).
pub(super) const SCAN_AFTER_FAILURES: usize = 2;

/// explore_lite's parameters, and the raster's resolution.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ExploreLiteParams {
    /// The raster's nominal cell size, metres (0.025: half a typical costmap's, see
    /// [`ExploreLite`]'s departures). With a footprint the cell is shrunk a little so that
    /// a whole number of cells spans the clearance (0.0224 m for a 0.2 m disc).
    pub resolution: f64,
    /// The weight of the distance to a frontier, per metre (`potential_scale`, 1e-3).
    pub potential_scale: f64,
    /// The weight of a frontier's size, per metre (`gain_scale`, 1.0).
    pub gain_scale: f64,
    /// The shortest frontier worth a trip, metres (`min_frontier_size`, 0.5): size ×
    /// resolution.
    pub min_frontier_size: f64,
}

impl Default for ExploreLiteParams {
    fn default() -> Self {
        Self { resolution: 0.025, potential_scale: 1e-3, gain_scale: 1.0, min_frontier_size: 0.5 }
    }
}

/// Parameters [`ExploreLite::with_params`] refuses.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InvalidExploreLiteParams {
    /// A resolution that is not a finite number > 0.
    #[error("the raster resolution must be a finite number > 0, got {0}")]
    Resolution(f64),
    /// A weight or a size that is not finite.
    #[error("{name} must be a finite number, got {value}")]
    NotFinite {
        /// The parameter.
        name: &'static str,
        /// Its value.
        value: f64,
    },
}

/// An explore_lite-style frontier explorer: the baseline ROS users run today (the
/// `explore_lite` package of m-explore, with move_base driving the robot), on an occupancy
/// raster of what has been seen.
///
/// # What it does
/// Every scan is rasterised once, when it arrives, into an occupancy grid that grows with the
/// views (a bounding box, re-allocated when a view falls outside it). A cell is
/// - **free** when its closed square lies inside the closed region of some view: its centre is
///   inside (scanline fill) and no edge of that region touches it (a supercover of the
///   region's edges, grown by a hair so that rounding stays on the safe side);
/// - **occupied** when a wall piece ([`BoundaryPiece::Edge`], [`BoundaryPiece::Partial`] or
///   a scanned [`BoundaryPiece::Wall`]) of
///   any view touches it (walls are true obstacles; occupied wins over free);
/// - **unknown** otherwise, including the cells a window or a range chord runs through, unless
///   another view contains them whole (then they are free: no frontier at the seam of two
///   views).
///
/// After each scan it searches frontiers as explore_lite's `FrontierSearch::searchFrom`
/// does: a breadth-first search over free cells (4-connected) from the robot's cell (or the
/// nearest free cell); an unknown cell with a free 4-neighbour is a frontier cell, and each
/// one met starts a cluster grown over frontier cells by 8-connectivity. A cluster has a size
/// (cells), a centroid, and a distance (from the centre of the robot's cell to its nearest
/// cell); clusters shorter than `min_frontier_size` (size × resolution) are dropped, and the
/// others are ranked by the cost `potential_scale · distance − gain_scale · size ·
/// resolution`. It takes the cheapest one that is not blacklisted (explore_lite's rule: a
/// goal within 5 cells of a blacklisted point, in both coordinates, is blacklisted too),
/// drives to it and scans on arrival. The run is priced by the run's cost model like every
/// strategy's; the choice is explore_lite's and does not look at it. It is done when no
/// frontier of at least `min_frontier_size` that it can reach is left.
///
/// # Safe motion
/// Moves are planned on **safe** cells only: a cell is safe when every cell within
/// `⌈clearance / resolution⌉` cells of it (Chebyshev) is free, where the clearance is the
/// footprint's [`planning_clearance`](Footprint::planning_clearance) (for a point robot safe
/// is free). A* plans over safe cells, 8-connected (a diagonal step only when both
/// orthogonal neighbours are safe); the cell path is then cut into straight moves, each
/// extended greedily while every cell its supercover touches is safe. So every move lies in
/// the union of safe cells' squares, and the robot's disc (of the planning clearance) around
/// any point of it lies in free cells: the world accepts the move. The first move, from the
/// viewpoint (not a cell centre), either stays in safe cells the same way or, when the robot
/// stands too close to a wall for its cell to be safe (a start), goes straight to a nearby
/// safe cell through the region just scanned, keeping the clearance from its boundary.
///
/// # Defaults
/// Those of explore_lite's node (`explore.cpp` and its wiki page): `potential_scale` 1e-3,
/// `gain_scale` 1.0, `min_frontier_size` 0.5 m, and its blacklist tolerance of 5 cells. The
/// launch file `explore.launch` sets `potential_scale` 3.0 and `min_frontier_size` 0.75;
/// [`ExploreLite::with_params`] takes those or any others. explore_lite has no resolution of
/// its own (it reads move_base's costmap): the default 0.025 m is half a typical costmap's
/// 0.05 m (see the departures).
///
/// # What it inherits
/// - **Open space with a short range.** The frontier around a scan in open space is one ring
///   of chords, one cluster, whose centroid is where the robot stands: its goal is the robot's
///   own cell, so it is blacklisted and the exploration may end early. explore_lite sends the
///   same goal and times out there (users report the robot stuck in large open areas with the
///   goal on its own spot: hrnr/m-explore issue 52).
/// - **Metric sizes.** `min_frontier_size` and the resolution are metres: on polygons whose
///   units are not (the art-gallery benchmarks), openings shorter than 0.5 units are ignored
///   and passages narrower than two cells closed.
///
/// # Departures from explore_lite
/// - **Discrete stop and scan.** explore_lite replans at `planner_frequency` (1 Hz) while the
///   robot drives and the map fills in, and may switch goals mid-trip; here the map changes
///   only at scans, so it plans once per stop and drives the whole trip, then scans.
/// - **The goal is moved to a safe cell.** explore_lite sends the centroid itself to
///   move_base; it often lies in unknown space or in an obstacle, where move_base would fail
///   (or, with planning through unknown space, drive into the unknown). Here the goal is the
///   reachable safe cell nearest to the centroid through space seen free (from the
///   centroid's cell if it is free, else entering free space through the frontier's own
///   cells); its centre is where the robot scans. The nearest cell as the crow flies may lie
///   across a wall from the frontier, where a scan sees nothing of it and the frontier is
///   blacklisted (`lse_arena`: 85% of the area visible from the reachable region seen).
/// - **A finer raster.** At a typical costmap's 0.05 m, the inflation (`⌈clearance /
///   resolution⌉` cells around a safe cell, beyond the cells walls touch) closes passages a
///   0.4 m robot passes with a quarter of a metre to spare, and the space behind them stays
///   unseen (`lse_arena`: 96.5% seen at 0.05 m, all of it at 0.025 m). The default is 0.025
///   m, shrunk for a footprint so that a whole number of cells spans the clearance (0.0224 m
///   for a 0.2 m disc: with 0.025 m the clearance of 8.04 cells was inflated to 9, and
///   willow-full's doors at 0.1 m cells, barely wider than the robot, stayed closed: 9%
///   seen, 98.8% now). Both make this baseline stronger, not weaker.
/// - **Unknown space is never traversed.** explore_lite's planner may plan through unknown
///   space; here every move lies in cells seen free, so no move can be refused.
/// - **No progress timeout.** `progress_timeout` (30 s) blacklists a goal the robot does not
///   get closer to; no time passes without progress in the simulator. Its static-world
///   counterpart: a frontier whose goal cell is where a scan already stood (the robot's own
///   cell included), or less than 5 cells from it in both coordinates (explore_lite's own
///   tolerance for one goal), is blacklisted, since a scan there would see nothing new. With
///   the cell alone, on raw scans the robot crept: 190 scans of 120 runs stood 2 to 15 cm
///   from the scan before (a frontier that noise leaves after every scan, its goal the next
///   cell over). A frontier with no reachable safe cell, or no A* path, is blacklisted as
///   move_base's failure would.
/// - **After a failed move** (on raw scans or a real robot: the navigation stack refused or
///   aborted a goal) the goal is blacklisted, the robot drives back to the last waypoint it
///   reached (a safe cell's centre) and plans again from there, as explore_lite replans from
///   wherever the robot stands. Unlike explore_lite's, that blacklisting is not for good.
///   On raw scans a move fails mostly because odometry drifted on a long trip, not because
///   the frontier cannot be reached, and one drifted belief fails every trip planned from
///   it. On the warehouse (seed 2) four moves in a row failed after a 45 m drive, each
///   blacklisting a large frontier, and the run ended with 91.8% of the area seen. So:
///   after two failed moves with no scan between, the robot scans where it stands, which
///   places it again (ICP corrects the belief); and at what would be the end, the frontiers
///   blacklisted by failed moves are tried again when scans were added since they last
///   were, or else, once until the next scan at a frontier, after a scan where the robot
///   stands. Every try ends in a scan or leaves the blacklist as it was, so the exploration
///   ends. With an exact sensor no move fails, and nothing changes.
/// - **Gaps in a wall seen at a slant** (raw scans). A wall seen from far away at a slant returns
///   beams a metre or more apart, and a costmap leaves the cells between its hits unmarked, so that
///   the unknown space behind forms frontiers along the wall. Here a window of a scan that is a gap
///   in a wall seen at 30° or less (the window strategies' reading, or a window between two walls
///   on one line) is assumed to be that wall: its cells are no frontier until a later scan's region
///   holds them (they are free) or a later scan's window runs along them (it saw through: they are
///   unknown again). Beams that entered a door end off the wall's line, so a door they saw stays a
///   frontier. Raster cells marked as walls for good, as this reading first did (a window between
///   two walls only), shut a door of the built-in office seen from 12 m down its corridor for
///   good (a room never entered, 95.3%, in a run that took the chains as walls too); with the
///   reading assumed, the grid's 120 runs (office, depot, warehouse, seeds 1 to 40) took 3,995
///   scans instead of 4,186, 10 runs instead of 26 went beyond 1.25 × their exact run, and 1
///   instead of 14 had a stop beyond 0.1 m of pose error (relays 142 → 100), the lowest coverage
///   99.44% (99.43% before).
/// - **Frontiers along a wall** (raw scans). Scans place one wall a few centimetres apart. A
///   scan that placed it farther frees cells beyond the wall another scan placed nearer, and
///   the unknown cells beyond them are a frontier all along the wall (a rack's end on the
///   warehouse: the same cluster chosen twice, each scan seeing nothing new). A cluster
///   whose cells farther than the sensor's wall tolerance from every wall seen or assumed
///   span less than half of `min_frontier_size` is no frontier. A window reaches away from
///   the walls at its ends; it keeps its cluster whole, the cells beside the walls included.
///   Dropping every cell near a wall instead cut short windows below `min_frontier_size`
///   (lse_arena: 3 of 10 runs below 99%, one 96.7%). See the README's raw-scan figures.
/// - **`orientation_scale`** does nothing in explore_lite either; it is not modelled.
/// - **Cost and centroid.** explore_lite multiplies the distance (already in metres) by the
///   resolution once more; here both terms are in metres, `potential_scale · distance −
///   gain_scale · size · resolution` (with the default 1e-3 the distance barely counts in
///   either). explore_lite's centroid leaves out the cluster's first cell while dividing by a
///   size that counts it; here every cell counts in the centroid and the distance.
/// - **Map size.** The raster grows to at most [`MAX_SIDE_CELLS`] cells a side around the
///   start (410 m at 0.025 m), as a costmap has a fixed size; nothing is mapped beyond, and
///   its edge is no frontier.
///
/// Its whole state is serialisable.
///
/// [`BoundaryPiece::Edge`]: crate::algorithm::visibility::BoundaryPiece::Edge
/// [`BoundaryPiece::Partial`]: crate::algorithm::visibility::BoundaryPiece::Partial
/// [`BoundaryPiece::Wall`]: crate::algorithm::visibility::BoundaryPiece::Wall
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExploreLite {
    params: ExploreLiteParams,
    footprint: Footprint,
    /// The robot may stand nearer a wall than its clearance (raw scans): a trip out of there
    /// keeps 99% of the clearance it has.
    #[serde(default)]
    relaxed: bool,
    /// The sensor's wall tolerance on raw scans (0 for the exact sensor): a window of a scan
    /// that is a gap in a wall seen at a slant is assumed to be that wall ([`gaps_in_walls`]).
    #[serde(default)]
    wall_tolerance: f64,
    raster: Raster,
    /// The centroids of blacklisted frontiers.
    blacklist: Vec<Point>,
    /// The cells scans stood in.
    scanned: BTreeSet<[i64; 2]>,
    /// The region of the last scan and where it was taken: the first move of a trip may cross
    /// it straight.
    last: Option<LastView>,
    /// The trip being driven.
    #[serde(default)]
    trip: Trip,
    /// The centroid of the frontier the trip is for: blacklisted if a move of the trip fails
    /// (move_base's failure).
    #[serde(default)]
    goal: Option<Point>,
    /// The centroids blacklisted because a move toward them failed: cleared, so tried
    /// again, at what would be the end when scans were added since (see the departures).
    #[serde(default)]
    failed: Vec<Point>,
    /// How many scans were added when `failed` was last cleared.
    #[serde(default)]
    retried_at: usize,
    /// How many scans were added.
    #[serde(default)]
    views: usize,
    /// Moves failed since the last scan.
    #[serde(default)]
    failures_since_scan: usize,
    /// A scan to place the robot again was taken, and no scan at a frontier since.
    #[serde(default)]
    placed_again: bool,
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct LastView {
    at: Point,
    polygon: Vec<Point>,
}

impl ExploreLite {
    /// A fresh explorer with explore_lite's defaults for a robot with a footprint
    /// ([`RobotSetup`]; its sensor's window rule is not used: `min_frontier_size` plays its
    /// part).
    pub fn for_robot(setup: &RobotSetup) -> Self {
        Self::build(setup, ExploreLiteParams::default())
    }

    /// A fresh explorer with these parameters.
    ///
    /// # Errors
    /// [`InvalidExploreLiteParams`] for a resolution that is not a finite number > 0, or a
    /// weight or size that is not finite.
    pub fn with_params(
        setup: &RobotSetup,
        params: ExploreLiteParams,
    ) -> Result<Self, InvalidExploreLiteParams> {
        let r = params.resolution;
        if !r.is_finite() || r <= 0.0 {
            return Err(InvalidExploreLiteParams::Resolution(r));
        }
        for (name, value) in [
            ("potential_scale", params.potential_scale),
            ("gain_scale", params.gain_scale),
            ("min_frontier_size", params.min_frontier_size),
        ] {
            if !value.is_finite() {
                return Err(InvalidExploreLiteParams::NotFinite { name, value });
            }
        }
        Ok(Self::build(setup, params))
    }

    fn build(setup: &RobotSetup, params: ExploreLiteParams) -> Self {
        Self {
            params,
            footprint: setup.footprint.clone(),
            relaxed: setup.sensor.wall_tolerance > 0.0,
            wall_tolerance: setup.sensor.wall_tolerance,
            raster: Raster::new(params.resolution),
            blacklist: Vec::new(),
            scanned: BTreeSet::new(),
            last: None,
            trip: Trip::default(),
            goal: None,
            failed: Vec::new(),
            retried_at: 0,
            views: 0,
            failures_since_scan: 0,
            placed_again: false,
        }
    }

    /// The parameters.
    pub fn params(&self) -> &ExploreLiteParams {
        &self.params
    }

    /// The centroids of the frontiers blacklisted so far: for good, then those blacklisted
    /// because a move toward them failed, until they are tried again.
    pub fn blacklisted(&self) -> Vec<Point> {
        self.blacklist.iter().chain(&self.failed).copied().collect()
    }

    /// Whether a goal is on the blacklist (explore_lite's `goalOnBlacklist`).
    fn on_blacklist(&self, p: Point) -> bool {
        let tol = BLACKLIST_TOLERANCE_CELLS * self.raster.res;
        self.blacklist
            .iter()
            .chain(&self.failed)
            .any(|b| (p[0] - b[0]).abs() < tol && (p[1] - b[1]).abs() < tol)
    }

    /// Whether a scan stood less than [`BLACKLIST_TOLERANCE_CELLS`] from `cell` in both
    /// coordinates, explore_lite's own tolerance for one goal: a scan there would see what
    /// that scan saw.
    fn scanned_near(&self, cell: [i64; 2]) -> bool {
        let t = BLACKLIST_TOLERANCE_CELLS as i64 - 1;
        let lo = [cell[0] - t, i64::MIN];
        let hi = [cell[0] + t, i64::MAX];
        self.scanned.range(lo..=hi).any(|c| (c[1] - cell[1]).abs() <= t)
    }

    /// The clearance planned moves keep (0 for a point robot).
    fn clearance(&self) -> f64 {
        self.footprint.planning_clearance(self.raster.scale)
    }

    /// The inflation radius, cells: 0 for a point robot, else `⌈clearance / res⌉`. The robot
    /// stands anywhere in a safe cell's square, at most half a cell (per coordinate) from its
    /// centre; the cells within `k` of it cover `(k + ½)·res` around the centre, so its disc
    /// of the clearance lies in them when `k·res ≥ clearance`.
    fn inflation(&self) -> i64 {
        if self.footprint.is_point() {
            0
        } else {
            (self.clearance() / self.raster.res).ceil() as i64
        }
    }

    /// Within how many cells of a wall seen a frontier cell lies along that wall
    /// ([`Raster::frontiers`]): the sensor's wall tolerance (raw scans), 0 for the exact
    /// sensor.
    fn wall_cells(&self) -> i64 {
        if self.wall_tolerance > 0.0 && self.raster.res > 0.0 {
            (self.wall_tolerance / self.raster.res).ceil() as i64
        } else {
            0
        }
    }

    /// The raster's cell size for a robot with a footprint: the nominal resolution shrunk so
    /// that a whole number of cells spans the clearance, `c′ / ⌈c′ / resolution⌉`, where `c′`
    /// is the planning clearance at a scale of `max(4·scale, 1000)` (`scale` the magnitude of
    /// the first scan's coordinates), at least the clearance of any later scan of a map that
    /// size. With the nominal cell, the rounding up of `clearance / resolution` loses up to a
    /// cell on each side of a passage (0.2 m clearance at 0.025 m: 8.04 cells, 9 inflated,
    /// 0.024 m lost per side), and doors that fit the robot with a few centimetres to spare
    /// stayed closed (willow-full at 0.1 m cells: 9% seen). A point robot keeps the nominal
    /// resolution.
    fn fitted_resolution(&self, scale: f64) -> f64 {
        let res = self.params.resolution;
        if self.footprint.is_point() {
            return res;
        }
        let c = self.footprint.planning_clearance((4.0 * scale).max(1000.0));
        let k = (c / res).ceil().max(1.0);
        c / k
    }

    /// Records a scan: rasterises it and remembers where it stood.
    fn add(&mut self, obs: &PolygonObservation) {
        if self.raster.anchor.is_none() {
            let res = self.fitted_resolution(magnitude(&obs.region.polygon));
            self.raster = Raster::new(res);
        }
        let k_before = self.inflation();
        self.raster.scale = self.raster.scale.max(magnitude(&obs.region.polygon)).max(1.0);
        let k = self.inflation();
        let pieces = &obs.region.boundary;
        let changed = self.raster.add_view(&obs.region.polygon, pieces, obs.at);
        // Walls assumed across gaps that this view sees through are no walls; this view's own
        // gaps in a wall are assumed to be wall. With the exact sensor nothing is assumed.
        if self.wall_tolerance > 0.0 {
            for piece in pieces {
                if let BoundaryPiece::Window { from, to, .. } = *piece {
                    self.raster.unassume(from, to);
                }
            }
            for (a, b) in gaps_in_walls(pieces, obs.at, self.wall_tolerance) {
                self.raster.assume_wall(a, b);
            }
        }
        if k == k_before {
            if let Some((lo, hi)) = changed {
                self.raster.update_safe(lo, hi, k);
            }
        } else {
            self.raster.update_safe_everywhere(k);
        }
        self.scanned.insert(self.raster.cell_of(obs.at));
        self.last = Some(LastView { at: obs.at, polygon: obs.region.polygon.clone() });
        self.views += 1;
    }

    /// After a scan at `at`: the cheapest reachable frontier's trip, or done.
    fn plan(&mut self, at: Point) -> Action<Point> {
        match self.plan_frontier(at) {
            Action::Done => self.at_the_end(at),
            a => a,
        }
    }

    /// What would be the end, with the robot at `at`: the frontiers blacklisted by failed
    /// moves are tried again when scans were added since they last were (a scan corrects
    /// the pose odometry drifted, and may open a way); else, when some are left and the
    /// robot does not stand where it last scanned, a scan where it stands places it again
    /// (once until a scan at a frontier). Each try ends in a scan or leaves the blacklist as
    /// it was, so the exploration ends.
    fn at_the_end(&mut self, at: Point) -> Action<Point> {
        if self.failed.is_empty() {
            return Action::Done;
        }
        if self.views > self.retried_at {
            // Planning blacklists for good what it cannot reach, so nothing is left to retry.
            self.retried_at = self.views;
            self.failed.clear();
            return self.plan_frontier(at);
        }
        self.scan_to_place_again(at)
    }

    /// A scan where the robot stands at `at`, to place it again, unless one was taken with no
    /// scan at a frontier since, or the robot stands where it last scanned.
    fn scan_to_place_again(&mut self, at: Point) -> Action<Point> {
        if self.placed_again || self.last.as_ref().is_some_and(|l| l.at == at) {
            return Action::Done;
        }
        self.placed_again = true;
        self.goal = None;
        self.trip.clear();
        Action::Scan
    }

    /// The cheapest reachable frontier's trip from `at`, or done.
    fn plan_frontier(&mut self, at: Point) -> Action<Point> {
        let frontiers = self.raster.frontiers(at, &self.params, self.wall_cells());
        if frontiers.is_empty() {
            return Action::Done;
        }
        let entries = self.entries(at);
        let reach = self.raster.reachable(&entries);
        let here = self.raster.cell_of(at);
        for f in frontiers {
            if self.on_blacklist(f.centroid) {
                continue;
            }
            let trip = self.raster.goal_for(&f, &reach).and_then(|goal| {
                let cell = self.raster.global(goal);
                if cell == here || self.scanned_near(cell) {
                    return None;
                }
                let path = self.raster.astar(&entries, goal)?;
                self.raster.compress(at, &entries, &path)
            });
            match trip {
                Some(waypoints) if !waypoints.is_empty() => {
                    self.trip.set_route(waypoints.into_iter().rev().collect());
                    self.goal = Some(f.centroid);
                    return self.trip.next_move();
                }
                _ => self.blacklist.push(f.centroid),
            }
        }
        Action::Done
    }

    /// The cells a trip from `at` may start with ([`Raster::entries`]): the last scan's
    /// region is the one the robot stands in.
    fn entries(&self, at: Point) -> Vec<Entry> {
        let view = self.last.as_ref().filter(|v| v.at == at).map(|v| v.polygon.as_slice());
        self.raster.entries(at, view, self.clearance(), self.inflation(), self.relaxed)
    }
}

impl PolygonStrategy for ExploreLite {
    fn name(&self) -> &'static str {
        "explore_lite"
    }

    fn ahead(&self) -> Vec<Point> {
        self.trip.ahead()
    }

    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point> {
        match feedback {
            PolygonFeedback::Start { .. } => Action::Scan,
            PolygonFeedback::Arrived => match self.trip.arrived() {
                Next::Act(a) => a,
                // Where the trip starts anew: the last scan, or the waypoint a way back after a
                // failed move ended at.
                Next::Replan => match self.trip.start().or(self.last.as_ref().map(|l| l.at)) {
                    Some(at) => self.plan(at),
                    None => Action::Done,
                },
            },
            PolygonFeedback::Scanned(obs) => {
                // A scan at a frontier's goal (not one to place the robot again) allows the
                // next scan to place it again.
                if self.goal.is_some() {
                    self.placed_again = false;
                }
                self.add(obs);
                self.trip.begin(obs.at);
                self.goal = None;
                self.failures_since_scan = 0;
                self.plan(obs.at)
            }
            PolygonFeedback::MoveFailed { at, .. } => {
                if let Some(g) = self.goal.take() {
                    self.failed.push(g);
                }
                self.failures_since_scan += 1;
                // A second failure with no scan between: the robot's belief is what is wrong
                // (odometry drifted over a long trip), so it scans where it stands.
                if self.failures_since_scan >= SCAN_AFTER_FAILURES
                    && let Action::Scan = self.scan_to_place_again(*at)
                {
                    return Action::Scan;
                }
                // Every waypoint is a safe cell's centre: plan again from the latest one reached.
                match self.trip.failed_back_to(|_| true) {
                    Action::Done => self.scan_to_place_again(*at),
                    a => a,
                }
            }
        }
    }
}

/// A frontier cluster, as explore_lite's `Frontier`.
#[derive(Debug, Clone, PartialEq)]
struct Frontier {
    /// Cells.
    size: usize,
    /// Their local indices, in the order the cluster grew.
    cells: Vec<usize>,
    /// From the centre of the robot's cell to the nearest cell's centre, metres.
    min_distance: f64,
    /// The mean of its cells' centres.
    centroid: Point,
    /// `potential_scale · min_distance − gain_scale · size · resolution`.
    cost: f64,
}

impl Raster {
    /// explore_lite's frontier search from the robot at `at`: the clusters of at least
    /// `min_frontier_size`, cheapest first (ties in the order found).
    ///
    /// With `wall_cells` above 0 (raw scans), a cluster is no frontier when its cells farther
    /// than that many cells (Chebyshev) from every wall seen or assumed span less than half
    /// of `min_frontier_size`: scans place one wall a few centimetres apart, and a scan that
    /// placed it farther frees cells beyond the wall another scan placed nearer, which
    /// leaves unknown cells beside free ones all along it. A window's cluster reaches away
    /// from the walls at its ends, and is kept whole.
    fn frontiers(&self, at: Point, params: &ExploreLiteParams, wall_cells: i64) -> Vec<Frontier> {
        let Some(pos) = self.local(self.cell_of(at)) else { return Vec::new() };
        let n = self.cells.len();
        let free = |i: usize| self.cells[i] & STATE == FREE;
        // The nearest free cell to start from (explore_lite's nearestCell: breadth first over
        // 8-neighbours).
        let start = {
            let mut seen = vec![false; n];
            let mut q = VecDeque::from([pos]);
            seen[pos] = true;
            let mut found = None;
            while let Some(i) = q.pop_front() {
                if free(i) {
                    found = Some(i);
                    break;
                }
                for j in self.neighbours(i, true) {
                    if !seen[j] {
                        seen[j] = true;
                        q.push_back(j);
                    }
                }
            }
            match found {
                Some(i) => i,
                None => return Vec::new(),
            }
        };
        let reference = self.centre(self.global(pos));
        let mut visited = vec![false; n];
        let mut flagged = vec![false; n];
        // Free cells keep MARGIN from the box's edge: the cells met below are never on it.
        let off = self.offsets();
        let step = |i: usize, o: isize| i.wrapping_add_signed(o);
        // Unknown cells in the margin (reached only when the raster is at its largest) are
        // beyond the map, not frontiers.
        let is_new_frontier = |i: usize, flagged: &[bool]| {
            self.cells[i] & STATE == UNKNOWN
                && !flagged[i]
                && off[..4].iter().any(|&o| self.cells[step(i, o)] & STATE == FREE)
                && self.inner(i)
        };
        let mut out = Vec::new();
        let mut q = VecDeque::from([start]);
        visited[start] = true;
        while let Some(i) = q.pop_front() {
            for j in off[..4].iter().map(|&o| step(i, o)) {
                if free(j) && !visited[j] {
                    visited[j] = true;
                    q.push_back(j);
                } else if is_new_frontier(j, &flagged) {
                    flagged[j] = true;
                    // Grow the cluster over 8-connected frontier cells.
                    let (mut cells, mut sum, mut min_distance) =
                        (Vec::new(), [0.0, 0.0], f64::INFINITY);
                    let mut cq = VecDeque::from([j]);
                    while let Some(c) = cq.pop_front() {
                        let p = self.centre(self.global(c));
                        cells.push(c);
                        sum = [sum[0] + p[0], sum[1] + p[1]];
                        min_distance =
                            min_distance.min((p[0] - reference[0]).hypot(p[1] - reference[1]));
                        for d in off.iter().map(|&o| step(c, o)) {
                            if is_new_frontier(d, &flagged) {
                                flagged[d] = true;
                                cq.push_back(d);
                            }
                        }
                    }
                    let size = cells.len();
                    // Only on raw scans, and only for a cluster long enough to count.
                    let along_walls = || {
                        let away =
                            cells.iter().filter(|&&c| !self.wall_within(c, wall_cells)).count();
                        (away as f64) * self.res < 0.5 * params.min_frontier_size
                    };
                    if size as f64 * self.res >= params.min_frontier_size
                        && !(wall_cells > 0 && along_walls())
                    {
                        let centroid = [sum[0] / size as f64, sum[1] / size as f64];
                        let cost = params.potential_scale * min_distance
                            - params.gain_scale * size as f64 * self.res;
                        out.push(Frontier { size, cells, min_distance, centroid, cost });
                    }
                }
            }
        }
        out.sort_by(|a, b| a.cost.total_cmp(&b.cost));
        out
    }

    /// Whether a cell within `k` cells (Chebyshev) of the local cell `i` is a wall seen or
    /// assumed.
    fn wall_within(&self, i: usize, k: i64) -> bool {
        let c = self.global(i);
        (-k..=k).any(|dy| {
            (-k..=k).any(|dx| matches!(self.state([c[0] + dx, c[1] + dy]), OCCUPIED | ASSUMED))
        })
    }

    /// The goal for a frontier: the reachable cell nearest to its centroid through space seen
    /// free. From the centroid's cell when it is free; otherwise the way enters free space
    /// through one of the frontier's own cells, and its length counts from the centroid to
    /// that cell. So a goal is never across a wall from the frontier, where a scan would see
    /// nothing of it; the cell nearest to the centroid as the crow flies is the fallback when
    /// no such way exists.
    fn goal_for(&self, f: &Frontier, reach: &[bool]) -> Option<usize> {
        const SOURCE: usize = usize::MAX;
        let free = |i: usize| self.cells[i] & STATE == FREE;
        let seeds: Vec<(usize, u64)> = match self.local(self.cell_of(f.centroid)) {
            Some(i) if free(i) => vec![(i, 0)],
            _ => f
                .cells
                .iter()
                .map(|&c| (c, self.step_cost(f.centroid, self.centre(self.global(c)))))
                .collect(),
        };
        let off = self.offsets();
        // Free cells and frontier cells keep MARGIN from the box's edge: their neighbours are
        // indexed unchecked.
        let found = pathfinding::directed::dijkstra::dijkstra(
            &SOURCE,
            |&i: &usize| -> Vec<(usize, u64)> {
                if i == SOURCE {
                    return seeds.clone();
                }
                off.iter()
                    .enumerate()
                    .map(|(k, &o)| (i.wrapping_add_signed(o), if k < 4 { STEP } else { DIAGONAL }))
                    .filter(|&(j, _)| free(j))
                    .collect()
            },
            |&i| i != SOURCE && reach[i],
        );
        match found {
            Some((path, _)) => path.last().copied(),
            None => self.nearest_reachable(f.centroid, reach),
        }
    }

    /// The reachable cell whose centre is nearest to `p` (the first in row order on ties).
    fn nearest_reachable(&self, p: Point, reach: &[bool]) -> Option<usize> {
        if !reach.iter().any(|&r| r) {
            return None;
        }
        let c = self.cell_of(p);
        let end =
            [self.origin[0] + self.size[0] as i64 - 1, self.origin[1] + self.size[1] as i64 - 1];
        // The farthest ring that still meets the box.
        let span = (0..2)
            .map(|k| (c[k] - self.origin[k]).abs().max((end[k] - c[k]).abs()))
            .max()
            .unwrap_or(0);
        let mut best: Option<(f64, usize)> = None;
        let consider = |x: i64, y: i64, best: &mut Option<(f64, usize)>| {
            let Some(i) = self.local([x, y]).filter(|&i| reach[i]) else { return };
            let q = self.centre([x, y]);
            let d = (q[0] - p[0]).hypot(q[1] - p[1]);
            if best.is_none_or(|(b, bi)| d < b || (d == b && i < bi)) {
                *best = Some((d, i));
            }
        };
        for r in 0..=span {
            // Every cell of ring r has its centre at least (r − 1/2)·res from p: once that
            // exceeds the best distance, no ring further out can do better.
            if best.is_some_and(|(d, _)| (r as f64 - 1.0) * self.res > d) {
                break;
            }
            if r == 0 {
                consider(c[0], c[1], &mut best);
                continue;
            }
            for x in c[0] - r..=c[0] + r {
                consider(x, c[1] - r, &mut best);
                consider(x, c[1] + r, &mut best);
            }
            for y in c[1] - r + 1..c[1] + r {
                consider(c[0] - r, y, &mut best);
                consider(c[0] + r, y, &mut best);
            }
        }
        best.map(|b| b.1)
    }
}

/// The windows of a raw scan's boundary (`tol` above 0) that are gaps in a wall seen at a
/// slant, read as the window strategies read them ([`known::gap_in_a_wall`]), or as a gap
/// between two walls on one line ([`known::gap_between_two_walls`]): the raster assumes them
/// to be wall ([`Raster::assume_wall`]), so that the cells beyond are no frontier, until a
/// view holds their cells (free) or sees through them (unknown again).
fn gaps_in_walls(pieces: &[BoundaryPiece], at: Point, tol: f64) -> Vec<(Point, Point)> {
    if tol <= 0.0 {
        return Vec::new();
    }
    (0..pieces.len())
        .filter_map(|i| match pieces[i] {
            BoundaryPiece::Window { from, to, .. }
                if known::gap_between_two_walls(pieces, i, at, tol)
                    || known::gap_in_a_wall(pieces, i, at, tol) =>
            {
                Some((from, to))
            }
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::raster::{ASSUMED, MARGIN, OCCUPIED, SAFE, supercover};
    use super::*;
    use crate::algorithm::visibility::BoundaryPiece;
    use crate::algorithm::visibility::VisibilityRegion;
    use crate::geometry::EdgeId;
    use crate::protocol::MoveFailure;
    use rand::{RngExt, SeedableRng};

    const E: EdgeId = EdgeId { ring: 0, index: 0 };

    /// A rectangle's region seen from its middle, counter-clockwise from the lower-left
    /// corner; `windows[k]` makes side k (bottom, right, top, left) a window.
    fn rectangle(lo: Point, hi: Point, windows: [bool; 4]) -> PolygonObservation {
        let polygon = vec![lo, [hi[0], lo[1]], hi, [lo[0], hi[1]]];
        let boundary = (0..4)
            .map(|k| {
                let (from, to) = (polygon[k], polygon[(k + 1) % 4]);
                if windows[k] {
                    BoundaryPiece::Window { from, to, reflex: from, far: to }
                } else {
                    BoundaryPiece::Edge { from, to, edge: E }
                }
            })
            .collect();
        let at = [0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1])];
        PolygonObservation::new(at, VisibilityRegion { viewpoint: at, polygon, boundary })
    }

    fn raster_of(res: f64, views: &[&PolygonObservation]) -> Raster {
        let mut r = Raster::new(res);
        for v in views {
            if let Some((lo, hi)) = r.add_view(&v.region.polygon, &v.region.boundary, v.at) {
                r.update_safe(lo, hi, 0);
            }
        }
        r
    }

    /// The cells of each state in the box `lo..=hi`.
    fn cells_in(r: &Raster, lo: [i64; 2], hi: [i64; 2], state: u8) -> Vec<[i64; 2]> {
        let mut out = Vec::new();
        for y in lo[1]..=hi[1] {
            for x in lo[0]..=hi[0] {
                if r.state([x, y]) == state {
                    out.push([x, y]);
                }
            }
        }
        out
    }

    /// A raster from rows of text, the top row first: `.` free, `#` occupied, anything else
    /// unknown; cell (0, 0) is the bottom-left character. Safe bits for inflation `k`.
    fn raster_from(res: f64, rows: &[&str], k: i64) -> Raster {
        let mut r = Raster::new(res);
        r.anchor = Some([0, 0]);
        let h = rows.len() as i64;
        let w = rows[0].len() as i64;
        r.ensure([0, 0], [w - 1, h - 1]);
        for (t, row) in rows.iter().enumerate() {
            for (x, ch) in row.chars().enumerate() {
                let i = r.local([x as i64, h - 1 - t as i64]).unwrap();
                r.cells[i] = match ch {
                    '.' => FREE,
                    '#' => OCCUPIED,
                    _ => UNKNOWN,
                };
            }
        }
        r.update_safe_everywhere(k);
        r
    }

    #[test]
    fn a_square_view_is_free_inside_and_occupied_along_its_walls() {
        // Off the grid lines: the cells 1..=8 lie inside [0.03, 0.97]², cells 0 and 9 meet
        // its sides.
        let v = rectangle([0.03, 0.03], [0.97, 0.97], [false; 4]);
        let r = raster_of(0.1, &[&v]);
        let free = cells_in(&r, [-3, -3], [12, 12], FREE);
        assert_eq!(free.len(), 64);
        assert!(free.iter().all(|c| (1..=8).contains(&c[0]) && (1..=8).contains(&c[1])));
        let occupied = cells_in(&r, [-3, -3], [12, 12], OCCUPIED);
        assert_eq!(occupied.len(), 100 - 64);
        assert!(occupied.iter().all(|c| c.iter().any(|&v| v == 0 || v == 9)));
        // On the grid lines: a side at x = 0 touches the cells on both of its sides.
        let v = rectangle([0.0, 0.0], [1.0, 1.0], [false; 4]);
        let r = raster_of(0.1, &[&v]);
        assert_eq!(cells_in(&r, [-3, -3], [12, 12], FREE).len(), 64);
        assert_eq!(cells_in(&r, [-3, -3], [12, 12], OCCUPIED).len(), 12 * 12 - 64);
        // Nothing but what the view saw is free, and the rest is unknown.
        assert_eq!(r.state([-3, 5]), UNKNOWN);
        assert_eq!(r.state([40, 5]), UNKNOWN);
    }

    #[test]
    fn a_window_leaves_its_cells_unknown_and_they_form_a_frontier() {
        // The right side is a window: its cells (column 9, rows 1..=8) are neither free nor
        // occupied; the corners, where walls meet it, are occupied.
        let v = rectangle([0.03, 0.03], [0.97, 0.97], [false, true, false, false]);
        let r = raster_of(0.1, &[&v]);
        for y in 1..=8 {
            assert_eq!(r.state([9, y]), UNKNOWN, "row {y}");
        }
        assert_eq!(r.state([9, 0]), OCCUPIED);
        assert_eq!(r.state([9, 9]), OCCUPIED);
        // One frontier: 8 cells at x = 0.95, centroid (0.95, 0.5); the robot's cell (5, 4)
        // has its centre at (0.55, 0.45), 0.4 from the nearest frontier cell (9, 4).
        let f = r.frontiers([0.52, 0.47], &ExploreLiteParams::default(), 0);
        assert_eq!(f.len(), 1);
        assert_eq!(f[0].size, 8);
        assert!((f[0].centroid[0] - 0.95).abs() < 1e-12 && (f[0].centroid[1] - 0.5).abs() < 1e-12);
        assert!((f[0].min_distance - 0.4).abs() < 1e-12);
        assert!((f[0].cost - (1e-3 * 0.4 - 8.0 * 0.1)).abs() < 1e-12);
        // Shorter than min_frontier_size (0.8 m < 0.9 m): dropped.
        let p = ExploreLiteParams { min_frontier_size: 0.9, ..ExploreLiteParams::default() };
        assert!(r.frontiers([0.52, 0.47], &p, 0).is_empty());
    }

    #[test]
    fn unknown_cells_beside_a_wall_another_scan_placed_nearer_are_no_frontier_on_raw_scans() {
        // A sees the left of a room (a window on its right), its top wall at y = 0.93 (row 9,
        // columns 0 to 14); B
        // sees all of it, placed that wall 0.24 m farther and saw a gap there (a window at
        // y = 1.17). B frees row 10 (centres at 1.05) beyond A's wall, reached from the
        // robot around its end; row 11, which B's window crosses, stays unknown.
        let a = rectangle([0.03, 0.03], [1.47, 0.93], [false, true, false, false]);
        let b = rectangle([0.03, 0.03], [1.97, 1.17], [false, false, true, false]);
        let r = raster_of(0.1, &[&a, &b]);
        for x in 1..=18 {
            let beyond = if x <= 14 { OCCUPIED } else { FREE };
            assert_eq!(
                (r.state([x, 9]), r.state([x, 10]), r.state([x, 11])),
                (beyond, FREE, UNKNOWN)
            );
        }
        // explore_lite's rule: row 11 is a frontier all along.
        let p = ExploreLiteParams::default();
        let f = r.frontiers([1.0, 0.5], &p, 0);
        assert_eq!(f.len(), 1, "{f:?}");
        assert!(f[0].cells.iter().all(|&c| r.global(c)[1] == 11), "{f:?}");
        // Every cell of it lies within two cells of a wall (A's, or B's sides): no frontier.
        // Within one, only the cells beside B's sides do, and it stays whole.
        assert!(r.frontiers([1.0, 0.5], &p, 2).is_empty());
        let f = r.frontiers([1.0, 0.5], &p, 1);
        assert_eq!((f.len(), f[0].size), (1, 18), "{f:?}");
        // A true opening reaches away from the walls it meets: its frontier stays whole,
        // the cells beside the walls included (so a short one is not cut below
        // min_frontier_size). A window 0.8 m long (rows 1 to 8, walls at rows 0 and 9) is
        // none when its cells farther than k from both span less than half of
        // min_frontier_size (0.25 m): 6, 4, then 2 cells of 0.1 m for k = 1, 2, 3.
        let v = rectangle([0.03, 0.03], [0.97, 0.97], [false, true, false, false]);
        let w = raster_of(0.1, &[&v]);
        for k in 1..=2 {
            let f = w.frontiers([0.52, 0.47], &p, k);
            assert_eq!((f.len(), f[0].size), (1, 8), "{k}: {f:?}");
        }
        assert!(w.frontiers([0.52, 0.47], &p, 3).is_empty());
    }

    #[test]
    fn cells_a_window_crosses_are_free_when_another_view_holds_them_whole() {
        // A sees [0.03, 0.97] with a window on its right; B sees [0.53, 1.47] with a window
        // on its left. Each window runs inside the other view: no frontier at the seam.
        let a = rectangle([0.03, 0.03], [0.97, 0.97], [false, true, false, false]);
        let b = rectangle([0.53, 0.03], [1.47, 0.97], [false, false, false, true]);
        for order in [[&a, &b], [&b, &a]] {
            let r = raster_of(0.1, &order);
            let free = cells_in(&r, [-3, -3], [20, 12], FREE);
            assert_eq!(free.len(), 13 * 8, "columns 1..=13, rows 1..=8");
            assert!(r.frontiers([0.52, 0.47], &ExploreLiteParams::default(), 0).is_empty());
        }
    }

    #[test]
    fn the_raster_stops_at_its_largest_side_and_keeps_free_cells_off_its_edge() {
        // A corridor 20 000 cells long at 1 m: the raster holds MAX_SIDE_CELLS of it around
        // the viewpoint, and no free cell comes within MARGIN of its edge.
        let v = rectangle([-10_000.5, 0.5], [10_000.5, 9.5], [false, false, false, false]);
        let r = raster_of(1.0, &[&v]);
        assert_eq!(r.size[0] as i64, MAX_SIDE_CELLS);
        assert!(r.size[1] < 200);
        for i in 0..r.cells.len() {
            if r.cells[i] & STATE == FREE {
                assert!(r.inner(i), "{:?}", r.global(i));
            }
        }
        let free = r.cells.iter().filter(|&&c| c & STATE == FREE).count();
        assert_eq!(free, (MAX_SIDE_CELLS as usize - 2 * MARGIN) * 8);
        // The searches run to the edge without leaving the box, and the map's edge is no
        // frontier.
        let f = r.frontiers([0.0, 5.0], &ExploreLiteParams::default(), 0);
        assert!(f.is_empty(), "{f:?}");
    }

    #[test]
    fn a_wall_piece_marks_occupied_over_free() {
        // A thin view along a wall piece that cuts through cells another view saw free (a
        // wall is a true obstacle: occupied wins).
        let a = rectangle([0.03, 0.03], [0.97, 0.97], [true; 4]);
        let mut r = raster_of(0.1, &[&a]);
        assert_eq!(r.state([4, 4]), FREE);
        let wall = PolygonObservation::new(
            [0.45, 0.45],
            VisibilityRegion {
                viewpoint: [0.45, 0.45],
                polygon: vec![[0.45, 0.45], [0.65, 0.45], [0.45, 0.46]],
                boundary: vec![
                    BoundaryPiece::Partial { from: [0.45, 0.45], to: [0.65, 0.45], edge: E },
                    BoundaryPiece::Frontier { from: [0.65, 0.45], to: [0.45, 0.46] },
                    BoundaryPiece::Frontier { from: [0.45, 0.46], to: [0.45, 0.45] },
                ],
            },
        );
        r.add_view(&wall.region.polygon, &wall.region.boundary, wall.at);
        for x in 4..=6 {
            assert_eq!(r.state([x, 4]), OCCUPIED, "cell ({x}, 4)");
        }
        assert_eq!(r.state([3, 4]), FREE);
        assert_eq!(r.state([4, 3]), FREE);
    }

    #[test]
    fn clusters_grow_by_eight_connectivity_and_rank_by_cost() {
        // 1 m cells, the top row first (y = 6 down to 0); the robot stands in cell (1, 1).
        // Frontier cells, unknown with a free 4-neighbour: (8, 5), (8, 4), (7, 2), (6, 1).
        // Not frontier cells: (9, 5), (9, 3), (7, 1), (8, 1) (no free 4-neighbour).
        let rows = [
            "##########",
            "#.......??",
            "#.......?#",
            "#.......#?",
            "#......?##",
            "#.....???#",
            "##########",
        ];
        let r = raster_from(1.0, &rows, 0);
        let p = ExploreLiteParams { min_frontier_size: 0.0, ..ExploreLiteParams::default() };
        let f = r.frontiers([1.5, 1.5], &p, 0);
        // Clusters by 8-connectivity: {(8, 5), (8, 4)} and {(7, 2), (6, 1)} (diagonal).
        assert_eq!(f.len(), 2, "{f:?}");
        let mut sizes: Vec<usize> = f.iter().map(|c| c.size).collect();
        sizes.sort_unstable();
        assert_eq!(sizes, [2, 2]);
        // Equal sizes: the nearer wins. Robot cell centre (1.5, 1.5).
        let d_low = (6.5f64 - 1.5).hypot(0.0); // (6, 1) centre (6.5, 1.5)
        let d_high = (8.5f64 - 1.5).hypot(4.5 - 1.5); // (8, 4) centre (8.5, 4.5)
        assert!((f[0].min_distance - d_low).abs() < 1e-12, "{f:?}");
        assert!((f[1].min_distance - d_high).abs() < 1e-12);
        assert_eq!(f[0].centroid, [7.0, 2.0]);
        assert_eq!(f[1].centroid, [8.5, 5.0]);
        assert!((f[0].cost - (1e-3 * d_low - 2.0)).abs() < 1e-12);
        // The default min_frontier_size (0.5 m, half a cell here) keeps both.
        assert_eq!(r.frontiers([1.5, 1.5], &ExploreLiteParams::default(), 0).len(), 2);
        // Three cells needed: none left.
        let p = ExploreLiteParams { min_frontier_size: 2.5, ..ExploreLiteParams::default() };
        assert!(r.frontiers([1.5, 1.5], &p, 0).is_empty());
    }

    #[test]
    fn a_goal_is_the_nearest_through_free_space_not_across_a_wall() {
        // 1 m cells, the top row first. The frontier is the top of the right room, cells
        // (5..=8, 5); the reachable cells are (3, 5), across the wall, and (8, 1), far down
        // the right room.
        let rows = [
            "##########", //
            "#...#????#",
            "#...#....#",
            "#...#....#",
            "#...#....#",
            "#........#",
            "##########",
        ];
        let r = raster_from(1.0, &rows, 0);
        let p = ExploreLiteParams { min_frontier_size: 0.0, ..ExploreLiteParams::default() };
        let f = r.frontiers([6.5, 2.5], &p, 0);
        assert_eq!(f.len(), 1, "{f:?}");
        assert_eq!(f[0].centroid, [7.0, 5.5]);
        let mut reach = vec![false; r.cells.len()];
        let (left, right) = (r.local([3, 5]).unwrap(), r.local([8, 1]).unwrap());
        reach[left] = true;
        reach[right] = true;
        // As the crow flies the cell across the wall is nearer (3.5 m against 4.3 m) ...
        assert_eq!(r.nearest_reachable(f[0].centroid, &reach), Some(left));
        // ... through free space the one in the frontier's own room is.
        assert_eq!(r.goal_for(&f[0], &reach), Some(right));
        // From a free centroid the search starts at the centroid's own cell.
        let g = Frontier { centroid: [2.5, 3.5], ..f[0].clone() };
        assert_eq!(r.goal_for(&g, &reach), Some(left));
    }

    #[test]
    fn the_bigger_frontier_wins_over_the_nearer_one() {
        let rows =
            ["#????????#", "#........#", "#........#", "#........#", "?........#", "##########"];
        let r = raster_from(0.1, &rows, 0);
        let p = ExploreLiteParams { min_frontier_size: 0.0, ..ExploreLiteParams::default() };
        let f = r.frontiers([0.15, 0.15], &p, 0);
        assert_eq!(f.len(), 2);
        assert_eq!(f[0].size, 8);
        assert_eq!(f[1].size, 1);
        let cost = |size: f64, d: f64| 1e-3 * d - size * 0.1;
        assert!((f[0].cost - cost(8.0, f[0].min_distance)).abs() < 1e-12);
        assert!((f[1].cost - cost(1.0, 0.1)).abs() < 1e-12);
    }

    /// Whether every cell whose closed square lies within `d` of `p` is safe (brute force).
    fn safe_around(r: &Raster, p: Point, d: f64) -> bool {
        let c = r.cell_of(p);
        (-1..=1).all(|dy| {
            (-1..=1).all(|dx| {
                let q = [c[0] + dx, c[1] + dy];
                let (lo, hi) = (r.centre(q), r.centre(q));
                let (lo, hi) = (
                    [lo[0] - 0.5 * r.res, lo[1] - 0.5 * r.res],
                    [hi[0] + 0.5 * r.res, hi[1] + 0.5 * r.res],
                );
                let gap = [
                    (lo[0] - p[0]).max(p[0] - hi[0]).max(0.0),
                    (lo[1] - p[1]).max(p[1] - hi[1]).max(0.0),
                ];
                gap[0].max(gap[1]) > d || r.is_safe(q)
            })
        })
    }

    /// A seeded raster: free cells with random occupied blocks.
    fn random_raster(seed: u64, k: i64) -> Raster {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let (w, h) = (60usize, 40usize);
        let mut grid = vec![vec!['.'; w]; h];
        for row in &mut grid {
            row[0] = '#';
            row[w - 1] = '#';
        }
        grid[0] = vec!['#'; w];
        grid[h - 1] = vec!['#'; w];
        for _ in 0..25 {
            let (x, y) = (rng.random_range(1..w - 6), rng.random_range(1..h - 6));
            let (bw, bh) = (rng.random_range(1..6), rng.random_range(1..6));
            for row in grid.iter_mut().skip(y).take(bh) {
                for c in row.iter_mut().skip(x).take(bw) {
                    *c = '#';
                }
            }
        }
        let rows: Vec<String> = grid.iter().rev().map(|r| r.iter().collect()).collect();
        let refs: Vec<&str> = rows.iter().map(String::as_str).collect();
        raster_from(0.05, &refs, k)
    }

    #[test]
    fn distances_are_those_of_the_cheapest_paths_through_safe_cells() {
        // Against a brute force from the definition: relax every safe cell's steps (4
        // orthogonal ones of 1000, 4 diagonal ones of 1414 allowed only when both orthogonal
        // cells are safe) until nothing changes.
        for seed in 0..6 {
            for k in [0, 1, 2] {
                let r = random_raster(seed, k);
                let safe = |x: i64, y: i64| r.is_safe([x, y]);
                let Some(s) = (0..r.cells.len()).find(|&i| r.cells[i] & SAFE != 0) else {
                    continue;
                };
                let entries = [Entry { cell: s, cost: 7, direct: false }];
                let got = r.distances(&entries);
                let mut want = vec![u64::MAX; r.cells.len()];
                want[s] = 7;
                let mut changed = true;
                while changed {
                    changed = false;
                    for i in 0..r.cells.len() {
                        if want[i] == u64::MAX {
                            continue;
                        }
                        let [x, y] = r.global(i);
                        for dx in -1i64..=1 {
                            for dy in -1i64..=1 {
                                if (dx, dy) == (0, 0) || !safe(x + dx, y + dy) {
                                    continue;
                                }
                                let diagonal = dx != 0 && dy != 0;
                                if diagonal && !(safe(x + dx, y) && safe(x, y + dy)) {
                                    continue;
                                }
                                let j = r.local([x + dx, y + dy]).unwrap();
                                let c = want[i] + if diagonal { 1414 } else { 1000 };
                                if c < want[j] {
                                    want[j] = c;
                                    changed = true;
                                }
                            }
                        }
                    }
                }
                assert_eq!(got, want, "seed {seed} k {k}");
                // A* finds paths of the same cost.
                let goal = (0..r.cells.len()).rev().find(|&i| want[i] != u64::MAX).unwrap();
                let path = r.astar(&entries, goal).unwrap();
                let cost: u64 = 7 + path
                    .windows(2)
                    .map(|w| {
                        let (a, b) = (r.global(w[0]), r.global(w[1]));
                        if a[0] != b[0] && a[1] != b[1] { 1414 } else { 1000 }
                    })
                    .sum::<u64>();
                assert_eq!(cost, want[goal], "seed {seed} k {k}");
            }
        }
    }

    #[test]
    fn compressed_moves_stay_in_safe_cells() {
        let mut checked = 0;
        for seed in 0..12 {
            for k in [0, 2] {
                let r = random_raster(seed, k);
                let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(100 + seed);
                let safe: Vec<usize> =
                    (0..r.cells.len()).filter(|&i| r.cells[i] & SAFE != 0).collect();
                if safe.len() < 2 {
                    continue;
                }
                for _ in 0..10 {
                    let s = safe[rng.random_range(0..safe.len())];
                    // The robot anywhere in its cell, not at the centre.
                    let c = r.centre(r.global(s));
                    let at = [
                        c[0] + rng.random_range(-0.45..0.45) * r.res,
                        c[1] + rng.random_range(-0.45..0.45) * r.res,
                    ];
                    if !r.segment_is_safe(at, c) {
                        continue;
                    }
                    let entries = [Entry { cell: s, cost: r.step_cost(at, c), direct: false }];
                    let reach = r.reachable(&entries);
                    let goal = safe[rng.random_range(0..safe.len())];
                    let Some(path) = r.astar(&entries, goal) else {
                        assert!(!reach[goal], "A* found no path to a reachable cell");
                        continue;
                    };
                    assert!(reach[goal]);
                    let moves = r.compress(at, &entries, &path).unwrap();
                    assert_eq!(*moves.last().unwrap(), r.centre(r.global(goal)));
                    assert!(moves.len() <= path.len());
                    let mut from = at;
                    for &to in &moves {
                        // An independent check: points every res/64 along the move, and the
                        // cells within a hair of each.
                        let n = ((to[0] - from[0]).hypot(to[1] - from[1]) / r.res * 64.0)
                            .ceil()
                            .max(1.0) as usize;
                        for i in 0..=n {
                            let t = i as f64 / n as f64;
                            let p =
                                [from[0] + t * (to[0] - from[0]), from[1] + t * (to[1] - from[1])];
                            assert!(
                                safe_around(&r, p, 1e-9),
                                "seed {seed} k {k}: {from:?} → {to:?} at {p:?}"
                            );
                        }
                        from = to;
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 100, "{checked} moves checked");
    }

    #[test]
    fn the_supercover_holds_the_segment_and_little_more() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let res = 0.05;
        for _ in 0..300 {
            let a = [rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0)];
            let b = if rng.random_bool(0.2) {
                [a[0], rng.random_range(-2.0..2.0)]
            } else {
                [rng.random_range(-2.0..2.0), rng.random_range(-2.0..2.0)]
            };
            let eps = 1e-9;
            let mut cells = BTreeSet::new();
            supercover(res, a, b, eps, |c| {
                cells.insert(c);
                true
            });
            // Every point of the segment lies in a visited cell.
            for i in 0..=2000 {
                let t = f64::from(i) / 2000.0;
                let p = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])];
                let c = [(p[0] / res).floor() as i64, (p[1] / res).floor() as i64];
                assert!(cells.contains(&c), "{a:?} {b:?}: {p:?}");
            }
            // Every visited cell's square comes within a few hairs of the segment.
            for c in &cells {
                let (x0, y0) = (c[0] as f64 * res, c[1] as f64 * res);
                let sq = [[x0, y0], [x0 + res, y0], [x0 + res, y0 + res], [x0, y0 + res]];
                let inside =
                    |p: Point| p[0] >= x0 && p[0] <= x0 + res && p[1] >= y0 && p[1] <= y0 + res;
                let d = if inside(a) || inside(b) {
                    0.0
                } else {
                    (0..4)
                        .map(|k| crate::geometry::segments_distance(a, b, sq[k], sq[(k + 1) % 4]))
                        .fold(f64::INFINITY, f64::min)
                };
                assert!(d <= 4.0 * eps, "{a:?} {b:?}: cell {c:?} at {d}");
            }
        }
    }

    #[test]
    fn safe_cells_keep_the_inflation_from_everything_not_free() {
        let rows = ["..........", "..........", "....#.....", "..........", ".........."];
        let r = raster_from(1.0, &rows, 1);
        // k = 1: safe when the 3 × 3 block around is free and inside the box.
        assert!(r.is_safe([1, 1]) && r.is_safe([7, 2]));
        assert!(!r.is_safe([3, 2]) && !r.is_safe([5, 3]) && !r.is_safe([4, 1]));
        assert!(!r.is_safe([0, 2]), "the box's edge: unknown beyond");
        let r0 = raster_from(1.0, &rows, 0);
        assert!(r0.is_safe([3, 2]) && !r0.is_safe([4, 2]));
    }

    #[test]
    fn a_goal_near_a_blacklisted_one_is_blacklisted_too() {
        let mut s = ExploreLite::for_robot(&RobotSetup::default());
        s.blacklist.push([1.0, 1.0]);
        // Five cells of the raster, in both coordinates.
        let r = s.raster.res;
        assert!(s.on_blacklist([1.0 + 4.9 * r, 1.0 - 4.9 * r]));
        assert!(!s.on_blacklist([1.0 + 5.1 * r, 1.0]));
    }

    #[test]
    fn parameters_are_checked() {
        let setup = RobotSetup::default();
        let bad = ExploreLiteParams { resolution: 0.0, ..ExploreLiteParams::default() };
        assert!(matches!(
            ExploreLite::with_params(&setup, bad),
            Err(InvalidExploreLiteParams::Resolution(_))
        ));
        let bad = ExploreLiteParams { gain_scale: f64::NAN, ..ExploreLiteParams::default() };
        assert!(ExploreLite::with_params(&setup, bad).is_err());
        let ok = ExploreLite::with_params(&setup, ExploreLiteParams::default()).unwrap();
        assert_eq!(ok, ExploreLite::for_robot(&setup));
    }

    /// A room 4 × 2 with a window on its right, and an explorer (cells of 0.1) that scanned
    /// it from its middle: the room's view and the explorer's first action.
    fn scanned_room() -> (ExploreLite, PolygonObservation, Action<Point>) {
        let v = rectangle([0.0, 0.0], [4.0, 2.0], [false, true, false, false]);
        let mut s = ExploreLite::with_params(
            &RobotSetup::default(),
            ExploreLiteParams { resolution: 0.1, ..Default::default() },
        )
        .unwrap();
        assert_eq!(s.act(&PolygonFeedback::Start { at: v.at }), Action::Scan);
        let first = s.act(&PolygonFeedback::Scanned(v.clone()));
        (s, v, first)
    }

    /// Answers every move with an arrival, but fails the first `fail` moves at where the
    /// robot was sent from; returns the first scan or done.
    fn drive(
        s: &mut ExploreLite,
        first: Action<Point>,
        from: Point,
        mut fail: usize,
    ) -> Action<Point> {
        let (mut a, mut at, mut moves) = (first, from, 0);
        while let Action::MoveTo { to } = a {
            moves += 1;
            assert!(moves < 100, "the trip never ends");
            a = if fail > 0 {
                fail -= 1;
                s.act(&PolygonFeedback::MoveFailed { at, reason: MoveFailure::Blocked })
            } else {
                at = to;
                s.act(&PolygonFeedback::Arrived)
            };
        }
        a
    }

    #[test]
    fn a_frontier_blacklisted_by_a_failed_move_is_tried_again_before_the_end() {
        // The one frontier's trip fails once. With explore_lite's blacklist for good the run
        // would end there, with the frontier open.
        let (mut s, v, first) = scanned_room();
        let end = drive(&mut s, first, v.at, 1);
        assert_eq!(end, Action::Scan, "the frontier is tried again and reached");
        assert!(s.blacklisted().is_empty());
        // Every move fails: the tries end (`drive` counts the moves), with the frontier
        // blacklisted.
        let (mut s, v, first) = scanned_room();
        let end = drive(&mut s, first, v.at, usize::MAX);
        assert_eq!(end, Action::Done);
        assert_eq!(s.blacklisted().len(), 1);
    }

    #[test]
    fn two_failed_moves_with_no_scan_between_make_it_scan_where_it_stands() {
        let (mut s, v, first) = scanned_room();
        let Action::MoveTo { to } = first else { panic!("a trip to the frontier: {first:?}") };
        let at = [0.5 * (v.at[0] + to[0]), v.at[1]];
        assert!(matches!(
            s.act(&PolygonFeedback::MoveFailed { at, reason: MoveFailure::Blocked }),
            Action::MoveTo { .. }
        ));
        assert_eq!(
            s.act(&PolygonFeedback::MoveFailed { at, reason: MoveFailure::Blocked }),
            Action::Scan,
            "the second failure in a row: a scan to place the robot again"
        );
        // The scan places the robot; the frontier blacklisted by the failures is tried again.
        let mut w = rectangle([0.0, 0.0], [4.0, 2.0], [false, true, false, false]);
        w.at = at;
        w.region.viewpoint = at;
        let next = s.act(&PolygonFeedback::Scanned(w));
        assert!(matches!(next, Action::MoveTo { .. }), "{next:?}");
    }

    /// A hall 4 × 1 m seen from `at` as from a raw scan: its bottom wall has a gap from
    /// x = 2 to 2.8 on its line.
    fn hall_with_a_gap(at: Point) -> PolygonObservation {
        let wall = |from: Point, to: Point| BoundaryPiece::Wall { from, to };
        let (a, b) = ([2.0, 0.03], [2.8, 0.03]);
        let polygon = vec![[0.03, 0.03], a, b, [3.97, 0.03], [3.97, 0.97], [0.03, 0.97]];
        let boundary = vec![
            wall([0.03, 0.03], a),
            BoundaryPiece::Window { from: a, to: b, reflex: a, far: b },
            wall(b, [3.97, 0.03]),
            wall([3.97, 0.03], [3.97, 0.97]),
            wall([3.97, 0.97], [0.03, 0.97]),
            wall([0.03, 0.97], [0.03, 0.03]),
        ];
        PolygonObservation::new(at, VisibilityRegion { viewpoint: at, polygon, boundary })
    }

    fn raw_scans() -> RobotSetup {
        let sensor =
            crate::protocol::polygon::Sensor { wall_tolerance: 0.07, ..Default::default() };
        RobotSetup { sensor, ..RobotSetup::default() }
    }

    #[test]
    fn a_gap_in_one_wall_seen_at_a_slant_is_no_frontier_on_raw_scans() {
        // Seen from (0.3, 0.8), the gap is at asin(0.77 / 2.24) = 20°.
        let at = [0.3, 0.8];
        let frontiers = |setup: &RobotSetup| {
            let mut s = ExploreLite::for_robot(setup);
            s.add(&hall_with_a_gap(at));
            s.raster.frontiers(at, &s.params, s.wall_cells()).len()
        };
        // Read as a window (the exact sensor's rule), its cells form a frontier; on raw scans
        // it is the wall, as the window strategies read it.
        assert_eq!(frontiers(&RobotSetup::default()), 1);
        assert_eq!(frontiers(&raw_scans()), 0);
    }

    #[test]
    fn a_gap_assumed_to_be_wall_opens_again_when_a_later_scan_sees_through_it() {
        let mut s = ExploreLite::for_robot(&raw_scans());
        s.add(&hall_with_a_gap([0.3, 0.8]));
        let gap = s.raster.cell_of([2.4, 0.03]);
        assert_eq!(s.raster.state(gap), ASSUMED);
        // Seen head-on from (2.4, 0.8) the gap is a window (at 90°, no wall seen at a
        // slant): the wall assumed across it is not there, and its cells are a frontier again.
        let at = [2.4, 0.8];
        s.add(&hall_with_a_gap(at));
        assert_eq!(s.raster.state(gap), UNKNOWN);
        assert_eq!(s.raster.frontiers(at, &s.params, s.wall_cells()).len(), 1);
        // A scan at a slant again assumes it shut; one whose region holds its cells frees them.
        s.add(&hall_with_a_gap([0.3, 0.8]));
        assert_eq!(s.raster.state(gap), ASSUMED);
        let mut below = hall_with_a_gap(at);
        let (a, b) = ([2.0, 0.03], [2.8, 0.03]);
        let (c, d) = ([2.0, -1.0], [2.8, -1.0]);
        below.region.polygon =
            vec![[0.03, 0.03], a, c, d, b, [3.97, 0.03], [3.97, 0.97], [0.03, 0.97]];
        let window =
            |from: Point, to: Point| BoundaryPiece::Window { from, to, reflex: from, far: to };
        let wall = |from: Point, to: Point| BoundaryPiece::Wall { from, to };
        below.region.boundary = vec![
            wall([0.03, 0.03], a),
            window(a, c),
            window(c, d),
            window(d, b),
            wall(b, [3.97, 0.03]),
            wall([3.97, 0.03], [3.97, 0.97]),
            wall([3.97, 0.97], [0.03, 0.97]),
            wall([0.03, 0.97], [0.03, 0.03]),
        ];
        s.add(&below);
        assert_eq!(s.raster.state(gap), FREE);
    }

    #[test]
    fn a_goal_less_than_the_tolerance_from_a_scan_counts_as_where_it_stood() {
        let mut s = ExploreLite::for_robot(&RobotSetup::default());
        s.scanned.insert([10, 10]);
        s.scanned.insert([40, -3]);
        // Less than 5 cells off in both coordinates, as explore_lite's blacklist test.
        for (c, near) in [
            ([10, 10], true),
            ([14, 6], true),
            ([6, 14], true),
            ([15, 10], false),
            ([10, 5], false),
            ([36, 1], true),
            ([36, 2], false),
            ([25, 3], false),
        ] {
            assert_eq!(s.scanned_near(c), near, "{c:?}");
            let brute =
                s.scanned.iter().any(|q| (q[0] - c[0]).abs() < 5 && (q[1] - c[1]).abs() < 5);
            assert_eq!(brute, near, "{c:?}");
        }
    }

    #[test]
    fn a_frontier_it_cannot_get_closer_to_is_blacklisted_and_it_is_done() {
        // A closet 0.3 × 0.3 with a window on its right, seen from inside: the frontier's
        // nearest free cell is where the robot stands, so scanning there again would see
        // nothing new.
        let v = rectangle([0.0, 0.0], [0.3, 0.3], [false, true, false, false]);
        let mut s = ExploreLite::with_params(
            &RobotSetup::default(),
            ExploreLiteParams { resolution: 0.1, min_frontier_size: 0.0, ..Default::default() },
        )
        .unwrap();
        assert_eq!(s.act(&PolygonFeedback::Start { at: v.at }), Action::Scan);
        assert_eq!(s.act(&PolygonFeedback::Scanned(v)), Action::Done);
        assert_eq!(s.blacklisted().len(), 1);
    }
}
