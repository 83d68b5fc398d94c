//! The programs as the solvers take them: microlp directly (binary, or relaxed to [0, 1]),
//! CBC and HiGHS through good_lp; each returns the proven optimum or the bound it reached.

use std::time::Instant;

use super::Solver;
use crate::offline::polygon::OfflineError;

/// One integer program: cover every row, respect every cut, start chosen, dominated
/// candidates left out.
pub(super) struct Model<'m> {
    pub(super) n: usize,
    /// Candidates fixed to 0: another does everything they do.
    pub(super) out: &'m [usize],
    pub(super) covers: &'m [Vec<usize>],
    /// `(separator, u)`: `Σ_{z ∈ separator} x_z ≥ x_u`.
    pub(super) cuts: &'m [(Vec<usize>, usize)],
}

/// What a solver returned.
pub(super) enum Solved {
    /// Proven optimal.
    Optimal(Vec<usize>),
    /// Stopped by the deadline, with its proven bound if it has one.
    Stopped(Option<f64>),
}

/// The linear relaxation's optimum `x` and value, or `None` when the budget ran out.
pub(super) fn relaxation(
    m: &Model,
    deadline: Option<Instant>,
) -> Result<Option<(Vec<f64>, f64)>, OfflineError> {
    use microlp::{SolveOptions, SolveOutcome};
    let (p, x) = microlp_model(m, false);
    let mut opts = SolveOptions::default();
    opts.time_limit = remaining(deadline);
    match p.solve_with(opts) {
        Ok(SolveOutcome::Solution(s)) => {
            Ok(Some((x.iter().map(|&v| s.var_value(v)).collect(), s.objective())))
        }
        Ok(SolveOutcome::Interrupted(_)) => Ok(None),
        Err(e) => Err(OfflineError::Solver(e.to_string())),
    }
}

/// Runs one program; `nodes`, when set, is the branch-and-bound nodes left (microlp only: a
/// deterministic budget), and is charged with the nodes used.
pub(super) fn run_solver(
    solver: Solver,
    m: &Model,
    warm: Option<&[usize]>,
    deadline: Option<Instant>,
    nodes: &mut Option<u64>,
) -> Result<Solved, OfflineError> {
    match solver {
        Solver::Microlp => solve_microlp(m, warm, deadline, nodes),
        #[cfg(feature = "cbc")]
        Solver::Cbc => solve_good_lp(
            m,
            warm,
            deadline,
            good_lp::coin_cbc,
            |mut p| {
                p.set_parameter("log", "0");
                p.set_parameter("slog", "0");
                p.set_parameter("threads", "1");
                p
            },
            |s| Some(s.model().best_possible_value()),
        ),
        #[cfg(feature = "highs")]
        Solver::Highs => solve_good_lp(
            m,
            warm,
            deadline,
            good_lp::highs,
            |mut p| {
                p.set_verbose(false);
                p.set_threads(1)
            },
            |_| None,
        ),
        #[allow(unreachable_patterns)]
        other => Err(OfflineError::Solver(format!("solver {} is not built in", other.name()))),
    }
}

fn remaining(deadline: Option<Instant>) -> Option<std::time::Duration> {
    deadline.map(|t| t.saturating_duration_since(Instant::now()))
}

/// The program as microlp takes it: binary variables, or their relaxation to [0, 1].
fn microlp_model(m: &Model, binary: bool) -> (microlp::Problem, Vec<microlp::Variable>) {
    use microlp::{ComparisonOp, OptimizationDirection, Problem};
    let mut p = Problem::new(OptimizationDirection::Minimize);
    let x: Vec<microlp::Variable> = (0..m.n)
        .map(|c| {
            let fixed = if c == 0 { Some(1.0) } else { m.out.contains(&c).then_some(0.0) };
            match (binary, fixed) {
                (true, None) => p.add_binary_var(1.0),
                (true, Some(v)) => p.add_integer_var(1.0, (v as i32, v as i32)),
                (false, None) => p.add_var(1.0, (0.0, 1.0)),
                (false, Some(v)) => p.add_var(1.0, (v, v)),
            }
        })
        .collect();
    for row in m.covers {
        let e: Vec<(microlp::Variable, f64)> = row.iter().map(|&c| (x[c], 1.0)).collect();
        p.add_constraint(e, ComparisonOp::Ge, 1.0);
    }
    for (sep, u) in m.cuts {
        let mut e: Vec<(microlp::Variable, f64)> = sep.iter().map(|&z| (x[z], 1.0)).collect();
        e.push((x[*u], -1.0));
        p.add_constraint(e, ComparisonOp::Ge, 0.0);
    }
    (p, x)
}

