//! Beliefs and truths about the hidden edge angle θ ∈ [0, π].
//!
//! The corner paper models the robot's belief as a distribution `P(θ)`: a truncated Gaussian
//! (rectilinear buildings), a uniform (no prior knowledge), mixtures, or a histogram of the
//! angles observed so far. Every distribution here has an exact CDF, so expected times are
//! computed exactly, not sampled.

use std::f64::consts::PI;
use std::path::Path;

use rand::Rng;
use rand::RngExt;
use serde::{Deserialize, Serialize};

use crate::kernel::Num;
use crate::kernel::tolerance::{ANGLE_SLACK, COUNT_SLACK};

/// A Gaussian with less mass than this inside [0, π] is refused: truncating it to [0, π]
/// would divide by (almost) nothing.
const NEGLIGIBLE_MASS: f64 = 1e-12;

/// How far past π (radians) a histogram bucket may end before it is refused; buckets that end
/// past π are clipped to it.
const BUCKET_END_SLACK: f64 = 1e-9;

/// A distribution of the edge angle θ on [0, π] (radians).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum AngleDistribution {
    /// Uniform on `[lo, hi]`.
    Uniform {
        /// Lower end, radians.
        lo: f64,
        /// Upper end, radians.
        hi: f64,
    },
    /// A Gaussian truncated to [0, π] and renormalised.
    Normal {
        /// Mean, radians.
        mean: f64,
        /// Standard deviation, radians.
        sd: f64,
    },
    /// A weighted mixture; weights sum to one.
    Mixture {
        /// `(weight, component)` pairs.
        parts: Vec<(f64, AngleDistribution)>,
    },
    /// Piecewise uniform over disjoint buckets `[lo, hi]` with probabilities summing to one.
    Histogram {
        /// `(lo, hi, probability)` for each bucket, sorted and disjoint.
        buckets: Vec<(f64, f64, f64)>,
    },
}

/// The most buckets a bucketed or observed histogram may have (a width of 0.01°): its CDF
/// costs one pass over the buckets, and sampling evaluates it 60 times per draw.
pub const MAX_BUCKETS: usize = 18_000;

/// The number of buckets of width `bucket` (radians) over [0, π].
fn bucket_count(bucket: f64) -> Result<usize, InvalidDistribution> {
    if !(bucket.is_finite() && bucket > 0.0 && bucket <= PI) {
        return Err(InvalidDistribution::BucketWidth(bucket));
    }
    let n = (PI / bucket - COUNT_SLACK).ceil();
    if n > MAX_BUCKETS as f64 {
        return Err(InvalidDistribution::TooManyBuckets { width: bucket, count: n });
    }
    Ok(n as usize)
}

