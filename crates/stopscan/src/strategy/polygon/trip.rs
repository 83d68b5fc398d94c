//! The trip a polygon strategy is driving, and what it does when a move fails.
//!
//! A trip starts where the last scan was taken and runs through waypoints that all lie in
//! space seen free. When the robot reports that it could not reach a waypoint, the strategy
//! drops the trip's goal (the caller blacklists it) and the robot drives back the way it
//! came, through the waypoints it did reach, to where the trip started: from there every
//! route the strategy knows is valid again, and it plans anew. A way back that fails too is
//! tried again, up to [`MAX_MOVE_FAILURES`] failures in a row; then the trip gives up (the
//! robot is stuck where it came from), and the strategy scans where the robot stands to plan
//! on from there, once per place (`Known::stuck`).

use serde::{Deserialize, Serialize};

use crate::kernel::Point;
use crate::protocol::Action;

/// How many moves may fail in a row (no scan, no arrival between them) before a trip gives
/// up: the robot cannot even drive back the way it came.
pub const MAX_MOVE_FAILURES: u32 = 3;

/// A trip: the waypoints still to drive, and those reached since it started.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(super) struct Trip {
    /// Waypoints still to drive, last first.
    route: Vec<Point>,
    /// Where the trip started (the last scan's viewpoint).
    #[serde(default)]
    start: Option<Point>,
    /// The waypoints reached since, in order.
    #[serde(default)]
    driven: Vec<Point>,
    /// The waypoint the robot was sent to last.
    #[serde(default)]
    issued: Option<Point>,
    /// Driving back to `start` after a failed move.
    #[serde(default)]
    returning: bool,
    /// Failed moves since the last arrival.
    #[serde(default)]
    failures: u32,
    /// Where the way back after a failed move ends, when not at the start: the trip starts
    /// anew there.
    #[serde(default)]
    back_to: Option<Point>,
}

/// What the strategy does after an arrival.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Next {
    /// Drive on, or scan at the trip's end.
    Act(Action<Point>),
    /// Back where the trip started after a failed move: plan again from there.
    Replan,
}

impl Trip {
    /// A new trip from the scan at `start`, with no waypoints yet.
    pub(super) fn begin(&mut self, start: Point) {
        *self = Self { start: Some(start), ..Self::default() };
    }

    /// Sets the waypoints to drive (last first), replacing any left.
    pub(super) fn set_route(&mut self, route: Vec<Point>) {
        self.route = route;
        self.returning = false;
    }

    /// The next action: the next waypoint, or the scan at the trip's end.
    pub(super) fn next_move(&mut self) -> Action<Point> {
        match self.route.pop() {
            Some(p) => {
                self.issued = Some(p);
                Action::MoveTo { to: p }
            }
            None => Action::Scan,
        }
    }

    /// The robot reached the waypoint it was sent to.
    pub(super) fn arrived(&mut self) -> Next {
        self.failures = 0;
        if let Some(p) = self.issued.take() {
            if self.returning {
                self.driven.pop();
            } else {
                self.driven.push(p);
            }
        }
        if self.returning && self.route.is_empty() {
            self.returning = false;
            self.driven.clear();
            if let Some(p) = self.back_to.take() {
                self.start = Some(p);
            }
            return Next::Replan;
        }
        Next::Act(self.next_move())
    }

    /// The waypoint the robot was sent to last, unless it is driving back after a failed
    /// move.
    pub(super) fn issued_ahead(&self) -> Option<Point> {
        self.issued.filter(|_| !self.returning)
    }

    /// The waypoints still to drive after the one the robot was sent to last, in order (the
    /// last is where the trip's scan is to be taken); none while driving back after a failed
    /// move (that way ends in planning again, not in a scan).
    pub(super) fn ahead(&self) -> Vec<Point> {
        if self.returning { Vec::new() } else { self.route.iter().rev().copied().collect() }
    }

    /// The waypoints reached since the trip started, in order.
    pub(super) fn driven(&self) -> &[Point] {
        &self.driven
    }

    /// Forgets the trip: the robot scans where it stands.
    pub(super) fn clear(&mut self) {
        *self = Self::default();
    }

    /// Where the trip started: the last scan's viewpoint, or where a way back after a failed
    /// move ended.
    pub(super) fn start(&self) -> Option<Point> {
        self.start
    }

    /// [`failed`](Self::failed), with the way back ending at the latest waypoint reached for
    /// which `keep` holds (a viewpoint: from there every route the strategy knows is valid
    /// again), or at the start if none does. The robot drives less on odometry alone than all
    /// the way back: after a long trip without a scan, odometry's drift could put a way back
    /// of tens of metres into the shelves (the warehouse, `cost_aware`, seed 3, which then
    /// gave up at 97% of the area).
    pub(super) fn failed_back_to(&mut self, keep: impl Fn(Point) -> bool) -> Action<Point> {
        if self.returning || self.start.is_none() || self.failures >= MAX_MOVE_FAILURES {
            return self.failed();
        }
        let Some(k) = self.driven.iter().rposition(|&p| keep(p)) else { return self.failed() };
        self.failures += 1;
        self.back_to = Some(self.driven[k]);
        self.route = self.driven[k..].to_vec();
        self.returning = true;
        self.issued = None;
        self.next_move()
    }

