//! The corner strategies selectable by name: one list for lookup, building and help text.

use serde::{Deserialize, Serialize};

use super::mdp::{CornerMdp, CornerMdpError, Memory, Reading};
use super::{ExprecReading, InvalidStopList, StopList, circle, exprec, unirec};
use crate::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use crate::strategy::{Entry, Registry};

/// How a corner registry entry builds its stop list, for a setup and a belief (the belief is
/// used by the MDP policies only).
pub type CornerBuild = fn(
    setup: &CornerSetup,
    belief: &AngleDistribution,
    options: &BuildOptions,
) -> Result<StopList, BuildError>;

/// Every corner strategy, in display order: names, help text and construction.
pub const REGISTRY: Registry<CornerBuild> = Registry::new(&[
    Entry {
        name: "unirec",
        summary: "scans at δ, 2δ, 3δ, … with δ = τv/D (corner paper, Table I; ratio → π)",
        build: |s, _, o| Ok(unirec(s.delta(), o.route, o.last_step)?),
    },
    Entry {
        name: "exprec",
        summary: "scans at exponentially spaced stops (corner paper, Table I; ratio → 2.2214)",
        build: |s, _, o| Ok(exprec(s.delta(), o.exprec, o.route, o.last_step)?),
    },
    Entry {
        name: "circle",
        summary: "the circle paper's strategy at d = D/(vτ): chords with equalised ratio c(d) → 2",
        build: |s, _, _| Ok(circle::solve(s.normalised_distance())?.stop_list()),
    },
    Entry {
        name: "policy1",
        summary: "MDP1's optimal policy for the belief (memoryless states s_i, s'_i)",
        build: |s, b, o| mdp(Memory::None, s, b, o),
    },
    Entry {
        name: "policy2",
        summary: "MDP2's optimal policy for the belief (states s_ij, remembers the last scan)",
        build: |s, b, o| mdp(Memory::Last, s, b, o),
    },
]);

/// The names in [`REGISTRY`].
pub fn names() -> impl Iterator<Item = &'static str> {
    REGISTRY.names()
}

/// One line per strategy, for `--help`.
pub fn help() -> String {
    REGISTRY.help()
}

/// The optimal policy of MDP1 or MDP2 for `belief`, as a stop list.
fn mdp(
    memory: Memory,
    setup: &CornerSetup,
    belief: &AngleDistribution,
    o: &BuildOptions,
) -> Result<StopList, BuildError> {
    CornerMdp {
        setup: *setup,
        step: o.mdp_step,
        memory,
        reading: o.reading,
        belief: belief.clone(),
    }
    .solve()
    .map(|p| p.stop_list)
    .map_err(BuildError::from)
}

/// How the registry builds strategies: the readings of the corner paper and the MDP grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BuildOptions {
    /// Last-step charge for UNIREC and EXPREC.
    pub last_step: LastStep,
    /// Which EXPREC.
    pub exprec: ExprecReading,
    /// Route of UNIREC and EXPREC (the circle strategy always drives chords).
    pub route: Route,
    /// MDP stop spacing, radians.
    pub mdp_step: f64,
    /// MDP transition reading.
    pub reading: Reading,
}

impl Default for BuildOptions {
    fn default() -> Self {
        Self {
            last_step: LastStep::Capped,
            exprec: ExprecReading::TableI,
            route: Route::Arc,
            mdp_step: 5f64.to_radians(),
            reading: Reading::Conditional,
        }
    }
}

/// Why a strategy could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum BuildError {
    /// The name is not in the registry; the message lists the names.
    #[error("unknown strategy {0:?}; use one of: {1}")]
    Unknown(String, String),
    /// UNIREC or EXPREC rejected δ or the last-step reading.
    #[error(transparent)]
    StopList(#[from] InvalidStopList),
    /// An MDP policy could not be built or solved.
    #[error(transparent)]
    Mdp(#[from] CornerMdpError),
    /// The circle strategy rejected the setup's distance.
    #[error(transparent)]
    Circle(#[from] circle::CircleError),
}

/// Builds the stop list of the strategy called `name` for a setup and a belief (the
/// belief is used by the MDP policies only).
///
/// # Errors
/// [`BuildError`] for an unknown name or invalid parameters.
pub fn build(
    name: &str,
    setup: &CornerSetup,
    belief: &AngleDistribution,
    o: &BuildOptions,
) -> Result<StopList, BuildError> {
    let entry = REGISTRY.get(name).map_err(|e| BuildError::Unknown(e.name, e.known))?;
    (entry.build)(setup, belief, o)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::CostModel;

    #[test]
    fn every_registered_name_builds() {
        let s = CornerSetup::new(10.0, CostModel::new(2.0, 0.0, 0.5).unwrap()).unwrap();
        let b = AngleDistribution::parse("uniform:0,180").unwrap();
        for name in names() {
            let list = build(name, &s, &b, &BuildOptions::default()).unwrap();
            assert_eq!(list.angles().last(), Some(&crate::protocol::corner::CORNER), "{name}");
        }
        assert!(matches!(
            build("warp", &s, &b, &BuildOptions::default()),
            Err(BuildError::Unknown(..))
        ));
        assert!(help().lines().count() == REGISTRY.len());
    }
}
