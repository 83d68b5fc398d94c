//! A simulated 2D lidar as unkind as a real one: beams cast into the true polygon world, with
//! range noise, dropouts and spurious returns, reported as a [`LaserScan`] under ROS REP 117.

use std::str::FromStr;

use rand::{Rng, RngExt};

use crate::geometry::{Domain, ray_segment};
use crate::kernel::Point;
use crate::protocol::laser::{LaserScan, Pose};

/// A 2D lidar's model.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Lidar {
    /// Beams per revolution, spread evenly over a full turn.
    pub beams: usize,
    /// The nearest return it reports, metres.
    pub range_min: f64,
    /// The farthest return it reports, metres: beyond, `+inf` (no return).
    pub range_max: f64,
    /// The range noise's standard deviation, metres (Gaussian).
    pub sigma: f64,
    /// The chance that a beam returns nothing valid (`NaN`).
    pub dropout: f64,
    /// The chance that a beam returns a spurious range, uniform between `range_min` and its
    /// true range (dust, a mixed pixel).
    pub spurious: f64,
}

impl Default for Lidar {
    /// 720 beams, 0.05 to 20 m, σ = 0.02 m, 1% dropouts, no spurious returns: the figures of
    /// the raw-scan benchmark.
    fn default() -> Self {
        Self {
            beams: 720,
            range_min: 0.05,
            range_max: 20.0,
            sigma: 0.02,
            dropout: 0.01,
            spurious: 0.0,
        }
    }
}

/// Why a lidar specification was refused.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("sensor `{spec}`: {problem}")]
pub struct InvalidLidar {
    /// The specification as given.
    pub spec: String,
    /// What is wrong with it.
    pub problem: String,
}

impl FromStr for Lidar {
    type Err = InvalidLidar;

    /// `lidar` or `lidar:key=value,…` with keys `beams`, `min`, `max`, `sigma`, `dropout`,
    /// `spurious` (the rest keep [`Lidar::default`]'s values).
    fn from_str(spec: &str) -> Result<Self, InvalidLidar> {
        let bad = |problem: String| InvalidLidar { spec: spec.into(), problem };
        let rest = spec
            .strip_prefix("lidar")
            .ok_or_else(|| bad("the only sensor model is `lidar[:beams=720,max=20,sigma=0.02,dropout=0.01,spurious=0,min=0.05]`".into()))?;
        let mut l = Self::default();
        let rest = match rest {
            "" => "",
            r => r
                .strip_prefix(':')
                .ok_or_else(|| bad("options follow a colon: lidar:beams=720".into()))?,
        };
        for item in rest.split(',').filter(|s| !s.is_empty()) {
            let (k, v) =
                item.split_once('=').ok_or_else(|| bad(format!("`{item}` is not key=value")))?;
            let num: f64 =
                v.trim().parse().map_err(|_| bad(format!("`{k}` must be a number, got `{v}`")))?;
            match k.trim() {
                "beams" => {
                    if !(num.fract() == 0.0 && (8.0..=100_000.0).contains(&num)) {
                        return Err(bad(format!(
                            "`beams` must be a whole number from 8 to 100000, got {v}"
                        )));
                    }
                    l.beams = num as usize;
                }
                "min" => l.range_min = num,
                "max" => l.range_max = num,
                "sigma" => l.sigma = num,
                "dropout" => l.dropout = num,
                "spurious" => l.spurious = num,
                other => {
                    return Err(bad(format!(
                        "unknown key `{other}`; use beams, min, max, sigma, dropout, spurious"
                    )));
                }
            }
        }
        l.check().map_err(bad)?;
        Ok(l)
    }
}

impl Lidar {
    /// Checks the model's values; the message names the key.
    ///
    /// # Errors
    /// A message naming the first key out of bounds.
    pub fn check(&self) -> Result<(), String> {
        if !(self.range_min.is_finite() && self.range_min >= 0.0) {
            return Err(format!(
                "`min` must be a finite number of metres >= 0, got {}",
                self.range_min
            ));
        }
        if !(self.range_max.is_finite() && self.range_max > self.range_min) {
            return Err(format!("`max` must be finite and above `min`, got {}", self.range_max));
        }
        if !(self.sigma.is_finite() && (0.0..=1.0).contains(&self.sigma)) {
            return Err(format!("`sigma` must be between 0 and 1 m, got {}", self.sigma));
        }
        for (k, p) in [("dropout", self.dropout), ("spurious", self.spurious)] {
            if !(0.0..=0.5).contains(&p) {
                return Err(format!("`{k}` must be a chance between 0 and 0.5, got {p}"));
            }
        }
        Ok(())
    }

