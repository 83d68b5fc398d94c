//! MDP1 and MDP2 of the corner paper (§III), solved exactly by backward induction.
//!
//! The circle is discretised into stops `φ_i = min(iδ, π/2)`, `i = 0..=n`, `n = ⌈π/(2δ)⌉`;
//! stop 0 is the start (already scanned) and stop `n` the corner, where a scan sees every θ.
//! Rewards are negative times, so maximising reward is minimising expected time.
//!
//! * **MDP1** (states `s_i`, `s'_i`): the robot remembers only whether it has just scanned.
//! * **MDP2** (states `s_{i,j}`): the robot is at stop `i` and its last scan was at stop `j`.
//!
//! # Why backward induction is exact
//! Every action either moves forward (`i → i+1`) or scans, and a scan at `s_{i,j}` (j < i)
//! either ends in `F` or leads to `s_{i,i}`, whose only useful action is to move on. The one
//! cycle is the self-loop "scan again at `s_{i,i}`": it reveals nothing new (θ > φ_i is
//! already known) and costs τ > 0, so every policy that uses it is strictly worse than the
//! same policy without it. Removing it leaves a graph ordered by `(i, j)` lexicographically
//! — every transition increases `i`, or keeps `i` and raises `j` to `i` — hence acyclic, and
//! one backward sweep over `i = n..0` computes the optimal values exactly. The general
//! [`policy_iteration`] on the full MDP (self-loop
//! included) must and does agree.
//!
//! # Transition probabilities (the cut text)
//! The paper prints `P(F | s_{i,j}, Rec) = P(jδ ≤ θ ≤ iδ)` for MDP2 and its MDP1 formulas are
//! cut. [`Reading::Conditional`] (default) uses the Bayes-correct `P(θ ≤ φ_i | θ > φ_j)`: the
//! robot knows θ > φ_j, and only then is the MDP's value the true expected time. For MDP1,
//! whose state cannot know `j`, it conditions on the previous stop, `P(θ ≤ φ_i | θ > φ_{i−1})`.
//! [`Reading::Literal`] uses the printed unconditional mass `P(φ_j < θ ≤ φ_i)` for MDP2, and
//! `P(θ ≤ φ_i)` (the same with `j = 0`, "enough probability accumulated") for MDP1.

use serde::{Deserialize, Serialize};

use super::StopList;
use crate::algorithm::mdp::{Mdp, MdpError, MdpSolution, policy_iteration};
use crate::kernel::tolerance::{ANGLE_SLACK, COUNT_SLACK};
use crate::protocol::corner::{AngleDistribution, CORNER, CornerSetup, LastStep, Route};

/// Which MDP.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Memory {
    /// MDP1: no memory of the last scan.
    None,
    /// MDP2: the last scan's stop is part of the state.
    Last,
}

/// How the cut transition probabilities are read (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Reading {
    /// Bayes-correct conditional probabilities (default).
    #[default]
    Conditional,
    /// The unconditional masses as printed.
    Literal,
}

/// A corner MDP instance.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CornerMdp {
    /// Distance and cost model.
    pub setup: CornerSetup,
    /// The sampling step δ in radians.
    pub step: f64,
    /// MDP1 or MDP2.
    pub memory: Memory,
    /// How transition probabilities are read.
    pub reading: Reading,
    /// The belief `P(θ)`.
    pub belief: AngleDistribution,
}

/// Why a corner MDP could not be built or solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum CornerMdpError {
    /// The step must be positive and at most π/2.
    #[error("the sampling step must be in (0, 90] degrees, got {} degrees", crate::kernel::Num(*.0))]
    Step(f64),
    /// Too many stops for memory: MDP2 has n(n+1)/2 states and an (n+1)² policy image, at
    /// most [`MAX_STOPS_MDP2`] stops; MDP1 at most [`MAX_STOPS_MDP1`]. Use a larger step.
    #[error(
        "a step of {}° gives {} stops; {} handles at most {max} (a step of at least {}°)",
        crate::kernel::Num(*.step_deg),
        crate::kernel::Num(*.stops),
        if *.memory == Memory::Last { "MDP2" } else { "MDP1" },
        crate::kernel::Num(90.0 / *.max as f64)
    )]
    TooLarge {
        /// The step, degrees.
        step_deg: f64,
        /// The stops it gives.
        stops: f64,
        /// Which MDP.
        memory: Memory,
        /// The most stops that MDP handles.
        max: usize,
    },
    /// The general solver failed.
    #[error(transparent)]
    Solver(#[from] MdpError),
}

