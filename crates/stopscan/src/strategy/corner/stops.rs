//! Stop lists and the two competitive strategies of the corner paper.

use serde::{Deserialize, Serialize};

use super::{CornerFeedback, CornerStrategy};
use crate::protocol::Action;
use crate::protocol::corner::{CORNER, CornerObservation, CornerSetup, LastStep, Route, Stop};

/// Tolerance under which a nominal angle counts as the corner itself.
const AT_CORNER: f64 = 1e-12;

/// The stops at which a corner strategy scans, in order, ending at the corner.
///
/// `angles` are strictly increasing in (0, π/2] and the last is π/2 (the corner, where every
/// edge is seen). `charged_last` is the nominal angle charged for the last step under
/// [`LastStep::Nominal`]; it equals π/2 otherwise.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StopList {
    angles: Vec<f64>,
    charged_last: f64,
    route: Route,
}

/// Why a stop list was rejected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum InvalidStopList {
    /// Stop angles must be finite, positive and strictly increasing.
    #[error(
        "stop {} of the list ({}°) must be finite, positive and above the previous stop",
        .index + 1,
        crate::kernel::Num(.angle.to_degrees())
    )]
    NotIncreasing {
        /// Position in the list.
        index: usize,
        /// The offending angle.
        angle: f64,
    },
    /// The nominal last-step reading is only defined along the arc.
    #[error("the nominal last-step charge is defined for the arc route only")]
    NominalNeedsArc,
    /// δ must be finite and positive.
    #[error("delta must be finite and positive, got {}", crate::kernel::Num(*.0))]
    Delta(f64),
    /// δ is so small that UNIREC would need more than [`MAX_STOPS`] stops (16 bytes each,
    /// and the exact evaluations are linear in them). Use a larger δ.
    #[error(
        "δ = {} needs {} UNIREC stops; at most {max} are allowed (δ ≥ {})",
        crate::kernel::Num(*.delta),
        crate::kernel::Num(*.stops),
        crate::kernel::Num(CORNER / *.max as f64)
    )]
    TooMany {
        /// δ.
        delta: f64,
        /// The stops it needs.
        stops: f64,
        /// The most allowed.
        max: usize,
    },
}

/// The most stops a stop list built from δ may have (UNIREC at δ ≈ 1.6e-8): 1.6 GB with its
/// costs. Callers may set a lower limit (the CLI's default is 10⁷).
pub const MAX_STOPS: usize = 100_000_000;

/// The number of UNIREC stops at step δ: ⌈(π/2)/δ⌉ (1 when δ > 1), computed without building
/// them.
pub fn unirec_stops(delta: f64) -> f64 {
    if delta > 1.0 { 1.0 } else { (CORNER / delta - AT_CORNER).ceil().max(1.0) }
}

impl StopList {
    /// Builds a stop list from nominal angles (radians). The first angle at or beyond π/2
    /// becomes the corner and ends the list; if none reaches π/2 the corner is appended.
    ///
    /// # Errors
    /// [`InvalidStopList`] if the angles are not positive and strictly increasing, or if
    /// [`LastStep::Nominal`] is combined with [`Route::Chord`].
    pub fn from_nominal(
        nominal: &[f64],
        route: Route,
        last_step: LastStep,
    ) -> Result<Self, InvalidStopList> {
        if last_step == LastStep::Nominal && route == Route::Chord {
            return Err(InvalidStopList::NominalNeedsArc);
        }
        let mut angles = Vec::with_capacity(nominal.len() + 1);
        let mut charged_last = CORNER;
        for (index, &angle) in nominal.iter().enumerate() {
            let prev = angles.last().copied().unwrap_or(0.0);
            if !(angle.is_finite() && angle > prev) {
                return Err(InvalidStopList::NotIncreasing { index, angle });
            }
            if angle >= CORNER - AT_CORNER {
                if last_step == LastStep::Nominal {
                    charged_last = angle.max(CORNER);
                }
                break;
            }
            angles.push(angle);
        }
        angles.push(CORNER);
        Ok(Self { angles, charged_last, route })
    }

    /// The stop angles (radians), ending with π/2.
    pub fn angles(&self) -> &[f64] {
        &self.angles
    }

    /// The route between stops.
    pub fn route(&self) -> Route {
        self.route
    }

    /// The angle charged for the last step (π/2 unless the nominal reading applies).
    pub fn charged_last(&self) -> f64 {
        self.charged_last
    }

