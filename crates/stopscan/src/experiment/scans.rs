//! The raw-scan pipeline measured on its own: how long reading a scan and aligning it take,
//! and how often ICP converges from a wrong odometry guess.
//!
//! Each trial draws a pose `a` in the free space and a second pose `b` within `step` metres
//! of it, in sight of it (consecutive stops), with any heading. The lidar scans from both;
//! `a`'s scan is read into a wall map; `b`'s scan is aligned to it from `b` moved by up to
//! `max_shift` metres (uniform in the disc) and turned by up to `max_turn` (uniform), with an
//! odometry prior of a third of those, then refined against `a`'s walls fitted finer
//! ([`icp::refine`]), as the raw-scan driver does. A trial converges when the aligned pose is within
//! [`CONVERGED_SHIFT`] and [`CONVERGED_TURN`] of the truth.

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use crate::geometry::{Domain, Location};
use crate::protocol::laser::{Pose, wrap};
use crate::sensing::icp::{self, Prior, WallMap};
use crate::sensing::ingest::ingest;
use crate::sim::lidar::LidarSetup;
use crate::world::lidar::{Lidar, Walls};

/// A trial converged when the aligned position is within this of the truth, metres.
pub const CONVERGED_SHIFT: f64 = 0.05;
/// … and the heading within this, radians (1°).
pub const CONVERGED_TURN: f64 = std::f64::consts::PI / 180.0;

/// What the trials measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScanPairs {
    /// Trials run.
    pub trials: usize,
    /// Trials whose alignment converged to the truth.
    pub converged: usize,
    /// `converged / trials`.
    pub converged_share: f64,
    /// Trials where ICP kept odometry (fallback) or found a degenerate direction.
    pub fallbacks: usize,
    /// Degenerate trials.
    pub degenerate: usize,
    /// The position error after alignment: median and 95th percentile, metres.
    pub position_error_median: f64,
    /// 95th percentile, metres.
    pub position_error_p95: f64,
    /// The heading error after alignment: median, radians. A heading off by 0.003 rad puts
    /// walls 20 m away 6 cm off, and the next scan aligned to them with them.
    pub heading_error_median: f64,
    /// 95th percentile, radians.
    pub heading_error_p95: f64,
    /// Mean time to read one scan (ingestion), milliseconds.
    pub ingest_ms: f64,
    /// Mean time to align one scan (ICP, with the wall map built), milliseconds.
    pub icp_ms: f64,
}

