//! Region-of-interest missions from Python: a team explores a region (Algorithm 1 of the ROI
//! paper), as `stopscan roi` flies it, and the run record comes back as the CLI writes it.

use std::path::PathBuf;

use pyo3::prelude::*;
use stopscan::io::atomic;
use stopscan::pipeline::limits;
use stopscan::pipeline::mission::{MissionRun, MissionSpec, RegionSource};
use stopscan::protocol::CostModel;
use stopscan::sim::Recording;
use stopscan::sim::grid::{MAX_FRAMES, Search};
use stopscan::world::grid::camera::CameraModel;
use stopscan::world::grid::{Drift, GridSensor};

use crate::{soft_limit, value_error};

/// Flies a mission and returns its run record as JSON text, exactly as `stopscan roi --out`
/// writes it. The region is a file (`region`: a text grid, a PNG/PGM mask or a polygon), a
/// text grid given in place (`grid`, with its `name`), or a random region of `random`
/// cells grown from `seed`. Cells are (row, column). The SVG replay, the browser replay
/// and the MCAP recording are written where `svg`, `report` and `mcap` say. The GIL is
/// released while the team flies.
#[pyfunction]
#[pyo3(signature = (region=None, *, grid=None, name="roi", random=None, robots=1, cell_size=1.0, cell_px=1, invert_mask=false, start=None, robot_speed=1.0, roi_speed=0.0, roi_heading_deg=0.0, battery_s=None, scan_time=0.0, move_time=0.0, camera=false, frames=5, search_box=None, launch=None, paths=true, seed=0, svg=None, report=None, mcap=None, allow_large=false))]
#[allow(
    clippy::too_many_arguments,
    clippy::fn_params_excessive_bools,
    clippy::needless_pass_by_value
)] // Python's keywords
pub(crate) fn roi_json(
    py: Python<'_>,
    region: Option<PathBuf>,
    grid: Option<String>,
    name: &str,
    random: Option<usize>,
    robots: usize,
    cell_size: f64,
    cell_px: usize,
    invert_mask: bool,
    start: Option<(i32, i32)>,
    robot_speed: f64,
    roi_speed: f64,
    roi_heading_deg: f64,
    battery_s: Option<f64>,
    scan_time: f64,
    move_time: f64,
    camera: bool,
    frames: usize,
    search_box: Option<(i32, i32, i32, i32)>,
    launch: Option<(i32, i32)>,
    paths: bool,
    seed: u64,
    svg: Option<PathBuf>,
    report: Option<PathBuf>,
    mcap: Option<PathBuf>,
    allow_large: bool,
) -> PyResult<String> {
    let start = start.map(|(r, c)| [r, c]);
    let source = match (region, grid, random) {
        (Some(path), None, None) => RegionSource::File {
            path: std::path::absolute(&path).unwrap_or(path),
            cell_size,
            cell_px: cell_px.max(1),
            start,
            invert: invert_mask,
        },
        (None, Some(text), None) => {
            RegionSource::Grid { name: name.to_string(), text, cell_size, start }
        }
        (None, None, Some(cells)) => {
            if start.is_some() {
                return Err(value_error(
                    "start applies to a given region; a random region starts where it was grown",
                ));
            }
            soft_limit(
                allow_large,
                cells as f64,
                limits::CELLS,
                &format!("random {cells} (cells)"),
            )?;
            RegionSource::Random { cells, seed, cell_size }
        }
        _ => {
            return Err(value_error(
                "give exactly one of region (a file), grid (an array) or random (cells)",
            ));
        }
    };
    soft_limit(allow_large, robots as f64, limits::ROBOTS, &format!("robots {robots}"))?;
    if robots == 0 {
        return Err(value_error("robots must be at least 1"));
    }
    if camera && !(1..=MAX_FRAMES).contains(&frames) {
        return Err(value_error(format!(
            "frames must be between 1 and {MAX_FRAMES}, got {frames}"
        )));
    }
    if !(roi_speed.is_finite() && roi_speed >= 0.0) {
        return Err(value_error(format!(
            "roi_speed must be a non-negative number of m/s, got {roi_speed}"
        )));
    }
    if !roi_heading_deg.is_finite() {
        return Err(value_error(format!("roi_heading_deg must be finite, got {roi_heading_deg}")));
    }
    let search = match (search_box, launch) {
        (Some((r0, c0, r1, c1)), Some((lr, lc))) => {
            if !(r0 <= r1 && c0 <= c1) {
                return Err(value_error(
                    "search_box must be (row0, col0, row1, col1) with row0 ≤ row1 and col0 ≤ col1",
                ));
            }
            let search = Search { launch: [lr, lc], min: [r0, c0], max: [r1, c1] };
            let cells = search.cells();
            soft_limit(allow_large, cells, limits::CELLS, &format!("search_box of {cells} cells"))?;
            Some(search)
        }
        (None, None) => None,
        _ => return Err(value_error("a lawn-mowing search needs both search_box and launch")),
    };
    let cost = CostModel::new(scan_time, move_time, robot_speed).map_err(value_error)?;
    let sensor = if camera {
        GridSensor::Camera(CameraModel { frames, ..CameraModel::default() })
    } else {
        GridSensor::Ideal
    };
    let spec = MissionSpec {
        source,
        drift: Drift { speed: roi_speed, heading_deg: roi_heading_deg },
        sensor,
        robots,
        cost,
        battery_s,
        search,
        recording: if paths { Recording::PATHS } else { Recording::NONE },
        seed,
        // Not written: the record comes back as text, the pictures go where they are asked.
        out: PathBuf::from("roi-run.json"),
        svg: PathBuf::from("roi-run.svg"),
        report: None,
        mcap: None,
        trace: None,
    };
    let camera = camera.then_some(Camera { frames, allow_large });
    py.detach(move || fly(spec, camera, [svg, report, mcap])).map_err(value_error)
}

