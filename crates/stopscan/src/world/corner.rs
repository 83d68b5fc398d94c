//! The corner world: a known corner at distance `D` and a hidden edge at angle θ.

use serde::{Deserialize, Serialize};

use crate::protocol::corner::{CORNER, CornerObservation, CornerSetup, LastStep, Route, Stop};

/// The truth of one corner instance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CornerWorld {
    /// What the robot is told.
    pub setup: CornerSetup,
    /// The hidden edge angle θ ∈ [0, π] (radians), unknown to the robot.
    pub theta: f64,
    /// How a step that asks to pass the corner is charged.
    pub last_step: LastStep,
}

impl CornerWorld {
    /// Drives from stop angle `from` towards `to`. The robot cannot pass the corner: it stops
    /// there, and the step is charged as [`LastStep`] says. Returns `(reached angle, metres)`.
    pub fn drive(&self, from: f64, to: &Stop) -> (f64, f64) {
        let reached = to.angle.min(CORNER);
        let charged = match (self.last_step, to.route) {
            (LastStep::Nominal, Route::Arc) => to.angle,
            _ => reached,
        };
        (reached, self.setup.travel(from, charged.max(from), to.route))
    }

    /// The sensor: a scan at stop angle φ sees the edge exactly when θ ≤ φ, or at the corner.
    pub fn scan(&self, at: f64) -> CornerObservation {
        if at >= CORNER || self.theta <= at {
            CornerObservation::Seen { theta: self.theta }
        } else {
            CornerObservation::Hidden
        }
    }
}
