//! Region-of-interest files: a text grid, a PGM or PNG mask, or any polygon format (rasterised
//! to its outer grid approximation, section 5 of the ROI paper).
//!
//! **Text grid**: one line per row, `#` a region cell, `.` (or a space) outside, `S` the start
//! cell (a region cell); lines starting with `;` are comments. **Mask**: a PGM (P2/P5) or PNG
//! image whose pixels of grey level 128 or more are region (below 128 with `invert`); blocks of
//! `cell_px` × `cell_px` pixels are one cell, which is a region cell when any of its pixels is
//! (the outer approximation).

use std::path::Path;

use super::{LoadError, ros_map};
use crate::protocol::grid::Cell;
use crate::world::grid::GridRoi;

/// How to read a region file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GridOptions {
    /// The side of a cell, metres.
    pub cell_size: f64,
    /// Pixels per cell side, for masks.
    pub cell_px: usize,
    /// The start cell (row, col), for masks and text grids without `S`; default the first
    /// region cell in reading order.
    pub start: Option<Cell>,
    /// For masks: the region is dark (grey below 128) instead of light.
    pub invert: bool,
}

impl Default for GridOptions {
    fn default() -> Self {
        Self { cell_size: 1.0, cell_px: 1, start: None, invert: false }
    }
}

/// Reads a region of interest, choosing the format by content: a PNG or PGM image is a mask,
/// text whose first line (after `;` comments) starts with `#`, `.` or `S` is a text grid,
/// anything else is read as a polygon environment
/// (GeoJSON, WKT, .pol; its `start` is where the grid is centred).
///
/// # Errors
/// [`LoadError`] naming the file, the line or cell, and the problem.
pub fn read_roi(path: &Path, opts: &GridOptions) -> Result<GridRoi, LoadError> {
    let file = path.display().to_string();
    let bytes =
        std::fs::read(path).map_err(|source| LoadError::Io { file: file.clone(), source })?;
    let name = path.file_stem().and_then(|s| s.to_str()).unwrap_or("roi").to_string();
    // An image extension decides whatever the bytes are, so that a damaged PNG is reported
    // as a bad image, not as text that is not UTF-8.
    let image_ext = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| ["png", "pgm"].iter().any(|x| e.eq_ignore_ascii_case(x)));
    if image_ext
        || bytes.starts_with(b"\x89PNG")
        || bytes.starts_with(b"P5")
        || bytes.starts_with(b"P2")
    {
        return read_mask(path, &name, opts);
    }
    let Ok(text) = std::str::from_utf8(&bytes) else {
        return Err(LoadError::Syntax {
            file,
            line: 0,
            reason:
                "binary content that is neither a PNG nor a PGM mask, nor a text grid or polygon"
                    .into(),
        });
    };
    // GeoJSON opens with `{`, WKT with `P`, .pol with a digit, the benchmark format with `O`.
    let looks_like_grid = text
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with(';'))
        .is_none_or(|l| l.starts_with(['#', '.', 'S']));
    if looks_like_grid {
        return parse_text_grid(text, &file, &name, opts);
    }
    if let Some([row, col]) = opts.start {
        return Err(LoadError::Syntax {
            file,
            line: 0,
            reason: format!(
                "a start cell (row {row}, col {col}) applies to masks and text grids; a polygon's grid is centred on its own start (GeoJSON \"start\")"
            ),
        });
    }
    let env = super::read_environment(path)?;
    let start = match env.default_start() {
        Some(s) => s,
        None => crate::world::polygon::PolygonWorld::new(env.domain.clone())
            .map_err(|e| LoadError::Syntax { file: file.clone(), line: 0, reason: e.to_string() })?
            .interior_point(),
    };
    GridRoi::outer_approximation(name, &env.domain, start, opts.cell_size)
        .map_err(|source| LoadError::InvalidRoi { file, source })
}

