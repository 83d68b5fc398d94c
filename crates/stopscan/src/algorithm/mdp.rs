//! Finite Markov decision processes with costs (stochastic shortest path), stored sparsely,
//! solved by policy iteration.
//!
//! A state without actions is terminal and has value 0. Values are expected total costs to
//! termination, and a policy minimises them. This is the "general" solver: it accepts cyclic
//! MDPs (self-loops included), evaluates each policy exactly when its graph is acyclic and
//! by Gauss–Seidel sweeps otherwise.

use crate::kernel::tolerance::SAME_VALUE_REL;

/// How far the probabilities of an action's transitions may sum from one (they are the
/// caller's floating-point arithmetic, a difference of CDF values say).
const PROBABILITY_SUM_TOLERANCE: f64 = 1e-9;

/// Why an MDP could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MdpError {
    /// A transition names a state that does not exist, or probabilities do not sum to one.
    #[error("state {state}, action {action}: {reason}")]
    Malformed {
        /// The state.
        state: usize,
        /// The action index within the state.
        action: usize,
        /// What is wrong.
        reason: String,
    },
    /// The policy does not reach a terminal state with probability one from every state
    /// (its evaluation diverged). Start from a proper policy: action 0 must be proper.
    #[error("the policy is improper: its evaluation did not converge after {0} sweeps")]
    ImproperPolicy(usize),
}

/// A sparse MDP in compressed rows: states → actions → transitions.
#[derive(Debug, Clone, Default)]
pub struct Mdp {
    state_start: Vec<usize>,
    action_cost: Vec<f64>,
    action_start: Vec<usize>,
    next: Vec<u32>,
    prob: Vec<f64>,
}

impl Mdp {
    /// An empty MDP; add states in order with [`Mdp::add_state`].
    pub fn new() -> Self {
        Self { state_start: vec![0], action_start: vec![0], ..Self::default() }
    }

    /// Appends a state with its actions, each `(cost, [(next, probability), ..])`, and returns
    /// its index. A state with no actions is terminal. Transitions may name states not added
    /// yet; [`Mdp::validate`] checks them.
    pub fn add_state(&mut self, actions: &[(f64, &[(usize, f64)])]) -> usize {
        for (cost, trans) in actions {
            self.action_cost.push(*cost);
            for &(n, p) in *trans {
                self.next.push(n as u32);
                self.prob.push(p);
            }
            self.action_start.push(self.next.len());
        }
        self.state_start.push(self.action_cost.len());
        self.state_start.len() - 2
    }

    /// Number of states.
    pub fn states(&self) -> usize {
        self.state_start.len() - 1
    }

    /// Number of state–action pairs.
    pub fn actions(&self) -> usize {
        self.action_cost.len()
    }

    fn action_range(&self, s: usize) -> std::ops::Range<usize> {
        self.state_start[s]..self.state_start[s + 1]
    }

    fn q(&self, a: usize, values: &[f64]) -> f64 {
        let t = self.action_start[a]..self.action_start[a + 1];
        self.action_cost[a]
            + self.next[t.clone()]
                .iter()
                .zip(&self.prob[t])
                .map(|(&n, &p)| p * values[n as usize])
                .sum::<f64>()
    }

    /// Checks every transition: target exists, probabilities finite, non-negative, sum 1.
    ///
    /// # Errors
    /// [`MdpError::Malformed`] for the first bad action.
    pub fn validate(&self) -> Result<(), MdpError> {
        let n = self.states();
        for s in 0..n {
            for (k, a) in self.action_range(s).enumerate() {
                let t = self.action_start[a]..self.action_start[a + 1];
                let bad = |reason: String| MdpError::Malformed { state: s, action: k, reason };
                if !self.action_cost[a].is_finite() {
                    return Err(bad("cost is not finite".into()));
                }
                let mut sum = 0.0;
                for (&nx, &p) in self.next[t.clone()].iter().zip(&self.prob[t]) {
                    if nx as usize >= n {
                        return Err(bad(format!("transition to missing state {nx}")));
                    }
                    if !(p.is_finite() && p >= 0.0) {
                        return Err(bad(format!("probability {p} is not in [0, 1]")));
                    }
                    sum += p;
                }
                if (sum - 1.0).abs() > PROBABILITY_SUM_TOLERANCE {
                    return Err(bad(format!("probabilities sum to {sum}, not 1")));
                }
            }
        }
        Ok(())
    }
}