/// The most stops MDP2 handles (0.0045° steps): 2·10⁸ states, a 400 MB policy image.
pub const MAX_STOPS_MDP2: usize = 20_000;

/// The most stops MDP1 handles (9·10⁻⁵° steps): about 85 bytes and 0.1 µs per stop.
pub const MAX_STOPS_MDP1: usize = 1_000_000;

/// The discretised circle of a [`CornerMdp`].
struct Grid {
    /// Stop intervals; stops are `0..=n`.
    n: usize,
    /// Stop angles.
    phi: Vec<f64>,
    /// The belief's CDF at each stop.
    cdf: Vec<f64>,
    /// Travel time from stop `i` to `i + 1`.
    step: Vec<f64>,
}

/// What each state does, for policy images (the corner paper's Fig. 4 and Fig. 6).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StateAction {
    /// `j > i`: no such state.
    Inaccessible,
    /// Move on.
    Move,
    /// Reconstruct (scan).
    Reconstruct,
}

/// A solved corner MDP.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CornerPolicy {
    /// Number of stop intervals `n` (stops `0..=n`).
    pub stops: usize,
    /// Number of MDP states (terminal `F` excluded).
    pub states: usize,
    /// The MDP's own value of the start state (expected time under its transition model).
    pub model_value: f64,
    /// The stops where the policy scans if the edge stays hidden, as a stop list.
    pub stop_list: StopList,
    /// The stop indices where it scans (the last is `n`).
    pub scan_stops: Vec<usize>,
    /// Policy image rows: MDP2 row `i`, column `j`; MDP1 row 0 is `s_i`, row 1 is `s'_i`.
    pub image: Vec<Vec<StateAction>>,
}

impl CornerMdp {
    /// The discretisation: stops, the belief's CDF at each, and the travel time of each step.
    fn grid(&self) -> Result<Grid, CornerMdpError> {
        if !(self.step.is_finite() && self.step > 0.0 && self.step <= CORNER + ANGLE_SLACK) {
            return Err(CornerMdpError::Step(self.step.to_degrees()));
        }
        let stops = (CORNER / self.step - COUNT_SLACK).ceil();
        let max = match self.memory {
            Memory::Last => MAX_STOPS_MDP2,
            Memory::None => MAX_STOPS_MDP1,
        };
        if stops > max as f64 {
            return Err(CornerMdpError::TooLarge {
                step_deg: self.step.to_degrees(),
                stops,
                memory: self.memory,
                max,
            });
        }
        let n = stops as usize;
        let phi: Vec<f64> = (0..=n).map(|i| (i as f64 * self.step).min(CORNER)).collect();
        let cdf = phi.iter().map(|&p| self.belief.cdf(p)).collect();
        let step = (0..n)
            .map(|i| self.setup.travel(phi[i], phi[i + 1], Route::Arc) / self.setup.cost.speed)
            .collect();
        Ok(Grid { n, phi, cdf, step })
    }

    /// Probability that a scan at stop `i` misses the edge, given the last scan at `j`.
    fn miss(&self, cdf: &[f64], i: usize, j: usize) -> f64 {
        let (fi, fj) = (cdf[i], cdf[j]);
        match self.reading {
            Reading::Conditional => {
                if fj >= 1.0 {
                    0.0
                } else {
                    ((1.0 - fi) / (1.0 - fj)).clamp(0.0, 1.0)
                }
            }
            Reading::Literal => (1.0 - (fi - fj)).clamp(0.0, 1.0),
        }
    }

    /// Solves the MDP exactly by one backward sweep (see the module docs).
    ///
    /// # Errors
    /// [`CornerMdpError`] for a bad step or an MDP2 too large for memory.
    ///
    /// # Complexity
    /// MDP2: O(n²) time, O(n²) bits for the policy and O(n) floats for values.
    /// MDP1: O(n) time and space.
    pub fn solve(&self) -> Result<CornerPolicy, CornerMdpError> {
        let g = self.grid()?;
        Ok(match self.memory {
            Memory::Last => self.solve_mdp2(&g),
            Memory::None => self.solve_mdp1(&g),
        })
    }

