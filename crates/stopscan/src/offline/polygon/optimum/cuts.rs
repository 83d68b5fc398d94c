//! Connectivity: the cuts that separate a disconnected integer solution, the cuts a
//! fractional optimum violates (a maximum flow through split nodes), and the repair that joins
//! a disconnected set to the start.

use std::time::Instant;

use super::solvers::{Model, relaxation};
use crate::offline::polygon::{OfflineError, Problem};

/// `chosen` with the start, connected: each chosen candidate the start's part cannot reach
/// is joined to it by a shortest chain of candidates in the visibility graph, nearest first.
pub(super) fn connect(p: &Problem, chosen: &[usize]) -> Vec<usize> {
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
pub(super) fn separators(p: &Problem, chosen: &[usize]) -> Vec<(Vec<usize>, usize)> {
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
pub(super) fn strengthen(
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
