//! Reproduction of Fig. 7 (b)–(d) of the multi-robot ROI paper: the time of Algorithm 1
//! against the number of cells, the number of robots and the speed ratio S_r/S_p, 100 random
//! regions per point, beside Lemma 1's upper bound, Lemma 2's lower bound and the lawn-mower
//! baseline.

use std::fmt::Write;

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::{CsvTable, ExperimentError, NamedChart, Reproduction, Row, sample_seed};
use crate::kernel::tolerance::SAME_VALUE_REL;
use crate::offline::grid::GridBounds;
use crate::protocol::CostModel;
use crate::render::{LineChart, Series};
use crate::sim::Recording;
use crate::sim::grid::explore;
use crate::world::grid::{Drift, GridRoi, GridSensor, GridWorld};

/// The identifiers this module reproduces.
pub const IDS: &[&str] = &["roi-fig-7"];

/// The paper's fixed values when a variable is not swept: 120 cells, 20 robots, S_r/S_p = 2.5.
pub const FIXED: (usize, usize, f64) = (120, 20, 2.5);

/// One point of a sweep: `trials` random regions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fig7Row {
    /// `cells`, `robots` or `speed_ratio`.
    pub sweep: String,
    /// The swept value.
    pub x: f64,
    /// C.
    pub cells: usize,
    /// R.
    pub robots: usize,
    /// S_r / S_p.
    pub speed_ratio: f64,
    /// Trials.
    pub trials: usize,
    /// Mean time of Algorithm 1, s.
    pub mean: f64,
    /// Its minimum over the trials.
    pub min: f64,
    /// Its maximum.
    pub max: f64,
    /// Mean of Lemma 1's upper bound.
    pub upper: f64,
    /// Mean of Lemma 2's lower bound.
    pub lower: f64,
    /// Mean of the lawn-mower baseline.
    pub lawn_mower: f64,
    /// Trials whose time is within their Lemma 1 bound.
    pub within_upper: usize,
}

/// One trial: a random region of `cells` cells, drifting at S_r / `ratio` in one of the four
/// grid directions (the paper's simulation), explored by `robots` robots of speed 1.
fn trial(
    cells: usize,
    robots: usize,
    ratio: f64,
    seed: u64,
) -> Result<(f64, GridBounds), ExperimentError> {
    let roi = GridRoi::random(cells, seed)?;
    let heading = 90.0 * (seed >> 60 & 3) as f64;
    let drift = Drift { speed: 1.0 / ratio, heading_deg: heading };
    let mut world = GridWorld::new(roi, drift, GridSensor::Ideal, seed);
    let cost = CostModel { scan_time: 0.0, move_time: 0.0, speed: 1.0 };
    let m = explore(&mut world, robots, cost, Recording::NONE)?;
    Ok((m.team.makespan(), GridBounds::of_world(&world, robots, &cost)))
}

/// Runs one sweep point.
fn point(
    sweep: &str,
    x: f64,
    (cells, robots, ratio): (usize, usize, f64),
    trials: usize,
    seed: u64,
    index: u64,
) -> Result<Fig7Row, ExperimentError> {
    let runs: Vec<(f64, GridBounds)> = (0..trials as u64)
        .into_par_iter()
        .map(|t| trial(cells, robots, ratio, sample_seed(seed, index * 1_000_003 + t)))
        .collect::<Result<_, _>>()?;
    let n = runs.len().max(1) as f64;
    let mean = |f: &dyn Fn(&(f64, GridBounds)) -> f64| runs.iter().map(f).sum::<f64>() / n;
    Ok(Fig7Row {
        sweep: sweep.into(),
        x,
        cells,
        robots,
        speed_ratio: ratio,
        trials,
        mean: mean(&|r| r.0),
        min: runs.iter().map(|r| r.0).fold(f64::INFINITY, f64::min),
        max: runs.iter().map(|r| r.0).fold(f64::NEG_INFINITY, f64::max),
        upper: mean(&|r| r.1.lemma1_upper),
        lower: mean(&|r| r.1.lemma2_lower),
        lawn_mower: mean(&|r| r.1.lawn_mower),
        within_upper: runs
            .iter()
            .filter(|r| r.0 <= r.1.lemma1_upper * (1.0 + SAME_VALUE_REL))
            .count(),
    })
}

