//! The corner papers' experiments: the four-strategy lineup, Monte Carlo through the real
//! simulator, and the reproductions of their tables and figures.
//!
//! - `tables`: Tables II–IV of the corner paper, under one declared reading;
//! - `figures`: Figs. 4, 6, 7 and 8 of the corner paper, Table 1 and Fig. 7 of the circle paper;
//! - here: the [`lineup`], [`monte_carlo`] through the simulator, the [`demo`] and
//!   [`reproduce`] by id.

mod figures;
mod tables;

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use super::{ExperimentError, MonteCarlo, Reproduction, sample_seed};
use crate::offline::corner::{expected, worst_case};
use crate::protocol::CostModel;
use crate::protocol::corner::{
    AngleDistribution, CornerSetup, InvalidCornerSetup, LastStep, Route,
};
use crate::render::{LineChart, Series};
use crate::sim::{NoObserver, corner::run};
use crate::strategy::corner::mdp::Reading;
use crate::strategy::corner::registry::{self, BuildOptions};
use crate::strategy::corner::{ExprecReading, StopList, circle, exprec, unirec};
use crate::world::corner::CornerWorld;

/// The reproductions this module knows.
pub const IDS: &[&str] = &[
    "corner-table-2",
    "corner-table-3",
    "corner-table-4",
    "corner-fig-4",
    "corner-fig-6",
    "corner-fig-7",
    "corner-fig-8",
    "circle-table-1",
    "circle-fig-7",
];

/// A named strategy reduced to its stop list.
#[derive(Debug, Clone, PartialEq)]
pub struct Contender {
    /// Display name, with its reading (`UNIREC [nominal last step]`).
    pub name: String,
    /// The stops.
    pub list: StopList,
}

/// How the lineup reads the ambiguous parts of the corner paper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineupOptions {
    /// Last-step charge for UNIREC and EXPREC.
    pub last_step: LastStep,
    /// Which EXPREC.
    pub exprec: ExprecReading,
    /// Transition reading of both MDPs.
    pub reading: Reading,
    /// The MDPs' sampling step, radians.
    pub mdp_step: f64,
}

impl Default for LineupOptions {
    fn default() -> Self {
        Self {
            last_step: LastStep::Capped,
            exprec: ExprecReading::TableI,
            reading: Reading::Conditional,
            mdp_step: 5f64.to_radians(),
        }
    }
}

/// UNIREC, EXPREC, POLICY1 and POLICY2 for one setup and belief.
///
/// # Errors
/// [`ExperimentError::Strategy`] if a strategy cannot be built for the setup and belief.
pub fn lineup(
    setup: &CornerSetup,
    belief: &AngleDistribution,
    o: LineupOptions,
) -> Result<Vec<Contender>, ExperimentError> {
    let opts = BuildOptions {
        last_step: o.last_step,
        exprec: o.exprec,
        route: Route::Arc,
        mdp_step: o.mdp_step,
        reading: o.reading,
    };
    ["unirec", "exprec", "policy1", "policy2"]
        .iter()
        .map(|name| {
            let list = registry::build(name, setup, belief, &opts)?;
            Ok(Contender { name: name.to_uppercase(), list })
        })
        .collect()
}

/// Monte Carlo: draws θ from `truth`, runs the stop list's strategy through the simulator,
/// and averages the time. Sample `i` uses its own generator seeded from `(seed, i)`.
///
/// # Errors
/// [`ExperimentError::Sim`] if the strategy misbehaves (it cannot for a stop list).
pub fn monte_carlo(
    list: &StopList,
    setup: &CornerSetup,
    truth: &AngleDistribution,
    samples: usize,
    seed: u64,
) -> Result<MonteCarlo, ExperimentError> {
    monte_carlo_with(list, setup, truth, samples, seed, &|_| {})
}

/// Samples per chunk of [`monte_carlo_with`]: each chunk is reduced on one thread.
const MC_CHUNK: u64 = 1 << 16;
/// Chunks run in parallel at a time: memory is bounded by one batch's summaries.
const MC_BATCH: u64 = 256;

/// Count, mean and sum of squared deviations of some samples (Welford, merged by Chan et al.).
#[derive(Debug, Clone, Copy, Default)]
struct Moments {
    n: u64,
    mean: f64,
    m2: f64,
}

impl Moments {
    fn push(&mut self, x: f64) {
        self.n += 1;
        let d = x - self.mean;
        self.mean += d / self.n as f64;
        self.m2 += d * (x - self.mean);
    }

    fn merge(self, o: Self) -> Self {
        if o.n == 0 {
            return self;
        }
        if self.n == 0 {
            return o;
        }
        let n = self.n + o.n;
        let d = o.mean - self.mean;
        Self {
            n,
            mean: self.mean + d * o.n as f64 / n as f64,
            m2: self.m2 + o.m2 + d * d * (self.n as f64 * o.n as f64 / n as f64),
        }
    }
}

