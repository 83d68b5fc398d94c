//! Exact evaluation of corner strategies: worst-case competitive ratios by enumerating the
//! breakpoints of the piecewise cost, expected times by integrating over θ exactly, and the
//! global optimum over the plane ([`optimal`]).
//!
//! - here: [`worst_case`] and [`expected`];
//! - [`optimal`]: the globally optimal scan points over the plane (the circle paper's §3.2).

pub mod optimal;

use serde::{Deserialize, Serialize};

use crate::protocol::corner::{AngleDistribution, CORNER, CornerSetup};
use crate::strategy::corner::StopList;

/// The worst case of a stop list over all edge angles θ ∈ (0, π].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WorstCase {
    /// The strict supremum of `cost(θ) / OPT(θ)` over θ > 0.
    pub worst_ratio: f64,
    /// The θ (radians) it is approached at, from above: a stop angle, or 0.
    pub theta_at_worst: f64,
    /// The ratio with the competitive definition's additive constant `b`:
    /// the smallest `c` with `cost(θ) ≤ c·OPT(θ) + b` for all θ.
    pub asymptotic_ratio: f64,
    /// Where that is approached.
    pub theta_at_asymptotic: f64,
    /// The additive constant used, `b = sqrt(τ · D / v)` seconds.
    pub additive_constant: f64,
}

/// The exact worst-case competitive ratio of a stop list.
///
/// The cost is a step function of θ, constant on each `(φ_{k−1}, φ_k]` (and on
/// `(φ_{m−2}, π]` for the corner), while `OPT(θ) = τ + t_M + D·sin(min(θ, π/2))/v` increases.
/// So on each piece the ratio is largest as θ approaches the piece's left end from above,
/// and the supremum is the largest of these `m` breakpoint values: no sampling is involved.
///
/// The strict supremum is dominated, when δ = τv/D is not tiny, by edges just behind the
/// start line or just past an early stop, where the optimum is a single scan and the
/// strategy pays a few scans more. The competitive definition `cost ≤ c·OPT + b` allows an
/// additive constant; a constant `b` independent of θ but negligible against the large
/// instances is what makes the paper's ratios (π for UNIREC, (π/2)/sin(π/4) for EXPREC)
/// limits as δ → 0. We take `b = sqrt(τ·D/v)`, the geometric mean of one scan and the time
/// to reach the corner: `b/τ → ∞` absorbs any bounded number of extra scans while
/// `b / OPT → 0` on the instances that decide the limit.
///
/// # Complexity
/// O(m) time and space for m stops.
///
/// # Example
/// ```
/// use stopscan::protocol::{CostModel, corner::{CornerSetup, LastStep, Route}};
/// use stopscan::strategy::corner::unirec;
/// use stopscan::offline::corner::worst_case;
/// let setup = CornerSetup::new(1e4, CostModel::new(1.0, 0.0, 1.0).unwrap()).unwrap();
/// let list = unirec(setup.delta(), Route::Arc, LastStep::Capped).unwrap();
/// let w = worst_case(&list, &setup);
/// assert!((w.worst_ratio - std::f64::consts::PI).abs() < 1e-3);
/// ```
pub fn worst_case(list: &StopList, setup: &CornerSetup) -> WorstCase {
    let costs = list.costs(setup);
    let b = (setup.cost.scan_time * setup.distance / setup.cost.speed).sqrt();
    let mut w = WorstCase {
        worst_ratio: f64::NEG_INFINITY,
        theta_at_worst: 0.0,
        asymptotic_ratio: f64::NEG_INFINITY,
        theta_at_asymptotic: 0.0,
        additive_constant: b,
    };
    let mut left = 0.0;
    for (k, &cost) in costs.iter().enumerate() {
        let opt = setup.optimum(left);
        let r = cost / opt;
        if r > w.worst_ratio {
            (w.worst_ratio, w.theta_at_worst) = (r, left);
        }
        let a = (cost - b) / opt;
        if a > w.asymptotic_ratio {
            (w.asymptotic_ratio, w.theta_at_asymptotic) = (a, left);
        }
        left = list.angles()[k];
    }
    w
}

/// The expected outcome of a stop list when θ follows `truth`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Expected {
    /// Expected time to see the edge, seconds.
    pub time: f64,
    /// Expected number of scans.
    pub scans: f64,
    /// Expected metres driven.
    pub distance: f64,
}