/// A solved MDP: optimal values and the action index chosen in every state.
#[derive(Debug, Clone, PartialEq)]
pub struct MdpSolution {
    /// Expected total cost from each state.
    pub values: Vec<f64>,
    /// Chosen action (index within the state's actions); `usize::MAX` for terminal states.
    pub policy: Vec<usize>,
    /// Policy-improvement rounds performed.
    pub iterations: usize,
}

/// Policy iteration (Howard): evaluate the current policy exactly, improve greedily, repeat
/// until no state improves by more than a relative 1e-12. Starts from action 0 everywhere,
/// which must be a proper policy.
///
/// # Errors
/// [`MdpError`] if the MDP is malformed or a policy's evaluation diverges.
///
/// # Complexity
/// Each round is O(S + T) when the policy graph is acyclic (states S, transitions T) and
/// O(sweeps · (S + T)) otherwise; rounds are few in practice.
///
/// # Example
/// ```
/// use stopscan::algorithm::mdp::{Mdp, policy_iteration};
/// let mut m = Mdp::new();
/// // State 0: pay 5 to finish, or pay 1 to reach state 1, which finishes for 1.
/// m.add_state(&[(5.0, &[(2, 1.0)]), (1.0, &[(1, 1.0)])]);
/// m.add_state(&[(1.0, &[(2, 1.0)])]);
/// m.add_state(&[]);
/// let sol = policy_iteration(&m).unwrap();
/// assert_eq!(sol.values[0], 2.0);
/// assert_eq!(sol.policy[0], 1);
/// ```
pub fn policy_iteration(mdp: &Mdp) -> Result<MdpSolution, MdpError> {
    mdp.validate()?;
    let n = mdp.states();
    let mut policy: Vec<usize> =
        (0..n).map(|s| if mdp.action_range(s).is_empty() { usize::MAX } else { 0 }).collect();
    let mut values = vec![0.0; n];
    let order = reverse_topological(mdp);
    let mut iterations = 0;
    loop {
        iterations += 1;
        evaluate(mdp, &policy, &order, &mut values)?;
        let mut changed = false;
        for (s, chosen) in policy.iter_mut().enumerate() {
            if *chosen == usize::MAX {
                continue;
            }
            let base = mdp.state_start[s];
            let current = mdp.q(base + *chosen, &values);
            let mut best = (current, *chosen);
            for a in mdp.action_range(s) {
                let q = mdp.q(a, &values);
                if q < best.0 - SAME_VALUE_REL * (1.0 + best.0.abs()) {
                    best = (q, a - base);
                }
            }
            if best.1 != *chosen {
                *chosen = best.1;
                changed = true;
            }
        }
        if !changed {
            return Ok(MdpSolution { values, policy, iterations });
        }
    }
}

/// States in an order where, for the policy's graph, successors come first when it is
/// acyclic (iterative DFS post-order over all actions' graph, so one order serves all rounds).
fn reverse_topological(mdp: &Mdp) -> Vec<usize> {
    let n = mdp.states();
    let mut state = vec![0u8; n];
    let mut order = Vec::with_capacity(n);
    let mut stack: Vec<(usize, usize)> = Vec::new();
    for root in 0..n {
        if state[root] != 0 {
            continue;
        }
        state[root] = 1;
        stack.push((root, mdp.action_start[mdp.state_start[root]]));
        while let Some(&mut (s, ref mut t)) = stack.last_mut() {
            let end = mdp.action_start[mdp.state_start[s + 1]];
            if *t < end {
                let nx = mdp.next[*t] as usize;
                *t += 1;
                if state[nx] == 0 {
                    state[nx] = 1;
                    stack.push((nx, mdp.action_start[mdp.state_start[nx]]));
                }
            } else {
                state[s] = 2;
                order.push(s);
                stack.pop();
            }
        }
    }
    order
}

