//! Cost-aware exploration: after each scan, go where the predicted new area per second of
//! mission time is largest, scan there, and repeat until no window worth a trip is open.
//!
//! It is stopscan's own strategy (not from the papers), built for real maps where a scan
//! costs as much as a long drive (30 s against 0.5 m/s is 15 m):
//!
//! - **Candidates.** For every open window part (the paper's bookkeeping, [`super::known`],
//!   with the sensor rule and the footprint's clearance applied), its viewpoint beside the
//!   window, and viewpoints stepped back from it into the view's region (2 and 4 m):
//!   places that are not on any window, from where one scan may look through several.
//! - **Predicted gain.** What a scan at `z` would see behind every open window part of the
//!   same view that `z` sees across the region: the wedge the part subtends from `z`,
//!   beyond the part, out to the sensor range and no farther than the view's own region
//!   reaches from its viewpoint (the size of the space seen so far stands for the size of
//!   the space behind its windows). Parts are counted once per candidate.
//! - **Cost.** What the cost model charges to get there along the tree of known-free moves
//!   and scan: `move_time · moves + distance / speed + scan_time`.
//! - **Choice.** The largest gain per second; ties to the earlier candidate, so runs are
//!   deterministic. The trip is then driven to its end and the scan taken: no goal is
//!   switched mid-trip.
//! - **Routes.** Along the tree of moves, with the corners cut where a single view's region
//!   holds the straight move with the footprint's clearance (`Known::go_shortcut`).
//! - **Finishing guarantee.** The window the chosen viewpoint stands for is marked handled
//!   after its scan (as in the paper's algorithm), so every scan closes at least one window
//!   part and the run ends; it ends only when no window part worth a trip is open (windows
//!   the sensor rule excludes, or that no viewpoint with the footprint's clearance can be
//!   planned for, are counted in the run record).
//!
//! # Tried and not kept
//! Measured with `stopscan bench floors --data ../shared/data/ros-maps` (13,129 s with the
//! rules above, before deferred window parts were tried again: 13,202 s since, and 13,698 s
//! since the window rule judges whole openings) and on 16 other offices (`--seed 100
//! --offices 16`, 14,263 s; 14,511 s; 14,798 s):
//! - **The largest gain per second across all parts** instead of the soonest part: fewer scans
//!   (300 against 322) but far more driving, 16,193 s; with the time squared, cubed or to the
//!   fourth power in the rate, 15,724 s, 15,046 s and 14,787 s. Near parts left for later
//!   cost a long trip back.
//! - **A gain cast through a raster of what was seen** (rays through the part, stopped at
//!   walls seen before, counting unknown cells; the wedge counts space other scans already
//!   saw): 13,176 s. The soonest part is taken anyway, so the gain only picks among one part's
//!   candidates, where the two estimates agree.
//! - **Candidates near the part's end nearer the view's viewpoint** (a doorway, from where a
//!   scan sees the room and the corridor): 13,310 s, and 14,142 s on the other offices.
//! - **Borrowing another part's candidate** for the soonest part, when it sees across that
//!   part (12,610 s) or when both parts open into one hole of the union of the views
//!   (12,361 s, against 12,304 s): on office-2 the shadows of desks against walls stay
//!   joined to the unseen outside by the wall behind them, so they are not holes, and no
//!   candidate of one part sees across another's middle.
//! - Earlier: deferring parts with a small predicted gain, goals the footprint can pass, and
//!   more steps back (a 1 m step: 13,769 s).
//!
//! What did pay: the sensor rule's pocket term (`Sensor::min_pocket`, shared by every window
//! strategy). Of cost_aware's 29 scans on depot, the last 12 added under 0.5 m² each: the
//! hidden faces of pillars and shelves, whose windows open into holes of the union of what
//! was seen. Leaving holes under 0.5% of the area seen and under 2 m²: 11 scans on depot,
//! 12,268 s in all (0.80 × explore_lite), every map still above 99.2%; 12,304 s since parts
//! out of every single view's reach are planned through the union of the views; 12,334 s
//! since a viewpoint beside a part must see it (which cut `depth_first` to 13,506 s).
//!
//! Scans dominate the mission time (322 × 30 s of 13,129 s), and explore_lite scans as few
//! (315). On office-2, 16 of cost_aware's 32 scans and 12 of explore_lite's 29 add less than
//! 3 m² each (desk shadows, slivers between obstacles): the finishing guarantee visits every
//! such part that the window rule keeps, where explore_lite's raster drops openings under a
//! cell or two and clusters under 0.5 m.

use serde::{Deserialize, Serialize};

use super::known::{self, Known, Target};
use super::{PolygonFeedback, PolygonStrategy};
use crate::kernel::Point;
use crate::protocol::Action;
use crate::protocol::polygon::RobotSetup;

/// How far behind a window's own viewpoint the stepped-back candidates stand, metres. A 1 m
/// step was tried too: it sees little more than the window's own viewpoint and drew scans
/// toward door jambs (`bench floors`: 13,769 s with it, 13,036 s without; on 16 other offices,
/// seed 100, 14,375 s and 14,274 s).
const STEP_BACK: [f64; 2] = [2.0, 4.0];

/// Cost-aware exploration. Its whole state is serialisable.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CostAware {
    setup: RobotSetup,
    known: Known,
}

