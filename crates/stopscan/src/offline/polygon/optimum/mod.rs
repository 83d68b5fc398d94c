//! The exact minimum number of connected views over the candidates, by integer programming,
//! within a time budget.
//!
//! The model: a binary `x_c` per candidate, `x_start = 1`; every witness seen by a chosen
//! candidate; and the chosen set connected to the start in the visibility graph (the paper's
//! condition 2), added lazily as cuts. When a solution falls apart, let `C₀` be the chosen
//! candidates reachable from the start and `N(C₀)` its neighbours: none of them is chosen,
//! and every path from the start to a chosen candidate `v` outside `C₀` crosses them. The
//! cut takes the tighter separator next to `v`: the neighbours `N(S)` of the component `S` of
//! `v` once `C₀` and `N(C₀)` are removed, and requires `Σ_{z ∈ N(S)} x_z ≥ x_u` for every
//! chosen `u` in `S` (one such cut rules out every solution that leaves `S` cut off the same
//! way, not only the one found).
//!
//! Witnesses the start sees are covered by `x_start`; among the others, a witness seen by a
//! superset of the candidates that see another is implied by it and dropped. The greedy
//! reference is a feasible solution of every round (connected, and certified complete), so
//! it seeds the solver's incumbent; every round is a relaxation of the final problem, so its
//! proven bound is a lower bound on the optimum, as are the geometric bounds. When the
//! budget runs out, the report gives the best complete set found and the best lower bound.
//!
//! - here: the [`OptimumReport`] and the round loop that fills it;
//! - `reduce`: coverage rows implied by another, and dominated candidates;
//! - `cuts`: connectivity cuts at integer and at fractional points, and the repair that joins
//!   a disconnected set to the start;
//! - `solvers`: the program for microlp, and for CBC and HiGHS through good_lp.

mod cuts;
mod reduce;
mod solvers;

use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::{Greedy, OfflineError, Problem, ViewSet, greedy_from};
use cuts::{connect, separators, strengthen};
use reduce::{cover_rows, dominated, undominated};
use solvers::{Model, Solved, run_solver};

/// The integer-programming solver.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Solver {
    /// microlp: pure Rust, always built.
    #[default]
    Microlp,
    /// COIN-OR CBC through Debian's `coinor-libcbc-dev` (cargo feature `cbc`).
    Cbc,
    /// HiGHS, built from source with cmake (cargo feature `highs`).
    Highs,
}

impl Solver {
    /// Every solver, with whether this build has it.
    pub const ALL: [(Self, bool); 3] = [
        (Self::Microlp, true),
        (Self::Cbc, cfg!(feature = "cbc")),
        (Self::Highs, cfg!(feature = "highs")),
    ];

    /// Its name.
    pub fn name(self) -> &'static str {
        match self {
            Self::Microlp => "microlp",
            Self::Cbc => "cbc",
            Self::Highs => "highs",
        }
    }

    /// The solver of that name, if this build has it.
    ///
    /// # Errors
    /// A message naming the solvers built in, or the cargo feature that adds the one asked for.
    pub fn by_name(name: &str) -> Result<Self, String> {
        let built: Vec<&str> = Self::ALL.iter().filter(|s| s.1).map(|s| s.0.name()).collect();
        match Self::ALL.iter().find(|s| s.0.name() == name) {
            Some(&(s, true)) => Ok(s),
            Some(&(s, false)) => Err(format!(
                "solver {name} is not built in (build with --features {}); built in: {}",
                s.name(),
                built.join(", ")
            )),
            None => Err(format!("unknown solver {name:?}; built in: {}", built.join(", "))),
        }
    }
}

/// How the search for the optimum ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OptimumStatus {
    /// The optimum over the candidates is proven.
    Proven,
    /// The time budget ran out: the best set found and the best lower bound are reported.
    BudgetReached,
    /// Not attempted (too large, a range limit, no budget); the note says why.
    Skipped,
}

/// The result of the search for the optimum over the candidates.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OptimumReport {
    /// How it ended.
    pub status: OptimumStatus,
    /// The optimum when proven, else the best complete connected set found (the greedy
    /// reference at worst), if any.
    pub best: Option<ViewSet>,
    /// The best proven lower bound on the optimum over the candidates.
    pub lower: usize,
    /// The solver.
    pub solver: Solver,
    /// Seconds spent.
    pub seconds: f64,
    /// The time budget it had.
    pub budget_seconds: f64,
    /// Integer programs solved (each adds cuts or witnesses to the one before).
    pub rounds: usize,
    /// Why it was skipped or stopped.
    pub note: String,
}

impl OptimumReport {
    /// A search not attempted, for the reason `note`, with the lower bound known so far.
    pub fn skipped(solver: Solver, lower: usize, note: String) -> Self {
        Self {
            status: OptimumStatus::Skipped,
            best: None,
            lower,
            solver,
            seconds: 0.0,
            budget_seconds: 0.0,
            rounds: 0,
            note,
        }
    }

