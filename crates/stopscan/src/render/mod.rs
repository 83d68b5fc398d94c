//! Pictures: line charts and policy images, written as SVG and PNG side by side.
//!
//! Charts are data (a [`LineChart`] is serialisable), so the CLI, the docs' figures and later
//! the Python bindings draw the same thing.

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};

use crate::kernel::tolerance::COUNT_SLACK;
use crate::strategy::corner::mdp::Cell;

mod glyphs;
mod roi;
mod scene;
use glyphs::PaddedText;
pub use roi::roi_svg;
pub use scene::{exploration_svg, scene_svg};

/// Why a picture could not be written.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// Drawing or writing failed (a missing font, an unwritable path).
    #[error("cannot draw {path}: {reason}")]
    Draw {
        /// The file.
        path: PathBuf,
        /// The backend's message.
        reason: String,
    },
    /// There is nothing to draw.
    #[error("chart {0:?} has no finite points")]
    Empty(String),
}

/// One line of a chart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Series {
    /// Legend text.
    pub label: String,
    /// `(x, y)` points in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Draw markers at the points as well as the line.
    pub markers: bool,
    /// Draw a dashed reference line (bounds) rather than a data line.
    pub dashed: bool,
}

impl Series {
    /// A plain data line.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self { label: label.into(), points, markers: false, dashed: false }
    }
    /// A data line with markers.
    #[must_use]
    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }
    /// A dashed reference line.
    #[must_use]
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
}

/// A line chart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LineChart {
    /// Caption.
    pub title: String,
    /// A second, smaller line under the caption: the parameters the chart holds fixed.
    #[serde(default, skip_serializing_if = "String::is_empty")]
    pub subtitle: String,
    /// X axis label.
    pub x_label: String,
    /// Y axis label.
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
}

const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(90, 90, 90),
];

/// The size of every chart, in pixels.
pub const CHART_SIZE: (u32, u32) = (900, 560);

/// Writes `stem.svg` and `stem.png`; returns both paths.
///
/// # Errors
/// [`RenderError`] if the chart is empty or a file cannot be drawn.
pub fn write_chart(chart: &LineChart, stem: &Path) -> Result<Vec<PathBuf>, RenderError> {
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    draw_chart(&SVGBackend::new(&svg, CHART_SIZE).into_drawing_area(), chart)
        .map_err(|reason| RenderError::Draw { path: svg.clone(), reason })?;
    draw_chart(&PaddedText(BitMapBackend::new(&png, CHART_SIZE)).into_drawing_area(), chart)
        .map_err(|reason| RenderError::Draw { path: png.clone(), reason })?;
    Ok(vec![svg, png])
}

fn bounds(chart: &LineChart) -> Option<(f64, f64, f64, f64)> {
    // Data that span less than this are flat: pad them by half their magnitude.
    const FLAT_SPAN: f64 = 1e-12;
    let pts =
        chart.series.iter().flat_map(|s| &s.points).filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    let mut any = false;
    for &(x, y) in pts {
        any = true;
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    if !any {
        return None;
    }
    let pad = |a: f64, b: f64| {
        if b - a < FLAT_SPAN { 0.5 * a.abs().max(1.0) } else { 0.04 * (b - a) }
    };
    let (px, py) = (pad(x0, x1), pad(y0, y1));
    Some((x0 - px, x1 + px, y0 - py, y1 + py))
}

/// Axis ticks on `[lo, hi]`: the multiples of the finest step `m·10^k` (m = 1, 2 or 5) that
/// gives at most `max` ticks, and the number of decimals that step needs (0 for whole steps,
/// so counts print as `5`, not `5.0`).
pub fn ticks(lo: f64, hi: f64, max: usize) -> (Vec<f64>, usize) {
    let span = (hi - lo).abs().max(f64::MIN_POSITIVE);
    let mut k = (span / max.max(1) as f64).log10().floor() as i32 - 1;
    loop {
        for m in [1.0, 2.0, 5.0] {
            let step = m * 10f64.powi(k);
            let (first, last) =
                ((lo / step - COUNT_SLACK).ceil(), (hi / step + COUNT_SLACK).floor());
            if last - first + 1.0 <= max as f64 {
                let decimals = (-k).max(0) as usize;
                let ticks = (first as i64..=last as i64).map(|i| i as f64 * step).collect();
                return (ticks, decimals);
            }
        }
        k += 1;
    }
}

/// A tick label with a fixed number of decimals (never `-0`).
pub fn tick_label(v: f64, decimals: usize) -> String {
    let s = format!("{v:.decimals$}");
    if s.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') {
        s.trim_start_matches('-').to_string()
    } else {
        s
    }
}