/// The exact expected time of a stop list under a distribution of θ, integrated piece by
/// piece with the distribution's exact CDF.
///
/// # Complexity
/// O(m) CDF evaluations.
pub fn expected(list: &StopList, setup: &CornerSetup, truth: &AngleDistribution) -> Expected {
    let costs = list.costs(setup);
    let (tau, mt, v) = (setup.cost.scan_time, setup.cost.move_time, setup.cost.speed);
    let mut e = Expected { time: 0.0, scans: 0.0, distance: 0.0 };
    let mut left = 0.0;
    let last = costs.len() - 1;
    for (k, &cost) in costs.iter().enumerate() {
        let right = if k == last { std::f64::consts::PI } else { list.angles()[k] };
        let p = truth.mass(left, right);
        let n = (k + 1) as f64;
        e.time += p * cost;
        e.scans += p * n;
        e.distance += p * (cost - n * (tau + mt)) * v;
        left = right;
    }
    e
}

/// The paper's limits of the worst-case ratio as δ → 0, in closed form: π for UNIREC,
/// (π/2)/sin(π/4) for EXPREC (when a stop falls on π/4), 2 for the circle strategy.
pub fn limit_ratio(strategy: &str) -> Option<f64> {
    match strategy {
        "unirec" => Some(std::f64::consts::PI),
        "exprec" => Some(CORNER / std::f64::consts::FRAC_PI_4.sin()),
        "circle" => Some(2.0),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::CostModel;
    use crate::protocol::corner::{LastStep, Route};
    use crate::strategy::corner::{ExprecReading, circle, exprec, unirec};

    fn setup(d: f64) -> CornerSetup {
        CornerSetup::new(d, CostModel::new(1.0, 0.0, 1.0).unwrap()).unwrap()
    }

    #[test]
    fn unirec_worst_is_the_paper_bound() {
        // The paper: C ≤ (π + 2δ)/(1 + δ) attained at θ just above the last stop before π/2.
        for delta in [0.1, 0.01, 0.001] {
            let s = setup(1.0 / delta);
            let w = worst_case(&unirec(delta, Route::Arc, LastStep::Capped).unwrap(), &s);
            assert!(w.worst_ratio <= (std::f64::consts::PI + 2.0 * delta) / (1.0 + delta) + 1e-12);
            assert!(w.worst_ratio >= 2.0);
        }
        let s = setup(1e6);
        let w = worst_case(&unirec(1e-6, Route::Arc, LastStep::Capped).unwrap(), &s);
        assert!((w.worst_ratio - std::f64::consts::PI).abs() < 1e-5, "{w:?}");
    }

    #[test]
    fn exprec_tends_to_the_appendix_value_when_a_stop_hits_pi_over_4() {
        let target = limit_ratio("exprec").unwrap();
        let delta = std::f64::consts::FRAC_PI_4 / 2f64.powi(30);
        let s = setup(1.0 / delta);
        let w = worst_case(
            &exprec(delta, ExprecReading::TableI, Route::Arc, LastStep::Capped).unwrap(),
            &s,
        );
        assert!((w.asymptotic_ratio - target).abs() < 1e-3, "{w:?}");
        // The strict supremum is larger: just past the stop at 4δ the robot has paid 4 scans
        // and 8δ of travel against an optimum of 1 + 4 (all in units of τ): 12/5 = 2.4.
        assert!((w.worst_ratio - 2.4).abs() < 1e-6, "{w:?}");
        let a = exprec(delta, ExprecReading::Appendix, Route::Arc, LastStep::Capped).unwrap();
        let w = worst_case(&a, &s);
        // Appendix reading: just past δ, 2 scans and 3δ against 1 + 1: 5/2.
        assert!((w.worst_ratio - 2.5).abs() < 1e-6, "{w:?}");
        assert!((w.asymptotic_ratio - target).abs() < 1e-3, "{w:?}");
    }

    #[test]
    fn circle_stop_list_attains_c() {
        for d in [0.5, 1.0, 4.4, 40.0] {
            let sol = circle::solve(d).unwrap();
            let w = worst_case(&sol.stop_list(), &setup(d));
            assert!(
                (w.worst_ratio - sol.ratio).abs() < 1e-9,
                "d={d}: {} vs {}",
                w.worst_ratio,
                sol.ratio
            );
        }
    }

    #[test]
    fn expected_time_of_unirec_on_uniform() {
        // Hand computation: D=10, τ=2, v=0.5, δ=0.1, uniform on [0, π].
        let s = CornerSetup::new(10.0, CostModel::new(2.0, 0.0, 0.5).unwrap()).unwrap();
        let u = AngleDistribution::parse("uniform:0,180").unwrap();
        let list = unirec(0.1, Route::Arc, LastStep::Capped).unwrap();
        let e = expected(&list, &s, &u);
        let pi = std::f64::consts::PI;
        let want = (1..=15).map(|k| 4.0 * f64::from(k) * 0.1 / pi).sum::<f64>()
            + (pi - 1.5) / pi * (32.0 + 20.0 * pi / 2.0);
        assert!((e.time - want).abs() < 1e-9, "{} vs {want}", e.time);
    }
}
