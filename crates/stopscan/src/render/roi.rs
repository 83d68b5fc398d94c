//! The SVG replay of a grid mission: the region's cells (and its true shape and the map, when
//! there are), each robot's flight in its colour, and the robots moving along their flights in
//! time (SMIL animation, a fixed 20 s for the whole mission; the times come from the run
//! record).

use std::fmt::Write;

use crate::protocol::grid::Cell;
use crate::run_record::{GridRobotRecord, GridRunRecord};
use crate::world::grid::GridRoi;

/// Above this many flown cells in all, flights are not drawn (the picture would be too big).
const MAX_DRAWN_STEPS: usize = 200_000;

/// The shortest run the animation divides by (seconds): a run of no time still draws.
const MIN_DURATION: f64 = 1e-9;

/// The shortest path the key points divide by (cells): a robot that never moved still draws.
const MIN_PATH_LENGTH: f64 = 1e-12;

const COLOURS: [&str; 8] =
    ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"];

/// Picture coordinates: cell `[r, c]` is a square of side `px` centred at `(x(c), y(r))`.
struct Frame {
    lo: Cell,
    px: f64,
}

impl Frame {
    fn x(&self, c: f64) -> f64 {
        (c - f64::from(self.lo[1]) + 1.5) * self.px
    }
    fn y(&self, r: f64) -> f64 {
        (r - f64::from(self.lo[0]) + 1.5) * self.px
    }
    fn at(&self, c: Cell) -> (f64, f64) {
        (self.x(f64::from(c[1])), self.y(f64::from(c[0])))
    }
}

