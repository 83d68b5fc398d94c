//! `corner policy` and `corner simulate`: MDP policies for a belief, and strategies run
//! against a true distribution.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::{CornerError, save_policy_image};
use crate::experiment::MonteCarlo;
use crate::experiment::corner::{self as exp};
use crate::io::atomic;
use crate::kernel::Num;
use crate::offline::corner::{expected, worst_case};
use crate::protocol::CostModel;
use crate::protocol::corner::{AngleDistribution, CornerSetup};
use crate::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use crate::strategy::corner::registry::{self, BuildOptions};

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
