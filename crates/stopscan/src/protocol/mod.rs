//! What a driver and a strategy say to each other, and the [`CostModel`] that prices it.
//!
//! Strategies are fed observations and answer with actions; they never see the ground
//! truth. Everything here is serde-serialisable so that a real robot (or a log replay) can
//! speak the same protocol as the simulator.
//!
//! - [`corner`]: the corner family's setup, stops, readings and beliefs
//!   ([`corner::AngleDistribution`]);
//! - [`polygon`]: what a scan returns ([`polygon::PolygonObservation`]);
//! - [`grid`]: the ROI family's cells, frames, votes, records and time model;
//! - here: [`CostModel`], [`Action`], [`Feedback`], [`Tally`].

pub mod corner;
pub mod grid;
pub mod laser;
pub mod polygon;

use serde::{Deserialize, Serialize};

/// The one cost model of stopscan: `T = scan_time * scans + move_time * moves + distance / speed`.
///
/// Times are in seconds, distances in metres. The papers name the terms differently: the
/// scan time is τ in the corner paper and 1 in the circle paper; the speed is `v` (1 in the
/// circle paper); the corner paper has no per-move time (it is 0 there).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CostModel {
    /// Seconds per scan (reconstruction), τ.
    pub scan_time: f64,
    /// Seconds charged for every move between two stops (acceleration, settling).
    pub move_time: f64,
    /// Metres per second, v.
    pub speed: f64,
}

impl Default for CostModel {
    /// The circle paper's normalisation: one unit per scan, unit speed, free moves.
    fn default() -> Self {
        Self { scan_time: 1.0, move_time: 0.0, speed: 1.0 }
    }
}

/// Why a [`CostModel`] was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidCostModel {
    /// A term is negative, NaN or infinite. Give finite, non-negative times.
    #[error("{term} must be finite and non-negative, got {}", crate::kernel::Num(*.value))]
    NegativeOrNonFinite {
        /// The offending field.
        term: &'static str,
        /// Its value.
        value: f64,
    },
    /// The speed is zero, negative, NaN or infinite. Give a finite positive speed.
    #[error("speed must be finite and positive, got {}", crate::kernel::Num(*.0))]
    NonPositiveSpeed(f64),
}

impl CostModel {
    /// Builds a validated cost model.
    ///
    /// # Errors
    /// [`InvalidCostModel`] if a time is negative or not finite, or the speed is not positive.
    pub fn new(scan_time: f64, move_time: f64, speed: f64) -> Result<Self, InvalidCostModel> {
        for (term, value) in [("scan_time", scan_time), ("move_time", move_time)] {
            if !value.is_finite() || value < 0.0 {
                return Err(InvalidCostModel::NegativeOrNonFinite { term, value });
            }
        }
        if !speed.is_finite() || speed <= 0.0 {
            return Err(InvalidCostModel::NonPositiveSpeed(speed));
        }
        Ok(Self { scan_time, move_time, speed })
    }

    /// The total time of a tally.
    pub fn time(&self, tally: &Tally) -> f64 {
        self.price(tally).total()
    }

    /// Each term of the time of a tally, separately.
    pub fn price(&self, tally: &Tally) -> TimeBreakdown {
        TimeBreakdown {
            scan_time_total: self.scan_time * tally.scans as f64,
            move_time_total: self.move_time * tally.moves as f64,
            travel_time_total: tally.distance / self.speed,
        }
    }
}

/// What a run did: the quantities the [`CostModel`] prices.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Tally {
    /// Number of scans taken.
    pub scans: u64,
    /// Number of moves between stops.
    pub moves: u64,
    /// Metres driven.
    pub distance: f64,
}

/// The time of a run, term by term (DESIGN.md's metric names).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct TimeBreakdown {
    /// `scan_time * scans`.
    pub scan_time_total: f64,
    /// `move_time * moves`.
    pub move_time_total: f64,
    /// `distance / speed`.
    pub travel_time_total: f64,
}

impl TimeBreakdown {
    /// The sum of the three terms.
    pub fn total(&self) -> f64 {
        self.scan_time_total + self.move_time_total + self.travel_time_total
    }
}

/// What a run did and what it cost, term by term: the metrics every family's run record
/// and sweep row share (DESIGN.md's names). Records embed it flattened, so its fields sit
/// beside the family's own metrics.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct RunTotals {
    /// Scans (all robots).
    pub scans: u64,
    /// Moves (all robots).
    pub moves: u64,
    /// Metres driven or flown (all robots).
    pub distance: f64,
    /// Total time, seconds: the sum of the three terms for one robot; for a team, when the
    /// last robot is done.
    pub time: f64,
    /// `scan_time · scans`.
    pub scan_time_total: f64,
    /// `move_time · moves`.
    pub move_time_total: f64,
    /// `distance / speed`.
    pub travel_time_total: f64,
}

