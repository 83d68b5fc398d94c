//! The corner family: looking around a corner when every scan costs time.
//!
//! The robot stands at `x = (0, 0)`; the corner `y = (D, 0)` is known. The hidden edge leaves
//! `y` at an unknown angle θ ∈ [0, π] from the line `xy`. Stops lie on the circle of diameter
//! `xy` (the corner paper's Fig. 1): the stop at angle φ = ∠xyz lies at arc length `D·φ` from
//! `x`, and a scan there sees the edge exactly when θ ≤ φ. The corner itself is φ = π/2 and
//! sees every θ; edges with θ ≥ π/2 are seen only from the corner.
//!
//! - `distribution`: [`AngleDistribution`], beliefs and truths about θ with exact CDFs;
//! - here: the setup, the stops and what a scan tells.

mod distribution;

pub use distribution::{AngleDistribution, BucketProblem, InvalidDistribution, MAX_BUCKETS};

use serde::{Deserialize, Serialize};

use super::CostModel;

/// A right angle, the corner's stop angle.
pub const CORNER: f64 = std::f64::consts::FRAC_PI_2;

/// What the robot knows before it starts: the distance to the corner and the cost model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CornerSetup {
    /// Distance `D` from the robot to the corner, in metres.
    pub distance: f64,
    /// How time is charged.
    pub cost: CostModel,
}

/// Why a [`CornerSetup`] was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidCornerSetup {
    /// The distance must be finite and positive.
    #[error("the distance to the corner must be finite and positive, got {}", crate::kernel::Num(*.0))]
    Distance(f64),
    /// The scan time must be positive: with free scans the problem is the continuous one.
    #[error("the scan time must be positive for the corner problem, got {}", crate::kernel::Num(*.0))]
    ScanTime(f64),
}

impl CornerSetup {
    /// A validated setup.
    ///
    /// # Errors
    /// [`InvalidCornerSetup`] for a non-positive distance or scan time.
    pub fn new(distance: f64, cost: CostModel) -> Result<Self, InvalidCornerSetup> {
        if !distance.is_finite() || distance <= 0.0 {
            return Err(InvalidCornerSetup::Distance(distance));
        }
        if cost.scan_time <= 0.0 {
            return Err(InvalidCornerSetup::ScanTime(cost.scan_time));
        }
        Ok(Self { distance, cost })
    }

    /// The corner paper's δ = τ·v / D: the angle travelled on the circle in one scan time.
    pub fn delta(&self) -> f64 {
        self.cost.scan_time * self.cost.speed / self.distance
    }

    /// The circle paper's normalised distance `d = D / (v·τ) = 1/δ`.
    pub fn normalised_distance(&self) -> f64 {
        1.0 / self.delta()
    }

    /// The point of the circle at stop angle φ (φ = 0 is the robot, φ = π/2 the corner).
    pub fn position(&self, angle: f64) -> [f64; 2] {
        let (s, c) = angle.sin_cos();
        [self.distance * s * s, self.distance * s * c]
    }

    /// Metres driven from stop angle `from` to stop angle `to` (`to ≥ from`) along `route`.
    pub fn travel(&self, from: f64, to: f64, route: Route) -> f64 {
        match route {
            Route::Arc => self.distance * (to - from),
            Route::Chord => self.distance * (to - from).min(CORNER).sin(),
        }
    }

    /// The offline optimum for edge angle θ: one move and one scan from the foot of the
    /// perpendicular to the edge's line, `τ + t_M + D·sin θ / v` for θ < π/2 and
    /// `τ + t_M + D / v` otherwise.
    pub fn optimum(&self, theta: f64) -> f64 {
        let reach = if theta < CORNER { theta.max(0.0).sin() } else { 1.0 };
        self.cost.scan_time + self.cost.move_time + self.distance * reach / self.cost.speed
    }
}

/// How the robot drives between two stops on the circle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Route {
    /// Along the circle, as the corner paper charges it (`D·Δφ`).
    #[default]
    Arc,
    /// Along the straight chord (`D·sin Δφ`), the circle paper's polygonal path and the
    /// corner paper's footnote 1.
    Chord,
}

/// How a last step that would pass the corner is charged.
///
/// UNIREC and EXPREC visit angles `iδ` (or `2^i δ`) until the edge is seen; the last one can
/// exceed π/2, where the corner already is. The paper's cost formula `⌈θ/δ⌉δ·D/v` charges the
/// nominal angle, which no robot can drive; the physical reading stops at the corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LastStep {
    /// Stop at the corner and charge the distance actually driven (default).
    #[default]
    Capped,
    /// Charge the nominal angle of the last stop, as the paper's formula does (arc route only).
    Nominal,
}

/// What a scan at a stop tells the robot.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "seen", rename_all = "snake_case")]
pub enum CornerObservation {
    /// The hidden edge is visible; its angle is now known.
    Seen {
        /// The edge angle θ, radians.
        theta: f64,
    },
    /// The edge is still hidden: θ is larger than the stop angle of this scan.
    Hidden,
}

/// A place in the corner family: a stop angle on the circle, with the route that reaches it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Stop {
    /// Stop angle φ ∈ (0, π/2]; a nominal angle above π/2 means the corner.
    pub angle: f64,
    /// How to drive there from the current stop.
    pub route: Route,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setup() -> CornerSetup {
        CornerSetup::new(10.0, CostModel::new(2.0, 0.0, 0.5).unwrap()).unwrap()
    }

    #[test]
    fn circle_positions() {
        let s = setup();
        let p0 = s.position(0.0);
        let p1 = s.position(CORNER);
        assert!(p0[0].abs() < 1e-12 && p0[1].abs() < 1e-12);
        assert!((p1[0] - 10.0).abs() < 1e-12 && p1[1].abs() < 1e-12);
        // Inscribed angle: the chord from x to the stop at φ has length D sin φ.
        let p = s.position(0.3);
        assert!((p[0].hypot(p[1]) - 10.0 * 0.3f64.sin()).abs() < 1e-12);
    }

    #[test]
    fn delta_and_optimum() {
        let s = setup();
        assert!((s.delta() - 0.1).abs() < 1e-15);
        assert!((s.optimum(CORNER) - 22.0).abs() < 1e-12);
        assert!((s.optimum(3.0) - 22.0).abs() < 1e-12);
        assert!((s.optimum(0.0) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_degenerate_setups() {
        assert!(CornerSetup::new(0.0, CostModel::default()).is_err());
        assert!(CornerSetup::new(1.0, CostModel::new(0.0, 0.0, 1.0).unwrap()).is_err());
    }
}