/// A rectangle in pixels, `left ≤ x ≤ right`, `top ≤ y ≤ bottom`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PixelBox {
    /// Left edge.
    pub left: f64,
    /// Top edge.
    pub top: f64,
    /// Right edge.
    pub right: f64,
    /// Bottom edge.
    pub bottom: f64,
}

impl PixelBox {
    /// Whether the segment from `a` to `b` meets the box (Liang–Barsky clipping).
    pub fn meets_segment(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut t0, mut t1) = (0.0f64, 1.0f64);
        for (p, q) in [
            (-dx, a.0 - self.left),
            (dx, self.right - a.0),
            (-dy, a.1 - self.top),
            (dy, self.bottom - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
                if t0 > t1 {
                    return false;
                }
            }
        }
        true
    }

    /// Whether any line (a polyline of pixel points; one point is a marker) comes within
    /// `clear` pixels of the box.
    pub fn meets_any(&self, lines: &[Vec<(f64, f64)>], clear: f64) -> bool {
        let grown = Self {
            left: self.left - clear,
            top: self.top - clear,
            right: self.right + clear,
            bottom: self.bottom + clear,
        };
        lines.iter().any(|l| match l.as_slice() {
            [] => false,
            [p] => grown.meets_segment(*p, *p),
            l => l.windows(2).any(|w| grown.meets_segment(w[0], w[1])),
        })
    }
}

/// Space kept between the legend box and any data line or marker, in pixels (lines are 2 px
/// wide, markers have a 3 px radius).
pub const LEGEND_CLEARANCE: f64 = 5.0;
/// The legend box's distance from the plotting area's edges, in pixels.
const LEGEND_INSET: f64 = 8.0;

/// Where the legend box (`size` pixels) goes in a plotting area of `plot` pixels: the first
/// corner (upper right, upper left, lower right, lower left) where no data line or marker
/// (`lines`, in pixels relative to the plotting area) comes within [`LEGEND_CLEARANCE`] of
/// it. `None` when every corner is taken.
pub fn legend_corner(
    plot: (f64, f64),
    size: (f64, f64),
    lines: &[Vec<(f64, f64)>],
) -> Option<PixelBox> {
    let (w, h) = size;
    let (left, right) = (LEGEND_INSET, plot.0 - LEGEND_INSET - w);
    let (top, bottom) = (LEGEND_INSET, plot.1 - LEGEND_INSET - h);
    [(right, top), (left, top), (right, bottom), (left, bottom)]
        .into_iter()
        .map(|(x, y)| PixelBox { left: x, top: y, right: x + w, bottom: y + h })
        .find(|b| b.left >= 0.0 && b.top >= 0.0 && !b.meets_any(lines, LEGEND_CLEARANCE))
}

/// How a chart is laid out: axis ranges and ticks, its data in pixels and the legend box.
#[derive(Debug, Clone, PartialEq)]
pub struct ChartLayout {
    /// X range.
    pub x: (f64, f64),
    /// Y range (raised above the data when no corner was free for the legend).
    pub y: (f64, f64),
    /// X ticks and their decimals.
    pub x_ticks: (Vec<f64>, usize),
    /// Y ticks and their decimals.
    pub y_ticks: (Vec<f64>, usize),
    /// Every series (one polyline, and one single-point line per marker), in pixels relative
    /// to the plotting area.
    pub lines: Vec<Vec<(f64, f64)>>,
    /// The plotting area's size in pixels.
    pub plot: (f64, f64),
    /// The legend box, relative to the plotting area.
    pub legend: PixelBox,
}