/// The swept values: cells, robots, speed ratios (ten points each).
pub const CELLS: [usize; 10] = [40, 80, 120, 160, 200, 240, 280, 320, 360, 400];
/// Robots of sweep (c).
pub const ROBOTS: [usize; 10] = [1, 2, 4, 8, 12, 16, 20, 24, 28, 32];
/// S_r / S_p of sweep (d).
pub const RATIOS: [f64; 10] = [1.5, 2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0];

/// The points of the three sweeps ([`fig7_rows`] makes one row per point).
pub const FIG7_POINTS: usize = CELLS.len() + ROBOTS.len() + RATIOS.len();

/// All three sweeps, `trials` regions per point; `progress` is called after each of the
/// [`FIG7_POINTS`] points.
///
/// # Errors
/// [`ExperimentError::Roi`] or [`ExperimentError::Mission`] if a region or a run fails (it
/// never should).
pub fn fig7_rows(
    trials: usize,
    seed: u64,
    progress: &mut dyn FnMut(),
) -> Result<Vec<Fig7Row>, ExperimentError> {
    let (c0, r0, s0) = FIXED;
    let points = CELLS
        .iter()
        .map(|&c| ("cells", c as f64, (c, r0, s0)))
        .chain(ROBOTS.iter().map(|&r| ("robots", r as f64, (c0, r, s0))))
        .chain(RATIOS.iter().map(|&s| ("speed_ratio", s, (c0, r0, s))));
    let mut rows = Vec::with_capacity(FIG7_POINTS);
    for (k, (sweep, x, at)) in points.enumerate() {
        rows.push(point(sweep, x, at, trials, seed, k as u64)?);
        progress();
    }
    Ok(rows)
}

/// The rows as CSV (header and one line per point).
pub fn csv(rows: &[Fig7Row]) -> String {
    let mut out = String::from(
        "sweep,x,cells,robots,speed_ratio,trials,mean,min,max,upper,lower,lawn_mower,within_upper\n",
    );
    for r in rows {
        let _ = writeln!(
            out,
            "{},{},{},{},{},{},{},{},{},{},{},{},{}",
            r.sweep,
            r.x,
            r.cells,
            r.robots,
            r.speed_ratio,
            r.trials,
            r.mean,
            r.min,
            r.max,
            r.upper,
            r.lower,
            r.lawn_mower,
            r.within_upper
        );
    }
    out
}

/// The values a sweep holds fixed, for the chart's subtitle.
fn fixed_parameters(sweep: &str, trials: usize) -> String {
    let (c, r, s) = FIXED;
    let held = match sweep {
        "cells" => format!("R = {r} robots, S_r/S_p = {s}"),
        "robots" => format!("C = {c} cells, S_r/S_p = {s}"),
        _ => format!("C = {c} cells, R = {r} robots"),
    };
    format!("{held}; S_r = 1 m/s, 1 m cells; {trials} random drifting regions per point")
}

fn chart(rows: &[Fig7Row], sweep: &str, title: &str, x_label: &str) -> LineChart {
    let pick = |f: &dyn Fn(&Fig7Row) -> f64| -> Vec<(f64, f64)> {
        rows.iter().filter(|r| r.sweep == sweep).map(|r| (r.x, f(r))).collect()
    };
    let trials = rows.iter().find(|r| r.sweep == sweep).map_or(0, |r| r.trials);
    LineChart {
        title: title.into(),
        subtitle: fixed_parameters(sweep, trials),
        x_label: x_label.into(),
        y_label: "exploration time (s)".into(),
        series: vec![
            Series::line("Algorithm 1, mean", pick(&|r| r.mean)).with_markers(),
            Series::line("Algorithm 1, min", pick(&|r| r.min)),
            Series::line("Algorithm 1, max", pick(&|r| r.max)),
            Series::line("upper bound (Lemma 1)", pick(&|r| r.upper)).dashed(),
            Series::line("lower bound (Lemma 2)", pick(&|r| r.lower)).dashed(),
            Series::line("lawn mower", pick(&|r| r.lawn_mower)).dashed(),
        ],
    }
}