    /// Number of stops, the corner included.
    pub fn len(&self) -> usize {
        self.angles.len()
    }

    /// A stop list is never empty (it always ends at the corner).
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The time at which the edge is first seen if that happens at stop `k`, for every `k`:
    /// `(k+1)·τ + (k+1)·t_M + distance_k / v`.
    ///
    /// # Complexity
    /// O(len) time and space.
    pub fn costs(&self, setup: &CornerSetup) -> Vec<f64> {
        let mut out = Vec::with_capacity(self.angles.len());
        let mut metres = 0.0;
        let mut prev = 0.0;
        let last = self.angles.len() - 1;
        for (k, &a) in self.angles.iter().enumerate() {
            let to = if k == last { self.charged_last } else { a };
            metres += setup.travel(prev, to, self.route);
            prev = a;
            let n = (k + 1) as f64;
            out.push(n * (setup.cost.scan_time + setup.cost.move_time) + metres / setup.cost.speed);
        }
        out
    }

    /// The stop at which an edge at angle θ is first seen.
    pub fn seen_at(&self, theta: f64) -> usize {
        self.angles.partition_point(|&a| a < theta).min(self.angles.len() - 1)
    }

    /// A strategy object that drives this list.
    pub fn into_strategy(self, name: impl Into<String>) -> StopListStrategy {
        StopListStrategy { name: name.into(), list: self, next: 0, finished: false }
    }
}

/// UNIREC (corner paper, Table I): scan at δ, 2δ, 3δ, … until the edge is seen; with δ > 1
/// the robot goes straight to the corner.
///
/// # Errors
/// [`InvalidStopList::Delta`] for a non-positive δ, [`InvalidStopList::TooMany`] when δ
/// needs more than [`MAX_STOPS`] stops, or an invalid route/last-step pair.
pub fn unirec(delta: f64, route: Route, last_step: LastStep) -> Result<StopList, InvalidStopList> {
    if delta.is_finite() && delta > 0.0 && unirec_stops(delta) > MAX_STOPS as f64 {
        return Err(InvalidStopList::TooMany { delta, stops: unirec_stops(delta), max: MAX_STOPS });
    }
    let nominal = geometric_stops(delta, |i| i as f64 * delta)?;
    StopList::from_nominal(&nominal, route, last_step)
}

/// Which EXPREC the text means: Table I and §II-B disagree with the appendix.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ExprecReading {
    /// Table I ("Visit iδ; i ← 2i"): stops at δ, 2δ, 4δ, 8δ, …
    #[default]
    TableI,
    /// The appendix ("during the i-th step the robot traverses 2^(i-1)δ, the total angle so
    /// far is (2^i − 1)δ"): stops at δ, 3δ, 7δ, 15δ, …
    Appendix,
}

/// EXPREC (corner paper, Table I): exponentially growing steps.
///
/// # Errors
/// [`InvalidStopList::Delta`] for a non-positive δ, or an invalid route/last-step pair.
pub fn exprec(
    delta: f64,
    reading: ExprecReading,
    route: Route,
    last_step: LastStep,
) -> Result<StopList, InvalidStopList> {
    let nominal = geometric_stops(delta, |i| match reading {
        ExprecReading::TableI => 2f64.powi(i as i32 - 1) * delta,
        ExprecReading::Appendix => (2f64.powi(i as i32) - 1.0) * delta,
    })?;
    StopList::from_nominal(&nominal, route, last_step)
}

/// Nominal stop angles `f(1), f(2), …` up to and including the first one at or past the
/// corner; `[π/2]` when δ > 1 (Table I: "If δ > 1 go to the corner").
fn geometric_stops(delta: f64, f: impl Fn(usize) -> f64) -> Result<Vec<f64>, InvalidStopList> {
    if !(delta.is_finite() && delta > 0.0) {
        return Err(InvalidStopList::Delta(delta));
    }
    if delta > 1.0 {
        return Ok(vec![CORNER]);
    }
    let mut out = Vec::new();
    for i in 1.. {
        let a = f(i);
        out.push(a);
        if a >= CORNER - AT_CORNER {
            break;
        }
    }
    Ok(out)
}

/// A [`StopList`] driven as an online strategy: move to the next stop, scan, repeat until seen.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StopListStrategy {
    name: String,
    list: StopList,
    next: usize,
    finished: bool,
}

impl StopListStrategy {
    /// The list it drives.
    pub fn list(&self) -> &StopList {
        &self.list
    }
}