const TITLE_PX: u32 = 22;
const SUBTITLE_PX: u32 = 14;
const LEGEND_PX: u32 = 13;
/// Legend geometry: padding inside the box, line sample length, gaps.
const LEGEND_PAD: i32 = 8;
const LEGEND_SAMPLE: i32 = 24;
const LEGEND_ROW_GAP: i32 = 4;

/// The caption and the subtitle; returns the area below them.
fn titled<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<DrawingArea<DB, Shift>, String> {
    let area = root.titled(&chart.title, ("sans-serif", TITLE_PX)).map_err(|e| e.to_string())?;
    if chart.subtitle.is_empty() {
        Ok(area)
    } else {
        area.titled(&chart.subtitle, ("sans-serif", SUBTITLE_PX)).map_err(|e| e.to_string())
    }
}

/// Size of the legend box and the height of one row, in pixels.
fn legend_size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<((f64, f64), i32), String> {
    let font: TextStyle = ("sans-serif", LEGEND_PX).into_font().into();
    let (mut w, mut row) = (0u32, LEGEND_PX);
    for s in &chart.series {
        let (tw, th) = area.estimate_text_size(&s.label, &font).map_err(|e| e.to_string())?;
        w = w.max(tw);
        row = row.max(th);
    }
    let n = chart.series.len() as i32;
    let width = 2 * LEGEND_PAD + LEGEND_SAMPLE + 8 + w as i32;
    let height = 2 * LEGEND_PAD + n * row as i32 + (n - 1).max(0) * LEGEND_ROW_GAP;
    Ok(((f64::from(width), f64::from(height)), row as i32))
}

/// A linear axis that puts its ticks where [`ticks`] says (plotters would pick its own).
/// Labels come from the chart's formatter, never from `DefaultFormatting`.
struct Axis {
    inner: RangedCoordf64,
    ticks: Vec<f64>,
}

impl Axis {
    fn new(range: (f64, f64), ticks: &[f64]) -> Self {
        Self { inner: (range.0..range.1).into(), ticks: ticks.to_vec() }
    }
}

impl Ranged for Axis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.inner.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        // No light mesh lines; bold lines and labels at the ticks.
        if hint.weight().allow_light_points() { Vec::new() } else { self.ticks.clone() }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.inner.range()
    }
}

fn build<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    x: (f64, f64),
    y: (f64, f64),
    xt: &[f64],
    yt: &[f64],
) -> Result<ChartContext<'a, DB, Cartesian2d<Axis, Axis>>, String> {
    ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(Axis::new(x, xt), Axis::new(y, yt))
        .map_err(|e| e.to_string())
}

fn finite(s: &Series) -> Vec<(f64, f64)> {
    s.points.iter().copied().filter(|p| p.0.is_finite() && p.1.is_finite()).collect()
}

/// Lays a chart out on `area` (the space below its titles): ticks, data in pixels, and a
/// legend box that no data line or marker comes near. When no corner is free, the y range
/// is raised until the upper right corner is.
fn layout<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<ChartLayout, String> {
    let (x0, x1, y0, mut y1) =
        bounds(chart).ok_or_else(|| format!("chart {:?} has no finite points", chart.title))?;
    let (size, _) = legend_size(area, chart)?;
    let x_ticks = ticks(x0, x1, 10);
    for _ in 0..4 {
        let y_ticks = ticks(y0, y1, 8);
        let ctx = build(area, (x0, x1), (y0, y1), &x_ticks.0, &y_ticks.0)?;
        let base = ctx.plotting_area().get_base_pixel();
        let (pw, ph) = ctx.plotting_area().dim_in_pixel();
        let px = |p: &(f64, f64)| {
            let (x, y) = ctx.backend_coord(p);
            (f64::from(x - base.0), f64::from(y - base.1))
        };
        let mut lines = Vec::new();
        for s in &chart.series {
            let pts = finite(s);
            lines.push(pts.iter().map(px).collect::<Vec<_>>());
            if s.markers {
                lines.extend(pts.iter().map(|p| vec![px(p)]));
            }
        }
        let plot = (f64::from(pw), f64::from(ph));
        if let Some(legend) = legend_corner(plot, size, &lines) {
            return Ok(ChartLayout {
                x: (x0, x1),
                y: (y0, y1),
                x_ticks,
                y_ticks,
                lines,
                plot,
                legend,
            });
        }
        // Headroom: the top `need` pixels of the plot must hold no data. The current top
        // maps to pixel 0; raising it by e maps it to plot_h·e/(span + e).
        let need = LEGEND_INSET + size.1 + LEGEND_CLEARANCE + 2.0;
        if need >= plot.1 {
            break;
        }
        y1 += need * (y1 - y0) / (plot.1 - need);
    }
    Err(format!("chart {:?}: no room for the legend", chart.title))
}

