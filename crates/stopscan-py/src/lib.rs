//! The Python bindings (`import stopscan`): the native part, `stopscan._stopscan`. The
//! Python package (`python/stopscan/__init__.py`) wraps it: it turns shapely geometries,
//! `__geo_interface__` objects and sequences into what these functions take, and run
//! records from JSON text into dicts.
//!
//! Everything runs the library's own pipelines ([`stopscan::pipeline`]), so a run record made
//! here is the CLI's, byte for byte. Heavy work releases the GIL.

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use stopscan::algorithm::visibility::{
    BoundaryPiece, Visibility, VisibilityError, VisibilityRegion, expansion,
};
use stopscan::io::Environment;
use stopscan::io::ros_map::RosMapOptions;
use stopscan::kernel::Point;
use stopscan::offline::polygon::ReferenceLimits;
use stopscan::pipeline::explore::ExploreOptions;
use stopscan::protocol::polygon::{Footprint, PolygonObservation};
use stopscan::protocol::{Action, CostModel, Feedback, MoveFailure};
use stopscan::strategy::polygon::PolygonFeedback;

mod corner;
mod roi;
mod sweep;

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// Refuses `demand` above the soft limit `max` (the CLI's, [`stopscan::pipeline::limits`])
/// unless `allow_large`: `what` says what was asked.
fn soft_limit(allow_large: bool, demand: f64, max: u64, what: &str) -> PyResult<()> {
    if allow_large || demand <= max as f64 {
        return Ok(());
    }
    Err(value_error(format!("{what}: the limit is {max}; pass allow_large=True to go beyond it")))
}

/// `n × 2` float64 array of points.
fn points_array<'py>(py: Python<'py>, points: &[Point]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = points.iter().flat_map(|p| [p[0], p[1]]).collect();
    Array2::from_shape_vec((points.len(), 2), flat).expect("n × 2 elements").into_pyarray(py)
}

fn points_of(a: &PyReadonlyArray2<'_, f64>) -> PyResult<Vec<Point>> {
    let v = a.as_array();
    if v.ncols() != 2 {
        return Err(value_error(format!(
            "expected an array of shape (n, 2), got (n, {})",
            v.ncols()
        )));
    }
    Ok(v.rows().into_iter().map(|r| [r[0], r[1]]).collect())
}

/// An environment: a polygon with holes (validated), its frame and the start its file gives.
#[pyclass(frozen, module = "stopscan", name = "Environment")]
struct PyEnvironment {
    env: Environment,
    name: String,
    /// The visibility structure (a triangulation), built on the first query and kept: a
    /// query then costs what the CLI's does.
    vis: std::sync::OnceLock<Result<Visibility, String>>,
}

impl PyEnvironment {
    fn new(env: Environment, name: String) -> Self {
        Self { env, name, vis: std::sync::OnceLock::new() }
    }

    fn visibility(&self) -> Result<&Visibility, String> {
        self.vis
            .get_or_init(|| Visibility::new(self.env.domain.clone()).map_err(|e| e.to_string()))
            .as_ref()
            .map_err(Clone::clone)
    }
}

#[pymethods]
impl PyEnvironment {
    /// The name runs are recorded under (the file's stem).
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// The outer boundary, input coordinates, shape (n, 2).
    #[getter]
    fn outer<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let f = self.env.frame;
        let ring: Vec<Point> = self.env.domain.outer().iter().map(|&p| f.to_input(p)).collect();
        points_array(py, &ring)
    }

    /// The holes, input coordinates, each of shape (n, 2).
    #[getter]
    fn holes<'py>(&self, py: Python<'py>) -> Vec<Bound<'py, PyArray2<f64>>> {
        let f = self.env.frame;
        self.env
            .domain
            .holes()
            .iter()
            .map(|h| {
                let ring: Vec<Point> = h.iter().map(|&p| f.to_input(p)).collect();
                points_array(py, &ring)
            })
            .collect()
    }

    /// The free area, square metres.
    #[getter]
    fn area(&self) -> f64 {
        self.env.domain.area()
    }

    /// The reflex vertices' count, r.
    #[getter]
    fn reflex_vertices(&self) -> usize {
        self.env.domain.reflex_vertices().len()
    }

    /// The start the file gives (input coordinates), if any.
    #[getter]
    fn start(&self) -> Option<(f64, f64)> {
        self.env.default_start().map(|p| {
            let q = self.env.frame.to_input(p);
            (q[0], q[1])
        })
    }

    /// The cell size of the occupancy map it was traced from, if it was.
    #[getter]
    fn cell_size(&self) -> Option<f64> {
        self.env.cell_size
    }

    fn __repr__(&self) -> String {
        format!(
            "Environment({:?}: {} vertices, {} holes, {:.3} m²)",
            self.name,
            self.env.domain.vertex_count(),
            self.env.domain.holes().len(),
            self.env.domain.area()
        )
    }
}

