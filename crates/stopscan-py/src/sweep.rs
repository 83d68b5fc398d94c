//! Sweeps from Python, one run at a time, so that a scheduler (Ray, or any other) can spread
//! them: the driver lists and loads the files (`sweep_files`, `sweep_load`), each task runs
//! one file with one strategy (`sweep_run`), and the rows join into the CSV that `stopscan
//! explore --env DIR` writes, byte for byte (`sweep_csv_header` and each row's line).

use std::path::PathBuf;

use pyo3::prelude::*;
use stopscan::experiment::polygon::{SweepInput, SweepRow};
use stopscan::pipeline::explore::ExploreOptions;
use stopscan::pipeline::sweep;

use crate::{explore_options, value_error};

/// The sweep's options from the keyword arguments (a point robot's: sweeps refuse a robot).
#[allow(clippy::too_many_arguments)] // Python's keywords
fn options(
    strategy: &str,
    scan_time: f64,
    move_time: f64,
    speed: f64,
    range: Option<f64>,
    simplify: Option<f64>,
    bounds_seconds: Option<f64>,
    bounds_steps: Option<u64>,
) -> PyResult<ExploreOptions> {
    let mut o = explore_options(strategy, scan_time, move_time, speed, range, None, 0, None, None)?;
    o.simplify = simplify;
    if let Some(b) = bounds_seconds {
        o.limits.bounds_seconds = b;
    }
    o.limits.bounds_steps = bounds_steps;
    Ok(o)
}

/// A row as (its JSON text, its CSV line).
fn row_texts(row: &SweepRow) -> PyResult<(String, String)> {
    let json = serde_json::to_string(row).map_err(value_error)?;
    let mut line = Vec::new();
    {
        let mut w = csv::WriterBuilder::new().has_headers(false).from_writer(&mut line);
        w.serialize(row.csv_row()).map_err(value_error)?;
        w.flush().map_err(value_error)?;
    }
    Ok((json, String::from_utf8(line).map_err(value_error)?))
}

/// The environment files of a folder a sweep reads (one level, by extension), sorted.
#[pyfunction]
#[allow(clippy::needless_pass_by_value)] // Python hands over owned arguments
pub(crate) fn sweep_files(dir: PathBuf) -> PyResult<Vec<PathBuf>> {
    sweep::environment_files(&dir).map_err(value_error)
}

/// Checks a sweep's options: returns its strategies (every registered one for `all`) and a
/// warning for the caller to show, if any.
#[pyfunction]
#[allow(clippy::too_many_arguments)] // Python's keywords
#[pyo3(signature = (strategy="all", scan_time=1.0, move_time=0.0, speed=1.0, range=None, simplify=None, bounds_seconds=None, bounds_steps=None))]
pub(crate) fn sweep_check(
    strategy: &str,
    scan_time: f64,
    move_time: f64,
    speed: f64,
    range: Option<f64>,
    simplify: Option<f64>,
    bounds_seconds: Option<f64>,
    bounds_steps: Option<u64>,
) -> PyResult<(Vec<String>, Option<String>)> {
    let o = options(
        strategy,
        scan_time,
        move_time,
        speed,
        range,
        simplify,
        bounds_seconds,
        bounds_steps,
    )?;
    let strategies = sweep::sweep_strategies(&o).map_err(value_error)?;
    let warning = (range.is_none() && strategies.contains(&"range_limited"))
        .then(|| sweep::SweepWarning::UnlimitedRange.to_string());
    Ok((strategies.into_iter().map(String::from).collect(), warning))
}

/// One file loaded for a sweep: (its name, the input as JSON text for the runs, or `None`
/// and why it does not load).
#[pyfunction]
#[pyo3(signature = (path, simplify=None))]
#[allow(clippy::needless_pass_by_value)] // Python hands over owned arguments
pub(crate) fn sweep_load(
    py: Python<'_>,
    path: PathBuf,
    simplify: Option<f64>,
) -> PyResult<(String, Option<String>, Option<String>)> {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("?").to_string();
    match py.detach(|| sweep::load_input(&path, simplify)) {
        Ok(input) => Ok((name, Some(serde_json::to_string(&input).map_err(value_error)?), None)),
        Err(error) => Ok((name, None, Some(error))),
    }
}

/// One run of a sweep: `strategy` on the input `sweep_load` gave, as (the row's JSON text,
/// its CSV line). The GIL is released during the run.
#[pyfunction]
#[pyo3(signature = (input, strategy, scan_time=1.0, move_time=0.0, speed=1.0, range=None, bounds_seconds=None, bounds_steps=None))]
#[allow(clippy::too_many_arguments)] // Python's keywords
pub(crate) fn sweep_run(
    py: Python<'_>,
    input: &str,
    strategy: &str,
    scan_time: f64,
    move_time: f64,
    speed: f64,
    range: Option<f64>,
    bounds_seconds: Option<f64>,
    bounds_steps: Option<u64>,
) -> PyResult<(String, String)> {
    // Checked as a sweep of every strategy: `range_limited` in a sweep runs without a range.
    let o = options("all", scan_time, move_time, speed, range, None, bounds_seconds, bounds_steps)?;
    sweep::sweep_strategies(&o).map_err(value_error)?;
    sweep::strategies(strategy).map_err(value_error)?;
    let input: SweepInput = serde_json::from_str(input)
        .map_err(|e| value_error(format!("not a sweep input (from sweep_load): {e}")))?;
    let row = py.detach(|| sweep::sweep_run(&input, strategy, &o));
    row_texts(&row)
}

/// The row of a run that could not start (a file that does not load), as `sweep_run`'s.
#[pyfunction]
pub(crate) fn sweep_failed(name: &str, strategy: &str, error: &str) -> PyResult<(String, String)> {
    row_texts(&SweepRow::failed(name, strategy, error))
}

/// The sweep CSV's header line.
#[pyfunction]
pub(crate) fn sweep_csv_header() -> PyResult<String> {
    let mut text = Vec::new();
    sweep::write_csv(&[SweepRow::failed("", "", "")], &mut text).map_err(value_error)?;
    let text = String::from_utf8(text).map_err(value_error)?;
    Ok(text.split_inclusive('\n').next().unwrap_or_default().to_string())
}
