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

use std::f64::consts::PI;

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::algorithm::nelder_mead::{NelderMeadParams, minimize};
use crate::kernel::tolerance::SAME_VALUE_REL;
use crate::protocol::corner::CORNER;
use crate::strategy::corner::circle;

/// The hidden edge's angle at which a scan at `p` stops seeing: the angle ∠ABP in `[0, π]`,
/// measured at the corner `B = (d, 0)` from `BA` towards `+y`. Points on the line `AB` before
/// the corner see no hidden edge (0); the corner itself and the line's extension past it see
/// every edge (π). Points below the line (`y < 0`) are on the wall's side and see none.
fn reach(d: f64, p: [f64; 2]) -> f64 {
    if p[1] < 0.0 {
        0.0
    } else if p[1] == 0.0 {
        if p[0] >= d { PI } else { 0.0 }
    } else {
        p[1].atan2(d - p[0])
    }
}

/// The exact worst-case ratio of scan points `pts` (then the corner) at distance `d`.
///
/// The model (circle paper §3.1, over every edge the corner can hide): the hidden edge leaves
/// the corner `B = (d, 0)` at an angle θ ∈ (0, π] from `BA`; a scan at `P` sees it exactly when
/// θ ≤ ∠ABP (`reach`), and the scan at the corner sees every edge. The robot scans at each
/// point in turn and then at the corner, until it sees the edge; its cost is one per scan plus
/// the distance driven (scan cost 1, speed 1). The optimum for θ is one scan at the point of
/// `{P : ∠ABP ≥ θ}` nearest to `A`: the foot of the perpendicular, `1 + d·sin θ`, for
/// θ ≤ π/2, and the corner itself, `1 + d`, beyond. A point past the corner's perpendicular
/// (∠ABP > π/2) sees edges only up to its own angle: edges beyond it are seen from the corner
/// (or a later point), and that scan is charged.
///
/// The cost is constant between consecutive record angles reached, while the optimum grows
/// with θ, so the supremum over each interval is approached just past its left end: the ratio
/// is a maximum over at most `k + 1` breakpoints, computed exactly (a supremum: edges exactly
/// at a record angle are seen one scan earlier).
///
/// # Complexity
/// O(k) for k points.
pub fn plane_ratio(d: f64, pts: &[[f64; 2]]) -> f64 {
    ratio_of(d, pts.iter().copied())
}

/// [`plane_ratio`] over any sequence of points, in one pass without allocating: each new
/// record angle closes the interval opened by the previous one, at the cost of the scan that
/// set it.
fn ratio_of(d: f64, pts: impl Iterator<Item = [f64; 2]>) -> f64 {
    let opt = |reached: f64| 1.0 + d * reached.min(CORNER).sin();
    let (mut worst, mut reached, mut len, mut prev, mut scans) = (0.0_f64, 0.0, 0.0, [0.0, 0.0], 0);
    for p in pts {
        len += (p[0] - prev[0]).hypot(p[1] - prev[1]);
        prev = p;
        scans += 1;
        let beta = reach(d, p);
        if beta > reached {
            worst = worst.max((f64::from(scans) + len) / opt(reached));
            reached = beta;
            if reached >= PI {
                return worst; // every edge is seen
            }
        }
    }
    len += (d - prev[0]).hypot(prev[1]);
    worst.max((f64::from(scans + 1) + len) / opt(reached))
}

/// The optimum found for `(d, k)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimalScans {
    /// Normalised distance.
    pub distance: f64,
    /// The most intermediate scans allowed.
    pub max_scans: usize,
    /// Intermediate scans the optimum uses (at most `max_scans`).
    pub scans: usize,
    /// The exact worst-case ratio of `scan_points`.
    pub ratio: f64,
    /// The intermediate scan points (the final scan is at the corner `(d, 0)`), rounded to
    /// 1e-9.
    pub scan_points: Vec<[f64; 2]>,
    /// The best ratio found with at most `j` intermediate scans, for `j = 0..=max_scans`.
    pub ratio_by_scans: Vec<f64>,
    /// The circle strategy's ratio at the same distance, for comparison.
    pub circle_ratio: f64,
    /// Intermediate scans the circle strategy uses there.
    pub circle_scans: usize,
}

