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
//! 5. Its boundary is traced along cell edges (free space on the left), collinear vertices
//!    are dropped, and each ring is simplified by Douglas–Peucker to within one cell,
//!    tightening the tolerance until the result validates.
//!
//! The YAML reader handles the flat `key: value` files that `map_server` writes (numbers,
//! strings, `[a, b, c]` lists, `#` comments), not general YAML.

use std::collections::VecDeque;
use std::path::{Path, PathBuf};

use super::{Environment, LoadError};
use crate::geometry::Domain;
use crate::kernel::Point;

/// How a map is turned into a domain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RosMapOptions {
    /// The robot's start (world coordinates, metres); the region containing it is kept.
    pub start: Option<Point>,
    /// Enclosed obstacle specks smaller than this (square metres) become free.
    pub min_speck_area: f64,
}

impl Default for RosMapOptions {
    fn default() -> Self {
        Self { start: None, min_speck_area: 0.05 }
    }
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

/// Reads a `map_server` YAML and its image into the free-space domain containing the start.
///
/// # Errors
/// [`LoadError`] naming the file and the problem (a YAML without its image, an empty map, a
/// start in an obstacle, …).
pub fn read(path: &Path, opts: &RosMapOptions) -> Result<Environment, LoadError> {
    let y = read_yaml(path)?;
    let img = read_image(&y.image)?;
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
    let cell_of = |p: Point| -> Option<usize> {
        let c = (p[0] / y.resolution).floor();
        let r = h as f64 - 1.0 - (p[1] / y.resolution).floor();
        (c >= 0.0 && r >= 0.0 && (c as usize) < w && (r as usize) < h)
            .then(|| r as usize * w + c as usize)
    };
    let seed = match start {
        Some(s) => {
            let given = frame.to_input(s);
            let c = cell_of(s)
                .ok_or_else(|| err(path, 0, format!("the start {given:?} is outside the map")))?;
            if !free[c] {
                return Err(err(path, 0, format!("the start {given:?} is not in a free cell")));
            }
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
        changed |= unpinch(&mut free, &region, w, h);
        if !changed {
            break region;
        }
    };
    let rings = trace(&region, w, h, y.resolution);
    let domain = simplify_until_valid(path, &rings, y.resolution)?;
    Ok(Environment { domain, start, queries: Vec::new(), frame })
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

/// Blocks one free cell of every diagonal pinch of the region. Returns whether it changed.
fn unpinch(free: &mut [bool], region: &[bool], w: usize, h: usize) -> bool {
    let mut changed = false;
    for r in 0..h.saturating_sub(1) {
        for c in 0..w.saturating_sub(1) {
            let (a, b, cc, d) = (r * w + c, r * w + c + 1, (r + 1) * w + c, (r + 1) * w + c + 1);
            let (fa, fb, fc, fd) = (region[a], region[b], region[cc], region[d]);
            if fa && fd && !fb && !fc {
                free[a] = false;
                changed = true;
            } else if fb && fc && !fa && !fd {
                free[b] = false;
                changed = true;
            }
        }
    }
    changed
}

/// The region's boundary along cell edges (in the grid's frame: the map's lower left corner at
/// the origin), free space on the left, collinear vertices dropped.
fn trace(region: &[bool], w: usize, h: usize, res: f64) -> Vec<Vec<Point>> {
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
    let to_world = |v: usize| [(v % (w + 1)) as f64 * res, (h - v / (w + 1)) as f64 * res];
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
            ring.push(to_world(v));
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

/// Douglas–Peucker on a closed ring (split at the vertex farthest from vertex 0).
fn simplify_ring(ring: &[Point], tol: f64) -> Vec<Point> {
    if tol <= 0.0 || ring.len() <= 4 {
        return ring.to_vec();
    }
    let far = (1..ring.len())
        .max_by(|&a, &b| dist2(ring[0], ring[a]).total_cmp(&dist2(ring[0], ring[b])))
        .unwrap_or(1);
    let mut keep = vec![false; ring.len() + 1];
    keep[0] = true;
    keep[far] = true;
    keep[ring.len()] = true;
    let at = |i: usize| ring[i % ring.len()];
    let mut stack = vec![(0, far), (far, ring.len())];
    while let Some((a, b)) = stack.pop() {
        if b <= a + 1 {
            continue;
        }
        let (pa, pb) = (at(a), at(b));
        let (k, d) = (a + 1..b)
            .map(|k| (k, crate::geometry::segment_distance(at(k), pa, pb)))
            .max_by(|x, y| x.1.total_cmp(&y.1))
            .unwrap_or((a, 0.0));
        if d > tol {
            keep[k] = true;
            stack.push((a, k));
            stack.push((k, b));
        }
    }
    (0..ring.len()).filter(|&i| keep[i]).map(|i| ring[i]).collect()
}

fn dist2(a: Point, b: Point) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)
}

fn simplify_until_valid(path: &Path, rings: &[Vec<Point>], res: f64) -> Result<Domain, LoadError> {
    let mut tol = res;
    loop {
        let mut rs: Vec<Vec<Point>> = rings.iter().map(|r| simplify_ring(r, tol)).collect();
        let outer = rs.remove(0);
        match Domain::new(outer, rs) {
            Ok(d) => return Ok(d),
            Err(e) if tol == 0.0 => {
                return Err(LoadError::Invalid { file: path.display().to_string(), source: e });
            }
            Err(_) => tol = if tol < res / 64.0 { 0.0 } else { tol / 2.0 },
        }
    }
}
