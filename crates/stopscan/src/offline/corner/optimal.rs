//! The globally optimal scan points for a fixed number of intermediate scans, anywhere in
//! the plane (circle paper §3.2, which calls it impractical).
//!
//! Units as in the circle paper: scan cost 1, speed 1, start `A = (0, 0)`, corner
//! `B = (d, 0)`. A scan at `P` sees every object hidden behind a line through `B` at angle
//! α ≤ β(P), where β(P) = ∠ABP. An object just behind angle α costs the optimum
//! `1 + d·sin α`. With scan points `P_1..P_k` and the final scan at `B`, the object just
//! behind the best angle reached so far is seen at the first later scan with a larger angle,
//! so the worst-case ratio is a maximum over `k + 1` breakpoints, computed exactly.
//! The optimisation over the `2k` coordinates is a non-smooth minimax, solved by a restarted
//! Nelder–Mead simplex from several starts: the circle strategy's own points (so the result
//! is never worse than the circle strategy with the same number of scans), evenly spaced
//! points on the semicircle, and seeded random perturbations.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::algorithm::nelder_mead::{NelderMeadParams, minimize};
use crate::protocol::corner::CORNER;
use crate::strategy::corner::circle;

/// The exact worst-case ratio of scan points `pts` (then the corner) at distance `d`.
///
/// # Complexity
/// O(k²) for k points.
pub fn plane_ratio(d: f64, pts: &[[f64; 2]]) -> f64 {
    let k = pts.len();
    let beta: Vec<f64> = pts.iter().map(|p| p[1].atan2(d - p[0]).clamp(0.0, CORNER)).collect();
    let mut path = Vec::with_capacity(k + 1);
    let mut len = 0.0;
    let mut prev = [0.0, 0.0];
    for p in pts.iter().chain(std::iter::once(&[d, 0.0])) {
        len += (p[0] - prev[0]).hypot(p[1] - prev[1]);
        path.push(len);
        prev = *p;
    }
    let mut worst = 0.0_f64;
    let mut reached = 0.0_f64;
    for i in 0..=k {
        if i > 0 {
            if beta[i - 1] <= reached {
                continue; // no new angle: no new breakpoint
            }
            reached = beta[i - 1];
        }
        if reached >= CORNER {
            break;
        }
        // First later scan that sees beyond `reached` (the corner always does).
        let j = (i..k).find(|&j| beta[j] > reached).unwrap_or(k);
        let cost = (j + 1) as f64 + path[j];
        worst = worst.max(cost / (1.0 + d * reached.sin()));
    }
    worst
}

/// The optimum found for `(d, k)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimalScans {
    /// Normalised distance.
    pub distance: f64,
    /// Intermediate scans.
    pub scans: usize,
    /// The best worst-case ratio found.
    pub ratio: f64,
    /// The intermediate scan points (the final scan is at the corner `(d, 0)`).
    pub scan_points: Vec<[f64; 2]>,
    /// The circle strategy's ratio at the same distance, for comparison.
    pub circle_ratio: f64,
    /// Intermediate scans the circle strategy uses there.
    pub circle_scans: usize,
}

/// Finds the globally optimal positions of `k` intermediate scans at distance `d`.
///
/// # Arguments
/// `d > 0`; `k ≤ 12`; `seed` drives the random restarts.
///
/// # Complexity
/// A few hundred thousand evaluations of [`plane_ratio`] for k ≤ 6.
pub fn optimal_scans(d: f64, k: usize, seed: u64) -> OptimalScans {
    assert!(d.is_finite() && d > 0.0, "the distance must be finite and positive");
    let circ = circle::solve(d);
    let unpack = |z: &[f64]| -> Vec<[f64; 2]> { z.chunks(2).map(|c| [c[0], c[1]]).collect() };
    let objective = |z: &[f64]| plane_ratio(d, &unpack(z));
    if k == 0 {
        return OptimalScans {
            distance: d,
            scans: 0,
            ratio: plane_ratio(d, &[]),
            scan_points: vec![],
            circle_ratio: circ.ratio,
            circle_scans: circ.scans,
        };
    }
    let mut starts: Vec<Vec<f64>> = Vec::new();
    let on_circle = |a: f64| [d * a.sin().powi(2), d * a.sin() * a.cos()];
    // The circle strategy's own angles, truncated, or padded evenly towards the corner.
    let mut angles: Vec<f64> = circ.angles[..circ.scans].to_vec();
    angles.truncate(k);
    let (have, last) = (angles.len(), angles.last().copied().unwrap_or(0.0));
    for i in 1..=k - have {
        angles.push(last + (CORNER - last) * i as f64 / (k - have + 1) as f64);
    }
    starts.push(angles.iter().flat_map(|&a| on_circle(a)).collect());
    starts.push((1..=k).flat_map(|i| on_circle(CORNER * i as f64 / (k + 1) as f64)).collect());
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for _ in 0..4 {
        let base = starts[rng.random_range(0..2)].clone();
        starts.push(
            base.iter().map(|v| v + rng.random_range(-0.1..0.1) * d.max(1.0) * 0.2).collect(),
        );
    }
    let params = NelderMeadParams::default().with_initial_step(0.05);
    let mut best: Option<(Vec<f64>, f64)> = None;
    for z0 in starts {
        let (z, v) = minimize(objective, &z0, params);
        if best.as_ref().is_none_or(|b| v < b.1) {
            best = Some((z, v));
        }
    }
    let (z, ratio) = best.expect("at least one start");
    OptimalScans {
        distance: d,
        scans: k,
        ratio,
        scan_points: unpack(&z),
        circle_ratio: circ.ratio,
        circle_scans: circ.scans,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_ratio_of_circle_points_is_c() {
        let s = circle::solve(4.4);
        let r = plane_ratio(4.4, &s.scan_points[..s.scans]);
        assert!((r - s.ratio).abs() < 1e-9, "{r} vs {}", s.ratio);
    }

    #[test]
    fn no_scans_goes_straight() {
        assert!((plane_ratio(2.0, &[]) - 3.0).abs() < 1e-15);
    }

    #[test]
    fn the_paper_optimum_at_d1() {
        let o = optimal_scans(1.0, 1, 0);
        assert!((o.ratio - 1.808_201).abs() < 1e-6, "{o:?}");
    }
}
