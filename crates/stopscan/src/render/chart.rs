//! Line charts: the serialisable [`LineChart`] and its drawing with plotters, laid out so
//! that the legend covers no data ([`super::layout`]).

use std::path::{Path, PathBuf};

use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::drawing::DrawingAreaErrorKind;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde::{Deserialize, Serialize};

use super::RenderError;
use super::glyphs::PaddedText;
use super::layout::{
    ChartLayout, LEGEND_CLEARANCE, LEGEND_INSET, PixelBox, PixelSize, legend_corner, tick_label,
    ticks,
};

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
) -> Result<(PixelSize, i32), String> {
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
    Ok((PixelSize { width: f64::from(width), height: f64::from(height) }, row as i32))
}

/// A linear axis that puts its ticks where [`ticks`] says (plotters would pick its own).
/// Labels come from the chart's formatter, never from `DefaultFormatting`.
struct Axis {
    inner: RangedCoordf64,
    ticks: Vec<f64>,
}

impl Axis {
    fn new(range: std::ops::Range<f64>, ticks: &[f64]) -> Self {
        Self { inner: range.into(), ticks: ticks.to_vec() }
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
    x: std::ops::Range<f64>,
    y: std::ops::Range<f64>,
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
        let ctx = build(area, x0..x1, y0..y1, &x_ticks.values, &y_ticks.values)?;
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
        let plot = PixelSize { width: f64::from(pw), height: f64::from(ph) };
        if let Some(legend) = legend_corner(plot, size, &lines) {
            return Ok(ChartLayout { x: x0..x1, y: y0..y1, x_ticks, y_ticks, lines, plot, legend });
        }
        // Headroom: the top `need` pixels of the plot must hold no data. The current top
        // maps to pixel 0; raising it by e maps it to plot_h·e/(span + e).
        let need = LEGEND_INSET + size.height + LEGEND_CLEARANCE + 2.0;
        if need >= plot.height {
            break;
        }
        y1 += need * (y1 - y0) / (plot.height - need);
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
    let mut ctx = build(&area, l.x.clone(), l.y.clone(), &l.x_ticks.values, &l.y_ticks.values)?;
    let (xd, yd) = (l.x_ticks.decimals, l.y_ticks.decimals);
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
