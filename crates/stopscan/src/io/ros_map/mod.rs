//! ROS `map_server` maps: a YAML file (`image`, `resolution`, `origin`, `negate`,
//! `occupied_thresh`, `free_thresh`, optional `mode`) and its PGM or PNG image, turned into
//! the free-space polygon that contains the start.
//!
//! 1. Occupancy `p = (255 − v)/255` (or `v/255` with `negate: 1`); a cell is free when
//!    `p < free_thresh`. Unknown cells count as obstacles.
//! 2. The free region is the 4-connected free component containing the start cell (the
//!    largest component when no start is given).
//! 3. Obstacle specks enclosed by it with an area below `min_speck_area` are filled.
//! 4. Where the region touches itself diagonally (a 2×2 checkerboard of free and blocked
//!    cells), one free cell of the pair is blocked: the rings would otherwise touch at a
//!    point. This removes at most one cell per pinch and never opens a wall.
//! 5. Its boundary is traced along cell edges (free space on the left) and collinear
//!    vertices are dropped: the *traced* boundary.
//! 6. The traced boundary is simplified within the tolerance `simplify` (metres; by default
//!    [`DEFAULT_SIMPLIFY_CELLS`] cells), preserving its topology (`simplify` module):
//!    - the tolerance is a distance in metres, applied in the local frame (the map's grid,
//!      whatever its YAML origin), never a count of cells or an area;
//!    - the simplified boundary lies within the tolerance of the traced boundary and the
//!      traced boundary within the tolerance of the simplified one (Hausdorff distance, ring
//!      by ring), and its vertices are traced vertices;
//!    - no ring intersects itself or another, no hole vanishes, leaves the outer ring or enters
//!      another hole, no ring drops below three vertices, and the start keeps its side of every
//!      ring (inside the free space if it was);
//!    - a tolerance of 0 keeps the traced boundary.
//!
//!    The result is validated as a [`Domain`]; should that fail, the tolerance is halved until
//!    it passes (down to the traced boundary), and [`MapImportReport::tolerance_used`] says so.
//!
//! [`read_with_report`] also returns what the simplification did: vertices, reflex vertices
//! and free area before and after, and the area change ([`MapImportReport`]).
//!
//! The YAML reader handles the flat `key: value` files that `map_server` writes (numbers,
//! strings, `[a, b, c]` lists, `#` comments), not general YAML.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use serde::Serialize;

use super::{Environment, LoadError};
use crate::geometry::Domain;
use crate::kernel::Point;

mod simplify;
#[cfg(test)]
mod tests;

/// The default simplification tolerance, in cells of the map (so `1.5 × resolution` metres).
///
/// A straight wall at a slant is drawn as a staircase of 1-cell steps whose corners lie in a
/// strip across the wall `(|p| + |q| − 1)/√(p² + q²)` cells wide for a slope `p/q` in lowest
/// terms: nearly 1 cell for a shallow slope `1/q`, 0.71 at 45°, 1.11 at 2/5, 1.28 at 5/6, and
/// up to √2 (never reaching it) for slopes near 45° with long periods. A tolerance above √2
/// cells lets every such staircase become straight edges, whatever its slope; 1.5 is the round
/// figure just above. (On synthetic walls of slopes from 1/10 to 10, 1.2 cells still left
/// steps; 1.4 and 1.5 left none.) Its cost is small: the boundary moves at most 1.5 cells, to
/// either side of a wall, so the free area changes by well under 1 % on the shared maps, and
/// topology is kept whatever a corridor's, doorway's or pillar's width.
pub const DEFAULT_SIMPLIFY_CELLS: f64 = 1.5;

/// How close to a grid line (in cells) a start counts as on it, and so in the cells either
/// side: far above the rounding of dividing a coordinate by the resolution, far below any
/// offset a user means.
const START_ON_LINE: f64 = 1e-9;

