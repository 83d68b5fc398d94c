//! The circle strategy: `corner circle`, `thresholds`, `optimal` and `collapse`.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{CornerError, distance_error, positive, save_chart};
use crate::io::atomic;
use crate::kernel::Num;
use crate::offline::corner::optimal::{MAX_SCANS, OptimalError, OptimalScans, optimal_scans_with};
use crate::pipeline::{InvalidParameter, Progress};
use crate::render::{LineChart, Series};
use crate::strategy::corner::circle::{self, Collapse, Threshold};

/// The most thresholds [`thresholds`] computes.
pub const MAX_THRESHOLDS: usize = 60;

/// `corner circle`: the circle strategy at normalised distance `d`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CircleReport {
    /// `d = D/(vτ)`.
    pub distance: f64,
    /// `c(d)`.
    pub ratio: f64,
    /// Intermediate scans.
    pub scans: usize,
    /// Scans with the one at the corner.
    pub total_scans: usize,
    /// Step lengths, the last ending at the corner.
    pub steps: Vec<f64>,
    /// The scan points, the last at the corner `(d, 0)`.
    pub scan_points: Vec<[f64; 2]>,
    /// The corner angle of each scan point, degrees.
    pub angles_deg: Vec<f64>,
    /// The units.
    pub units: String,
    /// The pictures written.
    pub files: Vec<String>,
}

/// The circle strategy at `d`; with `pictures`, draws its path (`circle.svg`, `circle.png`)
/// and writes the solution (`circle.json`) there.
///
/// # Errors
/// [`CornerError::Parameter`] for a distance that is not finite and positive; a picture that
/// cannot be written.
pub fn circle(d: f64, pictures: Option<&Path>) -> Result<CircleReport, CornerError> {
    let s = circle::solve(d).map_err(distance_error)?;
    let mut files = Vec::new();
    if let Some(dir) = pictures {
        atomic::ensure_dir(dir)?;
        let mut path = vec![(0.0, 0.0)];
        path.extend(s.scan_points.iter().map(|p| (p[0], p[1])));
        let arc: Vec<(f64, f64)> = (0..=200)
            .map(|k| {
                let a = std::f64::consts::FRAC_PI_2 * f64::from(k) / 200.0;
                (d * a.sin().powi(2), d * a.sin() * a.cos())
            })
            .collect();
        let chart = LineChart {
            title: format!("Circle strategy at d = {}: c = {:.6}", Num(d), s.ratio),
            subtitle: String::new(),
            x_label: "x (start at 0, corner at d)".into(),
            y_label: "y".into(),
            series: vec![
                Series::line("semicircle", arc).dashed(),
                Series::line("path and scan points", path).with_markers(),
            ],
        };
        files = save_chart(dir, "circle", &chart)?;
        atomic::write_json(&dir.join("circle.json"), &s)?;
    }
    Ok(CircleReport {
        distance: s.distance,
        ratio: s.ratio,
        scans: s.scans,
        total_scans: s.scans + 1,
        angles_deg: s.angles.iter().map(|a| a.to_degrees()).collect(),
        steps: s.steps,
        scan_points: s.scan_points,
        units: "scan cost 1, speed 1; 'scans' counts intermediate scans, the corner scan is extra"
            .into(),
        files,
    })
}

/// `corner thresholds`: the circle paper's Table 1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ThresholdsReport {
    /// One row per number of intermediate scans, from 0.
    pub thresholds: Vec<Threshold>,
}

/// The distances where the circle strategy needs one more scan, for `0..count` scans.
///
/// # Errors
/// [`CornerError::Parameter`] unless `1 ≤ count ≤` [`MAX_THRESHOLDS`].
pub fn thresholds(count: usize) -> Result<ThresholdsReport, CornerError> {
    if count == 0 || count > MAX_THRESHOLDS {
        return Err(InvalidParameter::new("count", "be between 1 and 60", &count).into());
    }
    Ok(ThresholdsReport { thresholds: circle::thresholds(count) })
}

/// `corner optimal`: the global optimum and how much it improves on the circle strategy.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimalReport {
    /// The optimum found.
    #[serde(flatten)]
    pub optimum: OptimalScans,
    /// The circle strategy's ratio minus the optimum's.
    pub improvement_over_circle: f64,
}

/// The globally optimal positions of at most `k` intermediate scans at distance `d`;
/// `progress` hears each number of points searched.
///
/// # Errors
/// [`CornerError::Parameter`] for a distance that is not finite and positive, or more than
/// [`MAX_SCANS`] scans.
pub fn optimal(
    d: f64,
    k: usize,
    seed: u64,
    progress: Progress,
) -> Result<OptimalReport, CornerError> {
    let o = optimal_scans_with(d, k, seed, &mut |j, r| {
        progress(&format!("searched {j} of {k} points: best ratio {r:.6}"));
    })
    .map_err(|e| match e {
        OptimalError::Distance(e) => distance_error(e),
        OptimalError::TooManyScans(k) => InvalidParameter::new(
            "scans",
            format!("be at most {MAX_SCANS} (the optimisation is over 2·scans coordinates)"),
            &k,
        )
        .into(),
    })?;
    Ok(OptimalReport { improvement_over_circle: o.circle_ratio - o.ratio, optimum: o })
}

/// Theorem 1 at ratio `c` (above 1) and distance `d` (default `10/(2 − c)` below 2, far
/// beyond the proof's `1/(2 − c)`, else 100).
///
/// # Errors
/// [`CornerError::Parameter`] for a ratio or distance that is not finite and positive, or a
/// ratio of at most 1.
pub fn collapse(c: f64, d: Option<f64>) -> Result<Collapse, CornerError> {
    let c = positive("ratio", c)?;
    if c <= 1.0 {
        return Err(InvalidParameter::new("ratio", "exceed 1", &Num(c)).into());
    }
    let d = match d {
        Some(d) => positive("distance", d)?,
        None if c < 2.0 => 10.0 / (2.0 - c),
        None => 100.0,
    };
    Ok(circle::collapse(d, c))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_are_named() {
        let e = circle(-1.0, None).unwrap_err().to_string();
        assert_eq!(e, "distance must be a finite positive number, got -1");
        let e = optimal(1.0, 13, 0, &mut |_| {}).unwrap_err().to_string();
        assert!(e.starts_with("scans must be at most 12"), "{e}");
        assert!(thresholds(61).is_err() && thresholds(0).is_err());
        assert_eq!(collapse(0.5, None).unwrap_err().to_string(), "ratio must exceed 1, got 0.5");
        assert_eq!(collapse(1.5, None).unwrap().distance, 20.0);
    }
}
