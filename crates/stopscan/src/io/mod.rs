//! Environment formats. Loaders check everything once, report the file, the place and the
//! problem, and never panic.
//!
//! - [`text_formats`]: GeoJSON, WKT and `.pol` (and GeoJSON out);
//! - [`ros_map`]: ROS `map_server` occupancy grids, traced into polygons and simplified;
//! - [`bench_format`]: the visibility benchmark format;
//! - [`grid`]: region-of-interest files (text grid, mask, polygon);
//! - [`atomic`]: writing files whole or not at all, and the output-target checks;
//! - [`journal`]: append-only journals of JSON lines, cut back past a torn last line;
//! - [`sweep`]: the environment files of a sweep folder;
//! - here: [`read_environment`] by file extension, [`Environment`], [`LoadError`].

pub mod atomic;
pub mod bench_format;
pub mod grid;
pub mod journal;
pub mod ros_map;
pub mod sweep;
pub mod text_formats;

use crate::geometry::{Frame, InvalidEnvironment};

/// Why an environment file could not be loaded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum LoadError {
    /// The file could not be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: String,
        /// The system error.
        source: std::io::Error,
    },
    /// The text is malformed at a line (1-based), or as a whole (line 0: the message then
    /// names no line).
    #[error("{file}{}: {reason}", line_suffix(*line))]
    Syntax {
        /// The file.
        file: String,
        /// The line, 1-based; 0 when the whole file is at fault.
        line: usize,
        /// What is wrong.
        reason: String,
    },
    /// A region of interest is invalid (empty, disconnected, start outside).
    #[error("{file}: {source}")]
    InvalidRoi {
        /// The file.
        file: String,
        /// The problem, with a cell where it is.
        source: crate::world::grid::InvalidRoi,
    },
    /// A loader's option is out of its range (named as the option's field), whatever the file.
    #[error("{name} must {requirement}, got {}", crate::kernel::Num(*.value))]
    InvalidOption {
        /// The option.
        name: &'static str,
        /// What it must be.
        requirement: &'static str,
        /// What it was.
        value: f64,
    },
    /// The text parses but the environment is invalid.
    #[error("{file}: {source}")]
    Invalid {
        /// The file.
        file: String,
        /// The validation error (names the ring and vertex).
        source: InvalidEnvironment,
    },
}

/// `":LINE"` for a line, nothing for 0 (the whole file): `file:3: …` or `file: …`.
pub(crate) fn line_suffix(line: usize) -> String {
    if line == 0 { String::new() } else { format!(":{line}") }
}

/// An environment with the start and query points it may carry, in the local frame
/// computations run in ([`Frame`]).
#[derive(Debug, Clone)]
pub struct Environment {
    /// The validated domain (local frame).
    pub domain: crate::geometry::Domain,
    /// The robot's start carried by the file (GeoJSON's `start` property, a ROS map's
    /// `--start`), in the local frame.
    pub start: Option<crate::kernel::Point>,
    /// Visibility query points carried by the file (the benchmark format's `QUERIES`
    /// section), in the local frame.
    pub queries: Vec<crate::kernel::Point>,
    /// The cell size of the occupancy map the domain was traced from (metres), if it was.
    pub cell_size: Option<f64>,
    /// The file's frame: `input = local + frame.origin`. Points the user gives are moved into
    /// the local frame with [`Frame::to_local`], and results back with [`Frame::to_input`].
    pub frame: Frame,
}

impl Environment {
    /// An environment in its input's own frame, with no start and no query points.
    pub fn new(domain: crate::geometry::Domain) -> Self {
        Self { domain, start: None, queries: Vec::new(), cell_size: None, frame: Frame::IDENTITY }
    }

    /// The same environment with this start.
    #[must_use]
    pub fn with_start(self, start: Option<crate::kernel::Point>) -> Self {
        Self { start, ..self }
    }

    /// The same environment with these query points.
    #[must_use]
    pub fn with_queries(self, queries: Vec<crate::kernel::Point>) -> Self {
        Self { queries, ..self }
    }

    /// Where a run starts unless told otherwise: the file's start, else its first query
    /// point (a benchmark file's first query), else `None` (the caller picks an interior
    /// point).
    pub fn default_start(&self) -> Option<crate::kernel::Point> {
        self.start.or_else(|| self.queries.first().copied())
    }