/// The most intermediate scans [`optimal_scans`] places: the search is over `2·k`
/// coordinates, and each scan more costs seconds.
pub const MAX_SCANS: usize = 12;

/// Why the optimum cannot be searched for.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum OptimalError {
    /// The distance is not finite and positive.
    #[error(transparent)]
    Distance(#[from] circle::CircleError),
    /// More than [`MAX_SCANS`] intermediate scans.
    #[error(
        "at most {MAX_SCANS} intermediate scans can be placed (the optimisation is over 2·scans coordinates), got {0}"
    )]
    TooManyScans(usize),
}

/// Finds the globally optimal positions of at most `k` intermediate scans at distance `d`.
///
/// The robot stops as soon as it sees the edge, and the corner sees every edge, so a point
/// placed at the corner costs nothing more than the corner's own scan: the optimum with
/// exactly `k` points is the optimum with at most `k`, and the points after the first one that
/// sees every edge are never visited. They are dropped from the result.
///
/// The searches for 1, 2, …, k points are chained: each starts, besides the circle strategy's
/// points and evenly spaced points on the semicircle, from the best points for one fewer with
/// a point inserted in every gap or at the corner. The chain stops early once two more points
/// in a row bring no improvement (the ratio falls with each useful scan until one more scan
/// costs more than it saves). The returned points are rounded to 1e-9 (what the CLI prints,
/// and what a robot can be sent to), and `ratio` is the exact worst-case ratio of the rounded
/// points, so the two always agree.
///
/// # Arguments
/// `d > 0`; `k ≤ 12` ([`MAX_SCANS`]); `seed` drives the random restarts.
///
/// # Errors
/// [`OptimalError`] for a distance that is not finite and positive, or `k` above
/// [`MAX_SCANS`].
///
/// # Complexity
/// About `k²` restarted simplex searches of a few thousand evaluations of [`plane_ratio`].
pub fn optimal_scans(d: f64, k: usize, seed: u64) -> Result<OptimalScans, OptimalError> {
    optimal_scans_with(d, k, seed, &mut |_, _| {})
}

/// [`optimal_scans`], calling `progress(j, ratio)` after the search with `j` points (`ratio`:
/// the best with at most `j`), for a progress display.
///
/// # Errors
/// As [`optimal_scans`].
pub fn optimal_scans_with(
    d: f64,
    k: usize,
    seed: u64,
    progress: &mut dyn FnMut(usize, f64),
) -> Result<OptimalScans, OptimalError> {
    let circ = circle::solve(d)?;
    if k > MAX_SCANS {
        return Err(OptimalError::TooManyScans(k));
    }
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let round = |pts: &[[f64; 2]]| -> Vec<[f64; 2]> {
        let mut out: Vec<[f64; 2]> =
            pts.iter().map(|p| p.map(|v| (v * 1e9).round() / 1e9 + 0.0)).collect();
        // Points after the first that sees every edge are never reached; the corner itself is
        // the final scan anyway.
        if let Some(i) = out.iter().position(|&p| reach(d, p) >= PI) {
            out.truncate(if out[i] == [d, 0.0] { i } else { i + 1 });
        }
        out
    };
    let mut chain: Vec<[f64; 2]> = Vec::new();
    let mut best = (Vec::new(), plane_ratio(d, &[]));
    let mut ratio_by_scans = vec![best.1];
    let mut idle = 0;
    for j in 1..=k {
        if idle < 2 {
            chain = search(d, j, &circ, &chain, &mut rng);
            let pts = round(&chain);
            let r = plane_ratio(d, &pts);
            if r < best.1 * (1.0 - SAME_VALUE_REL) {
                best = (pts, r);
                idle = 0;
            } else {
                idle += 1;
            }
        }
        ratio_by_scans.push(best.1);
        progress(j, best.1);
    }
    let (scan_points, ratio) = best;
    Ok(OptimalScans {
        distance: d,
        max_scans: k,
        scans: scan_points.len(),
        ratio,
        scan_points,
        ratio_by_scans,
        circle_ratio: circ.ratio,
        circle_scans: circ.scans,
    })
}

