//! The corner commands' results as typed reports: the circle strategy, its thresholds and
//! collapse, the global optimum, exact worst-case ratios, MDP policies, simulations against a
//! true distribution, and the demo. Functions given a folder also draw their pictures there.
//!
//! The CLI prints and writes these reports through `serde_json::Value`, whose object keys are
//! sorted (as the command's JSON has always been); serialising a report directly gives the
//! same keys in field order.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{InvalidParameter, Progress};
use crate::experiment::corner::{self as exp, LineupOptions};
use crate::experiment::{ExperimentError, MonteCarlo};
use crate::io::atomic::{self, WriteError};
use crate::kernel::Num;
use crate::offline::corner::optimal::{MAX_SCANS, OptimalError, OptimalScans, optimal_scans_with};
use crate::offline::corner::{expected, limit_ratio, worst_case};
use crate::protocol::CostModel;
use crate::protocol::corner::{
    AngleDistribution, CornerSetup, InvalidCornerSetup, InvalidDistribution,
};
use crate::render::{LineChart, Series, write_chart, write_policy_image};
use crate::strategy::corner::circle::{self, CircleError, Collapse, Threshold};
use crate::strategy::corner::mdp::{CornerMdp, CornerMdpError, Memory, Reading};
use crate::strategy::corner::registry::{self, BuildError, BuildOptions};
use crate::strategy::corner::{InvalidStopList, StopList};

/// The most thresholds [`thresholds`] computes.
pub const MAX_THRESHOLDS: usize = 60;