/// Why a distribution or its specification was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidDistribution {
    /// The text is not one of `uniform:LO,HI`, `normal:MEAN,SD`, `mix:W*SPEC+W*SPEC...`,
    /// `histogram:FILE` or `observed:FILE[,BUCKET]` (degrees).
    #[error("cannot read distribution {spec:?}: {reason}")]
    Spec {
        /// The specification as given.
        spec: String,
        /// What is wrong with it.
        reason: String,
    },
    /// A histogram or observation file is malformed; the line number is 1-based.
    #[error("{file}{}: {reason}", if *line == 0 { String::new() } else { format!(":{line}") })]
    File {
        /// The file.
        file: String,
        /// The line (0 when the whole file is at fault).
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A bucket width outside (0°, 180°].
    #[error("bucket width must be in (0, 180] degrees, got {}°", Num(.0.to_degrees()))]
    BucketWidth(
        /// The width given, radians.
        f64,
    ),
    /// A bucket width so narrow that it gives more than [`MAX_BUCKETS`] buckets.
    #[error(
        "a bucket width of {}° gives {} buckets; use at least 0.01° (at most {MAX_BUCKETS} buckets)",
        Num(.width.to_degrees()),
        Num(*.count)
    )]
    TooManyBuckets {
        /// The width given, radians.
        width: f64,
        /// The number of buckets it gives over [0, π].
        count: f64,
    },
    /// A uniform distribution whose interval is empty or leaves [0°, 180°].
    #[error(
        "uniform needs 0 <= lo < hi <= 180 degrees, got [{}, {}]",
        Num(.lo.to_degrees()),
        Num(.hi.to_degrees())
    )]
    UniformBounds {
        /// The lower end, radians.
        lo: f64,
        /// The upper end, radians.
        hi: f64,
    },
    /// A Gaussian with a mean that is not finite or a standard deviation that is not positive.
    #[error(
        "normal needs a finite mean and a positive standard deviation, got {}, {}",
        Num(.mean.to_degrees()),
        Num(.sd.to_degrees())
    )]
    NormalParameters {
        /// The mean, radians.
        mean: f64,
        /// The standard deviation, radians.
        sd: f64,
    },
    /// A Gaussian with (numerically) no mass inside [0°, 180°], so it cannot be truncated
    /// to it.
    #[error(
        "normal({}, {}) has no mass in [0, 180] degrees",
        Num(.mean.to_degrees()),
        Num(.sd.to_degrees())
    )]
    NormalNoMass {
        /// The mean, radians.
        mean: f64,
        /// The standard deviation, radians.
        sd: f64,
    },
    /// A mixture without parts, with a negative or non-finite weight, or whose weights sum
    /// to zero.
    #[error("mixture weights must be non-negative with a positive sum")]
    MixtureWeights,
    /// A histogram without buckets.
    #[error("a histogram needs at least one bucket")]
    EmptyHistogram,
    /// A histogram bucket that is invalid on its own.
    #[error("histogram bucket {bucket} {}: {problem}", degrees(*.range))]
    InvalidBucket {
        /// The bucket, counted from 1 in the order given.
        bucket: usize,
        /// Its `[LO, HI]`, radians.
        range: [f64; 2],
        /// What is wrong with it.
        problem: BucketProblem,
    },
    /// Two histogram buckets overlap.
    #[error(
        "histogram bucket {bucket} {} overlaps bucket {other} {}",
        degrees(*.range),
        degrees(*.other_range)
    )]
    OverlappingBuckets {
        /// The later of the two in the order given, counted from 1.
        bucket: usize,
        /// Its `[LO, HI]`, radians.
        range: [f64; 2],
        /// The earlier one, counted from 1.
        other: usize,
        /// Its `[LO, HI]`, radians.
        other_range: [f64; 2],
    },
    /// A histogram whose weights do not have a positive finite sum.
    #[error("the histogram's weights sum to {}; give at least one positive weight", Num(*.0))]
    HistogramWeights(
        /// The sum of the weights.
        f64,
    ),
    /// An observed angle outside [0°, 180°].
    #[error("observed angle {} is outside [0, 180] degrees", Num(.0.to_degrees()))]
    ObservedAngle(
        /// The angle, radians.
        f64,
    ),
}

/// What is wrong with one bucket of a histogram, on its own.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BucketProblem {
    /// LO or HI is not finite.
    #[error("LO and HI must be finite")]
    NotFinite,
    /// LO is not below HI.
    #[error("LO must be below HI")]
    Empty,
    /// The bucket leaves [0°, 180°].
    #[error("leaves [0, 180] degrees")]
    OutsideRange,
    /// The weight is not finite.
    #[error("weight {} is not finite", Num(*.0))]
    WeightNotFinite(
        /// The weight.
        f64,
    ),
    /// The weight is negative.
    #[error("weight {} is negative", Num(*.0))]
    NegativeWeight(
        /// The weight.
        f64,
    ),
}

impl AngleDistribution {
    /// Uniform on `[lo, hi]` radians, validated.
    ///
    /// # Errors
    /// If the interval is empty or leaves [0, π].
    pub fn uniform(lo: f64, hi: f64) -> Result<Self, InvalidDistribution> {
        if !(lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi && hi <= PI + ANGLE_SLACK) {
            return Err(InvalidDistribution::UniformBounds { lo, hi });
        }
        Ok(Self::Uniform { lo, hi: hi.min(PI) })
    }