    /// The same environment moved next to the origin when its coordinates lie far from it
    /// ([`Frame::for_points`]): georeferenced maps. The translation is exact for the domain.
    ///
    /// # Errors
    /// [`InvalidEnvironment`] only if the translated domain does not validate, which an exact
    /// translation rules out.
    pub fn localised(self) -> Result<Self, InvalidEnvironment> {
        let frame = Frame::for_points(self.domain.rings().iter().flatten());
        if frame.is_identity() {
            return Ok(self);
        }
        let mut rings: Vec<Vec<crate::kernel::Point>> = self
            .domain
            .rings()
            .iter()
            .map(|r| r.iter().map(|&p| frame.to_local(p)).collect())
            .collect();
        let outer = rings.remove(0);
        let domain = crate::geometry::Domain::new(outer, rings)?;
        let queries = self.queries.iter().map(|&q| frame.to_local(q)).collect();
        let start = self.start.map(|s| frame.to_local(s));
        Ok(Self { domain, start, queries, frame, ..self })
    }
}

/// Reads an environment file, choosing the format by its content, in its local frame
/// ([`Environment::localised`]; a ROS map is always read in the frame of its grid).
///
/// GeoJSON, WKT, `.pol` ([`text_formats`]), the visibility benchmark format
/// ([`bench_format`]) and ROS `map_server` YAML ([`ros_map`]).
///
/// # Errors
/// [`LoadError`] naming the file, the place and the problem.
pub fn read_environment(path: &std::path::Path) -> Result<Environment, LoadError> {
    read_environment_with(path, &ros_map::RosMapOptions::default())
}

/// Reads an environment file as [`read_environment`] does, a ROS map with `map` (its start,
/// speck area and simplification, [`ros_map::RosMapOptions`]); other formats ignore `map`.
///
/// # Errors
/// [`LoadError`] naming the file, the place and the problem.
pub fn read_environment_with(
    path: &std::path::Path,
    map: &ros_map::RosMapOptions,
) -> Result<Environment, LoadError> {
    read_in_input_frame(path, map)?
        .localised()
        .map_err(|source| LoadError::Invalid { file: path.display().to_string(), source })
}

fn read_in_input_frame(
    path: &std::path::Path,
    map: &ros_map::RosMapOptions,
) -> Result<Environment, LoadError> {
    let bytes = std::fs::read(path)
        .map_err(|source| LoadError::Io { file: path.display().to_string(), source })?;
    let text = String::from_utf8(bytes).map_err(|_| LoadError::Syntax {
        file: path.display().to_string(),
        line: 0,
        reason: "binary content: not a text environment file (GeoJSON, WKT, .pol, the visibility benchmark format, ROS map .yaml)".into(),
    })?;
    let first =
        text.lines().map(str::trim).find(|l| !l.is_empty() && !l.starts_with('#')).unwrap_or("");
    let file = path.display().to_string();
    let ext = path.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    if matches!(ext.as_deref(), Some("yaml" | "yml")) {
        return ros_map::read(path, map);
    }
    if first.starts_with("OUTER") {
        let e = bench_format::parse(&text, &file)?;
        return Ok(Environment::new(e.domain).with_queries(e.queries));
    }
    if first.starts_with('{') || matches!(ext.as_deref(), Some("geojson" | "json")) {
        return text_formats::parse_geojson(&text, &file);
    }
    if first.len() >= 7 && first[..7].eq_ignore_ascii_case("POLYGON") {
        return text_formats::parse_wkt(&text, &file);
    }
    if ext.as_deref() == Some("pol")
        || first.split_whitespace().next().is_some_and(|t| t.parse::<usize>().is_ok())
    {
        return text_formats::parse_pol(&text, &file);
    }
    Err(LoadError::Syntax {
        file,
        line: 1,
        reason: "unrecognised environment format (supported: GeoJSON, WKT POLYGON, .pol, the visibility benchmark format, ROS map .yaml)".into(),
    })
}

/// Reads query points, one `x y` (or `x,y`) per line; `#` starts a comment.
///
/// # Errors
/// [`LoadError`] naming the file and line.
pub fn read_points(path: &std::path::Path) -> Result<Vec<crate::kernel::Point>, LoadError> {
    let file = path.display().to_string();
    let text = std::fs::read_to_string(path)
        .map_err(|source| LoadError::Io { file: file.clone(), source })?;
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let v: Vec<&str> =
            line.split(|c: char| c == ',' || c.is_whitespace()).filter(|s| !s.is_empty()).collect();
        match v.as_slice() {
            [x, y] => match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => out.push([x, y]),
                _ => {
                    return Err(LoadError::Syntax {
                        file,
                        line: i + 1,
                        reason: format!("expected two finite numbers, got {line:?}"),
                    });
                }
            },
            _ => {
                return Err(LoadError::Syntax {
                    file,
                    line: i + 1,
                    reason: format!("expected 'x y', got {line:?}"),
                });
            }
        }
    }
    Ok(out)
}