impl CornerStrategy for StopListStrategy {
    fn name(&self) -> &str {
        &self.name
    }

    fn act(&mut self, feedback: CornerFeedback) -> Action<Stop> {
        match feedback {
            CornerFeedback::Arrived => Action::Scan,
            CornerFeedback::Scanned(CornerObservation::Seen { .. }) => {
                self.finished = true;
                Action::Done
            }
            CornerFeedback::Start | CornerFeedback::Scanned(CornerObservation::Hidden) => {
                if self.finished || self.next >= self.list.len() {
                    self.finished = true;
                    return Action::Done;
                }
                let k = self.next;
                self.next += 1;
                let last = k + 1 == self.list.len();
                let angle = if last { self.list.charged_last } else { self.list.angles[k] };
                Action::MoveTo { to: Stop { angle, route: self.list.route } }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unirec_stops() {
        let s = unirec(0.5, Route::Arc, LastStep::Capped).unwrap();
        assert_eq!(s.angles(), &[0.5, 1.0, 1.5, CORNER]);
        assert_eq!(s.charged_last(), CORNER);
        let n = unirec(0.5, Route::Arc, LastStep::Nominal).unwrap();
        assert_eq!(n.charged_last(), 2.0);
        assert_eq!(unirec(1.5, Route::Arc, LastStep::Capped).unwrap().angles(), &[CORNER]);
    }

    #[test]
    fn exprec_readings() {
        let t = exprec(0.1, ExprecReading::TableI, Route::Arc, LastStep::Capped).unwrap();
        let want = [0.1, 0.2, 0.4, 0.8, CORNER];
        assert!(t.angles().iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-12));
        let a = exprec(0.1, ExprecReading::Appendix, Route::Arc, LastStep::Capped).unwrap();
        let want = [0.1, 0.3, 0.7, 1.5, CORNER];
        assert!(a.angles().iter().zip(want).all(|(x, y)| (x - y).abs() < 1e-12));
    }

    #[test]
    fn costs_match_the_paper_formula() {
        // UNIREC with δ = τv/D: seeing at stop k costs k·τ + k·δ·D/v = 2kτ.
        let setup = CornerSetup::new(10.0, crate::protocol::CostModel::new(2.0, 0.0, 0.5).unwrap())
            .unwrap();
        let s = unirec(setup.delta(), Route::Arc, LastStep::Nominal).unwrap();
        let c = s.costs(&setup);
        for (k, v) in c.iter().enumerate() {
            assert!((v - 4.0 * (k + 1) as f64).abs() < 1e-9, "{k}: {v}");
        }
    }

    #[test]
    fn rejects_bad_lists() {
        assert!(StopList::from_nominal(&[0.2, 0.1], Route::Arc, LastStep::Capped).is_err());
        assert!(StopList::from_nominal(&[f64::NAN], Route::Arc, LastStep::Capped).is_err());
        assert!(StopList::from_nominal(&[0.1], Route::Chord, LastStep::Nominal).is_err());
        assert!(unirec(0.0, Route::Arc, LastStep::Capped).is_err());
    }

    #[test]
    fn strategy_state_survives_a_serde_round_trip_mid_run() {
        let list = unirec(0.3, Route::Arc, LastStep::Capped).unwrap();
        let mut a = list.into_strategy("unirec");
        let _ = a.act(CornerFeedback::Start);
        let _ = a.act(CornerFeedback::Arrived);
        let saved = serde_json::to_string(&a).unwrap();
        let mut b: StopListStrategy = serde_json::from_str(&saved).unwrap();
        for _ in 0..12 {
            let fb = CornerFeedback::Scanned(CornerObservation::Hidden);
            let (x, y) = (a.act(fb), b.act(fb));
            assert_eq!(x, y);
            assert_eq!(a.act(CornerFeedback::Arrived), b.act(CornerFeedback::Arrived));
        }
        assert_eq!(a, b);
    }

    #[test]
    fn seen_at_is_first_stop_at_or_above() {
        let s = StopList::from_nominal(&[0.5, 1.0], Route::Arc, LastStep::Capped).unwrap();
        assert_eq!(s.seen_at(0.1), 0);
        assert_eq!(s.seen_at(0.5), 0);
        assert_eq!(s.seen_at(0.50001), 1);
        assert_eq!(s.seen_at(1.2), 2);
        assert_eq!(s.seen_at(3.0), 2);
    }
}