    /// A Gaussian truncated to [0, π], validated (radians).
    ///
    /// # Errors
    /// If the standard deviation is not positive or the mass inside [0, π] is negligible.
    pub fn normal(mean: f64, sd: f64) -> Result<Self, InvalidDistribution> {
        if !(mean.is_finite() && sd.is_finite() && sd > 0.0) {
            return Err(InvalidDistribution::NormalParameters { mean, sd });
        }
        if normal_cdf((PI - mean) / sd) - normal_cdf(-mean / sd) < NEGLIGIBLE_MASS {
            return Err(InvalidDistribution::NormalNoMass { mean, sd });
        }
        Ok(Self::Normal { mean, sd })
    }

    /// A mixture with weights normalised to one.
    ///
    /// # Errors
    /// If a weight is negative or all are zero.
    pub fn mixture(parts: Vec<(f64, AngleDistribution)>) -> Result<Self, InvalidDistribution> {
        let total: f64 = parts.iter().map(|p| p.0).sum();
        if parts.is_empty()
            || parts.iter().any(|p| !(p.0.is_finite() && p.0 >= 0.0))
            || total <= 0.0
        {
            return Err(InvalidDistribution::MixtureWeights);
        }
        Ok(Self::Mixture { parts: parts.into_iter().map(|(w, d)| (w / total, d)).collect() })
    }

    /// A histogram from `(lo, hi, weight)` buckets in radians; weights are normalised.
    ///
    /// # Errors
    /// If buckets are empty, overlap, leave [0, π] or the weights do not have a positive sum.
    pub fn histogram(mut buckets: Vec<(f64, f64, f64)>) -> Result<Self, InvalidDistribution> {
        if buckets.is_empty() {
            return Err(InvalidDistribution::EmptyHistogram);
        }
        let total = check_buckets(&buckets).map_err(|f| {
            let range = |k: usize| [buckets[k].0, buckets[k].1];
            match f {
                BucketFault::Invalid { index, problem } => InvalidDistribution::InvalidBucket {
                    bucket: index + 1,
                    range: range(index),
                    problem,
                },
                BucketFault::Overlap { index, other } => InvalidDistribution::OverlappingBuckets {
                    bucket: index + 1,
                    range: range(index),
                    other: other + 1,
                    other_range: range(other),
                },
            }
        })?;
        if !(total.is_finite() && total > 0.0) {
            return Err(InvalidDistribution::HistogramWeights(total));
        }
        buckets.sort_by(|a, b| a.0.total_cmp(&b.0));
        Ok(Self::Histogram {
            buckets: buckets.into_iter().map(|(l, h, w)| (l, h.min(PI), w / total)).collect(),
        })
    }

    /// The corner paper's learning idea: a histogram of the angles observed so far, with
    /// buckets of width `bucket` over [0, π] and a pseudo-count added to every bucket so that
    /// no angle is ever believed impossible.
    ///
    /// # Errors
    /// If the bucket width is not in (0, π], gives more than [`MAX_BUCKETS`] buckets, or an
    /// angle lies outside [0, π].
    pub fn from_observations(
        angles: &[f64],
        bucket: f64,
        pseudo_count: f64,
    ) -> Result<Self, InvalidDistribution> {
        let n = bucket_count(bucket)?;
        let mut counts = vec![pseudo_count.max(0.0); n];
        for &a in angles {
            if !(0.0..=PI).contains(&a) {
                return Err(InvalidDistribution::ObservedAngle(a));
            }
            counts[((a / bucket) as usize).min(n - 1)] += 1.0;
        }
        let buckets =
            (0..n).map(|k| (k as f64 * bucket, ((k + 1) as f64 * bucket).min(PI), counts[k]));
        Self::histogram(buckets.collect())
    }

    /// The distribution discretised into buckets of width `bucket` (each bucket keeps its exact
    /// mass and is uniform inside), as the corner paper's Fig. 5 distributions are.
    ///
    /// # Errors
    /// If the bucket width is not in (0, π] or gives more than [`MAX_BUCKETS`] buckets.
    pub fn bucketed(&self, bucket: f64) -> Result<Self, InvalidDistribution> {
        let n = bucket_count(bucket)?;
        let buckets = (0..n).map(|k| {
            let lo = k as f64 * bucket;
            let hi = ((k + 1) as f64 * bucket).min(PI);
            (lo, hi, self.cdf(hi) - self.cdf(lo))
        });
        Self::histogram(buckets.collect())
    }