fn solve_microlp(
    m: &Model,
    warm: Option<&[usize]>,
    deadline: Option<Instant>,
    nodes: &mut Option<u64>,
) -> Result<Solved, OfflineError> {
    use microlp::{SolveOptions, SolveOutcome};
    let (p, x) = microlp_model(m, true);
    let mut opts = SolveOptions::default();
    opts.time_limit = remaining(deadline);
    opts.node_limit = *nodes;
    opts.warm_start = warm.map(|w| {
        let mut v: Vec<(microlp::Variable, f64)> = x.iter().map(|&xi| (xi, 0.0)).collect();
        for &c in w {
            v[c].1 = 1.0;
        }
        v
    });
    let chosen = |s: &microlp::Solution| -> Vec<usize> {
        (0..m.n).filter(|&c| s.var_value(x[c]) > 0.5).collect()
    };
    let outcome = p.solve_with(opts);
    if let (Some(left), Ok(o)) = (nodes.as_mut(), &outcome) {
        *left = left.saturating_sub(o.stats().nodes_solved);
    }
    match outcome {
        Ok(SolveOutcome::Solution(s)) => {
            if s.termination_reason() == microlp::TerminationReason::ProvenOptimal {
                Ok(Solved::Optimal(chosen(&s)))
            } else {
                Ok(Solved::Stopped(s.stats().best_bound))
            }
        }
        Ok(SolveOutcome::Interrupted(i)) => Ok(Solved::Stopped(i.stats().best_bound)),
        Err(e) => Err(OfflineError::Solver(e.to_string())),
    }
}

/// A solver through good_lp: `configure` sets it up (quiet, one thread), `bound` reads the
/// best proven bound from a stopped solution where the solver reports one. HiGHS gets no
/// warm start: through good_lp 1.15 it then returned non-optimal sets as optimal (3 of 8
/// benchmark polygons), and without one it agrees with microlp and CBC.
#[cfg(any(feature = "cbc", feature = "highs"))]
fn solve_good_lp<S: good_lp::Solver>(
    m: &Model,
    warm: Option<&[usize]>,
    deadline: Option<Instant>,
    solver: S,
    configure: impl FnOnce(S::Model) -> S::Model,
    bound: impl FnOnce(&<S::Model as good_lp::SolverModel>::Solution) -> Option<f64>,
) -> Result<Solved, OfflineError>
where
    S::Model: good_lp::WithTimeLimit + good_lp::WithInitialSolution,
{
    use good_lp::{
        Expression, Solution, SolutionStatus, SolverModel, Variable, WithInitialSolution,
        WithTimeLimit, constraint, variable, variables,
    };
    let mut vars = variables!();
    let x: Vec<Variable> = (0..m.n).map(|_| vars.add(variable().binary())).collect();
    let objective: Expression = x.iter().copied().sum();
    let mut model = configure(vars.minimise(objective).using(solver));
    if let Some(t) = remaining(deadline) {
        model = model.with_time_limit(t.as_secs_f64().max(0.01));
    }
    if let Some(w) = warm.filter(|_| S::Model::name() != "Highs") {
        let mut v: Vec<(Variable, f64)> = x.iter().map(|&xi| (xi, 0.0)).collect();
        for &c in w {
            v[c].1 = 1.0;
        }
        model = model.with_initial_solution(v);
    }
    model = model.with(constraint!(x[0] == 1.0));
    for &c in m.out {
        model = model.with(constraint!(x[c] == 0.0));
    }
    for row in m.covers {
        let e: Expression = row.iter().map(|&c| x[c]).sum();
        model = model.with(constraint!(e >= 1.0));
    }
    for (sep, u) in m.cuts {
        let e: Expression = sep.iter().map(|&z| x[z]).sum();
        model = model.with(constraint!(e >= x[*u]));
    }
    let sol = model.solve().map_err(|e| OfflineError::Solver(e.to_string()))?;
    Ok(match sol.status() {
        SolutionStatus::Optimal => {
            Solved::Optimal((0..m.n).filter(|&c| sol.value(x[c]) > 0.5).collect())
        }
        // HiGHS stops at a relative gap of 1e-4 by default: below one view for fewer than
        // 10,000 candidates, so with an integer objective it has proven the optimum.
        SolutionStatus::GapLimit if S::Model::name() == "Highs" && m.n < 10_000 => {
            Solved::Optimal((0..m.n).filter(|&c| sol.value(x[c]) > 0.5).collect())
        }
        _ => Solved::Stopped(bound(&sol)),
    })
}