/// The replay: `roi` drawn in the region's frame, `mapped` cells outlined, every robot of
/// `record` drawn and animated.
pub fn roi_svg(roi: &GridRoi, mapped: Option<&[Cell]>, record: &GridRunRecord) -> String {
    // Everything drawn: the region, the flights (a search starts outside it), the map.
    let [mut lo, mut hi] = roi.bounds();
    let extra = record.robots.iter().flat_map(|r| r.cells.iter()).chain(mapped.unwrap_or(&[]));
    for c in extra {
        lo = [lo[0].min(c[0]), lo[1].min(c[1])];
        hi = [hi[0].max(c[0]), hi[1].max(c[1])];
    }
    let (rows, cols) = (f64::from(hi[0] - lo[0] + 3), f64::from(hi[1] - lo[1] + 3));
    let f = Frame { lo, px: (800.0 / rows.max(cols)).clamp(0.5, 40.0) };
    let px = f.px;
    let (w, h) = (cols * px, rows * px);
    let mut out = String::new();
    let _ = writeln!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.3} {h:.3}">"#
    );
    let _ = writeln!(out, r##"<rect width="100%" height="100%" fill="#f4f4f4"/>"##);
    let _ =
        writeln!(out, r##"<path d="{}" fill="#bcd7b0" stroke="none"/>"##, runs(&f, roi.cells()));
    if let Some(m) = mapped {
        let mut d = String::new();
        for &c in m {
            let (x, y) = f.at(c);
            let _ =
                write!(d, "M{:.2},{:.2}h{px:.2}v{px:.2}h{:.2}Z", x - px / 2.0, y - px / 2.0, -px);
        }
        let sw = (px / 10.0).max(0.2);
        let _ =
            writeln!(out, r##"<path d="{d}" fill="none" stroke="#333" stroke-width="{sw:.2}"/>"##);
    }
    shape(&mut out, &f, roi);
    let s = record.robots.first().and_then(|r| r.cells.first().copied()).unwrap_or(roi.start());
    let (sx, sy) = f.at(s);
    let _ = writeln!(
        out,
        r##"<rect x="{:.2}" y="{:.2}" width="{px:.2}" height="{px:.2}" fill="#e00" fill-opacity="0.6"/>"##,
        sx - px / 2.0,
        sy - px / 2.0
    );
    let steps: usize = record.robots.iter().map(|r| r.cells.len()).sum();
    if steps <= MAX_DRAWN_STEPS {
        for r in &record.robots {
            flight(&mut out, &f, r, record.metrics.totals.time.max(MIN_DURATION));
        }
    } else {
        let _ = writeln!(
            out,
            r#"<text x="10" y="20" font-family="sans-serif" font-size="14">{steps} flown cells: flights not drawn</text>"#
        );
    }
    let _ = writeln!(
        out,
        r#"<text x="10" y="{:.0}" font-family="sans-serif" font-size="12">{} robots, {} cells, time {:.2} s</text>"#,
        h - 6.0,
        record.robots.len(),
        record.cells,
        record.metrics.totals.time
    );
    out.push_str("</svg>\n");
    out
}

/// The cells (sorted) as one path, one rectangle per run of cells in a row.
fn runs(f: &Frame, cells: &[Cell]) -> String {
    let px = f.px;
    let mut d = String::new();
    let mut i = 0;
    while i < cells.len() {
        let mut j = i;
        while j + 1 < cells.len() && cells[j + 1] == [cells[i][0], cells[j][1] + 1] {
            j += 1;
        }
        let (x, y) = f.at(cells[i]);
        let len = px * f64::from(cells[j][1] - cells[i][1] + 1);
        let _ = write!(d, "M{:.2},{:.2}h{len:.2}v{px:.2}h{:.2}Z", x - px / 2.0, y - px / 2.0, -len);
        i = j + 1;
    }
    d
}

/// The true region's outline, when the grid approximates a shape (metres; cell `[r, c]` is
/// centred at `(c·s, −r·s)`).
fn shape(out: &mut String, f: &Frame, roi: &GridRoi) {
    let Some(shape) = roi.shape() else { return };
    let m = roi.cell_size();
    let mut d = String::new();
    for ring in shape.rings() {
        for (k, p) in ring.iter().enumerate() {
            let sep = if k == 0 { "M" } else { " L" };
            let _ = write!(d, "{sep}{:.2},{:.2}", f.x(p[0] / m), f.y(-p[1] / m));
        }
        d.push('Z');
    }
    let sw = (f.px / 8.0).max(0.5);
    let _ =
        writeln!(out, r##"<path d="{d}" fill="none" stroke="#1f3fbf" stroke-width="{sw:.2}"/>"##);
}

/// One robot's flight, and the robot moving along it.
fn flight(out: &mut String, f: &Frame, r: &GridRobotRecord, total: f64) {
    let c = COLOURS[r.id % COLOURS.len()];
    let mut d = String::new();
    for (k, &cell) in r.cells.iter().enumerate() {
        let (x, y) = f.at(cell);
        let _ = write!(d, "{}{x:.2},{y:.2}", if k == 0 { "M" } else { " L" });
    }
    let sw = (f.px / 6.0).max(0.3);
    let _ = writeln!(
        out,
        r#"<path d="{d}" fill="none" stroke="{c}" stroke-opacity="0.6" stroke-width="{sw:.2}"/>"#
    );
    if r.cells.len() < 2 || r.times.len() != r.cells.len() {
        return;
    }
    let mut times: Vec<String> =
        r.times.iter().map(|t| format!("{:.6}", (t / total).clamp(0.0, 1.0))).collect();
    let mut points = key_points(&r.cells);
    // SMIL wants the last key time to be 1: the robot then rests where it ended.
    times.push("1".into());
    points.push_str(";1");
    let _ = writeln!(
        out,
        r##"<circle r="{:.2}" fill="{c}" stroke="#000" stroke-width="0.5"><animateMotion dur="20s" repeatCount="indefinite" calcMode="linear" keyPoints="{points}" keyTimes="{}" path="{d}"/></circle>"##,
        (f.px / 3.0).max(1.0),
        times.join(";")
    );
}

/// The fraction of the path's length at each vertex (SMIL's keyPoints).
fn key_points(cells: &[Cell]) -> String {
    let mut acc = vec![0.0];
    for w in cells.windows(2) {
        let l = f64::from(w[1][0] - w[0][0]).hypot(f64::from(w[1][1] - w[0][1]));
        acc.push(acc.last().copied().unwrap_or(0.0) + l);
    }
    let total = acc.last().copied().unwrap_or(0.0).max(MIN_PATH_LENGTH);
    acc.iter().map(|a| format!("{:.6}", a / total)).collect::<Vec<_>>().join(";")
}