/// How a map is turned into a domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RosMapOptions {
    /// The robot's start (world coordinates, metres); the region containing it is kept. A start
    /// on a cell's edge or corner is in the free cell beside it, if any.
    pub start: Option<Point>,
    /// Enclosed obstacle specks smaller than this (square metres) become free.
    pub min_speck_area: f64,
    /// The simplification tolerance (metres, finite and non-negative): the most the boundary
    /// may move from the one traced along cell edges. `None`: [`DEFAULT_SIMPLIFY_CELLS`] times
    /// the map's resolution; `Some(0.0)`: the traced boundary (collinear vertices dropped only).
    pub simplify: Option<f64>,
}

impl Default for RosMapOptions {
    /// No start (the largest free region), specks below 0.05 m² filled, the default
    /// simplification.
    fn default() -> Self {
        Self { start: None, min_speck_area: 0.05, simplify: None }
    }
}

/// A map read into a domain, with what its simplification did.
#[derive(Debug, Clone)]
pub struct MapImport {
    /// The environment: the simplified domain and the start, in the grid's frame.
    pub environment: Environment,
    /// The traced and the simplified boundary side by side.
    pub report: MapImportReport,
}

/// What the simplification of a map's traced boundary did. Areas in square metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MapImportReport {
    /// The map's cell size (metres).
    pub resolution: f64,
    /// The tolerance asked for (metres): the option, or the default for this resolution.
    pub tolerance: f64,
    /// The tolerance the result was simplified with: `tolerance`, unless the simplified domain
    /// failed validation and the tolerance was halved (never observed; kept as a safety net).
    pub tolerance_used: f64,
    /// Vertices of the traced boundary (cell edges, collinear vertices dropped).
    pub traced_vertices: usize,
    /// Its reflex vertices.
    pub traced_reflex_vertices: usize,
    /// The free area inside the traced boundary (the free cells kept, times a cell's area).
    pub traced_area: f64,
    /// Vertices of the simplified boundary.
    pub vertices: usize,
    /// Its reflex vertices.
    pub reflex_vertices: usize,
    /// The free area inside the simplified boundary.
    pub area: f64,
    /// `|area − traced_area|`: the net change (gains and losses along the walls cancel).
    pub area_change: f64,
    /// `area_change / traced_area`.
    pub relative_area_change: f64,
}

struct MapYaml {
    image: PathBuf,
    resolution: f64,
    origin: [f64; 2],
    negate: bool,
    free_thresh: f64,
}

fn err(file: &Path, line: usize, reason: impl Into<String>) -> LoadError {
    LoadError::Syntax { file: file.display().to_string(), line, reason: reason.into() }
}

