//! SVG scenes of a domain with visibility regions, written by hand (exact coordinates, no
//! rasterisation, deterministic text).

use std::fmt::Write;

use super::labels::{self, LabelSpace, Marker, Placed};
use super::layout::PixelBox;
use crate::algorithm::visibility::{BoundaryPiece, VisibilityRegion};
use crate::geometry::Domain;
use crate::kernel::Point;

/// The smallest width or height a scene is scaled from (metres), so that a degenerate domain
/// does not divide by zero.
const MIN_EXTENT: f64 = 1e-9;

/// An SVG picture of the domain (free space white, holes grey) with each region translucent,
/// its windows dashed and its viewpoint marked.
pub fn scene_svg(domain: &Domain, regions: &[VisibilityRegion]) -> String {
    const COLOURS: [&str; 6] = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b"];
    let [lo, hi] = domain.bounds();
    let (w, h) = ((hi[0] - lo[0]).max(MIN_EXTENT), (hi[1] - lo[1]).max(MIN_EXTENT));
    let scale = 800.0 / w.max(h);
    let (pw, ph) = (w * scale + 20.0, h * scale + 20.0);
    let x = |v: f64| 10.0 + (v - lo[0]) * scale;
    let y = |v: f64| 10.0 + (hi[1] - v) * scale;
    let path = |ring: &[[f64; 2]]| {
        let mut s = String::new();
        for (i, p) in ring.iter().enumerate() {
            let _ = write!(s, "{}{:.3},{:.3} ", if i == 0 { "M" } else { "L" }, x(p[0]), y(p[1]));
        }
        s.push('Z');
        s
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{pw:.0}" height="{ph:.0}" viewBox="0 0 {pw:.3} {ph:.3}">"#
    );
    let _ = writeln!(out, r##"<rect width="100%" height="100%" fill="#b8b8b8"/>"##);
    let mut d = path(domain.outer());
    for hole in domain.holes() {
        d.push(' ');
        d.push_str(&path(hole));
    }
    let _ = writeln!(
        out,
        r##"<path d="{d}" fill="#ffffff" fill-rule="evenodd" stroke="#222" stroke-width="1"/>"##
    );
    for (k, r) in regions.iter().enumerate() {
        let c = COLOURS[k % COLOURS.len()];
        let _ = writeln!(
            out,
            r#"<path d="{}" fill="{c}" fill-opacity="0.25" stroke="{c}" stroke-width="1"/>"#,
            path(&r.polygon)
        );
        for b in r.windows() {
            if let BoundaryPiece::Window { reflex, far, .. } = b {
                let _ = writeln!(
                    out,
                    r#"<line x1="{:.3}" y1="{:.3}" x2="{:.3}" y2="{:.3}" stroke="{c}" stroke-width="1.5" stroke-dasharray="4 3"/>"#,
                    x(reflex[0]),
                    y(reflex[1]),
                    x(far[0]),
                    y(far[1])
                );
            }
        }
        let _ = writeln!(
            out,
            r##"<circle cx="{:.3}" cy="{:.3}" r="4" fill="{c}" stroke="#000"/>"##,
            x(r.viewpoint[0]),
            y(r.viewpoint[1])
        );
    }
    out.push_str("</svg>\n");
    out
}

/// The longer side of an exploration picture's map, in pixels. Every other size in the
/// picture (margins, markers, lines, text) is a fixed fraction of it, so the text keeps its
/// size against the map whatever the map measures in metres, and the picture scales whole.
const MAP_PX: f64 = 1000.0;
/// The margin around the map and below the legend.
const MARGIN: f64 = MAP_PX / 80.0;
/// The scan numbers' font size.
const LABEL_FONT: f64 = MAP_PX / 80.0;
/// The legend's font size.
const LEGEND_FONT: f64 = MAP_PX / 60.0;
/// A scan marker's radius, and its outline's width.
const MARKER_RADIUS: f64 = MAP_PX / 220.0;
const MARKER_STROKE: f64 = MAP_PX / 1000.0;
/// The path's width, and the walls'.
const PATH_WIDTH: f64 = MAP_PX / 800.0;
const WALL_WIDTH: f64 = MAP_PX / 1000.0;
/// The least gap between a scan number and another number or a marker.
const LABEL_CLEARANCE: f64 = MAP_PX / 1000.0;
/// The opacity of the layer that tints the free space by the scan that first saw it.
const TINT_OPACITY: f64 = 0.3;
/// The configuration space: a crimson off the order ramp, a faint fill and a thin outline.
const CSPACE_COLOUR: &str = "#c2185b";
const CSPACE_FILL_OPACITY: f64 = 0.1;
const CSPACE_STROKE_OPACITY: f64 = 0.7;
const FREE_COLOUR: &str = "#ffffff";
const OBSTACLE_COLOUR: &str = "#b8b8b8";
const WALL_COLOUR: &str = "#222222";
const PATH_COLOUR: &str = "#111111";
/// The id of the order ramp's gradient (the legend's swatches).
const RAMP_ID: &str = "stopscan-scan-order";

/// The order ramp (viridis, sampled at tenths): dark purple for the first scan to yellow for
/// the last; perceptually uniform and readable in grey.
const RAMP: [[u8; 3]; 11] = [
    [0x44, 0x01, 0x54],
    [0x48, 0x24, 0x75],
    [0x41, 0x44, 0x87],
    [0x35, 0x5f, 0x8d],
    [0x2a, 0x78, 0x8e],
    [0x21, 0x91, 0x8c],
    [0x22, 0xa8, 0x84],
    [0x44, 0xbf, 0x70],
    [0x7a, 0xd1, 0x51],
    [0xbd, 0xdf, 0x26],
    [0xfd, 0xe7, 0x25],
];

/// The order ramp at `t` in [0, 1] (clamped), interpolated linearly between its samples, as
/// `#rrggbb`.
fn ramp(t: f64) -> String {
    let s = t.clamp(0.0, 1.0) * (RAMP.len() - 1) as f64;
    let i = (s.floor() as usize).min(RAMP.len() - 2);
    let f = s - i as f64;
    let (a, b) = (RAMP[i], RAMP[i + 1]);
    let c = |j: usize| (f64::from(a[j]) + (f64::from(b[j]) - f64::from(a[j])) * f).round() as u8;
    format!("#{:02x}{:02x}{:02x}", c(0), c(1), c(2))
}

/// The colour of scan `k` (0-based) of `n` on the order ramp.
fn order_colour(k: usize, n: usize) -> String {
    ramp(if n <= 1 { 0.0 } else { k as f64 / (n - 1) as f64 })
}

/// A pixel coordinate as SVG text: two decimals, trailing zeros dropped, never `-0`.
struct Px(f64);

impl std::fmt::Display for Px {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let s = format!("{:.2}", self.0);
        let s = s.trim_end_matches('0').trim_end_matches('.');
        f.write_str(if s == "-0" { "0" } else { s })
    }
}

