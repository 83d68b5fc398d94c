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
    let mut pts: Vec<Vec<f64>> = vec![x0.to_vec()];
    for i in 0..n {
        let mut x = x0.to_vec();
        x[i] += step * x[i].abs().max(1.0);
        pts.push(x);
    }
    let mut vals: Vec<f64> = pts.iter().map(|x| f(x)).collect();
    let mut evals = n + 1;
    let point = |c: &[f64], w: &[f64], t: f64| -> Vec<f64> {
        c.iter().zip(w).map(|(a, b)| a + t * (b - a)).collect()
    };
    while evals < p.max_evaluations {
        let mut idx: Vec<usize> = (0..=n).collect();
        idx.sort_by(|&a, &b| vals[a].total_cmp(&vals[b]));
        pts = idx.iter().map(|&i| pts[i].clone()).collect();
        vals = idx.iter().map(|&i| vals[i]).collect();
        let spread = vals[n] - vals[0];
        let diameter = pts[1..]
            .iter()
            .map(|x| x.iter().zip(&pts[0]).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max))
            .fold(0.0, f64::max);
        if spread <= p.f_tolerance * (1.0 + vals[0].abs()) && diameter <= p.x_tolerance {
            break;
        }
        if diameter <= 1e-15 {
            break;
        }
        let mut centroid = vec![0.0; n];
        for x in &pts[..n] {
            for (c, v) in centroid.iter_mut().zip(x) {
                *c += v / n as f64;
            }
        }
        let reflected = point(&centroid, &pts[n], -1.0);
        let fr = f(&reflected);
        evals += 1;
        if fr < vals[0] {
            let expanded = point(&centroid, &pts[n], -2.0);
            let fe = f(&expanded);
            evals += 1;
            if fe < fr {
                (pts[n], vals[n]) = (expanded, fe);
            } else {
                (pts[n], vals[n]) = (reflected, fr);
            }
        } else if fr < vals[n - 1] {
            (pts[n], vals[n]) = (reflected, fr);
        } else {
            let (towards, fw) =
                if fr < vals[n] { (&reflected, fr) } else { (&pts[n].clone(), vals[n]) };
            let contracted = point(&centroid, towards, 0.5);
            let fc = f(&contracted);
            evals += 1;
            if fc < fw {
                (pts[n], vals[n]) = (contracted, fc);
            } else {
                let best = pts[0].clone();
                for i in 1..=n {
                    pts[i] = point(&best, &pts[i], 0.5);
                    vals[i] = f(&pts[i]);
                }
                evals += n;
            }
        }
    }
    let i = (0..=n).min_by(|&a, &b| vals[a].total_cmp(&vals[b])).unwrap_or(0);
    (pts[i].clone(), vals[i])
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