/// Runs `trials` scan pairs in `domain` ([module docs](self)); `progress` is called after
/// each.
///
/// # Panics
/// Never: the simulated lidar's scans are valid.
pub fn scan_pairs(
    domain: &Domain,
    lidar: &Lidar,
    trials: usize,
    step: f64,
    max_shift: f64,
    max_turn: f64,
    seed: u64,
    progress: &mut dyn FnMut(),
) -> ScanPairs {
    let walls = Walls::of(domain);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    // Read and aligned as the raw-scan driver does.
    let setup = LidarSetup::new(*lidar, 0.0, seed);
    let (params, icp_params) = (setup.ingest, setup.icp);
    let [lo, hi] = crate::algorithm::cover::bounds_of(&domain.rings()[0]);
    let clear =
        |p: [f64; 2]| domain.locate(p) == Location::Interior && domain.boundary_distance(p) > 0.25;
    let (mut ingest_s, mut icp_s) = (0.0, 0.0);
    let (mut converged, mut fallbacks, mut degenerate) = (0, 0, 0);
    let mut errors = Vec::with_capacity(trials);
    let mut turns = Vec::with_capacity(trials);
    let mut done = 0;
    let mut attempts = 0usize;
    while done < trials && attempts < 1000 * trials.max(1) {
        attempts += 1;
        let a = [rng.random_range(lo[0]..hi[0]), rng.random_range(lo[1]..hi[1])];
        let ang: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        let d: f64 = step * rng.random::<f64>().sqrt();
        let b = [a[0] + d * ang.cos(), a[1] + d * ang.sin()];
        if !clear(a) || !clear(b) || !walls_free(&walls, a, b) {
            continue;
        }
        let pa = Pose::new(a, rng.random_range(-std::f64::consts::PI..std::f64::consts::PI));
        let pb = Pose::new(b, rng.random_range(-std::f64::consts::PI..std::f64::consts::PI));
        let sa = lidar.scan(&walls, &pa, &mut rng);
        let sb = lidar.scan(&walls, &pb, &mut rng);
        let t = std::time::Instant::now();
        let ga = ingest(&sa, &pa, &params).expect("the simulated scans are valid");
        let gb = ingest(&sb, &Pose::default(), &params).expect("the simulated scans are valid");
        ingest_s += t.elapsed().as_secs_f64() / 2.0;
        let (mut map, mut fine) = (WallMap::new(), WallMap::new());
        map.extend(&ga.walls);
        map.extend_bridges(&ga.bridges);
        fine.extend(&ga.fine_walls);
        fine.extend_bridges(&ga.bridges);
        let (r, phi): (f64, f64) =
            (max_shift * rng.random::<f64>().sqrt(), rng.random_range(0.0..std::f64::consts::TAU));
        let guess = Pose {
            x: pb.x + r * phi.cos(),
            y: pb.y + r * phi.sin(),
            theta: wrap(pb.theta + rng.random_range(-max_turn..=max_turn)),
        };
        let prior = Prior { position: max_shift / 3.0, heading: max_turn / 3.0 };
        let t = std::time::Instant::now();
        let al = icp::align(&gb.points, &gb.normals, &guess, Some(prior), &map, &icp_params);
        let al = icp::refine(&gb.points, &gb.fine_normals, &al, [&fine, &map], &icp_params)
            .unwrap_or(al);
        icp_s += t.elapsed().as_secs_f64();
        let err = (al.pose.x - pb.x).hypot(al.pose.y - pb.y);
        let turn = wrap(al.pose.theta - pb.theta).abs();
        if err <= CONVERGED_SHIFT && turn <= CONVERGED_TURN {
            converged += 1;
        }
        fallbacks += usize::from(al.fallback.is_some());
        degenerate += usize::from(al.degenerate.is_some());
        errors.push(err);
        turns.push(turn);
        done += 1;
        progress();
    }
    errors.sort_by(f64::total_cmp);
    turns.sort_by(f64::total_cmp);
    // The nearest-rank percentile `q` of sorted values (0 for none).
    let percentile = |v: &[f64], q: f64| {
        if v.is_empty() { 0.0 } else { v[((v.len() - 1) as f64 * q).round() as usize] }
    };
    ScanPairs {
        trials: done,
        converged,
        converged_share: if done > 0 { converged as f64 / done as f64 } else { 0.0 },
        fallbacks,
        degenerate,
        position_error_median: percentile(&errors, 0.5),
        position_error_p95: percentile(&errors, 0.95),
        heading_error_median: percentile(&turns, 0.5),
        heading_error_p95: percentile(&turns, 0.95),
        ingest_ms: 1e3 * ingest_s / done.max(1) as f64,
        icp_ms: 1e3 * icp_s / done.max(1) as f64,
    }
}

/// Whether `b` is in sight of `a` (no wall within the segment).
fn walls_free(walls: &Walls, a: [f64; 2], b: [f64; 2]) -> bool {
    let d = (b[0] - a[0]).hypot(b[1] - a[1]);
    d == 0.0 || walls.cast(a, [(b[0] - a[0]) / d, (b[1] - a[1]) / d], d).is_none()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn icp_converges_on_office_scan_pairs_from_a_wrong_guess() {
        let d = crate::generate::office(3, 6, 1).unwrap().domain;
        let r = scan_pairs(&d, &Lidar::default(), 60, 2.0, 0.3, 10f64.to_radians(), 5, &mut || {});
        assert_eq!(r.trials, 60);
        assert!(r.converged_share >= 0.9, "{r:?}");
    }
}