fn read_yaml(path: &Path) -> Result<MapYaml, LoadError> {
    let text = std::fs::read_to_string(path)
        .map_err(|source| LoadError::Io { file: path.display().to_string(), source })?;
    let (mut image, mut resolution, mut origin, mut negate, mut free) =
        (None, None, None, false, None);
    let mut occupied: Option<(f64, usize)> = None;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let (key, value) = line
            .split_once(':')
            .ok_or_else(|| err(path, i + 1, format!("expected 'key: value', got {line:?}")))?;
        let value = value.trim().trim_matches(|c| c == '"' || c == '\'');
        let num = |v: &str| {
            v.trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| err(path, i + 1, format!("{key}: expected a number, got {v:?}")))
        };
        let threshold = |v: &str, x: f64| {
            if (0.0..=1.0).contains(&x) {
                Ok(x)
            } else {
                Err(err(path, i + 1, format!("{key}: expected a number in [0, 1], got {v:?}")))
            }
        };
        match key.trim() {
            "image" => image = Some(value.to_string()),
            "resolution" => resolution = Some(num(value)?),
            "origin" => {
                let inner = value.trim_start_matches('[').trim_end_matches(']');
                let v: Result<Vec<f64>, _> = inner.split(',').map(num).collect();
                match v?.as_slice() {
                    [x, y, ..] => origin = Some([*x, *y]),
                    _ => return Err(err(path, i + 1, "origin: expected [x, y, yaw]")),
                }
            }
            "negate" => negate = num(value)? != 0.0,
            "free_thresh" => free = Some((threshold(value, num(value)?)?, i + 1)),
            "occupied_thresh" => occupied = Some((threshold(value, num(value)?)?, i + 1)),
            "mode" if !matches!(value, "trinary" | "scale") => {
                return Err(err(
                    path,
                    i + 1,
                    format!("mode: {value:?} is not supported (trinary or scale)"),
                ));
            }
            _ => {}
        }
    }
    let missing = |k: &str| err(path, 0, format!("the map YAML has no '{k}'"));
    let image = image.ok_or_else(|| missing("image"))?;
    let resolution = resolution.ok_or_else(|| missing("resolution"))?;
    if resolution <= 0.0 {
        return Err(err(
            path,
            0,
            format!("resolution must be positive, got {}", crate::kernel::Num(resolution)),
        ));
    }
    let (free_thresh, free_line) = free.ok_or_else(|| missing("free_thresh"))?;
    // map_server reads occupied_thresh too; the free region only needs free_thresh, but a
    // file whose thresholds contradict each other is wrong, not merely unusual.
    if let Some((occ, line)) = occupied
        && occ <= free_thresh
    {
        return Err(err(
            path,
            line,
            format!(
                "occupied_thresh {} is not above free_thresh {} (line {free_line}); map_server needs free_thresh < occupied_thresh",
                crate::kernel::Num(occ),
                crate::kernel::Num(free_thresh)
            ),
        ));
    }
    let dir = path.parent().unwrap_or(Path::new("."));
    Ok(MapYaml {
        image: dir.join(image),
        resolution,
        origin: origin.ok_or_else(|| missing("origin"))?,
        negate,
        free_thresh,
    })
}

/// A grey image, row 0 at the top.
pub(crate) struct Grey {
    pub(crate) w: usize,
    pub(crate) h: usize,
    pub(crate) px: Vec<u8>,
}

/// The image the YAML at `yaml` names (`image`, at `path`): one that cannot be read is named
/// with the YAML, as the usual fault is the YAML's `image` path, not the image.
fn read_image_of(yaml: &Path, path: &Path) -> Result<Grey, LoadError> {
    read_image(path).map_err(|e| match e {
        LoadError::Io { file, source } => LoadError::Io {
            file: format!("{file} (the image named by {}'s `image`)", yaml.display()),
            source,
        },
        e => e,
    })
}

pub(crate) fn read_image(path: &Path) -> Result<Grey, LoadError> {
    let bytes = std::fs::read(path)
        .map_err(|source| LoadError::Io { file: path.display().to_string(), source })?;
    if bytes.starts_with(b"\x89PNG") {
        return read_png(path, &bytes);
    }
    read_pgm(path, &bytes)
}

fn read_png(path: &Path, bytes: &[u8]) -> Result<Grey, LoadError> {
    let bad = |e: String| err(path, 0, format!("cannot decode PNG: {e}"));
    let mut dec = png::Decoder::new(bytes);
    dec.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = dec.read_info().map_err(|e| bad(e.to_string()))?;
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).map_err(|e| bad(e.to_string()))?;
    let (w, h) = (info.width as usize, info.height as usize);
    let ch = info.color_type.samples();
    let px = (0..w * h)
        .map(|i| {
            let p = &buf[i * ch..i * ch + ch];
            if ch >= 3 {
                ((u32::from(p[0]) + u32::from(p[1]) + u32::from(p[2])) / 3) as u8
            } else {
                p[0]
            }
        })
        .collect();
    Ok(Grey { w, h, px })
}