    /// One scan from `pose` (the scanner's true pose) in `walls`, drawing noise from `rng`.
    pub fn scan(&self, walls: &Walls, pose: &Pose, rng: &mut impl Rng) -> LaserScan {
        let inc = std::f64::consts::TAU / self.beams as f64;
        let angle_min = -std::f64::consts::PI;
        let ranges = (0..self.beams)
            .map(|i| {
                let a = pose.theta + angle_min + i as f64 * inc;
                let truth = walls.cast(pose.at(), [a.cos(), a.sin()], self.range_max);
                // Draw every random number for every beam, so that one beam's outcome does
                // not shift the others' draws.
                let (u_drop, u_spur, u_pos, noise) =
                    (rng.random::<f64>(), rng.random::<f64>(), rng.random::<f64>(), gaussian(rng));
                if u_drop < self.dropout {
                    return f64::NAN;
                }
                let far = truth.unwrap_or(self.range_max);
                if u_spur < self.spurious {
                    return self.range_min + u_pos * (far - self.range_min);
                }
                let Some(r) = truth else { return f64::INFINITY };
                let r = r + self.sigma * noise;
                if r >= self.range_max {
                    f64::INFINITY
                } else if r < self.range_min {
                    f64::NEG_INFINITY
                } else {
                    r
                }
            })
            .collect();
        LaserScan {
            angle_min,
            angle_increment: inc,
            range_min: self.range_min,
            range_max: self.range_max,
            ranges,
        }
    }
}