    fn solve_mdp2(&self, g: &Grid) -> CornerPolicy {
        let (n, cdf, step) = (g.n, &g.cdf, &g.step);
        let (tau, mt) = (self.setup.cost.scan_time, self.setup.cost.move_time);
        // scan[tri(i, j)] for j < i: true when scanning beats moving at s_{i,j}.
        let tri = |i: usize, j: usize| i * (i - 1) / 2 + j;
        let mut scan = vec![false; n * (n + 1) / 2];
        let mut next = vec![tau; n + 1]; // row i = n: scan at the corner.
        let mut row = vec![0.0; n + 1];
        let surv: Vec<f64> = cdf.iter().map(|f| 1.0 - f).collect();
        let inv: Vec<f64> = surv.iter().map(|&s| if s > 0.0 { 1.0 / s } else { 0.0 }).collect();
        for i in (0..n).rev() {
            let after_scan = mt + step[i] + next[i];
            row[i] = after_scan;
            let base = if i > 0 { tri(i, 0) } else { 0 };
            for j in 0..i {
                let mv = step[i] + next[j];
                let miss = match self.reading {
                    Reading::Conditional => (surv[i] * inv[j]).min(1.0),
                    Reading::Literal => self.miss(cdf, i, j),
                };
                let rec = tau + miss * after_scan;
                let s = rec < mv;
                scan[base + j] = s;
                row[j] = if s { rec } else { mv };
            }
            std::mem::swap(&mut next, &mut row);
        }
        let model_value = next[0];
        // Follow the policy from s_{0,0} while the edge stays hidden.
        let mut scan_stops = Vec::new();
        let mut j = 0;
        for i in 1..n {
            if scan[tri(i, j)] {
                scan_stops.push(i);
                j = i;
            }
        }
        scan_stops.push(n);
        let image = (0..=n)
            .map(|i| {
                (0..=n)
                    .map(|j| match j.cmp(&i) {
                        std::cmp::Ordering::Greater => StateAction::Inaccessible,
                        std::cmp::Ordering::Equal => {
                            if i == n {
                                StateAction::Reconstruct
                            } else {
                                StateAction::Move
                            }
                        }
                        std::cmp::Ordering::Less => {
                            if i == n || scan[tri(i, j)] {
                                StateAction::Reconstruct
                            } else {
                                StateAction::Move
                            }
                        }
                    })
                    .collect()
            })
            .collect();
        Self::finish(n, n * (n + 1) / 2 + n, model_value, &g.phi, scan_stops, image)
    }

    fn solve_mdp1(&self, g: &Grid) -> CornerPolicy {
        let (n, cdf, step) = (g.n, &g.cdf, &g.step);
        let (tau, mt) = (self.setup.cost.scan_time, self.setup.cost.move_time);
        let mut w = vec![0.0; n + 1];
        let mut scan = vec![false; n + 1];
        w[n] = tau;
        scan[n] = true;
        for i in (1..n).rev() {
            let after_scan = mt + step[i] + w[i + 1];
            let mv = step[i] + w[i + 1];
            let rec = tau + self.miss1(cdf, i) * after_scan;
            scan[i] = rec < mv;
            w[i] = if scan[i] { rec } else { mv };
        }
        let model_value = mt + step[0] + w[1];
        let scan_stops: Vec<usize> = (1..=n).filter(|&i| scan[i]).collect();
        let image = vec![
            (0..=n)
                .map(|i| if scan[i] { StateAction::Reconstruct } else { StateAction::Move })
                .collect(),
            (0..=n)
                .map(|i| if i == n { StateAction::Inaccessible } else { StateAction::Move })
                .collect(),
        ];
        Self::finish(n, 2 * n, model_value, &g.phi, scan_stops, image)
    }

    fn miss1(&self, cdf: &[f64], i: usize) -> f64 {
        match self.reading {
            Reading::Conditional => self.miss(cdf, i, i - 1),
            Reading::Literal => (1.0 - cdf[i]).clamp(0.0, 1.0),
        }
    }

    fn finish(
        n: usize,
        states: usize,
        model_value: f64,
        phi: &[f64],
        scan_stops: Vec<usize>,
        image: Vec<Vec<StateAction>>,
    ) -> CornerPolicy {
        let angles: Vec<f64> = scan_stops.iter().map(|&i| phi[i]).collect();
        let stop_list = StopList::from_nominal(&angles, Route::Arc, LastStep::Capped)
            .expect("grid stops are strictly increasing");
        CornerPolicy { stops: n, states, model_value, stop_list, scan_stops, image }
    }

