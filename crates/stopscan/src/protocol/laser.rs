//! What a real robot's range sensor says: one 2D laser scan, as in ROS's
//! `sensor_msgs/LaserScan`, and the pose it was taken at.
//!
//! The ranges follow ROS REP 117: a finite value in `[range_min, range_max]` is a return; `NaN`
//! is an erroneous measurement (a dropout); `+inf` means no object within `range_max`; `-inf`
//! means an object closer than `range_min`. JSON has no `NaN` or infinities, so in JSON a range
//! is a number, `null` (`NaN`), `"inf"` or `"-inf"`.

use serde::{Deserialize, Serialize};

use crate::kernel::Point;

/// A pose in the plane: position, metres, and heading, radians counter-clockwise from +x.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Pose {
    /// Position x.
    pub x: f64,
    /// Position y.
    pub y: f64,
    /// Heading.
    pub theta: f64,
}

impl Pose {
    /// A pose at `at` with heading `theta`.
    pub fn new(at: Point, theta: f64) -> Self {
        Self { x: at[0], y: at[1], theta }
    }

    /// The position.
    pub fn at(&self) -> Point {
        [self.x, self.y]
    }

    /// `p`, given in this pose's frame, in the frame the pose is given in.
    pub fn apply(&self, p: Point) -> Point {
        self.placing().apply(p)
    }

    /// The direction `v` (given in this pose's frame) in the frame the pose is given in:
    /// turned by the heading, not moved.
    pub fn turn(&self, v: Point) -> Point {
        self.placing().turn(v)
    }

    /// [`apply`](Self::apply) and [`turn`](Self::turn) for many points, with the heading's
    /// sine and cosine computed once (the same results to the bit).
    pub fn placing(&self) -> Placing {
        let (sin, cos) = self.theta.sin_cos();
        Placing { x: self.x, y: self.y, sin, cos }
    }

    /// This pose followed by `d` (given in this pose's frame): `self ∘ d`.
    #[must_use]
    pub fn compose(&self, d: &Pose) -> Pose {
        let at = self.apply(d.at());
        Pose { x: at[0], y: at[1], theta: wrap(self.theta + d.theta) }
    }

    /// The inverse transform.
    #[must_use]
    pub fn inverse(&self) -> Pose {
        let (s, c) = self.theta.sin_cos();
        Pose { x: -(c * self.x + s * self.y), y: s * self.x - c * self.y, theta: wrap(-self.theta) }
    }

    /// Whether every field is finite.
    pub fn is_finite(&self) -> bool {
        self.x.is_finite() && self.y.is_finite() && self.theta.is_finite()
    }
}

/// An angle wrapped into `(-π, π]`.
pub fn wrap(a: f64) -> f64 {
    let t = std::f64::consts::TAU;
    let w = a - t * (a / t).round();
    if w <= -std::f64::consts::PI { w + t } else { w }
}

/// One 2D range scan, in the sensor's frame (beam `i` points at
/// `angle_min + i · angle_increment`), with ROS `sensor_msgs/LaserScan`'s field names.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LaserScan {
    /// The first beam's angle, radians.
    pub angle_min: f64,
    /// The angle between neighbouring beams, radians (negative for a clockwise scanner).
    pub angle_increment: f64,
    /// The nearest valid return, metres.
    pub range_min: f64,
    /// The farthest valid return, metres.
    pub range_max: f64,
    /// One range per beam, metres (REP 117; see the module's notes for JSON).
    #[serde(with = "rep117")]
    pub ranges: Vec<f64>,
}

/// Why a laser scan was refused. Every variant names the field.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidScan {
    /// A field that must be a finite number is not, or is out of its bounds.
    #[error("field `{field}`: {problem}")]
    Field {
        /// The field's name.
        field: &'static str,
        /// What is wrong with it.
        problem: String,
    },
}

/// The most beams a scan may have (a 0.01° scanner has 36,000).
pub const MAX_BEAMS: usize = 100_000;