/// The layout [`write_chart`] uses, computed on an in-memory SVG of [`CHART_SIZE`].
///
/// # Errors
/// [`RenderError`] if the chart is empty or its legend does not fit.
pub fn chart_layout(chart: &LineChart) -> Result<ChartLayout, RenderError> {
    let mut svg = String::new();
    let root = SVGBackend::with_string(&mut svg, CHART_SIZE).into_drawing_area();
    let area = titled(&root, chart)
        .map_err(|r| RenderError::Draw { path: "(memory)".into(), reason: r })?;
    layout(&area, chart).map_err(|r| RenderError::Draw { path: "(memory)".into(), reason: r })
}

fn draw_chart<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &LineChart,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let area = titled(root, chart)?;
    let l = layout(&area, chart)?;
    let mut ctx = build(&area, l.x, l.y, &l.x_ticks.0, &l.y_ticks.0)?;
    let (xd, yd) = (l.x_ticks.1, l.y_ticks.1);
    ctx.configure_mesh()
        .x_desc(&chart.x_label)
        .y_desc(&chart.y_label)
        .x_label_formatter(&|v| tick_label(*v, xd))
        .y_label_formatter(&|v| tick_label(*v, yd))
        .light_line_style(WHITE.mix(0.0))
        .draw()
        .map_err(|e| e.to_string())?;
    for (k, s) in chart.series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let pts = finite(s);
        let style = color.stroke_width(if s.dashed { 1 } else { 2 });
        if s.dashed {
            ctx.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))
                .map_err(|e| e.to_string())?;
        } else {
            ctx.draw_series(LineSeries::new(pts.clone(), style)).map_err(|e| e.to_string())?;
        }
        if s.markers {
            ctx.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))
                .map_err(|e| e.to_string())?;
        }
    }
    draw_legend(&ctx.plotting_area().strip_coord_spec(), chart, l.legend)?;
    root.present().map_err(|e| e.to_string())
}

/// The legend: an opaque box with one row per series (its line sample, marker and label).
fn draw_legend<DB: DrawingBackend>(
    plot: &DrawingArea<DB, Shift>,
    chart: &LineChart,
    b: PixelBox,
) -> Result<(), String> {
    let e = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let (_, row) = legend_size(plot, chart)?;
    let (left, top) = (b.left.round() as i32, b.top.round() as i32);
    let corners = [(left, top), (b.right.round() as i32, b.bottom.round() as i32)];
    plot.draw(&Rectangle::new(corners, WHITE.filled())).map_err(e)?;
    plot.draw(&Rectangle::new(corners, BLACK.stroke_width(1))).map_err(e)?;
    let font = ("sans-serif", LEGEND_PX).into_font();
    for (k, s) in chart.series.iter().enumerate() {
        let color = PALETTE[k % PALETTE.len()];
        let y = top + LEGEND_PAD + k as i32 * (row + LEGEND_ROW_GAP) + row / 2;
        let x = left + LEGEND_PAD;
        if s.dashed {
            for (a, c) in [(0, 7), (10, 17), (20, LEGEND_SAMPLE)] {
                plot.draw(&PathElement::new(vec![(x + a, y), (x + c, y)], color.stroke_width(1)))
                    .map_err(e)?;
            }
        } else {
            plot.draw(&PathElement::new(
                vec![(x, y), (x + LEGEND_SAMPLE, y)],
                color.stroke_width(2),
            ))
            .map_err(e)?;
        }
        if s.markers {
            plot.draw(&Circle::new((x + LEGEND_SAMPLE / 2, y), 3, color.filled())).map_err(e)?;
        }
        let style = font.clone().color(&BLACK).pos(Pos::new(HPos::Left, VPos::Center));
        plot.draw(&Text::new(s.label.clone(), (x + LEGEND_SAMPLE + 8, y), style)).map_err(e)?;
    }
    Ok(())
}