fn read_pgm(path: &Path, bytes: &[u8]) -> Result<Grey, LoadError> {
    let mut pos = 0;
    let mut token = || -> Option<String> {
        loop {
            while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
                pos += 1;
            }
            if pos < bytes.len() && bytes[pos] == b'#' {
                while pos < bytes.len() && bytes[pos] != b'\n' {
                    pos += 1;
                }
                continue;
            }
            break;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        (pos > start).then(|| String::from_utf8_lossy(&bytes[start..pos]).into_owned())
    };
    let magic = token().unwrap_or_default();
    if magic != "P5" && magic != "P2" {
        return Err(err(path, 1, format!("not a PGM (P5/P2) or PNG image (magic {magic:?})")));
    }
    let mut dim = || token().and_then(|t| t.parse::<usize>().ok());
    let (w, h, max) = match (dim(), dim(), dim()) {
        (Some(w), Some(h), Some(m))
            if w > 0 && h > 0 && (1..=65535).contains(&m) && w.saturating_mul(h) <= 400_000_000 =>
        {
            (w, h, m)
        }
        _ => return Err(err(path, 0, "bad PGM header (width, height, maxval)")),
    };
    let scale = |v: usize| ((v * 255 + max / 2) / max).min(255) as u8;
    let px: Vec<u8> = if magic == "P5" {
        let data = &bytes[(pos + 1).min(bytes.len())..];
        let bpp = if max > 255 { 2 } else { 1 };
        if data.len() < w * h * bpp {
            return Err(err(
                path,
                0,
                format!("truncated PGM: {} bytes of pixels, expected {}", data.len(), w * h * bpp),
            ));
        }
        (0..w * h)
            .map(|i| {
                if bpp == 1 {
                    scale(data[i] as usize)
                } else {
                    scale(((data[2 * i] as usize) << 8) | data[2 * i + 1] as usize)
                }
            })
            .collect()
    } else {
        let mut v = Vec::with_capacity(w * h);
        for _ in 0..w * h {
            let t = token()
                .and_then(|t| t.parse::<usize>().ok())
                .ok_or_else(|| err(path, 0, "truncated or malformed P2 pixel data"))?;
            v.push(scale(t.min(max)));
        }
        v
    };
    Ok(Grey { w, h, px })
}

/// Reads a `map_server` YAML and its image into the free-space domain containing the start
/// ([`read_with_report`] without the report).
///
/// # Errors
/// As [`read_with_report`].
pub fn read(path: &Path, opts: &RosMapOptions) -> Result<Environment, LoadError> {
    read_with_report(path, opts).map(|m| m.environment)
}