/// [`monte_carlo`] in bounded memory, reporting progress: samples are cut into fixed chunks
/// of 65,536 indices, each reduced in order on one thread, and the chunks' moments are merged
/// in chunk order, so the result depends on the seed alone, not on the thread count. `tick`
/// receives the number of samples finished after each chunk (from any thread).
///
/// # Errors
/// [`ExperimentError::Sim`] if the strategy misbehaves (it cannot for a stop list).
///
/// # Complexity
/// O(samples · stops) time, O(threads + 256) memory beyond the stop list.
pub fn monte_carlo_with(
    list: &StopList,
    setup: &CornerSetup,
    truth: &AngleDistribution,
    samples: usize,
    seed: u64,
    tick: &(dyn Fn(u64) + Sync),
) -> Result<MonteCarlo, ExperimentError> {
    let last_step = if list.charged_last() > crate::protocol::corner::CORNER {
        LastStep::Nominal
    } else {
        LastStep::Capped
    };
    let total = samples as u64;
    let chunks = total.div_ceil(MC_CHUNK);
    let chunk = |c: u64| -> Result<Moments, ExperimentError> {
        let mut m = Moments::default();
        for i in c * MC_CHUNK..((c + 1) * MC_CHUNK).min(total) {
            let mut rng = ChaCha8Rng::seed_from_u64(sample_seed(seed, i));
            let world = CornerWorld { setup: *setup, theta: truth.sample(&mut rng), last_step };
            let mut strategy = list.clone().into_strategy("stops");
            m.push(run(&world, &mut strategy, &mut NoObserver)?.time.total());
        }
        tick(m.n);
        Ok(m)
    };
    let mut all = Moments::default();
    for batch in (0..chunks).step_by(MC_BATCH as usize) {
        let parts: Vec<Moments> = (batch..(batch + MC_BATCH).min(chunks))
            .into_par_iter()
            .map(chunk)
            .collect::<Result<_, _>>()?;
        all = parts.into_iter().fold(all, Moments::merge);
    }
    let n = all.n.max(1) as f64;
    let var = all.m2 / (n - 1.0).max(1.0);
    Ok(MonteCarlo { mean: all.mean, std_err: (var / n).sqrt(), samples })
}

/// The corner paper's experimental setup: the robot on the wall 10 m from the corner,
/// speed 0.5 m/s, reconstruction time τ (2 s or 10 s), free moves.
///
/// # Errors
/// [`InvalidCornerSetup`] if `tau` is not finite and positive.
pub fn paper_setup(tau: f64) -> Result<CornerSetup, InvalidCornerSetup> {
    CornerSetup::new(10.0, CostModel { scan_time: tau, move_time: 0.0, speed: 0.5 })
}

/// Distribution `k` (1–4) of the corner paper's Fig. 5, on 5° buckets.
///
/// 1: N(60°, 5°) (the mean survives in the text; σ = 5° is the N(60, 5) of Table IV).
/// 2: cut from the text; fitted by [`fit_distribution_2`].
/// 3: uniform on [0, π]. 4: 0.5·N(30°, 3°) + 0.5·N(90°, 3°) ("means π/6 and π/2, variance of
/// 3 degrees", read as a standard deviation of 3°, the same unit as N(60, 5)).
///
/// # Errors
/// [`ExperimentError::NoSuchFig5Distribution`] for `k` outside 1–4.
pub fn fig5(k: usize) -> Result<AngleDistribution, ExperimentError> {
    let spec = match k {
        1 => "normal:60,5".to_string(),
        2 => {
            let (m, s, _) = fit_distribution_2()?;
            format!("normal:{m},{s}")
        }
        3 => "uniform:0,180".to_string(),
        4 => "mix:0.5*normal:30,3+0.5*normal:90,3".to_string(),
        _ => {
            return Err(ExperimentError::NoSuchFig5Distribution(k));
        }
    };
    Ok(AngleDistribution::parse(&spec).and_then(|d| d.bucketed(5f64.to_radians()))?)
}