/// Why a corner command failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CornerError {
    /// A parameter outside its range (`distance`, `scans`, `count`, `ratio`, `delta`).
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// `stops` was asked for without stop angles.
    #[error("the stops strategy needs stop angles (degrees, increasing)")]
    StopsNeeded,
    /// The stop angles given are not a valid list.
    #[error(transparent)]
    Stops(#[from] StopsError),
    /// The setup is invalid.
    #[error(transparent)]
    Setup(#[from] InvalidCornerSetup),
    /// A belief or truth does not parse or is invalid.
    #[error(transparent)]
    Distribution(#[from] InvalidDistribution),
    /// A strategy could not be built.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// A stop list is invalid.
    #[error(transparent)]
    StopList(#[from] InvalidStopList),
    /// The MDP could not be solved.
    #[error(transparent)]
    Mdp(#[from] CornerMdpError),
    /// A simulation or the demo failed.
    #[error(transparent)]
    Experiment(#[from] ExperimentError),
    /// A picture or file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

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

fn distance_error(e: CircleError) -> CornerError {
    match e {
        CircleError::Distance(d) => {
            InvalidParameter::new("distance", "be a finite positive number", &Num(d)).into()
        }
    }
}

fn positive(name: &'static str, v: f64) -> Result<f64, CornerError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(InvalidParameter::new(name, "be a finite positive number", &Num(v)).into())
    }
}

/// Writes a chart as `NAME.svg` and `NAME.png` in `dir`; returns the paths as text.
///
/// # Errors
/// [`WriteError`] naming the files.
pub fn save_chart(dir: &Path, name: &str, chart: &LineChart) -> Result<Vec<String>, WriteError> {
    Ok(atomic::write_stem(&dir.join(name), |stem| write_chart(chart, stem))?
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

/// Writes a policy image as `NAME.svg` and `NAME.png` in `dir`; returns the paths as text.
///
/// # Errors
/// [`WriteError`] naming the files.
pub fn save_policy_image(
    dir: &Path,
    name: &str,
    title: &str,
    image: &[Vec<crate::strategy::corner::mdp::Cell>],
) -> Result<Vec<String>, WriteError> {
    Ok(atomic::write_stem(&dir.join(name), |stem| write_policy_image(image, title, stem))?
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

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

/// What `corner policy` solves.
#[derive(Debug, Clone, PartialEq)]
pub struct PolicyOptions<'a> {
    /// Distance and cost model.
    pub setup: CornerSetup,
    /// The belief's spec ([`AngleDistribution::parse`]).
    pub belief: &'a str,
    /// The truth's spec, the expected time is computed under (default: the belief).
    pub truth: Option<&'a str>,
    /// MDP1 or MDP2.
    pub memory: Memory,
    /// How transition probabilities are read.
    pub reading: Reading,
    /// Stop spacing, degrees.
    pub step_deg: f64,
    /// Also solve with general policy iteration, and compare.
    pub general: bool,
}

/// General policy iteration's answer beside backward induction's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GeneralSolverCheck {
    /// Its value of the start state.
    pub model_value: f64,
    /// Policy-improvement rounds.
    pub iterations: usize,
    /// Whether it agrees with backward induction to 1e-9.
    pub agrees_with_backward_induction: bool,
}

/// `corner policy`: an optimal MDP policy and its expected time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PolicyReport {
    /// MDP1 (`none`) or MDP2 (`last`).
    pub memory: Memory,
    /// The belief.
    pub belief: AngleDistribution,
    /// The truth.
    pub truth: AngleDistribution,
    /// Stop spacing, degrees.
    pub step_deg: f64,
    /// Stop intervals.
    pub stops: usize,
    /// MDP states.
    pub states: usize,
    /// The transition reading.
    pub reading: Reading,
    /// The MDP's value of the start state.
    pub model_value: f64,
    /// Exact expected time under the truth.
    pub expected_time: f64,
    /// Expected scans.
    pub expected_scans: f64,
    /// Expected metres.
    pub expected_distance: f64,
    /// The stop indices where the policy scans.
    pub scan_stops: Vec<usize>,
    /// Their angles, degrees.
    pub scan_angles_deg: Vec<f64>,
    /// General policy iteration's check, when asked for.
    pub general_solver: Option<GeneralSolverCheck>,
    /// The cost model.
    pub cost_model: CostModel,
    /// Distance to the corner, metres.
    pub distance: f64,
    /// The policy image files written.
    pub files: Vec<String>,
}

/// Solves MDP1 or MDP2 for a belief, with its expected time under the truth; with
/// `pictures`, draws the policy image there (`policy-mdp1` or `policy-mdp2`).
///
/// # Errors
/// [`CornerError`] for a spec that does not parse, an MDP that cannot be solved, or an image
/// that cannot be written.
pub fn policy(o: &PolicyOptions, pictures: Option<&Path>) -> Result<PolicyReport, CornerError> {
    let belief = AngleDistribution::parse(o.belief)?;
    let mdp = CornerMdp {
        setup: o.setup,
        step: o.step_deg.to_radians(),
        memory: o.memory,
        reading: o.reading,
        belief: belief.clone(),
    };
    let p = mdp.solve()?;
    let general_solver = if o.general {
        let (v, sol) = mdp.solve_general()?;
        Some(GeneralSolverCheck {
            model_value: v,
            iterations: sol.iterations,
            agrees_with_backward_induction: (v - p.model_value).abs() < 1e-9,
        })
    } else {
        None
    };
    let truth = match o.truth {
        Some(t) => AngleDistribution::parse(t)?,
        None => belief.clone(),
    };
    let e = expected(&p.stop_list, &o.setup, &truth);
    let mut files = Vec::new();
    if let Some(dir) = pictures {
        atomic::ensure_dir(dir)?;
        let last = o.memory == Memory::Last;
        let name = if last { "policy-mdp2" } else { "policy-mdp1" };
        let title = format!(
            "{} optimal policy, belief {}, δ = {}°",
            if last { "MDP2" } else { "MDP1" },
            o.belief,
            Num(o.step_deg)
        );
        files = save_policy_image(dir, name, &title, &p.image)?;
    }
    Ok(PolicyReport {
        memory: o.memory,
        belief,
        truth,
        step_deg: o.step_deg,
        stops: p.stops,
        states: p.states,
        reading: o.reading,
        model_value: p.model_value,
        expected_time: e.time,
        expected_scans: e.scans,
        expected_distance: e.distance,
        scan_stops: p.scan_stops,
        scan_angles_deg: p.stop_list.angles().iter().map(|x| x.to_degrees()).collect(),
        general_solver,
        cost_model: o.setup.cost,
        distance: o.setup.distance,
        files,
    })
}

/// `corner simulate`, parsed and ready to run ([`Simulation::run`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Simulation {
    /// Distance and cost model.
    pub setup: CornerSetup,
    /// What the robot believes.
    pub belief: AngleDistribution,
    /// What the world draws θ from.
    pub truth: AngleDistribution,
    /// The strategies, by registry name.
    pub strategies: Vec<String>,
    /// How the registry builds them.
    pub options: BuildOptions,
}

/// One strategy's simulation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulatedStrategy {
    /// Its registry name.
    pub strategy: String,
    /// Exact expected time.
    pub expected_time: f64,
    /// Exact expected scans.
    pub expected_scans: f64,
    /// Exact expected metres.
    pub expected_distance: f64,
    /// The Monte Carlo estimate of the time.
    pub monte_carlo: MonteCarlo,
    /// Its worst-case ratio.
    pub worst_ratio: f64,
    /// Its stops.
    pub stops: usize,
}

/// `corner simulate`: every strategy's exact expectation beside a seeded Monte Carlo.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SimulationReport {
    /// The belief.
    pub belief: AngleDistribution,
    /// The truth.
    pub truth: AngleDistribution,
    /// Samples per strategy.
    pub samples: usize,
    /// The seed.
    pub seed: u64,
    /// Distance to the corner, metres.
    pub distance: f64,
    /// The cost model.
    pub cost_model: CostModel,
    /// δ = τv/D.
    pub delta: f64,
    /// One per strategy, in the order asked.
    pub results: Vec<SimulatedStrategy>,
    /// The library version.
    pub stopscan_version: String,
}

impl Simulation {
    /// Parses the belief and the truth (default: the belief); `all` among the strategies
    /// stands for every registered one. Names are checked when the simulation runs.
    ///
    /// # Errors
    /// [`CornerError::Distribution`] for a spec that does not parse.
    pub fn new(
        setup: CornerSetup,
        belief: &str,
        truth: Option<&str>,
        strategies: &[String],
        options: BuildOptions,
    ) -> Result<Self, CornerError> {
        let belief = AngleDistribution::parse(belief)?;
        let truth = match truth {
            Some(t) => AngleDistribution::parse(t)?,
            None => belief.clone(),
        };
        let mut strategies: Vec<String> =
            strategies.iter().map(|s| s.trim().to_lowercase()).collect();
        if strategies.iter().any(|n| n == "all") {
            strategies = registry::names().map(String::from).collect();
        }
        Ok(Self { setup, belief, truth, strategies, options })
    }

    /// Runs `samples` Monte Carlo samples per strategy (strategy `k` seeded from
    /// `(seed, k)`); `tick` hears the samples done, from several threads.
    ///
    /// # Errors
    /// [`CornerError`] for an unknown strategy or one that cannot be built.
    pub fn run(
        &self,
        samples: usize,
        seed: u64,
        tick: &(dyn Fn(u64) + Sync),
    ) -> Result<SimulationReport, CornerError> {
        let setup = &self.setup;
        let mut results = Vec::new();
        for (k, name) in self.strategies.iter().enumerate() {
            let list = registry::build(name, setup, &self.belief, &self.options)?;
            let e = expected(&list, setup, &self.truth);
            let mc = exp::monte_carlo_with(
                &list,
                setup,
                &self.truth,
                samples,
                crate::experiment::sample_seed(seed, k as u64),
                tick,
            )?;
            let wc = worst_case(&list, setup);
            results.push(SimulatedStrategy {
                strategy: name.clone(),
                expected_time: e.time,
                expected_scans: e.scans,
                expected_distance: e.distance,
                monte_carlo: mc,
                worst_ratio: wc.worst_ratio,
                stops: list.len(),
            });
        }
        Ok(SimulationReport {
            belief: self.belief.clone(),
            truth: self.truth.clone(),
            samples,
            seed,
            distance: setup.distance,
            cost_model: setup.cost,
            delta: setup.delta(),
            results,
            stopscan_version: crate::VERSION.into(),
        })
    }
}

/// The demo's circle strategy at one distance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoCircle {
    /// `d`.
    pub distance: f64,
    /// `c(d)`.
    pub ratio: f64,
    /// Intermediate scans.
    pub scans: usize,
    /// Step lengths.
    pub steps: Vec<f64>,
    /// Scan points.
    pub scan_points: Vec<[f64; 2]>,
}

/// One corner-paper strategy of the demo.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoStrategy {
    /// Its name.
    pub name: String,
    /// Exact expected time, seconds.
    pub expected_time: f64,
    /// Worst-case ratio.
    pub worst_ratio: f64,
}

/// The demo's corner-paper setup and strategies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoCorner {
    /// Distance, metres.
    pub distance: f64,
    /// The cost model.
    pub cost_model: CostModel,
    /// δ = τv/D.
    pub delta: f64,
    /// The belief (and truth), described.
    pub belief: String,
    /// The MDPs' stop spacing, degrees.
    pub mdp_step_deg: f64,
    /// The four strategies.
    pub strategies: Vec<DemoStrategy>,
}