    /// `P(Θ ≤ θ)`, exact (to the precision of `erf` for Gaussians).
    pub fn cdf(&self, theta: f64) -> f64 {
        if theta <= 0.0 {
            return 0.0;
        }
        if theta >= PI {
            return 1.0;
        }
        match self {
            Self::Uniform { lo, hi } => ((theta - lo) / (hi - lo)).clamp(0.0, 1.0),
            Self::Normal { mean, sd } => {
                let a = normal_cdf(-mean / sd);
                let b = normal_cdf((PI - mean) / sd);
                ((normal_cdf((theta - mean) / sd) - a) / (b - a)).clamp(0.0, 1.0)
            }
            Self::Mixture { parts } => parts.iter().map(|(w, d)| w * d.cdf(theta)).sum(),
            Self::Histogram { buckets } => buckets
                .iter()
                .map(|&(lo, hi, p)| p * ((theta - lo) / (hi - lo)).clamp(0.0, 1.0))
                .sum::<f64>()
                .min(1.0),
        }
    }

    /// `P(a < Θ ≤ b)`.
    pub fn mass(&self, a: f64, b: f64) -> f64 {
        (self.cdf(b) - self.cdf(a)).max(0.0)
    }

    /// The quantile function: the smallest θ with `cdf(θ) ≥ u`, by bisection to 1e-13 rad.
    pub fn quantile(&self, u: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, PI);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.cdf(mid) >= u {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    }

    /// Draws one angle by inversion of the CDF.
    pub fn sample<R: Rng + ?Sized>(&self, rng: &mut R) -> f64 {
        let u: f64 = rng.random_range(0.0..1.0);
        self.quantile(u.max(f64::MIN_POSITIVE))
    }

    /// Parses a specification in degrees: `uniform:0,180`, `normal:60,5`,
    /// `mix:0.5*normal:30,3+0.5*normal:90,3`, `histogram:FILE` or `observed:FILE[,BUCKET_DEG]`.
    ///
    /// A histogram file has one bucket per line, `LO HI WEIGHT` in degrees (commas or
    /// white space); an observation file has one observed angle in degrees per line. `#`
    /// starts a comment in both.
    ///
    /// # Errors
    /// [`InvalidDistribution`] naming the specification, or the file and line, at fault.
    pub fn parse(spec: &str) -> Result<Self, InvalidDistribution> {
        let bad =
            |reason: &str| InvalidDistribution::Spec { spec: spec.into(), reason: reason.into() };
        let (kind, rest) = spec.split_once(':').ok_or_else(|| bad("expected KIND:PARAMETERS"))?;
        let numbers = |text: &str, count: usize| -> Result<Vec<f64>, InvalidDistribution> {
            let v: Result<Vec<f64>, _> = text.split(',').map(|t| t.trim().parse::<f64>()).collect();
            match v {
                Ok(v) if v.len() == count && v.iter().all(|x| x.is_finite()) => Ok(v),
                _ => Err(bad(&format!("expected {count} comma-separated numbers after '{kind}:'"))),
            }
        };
        match kind.trim() {
            "uniform" => {
                let v = numbers(rest, 2)?;
                Self::uniform(v[0].to_radians(), v[1].to_radians())
            }
            "normal" => {
                let v = numbers(rest, 2)?;
                Self::normal(v[0].to_radians(), v[1].to_radians())
            }
            "mix" => {
                let mut parts = Vec::new();
                for term in rest.split('+') {
                    let (w, inner) = term
                        .split_once('*')
                        .ok_or_else(|| bad("mixture terms are WEIGHT*SPEC joined by '+'"))?;
                    let w: f64 =
                        w.trim().parse().map_err(|_| bad(&format!("bad mixture weight {w:?}")))?;
                    parts.push((w, Self::parse(inner.trim())?));
                }
                Self::mixture(parts)
            }
            "histogram" => read_histogram(Path::new(rest.trim())),
            "observed" => {
                let (file, bucket) = match rest.rsplit_once(',') {
                    Some((f, b)) if b.trim().parse::<f64>().is_ok() => {
                        (f, b.trim().parse::<f64>().unwrap_or(5.0))
                    }
                    _ => (rest, 5.0),
                };
                let angles = read_observations(Path::new(file.trim()))?;
                Self::from_observations(&angles, bucket.to_radians(), 0.5)
            }
            other => Err(bad(&format!(
                "unknown kind {other:?}; use uniform, normal, mix, histogram or observed"
            ))),
        }
    }
}

