//! A pose graph over the stops: each scan's pose is a node; odometry between successive stops
//! and scan matches between stops that saw the same walls are edges. Solving it (Gauss-Newton,
//! robust to a wrong match) spreads a correction found late back over the stops before it, so
//! that walls placed from a poorly aligned stop are moved where later, better constrained
//! stops put them: a loop closure.
//!
//! Written here: the graph is small (the most recent [`WINDOW`] stops are solved, older ones
//! stay where they are), and a dense Cholesky factorisation of at most `3 · WINDOW` unknowns
//! costs well under a millisecond, which no linear-algebra dependency would improve on.

use crate::protocol::laser::{Pose, wrap};

/// The information (inverse covariance) of a measured relative pose, in `(x, y, θ)` of the
/// frame of the edge's first node: metres⁻² and radians⁻².
pub type Information = [[f64; 3]; 3];

/// How many of the most recent nodes are solved; older nodes are held where they are.
pub const WINDOW: usize = 64;

/// An edge whose Mahalanobis distance is beyond this weighs less (a Huber kernel): one wrong
/// scan match does not drag the graph.
const ROBUST: f64 = 3.0;

/// A measured pose of node `to` in the frame of node `from`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Edge {
    /// The node the measurement is relative to.
    pub from: usize,
    /// The node measured.
    pub to: usize,
    /// `to`'s pose in `from`'s frame.
    pub measured: Pose,
    /// How sure the measurement is.
    pub information: Information,
}

/// Poses and the measurements between them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PoseGraph {
    poses: Vec<Pose>,
    edges: Vec<Edge>,
}