/// Fits Distribution 2, whose description is cut from the text: a Gaussian N(µ, σ) on 5°
/// buckets (µ from 40° to 140°, σ from 5° to 60°, steps of 5°) minimising the squared relative
/// error against the paper's policy-independent numbers for it: UNIREC at τ = 2 and τ = 10
/// and EXPREC at τ = 2 (Table III's EXPREC column matches no reading for any distribution).
/// Returns `(µ°, σ°, residual)`.
///
/// # Errors
/// None in practice: the paper's setups and stop lists are valid; their errors are passed on.
pub fn fit_distribution_2() -> Result<(f64, f64, f64), ExperimentError> {
    let mut best = (0.0, 0.0, f64::INFINITY);
    let lists: Vec<(CornerSetup, StopList, StopList)> = [2.0, 10.0]
        .iter()
        .map(|&tau| {
            let s = paper_setup(tau)?;
            let u = unirec(s.delta(), Route::Arc, LastStep::Nominal)?;
            let e = exprec(s.delta(), ExprecReading::TableI, Route::Arc, LastStep::Nominal)?;
            Ok((s, u, e))
        })
        .collect::<Result<_, ExperimentError>>()?;
    for m in (40..=140).step_by(5) {
        for sd in (5..=60).step_by(5) {
            let Ok(t) =
                AngleDistribution::normal(f64::from(m).to_radians(), f64::from(sd).to_radians())
                    .and_then(|d| d.bucketed(5f64.to_radians()))
            else {
                continue;
            };
            let u2 = expected(&lists[0].1, &lists[0].0, &t).time;
            let e2 = expected(&lists[0].2, &lists[0].0, &t).time;
            let u10 = expected(&lists[1].1, &lists[1].0, &t).time;
            let r = ((u2 - tables::TABLE_2[1][0]) / tables::TABLE_2[1][0]).powi(2)
                + ((e2 - tables::TABLE_2[1][1]) / tables::TABLE_2[1][1]).powi(2)
                + ((u10 - tables::TABLE_3[1][0]) / tables::TABLE_3[1][0]).powi(2);
            if r < best.2 {
                best = (f64::from(m), f64::from(sd), r);
            }
        }
    }
    Ok(best)
}

/// Runs one reproduction.
///
/// # Errors
/// [`ExperimentError::UnknownId`] for an unknown identifier; model errors otherwise.
pub fn reproduce(id: &str, samples: usize, seed: u64) -> Result<Reproduction, ExperimentError> {
    match id {
        "corner-table-2" => tables::corner_table(tables::Table::Two, samples, seed),
        "corner-table-3" => tables::corner_table(tables::Table::Three, samples, seed),
        "corner-table-4" => tables::corner_table(tables::Table::Four, samples, seed),
        "corner-fig-4" | "corner-fig-6" => figures::corner_policy_figure(id),
        "corner-fig-7" => figures::corner_fig_7(),
        "corner-fig-8" => figures::corner_fig_8(),
        "circle-table-1" => Ok(figures::circle_table_1()),
        "circle-fig-7" => figures::circle_fig_7(seed),
        _ => Err(ExperimentError::UnknownId(id.into(), IDS.join(", "))),
    }
}

/// `c(d)` on `n` evenly spaced distances in `(0, d_max]`.
///
/// # Errors
/// [`circle::CircleError`] unless `d_max` is finite and positive.
pub fn ratio_curve(d_max: f64, n: usize) -> Result<Vec<(f64, f64)>, circle::CircleError> {
    (1..=n)
        .into_par_iter()
        .map(|i| {
            let d = d_max * i as f64 / n as f64;
            circle::ratio(d).map(|c| (d, c))
        })
        .collect()
}

/// One corner-paper strategy of the demo: its exact expected time and worst-case ratio.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoStrategy {
    /// Its name.
    pub name: String,
    /// Exact expected time, seconds.
    pub expected_time: f64,
    /// Worst-case ratio.
    pub worst_ratio: f64,
}

/// What the built-in demo computes.
#[derive(Debug, Clone, PartialEq)]
pub struct Demo {
    /// The circle strategy at a few distances.
    pub circles: Vec<circle::CircleSolution>,
    /// The four corner-paper strategies on the demo's belief.
    pub strategies: Vec<DemoStrategy>,
    /// The `c(d)` chart.
    pub chart: LineChart,
}

/// The built-in demo: the circle strategy at a few distances and the four corner-paper
/// strategies on one belief (Table II's setup, distribution 4).
///
/// # Errors
/// Model errors (none for the built-in values).
pub fn demo() -> Result<Demo, ExperimentError> {
    let circles = [0.5, 1.0, 2.0, 4.4, 10.0, 40.0]
        .iter()
        .map(|&d| circle::solve(d))
        .collect::<Result<_, _>>()?;
    let setup = paper_setup(2.0)?;
    let belief = fig5(4)?;
    let mut four = Vec::new();
    for c in lineup(&setup, &belief, LineupOptions::default())? {
        let e = expected(&c.list, &setup, &belief).time;
        let worst_ratio = worst_case(&c.list, &setup).worst_ratio;
        four.push(DemoStrategy { name: c.name, expected_time: e, worst_ratio });
    }
    let chart = LineChart {
        title: "Circle strategy: competitive ratio c(d)".into(),
        subtitle: "scan cost 1, speed 1; d = D/(vτ)".into(),
        x_label: "distance d (units of v·τ)".into(),
        y_label: "competitive ratio c".into(),
        series: vec![
            Series::line("c(d)", ratio_curve(20.0, 800)?),
            Series::line("lower bound 2", vec![(0.0, 2.0), (20.0, 2.0)]).dashed(),
        ],
    };
    Ok(Demo { circles, strategies: four, chart })
}