/// Evaluates a policy: one Gauss–Seidel sweep in post-order is exact for an acyclic policy
/// graph; cycles (self-loops included) need more sweeps until the change is below 1e-13.
fn evaluate(
    mdp: &Mdp,
    policy: &[usize],
    order: &[usize],
    values: &mut [f64],
) -> Result<(), MdpError> {
    const MAX_SWEEPS: usize = 100_000;
    for sweep in 0..MAX_SWEEPS {
        let mut delta = 0.0_f64;
        let mut scale = 0.0_f64;
        for &s in order {
            if policy[s] == usize::MAX {
                values[s] = 0.0;
                continue;
            }
            let a = mdp.state_start[s] + policy[s];
            let t = mdp.action_start[a]..mdp.action_start[a + 1];
            let mut stay = 0.0;
            let mut v = mdp.action_cost[a];
            for (&nx, &p) in mdp.next[t.clone()].iter().zip(&mdp.prob[t]) {
                if nx as usize == s {
                    stay += p;
                } else {
                    v += p * values[nx as usize];
                }
            }
            // A self-loop with probability p < 1 is solved in closed form: v = (c + ...)/(1 − p).
            let v = if stay > 0.0 {
                if stay >= 1.0 - 1e-15 {
                    return Err(MdpError::ImproperPolicy(sweep + 1));
                }
                v / (1.0 - stay)
            } else {
                v
            };
            delta = delta.max((v - values[s]).abs());
            scale = scale.max(v.abs());
            values[s] = v;
        }
        if !delta.is_finite() {
            return Err(MdpError::ImproperPolicy(sweep + 1));
        }
        if sweep > 0 && delta <= 1e-13 * (1.0 + scale) {
            return Ok(());
        }
    }
    Err(MdpError::ImproperPolicy(MAX_SWEEPS))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geometric_retry_with_self_loop() {
        // Pay 1 per try, succeed with probability 1/4: expected cost 4 (a cyclic MDP).
        let mut m = Mdp::new();
        m.add_state(&[(1.0, &[(0, 0.75), (1, 0.25)]), (10.0, &[(1, 1.0)])]);
        m.add_state(&[]);
        // Action 0 first is proper; improvement keeps it.
        let s = policy_iteration(&m).unwrap();
        assert!((s.values[0] - 4.0).abs() < 1e-12);
        assert_eq!(s.policy[0], 0);
    }

    #[test]
    fn improper_policy_is_an_error() {
        let mut m = Mdp::new();
        m.add_state(&[(1.0, &[(0, 1.0)])]);
        assert!(matches!(policy_iteration(&m), Err(MdpError::ImproperPolicy(_))));
    }

    #[test]
    fn malformed_is_an_error() {
        let mut m = Mdp::new();
        m.add_state(&[(1.0, &[(5, 1.0)])]);
        assert!(matches!(policy_iteration(&m), Err(MdpError::Malformed { .. })));
        let mut m = Mdp::new();
        m.add_state(&[(1.0, &[(0, 0.5)])]);
        assert!(policy_iteration(&m).is_err());
    }

    #[test]
    fn cycle_between_states_converges() {
        // 0 -> 1 (cost 1) ; 1 -> 0 w.p. 0.5, terminal w.p. 0.5 (cost 1). V1 = 1 + 0.5 V0, V0 = 1 + V1.
        let mut m = Mdp::new();
        m.add_state(&[(1.0, &[(1, 1.0)])]);
        m.add_state(&[(1.0, &[(0, 0.5), (2, 0.5)])]);
        m.add_state(&[]);
        let s = policy_iteration(&m).unwrap();
        assert!((s.values[0] - 4.0).abs() < 1e-10, "{:?}", s.values);
    }
}