/// Reads a `map_server` YAML and its image into the free-space domain containing the start,
/// and reports what the simplification did (see the module's steps).
///
/// # Errors
/// [`LoadError`] naming the file and the problem (a YAML without its image, an empty map, a
/// start in an obstacle, …); [`LoadError::InvalidOption`] for a `simplify` that is negative
/// or not finite.
///
/// # Complexity
/// O(w·h) for a w × h grid; the simplification makes O(n log n) heap operations for n traced
/// vertices, and each removal walks the traced vertices and the index cells along its new edge.
///
/// # Example
/// A 10 × 10 room of 0.1 m cells with a wall slanting across it as 1-cell steps; the default
/// tolerance (0.15 m) makes the staircase straight.
/// ```
/// use stopscan::io::ros_map::{RosMapOptions, read_with_report};
///
/// let dir = std::env::temp_dir().join(format!("stopscan-doc-simplify-{}", std::process::id()));
/// std::fs::create_dir_all(&dir)?;
/// // Row 0 is the top; cell (r, c) is free below the diagonal.
/// let px: Vec<u8> = (0..100).map(|i| if i / 10 > i % 10 { 254 } else { 0 }).collect();
/// let mut pgm = b"P5\n10 10\n255\n".to_vec();
/// pgm.extend_from_slice(&px);
/// std::fs::write(dir.join("m.pgm"), pgm)?;
/// std::fs::write(
///     dir.join("m.yaml"),
///     "image: m.pgm\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\nfree_thresh: 0.2\n",
/// )?;
/// let m = read_with_report(&dir.join("m.yaml"), &RosMapOptions::default())?;
/// let r = m.report;
/// assert_eq!((r.traced_vertices, r.vertices), (20, 3));
/// assert!((r.traced_area - 0.45).abs() < 1e-12 && (r.area - 0.405).abs() < 1e-12);
/// assert!((r.area_change - 0.045).abs() < 1e-12);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn read_with_report(path: &Path, opts: &RosMapOptions) -> Result<MapImport, LoadError> {
    if let Some(t) = opts.simplify
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(LoadError::InvalidOption {
            name: "simplify",
            requirement: "be a finite non-negative number of metres",
            value: t,
        });
    }
    let y = read_yaml(path)?;
    let img = read_image_of(path, &y.image)?;
    let (w, h) = (img.w, img.h);
    let mut free: Vec<bool> = img
        .px
        .iter()
        .map(|&v| {
            let v = f64::from(v) / 255.0;
            let p = if y.negate { v } else { 1.0 - v };
            p < y.free_thresh
        })
        .collect();
    // The map is traced in the frame of its grid (cell corners at multiples of the
    // resolution), whatever its origin: coordinates of a georeferenced origin would round
    // grid lines together.
    let frame = crate::geometry::Frame::at(y.origin);
    let start = opts.start.map(|s| frame.to_local(s));
    // The free cell the start lies in, or on the edge or corner of (a start on a grid line
    // belongs to the cells either side; the first free one is its cell).
    let cells_at = |p: Point| -> Vec<usize> {
        let near = |v: f64, n: usize| -> Vec<usize> {
            let mut out: Vec<usize> = [v - START_ON_LINE, v + START_ON_LINE]
                .into_iter()
                .filter(|k| *k >= 0.0 && *k < n as f64)
                .map(|k| k.floor() as usize)
                .collect();
            out.dedup();
            out
        };
        let (cols, rows) = (near(p[0] / y.resolution, w), near(p[1] / y.resolution, h));
        rows.iter().flat_map(|&r| cols.iter().map(move |&c| (h - 1 - r) * w + c)).collect()
    };
    let seed = match start {
        Some(s) => {
            let given = frame.to_input(s);
            let cells = cells_at(s);
            if cells.is_empty() {
                return Err(err(path, 0, format!("the start {given:?} is outside the map")));
            }
            let c = cells.into_iter().find(|&c| free[c]).ok_or_else(|| {
                err(path, 0, format!("the start {given:?} is not in a free cell"))
            })?;
            Some(c)
        }
        None => None,
    };
    let speck_cells = (opts.min_speck_area / (y.resolution * y.resolution)).floor() as usize;
    let region = loop {
        let region =
            component(&free, w, h, seed).ok_or_else(|| err(path, 0, "the map has no free cell"))?;
        let mut changed = fill_specks(&mut free, &region, w, h, speck_cells);
        let region =
            component(&free, w, h, seed).ok_or_else(|| err(path, 0, "the map has no free cell"))?;
        changed |= unpinch(&mut free, &region, w, h, seed);
        if !changed {
            break region;
        }
    };
    let corners = trace(&region, w, h);
    let tolerance = opts.simplify.unwrap_or(DEFAULT_SIMPLIFY_CELLS * y.resolution);
    let protect: Vec<Point> = start.into_iter().collect();
    let (domain, tolerance_used) =
        simplify_until_valid(path, &corners, y.resolution, tolerance, &protect)?;
    let rings: Vec<Vec<Point>> =
        corners.iter().map(|r| simplify::in_metres(r, y.resolution)).collect();
    let traced_area: f64 = rings.iter().map(|r| crate::geometry::signed_area_of(r)).sum();
    let area = domain.area();
    let area_change = (area - traced_area).abs();
    let report = MapImportReport {
        resolution: y.resolution,
        tolerance,
        tolerance_used,
        traced_vertices: rings.iter().map(Vec::len).sum(),
        traced_reflex_vertices: rings.iter().map(|r| reflex_count(r)).sum(),
        traced_area,
        vertices: domain.vertex_count(),
        reflex_vertices: domain.reflex_vertices().len(),
        area,
        area_change,
        relative_area_change: area_change / traced_area,
    };
    Ok(MapImport {
        environment: Environment {
            domain,
            start,
            queries: Vec::new(),
            cell_size: Some(y.resolution),
            frame,
        },
        report,
    })
}