impl LaserScan {
    /// Checks the header fields and the beam count.
    ///
    /// # Errors
    /// [`InvalidScan::Field`] naming the field: a non-finite angle, a zero increment, a
    /// negative or non-finite `range_min`, a `range_max` not above it, fewer than 3 or more
    /// than [`MAX_BEAMS`] beams, or beams that sweep more than one turn.
    pub fn validate(&self) -> Result<(), InvalidScan> {
        let bad = |field, problem: String| Err(InvalidScan::Field { field, problem });
        if !self.angle_min.is_finite() {
            return bad("angle_min", format!("must be finite, got {}", self.angle_min));
        }
        if !self.angle_increment.is_finite() || self.angle_increment == 0.0 {
            return bad(
                "angle_increment",
                format!("must be finite and not zero, got {}", self.angle_increment),
            );
        }
        if !self.range_min.is_finite() || self.range_min < 0.0 {
            return bad("range_min", format!("must be finite and >= 0, got {}", self.range_min));
        }
        if !self.range_max.is_finite() || self.range_max <= self.range_min {
            return bad(
                "range_max",
                format!(
                    "must be finite and above range_min ({}), got {}",
                    self.range_min, self.range_max
                ),
            );
        }
        let n = self.ranges.len();
        if !(3..=MAX_BEAMS).contains(&n) {
            return bad("ranges", format!("must hold 3 to {MAX_BEAMS} beams, got {n}"));
        }
        let sweep = self.angle_increment.abs() * (n - 1) as f64;
        if sweep >= std::f64::consts::TAU {
            return bad(
                "angle_increment",
                format!("{n} beams at this increment sweep {sweep:.4} rad, more than one turn"),
            );
        }
        Ok(())
    }

    /// Beam `i`'s angle in the sensor's frame.
    pub fn angle(&self, i: usize) -> f64 {
        self.angle_min + i as f64 * self.angle_increment
    }

    /// Whether the beams close a full turn (the last beam's neighbour is the first).
    pub fn is_full_turn(&self) -> bool {
        let n = self.ranges.len() as f64;
        self.angle_increment.abs() * (n + 0.5) >= std::f64::consts::TAU
    }
}

/// Serde for REP 117 ranges in JSON: numbers, `null` for `NaN`, `"inf"` and `"-inf"`.
mod rep117 {
    use serde::de::{self, SeqAccess, Visitor};
    use serde::ser::SerializeSeq;
    use serde::{Deserializer, Serializer};

    pub(super) fn serialize<S: Serializer>(v: &[f64], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(v.len()))?;
        for r in v {
            if r.is_nan() {
                seq.serialize_element(&Option::<f64>::None)?;
            } else if r.is_infinite() {
                seq.serialize_element(if *r > 0.0 { "inf" } else { "-inf" })?;
            } else {
                seq.serialize_element(r)?;
            }
        }
        seq.end()
    }

    #[derive(serde::Deserialize)]
    #[serde(untagged)]
    enum Range {
        Num(f64),
        Text(String),
        Null(()),
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        struct Ranges;
        impl<'de> Visitor<'de> for Ranges {
            type Value = Vec<f64>;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an array of ranges: numbers, null (NaN), \"inf\" or \"-inf\"")
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut a: A) -> Result<Vec<f64>, A::Error> {
                let mut out = Vec::with_capacity(a.size_hint().unwrap_or(0).min(super::MAX_BEAMS));
                while let Some(r) = a.next_element::<Range>()? {
                    if out.len() == super::MAX_BEAMS {
                        return Err(de::Error::custom(format!(
                            "more than {} beams",
                            super::MAX_BEAMS
                        )));
                    }
                    out.push(match r {
                        Range::Num(x) => x,
                        Range::Null(()) => f64::NAN,
                        Range::Text(t) if t == "inf" || t == "+inf" => f64::INFINITY,
                        Range::Text(t) if t == "-inf" => f64::NEG_INFINITY,
                        Range::Text(t) => {
                            return Err(de::Error::custom(format!(
                                "range {} is {t:?}: use a number, null, \"inf\" or \"-inf\"",
                                out.len()
                            )));
                        }
                    });
                }
                Ok(out)
            }
        }
        d.deserialize_seq(Ranges)
    }
}