fn data_lines(path: &Path) -> Result<Vec<(usize, String)>, InvalidDistribution> {
    let text = std::fs::read_to_string(path).map_err(|e| InvalidDistribution::File {
        file: path.display().to_string(),
        line: 0,
        reason: e.to_string(),
    })?;
    Ok(text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.split('#').next().unwrap_or("").trim().to_string()))
        .filter(|(_, l)| !l.is_empty())
        .collect())
}

/// What is wrong with a histogram's buckets: one bucket on its own, or a bucket that overlaps
/// an earlier one (indices from 0, in the order given).
enum BucketFault {
    Invalid { index: usize, problem: BucketProblem },
    Overlap { index: usize, other: usize },
}

/// `[LO°, HI°]` of a bucket given in radians.
fn degrees(range: [f64; 2]) -> String {
    format!("[{}°, {}°]", Num(range[0].to_degrees()), Num(range[1].to_degrees()))
}

/// Checks each bucket on its own (finite, LO below HI, inside [0, π], weight finite and not
/// negative), then that no two overlap; returns the total weight. One cause per fault.
fn check_buckets(buckets: &[(f64, f64, f64)]) -> Result<f64, BucketFault> {
    let fault = |index, problem| BucketFault::Invalid { index, problem };
    for (k, &(lo, hi, w)) in buckets.iter().enumerate() {
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(fault(k, BucketProblem::NotFinite));
        }
        if lo >= hi {
            return Err(fault(k, BucketProblem::Empty));
        }
        if lo < -ANGLE_SLACK || hi > PI + BUCKET_END_SLACK {
            return Err(fault(k, BucketProblem::OutsideRange));
        }
        if !w.is_finite() {
            return Err(fault(k, BucketProblem::WeightNotFinite(w)));
        }
        if w < 0.0 {
            return Err(fault(k, BucketProblem::NegativeWeight(w)));
        }
    }
    let mut order: Vec<usize> = (0..buckets.len()).collect();
    order.sort_by(|&a, &b| buckets[a].0.total_cmp(&buckets[b].0).then(a.cmp(&b)));
    for pair in order.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if buckets[b].0 < buckets[a].1 - ANGLE_SLACK {
            let (first, later) = (a.min(b), a.max(b));
            return Err(BucketFault::Overlap { index: later, other: first });
        }
    }
    Ok(buckets.iter().map(|b| b.2).sum())
}

fn file_error(path: &Path, line: usize, reason: String) -> InvalidDistribution {
    InvalidDistribution::File { file: path.display().to_string(), line, reason }
}