/// Where the map goes: metres to pixels, y up to y down.
struct MapFrame {
    lo: Point,
    hi: Point,
    scale: f64,
}

impl MapFrame {
    fn x(&self, v: f64) -> f64 {
        MARGIN + (v - self.lo[0]) * self.scale
    }
    fn y(&self, v: f64) -> f64 {
        MARGIN + (self.hi[1] - v) * self.scale
    }
    fn point(&self, p: Point) -> (f64, f64) {
        (self.x(p[0]), self.y(p[1]))
    }
    /// The map area (the map and its margins).
    fn area(&self) -> PixelBox {
        PixelBox {
            left: 0.0,
            top: 0.0,
            right: self.x(self.hi[0]) + MARGIN,
            bottom: self.y(self.lo[1]) + MARGIN,
        }
    }
    /// Appends a closed ring to path data `d` (`M x,y x,y … Z`).
    fn ring(&self, d: &mut String, ring: &[Point]) {
        for (i, &p) in ring.iter().enumerate() {
            let (x, y) = self.point(p);
            let _ = write!(d, "{}{},{}", if i == 0 { "M" } else { " " }, Px(x), Px(y));
        }
        if !ring.is_empty() {
            d.push('Z');
        }
    }
    /// Path data of several rings (drawn with `fill-rule="evenodd"`, holes are holes).
    fn rings<'a>(&self, rings: impl IntoIterator<Item = &'a Vec<Point>>) -> String {
        let mut d = String::new();
        for r in rings {
            self.ring(&mut d, r);
        }
        d
    }
}