impl PoseGraph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a node at `pose` (its initial estimate); returns its index. Node 0 is the map
    /// frame's anchor and never moves.
    pub fn add_node(&mut self, pose: Pose) -> usize {
        self.poses.push(pose);
        self.poses.len() - 1
    }

    /// Adds a measurement between two existing nodes.
    ///
    /// # Panics
    /// When either node does not exist.
    pub fn add_edge(&mut self, edge: Edge) {
        assert!(edge.from < self.poses.len() && edge.to < self.poses.len(), "no such node");
        self.edges.push(edge);
    }

    /// The current estimate of every node.
    pub fn poses(&self) -> &[Pose] {
        &self.poses
    }

    /// The edges.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// The residual of `edge` at the current poses, in the frame of its first node, with the
    /// Jacobians with respect to the first and the second node's `(x, y, θ)`.
    fn residual(&self, edge: &Edge) -> ([f64; 3], [[f64; 3]; 3], [[f64; 3]; 3]) {
        let (a, b, z) = (self.poses[edge.from], self.poses[edge.to], edge.measured);
        let (s, c) = a.theta.sin_cos();
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let e = [c * dx + s * dy - z.x, -s * dx + c * dy - z.y, wrap(b.theta - a.theta - z.theta)];
        let ja = [[-c, -s, -s * dx + c * dy], [s, -c, -c * dx - s * dy], [0.0, 0.0, -1.0]];
        let jb = [[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, 1.0]];
        (e, ja, jb)
    }

    /// The weighted squared error of every edge (robust weights included): what
    /// [`optimize`](Self::optimize) lowers.
    pub fn error(&self) -> f64 {
        self.edges
            .iter()
            .map(|edge| {
                let (e, _, _) = self.residual(edge);
                robust_cost(quadratic(&edge.information, &e))
            })
            .sum()
    }

    /// Gauss-Newton on the most recent [`WINDOW`] nodes (node 0 and older nodes held), at
    /// most `iterations` steps, each edge weighted by a Huber kernel on its Mahalanobis
    /// distance. Returns the steps taken.
    pub fn optimize(&mut self, iterations: usize) -> usize {
        let first = self.first_free();
        let n = self.poses.len().saturating_sub(first);
        if n == 0 {
            return 0;
        }
        for it in 0..iterations {
            let (mut h, g) = self.normal_equations(first);
            let Some(step) = cholesky_solve(&mut h, 3 * n, &g) else { return it };
            let mut largest = 0.0f64;
            for (k, p) in self.poses[first..].iter_mut().enumerate() {
                let d = &step[3 * k..3 * k + 3];
                p.x -= d[0];
                p.y -= d[1];
                p.theta = wrap(p.theta - d[2]);
                largest = largest.max(d[0].abs()).max(d[1].abs()).max(d[2].abs());
            }
            if largest < 1e-7 {
                return it + 1;
            }
        }
        iterations
    }

    /// The covariance of node `k`'s `(x, y, θ)` at the current poses (metres² and radians²),
    /// given every edge and the nodes [`optimize`](Self::optimize) holds: the inverse of the
    /// Gauss-Newton information, each edge robustly weighted as the solver weighs it. `None`
    /// for a held node (node 0, or one older than the window) or when the information is
    /// singular. The nodes held count as certain, so a chain of stops beyond the window
    /// reports its spread since the oldest node solved.
    pub fn covariance(&self, k: usize) -> Option<[[f64; 3]; 3]> {
        let first = self.first_free();
        if k < first || k >= self.poses.len() {
            return None;
        }
        let dim = 3 * (self.poses.len() - first);
        let (mut h, _) = self.normal_equations(first);
        cholesky(&mut h, dim)?;
        let at = 3 * (k - first);
        let mut out = [[0.0; 3]; 3];
        for c in 0..3 {
            let mut unit = vec![0.0; dim];
            unit[at + c] = 1.0;
            let col = solve_factored(&h, dim, &unit);
            for (r, row) in out.iter_mut().enumerate() {
                row[c] = col[at + r];
            }
        }
        Some(out)
    }

    /// The first node [`optimize`](Self::optimize) moves: node 0 and every node older than
    /// the most recent [`WINDOW`] are held.
    fn first_free(&self) -> usize {
        self.poses.len().saturating_sub(WINDOW).max(1)
    }

    /// The Gauss-Newton system `H`, `g` (row-major `H`, `3 n × 3 n` for the `n` nodes from
    /// `first` on) at the current poses, each edge weighted by a Huber kernel on its
    /// Mahalanobis distance; a node no edge reaches gets a tiny diagonal, so it stays put.
    fn normal_equations(&self, first: usize) -> (Vec<f64>, Vec<f64>) {
        let dim = 3 * self.poses.len().saturating_sub(first);
        let mut h = vec![0.0; dim * dim];
        let mut g = vec![0.0; dim];
        for edge in &self.edges {
            let free = |k: usize| (k >= first).then(|| 3 * (k - first));
            let (fa, fb) = (free(edge.from), free(edge.to));
            if fa.is_none() && fb.is_none() {
                continue;
            }
            let (e, ja, jb) = self.residual(edge);
            let chi = quadratic(&edge.information, &e).sqrt();
            let w = if chi <= ROBUST { 1.0 } else { ROBUST / chi };
            let omega = edge.information.map(|row| row.map(|v| v * w));
            // Ω·e and Jᵀ Ω J blocks.
            let oe: [f64; 3] = std::array::from_fn(|i| (0..3).map(|k| omega[i][k] * e[k]).sum());
            let blocks = [(fa, &ja), (fb, &jb)];
            for (pi, ji) in blocks {
                let Some(pi) = pi else { continue };
                for r in 0..3 {
                    g[pi + r] += (0..3).map(|k| ji[k][r] * oe[k]).sum::<f64>();
                }
                for (pj, jj) in blocks {
                    let Some(pj) = pj else { continue };
                    for r in 0..3 {
                        for col in 0..3 {
                            let v: f64 = (0..3)
                                .map(|k| {
                                    ji[k][r] * (0..3).map(|l| omega[k][l] * jj[l][col]).sum::<f64>()
                                })
                                .sum();
                            h[(pi + r) * dim + pj + col] += v;
                        }
                    }
                }
            }
        }
        for k in 0..dim {
            h[k * dim + k] += 1e-9;
        }
        (h, g)
    }
}

/// `eᵀ Ω e`.
fn quadratic(omega: &Information, e: &[f64; 3]) -> f64 {
    (0..3).map(|i| e[i] * (0..3).map(|k| omega[i][k] * e[k]).sum::<f64>()).sum()
}

/// The Huber cost of a squared Mahalanobis distance.
fn robust_cost(chi2: f64) -> f64 {
    let chi = chi2.sqrt();
    if chi <= ROBUST { chi2 } else { 2.0 * ROBUST * chi - ROBUST * ROBUST }
}