/// Reads an environment file of any format the CLI reads (GeoJSON, WKT, `.pol`, the
/// benchmark format, a ROS map's YAML), as `stopscan explore --env` does. A ROS map keeps the
/// free region holding `start` and is simplified within `simplify` metres.
#[pyfunction]
#[pyo3(signature = (path, start=None, simplify=None))]
#[allow(clippy::needless_pass_by_value)] // Python hands over owned arguments
fn load(
    py: Python<'_>,
    path: std::path::PathBuf,
    start: Option<(f64, f64)>,
    simplify: Option<f64>,
) -> PyResult<PyEnvironment> {
    let options =
        RosMapOptions { start: start.map(|s| [s.0, s.1]), simplify, ..RosMapOptions::default() };
    let env =
        py.detach(|| stopscan::io::read_environment_with(&path, &options)).map_err(value_error)?;
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("environment").to_string();
    Ok(PyEnvironment::new(env, name))
}

/// An environment from GeoJSON text (a Polygon, a Feature or a FeatureCollection, as the CLI
/// reads files), recorded under `name`.
#[pyfunction]
#[pyo3(signature = (text, name="polygon"))]
fn from_geojson(text: &str, name: &str) -> PyResult<PyEnvironment> {
    let env = stopscan::io::text_formats::parse_geojson(text, name).map_err(value_error)?;
    Ok(PyEnvironment::new(env, name.to_string()))
}

/// A region seen from one point: its viewpoint, its polygon and its windows (the edges that
/// cross free space), in the environment's input coordinates.
#[pyclass(frozen, module = "stopscan", name = "Region")]
struct PyRegion {
    region: VisibilityRegion,
    /// The area, computed in the environment's local frame where that is not the input's
    /// (far from the origin, input coordinates lose digits); `None`: computed when asked.
    area: Option<f64>,
}

#[pymethods]
impl PyRegion {
    /// The viewpoint.
    #[getter]
    fn viewpoint(&self) -> (f64, f64) {
        (self.region.viewpoint[0], self.region.viewpoint[1])
    }

    /// The polygon's vertices, counter-clockwise, shape (n, 2).
    #[getter]
    fn vertices<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        points_array(py, &self.region.polygon)
    }

    /// The area, square metres.
    #[getter]
    fn area(&self) -> f64 {
        self.area.unwrap_or_else(|| self.region.area())
    }

    /// The windows: shape (k, 2, 2), each from its first end to its second.
    #[getter]
    fn windows<'py>(&self, py: Python<'py>) -> Bound<'py, numpy::PyArray3<f64>> {
        let w: Vec<f64> = self
            .region
            .boundary
            .iter()
            .filter(|b| matches!(b, BoundaryPiece::Window { .. }))
            .flat_map(|b| {
                let (a, c) = b.ends();
                [a[0], a[1], c[0], c[1]]
            })
            .collect();
        let k = w.len() / 4;
        numpy::ndarray::Array3::from_shape_vec((k, 2, 2), w).expect("k × 2 × 2").into_pyarray(py)
    }

    /// GeoJSON's Polygon, for shapely (`shapely.geometry.shape(region)`).
    #[getter]
    fn __geo_interface__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("type", "Polygon")?;
        let mut ring: Vec<(f64, f64)> = self.region.polygon.iter().map(|p| (p[0], p[1])).collect();
        if let Some(&first) = ring.first() {
            ring.push(first);
        }
        d.set_item("coordinates", PyList::new(py, [ring])?)?;
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Region(viewpoint=({}, {}), {} vertices, area {:.6})",
            self.region.viewpoint[0],
            self.region.viewpoint[1],
            self.region.polygon.len(),
            self.area()
        )
    }
}