/// Parses a text grid (see the module documentation).
///
/// # Errors
/// [`LoadError::Syntax`] at the line of an unknown character or a second `S`;
/// [`LoadError::InvalidRoi`] for an empty or disconnected region.
pub fn parse_text_grid(
    text: &str,
    file: &str,
    name: &str,
    opts: &GridOptions,
) -> Result<GridRoi, LoadError> {
    let mut cells = Vec::new();
    let mut start: Option<(Cell, usize)> = None;
    let mut row = 0i32;
    for (i, line) in text.lines().enumerate() {
        if line.trim_start().starts_with(';') {
            continue;
        }
        for (col, ch) in line.trim_end().chars().enumerate() {
            let c = [row, col as i32];
            match ch {
                '#' => cells.push(c),
                '.' | ' ' => {}
                'S' => {
                    if let Some((s, l)) = start {
                        return Err(LoadError::Syntax {
                            file: file.into(),
                            line: i + 1,
                            reason: format!(
                                "a second start cell S at column {} (the first is at row {}, column {}, line {l})",
                                col + 1,
                                s[0],
                                s[1] + 1
                            ),
                        });
                    }
                    start = Some((c, i + 1));
                    cells.push(c);
                }
                other => {
                    return Err(LoadError::Syntax {
                        file: file.into(),
                        line: i + 1,
                        reason: format!(
                            "unexpected {other:?} at column {} (use # for region, . for outside, S for the start)",
                            col + 1
                        ),
                    });
                }
            }
        }
        row += 1;
    }
    let start = match (start, opts.start, cells.first()) {
        (Some((s, line)), Some(o), _) if o != s => {
            return Err(LoadError::Syntax {
                file: file.into(),
                line,
                reason: format!(
                    "the grid's start S (row {}, col {}) and the given start (row {}, col {}) disagree; give one",
                    s[0], s[1], o[0], o[1]
                ),
            });
        }
        (Some((s, _)), _, _) | (None, Some(s), _) => s,
        (None, None, Some(&first)) => first,
        (None, None, None) => {
            return Err(LoadError::InvalidRoi {
                file: file.into(),
                source: crate::world::grid::InvalidRoi::Empty,
            });
        }
    };
    GridRoi::new(name, cells, start, opts.cell_size)
        .map_err(|source| LoadError::InvalidRoi { file: file.into(), source })
}

fn read_mask(path: &Path, name: &str, opts: &GridOptions) -> Result<GridRoi, LoadError> {
    let file = path.display().to_string();
    if opts.cell_px == 0 {
        return Err(LoadError::Syntax {
            file,
            line: 0,
            reason: "cell_px must be at least 1".into(),
        });
    }
    let img = ros_map::read_image(path)?;
    let k = opts.cell_px;
    let (rows, cols) = (img.h.div_ceil(k), img.w.div_ceil(k));
    let mut cells = Vec::new();
    for r in 0..rows {
        for c in 0..cols {
            let any = (r * k..((r + 1) * k).min(img.h)).any(|y| {
                (c * k..((c + 1) * k).min(img.w))
                    .any(|x| (img.px[y * img.w + x] >= 128) != opts.invert)
            });
            if any {
                cells.push([r as i32, c as i32]);
            }
        }
    }
    let Some(&first) = cells.first() else {
        return Err(LoadError::InvalidRoi { file, source: crate::world::grid::InvalidRoi::Empty });
    };
    let start = opts.start.unwrap_or(first);
    GridRoi::new(name, cells, start, opts.cell_size)
        .map_err(|source| LoadError::InvalidRoi { file, source })
}

/// Writes a region as a text grid (with `S` on the start cell).
pub fn to_text_grid(roi: &GridRoi) -> String {
    let [lo, hi] = roi.bounds();
    let mut out = String::new();
    for r in lo[0]..=hi[0] {
        for c in lo[1]..=hi[1] {
            out.push(if [r, c] == roi.start() {
                'S'
            } else if roi.contains([r, c]) {
                '#'
            } else {
                '.'
            });
        }
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn text_grid_round_trip() {
        let text = "; a small region\n.##.\n#S#.\n.#..\n";
        let roi = parse_text_grid(text, "t.txt", "t", &GridOptions::default()).unwrap();
        assert_eq!(roi.len(), 6);
        assert_eq!(roi.start(), [1, 1]);
        assert_eq!(to_text_grid(&roi), ".##\n#S#\n.#.\n");
    }

    #[test]
    fn errors_name_the_line_and_column() {
        let e = parse_text_grid("##\n#x\n", "bad.txt", "b", &GridOptions::default()).unwrap_err();
        assert_eq!(
            e.to_string(),
            "bad.txt:2: unexpected 'x' at column 2 (use # for region, . for outside, S for the start)"
        );
        let e = parse_text_grid("S#\n.S\n", "two.txt", "b", &GridOptions::default()).unwrap_err();
        assert!(e.to_string().starts_with("two.txt:2: a second start cell"), "{e}");
        let e = parse_text_grid("S.#\n", "gap.txt", "b", &GridOptions::default()).unwrap_err();
        assert!(e.to_string().contains("not 4-connected: cell (row 0, col 2)"), "{e}");
        let e = parse_text_grid("...\n", "empty.txt", "b", &GridOptions::default()).unwrap_err();
        assert_eq!(e.to_string(), "empty.txt: the region has no cells");
    }
}