/// A [`Pose`] ready to place many points: its position, and its heading's sine and cosine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placing {
    x: f64,
    y: f64,
    sin: f64,
    cos: f64,
}

impl Placing {
    /// `p`, given in the pose's frame, in the frame the pose is given in.
    pub fn apply(&self, p: Point) -> Point {
        let (s, c) = (self.sin, self.cos);
        [self.x + c * p[0] - s * p[1], self.y + s * p[0] + c * p[1]]
    }

    /// The direction `v`, given in the pose's frame, turned by the heading.
    pub fn turn(&self, v: Point) -> Point {
        let (s, c) = (self.sin, self.cos);
        [c * v[0] - s * v[1], s * v[0] + c * v[1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scan(ranges: Vec<f64>) -> LaserScan {
        LaserScan {
            angle_min: -std::f64::consts::PI,
            angle_increment: std::f64::consts::TAU / ranges.len() as f64,
            range_min: 0.1,
            range_max: 20.0,
            ranges,
        }
    }

    #[test]
    fn rep117_values_round_trip_through_json() {
        let s = scan(vec![1.5, f64::NAN, f64::INFINITY, f64::NEG_INFINITY]);
        let text = serde_json::to_string(&s).unwrap();
        assert!(text.contains(r#""ranges":[1.5,null,"inf","-inf"]"#), "{text}");
        let back: LaserScan = serde_json::from_str(&text).unwrap();
        assert_eq!(back.ranges[0], 1.5);
        assert!(back.ranges[1].is_nan());
        assert_eq!(back.ranges[2], f64::INFINITY);
        assert_eq!(back.ranges[3], f64::NEG_INFINITY);
        let e =
            serde_json::from_str::<LaserScan>(&text.replace("\"-inf\"", "\"far\"")).unwrap_err();
        assert!(e.to_string().contains("range 3 is \"far\""), "{e}");
    }

    #[test]
    fn validation_names_the_field() {
        let field = |s: &LaserScan| match s.validate() {
            Err(InvalidScan::Field { field, .. }) => field,
            Ok(()) => "ok",
        };
        let good = scan(vec![1.0; 360]);
        assert_eq!(field(&good), "ok");
        assert!(good.is_full_turn());
        assert_eq!(field(&LaserScan { angle_increment: 0.0, ..good.clone() }), "angle_increment");
        assert_eq!(field(&LaserScan { angle_min: f64::NAN, ..good.clone() }), "angle_min");
        assert_eq!(field(&LaserScan { range_min: -1.0, ..good.clone() }), "range_min");
        assert_eq!(field(&LaserScan { range_max: 0.05, ..good.clone() }), "range_max");
        assert_eq!(field(&LaserScan { ranges: vec![1.0; 2], ..good.clone() }), "ranges");
        assert_eq!(field(&LaserScan { angle_increment: 0.1, ..good.clone() }), "angle_increment");
        let half = LaserScan { angle_increment: 0.5 * good.angle_increment, ..good };
        assert!(!half.is_full_turn());
    }

    #[test]
    fn poses_compose_and_invert() {
        let a = Pose { x: 1.0, y: 2.0, theta: 0.7 };
        let b = Pose { x: -0.5, y: 0.25, theta: -2.0 };
        let p = [0.3, -1.1];
        let ab = a.compose(&b);
        let q = ab.apply(p);
        let r = a.apply(b.apply(p));
        assert!((q[0] - r[0]).abs() < 1e-12 && (q[1] - r[1]).abs() < 1e-12);
        let id = a.compose(&a.inverse());
        assert!(id.x.abs() < 1e-12 && id.y.abs() < 1e-12 && id.theta.abs() < 1e-12);
        assert!((wrap(3.0 * std::f64::consts::PI) - std::f64::consts::PI).abs() < 1e-12);
    }
}
