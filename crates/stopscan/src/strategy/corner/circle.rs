//! The circle strategy of the circle paper (Fekete, Klein, Nüchter, §3.3).
//!
//! Units: one scan costs 1 and the speed is 1, so the corner lies at the normalised distance
//! `d = D / (v·τ)`. The robot drives chords of the semicircle spanned by start and corner. A
//! chord of length `x_j` is seen from the corner under `φ_j = arcsin(x_j / d)`, and the chord
//! from the start to position `i` is `d_i = d·sin(Σ φ_j)`. Recursion (1) makes the ratio equal
//! to `c` for an object hidden just behind each scan line:
//!
//! `x_1 = c − 1`, `x_{i+1} = c·(1 + d_i) − (i + 1) − Σ_{j≤i} x_j`.
//!
//! If the sequence reaches the corner, ratio `c` is achievable; if a step is not positive,
//! it collapses. The smallest achievable `c` is found by bisection.

use serde::{Deserialize, Serialize};

use crate::kernel::Num;
use crate::protocol::corner::{CORNER, LastStep, Route};
use crate::strategy::corner::StopList;

/// Why the circle strategy cannot be computed.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CircleError {
    /// The normalised distance to the corner is not a finite positive number.
    #[error("the distance must be a finite positive number, got {}", Num(*.0))]
    Distance(f64),
    /// The normalised distance is beyond [`MAX_DISTANCE`], where `c(d) − 2 < 1/d` is below
    /// what double precision resolves and the recursion's answer would be meaningless.
    #[error(
        "the distance {} is beyond {} (in units of v·τ): c(d) differs from 2 by less than 1/d, \
         below double precision; c(d) = 2 to every printed digit there",
        Num(*.0),
        Num(MAX_DISTANCE)
    )]
    TooFar(f64),
}

/// The largest normalised distance `d = D/(vτ)` the recursion is computed for. Beyond about
/// 1e18 the bracket `(2 − 1/d, …)` collapses in double precision and no `c` reaches; 1e15
/// keeps a margin of three orders of magnitude.
pub const MAX_DISTANCE: f64 = 1e15;

/// `d` if it is a distance the recursion accepts: finite, positive and at most
/// [`MAX_DISTANCE`].
fn distance(d: f64) -> Result<f64, CircleError> {
    if !(d.is_finite() && d > 0.0) {
        Err(CircleError::Distance(d))
    } else if d > MAX_DISTANCE {
        Err(CircleError::TooFar(d))
    } else {
        Ok(d)
    }
}

/// The largest `c` that the bisection starts from when it reaches; `c(d) ≤ 2.17` for all `d`.
const SAFE_HI: f64 = 3.0;

/// The relative precision to which [`ratio`] and the thresholds of Table 1 are searched.
const PRECISION: f64 = 1e-12;

/// How the recursion ended for one `(d, c)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// The sequence reaches the corner with this many steps (the last one ends at the corner).
    Reached(usize),
    /// A step was not positive after this many completed steps.
    Collapsed(usize),
}

/// Runs recursion (1) for distance `d` and ratio `c` without allocating.
///
/// Angles are accumulated with the addition theorem (`sin`, `cos` of `Σ φ_j` updated by one
/// square root per step), so no trigonometric call is made.
///
/// # Complexity
/// O(steps) time, O(1) space; the number of steps is at most `c·(1 + d) + 2`.
///
/// For distances far below 1, `c − 1` loses low bits when `c` is formed; use [`run_excess`]
/// with the excess from [`ratio_excess`] to replay the search's own decision exactly.
pub fn run(d: f64, c: f64) -> Outcome {
    walk(d, c - 1.0, |_, _, _| ())
}

/// [`run`] with the excess `e = c − 1` given directly (exact for any distance).
pub fn run_excess(d: f64, e: f64) -> Outcome {
    walk(d, e, |_, _, _| ())
}