fn read_histogram(path: &Path) -> Result<AngleDistribution, InvalidDistribution> {
    let mut buckets = Vec::new();
    let mut lines = Vec::new();
    for (no, line) in data_lines(path)? {
        let fields: Vec<&str> =
            line.split(|c: char| c == ',' || c.is_whitespace()).filter(|f| !f.is_empty()).collect();
        let values: Result<Vec<f64>, _> = fields.iter().map(|f| f.parse::<f64>()).collect();
        match values {
            Ok(v) if v.len() == 3 && v.iter().all(|x| x.is_finite()) => {
                buckets.push((v[0].to_radians(), v[1].to_radians(), v[2]));
                lines.push(no);
            }
            _ => {
                return Err(file_error(
                    path,
                    no,
                    format!("expected 'LO HI WEIGHT' in degrees, got {line:?}"),
                ));
            }
        }
    }
    if buckets.is_empty() {
        return Err(file_error(
            path,
            0,
            "the histogram has no buckets ('LO HI WEIGHT' lines)".into(),
        ));
    }
    match check_buckets(&buckets) {
        Err(f) => {
            let b = |k: usize| {
                format!("[{}, {}]", Num(buckets[k].0.to_degrees()), Num(buckets[k].1.to_degrees()))
            };
            let (index, reason) = match f {
                BucketFault::Overlap { index, other } => (
                    index,
                    format!("bucket {} overlaps {} of line {}", b(index), b(other), lines[other]),
                ),
                BucketFault::Invalid { index, problem } => {
                    (index, format!("bucket {}: {problem}", b(index)))
                }
            };
            return Err(file_error(path, lines[index], reason));
        }
        Ok(total) if !(total.is_finite() && total > 0.0) => {
            return Err(file_error(
                path,
                0,
                format!("the weights sum to {}; give at least one positive weight", Num(total)),
            ));
        }
        Ok(_) => {}
    }
    AngleDistribution::histogram(buckets).map_err(|e| file_error(path, 0, e.to_string()))
}

fn read_observations(path: &Path) -> Result<Vec<f64>, InvalidDistribution> {
    let mut angles = Vec::new();
    for (no, line) in data_lines(path)? {
        match line.parse::<f64>() {
            Ok(a) if (0.0..=180.0).contains(&a) => angles.push(a.to_radians()),
            _ => {
                return Err(file_error(
                    path,
                    no,
                    format!("expected one angle in [0, 180] degrees, got {line:?}"),
                ));
            }
        }
    }
    Ok(angles)
}

/// The standard normal CDF Φ(z).
fn normal_cdf(z: f64) -> f64 {
    0.5 * libm::erfc(-z / std::f64::consts::SQRT_2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;

    #[test]
    fn parses_the_design_specs() {
        for s in ["uniform:0,180", "normal:60,5", "mix:0.5*normal:30,3+0.5*normal:90,3"] {
            let d = AngleDistribution::parse(s).unwrap();
            assert!((d.cdf(PI) - 1.0).abs() < 1e-12, "{s}");
            assert!(d.cdf(0.0) == 0.0);
        }
        let u = AngleDistribution::parse("uniform:0,180").unwrap();
        assert!((u.cdf(PI / 2.0) - 0.5).abs() < 1e-15);
        let n = AngleDistribution::parse("normal:60,5").unwrap();
        assert!((n.cdf(60f64.to_radians()) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn rejects_bad_specs() {
        for s in [
            "",
            "normal:60",
            "normal:60,0",
            "uniform:90,10",
            "beta:1,2",
            "mix:normal:1,2",
            "normal:1000,1",
            "uniform:0,200",
            "histogram:/nonexistent/file",
        ] {
            assert!(AngleDistribution::parse(s).is_err(), "{s}");
        }
    }

    #[test]
    fn bucketed_keeps_mass() {
        let n = AngleDistribution::parse("normal:60,5").unwrap();
        let h = n.bucketed(5f64.to_radians()).unwrap();
        for deg in [50.0, 55.0, 60.0, 65.0, 70.0] {
            let t = f64::to_radians(deg);
            assert!((h.cdf(t) - n.cdf(t)).abs() < 1e-12);
        }
    }

    #[test]
    fn quantile_inverts_cdf() {
        let m = AngleDistribution::parse("mix:0.3*uniform:0,90+0.7*normal:120,10").unwrap();
        for u in [0.01, 0.2, 0.5, 0.9, 0.999] {
            assert!((m.cdf(m.quantile(u)) - u).abs() < 1e-9);
        }
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let x = m.sample(&mut rng);
        assert!((0.0..=PI).contains(&x));
    }

    #[test]
    fn observations_make_a_smoothed_histogram() {
        let d = AngleDistribution::from_observations(&[PI / 2.0; 10], PI / 36.0, 0.5).unwrap();
        let p = d.mass(PI / 2.0 - 1e-9, PI / 2.0 + PI / 36.0);
        assert!(p > 0.3, "the observed bucket dominates: {p}");
        assert!(d.mass(0.0, 0.01) > 0.0, "no angle is impossible");
    }
}