    /// The robot could not reach the waypoint it was sent to: the way back to where the trip
    /// started, or done after [`MAX_MOVE_FAILURES`] failures in a row or with no start known.
    /// The caller drops the trip's goal before asking.
    pub(super) fn failed(&mut self) -> Action<Point> {
        self.failures += 1;
        let Some(start) = self.start else { return Action::Done };
        if self.failures > MAX_MOVE_FAILURES {
            return Action::Done;
        }
        if self.returning {
            // The way back failed: try the same waypoint again.
            if let Some(p) = self.issued.take() {
                self.route.push(p);
            }
        } else {
            // Back through the waypoints reached, latest first, to the start.
            let mut back = vec![start];
            back.extend_from_slice(&self.driven);
            self.route = back;
            self.returning = true;
            self.issued = None;
        }
        self.next_move()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_failed_move_drives_back_through_the_waypoints_reached_then_replans() {
        let mut t = Trip::default();
        t.begin([0.0, 0.0]);
        t.set_route(vec![[3.0, 0.0], [2.0, 0.0], [1.0, 0.0]]);
        // What lies ahead of each move, in order, ends where the trip scans.
        assert_eq!(t.ahead(), vec![[1.0, 0.0], [2.0, 0.0], [3.0, 0.0]]);
        assert_eq!(t.next_move(), Action::MoveTo { to: [1.0, 0.0] });
        assert_eq!(t.ahead(), vec![[2.0, 0.0], [3.0, 0.0]]);
        assert_eq!(t.arrived(), Next::Act(Action::MoveTo { to: [2.0, 0.0] }));
        assert_eq!(t.arrived(), Next::Act(Action::MoveTo { to: [3.0, 0.0] }));
        assert!(t.ahead().is_empty());
        // Blocked between (2, 0) and (3, 0): back to (2, 0), (1, 0), then the start.
        assert_eq!(t.failed(), Action::MoveTo { to: [2.0, 0.0] });
        assert!(t.returning);
        // The way back ends in planning again, not in a scan.
        assert!(t.ahead().is_empty());
        assert_eq!(t.arrived(), Next::Act(Action::MoveTo { to: [1.0, 0.0] }));
        // The way back fails once: the same waypoint again.
        assert_eq!(t.failed(), Action::MoveTo { to: [1.0, 0.0] });
        assert_eq!(t.arrived(), Next::Act(Action::MoveTo { to: [0.0, 0.0] }));
        assert_eq!(t.arrived(), Next::Replan);
        assert!(!t.returning);
    }

    #[test]
    fn a_failed_move_drives_back_only_to_the_latest_waypoint_kept() {
        let mut t = Trip::default();
        t.begin([0.0, 0.0]);
        t.set_route(vec![[3.0, 0.0], [2.0, 0.0], [1.0, 0.0]]);
        t.next_move();
        t.arrived();
        t.arrived();
        // Blocked between (2, 0) and (3, 0), and (1, 0) is a viewpoint: back to (2, 0), then
        // (1, 0), where the trip starts anew.
        let viewpoint = |p: Point| p == [1.0, 0.0];
        assert_eq!(t.failed_back_to(viewpoint), Action::MoveTo { to: [2.0, 0.0] });
        assert_eq!(t.arrived(), Next::Act(Action::MoveTo { to: [1.0, 0.0] }));
        assert_eq!(t.arrived(), Next::Replan);
        assert_eq!(t.start(), Some([1.0, 0.0]));
        // With no waypoint kept, all the way back to the start, as `failed` does.
        t.begin([0.0, 0.0]);
        t.set_route(vec![[2.0, 0.0], [1.0, 0.0]]);
        t.next_move();
        t.arrived();
        assert_eq!(t.failed_back_to(|_| false), Action::MoveTo { to: [1.0, 0.0] });
        assert_eq!(t.arrived(), Next::Act(Action::MoveTo { to: [0.0, 0.0] }));
        assert_eq!(t.arrived(), Next::Replan);
        assert_eq!(t.start(), Some([0.0, 0.0]));
    }

    #[test]
    fn a_robot_that_cannot_drive_back_gives_up() {
        let mut t = Trip::default();
        t.begin([0.0, 0.0]);
        t.set_route(vec![[1.0, 0.0]]);
        assert_eq!(t.next_move(), Action::MoveTo { to: [1.0, 0.0] });
        for _ in 0..MAX_MOVE_FAILURES {
            assert_eq!(t.failed(), Action::MoveTo { to: [0.0, 0.0] });
        }
        assert_eq!(t.failed(), Action::Done);
        // Without a start (no scan yet), nothing to return to.
        assert_eq!(Trip::default().failed(), Action::Done);
    }
}