/// The recursion with a callback `(step length, sin α, cos α)` after each full step.
///
/// It takes the excess `e = c − 1` rather than `c`, so that `x_1 = e` is exact even when
/// `d` (and hence `e`) is tiny and `(1 + d) − 1` would cancel.
fn walk(d: f64, e: f64, mut on_step: impl FnMut(f64, f64, f64)) -> Outcome {
    // Keep every operation identical to `reaches3`, which must agree to the last bit.
    let inv_d = 1.0 / d;
    let (mut s, mut co, mut sum_x) = (0.0_f64, 1.0_f64, 0.0_f64);
    let mut x = e;
    let limit = step_limit(d, e);
    for i in 0..limit {
        if x.is_nan() || x <= 0.0 {
            return Outcome::Collapsed(i);
        }
        if x >= d * co {
            return Outcome::Reached(i + 1);
        }
        let sp = x * inv_d;
        let cp = (1.0 - sp * sp).sqrt();
        (s, co) = (s * cp + co * sp, co * cp - s * sp);
        sum_x += x;
        on_step(x, s, co);
        x = (1.0 + e) * (1.0 + d * s) - (i + 2) as f64 - sum_x;
    }
    Outcome::Collapsed(limit)
}

/// A guard on the number of steps: `x_{i+1} ≤ c·(1 + d) − (i + 1)`, so no walk is longer.
fn step_limit(d: f64, e: f64) -> usize {
    ((1.0 + e) * (1.0 + d)).ceil() as usize + 2
}

/// The smallest ratio `c(d)` the circle strategy achieves at normalised distance `d`.
///
/// # Arguments
/// `d > 0`, the distance to the corner in units of `v·τ`.
///
/// # Returns
/// `c(d)` to a relative precision of 1e-12.
///
/// # Errors
/// [`CircleError::Distance`] unless `d` is finite and positive.
///
/// # Complexity
/// O(20 · steps) time (20 rounds of three interleaved walks), O(1) space.
///
/// # Example
/// ```
/// let c = stopscan::strategy::corner::circle::ratio(40.0).unwrap();
/// assert!((c - 2.001525).abs() < 1e-6);
/// ```
pub fn ratio(d: f64) -> Result<f64, CircleError> {
    Ok(1.0 + ratio_excess(d)?)
}

/// `c(d) − 1`, searched directly so that small distances keep full relative precision.
///
/// # Errors
/// [`CircleError::Distance`] unless `d` is finite and positive.
pub fn ratio_excess(d: f64) -> Result<f64, CircleError> {
    Ok(excess_to(distance(d)?, PRECISION))
}