impl RunTotals {
    /// The totals of a tally whose terms are `terms` and whose time is `time`.
    pub fn new(tally: &Tally, time: f64, terms: &TimeBreakdown) -> Self {
        Self {
            scans: tally.scans,
            moves: tally.moves,
            distance: tally.distance,
            time,
            scan_time_total: terms.scan_time_total,
            move_time_total: terms.move_time_total,
            travel_time_total: terms.travel_time_total,
        }
    }
}

/// The shared action vocabulary: every family answers move, scan or done.
///
/// `P` is the family's notion of a place (a point of the plane, a stop on the corner
/// circle, a grid cell).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "action", rename_all = "snake_case")]
pub enum Action<P> {
    /// Drive to a place, then stop.
    MoveTo {
        /// Where to go.
        to: P,
    },
    /// Take a scan where the robot stands.
    Scan,
    /// The task is complete (or cannot progress); the driver stops.
    Done,
}

/// What the driver tells a strategy before asking for its next action. `P` is the family's
/// place, `O` its observation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum Feedback<P, O> {
    /// The run begins at this place. A named field, not a newtype: an internally tagged
    /// newtype variant cannot hold an array place (`[f64; 2]`, a grid cell), so a state saved
    /// before the first step would not serialise.
    Start {
        /// Where the robot stands.
        at: P,
    },
    /// The robot reached the place it asked for.
    Arrived,
    /// The scan it asked for.
    Scanned(O),
    /// The robot could not reach the place it asked for and stopped at `at`. The strategy
    /// drops (blacklists) that goal and goes on.
    MoveFailed {
        /// Where the robot stands now.
        at: P,
        /// Why the move failed.
        reason: MoveFailure,
    },
}

/// Why a move failed, as a navigation stack reports it (nav2's goal outcomes).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MoveFailure {
    /// The way is blocked, or the goal lies in an obstacle or where the robot does not fit.
    Blocked,
    /// The navigation stack gave up (nav2's `ABORTED`).
    Aborted,
    /// The move took too long (no progress within the navigation stack's timeout).
    TimedOut,
}

impl MoveFailure {
    /// The name used in the protocol and in traces.
    pub fn name(self) -> &'static str {
        match self {
            Self::Blocked => "blocked",
            Self::Aborted => "aborted",
            Self::TimedOut => "timed_out",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn prices_each_term() {
        let m = CostModel::new(2.0, 0.5, 0.5).unwrap();
        let t = Tally { scans: 3, moves: 2, distance: 10.0 };
        let p = m.price(&t);
        assert_eq!(p.scan_time_total, 6.0);
        assert_eq!(p.move_time_total, 1.0);
        assert_eq!(p.travel_time_total, 20.0);
        assert_eq!(m.time(&t), 27.0);
    }

    /// Every event serialises and reads back, for array places too (a polygon point, a grid
    /// cell): a saved state may hold any of them, the start included.
    #[test]
    fn every_event_round_trips_with_array_places() {
        #[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
        struct Seen {
            area: f64,
        }
        let events: [Feedback<[f64; 2], Seen>; 4] = [
            Feedback::Start { at: [1.5, -2.0] },
            Feedback::Arrived,
            Feedback::Scanned(Seen { area: 2.5 }),
            Feedback::MoveFailed { at: [0.5, 0.25], reason: MoveFailure::TimedOut },
        ];
        for e in events {
            let text = serde_json::to_string(&e).unwrap();
            let back: Feedback<[f64; 2], Seen> = serde_json::from_str(&text).unwrap();
            assert_eq!(back, e, "{text}");
        }
        let cell: Feedback<[i64; 2], ()> = Feedback::Start { at: [3, 4] };
        assert_eq!(serde_json::to_string(&cell).unwrap(), r#"{"event":"start","at":[3,4]}"#);
        let failed: Feedback<[i64; 2], ()> =
            Feedback::MoveFailed { at: [1, 2], reason: MoveFailure::Blocked };
        assert_eq!(
            serde_json::to_string(&failed).unwrap(),
            r#"{"event":"move_failed","at":[1,2],"reason":"blocked"}"#
        );
    }

    #[test]
    fn rejects_bad_terms() {
        assert!(CostModel::new(-1.0, 0.0, 1.0).is_err());
        assert!(CostModel::new(1.0, f64::NAN, 1.0).is_err());
        assert!(CostModel::new(1.0, 0.0, 0.0).is_err());
        assert!(CostModel::new(1.0, 0.0, f64::INFINITY).is_err());
    }
}