/// The reflex vertices of a ring with the free space on its left (right turns).
fn reflex_count(ring: &[Point]) -> usize {
    let n = ring.len();
    (0..n)
        .filter(|&i| {
            crate::kernel::orient_sign(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) < 0
        })
        .count()
}

/// The 4-connected free component containing `seed`, or the largest.
fn component(free: &[bool], w: usize, h: usize, seed: Option<usize>) -> Option<Vec<bool>> {
    let mut label = vec![u32::MAX; w * h];
    let mut best: Option<(usize, u32)> = None;
    let mut next = 0u32;
    let mut queue = VecDeque::new();
    for s in 0..w * h {
        if !free[s] || label[s] != u32::MAX {
            continue;
        }
        let mut size = 0;
        label[s] = next;
        queue.push_back(s);
        while let Some(c) = queue.pop_front() {
            size += 1;
            let (r, col) = (c / w, c % w);
            let ns = [
                (r > 0).then(|| c - w),
                (r + 1 < h).then(|| c + w),
                (col > 0).then(|| c - 1),
                (col + 1 < w).then(|| c + 1),
            ];
            for n in ns.into_iter().flatten() {
                if free[n] && label[n] == u32::MAX {
                    label[n] = next;
                    queue.push_back(n);
                }
            }
        }
        if best.is_none_or(|b| size > b.0) {
            best = Some((size, next));
        }
        next += 1;
    }
    let keep = match seed {
        Some(s) => label[s],
        None => best?.1,
    };
    (keep != u32::MAX).then(|| label.iter().map(|&l| l == keep).collect())
}

/// Fills 8-connected blocked components enclosed by the region (not touching the image border
/// or any other free component) with fewer than `max_cells` cells. Returns whether it changed.
fn fill_specks(free: &mut [bool], region: &[bool], w: usize, h: usize, max_cells: usize) -> bool {
    if max_cells == 0 {
        return false;
    }
    let mut seen = vec![false; w * h];
    let mut changed = false;
    for s in 0..w * h {
        if region[s] || seen[s] {
            continue;
        }
        let mut cells = vec![s];
        seen[s] = true;
        let mut i = 0;
        let mut enclosed = true;
        while i < cells.len() {
            let c = cells[i];
            i += 1;
            let (r, col) = ((c / w) as isize, (c % w) as isize);
            if r == 0 || col == 0 || r as usize == h - 1 || col as usize == w - 1 {
                enclosed = false;
            }
            for dr in -1..=1 {
                for dc in -1..=1 {
                    let (nr, nc) = (r + dr, col + dc);
                    if nr < 0 || nc < 0 || nr as usize >= h || nc as usize >= w {
                        continue;
                    }
                    let n = nr as usize * w + nc as usize;
                    if !region[n] && !seen[n] {
                        seen[n] = true;
                        cells.push(n);
                    }
                }
            }
        }
        if enclosed && cells.len() < max_cells {
            for c in cells {
                free[c] = true;
            }
            changed = true;
        }
    }
    changed
}

/// Blocks one free cell of every diagonal pinch of the region, never `seed` (the start's
/// cell): the upper one of the pair, or the lower one when the upper is the seed. Returns
/// whether it changed.
fn unpinch(free: &mut [bool], region: &[bool], w: usize, h: usize, seed: Option<usize>) -> bool {
    let mut changed = false;
    let mut block = |upper: usize, lower: usize| {
        free[if seed == Some(upper) { lower } else { upper }] = false;
        changed = true;
    };
    for r in 0..h.saturating_sub(1) {
        for c in 0..w.saturating_sub(1) {
            let (a, b, cc, d) = (r * w + c, r * w + c + 1, (r + 1) * w + c, (r + 1) * w + c + 1);
            let (fa, fb, fc, fd) = (region[a], region[b], region[cc], region[d]);
            if fa && fd && !fb && !fc {
                block(a, d);
            } else if fb && fc && !fa && !fd {
                block(b, cc);
            }
        }
    }
    changed
}

