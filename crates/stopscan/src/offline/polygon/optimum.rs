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

use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::{Greedy, OfflineError, Problem, ViewSet, greedy_from};

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

/// One integer program: cover every row, respect every cut, start chosen, dominated
/// candidates left out.
struct Model<'m> {
    n: usize,
    /// Candidates fixed to 0: another does everything they do.
    out: &'m [usize],
    covers: &'m [Vec<usize>],
    /// `(separator, u)`: `Σ_{z ∈ separator} x_z ≥ x_u`.
    cuts: &'m [(Vec<usize>, usize)],
}

/// What a solver returned.
enum Solved {
    /// Proven optimal.
    Optimal(Vec<usize>),
    /// Stopped by the deadline, with its proven bound if it has one.
    Stopped(Option<f64>),
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

/// The coverage rows of the witnesses the start does not see, without the rows implied by
/// another (a superset of another row's candidates).
fn cover_rows(p: &Problem) -> Vec<Vec<usize>> {
    let n = p.cands.len();
    let words = n.div_ceil(64);
    let mut rows: Vec<&Vec<usize>> = p.seen_by.iter().filter(|r| !r.contains(&0)).collect();
    rows.sort_by_key(|r| (r.len(), (*r).clone()));
    rows.dedup();
    let mut kept: Vec<(Vec<u64>, &Vec<usize>)> = Vec::new();
    for r in rows {
        let mut bits = vec![0u64; words];
        for &c in r {
            bits[c / 64] |= 1 << (c % 64);
        }
        let implied = kept.iter().any(|(k, _)| k.iter().zip(&bits).all(|(a, b)| a & !b == 0));
        if !implied {
            kept.push((bits, r));
        }
    }
    kept.into_iter().map(|(_, r)| r.clone()).collect()
}

/// Candidates another one dominates: it sees every witness they see (so it covers what they
/// cover) and every candidate they see (so it connects what they connect); the lower index
/// of two equal ones stays. Leaving them out keeps an optimum for the current witnesses.
/// Returns, per candidate, its dominator (`None` for those kept).
fn dominated(p: &Problem) -> Vec<Option<usize>> {
    let n = p.cands.len();
    let words = n.div_ceil(64);
    let mut covers: Vec<Vec<usize>> = vec![Vec::new(); n];
    for (w, by) in p.seen_by.iter().enumerate() {
        if !by.contains(&0) {
            for &c in by {
                covers[c].push(w);
            }
        }
    }
    let closed: Vec<Vec<u64>> = (0..n)
        .map(|c| {
            let mut b = vec![0u64; words];
            for &m in p.sees[c].iter().chain([&c]) {
                b[m / 64] |= 1 << (m % 64);
            }
            b
        })
        .collect();
    let subset = |a: &[usize], b: &[usize]| {
        let mut j = 0;
        a.iter().all(|x| {
            while j < b.len() && b[j] < *x {
                j += 1;
            }
            j < b.len() && b[j] == *x
        })
    };
    (0..n)
        .map(|c| {
            if c == 0 {
                return None;
            }
            (0..n).find(|&d| {
                d != c
                    && covers[c].len() <= covers[d].len()
                    && closed[c].iter().zip(&closed[d]).all(|(a, b)| a & !b == 0)
                    && subset(&covers[c], &covers[d])
                    && (d == 0
                        || covers[c].len() < covers[d].len()
                        || p.sees[c].len() < p.sees[d].len()
                        || d < c)
            })
        })
        .collect()
}

/// A solution with every dominated candidate replaced by the one that dominates it (in
/// turn, until one that stays): as large at most, still complete and connected.
fn undominated(solution: &[usize], dom: &[Option<usize>]) -> Vec<usize> {
    let mut out: Vec<usize> = solution
        .iter()
        .map(|&c| {
            let mut c = c;
            while let Some(d) = dom[c] {
                c = d;
            }
            c
        })
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// `chosen` with the start, connected: each chosen candidate the start's part cannot reach
/// is joined to it by a shortest chain of candidates in the visibility graph, nearest first.
fn connect(p: &Problem, chosen: &[usize]) -> Vec<usize> {
    let n = p.cands.len();
    let mut set: Vec<usize> = std::iter::once(0).chain(chosen.iter().copied()).collect();
    set.sort_unstable();
    set.dedup();
    loop {
        let (reached, rest) = p.reach(&set);
        if rest.is_empty() {
            return set;
        }
        let mut wanted = vec![false; n];
        for &r in &rest {
            wanted[r] = true;
        }
        let mut from = vec![usize::MAX; n];
        let mut queue: std::collections::VecDeque<usize> = reached.iter().copied().collect();
        for &r in &reached {
            from[r] = r;
        }
        let mut hit = None;
        while let Some(u) = queue.pop_front() {
            if wanted[u] {
                hit = Some(u);
                break;
            }
            for &m in &p.sees[u] {
                if from[m] == usize::MAX {
                    from[m] = u;
                    queue.push_back(m);
                }
            }
        }
        let Some(mut u) = hit else { return set };
        while from[u] != u {
            u = from[u];
            if !set.contains(&u) {
                set.push(u);
            }
        }
    }
}

/// The cuts that separate the chosen candidates the start cannot reach (see the module
/// documentation).
fn separators(p: &Problem, chosen: &[usize]) -> Vec<(Vec<usize>, usize)> {
    let n = p.cands.len();
    let (reached, _) = p.reach(chosen);
    let mut is_chosen = vec![false; n];
    for &c in chosen {
        is_chosen[c] = true;
    }
    // 0: free, 1: reached (C₀), 2: a neighbour of C₀.
    let mut mark = vec![0u8; n];
    for &c in &reached {
        mark[c] = 1;
    }
    for &c in &reached {
        for &m in &p.sees[c] {
            if mark[m] == 0 {
                mark[m] = 2;
            }
        }
    }
    let mut comp = vec![usize::MAX; n];
    let mut cuts = Vec::new();
    for &v in chosen {
        if mark[v] != 0 || comp[v] != usize::MAX {
            continue;
        }
        // The component of v among the free candidates.
        let mut part = vec![v];
        comp[v] = v;
        let mut k = 0;
        while k < part.len() {
            for &m in &p.sees[part[k]] {
                if mark[m] == 0 && comp[m] == usize::MAX {
                    comp[m] = v;
                    part.push(m);
                }
            }
            k += 1;
        }
        let mut sep: Vec<usize> = part
            .iter()
            .flat_map(|&c| p.sees[c].iter().copied())
            .filter(|&m| mark[m] == 2)
            .collect();
        sep.sort_unstable();
        sep.dedup();
        for &u in part.iter().filter(|&&u| is_chosen[u]) {
            cuts.push((sep.clone(), u));
        }
    }
    cuts
}

/// Rounds of the cutting-plane loop on the relaxation.
const ROOT_ROUNDS: usize = 40;
/// Cuts separated per round at most.
const ROOT_CUTS: usize = 60;

/// Solves the linear relaxation and adds the connectivity cuts its optimum violates, until
/// it violates none (or the rounds or the budget run out). Returns the last relaxation's
/// value, a lower bound on the optimum over the candidates.
fn strengthen(
    p: &Problem,
    covers: &[Vec<usize>],
    cuts: &mut Vec<(Vec<usize>, usize)>,
    deadline: Option<Instant>,
) -> Result<Option<f64>, OfflineError> {
    let mut known: std::collections::HashSet<(Vec<usize>, usize)> = cuts.iter().cloned().collect();
    let mut value = None;
    for _ in 0..ROOT_ROUNDS {
        if deadline.is_some_and(|t| Instant::now() >= t) {
            break;
        }
        let Some((x, v)) =
            relaxation(&Model { n: p.cands.len(), out: &[], covers, cuts }, deadline)?
        else {
            break;
        };
        value = Some(v);
        let fresh: Vec<_> = fractional_separators(p, &x, ROOT_CUTS, deadline)
            .into_iter()
            .filter(|c| known.insert(c.clone()))
            .collect();
        if fresh.is_empty() {
            break;
        }
        cuts.extend(fresh);
    }
    Ok(value)
}

/// The linear relaxation's optimum `x` and value, or `None` when the budget ran out.
fn relaxation(
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

/// Connectivity cuts violated by a fractional point `x`: for candidates `t` with `x_t > 0`,
/// the minimum node separator between the start and `t` in the visibility graph, with node
/// weights `x` (a maximum flow through split nodes); a separator lighter than `x_t` gives the
/// cut `Σ_{z ∈ separator} x_z ≥ x_t`. At most `limit` cuts, heaviest targets first.
fn fractional_separators(
    p: &Problem,
    x: &[f64],
    limit: usize,
    deadline: Option<Instant>,
) -> Vec<(Vec<usize>, usize)> {
    use pathfinding::directed::edmonds_karp::{EdmondsKarp, SparseCapacity};
    const SCALE: f64 = 1e6;
    const INF: i64 = i64::MAX / 4;
    let n = p.cands.len();
    let mut targets: Vec<usize> = (1..n).filter(|&v| x[v] > 1e-3).collect();
    targets.sort_by(|&a, &b| x[b].total_cmp(&x[a]).then(a.cmp(&b)));
    let mut cuts = Vec::new();
    for t in targets {
        if cuts.len() >= limit || deadline.is_some_and(|d| Instant::now() >= d) {
            break;
        }
        // Node v enters at 2v and leaves at 2v + 1; the flow leaves the start and enters t.
        let mut ek = SparseCapacity::<i64>::new(2 * n, 1, 2 * t);
        // Every capacity is at least 1 (a millionth): a min-cut edge is then saturated, so
        // it carries flow and appears among the cut edges the solver reports.
        for (v, &xv) in x.iter().enumerate().skip(1) {
            if v != t {
                ek.set_capacity(2 * v, 2 * v + 1, ((xv * SCALE).round() as i64).max(1));
            }
        }
        for u in 0..n {
            for &w in &p.sees[u] {
                ek.set_capacity(2 * u + 1, 2 * w, INF);
            }
        }
        let (_, flow, cut) = ek.augment();
        if (flow as f64) < (x[t] - 1e-4) * SCALE {
            let mut sep: Vec<usize> = cut
                .iter()
                .filter(|((a, b), _)| a / 2 == b / 2 && a % 2 == 0)
                .map(|((a, _), _)| a / 2)
                .collect();
            sep.sort_unstable();
            cuts.push((sep, t));
        }
    }
    cuts
}

/// Runs one program; `nodes`, when set, is the branch-and-bound nodes left (microlp only: a
/// deterministic budget), and is charged with the nodes used.
fn run_solver(
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