impl CostAware {
    /// A fresh strategy for a robot ([`RobotSetup`]): its cost model prices the trips, its
    /// sensor's range caps the predicted gain, its footprint and window rule apply.
    pub fn for_robot(setup: &RobotSetup) -> Self {
        Self { setup: setup.clone(), known: Known::for_robot(setup) }
    }

    /// The predicted new area of a scan at `z`: the wedges behind the open parts `gaps`
    /// (each with the view it belongs to) that `z` sees across the region of their view,
    /// out to that view's depth.
    fn gain(&self, z: Point, gaps: &[(usize, [Point; 2], f64)]) -> f64 {
        gaps.iter()
            .filter(|(u, g, _)| self.known.inside(*u, z) && self.known.sees_within(*u, z, *g))
            .map(|(_, g, depth)| wedge_beyond(z, g[0], g[1], *depth))
            .sum()
    }

    /// After the scan that became view `cur`: the candidate with the most predicted area per
    /// second.
    fn plan(&mut self, cur: usize) -> Action<Point> {
        let cost = self.setup.cost;
        let range = self.setup.sensor.range.unwrap_or(f64::INFINITY);
        // Every open window part, by view.
        let mut open: Vec<(usize, Vec<Target>)> = Vec::new();
        for v in 0..self.known.views.len() {
            if self.known.views[v].explored {
                continue;
            }
            let targets: Vec<Target> = (0..self.known.views[v].windows_len())
                .filter_map(|k| self.known.window_target(v, k).map(|t| t.0))
                .collect();
            if targets.is_empty() {
                self.known.views[v].explored = true;
            } else {
                open.push((v, targets));
            }
        }
        let known = &self.known;
        let gaps: Vec<(usize, [Point; 2], f64)> = open
            .iter()
            .flat_map(|(v, ts)| {
                let depth = range.min(known.reach_of(*v));
                ts.iter().map(move |t| (*v, known.gap_of(t), depth))
            })
            .collect();
        // Each window part's candidates, priced; the part whose best candidate comes soonest
        // (travel and scan time) goes first, at its candidate with the most area per second.
        let mut best: Option<(f64, f64, Target)> = None;
        for (v, targets) in &open {
            let route = self.known.route(cur, *v);
            for t in targets {
                let (steps, len) = self.known.trip_to(cur, t, &route);
                // The window's own viewpoint (reached straight or bending around corners),
                // then points stepped back from it that are reached straight.
                let mut zs = vec![t.clone()];
                zs.extend(
                    self.known.stepped_back(t, &STEP_BACK).into_iter().map(|z| t.moved_to(z)),
                );
                let mut part: Option<(f64, f64, Target)> = None;
                for z in zs {
                    let gain = self.gain(z.at, &gaps).max(f64::MIN_POSITIVE);
                    let dist = len + self.known.approach_length(&z);
                    let moves = steps + z.via.len() + 1;
                    let secs = cost.move_time * moves as f64 + dist / cost.speed + cost.scan_time;
                    let rate = gain / secs.max(f64::MIN_POSITIVE);
                    if part.as_ref().is_none_or(|b| rate > b.1) {
                        part = Some((secs, rate, z));
                    }
                }
                if let Some(p) = part
                    && best.as_ref().is_none_or(|b| p.0 < b.0)
                {
                    best = Some(p);
                }
            }
        }
        let Some((_, _, t)) = best else { return Action::Done };
        self.known.go_shortcut(cur, t)
    }
}

/// The area of the wedge that the segment `p q` subtends from `z`, beyond the segment and
/// within `depth` of `z` (0 if the segment lies beyond `depth`).
fn wedge_beyond(z: Point, p: Point, q: Point, depth: f64) -> f64 {
    let (a, b) = ([p[0] - z[0], p[1] - z[1]], [q[0] - z[0], q[1] - z[1]]);
    let (ra, rb) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
    if !depth.is_finite() || ra.min(rb) >= depth {
        return if depth.is_finite() { 0.0 } else { 0.5 * ra.max(rb) * ra.max(rb) };
    }
    let cross = a[0] * b[1] - a[1] * b[0];
    let theta = known::subtended(z, [p, q]);
    (0.5 * theta * depth * depth - 0.5 * cross.abs()).max(0.0)
}

impl PolygonStrategy for CostAware {
    fn name(&self) -> &'static str {
        "cost_aware"
    }

    fn act(&mut self, feedback: &PolygonFeedback) -> Action<Point> {
        known::act(self, feedback, |s| &mut s.known, Self::plan)
    }

    fn skipped(&self) -> super::Skipped {
        self.known.skipped
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_wedge_is_the_sector_less_the_triangle() {
        // A unit segment at distance 1, seen from the origin, out to depth 2: the sector of
        // angle 2·atan(1/2) and radius 2, less the triangle of base 1 and height 1.
        let w = wedge_beyond([0.0, 0.0], [1.0, -0.5], [1.0, 0.5], 2.0);
        let theta = 2.0 * 0.5f64.atan();
        assert!((w - (0.5 * theta * 4.0 - 0.5)).abs() < 1e-12, "{w}");
        // Beyond the depth: nothing.
        assert_eq!(wedge_beyond([0.0, 0.0], [3.0, -0.5], [3.0, 0.5], 2.0), 0.0);
    }
}