/// `c(d) − 1` to a relative tolerance `tol` (0 means: to adjacent floating-point numbers).
///
/// Each round runs three walks at the quarter points of the bracket in lockstep
/// ([`reaches3`]): the walk is a chain of dependent square roots, so three independent
/// chains cost little more than one, and each round shrinks the bracket fourfold. `d` is
/// finite and positive ([`distance`]).
fn excess_to(d: f64, tol: f64) -> f64 {
    debug_assert!(d.is_finite() && d > 0.0, "the distance must be finite and positive");
    // e = d reaches at once (x_1 = d is the whole diameter).
    let mut hi = d;
    if hi > SAFE_HI - 1.0 && reaches3(d, [SAFE_HI - 1.0; 3])[0] {
        hi = SAFE_HI - 1.0;
    }
    // Theorem 1: for d ≥ 1/δ no ratio 2 − δ is achievable, so c(d) > 2 − 1/d.
    let mut lo = (1.0 - 1.0 / d).max(0.0);
    loop {
        let w = hi - lo;
        let q = [lo + 0.25 * w, lo + 0.5 * w, lo + 0.75 * w];
        if w <= tol * (1.0 + hi) || !(lo < q[0] && q[0] < q[1] && q[1] < q[2] && q[2] < hi) {
            // Finish with plain bisection down to adjacent floats.
            loop {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi || hi - lo <= tol * (1.0 + hi) {
                    return hi;
                }
                if reaches3(d, [mid; 3])[0] {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
        }
        let r = reaches3(d, q);
        // Reaching is monotone in c: the first reaching quarter point is the new upper end.
        match r.iter().position(|&x| x) {
            Some(0) => hi = q[0],
            Some(k) => (lo, hi) = (q[k - 1], q[k]),
            None => lo = q[2],
        }
    }
}

/// Runs recursion (1) for three excesses at once and tells which reach the corner.
fn reaches3(d: f64, e: [f64; 3]) -> [bool; 3] {
    let inv_d = 1.0 / d;
    let mut s = [0.0_f64; 3];
    let mut co = [1.0_f64; 3];
    let mut sum = [0.0_f64; 3];
    let mut x = e;
    let mut done = [false; 3];
    let mut reached = [false; 3];
    let limit = e.map(|ek| step_limit(d, ek));
    for i in 0.. {
        for k in 0..3 {
            if done[k] {
                continue;
            }
            if i >= limit[k] || x[k].is_nan() || x[k] <= 0.0 {
                done[k] = true;
            } else if x[k] >= d * co[k] {
                done[k] = true;
                reached[k] = true;
            } else {
                let sp = x[k] * inv_d;
                let cp = (1.0 - sp * sp).sqrt();
                (s[k], co[k]) = (s[k] * cp + co[k] * sp, co[k] * cp - s[k] * sp);
                sum[k] += x[k];
                x[k] = (1.0 + e[k]) * (1.0 + d * s[k]) - (i + 2) as f64 - sum[k];
            }
        }
        if done.iter().all(|&b| b) {
            break;
        }
    }
    reached
}

/// A solved circle strategy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CircleSolution {
    /// Normalised distance `d`.
    pub distance: f64,
    /// The achieved ratio `c(d)`.
    pub ratio: f64,
    /// Intermediate scans (the paper's "number of scans"; the scan at the corner is extra).
    pub scans: usize,
    /// Step lengths, the last one ending at the corner (`scans + 1` of them).
    pub steps: Vec<f64>,
    /// Corner angle `Σ φ_j` of each scan point (radians; the last is π/2).
    pub angles: Vec<f64>,
    /// The scan points, start at `(0, 0)` and corner at `(d, 0)`; the last is the corner.
    pub scan_points: Vec<[f64; 2]>,
}

impl CircleSolution {
    /// The same scan points as a corner-paper stop list (chord route).
    ///
    /// # Panics
    /// If the public fields were edited so that `angles` is empty or not strictly increasing
    /// below the corner: a solution from [`solve`] always satisfies both.
    pub fn stop_list(&self) -> StopList {
        let inner = &self.angles[..self.angles.len() - 1];
        StopList::from_nominal(inner, Route::Chord, LastStep::Capped)
            .expect("circle angles are strictly increasing below the corner")
    }
}

/// Solves the circle strategy at normalised distance `d`: ratio, steps and scan points.
///
/// # Errors
/// [`CircleError::Distance`] unless `d` is finite and positive.
///
/// # Complexity
/// O(45 · steps) time, O(steps) space.
pub fn solve(d: f64) -> Result<CircleSolution, CircleError> {
    let e = ratio_excess(d)?;
    let c = 1.0 + e;
    let (mut steps, mut angles, mut points) = (Vec::new(), Vec::new(), Vec::new());
    let mut last_cos = 1.0;
    let outcome = walk(d, e, |x, s, co| {
        steps.push(x);
        angles.push(s.atan2(co));
        points.push([d * s * s, d * s * co]);
        last_cos = co;
    });
    debug_assert!(matches!(outcome, Outcome::Reached(_)));
    steps.push(d * last_cos);
    angles.push(CORNER);
    points.push([d, 0.0]);
    Ok(CircleSolution {
        distance: d,
        ratio: c,
        scans: steps.len() - 1,
        steps,
        angles,
        scan_points: points,
    })
}

/// One row of the circle paper's Table 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Threshold {
    /// Intermediate scans.
    pub scans: usize,
    /// The largest distance at which that many intermediate scans suffice.
    pub distance: f64,
    /// `c` at that distance, a local maximum (cusp) of `c(d)`.
    pub ratio: f64,
}

/// The intermediate scans the circle strategy needs at distance `d`.
///
/// # Errors
/// [`CircleError::Distance`] unless `d` is finite and positive.
pub fn scans(d: f64) -> Result<usize, CircleError> {
    Ok(scans_at(distance(d)?))
}

/// [`scans`] for a finite positive `d`.
fn scans_at(d: f64) -> usize {
    // Near a threshold the extra scan's step is O(Δd²): use the last bits.
    match walk(d, excess_to(d, 0.0), |_, _, _| ()) {
        Outcome::Reached(n) => n - 1,
        Outcome::Collapsed(_) => unreachable!("ratio() returns a reaching c"),
    }
}