/// Layers of an exploration picture that not every caller has; `Default` is none of them.
#[derive(Debug, Clone, Copy, Default)]
pub struct SceneExtras<'a> {
    /// The robot's configuration space (where its reference point may stand), in the
    /// domain's coordinates: its components, each a list of rings, the outer boundary first
    /// and then its holes (either orientation). Drawn faintly over the tint and beneath the
    /// path, and named in the legend, when given.
    pub cspace: Option<&'a [Vec<Vec<Point>>]>,
    /// Which scans were relays (taken on the way to place the robot, from raw scans), in the
    /// order of the regions: drawn as diamonds, and named in the legend, when any was.
    pub relays: Option<&'a [bool]>,
}

/// A legend entry's swatch.
enum Swatch {
    /// A filled rectangle: fill, fill opacity, outline (none when `None`).
    Fill(String, f64, Option<(&'static str, f64)>),
    /// The path's line.
    Line,
    /// The start's square.
    Start,
    /// A scan marker, in the ramp's middle colour.
    Marker,
    /// A relay's marker (a diamond), in the ramp's middle colour.
    Relay,
    /// The order ramp from 1 to the number given, labelled at both ends.
    Ramp(usize),
}

/// A legend entry: a swatch and its words.
struct Entry {
    swatch: Swatch,
    text: String,
}

/// Legend sizes, in ems of [`LEGEND_FONT`].
mod legend_em {
    /// A character's width as the legend's layout reckons it (wider than the average of
    /// common sans-serif faces, so that text never outruns its box).
    pub(super) const CHAR: f64 = 0.62;
    pub(super) const SWATCH_W: f64 = 1.8;
    pub(super) const SWATCH_H: f64 = 0.9;
    pub(super) const RAMP_W: f64 = 7.0;
    /// Between a swatch and its words, and between the ramp and its end labels.
    pub(super) const GAP: f64 = 0.45;
    /// Between entries in a row.
    pub(super) const COLUMN_GAP: f64 = 1.6;
    pub(super) const ROW: f64 = 1.6;
    pub(super) const PAD: f64 = 0.7;
}

fn text_em(text: &str) -> f64 {
    text.chars().count() as f64 * legend_em::CHAR
}

impl Entry {
    fn new(swatch: Swatch, text: impl Into<String>) -> Self {
        Self { swatch, text: text.into() }
    }

    /// The swatch's width in ems.
    fn swatch_em(&self) -> f64 {
        match self.swatch {
            Swatch::Ramp(n) => {
                text_em("1") + text_em(&n.to_string()) + legend_em::RAMP_W + 2.0 * legend_em::GAP
            }
            _ => legend_em::SWATCH_W,
        }
    }

    /// The entry's width in ems.
    fn width_em(&self) -> f64 {
        self.swatch_em() + legend_em::GAP + text_em(&self.text)
    }

    /// Draws the entry with its swatch's left edge at `x` and its row's middle at `y`.
    fn draw(&self, out: &mut String, x: f64, y: f64) {
        let em = LEGEND_FONT;
        let (sw, sh) = (legend_em::SWATCH_W * em, legend_em::SWATCH_H * em);
        let top = y - sh / 2.0;
        let baseline = y + 0.35 * em;
        match &self.swatch {
            Swatch::Fill(fill, opacity, outline) => {
                let stroke = match outline {
                    Some((c, o)) => format!(r#" stroke="{c}" stroke-opacity="{o}""#),
                    None => String::new(),
                };
                let _ = writeln!(
                    out,
                    r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" fill-opacity="{opacity}"{stroke}/>"#,
                    Px(x),
                    Px(top),
                    Px(sw),
                    Px(sh)
                );
            }
            Swatch::Line => {
                let _ = writeln!(
                    out,
                    r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{PATH_COLOUR}" stroke-width="{}"/>"#,
                    Px(x),
                    Px(y),
                    Px(x + sw),
                    Px(y),
                    Px(PATH_WIDTH)
                );
            }
            Swatch::Start => {
                let side = start_side();
                let _ = writeln!(
                    out,
                    r##"<rect x="{}" y="{}" width="{s}" height="{s}" fill="none" stroke="#000" stroke-width="{}"/>"##,
                    Px(x + sw / 2.0 - side / 2.0),
                    Px(y - side / 2.0),
                    Px(2.0 * MARKER_STROKE),
                    s = Px(side)
                );
            }
            Swatch::Marker => {
                let _ = writeln!(
                    out,
                    r##"<circle cx="{}" cy="{}" r="{}" fill="{}" stroke="#000" stroke-width="{}"/>"##,
                    Px(x + sw / 2.0),
                    Px(y),
                    Px(MARKER_RADIUS),
                    ramp(0.5),
                    Px(MARKER_STROKE)
                );
            }
            Swatch::Relay => {
                let _ = writeln!(
                    out,
                    r##"<path d="{}" fill="{}" stroke="#000" stroke-width="{}"/>"##,
                    diamond(x + sw / 2.0, y),
                    ramp(0.5),
                    Px(MARKER_STROKE)
                );
            }
            Swatch::Ramp(n) => {
                let bar = x + (text_em("1") + legend_em::GAP) * em;
                let last = n.to_string();
                let _ = writeln!(
                    out,
                    r#"<text x="{}" y="{}">1</text><rect x="{}" y="{}" width="{}" height="{}" fill="url(#{RAMP_ID})" stroke="{WALL_COLOUR}" stroke-width="0.5"/><text x="{}" y="{}">{last}</text>"#,
                    Px(x),
                    Px(baseline),
                    Px(bar),
                    Px(top),
                    Px(legend_em::RAMP_W * em),
                    Px(sh),
                    Px(bar + (legend_em::RAMP_W + legend_em::GAP) * em),
                    Px(baseline)
                );
            }
        }
        let _ = writeln!(
            out,
            r#"<text x="{}" y="{}">{}</text>"#,
            Px(x + (self.swatch_em() + legend_em::GAP) * em),
            Px(baseline),
            self.text
        );
    }
}

/// The start square's side.
fn start_side() -> f64 {
    3.6 * MARKER_RADIUS
}

/// The legend's entries, in the order drawn.
fn legend_entries(
    scans: usize,
    numbered: usize,
    path: usize,
    cspace: bool,
    relays: usize,
) -> Vec<Entry> {
    let mut e = vec![
        Entry::new(Swatch::Fill(FREE_COLOUR.into(), 1.0, Some((WALL_COLOUR, 1.0))), "free space"),
        Entry::new(Swatch::Fill(OBSTACLE_COLOUR.into(), 1.0, None), "obstacles and outside"),
    ];
    if cspace {
        e.push(Entry::new(
            Swatch::Fill(
                CSPACE_COLOUR.into(),
                CSPACE_FILL_OPACITY,
                Some((CSPACE_COLOUR, CSPACE_STROKE_OPACITY)),
            ),
            "configuration space",
        ));
    }
    if scans > 0 {
        e.push(Entry::new(
            Swatch::Fill(format!("url(#{RAMP_ID})"), TINT_OPACITY, None),
            "scan regions: tinted by the first scan to see them",
        ));
    }
    if path > 1 {
        e.push(Entry::new(Swatch::Line, "path"));
    }
    if path > 0 {
        e.push(Entry::new(Swatch::Start, "start"));
    }
    if scans > 0 {
        e.push(Entry::new(
            Swatch::Marker,
            format!("scan points, numbered where there is room ({numbered} of {scans})"),
        ));
    }
    if relays > 0 {
        e.push(Entry::new(Swatch::Relay, format!("relays: scans to place the robot ({relays})")));
    }
    if scans > 1 {
        e.push(Entry::new(Swatch::Ramp(scans), "scan order"));
    }
    e
}

/// The legend laid out in rows no wider than `max_width` pixels (wider only for an entry
/// that alone is wider), its box's top left corner at (`left`, `top`): the middle left of
/// each entry's row, and the box.
fn legend_layout(
    entries: &[Entry],
    max_width: f64,
    left: f64,
    top: f64,
) -> (Vec<(f64, f64)>, PixelBox) {
    let em = LEGEND_FONT;
    let pad = legend_em::PAD * em;
    let (row, gap) = (legend_em::ROW * em, legend_em::COLUMN_GAP * em);
    let (mut x, mut y, mut width) = (0.0f64, 0.0f64, 0.0f64);
    let mut at = Vec::with_capacity(entries.len());
    for e in entries {
        let w = e.width_em() * em;
        if x > 0.0 && x + w > max_width {
            (x, y) = (0.0, y + row);
        }
        at.push((left + pad + x, top + pad + y + row / 2.0));
        width = width.max(x + w);
        x += w + gap;
    }
    let height = if entries.is_empty() { 0.0 } else { y + row };
    let b =
        PixelBox { left, top, right: left + width + 2.0 * pad, bottom: top + height + 2.0 * pad };
    (at, b)
}

/// An SVG of an exploration run: the domain (free space white, obstacles grey), the free space
/// tinted by the first scan to see it, the configuration space faintly when `extras` has it,
/// the path driven, the start (a square), every scan point coloured by its order (dark purple
/// first to yellow last), numbered wherever its number fits without touching another number
/// or marker, and a legend below the map saying all that.
///
/// Scan `k` (1-based) is numbered by a `<text>` in the group `<g class="scan-labels">` (font
/// size on the group, `text-anchor="middle"`, baseline at `y`) whose box is
/// `font·(0.64·digits + 0.2)` wide and spans `0.8·font` above the baseline to `0.15·font`
/// below; the numbers go greedily in scan order (a uniform grid keeps it fast for thousands
/// of scans). Deterministic: the same input gives the same bytes.
pub fn exploration_svg(
    domain: &Domain,
    regions: &[VisibilityRegion],
    path: &[Point],
    extras: SceneExtras<'_>,
) -> String {
    let [lo, hi] = domain.bounds();
    let (w, h) = ((hi[0] - lo[0]).max(MIN_EXTENT), (hi[1] - lo[1]).max(MIN_EXTENT));
    let f = MapFrame { lo, hi, scale: MAP_PX / w.max(h) };
    let map = f.area();
    let n = regions.len();
    let start = path.first().map(|&p| {
        let (x, y) = f.point(p);
        let half = start_side() / 2.0 + MARKER_STROKE;
        PixelBox { left: x - half, top: y - half, right: x + half, bottom: y + half }
    });
    let markers = scan_markers(&f, regions, start);

    // The legend is laid out for the widest count it can show, before the numbers are placed
    // (they stay out of it all the same).
    let relay = |k: usize| extras.relays.is_some_and(|r| r.get(k).copied().unwrap_or(false));
    let relays = (0..n).filter(|&k| relay(k)).count();
    let widest = legend_entries(n, n, path.len(), extras.cspace.is_some(), relays);
    let max_width = widest
        .iter()
        .map(|e| e.width_em() * LEGEND_FONT)
        .fold(map.right - 2.0 * MARGIN - 2.0 * legend_em::PAD * LEGEND_FONT, f64::max);
    let (_, legend_box) = legend_layout(&widest, max_width, MARGIN, map.bottom + MARGIN);
    let mut reserved = vec![legend_box];
    reserved.extend(start);
    let space = LabelSpace { area: map, font: LABEL_FONT, clearance: LABEL_CLEARANCE };
    let placed = labels::place_labels(&markers, &reserved, space);
    let entries = legend_entries(n, placed.len(), path.len(), extras.cspace.is_some(), relays);
    let (at, legend_box) = legend_layout(&entries, max_width, MARGIN, map.bottom + MARGIN);
    let (cw, ch) = (map.right.max(legend_box.right + MARGIN), legend_box.bottom + MARGIN);

    let mut out = String::new();
    header(&mut out, cw, ch);
    draw_map(&mut out, &f, domain, regions, extras.cspace, path);
    draw_scans(&mut out, &markers, &relay, start, &placed);
    let _ = writeln!(out, r##"<g class="legend" font-size="{}" fill="#000">"##, Px(LEGEND_FONT));
    let _ = writeln!(
        out,
        r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{FREE_COLOUR}" stroke="{WALL_COLOUR}" stroke-width="{}"/>"#,
        Px(legend_box.left),
        Px(legend_box.top),
        Px(legend_box.right - legend_box.left),
        Px(legend_box.bottom - legend_box.top),
        Px(WALL_WIDTH)
    );
    for (e, &(x, y)) in entries.iter().zip(&at) {
        e.draw(&mut out, x, y);
    }
    out.push_str("</g>\n</svg>\n");
    out
}

/// The scans' markers in pixels. A scan at the start is marked by the start's square too:
/// its number goes beside that.
fn scan_markers(
    f: &MapFrame,
    regions: &[VisibilityRegion],
    start: Option<PixelBox>,
) -> Vec<Marker> {
    regions
        .iter()
        .map(|r| {
            let (x, y) = f.point(r.viewpoint);
            let mut reach = MARKER_RADIUS + MARKER_STROKE / 2.0;
            if let Some(s) =
                start.filter(|s| s.left <= x && x <= s.right && s.top <= y && y <= s.bottom)
            {
                reach = reach.max(x - s.left).max(s.right - x).max(y - s.top).max(s.bottom - y);
            }
            Marker { x, y, reach }
        })
        .collect()
}

/// The `<svg>` element of a `width` × `height` picture, the order ramp's gradient and the
/// white background.
fn header(out: &mut String, width: f64, height: f64) {
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{}" height="{}" viewBox="0 0 {} {}" font-family="sans-serif">"#,
        width.ceil(),
        height.ceil(),
        Px(width),
        Px(height)
    );
    let _ = write!(out, r#"<defs><linearGradient id="{RAMP_ID}">"#);
    for k in 0..RAMP.len() {
        let t = k as f64 / (RAMP.len() - 1) as f64;
        let _ = write!(out, r#"<stop offset="{}" stop-color="{}"/>"#, Px(t), ramp(t));
    }
    out.push_str("</linearGradient></defs>\n");
    let _ = writeln!(out, r#"<rect width="100%" height="100%" fill="{FREE_COLOUR}"/>"#);
}

/// The map area: obstacles, free space, the tint of the first scan to see each place, the
/// configuration space and the path.
fn draw_map(
    out: &mut String,
    f: &MapFrame,
    domain: &Domain,
    regions: &[VisibilityRegion],
    cspace: Option<&[Vec<Vec<Point>>]>,
    path: &[Point],
) {
    let map = f.area();
    let _ = writeln!(
        out,
        r#"<rect width="{}" height="{}" fill="{OBSTACLE_COLOUR}"/>"#,
        Px(map.right),
        Px(map.bottom)
    );
    let _ = writeln!(
        out,
        r#"<path class="free-space" d="{}" fill="{FREE_COLOUR}" fill-rule="evenodd" stroke="{WALL_COLOUR}" stroke-width="{}"/>"#,
        f.rings(domain.rings()),
        Px(WALL_WIDTH)
    );
    // Latest first, so that each point shows the first scan that saw it.
    let _ = writeln!(out, r#"<g class="regions" opacity="{TINT_OPACITY}">"#);
    for (k, r) in regions.iter().enumerate().rev() {
        let mut d = String::new();
        f.ring(&mut d, &r.polygon);
        let _ = writeln!(out, r#"<path d="{d}" fill="{}"/>"#, order_colour(k, regions.len()));
    }
    out.push_str("</g>\n");
    if let Some(cspace) = cspace {
        let _ = writeln!(
            out,
            r#"<path class="cspace" d="{}" fill="{CSPACE_COLOUR}" fill-opacity="{CSPACE_FILL_OPACITY}" fill-rule="evenodd" stroke="{CSPACE_COLOUR}" stroke-opacity="{CSPACE_STROKE_OPACITY}" stroke-width="{}"/>"#,
            f.rings(cspace.iter().flatten()),
            Px(WALL_WIDTH)
        );
    }
    if path.len() > 1 {
        let mut pts = String::new();
        for (i, &p) in path.iter().enumerate() {
            let (x, y) = f.point(p);
            let _ = write!(pts, "{}{},{}", if i == 0 { "" } else { " " }, Px(x), Px(y));
        }
        let _ = writeln!(
            out,
            r#"<polyline class="path" points="{pts}" fill="none" stroke="{PATH_COLOUR}" stroke-width="{}" stroke-linejoin="round"/>"#,
            Px(PATH_WIDTH)
        );
    }
}

/// A diamond marker's path around `(x, y)`, as wide as a scan marker's circle.
fn diamond(x: f64, y: f64) -> String {
    let r = MARKER_RADIUS * std::f64::consts::SQRT_2;
    format!(
        "M{},{}L{},{}L{},{}L{},{}Z",
        Px(x),
        Px(y - r),
        Px(x + r),
        Px(y),
        Px(x),
        Px(y + r),
        Px(x - r),
        Px(y)
    )
}

/// The scan markers in their order's colours (a relay's a diamond, the others circles), the
/// start's square and the numbers placed.
fn draw_scans(
    out: &mut String,
    markers: &[Marker],
    relay: &dyn Fn(usize) -> bool,
    start: Option<PixelBox>,
    placed: &[Placed],
) {
    let _ =
        writeln!(out, r##"<g class="scans" stroke="#000" stroke-width="{}">"##, Px(MARKER_STROKE));
    for (k, m) in markers.iter().enumerate() {
        let colour = order_colour(k, markers.len());
        let _ = if relay(k) {
            writeln!(out, r#"<path class="relay" d="{}" fill="{colour}"/>"#, diamond(m.x, m.y))
        } else {
            writeln!(
                out,
                r#"<circle cx="{}" cy="{}" r="{}" fill="{colour}"/>"#,
                Px(m.x),
                Px(m.y),
                Px(MARKER_RADIUS)
            )
        };
    }
    out.push_str("</g>\n");
    if let Some(b) = start {
        let side = start_side();
        let _ = writeln!(
            out,
            r##"<rect class="start" x="{}" y="{}" width="{s}" height="{s}" fill="none" stroke="#000" stroke-width="{}"/>"##,
            Px((b.left + b.right - side) / 2.0),
            Px((b.top + b.bottom - side) / 2.0),
            Px(2.0 * MARKER_STROKE),
            s = Px(side)
        );
    }
    let _ = writeln!(
        out,
        r##"<g class="scan-labels" font-size="{}" text-anchor="middle" fill="#000" stroke="#fff" stroke-width="{}" stroke-linejoin="round" paint-order="stroke">"##,
        Px(LABEL_FONT),
        Px(0.25 * LABEL_FONT)
    );
    for p in placed {
        let _ = writeln!(out, r#"<text x="{}" y="{}">{}</text>"#, Px(p.x), Px(p.y), p.scan + 1);
    }
    out.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_print_compactly() {
        let p = |v: f64| Px(v).to_string();
        let printed = [p(10.0), p(100.0), p(10.5), p(10.126), p(-0.001), p(-2.5), p(0.0)];
        assert_eq!(printed, ["10", "100", "10.5", "10.13", "0", "-2.5", "0"]);
    }

    #[test]
    fn the_order_ramp_runs_from_dark_purple_to_yellow() {
        assert_eq!(order_colour(0, 400), "#440154");
        assert_eq!(order_colour(399, 400), "#fde725");
        assert_eq!(order_colour(0, 1), "#440154");
        assert_eq!(ramp(0.5), "#21918c");
        assert_eq!(ramp(0.05), "#461365", "halfway between the first two samples");
        assert_eq!((ramp(-1.0), ramp(2.0)), (ramp(0.0), ramp(1.0)));
    }
}
