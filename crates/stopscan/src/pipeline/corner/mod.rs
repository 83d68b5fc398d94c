//! The corner commands' results as typed reports: the circle strategy, its thresholds and
//! collapse, the global optimum, exact worst-case ratios, MDP policies, simulations against a
//! true distribution, and the demo. Functions given a folder also draw their pictures there.
//!
//! The CLI prints and writes these reports through `serde_json::Value`, whose object keys are
//! sorted (as the command's JSON has always been); serialising a report directly gives the
//! same keys in field order.

mod circle;
mod demo;
mod policy;
mod ratio;

pub use circle::{
    CircleReport, MAX_THRESHOLDS, OptimalReport, ThresholdsReport, circle, collapse, optimal,
    thresholds,
};
pub use demo::{DemoCircle, DemoCorner, DemoReport, DemoStrategy, demo, demo_json};
pub use policy::{
    GeneralSolverCheck, PolicyOptions, PolicyReport, SimulatedStrategy, Simulation,
    SimulationReport, policy,
};
pub use ratio::{RatioReport, StopsError, ratio, stop_list};

use std::path::Path;

use crate::experiment::ExperimentError;
use crate::io::atomic::{self, WriteError};
use crate::kernel::Num;
use crate::pipeline::InvalidParameter;
use crate::protocol::corner::{InvalidCornerSetup, InvalidDistribution};
use crate::render::{LineChart, write_chart, write_policy_image};
use crate::strategy::corner::InvalidStopList;
use crate::strategy::corner::circle::CircleError;
use crate::strategy::corner::mdp::CornerMdpError;
use crate::strategy::corner::registry::BuildError;

/// Why a corner command failed.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum CornerError {
    /// A parameter outside its range (`distance`, `scans`, `count`, `ratio`, `delta`).
    #[error(transparent)]
    Parameter(#[from] InvalidParameter),
    /// `stops` was asked for without stop angles.
    #[error("the stops strategy needs stop angles (degrees, increasing)")]
    StopsNeeded,
    /// The stop angles given are not a valid list.
    #[error(transparent)]
    Stops(#[from] StopsError),
    /// The setup is invalid.
    #[error(transparent)]
    Setup(#[from] InvalidCornerSetup),
    /// A belief or truth does not parse or is invalid.
    #[error(transparent)]
    Distribution(#[from] InvalidDistribution),
    /// A strategy could not be built.
    #[error(transparent)]
    Build(#[from] BuildError),
    /// A stop list is invalid.
    #[error(transparent)]
    StopList(#[from] InvalidStopList),
    /// The MDP could not be solved.
    #[error(transparent)]
    Mdp(#[from] CornerMdpError),
    /// A simulation or the demo failed.
    #[error(transparent)]
    Experiment(#[from] ExperimentError),
    /// A picture or file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

pub(super) fn distance_error(e: CircleError) -> CornerError {
    match e {
        CircleError::Distance(d) => {
            InvalidParameter::new("distance", "be a finite positive number", &Num(d)).into()
        }
        CircleError::TooFar(d) => InvalidParameter::new(
            "distance",
            format!(
                "be at most {} (units of v·τ; beyond it c(d) = 2 below double precision)",
                Num(crate::strategy::corner::circle::MAX_DISTANCE)
            ),
            &Num(d),
        )
        .into(),
    }
}

pub(super) fn positive(name: &'static str, v: f64) -> Result<f64, CornerError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(InvalidParameter::new(name, "be a finite positive number", &Num(v)).into())
    }
}

/// Writes a chart as `NAME.svg` and `NAME.png` in `dir`; returns the paths as text.
///
/// # Errors
/// [`WriteError`] naming the files.
pub fn save_chart(dir: &Path, name: &str, chart: &LineChart) -> Result<Vec<String>, WriteError> {
    Ok(atomic::write_stem(&dir.join(name), |stem| write_chart(chart, stem))?
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

/// Writes a policy image as `NAME.svg` and `NAME.png` in `dir`; returns the paths as text.
///
/// # Errors
/// [`WriteError`] naming the files.
pub fn save_policy_image(
    dir: &Path,
    name: &str,
    title: &str,
    image: &[Vec<crate::strategy::corner::mdp::StateAction>],
) -> Result<Vec<String>, WriteError> {
    Ok(atomic::write_stem(&dir.join(name), |stem| write_policy_image(image, title, stem))?
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}