/// The region's boundary along cell edges, in cells (grid corners: whole numbers, the map's
/// lower left corner at the origin), free space on the left, collinear vertices dropped.
fn trace(region: &[bool], w: usize, h: usize) -> Vec<Vec<Point>> {
    // Vertex (i, j): column line i in 0..=w, row line j in 0..=h (j = 0 at the top).
    let vid = |i: usize, j: usize| j * (w + 1) + i;
    let mut next = vec![u32::MAX; (w + 1) * (h + 1)];
    let is = |r: isize, c: isize| {
        r >= 0
            && c >= 0
            && (r as usize) < h
            && (c as usize) < w
            && region[r as usize * w + c as usize]
    };
    for r in 0..h {
        for c in 0..w {
            if !region[r * w + c] {
                continue;
            }
            let (ri, ci) = (r as isize, c as isize);
            // Counter-clockwise in world coordinates (y up = rows decreasing).
            if !is(ri + 1, ci) {
                next[vid(c, r + 1)] = vid(c + 1, r + 1) as u32; // bottom, left to right
            }
            if !is(ri, ci + 1) {
                next[vid(c + 1, r + 1)] = vid(c + 1, r) as u32; // right, upwards
            }
            if !is(ri - 1, ci) {
                next[vid(c + 1, r)] = vid(c, r) as u32; // top, right to left
            }
            if !is(ri, ci - 1) {
                next[vid(c, r)] = vid(c, r + 1) as u32; // left, downwards
            }
        }
    }
    let corner = |v: usize| [(v % (w + 1)) as f64, (h - v / (w + 1)) as f64];
    let mut rings = Vec::new();
    for s in 0..next.len() {
        if next[s] == u32::MAX {
            continue;
        }
        let mut ring = Vec::new();
        let mut v = s;
        while next[v] != u32::MAX {
            let n = next[v] as usize;
            next[v] = u32::MAX;
            ring.push(corner(v));
            v = n;
        }
        rings.push(drop_collinear(&ring));
    }
    // The outer boundary is the ring of largest (positive) area.
    let area = |r: &Vec<Point>| crate::geometry::signed_area_of(r);
    if let Some(k) = (0..rings.len()).max_by(|&a, &b| area(&rings[a]).total_cmp(&area(&rings[b]))) {
        rings.swap(0, k);
    }
    rings
}

fn drop_collinear(ring: &[Point]) -> Vec<Point> {
    let n = ring.len();
    (0..n)
        .filter(|&i| {
            crate::kernel::orient_sign(ring[(i + n - 1) % n], ring[i], ring[(i + 1) % n]) != 0
        })
        .map(|i| ring[i])
        .collect()
}

/// The traced rings (`corners`, in cells) simplified within `tol` metres, in metres and
/// validated, with the tolerance that passed: `tol`, else halved until valid (below 1/64 of
/// it, the traced rings themselves).
fn simplify_until_valid(
    path: &Path,
    corners: &[Vec<Point>],
    resolution: f64,
    tol: f64,
    protect: &[Point],
) -> Result<(Domain, f64), LoadError> {
    let floor = tol / 64.0;
    let mut tol = tol;
    loop {
        let mut rs = simplify::simplify(corners, resolution, tol, protect);
        let outer = rs.remove(0);
        match Domain::new(outer, rs) {
            Ok(d) => return Ok((d, tol)),
            Err(e) if tol == 0.0 => {
                return Err(LoadError::Invalid { file: path.display().to_string(), source: e });
            }
            Err(_) => tol = if tol < floor { 0.0 } else { tol / 2.0 },
        }
    }
}
