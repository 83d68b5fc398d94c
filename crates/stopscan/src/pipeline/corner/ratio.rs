//! `corner ratio`: exact worst-case ratios of named strategies and given stops.

use serde::{Deserialize, Serialize};

use super::{CornerError, positive};
use crate::kernel::Num;
use crate::offline::corner::{limit_ratio, worst_case};
use crate::protocol::CostModel;
use crate::protocol::corner::{AngleDistribution, CornerSetup};
use crate::strategy::corner::StopList;
use crate::strategy::corner::registry::{self, BuildOptions};

/// Stop angles (degrees, as given; positions from 1) that do not make a stop list.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StopsError {
    /// A stop is not finite and positive.
    #[error("stop {stop} is {}°; stops must be finite and positive", Num(*.angle))]
    NotPositive {
        /// Its position.
        stop: usize,
        /// Its angle.
        angle: f64,
    },
    /// A stop follows one that already reaches the corner.
    #[error(
        "stop {stop} ({}°) follows stop {} ({}°), which already reaches the corner (90°); end the list there",
        Num(*.angle), .stop - 1, Num(*.previous)
    )]
    AfterCorner {
        /// Its position.
        stop: usize,
        /// Its angle.
        angle: f64,
        /// The angle before it.
        previous: f64,
    },
    /// A stop is not above the one before.
    #[error(
        "stop {stop} ({}°) is not above stop {} ({}°); give increasing angles",
        Num(*.angle), .stop - 1, Num(*.previous)
    )]
    NotIncreasing {
        /// Its position.
        stop: usize,
        /// Its angle.
        angle: f64,
        /// The angle before it.
        previous: f64,
    },
}

/// `corner ratio`: the exact worst-case ratio of a stop list.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RatioReport {
    /// `unirec`, `exprec`, `circle` or `stops`.
    pub strategy: String,
    /// δ = τv/D.
    pub delta: f64,
    /// Stops of the list.
    pub stops: usize,
    /// The strict supremum of cost/OPT over θ > 0.
    pub worst_ratio: f64,
    /// Where it is approached, radians.
    pub theta_at_worst: f64,
    /// The same in degrees.
    pub theta_at_worst_deg: f64,
    /// The ratio with the additive constant.
    pub asymptotic_ratio: f64,
    /// Where that is approached, radians.
    pub theta_at_asymptotic: f64,
    /// The additive constant, in units of τ.
    pub additive_constant: f64,
    /// The papers' closed-form value as δ → 0.
    pub limit_ratio: Option<f64>,
    /// What the numbers mean.
    pub explanation: String,
}

/// The stop list of `strategy` at step `delta`: a registered `unirec`, `exprec` or
/// `circle` (only δ matters: τ = v = 1, D = 1/δ), or `stops` at the angles `stops_deg`.
///
/// # Errors
/// [`CornerError`] for an invalid δ, a strategy that cannot be built, or stop angles that do
/// not make a list.
pub fn stop_list(
    strategy: &str,
    delta: f64,
    stops_deg: &[f64],
    options: &BuildOptions,
) -> Result<StopList, CornerError> {
    let delta = positive("delta", delta)?;
    let unit = CornerSetup::new(1.0 / delta, CostModel::default())?;
    let none = AngleDistribution::uniform(0.0, std::f64::consts::PI)?;
    if strategy != "stops" {
        return Ok(registry::build(strategy, &unit, &none, options)?);
    }
    if stops_deg.is_empty() {
        return Err(CornerError::StopsNeeded);
    }
    check_stops_deg(stops_deg)?;
    let rad: Vec<f64> = stops_deg.iter().map(|d| d.to_radians()).collect();
    Ok(StopList::from_nominal(&rad, options.route, options.last_step)?)
}

/// Stop angles checked in degrees, as given: each positive, finite and above the one before,
/// and none after one that already reaches the corner (90°).
fn check_stops_deg(stops: &[f64]) -> Result<(), StopsError> {
    for (k, &angle) in stops.iter().enumerate() {
        let stop = k + 1;
        if !(angle.is_finite() && angle > 0.0) {
            return Err(StopsError::NotPositive { stop, angle });
        }
        if k > 0 {
            let previous = stops[k - 1];
            if previous >= 90.0 {
                return Err(StopsError::AfterCorner { stop, angle, previous });
            }
            if angle <= previous {
                return Err(StopsError::NotIncreasing { stop, angle, previous });
            }
        }
    }
    Ok(())
}

/// The exact worst-case ratio of `strategy` at step `delta` ([`stop_list`]).
///
/// # Errors
/// As [`stop_list`].
pub fn ratio(
    strategy: &str,
    delta: f64,
    stops_deg: &[f64],
    options: &BuildOptions,
) -> Result<RatioReport, CornerError> {
    let list = stop_list(strategy, delta, stops_deg, options)?;
    // Only δ matters: normalise τ = v = 1, D = 1/δ.
    let setup = CornerSetup::new(1.0 / delta, CostModel::default())?;
    let w = worst_case(&list, &setup);
    Ok(RatioReport {
        strategy: strategy.into(),
        delta,
        stops: list.len(),
        worst_ratio: w.worst_ratio,
        theta_at_worst: w.theta_at_worst,
        theta_at_worst_deg: w.theta_at_worst.to_degrees(),
        asymptotic_ratio: w.asymptotic_ratio,
        theta_at_asymptotic: w.theta_at_asymptotic,
        additive_constant: w.additive_constant,
        limit_ratio: limit_ratio(strategy),
        explanation: "worst_ratio is the strict supremum of cost/OPT over θ in (0, π], approached as θ decreases to theta_at_worst (radians); asymptotic_ratio is the smallest c with cost ≤ c·OPT + b for all θ, with the additive constant b = sqrt(τ·D/v) in units of τ, which absorbs a bounded number of scans near θ = 0 and vanishes against OPT as δ → 0; limit_ratio is the papers' closed-form value as δ → 0".into(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::corner::{LastStep, Route};

    #[test]
    fn stop_lists_by_name() {
        let o = BuildOptions::default();
        assert_eq!(stop_list("unirec", 0.5, &[], &o).unwrap().len(), 4);
        assert!(matches!(stop_list("stops", 0.5, &[], &o), Err(CornerError::StopsNeeded)));
        assert_eq!(stop_list("stops", 0.5, &[30.0, 60.0], &o).unwrap().len(), 3);
        let e = stop_list("stops", 0.5, &[60.0, 30.0], &o).unwrap_err();
        assert_eq!(e.to_string(), "stop 2 (30°) is not above stop 1 (60°); give increasing angles");
        let e = stop_list("stops", 0.5, &[90.0, 95.0], &o).unwrap_err();
        assert!(e.to_string().contains("already reaches the corner"), "{e}");
        let chord = BuildOptions { route: Route::Chord, last_step: LastStep::Nominal, ..o };
        assert!(stop_list("unirec", 0.1, &[], &chord).is_err());
    }
}