/// What the camera's soft limit needs: frames per scan, and whether to lift it.
#[derive(Clone, Copy)]
struct Camera {
    frames: usize,
    allow_large: bool,
}

/// Loads the region, flies the mission, writes the pictures asked for (SVG, browser replay,
/// MCAP) and returns the run record's text.
fn fly(
    spec: MissionSpec,
    camera: Option<Camera>,
    outputs: [Option<PathBuf>; 3],
) -> Result<String, String> {
    let roi = spec.source.load().map_err(|e| e.to_string())?;
    if let Some(Camera { frames, allow_large }) = camera {
        let total = limits::camera_frames(roi.len(), spec.search.as_ref(), frames).round();
        if !allow_large && total > limits::FRAMES as f64 {
            return Err(format!(
                "a camera with {frames} frames per scan on {} region cells renders about {total} frames: the limit is {} (about 0.6 ms per frame); pass allow_large=True to go beyond it",
                roi.len(),
                limits::FRAMES
            ));
        }
    }
    let mut run = MissionRun::start(spec, roi).map_err(|e| e.to_string())?;
    let record = run.fly_record(None, &mut |_| {}).map_err(|e| e.to_string())?;
    let [svg, report, mcap] = outputs;
    if let Some(p) = svg {
        atomic::write_bytes(&p, run.svg(&record).as_bytes()).map_err(|e| e.to_string())?;
    }
    if let Some(p) = report {
        atomic::write_bytes(&p, run.report(&record).as_bytes()).map_err(|e| e.to_string())?;
    }
    if let Some(p) = mcap {
        let bytes = run.mcap(&record).map_err(|e| e.to_string())?;
        atomic::write_bytes(&p, &bytes).map_err(|e| e.to_string())?;
    }
    // Robots that gave up are in the record's `failures` (the Python side raises with the
    // record attached, as the CLI writes the record and then fails).
    let mut text = serde_json::to_string_pretty(&record).map_err(|e| e.to_string())?;
    text.push('\n');
    Ok(text)
}

/// Reads a region of interest as `stopscan roi --grid` does (a text grid, a PNG/PGM mask
/// with `cell_px` pixels per cell, or a polygon file through its outer grid approximation):
/// its name, its cells as an (n, 2) array of (row, column), its start cell and its cell size.
#[pyfunction]
#[pyo3(signature = (path, *, cell_size=1.0, cell_px=1, invert_mask=false, start=None))]
#[allow(clippy::needless_pass_by_value, clippy::type_complexity)] // Python's arguments and tuple
pub(crate) fn load_region(
    py: Python<'_>,
    path: PathBuf,
    cell_size: f64,
    cell_px: usize,
    invert_mask: bool,
    start: Option<(i32, i32)>,
) -> PyResult<(String, Bound<'_, numpy::PyArray2<i64>>, (i32, i32), f64)> {
    use numpy::IntoPyArray;
    let opts = stopscan::io::grid::GridOptions {
        cell_size,
        cell_px: cell_px.max(1),
        start: start.map(|(r, c)| [r, c]),
        invert: invert_mask,
    };
    let roi = py.detach(|| stopscan::io::grid::read_roi(&path, &opts)).map_err(value_error)?;
    let flat: Vec<i64> =
        roi.cells().iter().flat_map(|c| [i64::from(c[0]), i64::from(c[1])]).collect();
    let cells = numpy::ndarray::Array2::from_shape_vec((roi.len(), 2), flat)
        .map_err(value_error)?
        .into_pyarray(py);
    let s = roi.start();
    Ok((roi.name().to_string(), cells, (s[0], s[1]), roi.cell_size()))
}