/// A region handed to Python, with its area where it was taken ([`PyRegion::area`]).
type Seen = (VisibilityRegion, Option<f64>);

/// The regions seen from `queries` (input coordinates), one after the other with one scratch.
fn regions_from(
    vis: &Visibility,
    frame: stopscan::geometry::Frame,
    range: Option<f64>,
    queries: &[Point],
) -> Result<Vec<Seen>, String> {
    let mut out = Vec::with_capacity(queries.len());
    let mut scratch = expansion::Scratch::default();
    let mut region = VisibilityRegion::default();
    for &q in queries {
        let at = |e: VisibilityError| format!("point ({}, {}): {e}", q[0], q[1]);
        let local = frame.to_local(q);
        match range {
            None => vis.query_into(local, &mut scratch, &mut region).map_err(at)?,
            Some(r) => {
                let rr = vis.query_range(local, r).map_err(at)?;
                let polygon = rr.to_polygon(r * 1e-4);
                region =
                    VisibilityRegion { viewpoint: rr.viewpoint, polygon, boundary: Vec::new() };
            }
        }
        // In the input frame the region is handed over as it is, and its area waits until it
        // is asked for; elsewhere it is mapped and its area taken here.
        if frame.origin == [0.0, 0.0] {
            // The region is moved out and the next query writes into fresh buffers of the
            // same capacity: one allocation each, no copy, no regrowth.
            let next = VisibilityRegion {
                viewpoint: region.viewpoint,
                polygon: Vec::with_capacity(region.polygon.capacity()),
                boundary: Vec::with_capacity(region.boundary.capacity()),
            };
            out.push((std::mem::replace(&mut region, next), None));
        } else {
            out.push((region.mapped(|p| frame.to_input(p)), Some(region.area())));
        }
    }
    Ok(out)
}

/// Points per parallel task: small enough to share 1,000 queries among the cores, large
/// enough that a task's scratch is reused.
const CHUNK: usize = 64;

/// The regions seen from each of `points` (shape (n, 2), input coordinates), with a sensor of
/// `range` metres if given (arcs as chords within range·1e-4, as the CLI). The GIL is
/// released while they are computed, on `threads` threads (default: every core; 1: this
/// thread only), in chunks of 64 points; the regions come back in the points' order, and an
/// error names the first point (in that order) that has one.
#[pyfunction]
#[pyo3(signature = (env, points, range=None, threads=None))]
#[allow(clippy::needless_pass_by_value)] // Python hands over owned arguments
fn visibility(
    py: Python<'_>,
    env: &PyEnvironment,
    points: PyReadonlyArray2<'_, f64>,
    range: Option<f64>,
    threads: Option<usize>,
) -> PyResult<Vec<PyRegion>> {
    use rayon::prelude::*;
    let queries = points_of(&points)?;
    if let Some(r) = range
        && !(r.is_finite() && r > 0.0)
    {
        return Err(value_error(format!("range must be a finite positive distance, got {r}")));
    }
    if threads == Some(0) {
        return Err(value_error("threads must be at least 1"));
    }
    let frame = env.env.frame;
    let regions = py.detach(move || -> Result<Vec<Seen>, String> {
        let vis = env.visibility()?;
        let threads = threads.unwrap_or_else(rayon::current_num_threads);
        if threads == 1 || queries.len() <= CHUNK {
            return regions_from(vis, frame, range, &queries);
        }
        let parts = || -> Vec<Result<Vec<Seen>, String>> {
            queries.par_chunks(CHUNK).map(|c| regions_from(vis, frame, range, c)).collect()
        };
        let parts = if threads == rayon::current_num_threads() {
            parts()
        } else {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map_err(|e| e.to_string())?
                .install(parts)
        };
        let mut out = Vec::with_capacity(queries.len());
        for p in parts {
            out.extend(p?);
        }
        Ok(out)
    });
    Ok(regions
        .map_err(value_error)?
        .into_iter()
        .map(|(region, area)| PyRegion { region, area })
        .collect())
}