/// A standard normal draw (Box–Muller).
pub fn gaussian(rng: &mut impl Rng) -> f64 {
    let u1: f64 = rng.random::<f64>().max(f64::MIN_POSITIVE);
    let u2: f64 = rng.random();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// A domain's edges, bucketed by a uniform grid for ray casting.
#[derive(Debug, Clone)]
pub struct Walls {
    edges: Vec<[Point; 2]>,
    origin: Point,
    cell: f64,
    dims: [usize; 2],
    cells: Vec<Vec<u32>>,
}

impl Walls {
    /// The edges of `domain`.
    pub fn of(domain: &Domain) -> Self {
        let edges: Vec<[Point; 2]> = domain
            .rings()
            .iter()
            .flat_map(|r| (0..r.len()).map(move |i| [r[i], r[(i + 1) % r.len()]]))
            .collect();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for e in &edges {
            for p in e {
                for k in 0..2 {
                    lo[k] = lo[k].min(p[k]);
                    hi[k] = hi[k].max(p[k]);
                }
            }
        }
        // About as many cells as edges.
        let span = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let cell = (span / (edges.len() as f64).sqrt().max(1.0)).max(span / 4096.0);
        let dims = [
            (((hi[0] - lo[0]) / cell).floor() as usize + 1).min(4096),
            (((hi[1] - lo[1]) / cell).floor() as usize + 1).min(4096),
        ];
        let mut cells = vec![Vec::new(); dims[0] * dims[1]];
        let idx =
            |v: f64, k: usize| (((v - lo[k]) / cell).floor().max(0.0) as usize).min(dims[k] - 1);
        for (id, e) in edges.iter().enumerate() {
            for i in idx(e[0][0].min(e[1][0]), 0)..=idx(e[0][0].max(e[1][0]), 0) {
                for j in idx(e[0][1].min(e[1][1]), 1)..=idx(e[0][1].max(e[1][1]), 1) {
                    cells[j * dims[0] + i].push(id as u32);
                }
            }
        }
        Self { edges, origin: lo, cell, dims, cells }
    }

    /// The distance along the ray from `o` in the unit direction `u` to the first edge, if
    /// within `max`.
    pub fn cast(&self, o: Point, u: Point, max: f64) -> Option<f64> {
        // Walk the grid cells along the ray (Amanatides–Woo), nearest first.
        let (lo, c) = (self.origin, self.cell);
        let mut best = f64::INFINITY;
        let fx = (o[0] - lo[0]) / c;
        let fy = (o[1] - lo[1]) / c;
        let (mut i, mut j) = (fx.floor() as i64, fy.floor() as i64);
        let (si, sj) = (if u[0] >= 0.0 { 1 } else { -1 }, if u[1] >= 0.0 { 1 } else { -1 });
        let next = |f: f64, d: f64| {
            if d > 0.0 {
                (f.floor() + 1.0 - f) * c / d
            } else if d < 0.0 {
                (f - f.floor()) * c / -d
            } else {
                f64::INFINITY
            }
        };
        let (mut tx, mut ty) = (next(fx, u[0]), next(fy, u[1]));
        let (dx, dy) = (
            if u[0] == 0.0 { f64::INFINITY } else { c / u[0].abs() },
            if u[1] == 0.0 { f64::INFINITY } else { c / u[1].abs() },
        );
        let mut t = 0.0;
        loop {
            if i >= 0 && j >= 0 && (i as usize) < self.dims[0] && (j as usize) < self.dims[1] {
                for &id in &self.cells[j as usize * self.dims[0] + i as usize] {
                    let [a, b] = self.edges[id as usize];
                    if let Some(h) = ray_segment(o, u, a, b) {
                        best = best.min(h);
                    }
                }
            } else if (i < 0 && si < 0)
                || (j < 0 && sj < 0)
                || (i >= self.dims[0] as i64 && si > 0)
                || (j >= self.dims[1] as i64 && sj > 0)
            {
                break;
            }
            // Every hit within the cells walked so far is final once it is nearer than
            // where the ray leaves the current cell.
            let leave = tx.min(ty);
            if best <= leave || t > max {
                break;
            }
            if tx < ty {
                t = tx;
                tx += dx;
                i += si;
            } else {
                t = ty;
                ty += dy;
                j += sj;
            }
        }
        (best <= max).then_some(best)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    fn room() -> Domain {
        Domain::new(
            vec![[0.0, 0.0], [10.0, 0.0], [10.0, 6.0], [0.0, 6.0]],
            vec![vec![[4.0, 2.0], [4.0, 3.0], [5.0, 3.0], [5.0, 2.0]]],
        )
        .unwrap()
    }

    /// The ray's first hit by brute force over every edge.
    fn brute(d: &Domain, o: Point, u: Point) -> Option<f64> {
        d.rings()
            .iter()
            .flat_map(|r| (0..r.len()).map(move |i| [r[i], r[(i + 1) % r.len()]]))
            .filter_map(|e| ray_segment(o, u, e[0], e[1]))
            .reduce(f64::min)
    }

    #[test]
    fn the_grid_walk_finds_the_first_wall_as_brute_force_does() {
        let d = room();
        let w = Walls::of(&d);
        for k in 0..3600u32 {
            let a = f64::from(k) * std::f64::consts::TAU / 3600.0;
            let u = [a.cos(), a.sin()];
            for o in [[1.0, 1.0], [7.5, 4.2], [4.5, 1.0], [0.0, 3.0]] {
                let (g, b) = (w.cast(o, u, 100.0), brute(&d, o, u));
                match (g, b) {
                    (Some(g), Some(b)) => assert!((g - b).abs() < 1e-12, "{o:?} {a}: {g} {b}"),
                    (g, b) => assert_eq!(g, b, "{o:?} {a}"),
                }
            }
        }
    }

    #[test]
    fn a_noise_free_scan_reports_true_ranges_and_rep117_values() {
        let w = Walls::of(&room());
        let l = Lidar { beams: 360, sigma: 0.0, dropout: 0.0, range_max: 5.0, ..Lidar::default() };
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let s = l.scan(&w, &Pose { x: 1.0, y: 1.0, theta: 0.0 }, &mut rng);
        // Beam 180 looks along +x, below the pillar, at the wall 9 m away: beyond range.
        assert_eq!(s.ranges[180], f64::INFINITY);
        // Beam 90 looks along -y: the wall 1 m away.
        assert!((s.ranges[90] - 1.0).abs() < 1e-12);
        let noisy = Lidar { dropout: 0.2, spurious: 0.1, ..l };
        let s = noisy.scan(&w, &Pose { x: 1.0, y: 1.0, theta: 0.0 }, &mut rng);
        let nan = s.ranges.iter().filter(|r| r.is_nan()).count();
        assert!((40..110).contains(&nan), "{nan}");
        // The same seed gives the same scan.
        let a = noisy.scan(&w, &Pose::default(), &mut ChaCha8Rng::seed_from_u64(9));
        let b = noisy.scan(&w, &Pose::default(), &mut ChaCha8Rng::seed_from_u64(9));
        assert_eq!(format!("{a:?}"), format!("{b:?}"));
    }

    #[test]
    fn specs_parse_and_bad_ones_name_the_key() {
        let l: Lidar = "lidar:beams=360,max=12,sigma=0.01,dropout=0.02".parse().unwrap();
        assert_eq!((l.beams, l.range_max, l.sigma, l.dropout), (360, 12.0, 0.01, 0.02));
        assert_eq!("lidar".parse::<Lidar>().unwrap(), Lidar::default());
        for (spec, key) in [
            ("lidar:beams=7", "beams"),
            ("lidar:sigma=-1", "sigma"),
            ("lidar:dropout=0.9", "dropout"),
            ("lidar:max=0.01", "max"),
            ("lidar:speed=3", "speed"),
            ("lidar:beams", "beams"),
            ("camera", "lidar"),
        ] {
            let e = spec.parse::<Lidar>().unwrap_err().to_string();
            assert!(e.contains(key), "{spec}: {e}");
        }
    }
}
