//! Looking around a corner: UNIREC, EXPREC (corner paper, Table I), the circle strategy
//! (circle paper, §3.3) and the MDP policies POLICY1 / POLICY2 (corner paper, §III).
//!
//! Every deterministic corner strategy is a [`StopList`]: the robot only learns "seen" (and
//! stops) or "not yet", so until it sees the edge its trajectory is fixed in advance. The
//! MDP policies therefore also become stop lists once solved, which is what makes their
//! expected time exactly computable under any true distribution.
//!
//! - `stops`: [`StopList`], [`unirec`], [`exprec`] and [`StopListStrategy`], which drives a list;
//! - [`circle`]: the circle strategy, its ratio c(d) and its thresholds;
//! - [`mdp`]: MDP1 and MDP2, solved exactly;
//! - [`registry`]: the strategies selectable by name.

pub mod circle;
pub mod mdp;
pub mod registry;
mod stops;

pub use stops::{
    ExprecReading, InvalidStopList, MAX_STOPS, StopList, StopListStrategy, exprec, unirec,
    unirec_stops,
};

use crate::protocol::Action;
use crate::protocol::corner::{CornerObservation, Stop};

/// What the driver tells a corner strategy before asking for its next action.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum CornerFeedback {
    /// The run begins; the robot stands at the start and has scanned there.
    Start,
    /// The robot reached the stop it asked for.
    Arrived,
    /// The scan it asked for is done.
    Scanned(CornerObservation),
}

/// An online corner strategy: a state machine fed only with [`CornerFeedback`].
pub trait CornerStrategy {
    /// The registry name (`unirec`, `exprec`, `circle`, `policy1`, `policy2`, `stops`).
    fn name(&self) -> &str;
    /// The next action.
    fn act(&mut self, feedback: CornerFeedback) -> Action<Stop>;
}