/// Reproduces Fig. 7 (b)–(d) with `trials` regions per point (the paper: 100).
///
/// # Errors
/// [`ExperimentError::Roi`] or [`ExperimentError::Mission`] if a region or a run fails.
pub fn reproduce(trials: usize, seed: u64) -> Result<Reproduction, ExperimentError> {
    let rows = fig7_rows(trials, seed, &mut || {})?;
    let total: usize = rows.iter().map(|r| r.trials).sum();
    let within: usize = rows.iter().map(|r| r.within_upper).sum();
    let mut out = Vec::new();
    for r in &rows {
        out.push(Row::new(
            format!("{} = {}: mean time (min {:.2}, max {:.2}; Lemma 1 {:.2}, Lemma 2 {:.2}, lawn mower {:.2})", r.sweep, r.x, r.min, r.max, r.upper, r.lower, r.lawn_mower),
            None,
            r.mean,
        ));
    }
    // The paper's qualitative findings, checked.
    let closer_to_lower = rows.iter().filter(|r| r.mean - r.lower < r.upper - r.mean).count();
    let robots: Vec<&Fig7Row> = rows.iter().filter(|r| r.sweep == "robots").collect();
    let decreasing = robots.windows(2).all(|w| w[1].mean <= w[0].mean * 1.05);
    let ratio: Vec<&Fig7Row> = rows.iter().filter(|r| r.sweep == "speed_ratio").collect();
    let gap_shrinks =
        ratio.first().zip(ratio.last()).is_some_and(|(a, b)| b.upper - b.lower < a.upper - a.lower);
    Ok(Reproduction::new(
        "roi-fig-7",
        vec![
            format!("Fixed values as in the paper: {} cells, {} robots, S_r/S_p = {} when not swept; S_r = 1 m/s, cells of 1 m.", FIXED.0, FIXED.1, FIXED.2),
            format!("{trials} random regions per point (Eden growth from the start cell, seeded per trial), drifting north, south, east or west at random (section 6)."),
            "The paper does not give the swept ranges; ours: cells 40–400, robots 1–32, S_r/S_p 1.5–6.".into(),
            "Lemma 1 uses each trial's own d_max (the depth of the tree the robots built); logarithms are base 2.".into(),
            "The lawn mower sweeps the region's bounding rectangle split into R strips (the better of the two directions), ignoring the flights to the strips (section 6).".into(),
        ],
        out,
        vec![
            format!("{within} of {total} trials are within their Lemma 1 bound."),
            format!("{closer_to_lower} of {} points have a mean closer to the lower bound than to the upper bound (the paper: closer to the lower bound).", rows.len()),
            format!("Time decreases with the number of robots: {decreasing} (the paper: it does)."),
            format!("The gap between the upper and lower bounds shrinks as S_r/S_p grows: {gap_shrinks} (the paper: it does)."),
        ],
    )
    .with_charts(vec![
        NamedChart::new("roi-fig-7b", chart(&rows, "cells", "Fig. 7 (b): time against the number of cells", "cells C")),
        NamedChart::new("roi-fig-7c", chart(&rows, "robots", "Fig. 7 (c): time against the number of robots", "robots R")),
        NamedChart::new("roi-fig-7d", chart(&rows, "speed_ratio", "Fig. 7 (d): time against the speed ratio", "S_r / S_p")),
    ])
    .with_tables(vec![CsvTable { file: "roi-fig-7.csv".into(), csv: csv(&rows) }]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_chart_states_what_it_holds_fixed() {
        let rows = fig7_rows(1, 3, &mut || {}).unwrap();
        for (sweep, held, swept) in [
            ("cells", ["R = 20 robots", "S_r/S_p = 2.5"], "C = "),
            ("robots", ["C = 120 cells", "S_r/S_p = 2.5"], "R = "),
            ("speed_ratio", ["C = 120 cells", "R = 20 robots"], "S_r/S_p = "),
        ] {
            let c = chart(&rows, sweep, "t", "x");
            for h in held {
                assert!(c.subtitle.contains(h), "{sweep}: {}", c.subtitle);
            }
            assert!(!c.subtitle.contains(swept), "{sweep} is swept: {}", c.subtitle);
            assert!(c.subtitle.contains("1 random drifting regions per point"), "{}", c.subtitle);
        }
    }
}
