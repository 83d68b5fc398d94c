//! Derivative-free minimisation by the Nelder–Mead simplex method, with restarts.
//!
//! Used for small non-smooth problems (minimax ratios over a handful of points), where a
//! restarted simplex is reliable and needs no gradient.

/// Settings for [`minimize`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NelderMeadParams {
    /// Initial simplex edge, relative to `max(1, |x_i|)`.
    pub initial_step: f64,
    /// Stop when the spread of function values in the simplex is below this.
    pub f_tolerance: f64,
    /// Stop when the simplex diameter is below this.
    pub x_tolerance: f64,
    /// Function evaluations per restart.
    pub max_evaluations: usize,
    /// Restarts from the best point while they still improve.
    pub max_restarts: usize,
}

impl Default for NelderMeadParams {
    fn default() -> Self {
        Self {
            initial_step: 0.1,
            f_tolerance: 1e-15,
            x_tolerance: 1e-13,
            max_evaluations: 20_000,
            max_restarts: 50,
        }
    }
}

impl NelderMeadParams {
    /// Sets the initial simplex edge.
    #[must_use]
    pub fn with_initial_step(mut self, step: f64) -> Self {
        self.initial_step = step;
        self
    }
}

/// Minimises `f` from `x0`; returns the best point and its value.
///
/// Standard coefficients (reflection 1, expansion 2, contraction 1/2, shrink 1/2). After
/// convergence the simplex is rebuilt around the best point and the search restarts, which
/// escapes the premature collapse the plain method suffers on non-smooth functions.
///
/// # Complexity
/// O(max_evaluations · (n + cost of f)) per restart.
///
/// # Example
/// ```
/// use stopscan::algorithm::nelder_mead::{minimize, NelderMeadParams};
/// let (x, v) = minimize(|p| (p[0] - 1.0).powi(2) + (p[1] + 2.0).abs(), &[0.0, 0.0], NelderMeadParams::default());
/// assert!(v < 1e-9 && (x[0] - 1.0).abs() < 1e-4);
/// ```
pub fn minimize(
    f: impl Fn(&[f64]) -> f64,
    x0: &[f64],
    params: NelderMeadParams,
) -> (Vec<f64>, f64) {
    let mut best = (x0.to_vec(), f(x0));
    let mut step = params.initial_step;
    for _ in 0..=params.max_restarts {
        let (x, v) = simplex_run(&f, &best.0, step, &params);
        let improved = v < best.1 - 1e-15 * (1.0 + best.1.abs());
        if v <= best.1 {
            best = (x, v);
        }
        if !improved {
            if step < 1e-7 {
                break;
            }
            step *= 0.1;
        }
    }
    best
}

fn simplex_run(
    f: &impl Fn(&[f64]) -> f64,
    x0: &[f64],
    step: f64,
    p: &NelderMeadParams,
) -> (Vec<f64>, f64) {
    let n = x0.len();
    // The simplex, vertex `i` at `pts[i·n..(i+1)·n]`; `order` lists vertices best first.
    let mut pts: Vec<f64> = Vec::with_capacity((n + 1) * n);
    pts.extend_from_slice(x0);
    for i in 0..n {
        let start = pts.len();
        pts.extend_from_slice(x0);
        pts[start + i] += step * x0[i].abs().max(1.0);
    }
    let mut vals: Vec<f64> = pts.chunks_exact(n.max(1)).take(n + 1).map(f).collect();
    let mut evals = n + 1;
    let mut order: Vec<usize> = (0..=n).collect();
    let (mut centroid, mut reflected, mut trial) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    // `out = c + t·(w − c)`.
    let towards = |out: &mut [f64], c: &[f64], w: &[f64], t: f64| {
        for ((o, a), b) in out.iter_mut().zip(c).zip(w) {
            *o = a + t * (b - a);
        }
    };
    while evals < p.max_evaluations {
        order.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
        let (best, worst) = (order[0], order[n]);
        let vertex = |i: usize| i * n..(i + 1) * n;
        let spread = vals[worst] - vals[best];
        let diameter = order[1..]
            .iter()
            .map(|&i| {
                pts[vertex(i)]
                    .iter()
                    .zip(&pts[vertex(best)])
                    .map(|(a, b)| (a - b).abs())
                    .fold(0.0, f64::max)
            })
            .fold(0.0, f64::max);
        if spread <= p.f_tolerance * (1.0 + vals[best].abs()) && diameter <= p.x_tolerance {
            break;
        }
        if diameter <= 1e-15 {
            break;
        }
        centroid.fill(0.0);
        for &i in &order[..n] {
            for (c, v) in centroid.iter_mut().zip(&pts[vertex(i)]) {
                *c += v / n as f64;
            }
        }
        towards(&mut reflected, &centroid, &pts[vertex(worst)], -1.0);
        let fr = f(&reflected);
        evals += 1;
        if fr < vals[best] {
            towards(&mut trial, &centroid, &pts[vertex(worst)], -2.0);
            let fe = f(&trial);
            evals += 1;
            if fe < fr {
                pts[vertex(worst)].copy_from_slice(&trial);
                vals[worst] = fe;
            } else {
                pts[vertex(worst)].copy_from_slice(&reflected);
                vals[worst] = fr;
            }
        } else if fr < vals[order[n - 1]] {
            pts[vertex(worst)].copy_from_slice(&reflected);
            vals[worst] = fr;
        } else {
            let fw = if fr < vals[worst] {
                towards(&mut trial, &centroid, &reflected, 0.5);
                fr
            } else {
                towards(&mut trial, &centroid, &pts[vertex(worst)], 0.5);
                vals[worst]
            };
            let fc = f(&trial);
            evals += 1;
            if fc < fw {
                pts[vertex(worst)].copy_from_slice(&trial);
                vals[worst] = fc;
            } else {
                let anchor = pts[vertex(best)].to_vec();
                for &i in &order[1..] {
                    towards(&mut trial, &anchor, &pts[vertex(i)], 0.5);
                    pts[vertex(i)].copy_from_slice(&trial);
                    vals[i] = f(&trial);
                }
                evals += n;
            }
        }
    }
    let i = (0..=n).min_by(|&a, &b| vals[a].total_cmp(&vals[b])).unwrap_or(0);
    (pts[i * n..(i + 1) * n].to_vec(), vals[i])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rosenbrock() {
        let f = |x: &[f64]| 100.0 * (x[1] - x[0] * x[0]).powi(2) + (1.0 - x[0]).powi(2);
        let (x, v) = minimize(f, &[-1.2, 1.0], NelderMeadParams::default());
        assert!(v < 1e-12, "{v}");
        assert!((x[0] - 1.0).abs() < 1e-6 && (x[1] - 1.0).abs() < 1e-6);
    }

    #[test]
    fn minimax_of_two_lines() {
        // max(x, 1 − x) is minimal (1/2) at x = 1/2, a kink.
        let (x, v) = minimize(|x| x[0].max(1.0 - x[0]), &[3.0], NelderMeadParams::default());
        assert!((v - 0.5).abs() < 1e-12 && (x[0] - 0.5).abs() < 1e-9);
    }
}
