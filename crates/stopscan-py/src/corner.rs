//! The corner search from Python: the circle strategy, competitive ratios of stop lists and
//! the MDP policies, as `stopscan corner circle|ratio|policy --format json` report them.

use pyo3::prelude::*;
use stopscan::pipeline::corner::{self as pipeline, CornerError, PolicyOptions};
use stopscan::pipeline::limits;
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::CornerSetup;
use stopscan::strategy::corner::registry::BuildOptions;

use crate::{soft_limit, value_error};

/// `value` read as one of a library enum's names (snake case; `-` may stand for `_`), or an
/// error naming the parameter and what it accepts.
fn choice<T: serde::de::DeserializeOwned>(what: &str, value: &str, known: &str) -> PyResult<T> {
    serde_json::from_value(serde_json::Value::String(value.replace('-', "_")))
        .map_err(|_| value_error(format!("{what}: expected {known}, got {value:?}")))
}

/// A corner error in the words of the Python API.
fn corner_error(e: CornerError) -> PyErr {
    match e {
        CornerError::StopsNeeded => {
            value_error("strategy \"stops\" needs stops_deg (degrees, increasing)")
        }
        e => value_error(e),
    }
}

fn json<T: serde::Serialize>(report: &T) -> PyResult<String> {
    serde_json::to_string(report).map_err(value_error)
}

/// The circle strategy around a corner at distance `d` (the circle paper): its report as
/// JSON text (the stops, the ratio, the bound), as `stopscan corner circle --format json`.
#[pyfunction]
pub(crate) fn corner_circle(py: Python<'_>, d: f64) -> PyResult<String> {
    json(&py.detach(|| pipeline::circle(d, None)).map_err(corner_error)?)
}

/// The worst-case and asymptotic competitive ratios of a stop list (`unirec`, `exprec`,
/// `circle`, or `stops` with `stops_deg`) at δ = τ·v/D, as `stopscan corner ratio --format
/// json`. UNIREC needs π/(2δ) stops: above the CLI's soft limit it is refused unless
/// `allow_large`.
#[pyfunction]
#[pyo3(signature = (strategy, delta, stops_deg=None, *, last_step="capped", exprec="table_i", route="arc", allow_large=false))]
#[allow(clippy::too_many_arguments, clippy::needless_pass_by_value)] // Python's keywords
pub(crate) fn corner_ratio(
    py: Python<'_>,
    strategy: &str,
    delta: f64,
    stops_deg: Option<Vec<f64>>,
    last_step: &str,
    exprec: &str,
    route: &str,
    allow_large: bool,
) -> PyResult<String> {
    if !(delta.is_finite() && delta > 0.0) {
        return Err(value_error(format!("delta must be a finite positive number, got {delta}")));
    }
    if strategy == "unirec" {
        let stops = stopscan::strategy::corner::unirec_stops(delta);
        soft_limit(
            allow_large,
            stops,
            limits::STOPS,
            &format!("delta {delta} gives {stops} UNIREC stops"),
        )?;
    }
    let options = BuildOptions {
        last_step: choice("last_step", last_step, "capped or nominal")?,
        exprec: choice("exprec", exprec, "table_i or appendix")?,
        route: choice("route", route, "arc or chord")?,
        ..BuildOptions::default()
    };
    let stops = stops_deg.unwrap_or_default();
    let r =
        py.detach(|| pipeline::ratio(strategy, delta, &stops, &options)).map_err(corner_error)?;
    json(&r)
}

/// The MDP policy of the corner paper for a belief over the corner's angle (degrees:
/// `uniform:0,180`, `normal:60,5`, `mix:0.5*normal:30,3+0.5*normal:90,3`,
/// `histogram:FILE`, `observed:FILE[,BUCKET_DEG]`), as `stopscan corner policy --format
/// json`: MDP2 (`memory="last"`) or MDP1 (`"none"`), solved by backward induction (or
/// `solver="general"`, policy iteration, compared).
#[pyfunction]
#[pyo3(signature = (belief, *, truth=None, distance=10.0, scan_time=2.0, move_time=0.0, speed=0.5, memory="last", reading="conditional", step_deg=5.0, solver="backward"))]
#[allow(clippy::too_many_arguments)] // Python's keywords
pub(crate) fn corner_policy(
    py: Python<'_>,
    belief: &str,
    truth: Option<&str>,
    distance: f64,
    scan_time: f64,
    move_time: f64,
    speed: f64,
    memory: &str,
    reading: &str,
    step_deg: f64,
    solver: &str,
) -> PyResult<String> {
    let cost = CostModel::new(scan_time, move_time, speed).map_err(value_error)?;
    let general = match solver {
        "backward" => false,
        "general" => true,
        s => return Err(value_error(format!("solver: expected backward or general, got {s:?}"))),
    };
    let options = PolicyOptions {
        setup: CornerSetup::new(distance, cost).map_err(value_error)?,
        belief,
        truth,
        memory: choice("memory", memory, "none or last")?,
        reading: choice("reading", reading, "conditional or literal")?,
        step_deg,
        general,
    };
    json(&py.detach(|| pipeline::policy(&options, None)).map_err(corner_error)?)
}