/// The best `k` points found from the fixed starts and the warm starts built from `fewer`
/// (the best `k − 1` points).
fn search(
    d: f64,
    k: usize,
    circ: &circle::CircleSolution,
    fewer: &[[f64; 2]],
    rng: &mut ChaCha8Rng,
) -> Vec<[f64; 2]> {
    let unpack = |z: &[f64]| -> Vec<[f64; 2]> { z.chunks(2).map(|c| [c[0], c[1]]).collect() };
    let pack = |p: &[[f64; 2]]| -> Vec<f64> { p.iter().flatten().copied().collect() };
    let objective = |z: &[f64]| ratio_of(d, z.chunks_exact(2).map(|c| [c[0], c[1]]));
    let on_circle = |a: f64| [d * a.sin().powi(2), d * a.sin() * a.cos()];
    let mut starts: Vec<Vec<f64>> = Vec::new();
    // The circle strategy's own angles, truncated, or padded evenly towards the corner.
    let mut angles: Vec<f64> = circ.angles[..circ.scans].to_vec();
    angles.truncate(k);
    let (have, last) = (angles.len(), angles.last().copied().unwrap_or(0.0));
    for i in 1..=k - have {
        angles.push(last + (CORNER - last) * i as f64 / (k - have + 1) as f64);
    }
    starts.push(angles.iter().flat_map(|&a| on_circle(a)).collect());
    starts.push((1..=k).flat_map(|i| on_circle(CORNER * i as f64 / (k + 1) as f64)).collect());
    // One point more than the best with fewer scans, inserted in each gap of its path.
    let path: Vec<[f64; 2]> =
        std::iter::once([0.0, 0.0]).chain(fewer.iter().copied()).chain([[d, 0.0]]).collect();
    for gap in 0..path.len() - 1 {
        let (a, b) = (path[gap], path[gap + 1]);
        let mut pts = fewer.to_vec();
        pts.insert(gap, [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])]);
        starts.push(pack(&pts));
    }
    // The extra scan spent where it costs least: at the corner, after the others.
    if !fewer.is_empty() {
        let mut pts = fewer.to_vec();
        pts.push([d, 0.0]);
        starts.push(pack(&pts));
    }
    let fixed = starts.len();
    for _ in 0..4 {
        let base = starts[rng.random_range(0..fixed)].clone();
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
    let (mut z, mut v) = best.expect("at least two starts");
    // Polish: the minimax is non-smooth and a simplex stalls on its ridges; restart from
    // seeded perturbations of the best point at shrinking scales.
    for scale in [1e-2, 1e-3, 1e-4] {
        for _ in 0..3 {
            let z0: Vec<f64> = z.iter().map(|x| x + rng.random_range(-1.0..1.0) * scale).collect();
            let (z1, v1) = minimize(objective, &z0, params.with_initial_step(scale));
            if v1 < v {
                (z, v) = (z1, v1);
            }
        }
    }
    unpack(&z)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_ratio_of_circle_points_is_c() {
        let s = circle::solve(4.4).unwrap();
        let r = plane_ratio(4.4, &s.scan_points[..s.scans]);
        assert!((r - s.ratio).abs() < 1e-9, "{r} vs {}", s.ratio);
    }

    #[test]
    fn no_scans_goes_straight() {
        assert!((plane_ratio(2.0, &[]) - 3.0).abs() < 1e-15);
    }

    #[test]
    fn the_paper_optimum_at_d1() {
        let o = optimal_scans(1.0, 1, 0).unwrap();
        assert!((o.ratio - 1.808_201).abs() < 1e-6, "{o:?}");
    }

    #[test]
    fn bad_input_is_an_error() {
        assert!(matches!(optimal_scans(0.0, 1, 0), Err(OptimalError::Distance(_))));
        assert!(matches!(optimal_scans(f64::NAN, 1, 0), Err(OptimalError::Distance(_))));
        assert_eq!(optimal_scans(1.0, 13, 0), Err(OptimalError::TooManyScans(13)));
    }
}