/// Solves `h x = g` for a symmetric positive definite `h` (row-major, `n × n`, overwritten by
/// its Cholesky factor); `None` when it is not positive definite.
fn cholesky_solve(h: &mut [f64], n: usize, g: &[f64]) -> Option<Vec<f64>> {
    cholesky(h, n)?;
    Some(solve_factored(h, n, g))
}

/// Overwrites the lower triangle of `h` (row-major, `n × n`, symmetric positive definite) with
/// its Cholesky factor `L` (`h = L Lᵀ`); `None` when it is not positive definite.
fn cholesky(h: &mut [f64], n: usize) -> Option<()> {
    for j in 0..n {
        let mut d = h[j * n + j];
        for k in 0..j {
            d -= h[j * n + k] * h[j * n + k];
        }
        if !(d > 0.0 && d.is_finite()) {
            return None;
        }
        let d = d.sqrt();
        h[j * n + j] = d;
        for i in j + 1..n {
            let mut v = h[i * n + j];
            for k in 0..j {
                v -= h[i * n + k] * h[j * n + k];
            }
            h[i * n + j] = v / d;
        }
    }
    Some(())
}

/// Solves `L Lᵀ x = g` for the factor [`cholesky`] left in `l`.
fn solve_factored(l: &[f64], n: usize, g: &[f64]) -> Vec<f64> {
    // L y = g, then Lᵀ x = y.
    let mut x = g.to_vec();
    for i in 0..n {
        for k in 0..i {
            x[i] -= l[i * n + k] * x[k];
        }
        x[i] /= l[i * n + i];
    }
    for i in (0..n).rev() {
        for k in i + 1..n {
            x[i] -= l[k * n + i] * x[k];
        }
        x[i] /= l[i * n + i];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn diag(p: f64, t: f64) -> Information {
        [[1.0 / (p * p), 0.0, 0.0], [0.0, 1.0 / (p * p), 0.0], [0.0, 0.0, 1.0 / (t * t)]]
    }

    fn relative(a: &Pose, b: &Pose) -> Pose {
        a.inverse().compose(b)
    }

    #[test]
    fn the_jacobians_match_finite_differences() {
        let mut g = PoseGraph::new();
        g.add_node(Pose { x: 1.0, y: -2.0, theta: 0.7 });
        g.add_node(Pose { x: 3.5, y: 0.5, theta: -1.2 });
        let edge = Edge {
            from: 0,
            to: 1,
            measured: Pose { x: 0.3, y: 2.0, theta: 0.4 },
            information: diag(1.0, 1.0),
        };
        let (_, ja, jb) = g.residual(&edge);
        let h = 1e-6;
        for node in 0..2 {
            for axis in 0..3 {
                let bump = |g: &mut PoseGraph, s: f64| {
                    let p = &mut g.poses[node];
                    match axis {
                        0 => p.x += s,
                        1 => p.y += s,
                        _ => p.theta += s,
                    }
                };
                let mut plus = g.clone();
                bump(&mut plus, h);
                let mut minus = g.clone();
                bump(&mut minus, -h);
                let (ep, _, _) = plus.residual(&edge);
                let (em, _, _) = minus.residual(&edge);
                let jac = if node == 0 { &ja } else { &jb };
                for r in 0..3 {
                    let numeric = (ep[r] - em[r]) / (2.0 * h);
                    assert!(
                        (numeric - jac[r][axis]).abs() < 1e-6,
                        "node {node} axis {axis} row {r}"
                    );
                }
            }
        }
    }

    #[test]
    fn consistent_measurements_are_met_exactly() {
        // A square loop, started from odometry that drifted; the scan matches are exact.
        let truth = [
            Pose { x: 0.0, y: 0.0, theta: 0.0 },
            Pose { x: 4.0, y: 0.0, theta: 1.5 },
            Pose { x: 4.0, y: 4.0, theta: 3.0 },
            Pose { x: 0.0, y: 4.0, theta: -1.6 },
        ];
        let mut g = PoseGraph::new();
        for (k, t) in truth.iter().enumerate() {
            g.add_node(Pose {
                x: t.x + 0.1 * k as f64,
                y: t.y - 0.05 * k as f64,
                theta: t.theta + 0.02,
            });
        }
        for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 0), (0, 2)] {
            g.add_edge(Edge {
                from: a,
                to: b,
                measured: relative(&truth[a], &truth[b]),
                information: diag(0.05, 0.01),
            });
        }
        // Node 0 was placed off its truth by nothing but the drift of the others.
        g.poses[0] = truth[0];
        g.optimize(20);
        for (p, t) in g.poses().iter().zip(&truth) {
            assert!((p.x - t.x).abs() < 1e-9 && (p.y - t.y).abs() < 1e-9, "{p:?} {t:?}");
            assert!(wrap(p.theta - t.theta).abs() < 1e-9);
        }
        assert!(g.error() < 1e-12);
    }

    #[test]
    fn a_sure_loop_closure_outweighs_drifted_odometry() {
        // Odometry says the robot ended 0.5 m off; a confident match to the start says where
        // it is. The stops between share the correction.
        let mut g = PoseGraph::new();
        let n = 6;
        for k in 0..n {
            g.add_node(Pose { x: k as f64, y: 0.1 * k as f64, theta: 0.0 });
        }
        for k in 1..n {
            g.add_edge(Edge {
                from: k - 1,
                to: k,
                measured: Pose { x: 1.0, y: 0.1, theta: 0.0 },
                information: diag(0.1, 0.01),
            });
        }
        g.add_edge(Edge {
            from: 0,
            to: n - 1,
            measured: Pose { x: (n - 1) as f64, y: 0.0, theta: 0.0 },
            information: diag(0.01, 0.001),
        });
        g.optimize(20);
        let last = g.poses()[n - 1];
        assert!((last.x - (n - 1) as f64).abs() < 0.01 && last.y.abs() < 0.02, "{last:?}");
        // The middle moved part of the way.
        let mid = g.poses()[3];
        assert!(mid.y > 0.0 && mid.y < 0.3, "{mid:?}");
    }

    #[test]
    fn one_wrong_match_is_outvoted() {
        // Three consistent matches and one that is 1 m off: the robust kernel keeps the
        // node near the three.
        let mut g = PoseGraph::new();
        g.add_node(Pose::default());
        g.add_node(Pose { x: 2.0, y: 0.0, theta: 0.0 });
        let sure = diag(0.05, 0.01);
        for _ in 0..3 {
            g.add_edge(Edge {
                from: 0,
                to: 1,
                measured: Pose { x: 2.0, y: 0.0, theta: 0.0 },
                information: sure,
            });
        }
        g.add_edge(Edge {
            from: 0,
            to: 1,
            measured: Pose { x: 3.0, y: 0.0, theta: 0.0 },
            information: sure,
        });
        g.optimize(50);
        assert!((g.poses()[1].x - 2.0).abs() < 0.1, "{:?}", g.poses()[1]);
    }

    #[test]
    fn nodes_before_the_window_hold() {
        let mut g = PoseGraph::new();
        for k in 0..WINDOW + 5 {
            g.add_node(Pose { x: k as f64, y: 0.0, theta: 0.0 });
        }
        for k in 1..WINDOW + 5 {
            g.add_edge(Edge {
                from: k - 1,
                to: k,
                measured: Pose { x: 1.0, y: 0.2, theta: 0.0 },
                information: diag(0.1, 0.01),
            });
        }
        let before = g.poses()[..5].to_vec();
        g.optimize(10);
        assert_eq!(&g.poses()[..5], &before[..]);
        // The free nodes followed their odometry from the held ones.
        let p = g.poses()[WINDOW + 4];
        assert!((p.y - 0.2 * (WINDOW as f64)).abs() < 1e-6, "{p:?}");
    }

    /// A chain of stops along x, each leg measured with position deviation `legs[i]` and a
    /// heading known almost exactly, plus the extra edges given.
    fn chain(legs: &[f64], extra: &[Edge]) -> PoseGraph {
        let mut g = PoseGraph::new();
        for k in 0..=legs.len() {
            g.add_node(Pose { x: k as f64, y: 0.0, theta: 0.0 });
        }
        for (k, &s) in legs.iter().enumerate() {
            g.add_edge(Edge {
                from: k,
                to: k + 1,
                measured: Pose { x: 1.0, y: 0.0, theta: 0.0 },
                information: diag(s, 1e-6),
            });
        }
        for e in extra {
            g.add_edge(*e);
        }
        g.optimize(10);
        g
    }

    #[test]
    fn a_chain_of_legs_is_as_unsure_as_the_sum_of_their_variances() {
        // Independent errors add their variances: the last stop's position is off by the
        // sum of its legs' errors.
        let legs = [0.1, 0.2, 0.05, 0.3];
        let g = chain(&legs, &[]);
        let c = g.covariance(legs.len()).expect("a solved node");
        let sum: f64 = legs.iter().map(|s| s * s).sum();
        assert!((c[0][0] - sum).abs() < 1e-9 * sum.max(1.0), "{c:?} against {sum}");
        assert!((c[1][1] - sum).abs() < 1e-9 * sum.max(1.0), "{c:?} against {sum}");
        assert!(c[0][1].abs() < 1e-9);
        // The second stop knows only its first two legs.
        let c1 = g.covariance(2).expect("a solved node");
        assert!((c1[0][0] - (0.01 + 0.04)).abs() < 1e-9, "{c1:?}");
        // Node 0 anchors the frame.
        assert_eq!(g.covariance(0), None);
        assert_eq!(g.covariance(legs.len() + 1), None);
    }

    #[test]
    fn a_loop_closure_makes_the_stops_it_ties_as_sure_as_both_ways_together() {
        // Two independent measurements of one position combine as the inverse of the sum of
        // their inverse variances: two legs of 0.3 one way, one direct match of 0.1.
        let direct = Edge {
            from: 0,
            to: 2,
            measured: Pose { x: 2.0, y: 0.0, theta: 0.0 },
            information: diag(0.1, 1e-6),
        };
        let g = chain(&[0.3, 0.3], &[direct]);
        let c = g.covariance(2).expect("a solved node");
        let both = 1.0 / (1.0 / (2.0 * 0.09) + 1.0 / 0.01);
        assert!((c[0][0] - both).abs() < 1e-9, "{c:?} against {both}");
        // The middle stop: its first leg one way, against its second leg plus the match the
        // other way (0.09 against 0.09 + 0.01).
        let c1 = g.covariance(1).expect("a solved node");
        let mid = 1.0 / (1.0 / 0.09 + 1.0 / (0.09 + 0.01));
        assert!((c1[1][1] - mid).abs() < 1e-9, "{c1:?} against {mid}");
    }

    proptest::proptest! {
        /// Measurements taken from true poses are all met at the truth, so from a perturbed
        /// start the solve returns to it: whatever the graph's shape, the information's
        /// scale, or where the stops stand.
        #[test]
        fn exact_measurements_bring_every_stop_back_to_its_truth(
            truth in proptest::collection::vec((-20.0..20.0f64, -20.0..20.0f64, -3.1..3.1f64), 2..12),
            extra in proptest::collection::vec((0usize..12, 0usize..12), 0..12),
            noise in proptest::collection::vec((-0.2..0.2f64, -0.2..0.2f64, -0.1..0.1f64), 12),
            scale in proptest::collection::vec((1.0..1000.0f64, 1.0..1000.0f64), 24),
        ) {
            let truth: Vec<Pose> = truth.iter().map(|&(x, y, theta)| Pose { x, y, theta }).collect();
            let n = truth.len();
            let mut g = PoseGraph::new();
            for (k, t) in truth.iter().enumerate() {
                let (dx, dy, dt) = if k == 0 { (0.0, 0.0, 0.0) } else { noise[k] };
                g.add_node(Pose { x: t.x + dx, y: t.y + dy, theta: wrap(t.theta + dt) });
            }
            let pairs: Vec<(usize, usize)> = (1..n)
                .map(|k| (k - 1, k))
                .chain(extra.iter().map(|&(a, b)| (a % n, b % n)).filter(|(a, b)| a != b))
                .collect();
            for (i, &(a, b)) in pairs.iter().enumerate() {
                let (p, t) = scale[i % scale.len()];
                g.add_edge(Edge {
                    from: a,
                    to: b,
                    measured: relative(&truth[a], &truth[b]),
                    information: diag(1.0 / p.sqrt(), 1.0 / t.sqrt()),
                });
            }
            g.optimize(50);
            for (p, t) in g.poses().iter().zip(&truth) {
                proptest::prop_assert!((p.x - t.x).abs() < 1e-6 && (p.y - t.y).abs() < 1e-6, "{:?} {:?}", p, t);
                proptest::prop_assert!(wrap(p.theta - t.theta).abs() < 1e-6);
            }
            proptest::prop_assert!(g.error() < 1e-9);
        }
    }
}