/// Writes a policy image like the corner paper's Fig. 4 / Fig. 6 as `stem.svg` and `stem.png`.
/// For MDP2, row `i` (downwards) is the robot's stop and column `j` the last scan's stop; for
/// MDP1 (two rows) the columns are stops and the rows `s_i` and `s'_i`. Blue is inaccessible,
/// green reconstruct, red move.
///
/// # Errors
/// [`RenderError`] if the image is empty or cannot be drawn.
pub fn write_policy_image(
    rows: &[Vec<Cell>],
    title: &str,
    stem: &Path,
) -> Result<Vec<PathBuf>, RenderError> {
    if rows.is_empty() || rows[0].is_empty() {
        return Err(RenderError::Empty(title.into()));
    }
    let svg = stem.with_extension("svg");
    let png = stem.with_extension("png");
    let side = 560u32;
    let h = if rows.len() <= 2 { 220 } else { side + 60 };
    draw_policy(&SVGBackend::new(&svg, (side + 80, h)).into_drawing_area(), rows, title)
        .map_err(|reason| RenderError::Draw { path: svg.clone(), reason })?;
    draw_policy(
        &PaddedText(BitMapBackend::new(&png, (side + 80, h))).into_drawing_area(),
        rows,
        title,
    )
    .map_err(|reason| RenderError::Draw { path: png.clone(), reason })?;
    Ok(vec![svg, png])
}