    /// The proven optimum, if any.
    pub fn views(&self) -> Option<usize> {
        (self.status == OptimumStatus::Proven)
            .then(|| self.best.as_ref().map(|b| b.viewpoints.len()))
            .flatten()
    }

    /// The best set's size minus the lower bound, when there is a best set.
    pub fn gap(&self) -> Option<usize> {
        self.best.as_ref().map(|b| b.viewpoints.len().saturating_sub(self.lower))
    }
}

/// Searches for the optimum over the candidates of `p` until `deadline`.
pub(super) fn solve(
    p: &mut Problem,
    geometric_lower: usize,
    greedy: Option<&Greedy>,
    solver: Solver,
    deadline: Option<Instant>,
    mut nodes: Option<u64>,
    progress: super::Progress,
) -> Result<OptimumReport, OfflineError> {
    let began = Instant::now();
    let mut report = OptimumReport {
        status: OptimumStatus::BudgetReached,
        best: greedy.filter(|g| g.set.certified).map(|g| g.set.clone()),
        lower: geometric_lower.max(1),
        solver,
        seconds: 0.0,
        budget_seconds: f64::INFINITY,
        rounds: 0,
        note: String::new(),
    };
    let mut warm: Option<Vec<usize>> = greedy.filter(|g| g.set.certified).map(|g| g.chosen.clone());
    // A chosen candidate the start does not see needs a chosen neighbour.
    let mut cuts: Vec<(Vec<usize>, usize)> = (1..p.cands.len())
        .filter(|&v| !p.sees[v].contains(&0) && !p.sees[0].contains(&v))
        .map(|v| (p.sees[v].clone(), v))
        .collect();
    let mut strengthened_for = 0;
    let outcome = loop {
        if deadline.is_some_and(|t| Instant::now() >= t) {
            break "the time budget ran out".to_string();
        }
        let covers = cover_rows(p);
        if covers.iter().any(Vec::is_empty) {
            break "a witness is seen by no candidate".to_string();
        }
        report.rounds += 1;
        progress(&format!(
            "optimum: round {}, {} witnesses, {} cuts, lower bound {}",
            report.rounds,
            covers.len(),
            cuts.len(),
            report.lower
        ));
        // Tighten the relaxation first: connectivity cuts at its fractional optima.
        let lpv = if covers.len() == strengthened_for {
            None
        } else {
            strengthened_for = covers.len();
            strengthen(p, &covers, &mut cuts, deadline)?
        };
        if let Some(lp) = lpv {
            report.lower = report.lower.max((lp - 1e-6).ceil().max(1.0) as usize);
        }
        let dom = dominated(p);
        let out: Vec<usize> = (0..dom.len()).filter(|&c| dom[c].is_some()).collect();
        let model = Model { n: p.cands.len(), out: &out, covers: &covers, cuts: &cuts };
        let hint = warm.as_deref().map(|w| undominated(w, &dom));
        let chosen = match run_solver(solver, &model, hint.as_deref(), deadline, &mut nodes)? {
            Solved::Optimal(chosen) => {
                report.lower = report.lower.max(chosen.len());
                chosen
            }
            Solved::Stopped(bound) => {
                if let Some(b) = bound {
                    report.lower = report.lower.max((b - 1e-6).ceil().max(1.0) as usize);
                }
                break if nodes == Some(0) {
                    "the node budget ran out".to_string()
                } else {
                    "the time budget ran out".to_string()
                };
            }
        };
        // Both checks at once: cuts where the set falls apart, witnesses where it leaves a
        // window open (true points of the free space either way, so both only tighten).
        let (_, rest) = p.reach(&chosen);
        let complete = p.certify(&chosen)?;
        if rest.is_empty() && complete {
            report.best = Some(p.view_set(&chosen, true));
            report.status = OptimumStatus::Proven;
            break String::new();
        }
        if !rest.is_empty() {
            cuts.extend(separators(p, &chosen));
        }
        // The relaxation's set, repaired (connected, then completed greedily), may beat the
        // best set so far; once it meets the lower bound it is optimal.
        let repaired = greedy_from(p, &connect(p, &chosen))?;
        let best = report.best.as_ref().map_or(usize::MAX, |b| b.viewpoints.len());
        if repaired.set.certified && repaired.chosen.len() < best {
            warm = Some(repaired.chosen.clone());
            report.best = Some(repaired.set);
            if repaired.chosen.len() <= report.lower {
                report.status = OptimumStatus::Proven;
                break String::new();
            }
        }
    };
    let met = report.best.as_ref().is_some_and(|b| b.viewpoints.len() <= report.lower);
    if met {
        // The best set meets a proven lower bound: it is optimal, budget or not.
        report.status = OptimumStatus::Proven;
    } else if report.status != OptimumStatus::Proven {
        report.note = outcome;
    }
    report.seconds = began.elapsed().as_secs_f64();
    Ok(report)
}