/// `corner demo` (`corner-demo.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DemoReport {
    /// `stopscan-corner-demo/1`.
    pub format: String,
    /// The circle strategy at six distances.
    pub circle: Vec<DemoCircle>,
    /// The corner paper's strategies on one belief.
    pub corner: DemoCorner,
    /// The chart files written.
    pub files: Vec<String>,
    /// The library version.
    pub stopscan_version: String,
}

/// The corner demo: the circle strategy at six distances and the four corner-paper
/// strategies on one belief; writes the `c(d)` chart (`circle-ratio`) and the report
/// (`corner-demo.json`, keys sorted) into `dir`, created if missing.
///
/// # Errors
/// [`CornerError`] if the demo cannot be computed or its files cannot be written.
pub fn demo(dir: &Path) -> Result<DemoReport, CornerError> {
    let exp::Demo { circles, strategies, chart } = exp::demo()?;
    atomic::ensure_dir(dir)?;
    let files = save_chart(dir, "circle-ratio", &chart)?;
    let setup = exp::paper_setup(2.0);
    let report = DemoReport {
        format: "stopscan-corner-demo/1".into(),
        circle: circles
            .into_iter()
            .map(|s| DemoCircle {
                distance: s.distance,
                ratio: s.ratio,
                scans: s.scans,
                steps: s.steps,
                scan_points: s.scan_points,
            })
            .collect(),
        corner: DemoCorner {
            distance: setup.distance,
            cost_model: setup.cost,
            delta: setup.delta(),
            belief: "mix:0.5*normal:30,3+0.5*normal:90,3 on 5° buckets (the corner paper's distribution 4)".into(),
            mdp_step_deg: LineupOptions::default().mdp_step.to_degrees(),
            strategies: strategies
                .into_iter()
                .map(|(name, expected_time, worst_ratio)| DemoStrategy {
                    name,
                    expected_time,
                    worst_ratio,
                })
                .collect(),
        },
        files,
        stopscan_version: crate::VERSION.into(),
    };
    // Not run.json: that is the main job's run record, in the same default folder.
    let path = demo_json(dir);
    atomic::write(&path, |w| {
        let sorted = serde_json::to_value(&report)?;
        serde_json::to_writer_pretty(&mut *w, &sorted)?;
        w.write_all(b"\n")
    })?;
    Ok(report)
}

/// Where [`demo`] writes its report in `dir`.
pub fn demo_json(dir: &Path) -> PathBuf {
    dir.join("corner-demo.json")
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