fn draw_policy<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    rows: &[Vec<Cell>],
    title: &str,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (n_rows, n_cols) = (rows.len() as f64, rows[0].len() as f64);
    let mut ctx = ChartBuilder::on(root)
        .caption(title, ("sans-serif", 15))
        .margin(10)
        .x_label_area_size(48)
        .y_label_area_size(44)
        .build_cartesian_2d(0.0..n_cols, n_rows..0.0)
        .map_err(|e| e.to_string())?;
    ctx.configure_mesh()
        .disable_mesh()
        .x_desc(if rows.len() <= 2 {
            "stop i   (green: reconstruct, red: move, blue: no such state)"
        } else {
            "last scan stop j   (green: reconstruct, red: move, blue: no such state)"
        })
        .y_desc(if rows.len() <= 2 { "top: s_i, bottom: s'_i" } else { "current stop i" })
        .y_labels(if rows.len() <= 2 { 3 } else { 10 })
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()
        .map_err(|e| e.to_string())?;
    let cells = rows.iter().enumerate().flat_map(|(i, row)| {
        row.iter().enumerate().map(move |(j, c)| {
            let color = match c {
                Cell::Inaccessible => RGBColor(70, 110, 200),
                Cell::Move => RGBColor(200, 50, 50),
                Cell::Reconstruct => RGBColor(60, 170, 70),
            };
            Rectangle::new([(j as f64, i as f64), (j as f64 + 1.0, i as f64 + 1.0)], color.filled())
        })
    });
    ctx.draw_series(cells).map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_axes_print_whole_numbers() {
        // Fig. 7 (c): 1 to 32 robots, padded by 4%.
        let (t, d) = ticks(1.0 - 1.24, 32.0 + 1.24, 10);
        assert_eq!(d, 0);
        let labels: Vec<String> = t.iter().map(|&v| tick_label(v, d)).collect();
        assert_eq!(labels, ["0", "5", "10", "15", "20", "25", "30"]);
        // Cells 40–400.
        let (t, d) = ticks(25.6, 414.4, 10);
        assert_eq!((t[0], d), (50.0, 0));
        assert!(t.iter().all(|v| !tick_label(*v, d).contains('.')));
        // A fractional axis keeps one decimal throughout: 1.5, 2.0, … 6.0.
        let (t, d) = ticks(1.32, 6.18, 10);
        assert_eq!(d, 1);
        assert_eq!(tick_label(t[0], d), "1.5");
        assert_eq!(tick_label(t[1], d), "2.0");
        assert!(t.len() <= 10);
        // Sign of zero and tiny steps.
        assert_eq!(tick_label(-0.0, 0), "0");
        assert_eq!(tick_label(-1e-17, 2), "0.00");
        let (t, d) = ticks(0.0, 0.003, 8);
        assert_eq!(d, 4);
        assert_eq!(tick_label(t[1], d), "0.0005");
    }

    #[test]
    fn legend_takes_the_first_free_corner() {
        let plot = (800.0, 400.0);
        let size = (150.0, 80.0);
        // A flat line along the top covers both upper corners.
        let top = vec![(0.0, 20.0), (800.0, 20.0)];
        let b = legend_corner(plot, size, std::slice::from_ref(&top)).unwrap();
        assert_eq!((b.left, b.top), (800.0 - 8.0 - 150.0, 400.0 - 8.0 - 80.0), "lower right");
        assert!(!b.meets_any(std::slice::from_ref(&top), LEGEND_CLEARANCE));
        // A marker alone in the lower right corner moves it to the lower left.
        let marker = vec![(700.0, 350.0)];
        let b = legend_corner(plot, size, &[top.clone(), marker]).unwrap();
        assert_eq!((b.left, b.top), (8.0, 312.0));
        // A diagonal through the whole plot leaves the other two corners.
        let diag = vec![(0.0, 0.0), (800.0, 400.0)];
        let b = legend_corner(plot, size, std::slice::from_ref(&diag)).unwrap();
        assert_eq!((b.left, b.top), (642.0, 8.0));
        // Every corner taken.
        let bottom = vec![(0.0, 380.0), (800.0, 380.0)];
        assert!(legend_corner(plot, size, &[top, bottom]).is_none());
    }

    #[test]
    fn segments_meet_boxes_exactly() {
        let b = PixelBox { left: 10.0, top: 10.0, right: 20.0, bottom: 20.0 };
        assert!(b.meets_segment((0.0, 15.0), (30.0, 15.0)));
        assert!(b.meets_segment((15.0, 15.0), (15.0, 15.0)));
        assert!(!b.meets_segment((0.0, 0.0), (9.0, 30.0)));
        assert!(b.meets_segment((0.0, 0.0), (30.0, 30.0)));
        assert!(!b.meets_segment((21.0, 0.0), (40.0, 30.0)));
        assert!(!b.meets_any(&[vec![(25.0, 15.0)]], 4.0));
        assert!(b.meets_any(&[vec![(23.0, 15.0)]], 4.0));
    }

    /// Every chart the reproductions and the demo draw: the legend box stays clear of every
    /// line and marker, and charts with fixed parameters say so under the title.
    #[test]
    fn legends_never_cover_data_in_the_produced_charts() {
        let mut charts = Vec::new();
        for id in ["corner-fig-7", "corner-fig-8", "roi-fig-7"] {
            charts.extend(crate::experiment::reproduce(id, 2, 1).unwrap().charts);
        }
        charts.push(("demo".into(), crate::experiment::corner::demo().unwrap().chart));
        assert!(charts.len() >= 7);
        for (name, chart) in &charts {
            let l = chart_layout(chart).unwrap();
            assert!(!l.legend.meets_any(&l.lines, LEGEND_CLEARANCE), "{name}");
            assert!(l.legend.left >= 0.0 && l.legend.right <= l.plot.0, "{name}");
            assert!(l.legend.top >= 0.0 && l.legend.bottom <= l.plot.1, "{name}");
            if name.starts_with("roi-fig-7") || name.starts_with("corner-fig") {
                assert!(!chart.subtitle.is_empty(), "{name} states no fixed parameters");
            }
        }
    }
}