/// The pipeline's options from the keyword arguments.
#[allow(clippy::too_many_arguments)]
pub(crate) fn explore_options(
    strategy: &str,
    scan_time: f64,
    move_time: f64,
    speed: f64,
    range: Option<f64>,
    robot_radius: Option<f64>,
    seed: u64,
    optimum_seconds: Option<f64>,
    optimum_nodes: Option<u64>,
) -> PyResult<ExploreOptions> {
    let footprint = match robot_radius {
        Some(r) => Footprint::disc(r).map_err(|e| value_error(format!("robot_radius: {e}")))?,
        None => Footprint::Point,
    };
    let defaults = ReferenceLimits::default();
    Ok(ExploreOptions {
        strategy: strategy.to_string(),
        cost: CostModel::new(scan_time, move_time, speed).map_err(value_error)?,
        range,
        footprint,
        limits: ReferenceLimits {
            optimum_seconds: optimum_seconds.unwrap_or(defaults.optimum_seconds),
            optimum_nodes: optimum_nodes.or(defaults.optimum_nodes),
            ..defaults
        },
        seed,
        ..ExploreOptions::default()
    })
}

/// Explores `env` from `start` (input coordinates; by default the file's start) and returns
/// the run record as JSON text, exactly as `stopscan explore --out` writes it. The GIL is
/// released during the run.
#[pyfunction]
#[pyo3(signature = (env, start=None, strategy="depth_first", scan_time=1.0, move_time=0.0, speed=1.0, range=None, robot_radius=None, seed=0, optimum_seconds=None, optimum_nodes=None))]
#[allow(clippy::too_many_arguments)]
fn explore_json(
    py: Python<'_>,
    env: &PyEnvironment,
    start: Option<(f64, f64)>,
    strategy: &str,
    scan_time: f64,
    move_time: f64,
    speed: f64,
    range: Option<f64>,
    robot_radius: Option<f64>,
    seed: u64,
    optimum_seconds: Option<f64>,
    optimum_nodes: Option<u64>,
) -> PyResult<String> {
    let options = explore_options(
        strategy,
        scan_time,
        move_time,
        speed,
        range,
        robot_radius,
        seed,
        optimum_seconds,
        optimum_nodes,
    )?;
    let start = start.map(|s| env.env.frame.to_local([s.0, s.1]));
    let result = py.detach(|| {
        stopscan::pipeline::explore::explore(&env.name, &env.env, start, &options, &mut |_| {})
    });
    let o = result.map_err(value_error)?;
    let mut text = serde_json::to_string_pretty(&o.record).map_err(value_error)?;
    text.push('\n');
    if let Some(e) = &o.failure {
        return Err(value_error(format!("the run ended early: {e}")));
    }
    Ok(text)
}

/// An online exploration strategy, driven step by step: tell it what happened
/// (`observe`), ask it what to do (`next_action`). Coordinates are the driver's own.
#[pyclass(module = "stopscan", name = "Strategy", unsendable)]
struct PyStrategy {
    inner: Box<dyn stopscan::strategy::polygon::PolygonStrategy + Send>,
    feedback: Option<PolygonFeedback>,
    /// The frame the strategy computes in, [`stopscan::geometry::Frame::near`] the start: the
    /// driver's coordinates may be georeferenced (millions of metres), while the strategy's
    /// tolerances are a map's.
    frame: stopscan::geometry::Frame,
}

#[pymethods]
impl PyStrategy {
    #[new]
    #[pyo3(signature = (name="depth_first", scan_time=1.0, move_time=0.0, speed=1.0, range=None, robot_radius=None))]
    fn new(
        name: &str,
        scan_time: f64,
        move_time: f64,
        speed: f64,
        range: Option<f64>,
        robot_radius: Option<f64>,
    ) -> PyResult<Self> {
        let o =
            explore_options(name, scan_time, move_time, speed, range, robot_radius, 0, None, None)?;
        let setup = o.robot_for(None);
        let inner = stopscan::strategy::polygon::build_for(name, &setup).map_err(value_error)?;
        Ok(Self { inner, feedback: None, frame: stopscan::geometry::Frame::IDENTITY })
    }