/// The distances at which the circle strategy needs one more scan (Table 1), for
/// `0..count` intermediate scans.
///
/// Each threshold is bracketed by a march in `d` and refined by bisection to 1e-12.
pub fn thresholds(count: usize) -> Vec<Threshold> {
    let mut out = Vec::with_capacity(count);
    let mut lo = 1e-6;
    for k in 0..count {
        let mut hi = lo;
        while scans_at(hi) <= k {
            lo = hi;
            hi += 0.05 * (1.0 + hi.sqrt());
        }
        while hi - lo > PRECISION * hi {
            let mid = 0.5 * (lo + hi);
            if scans_at(mid) <= k {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        out.push(Threshold { scans: k, distance: lo, ratio: 1.0 + excess_to(lo, 0.0) });
        lo = hi;
    }
    out
}

/// Theorem 1 made visible: for `c < 2` the recursion collapses before the corner when
/// `d ≥ 1 / (2 − c)`; the robot never gets further than `1 / (2 − c)` from the start.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Collapse {
    /// The ratio tried.
    pub ratio: f64,
    /// The distance tried.
    pub distance: f64,
    /// Whether the sequence reached the corner.
    pub reached: bool,
    /// Steps completed before the collapse.
    pub steps: usize,
    /// The farthest the robot got from the start (`d·sin Σφ`).
    pub farthest: f64,
    /// The proof's bound `1 / (2 − c)` on that distance (infinite for `c ≥ 2`).
    pub bound: f64,
}

/// Runs the recursion at `(d, c)` and reports how far it got.
pub fn collapse(d: f64, c: f64) -> Collapse {
    let mut farthest = 0.0_f64;
    let outcome = walk(d, c - 1.0, |_, s, _| farthest = farthest.max(d * s));
    let (reached, steps) = match outcome {
        Outcome::Reached(n) => (true, n),
        Outcome::Collapsed(n) => (false, n),
    };
    if reached {
        farthest = d;
    }
    let bound = if c < 2.0 { 1.0 / (2.0 - c) } else { f64::INFINITY };
    Collapse { ratio: c, distance: d, reached, steps, farthest, bound }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d40_brackets_of_figure_4() {
        assert!(matches!(run(40.0, 2.0016), Outcome::Reached(_)));
        assert!(matches!(run(40.0, 2.0015), Outcome::Collapsed(_)));
        // The paper prints "2.001525..." (truncated).
        assert_eq!((ratio(40.0).unwrap() * 1e6).floor(), 2_001_525.0);
    }

    #[test]
    fn distances_that_are_not_finite_and_positive_are_errors() {
        for d in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(solve(d), Err(CircleError::Distance(_))), "{d}");
            assert!(ratio(d).is_err() && scans(d).is_err(), "{d}");
        }
        assert_eq!(
            solve(-1.0).unwrap_err().to_string(),
            "the distance must be a finite positive number, got -1"
        );
    }

    /// Up to the limit the ratio is the strategy's (about 2, above Theorem 1's 2 − 1/d, with
    /// scans); beyond it the distance is refused rather than answered with a meaningless c.
    #[test]
    fn huge_distances_are_solved_up_to_the_limit_and_refused_beyond() {
        for d in [1e9, 1e12, MAX_DISTANCE] {
            let c = ratio(d).unwrap();
            assert!(c >= 2.0 - 1.0 / d && c < 2.0 + 1e-9, "c({d}) = {c}");
            assert!(scans(d).unwrap() > 50, "{d}");
        }
        for d in [1.0001 * MAX_DISTANCE, 1e20, 1e300] {
            assert!(matches!(solve(d), Err(CircleError::TooFar(_))), "{d}");
        }
    }

    #[test]
    fn small_distances_go_straight() {
        for d in [0.1, 0.3, 0.6] {
            assert!((ratio(d).unwrap() - (1.0 + d)).abs() < 1e-12);
            assert_eq!(scans(d).unwrap(), 0);
        }
    }

    #[test]
    fn solution_is_consistent() {
        let s = solve(4.4).unwrap();
        assert_eq!(s.steps.len(), s.scans + 1);
        assert_eq!(s.scan_points.len(), s.scans + 1);
        assert!((s.steps[0] - (s.ratio - 1.0)).abs() < 1e-12);
        let mut prev = [0.0, 0.0];
        for (x, p) in s.steps.iter().zip(&s.scan_points) {
            let len = (p[0] - prev[0]).hypot(p[1] - prev[1]);
            assert!((len - x).abs() < 1e-9, "{len} vs {x}");
            prev = *p;
        }
    }

    #[test]
    fn below_two_collapses() {
        for c in [1.9, 1.99, 1.999] {
            let r = collapse(10.0 / (2.0 - c), c);
            assert!(!r.reached);
            assert!(r.farthest <= r.bound + 1e-9, "{r:?}");
        }
    }
}