    /// The same MDP as a general sparse [`Mdp`], self-loop included, for the general solver.
    /// Returns the MDP and the index of the start state. Action 0 is always "move" (or the
    /// forced scan at the corner), which is a proper policy.
    ///
    /// # Errors
    /// [`CornerMdpError`] for a bad step.
    #[expect(clippy::needless_range_loop, reason = "state ids are computed from the stop index")]
    pub fn to_general(&self) -> Result<(Mdp, usize), CornerMdpError> {
        let Grid { n, cdf, step, .. } = self.grid()?;
        let (tau, mt) = (self.setup.cost.scan_time, self.setup.cost.move_time);
        let mut m = Mdp::new();
        match self.memory {
            Memory::Last => {
                // State ids: s_{i,j} = i(i+1)/2 + j for 0 ≤ j ≤ i ≤ n, then F.
                let id = |i: usize, j: usize| i * (i + 1) / 2 + j;
                let f = id(n, n) + 1;
                for i in 0..=n {
                    for j in 0..=i {
                        if i == n {
                            m.add_state(&[(tau, &[(f, 1.0)])]);
                            continue;
                        }
                        let mv_cost = step[i] + if j == i { mt } else { 0.0 };
                        let mv = [(id(i + 1, j), 1.0)];
                        if j == i {
                            // The useless self-loop: scanning again where it just scanned.
                            m.add_state(&[(mv_cost, &mv), (tau, &[(id(i, i), 1.0)])]);
                        } else {
                            let miss = self.miss(&cdf, i, j);
                            let rec = [(f, 1.0 - miss), (id(i, i), miss)];
                            m.add_state(&[(mv_cost, &mv), (tau, &rec)]);
                        }
                    }
                }
                m.add_state(&[]);
                Ok((m, id(0, 0)))
            }
            Memory::None => {
                // s_i = i, s'_i = n + 1 + i, F = 2n + 2. Start is s'_0.
                let f = 2 * n + 2;
                for i in 0..=n {
                    if i == n {
                        m.add_state(&[(tau, &[(f, 1.0)])]);
                    } else if i == 0 {
                        m.add_state(&[(step[0], &[(1, 1.0)])]);
                    } else {
                        let miss = self.miss1(&cdf, i);
                        m.add_state(&[
                            (step[i], &[(i + 1, 1.0)]),
                            (tau, &[(f, 1.0 - miss), (n + 1 + i, miss)]),
                        ]);
                    }
                }
                for i in 0..=n {
                    if i == n {
                        m.add_state(&[(tau, &[(f, 1.0)])]);
                    } else {
                        m.add_state(&[(mt + step[i], &[(i + 1, 1.0)])]);
                    }
                }
                m.add_state(&[]);
                Ok((m, n + 1))
            }
        }
    }

    /// Solves [`CornerMdp::to_general`] with policy iteration; returns the start value and the
    /// full solution.
    ///
    /// # Errors
    /// [`CornerMdpError`] for a bad step or a solver failure.
    pub fn solve_general(&self) -> Result<(f64, MdpSolution), CornerMdpError> {
        let (m, start) = self.to_general()?;
        let sol = policy_iteration(&m)?;
        Ok((sol.values[start], sol))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::CostModel;

    fn mdp(memory: Memory, belief: &str, step_deg: f64) -> CornerMdp {
        CornerMdp {
            setup: CornerSetup::new(10.0, CostModel::new(2.0, 0.0, 0.5).unwrap()).unwrap(),
            step: step_deg.to_radians(),
            memory,
            reading: Reading::Conditional,
            belief: AngleDistribution::parse(belief).unwrap(),
        }
    }

    #[test]
    fn general_solver_agrees_with_backward_induction() {
        for memory in [Memory::None, Memory::Last] {
            for belief in ["uniform:0,180", "normal:60,5", "mix:0.5*normal:30,3+0.5*normal:90,3"] {
                let m = mdp(memory, belief, 5.0);
                let exact = m.solve().unwrap().model_value;
                let (general, _) = m.solve_general().unwrap();
                assert!(
                    (exact - general).abs() < 1e-9,
                    "{memory:?} {belief}: {exact} vs {general}"
                );
            }
        }
    }

    #[test]
    fn mdp2_state_count_and_corner() {
        let p = mdp(Memory::Last, "uniform:0,180", 0.1).solve().unwrap();
        assert_eq!(p.stops, 900);
        assert_eq!(*p.scan_stops.last().unwrap(), 900);
        assert!(p.states > 405_000);
    }

    #[test]
    fn step_is_validated() {
        assert!(mdp(Memory::Last, "uniform:0,180", 0.0).solve().is_err());
        assert!(mdp(Memory::Last, "uniform:0,180", 100.0).solve().is_err());
    }
}