    /// The strategy's registry name.
    #[getter]
    fn name(&self) -> String {
        self.inner.name().to_string()
    }

    /// What happened since the last action: exactly one of `start=(x, y)` (the robot stands
    /// there; first), `arrived=True`, `region=Region` (the scan asked for), or
    /// `failed=(x, y)` with `reason` ("blocked", "aborted" or "timed_out").
    #[pyo3(signature = (*, start=None, arrived=false, region=None, failed=None, reason="blocked"))]
    fn observe(
        &mut self,
        start: Option<(f64, f64)>,
        arrived: bool,
        region: Option<PyRef<'_, PyRegion>>,
        failed: Option<(f64, f64)>,
        reason: &str,
    ) -> PyResult<()> {
        let given = usize::from(start.is_some())
            + usize::from(arrived)
            + usize::from(region.is_some())
            + usize::from(failed.is_some());
        if given != 1 {
            return Err(value_error("observe takes exactly one of start, arrived, region, failed"));
        }
        if let Some(s) = start {
            if !(s.0.is_finite() && s.1.is_finite()) {
                return Err(value_error(format!("start: must be finite, got {s:?}")));
            }
            self.frame = stopscan::geometry::Frame::near([s.0, s.1]);
        }
        let frame = self.frame;
        self.feedback = Some(if let Some(s) = start {
            Feedback::Start { at: frame.to_local([s.0, s.1]) }
        } else if arrived {
            Feedback::Arrived
        } else if let Some(r) = region {
            let region = r.region.mapped(|p| frame.to_local(p));
            Feedback::Scanned(PolygonObservation::new(region.viewpoint, region))
        } else {
            let at = frame.to_local(failed.map(|f| [f.0, f.1]).unwrap_or_default());
            let reason = match reason {
                "blocked" => MoveFailure::Blocked,
                "aborted" => MoveFailure::Aborted,
                "timed_out" => MoveFailure::TimedOut,
                r => {
                    return Err(value_error(format!(
                        "reason: expected blocked, aborted or timed_out, got {r:?}"
                    )));
                }
            };
            Feedback::MoveFailed { at, reason }
        });
        Ok(())
    }

    /// The next action, as a dict: `{"type": "move", "to": (x, y)}`, `{"type": "scan"}` or
    /// `{"type": "done"}`.
    fn next_action<'py>(&mut self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let Some(feedback) = self.feedback.take() else {
            return Err(value_error("call observe first (start=(x, y) before the first action)"));
        };
        let inner = &mut self.inner;
        let action = py.detach(|| inner.act(&feedback));
        let d = PyDict::new(py);
        match action {
            Action::MoveTo { to } => {
                d.set_item("type", "move")?;
                let to = self.frame.to_input(to);
                d.set_item("to", (to[0], to[1]))?;
            }
            Action::Scan => d.set_item("type", "scan")?,
            Action::Done => d.set_item("type", "done")?,
        }
        Ok(d)
    }
}

/// The native module.
#[pymodule]
fn _stopscan(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyEnvironment>()?;
    m.add_class::<PyRegion>()?;
    m.add_class::<PyStrategy>()?;
    m.add_function(wrap_pyfunction!(load, m)?)?;
    m.add_function(wrap_pyfunction!(from_geojson, m)?)?;
    m.add_function(wrap_pyfunction!(visibility, m)?)?;
    m.add_function(wrap_pyfunction!(explore_json, m)?)?;
    m.add_function(wrap_pyfunction!(corner::corner_circle, m)?)?;
    m.add_function(wrap_pyfunction!(corner::corner_ratio, m)?)?;
    m.add_function(wrap_pyfunction!(corner::corner_policy, m)?)?;
    m.add_function(wrap_pyfunction!(roi::roi_json, m)?)?;
    m.add_function(wrap_pyfunction!(roi::load_region, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_files, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_check, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_load, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_run, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_failed, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_csv_header, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
