//! `report.html`: one self-contained page that replays a run in the browser, step by step,
//! with play, pause and a slider, beside its metrics (the time split into its terms), its
//! bounds and its certified ratio. No network: the run's data is embedded as JSON and drawn
//! by the page's own script (`report/*.js`, included at compile time).
//!
//! - [`polygon_report`]: an exploration. Each scan's region appears as it is taken (one
//!   `<path class="scan">` per scan taken so far), the path grows, and the frontiers left open
//!   at that step are highlighted. The step's scans, moves, distance and time terms are
//!   recomputed here from the run's tally at each scan and priced by the record's
//!   [`CostModel`](crate::protocol::CostModel), so the last step shows the record's totals.
//! - [`roi_report`]: a grid mission. The team's robots move along their flights in time, and
//!   each cell is marked when a robot first reaches it.
//!
//! Geometry is embedded rounded to a millionth of the drawing's extent (far below a pixel,
//! and fine enough that a probe a hundred-thousandth beyond a frontier still lands where
//! the exact geometry puts it), to keep the file small; the metrics are embedded exactly. The
//! page reads `#step=K` (start at step K) and `#play` (start playing) from its address, and
//! records on `<body>` the step shown (`data-step`) and how long after navigation its first
//! frame was drawn (`data-first-frame-ms`), which the browser test reads.

use serde::Serialize;

use crate::algorithm::cover::frontier_history;
use crate::algorithm::visibility::VisibilityRegion;
use crate::geometry::{Domain, Location};
use crate::kernel::Point;
use crate::protocol::Tally;
use crate::protocol::grid::Cell;
use crate::run_record::{GridRunRecord, RunRecord};
use crate::world::grid::GridRoi;

const STYLE: &str = include_str!("report/report.css");
const COMMON_JS: &str = include_str!("report/common.js");
const POLYGON_JS: &str = include_str!("report/polygon.js");
const ROI_JS: &str = include_str!("report/roi.js");

/// Above this many flown cells in all, a grid report leaves the flights out (and says so):
/// the page would be too big to open quickly.
pub const MAX_REPORTED_CELLS: usize = 200_000;

/// What a polygon exploration's replay is made of, in the frame the run was computed in.
#[derive(Debug, Clone)]
pub struct PolygonReplay {
    /// The free space explored (for the open frontiers' probes and the drawing).
    pub domain: Domain,
    /// The robot's configuration space, when it has a footprint: components, each a list of
    /// rings.
    pub cspace: Option<Vec<Vec<Vec<Point>>>>,
    /// The regions seen, in scan order.
    pub regions: Vec<VisibilityRegion>,
    /// The polyline driven, from the start.
    pub path: Vec<Point>,
    /// The tally when each scan was taken, that scan counted: `steps[k]` after scan `k + 1`.
    pub steps: Vec<Tally>,
    /// When each scan began, seconds.
    pub scan_times: Vec<f64>,
    /// The whole run's tally.
    pub total: Tally,
    /// The raw scans, when the run was driven from a simulated lidar.
    pub raw: Option<RawReplay>,
    /// The frontiers' histories ([`PolygonReplay::frontier_history`]), computed on first use
    /// and kept for the next picture (build with `Default::default()`).
    pub frontiers: std::sync::OnceLock<Vec<crate::algorithm::cover::FrontierHistory>>,
}

impl PolygonReplay {
    /// Each frontier of the scans and how its open parts shrank
    /// ([`frontier_history`] in the free space's interior), computed once for the report and
    /// the MCAP recording.
    pub fn frontier_history(&self) -> &[crate::algorithm::cover::FrontierHistory] {
        self.frontiers.get_or_init(|| {
            frontier_history(&self.regions, |p: Point| self.domain.locate(p) == Location::Interior)
        })
    }
}

/// What a raw-scan run adds to its replay: each stop's scan as the lidar returned it, where
/// it was truly taken, and where the robot believed it was after ICP.
#[derive(Debug, Clone)]
pub struct RawReplay {
    /// The scans.
    pub laser: Vec<crate::protocol::laser::LaserScan>,
    /// The true poses.
    pub truth: Vec<crate::protocol::laser::Pose>,
    /// The poses believed after alignment.
    pub estimate: Vec<crate::protocol::laser::Pose>,
}

/// One step of the replay: what has been done and what it cost.
#[derive(Debug, Clone, Serialize)]
struct Frame {
    scans: u64,
    moves: u64,
    distance: f64,
    /// Path vertices drawn.
    path: usize,
    scan_time_total: f64,
    move_time_total: f64,
    travel_time_total: f64,
    time: f64,
}

/// A frontier and when its parts were open: `open[i] = [step, t0, t1, t0, t1, ...]`.
#[derive(Debug, Clone, Serialize)]
struct Frontier {
    scan: usize,
    a: Point,
    b: Point,
    window: bool,
    open: Vec<Vec<f64>>,
}

#[derive(Debug, Clone, Serialize)]
struct Scan {
    at: Point,
    poly: Vec<f64>,
}

#[derive(Serialize)]
struct PolygonData<'a> {
    kind: &'static str,
    title: String,
    bounds: [f64; 4],
    domain: Vec<Vec<f64>>,
    cspace: Option<Vec<Vec<f64>>>,
    path: Vec<f64>,
    scans: Vec<Scan>,
    frames: Vec<Frame>,
    frontiers: Vec<Frontier>,
    /// The seed in words: a u64 does not survive JavaScript's numbers.
    seed: String,
    record: &'a RunRecord,
}

/// Rounds coordinates to a millionth of `extent` (at most 12 decimals).
struct Rounder {
    scale: f64,
}

impl Rounder {
    fn new(extent: f64) -> Self {
        let decimals = (6.0 - extent.max(1e-12).log10()).ceil().clamp(0.0, 12.0);
        Self { scale: 10f64.powf(decimals) }
    }
    fn x(&self, v: f64) -> f64 {
        (v * self.scale).round() / self.scale
    }
    fn point(&self, p: Point) -> Point {
        [self.x(p[0]), self.x(p[1])]
    }
    fn flat(&self, ring: &[Point]) -> Vec<f64> {
        ring.iter().flat_map(|p| [self.x(p[0]), self.x(p[1])]).collect()
    }
}

/// The index of the path vertex at which each scan was taken: the first vertex that is the
/// scan's viewpoint at or after both the previous scan's and the scan's move count (every
/// move adds at least one vertex), or failing that the nearest one after them.
pub(super) fn scan_vertices(
    path: &[Point],
    regions: &[VisibilityRegion],
    steps: &[Tally],
) -> Vec<usize> {
    let mut at = 0;
    regions
        .iter()
        .zip(steps)
        .map(|(r, t)| {
            at = at.max(usize::try_from(t.moves).unwrap_or(usize::MAX).min(path.len()));
            let v = r.viewpoint;
            let rest = path.get(at..).unwrap_or(&[]);
            let found = rest.iter().position(|&p| p == v).or_else(|| {
                let d = |p: &Point| (p[0] - v[0]).hypot(p[1] - v[1]);
                (0..rest.len()).min_by(|&i, &j| d(&rest[i]).total_cmp(&d(&rest[j])))
            });
            at += found.unwrap_or(0);
            at
        })
        .collect()
}

/// The replay's steps: the start, each scan, and the end when the robot moved after its last
/// scan.
fn frames(replay: &PolygonReplay, record: &RunRecord) -> Vec<Frame> {
    let cost = &record.cost_model;
    let frame = |t: &Tally, path: usize| {
        let terms = cost.price(t);
        Frame {
            scans: t.scans,
            moves: t.moves,
            distance: t.distance,
            path,
            scan_time_total: terms.scan_time_total,
            move_time_total: terms.move_time_total,
            travel_time_total: terms.travel_time_total,
            time: terms.total(),
        }
    };
    let vertices = scan_vertices(&replay.path, &replay.regions, &replay.steps);
    let mut out = vec![frame(&Tally::default(), 1.min(replay.path.len()))];
    for (t, &v) in replay.steps.iter().zip(&vertices) {
        out.push(frame(t, v + 1));
    }
    if out.last().is_some_and(|f| f.moves < replay.total.moves || f.scans < replay.total.scans) {
        out.push(frame(&replay.total, replay.path.len()));
    }
    out
}

/// Embeds `data` in a page: its JSON (with `<` escaped, so that no string closes the script
/// element), the style and the scripts.
fn page<T: Serialize>(title: &str, data: &T, script: &str) -> String {
    let json = serde_json::to_string(data)
        .unwrap_or_else(|e| format!("{{\"error\":\"cannot serialise: {e}\"}}"))
        .replace('<', "\\u003c");
    let title = escape(title);
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{title}</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n\
         <header><h1>{title}</h1><p id=\"subtitle\"></p></header>\n\
         <main>\n<section id=\"view\"></section>\n<aside id=\"panel\"></aside>\n</main>\n\
         <nav id=\"controls\"></nav>\n\
         <script type=\"application/json\" id=\"run-data\">{json}</script>\n\
         <script>\n{COMMON_JS}\n{script}\n</script>\n</body>\n</html>\n"
    )
}

/// HTML text: `&`, `<`, `>` and quotes escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;").replace('"', "&quot;")
}

/// The replay of a polygon exploration: `replay` (in the run's frame) beside its `record`.
pub fn polygon_report(replay: &PolygonReplay, record: &RunRecord) -> String {
    let [lo, hi] = replay.domain.bounds();
    let r = Rounder::new((hi[0] - lo[0]).max(hi[1] - lo[1]));
    let frontiers = replay
        .frontier_history()
        .iter()
        .map(|h| Frontier {
            scan: h.scan,
            a: r.point(h.from),
            b: r.point(h.to),
            window: h.window,
            open: h
                .open
                .iter()
                .map(|(step, iv)| {
                    std::iter::once(*step as f64).chain(iv.iter().flatten().copied()).collect()
                })
                .collect(),
        })
        // A frontier closed from the moment it appeared is never drawn.
        .filter(|f| f.open.len() > 1 || f.open.first().is_some_and(|o| o.len() > 1))
        .collect();
    let data = PolygonData {
        kind: "polygon",
        title: format!("{}: {}", record.environment.name, record.strategy.name),
        bounds: [lo[0], lo[1], hi[0], hi[1]],
        domain: replay.domain.rings().iter().map(|ring| r.flat(ring)).collect(),
        cspace: replay
            .cspace
            .as_ref()
            .map(|c| c.iter().flatten().map(|ring| r.flat(ring)).collect()),
        path: r.flat(&replay.path),
        scans: replay
            .regions
            .iter()
            .map(|g| Scan { at: r.point(g.viewpoint), poly: r.flat(&g.polygon) })
            .collect(),
        frames: frames(replay, record),
        frontiers,
        seed: record.seed.to_string(),
        record,
    };
    let title = format!("stopscan: {} on {}", record.strategy.name, record.environment.name);
    page(&title, &data, POLYGON_JS)
}

#[derive(Serialize)]
struct RoiRobot {
    id: usize,
    /// `[row, col, row, col, ...]`.
    cells: Vec<i32>,
    times: Vec<f64>,
    finish: f64,
}

#[derive(Serialize)]
struct RoiData<'a> {
    kind: &'static str,
    title: String,
    /// The region's cells as runs along rows: `[row, first col, last col, ...]`.
    runs: Vec<i32>,
    /// The true region's outline in cell units (`x = col`, `y = row`), when there is one.
    shape: Option<Vec<Vec<f64>>>,
    /// The map's cells (`[row, col, ...]`), when the mission mapped.
    mapped: Option<Vec<i32>>,
    /// The flights, or none when there are more than [`MAX_REPORTED_CELLS`] flown cells.
    robots: Option<Vec<RoiRobot>>,
    flown_cells: usize,
    /// The seed in words (see [`PolygonData`]).
    seed: String,
    record: &'a GridRunRecord,
}

/// Runs of consecutive cells along rows, of sorted cells.
pub(super) fn row_runs(cells: &[Cell]) -> Vec<i32> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < cells.len() {
        let mut j = i;
        while j + 1 < cells.len() && cells[j + 1] == [cells[i][0], cells[j][1] + 1] {
            j += 1;
        }
        out.extend([cells[i][0], cells[i][1], cells[j][1]]);
        i = j + 1;
    }
    out
}

/// The replay of a grid mission: `roi`, the cells `mapped` (when it mapped) and every robot
/// of `record` moving in time.
pub fn roi_report(roi: &GridRoi, mapped: Option<&[Cell]>, record: &GridRunRecord) -> String {
    let flown: usize = record.robots.iter().map(|r| r.cells.len()).sum();
    let m = roi.cell_size();
    let shape = roi.shape().map(|s| {
        s.rings()
            .iter()
            .map(|ring| ring.iter().flat_map(|p| [p[0] / m, -p[1] / m]).collect())
            .collect()
    });
    let robots = (flown <= MAX_REPORTED_CELLS).then(|| {
        record
            .robots
            .iter()
            .map(|r| RoiRobot {
                id: r.id,
                cells: r.cells.iter().flatten().copied().collect(),
                times: r.times.clone(),
                finish: r.finish_time,
            })
            .collect()
    });
    let data = RoiData {
        kind: "roi",
        title: format!("{}: {}", record.environment.name, record.strategy.name),
        runs: row_runs(roi.cells()),
        shape,
        mapped: mapped.map(|c| c.iter().flatten().copied().collect()),
        robots,
        flown_cells: flown,
        seed: record.seed.to_string(),
        record,
    };
    let title = format!(
        "stopscan: {} robots, {} on {}",
        record.robots.len(),
        record.strategy.name,
        record.environment.name
    );
    page(&title, &data, ROI_JS)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_keeps_a_millionth_of_the_extent() {
        assert_eq!(Rounder::new(20.0).x(1.234_567_89), 1.234_57);
        assert_eq!(Rounder::new(2_000.0).x(1.234_567), 1.235);
        assert_eq!(Rounder::new(1e9).x(4_000_123_456.7), 4_000_123_457.0);
    }

    #[test]
    fn rows_are_cut_into_runs() {
        let cells = [[0, 0], [0, 1], [0, 2], [0, 4], [1, 4], [1, 5]];
        assert_eq!(row_runs(&cells), vec![0, 0, 2, 0, 4, 4, 1, 4, 5]);
    }

    #[test]
    fn the_page_cannot_be_closed_by_the_data() {
        let html = page("a <b>", &serde_json::json!({"name": "</script><b>"}), "");
        assert!(html.contains("<title>a &lt;b&gt;</title>"));
        assert_eq!(html.matches("</script>").count(), 2);
    }

    #[test]
    fn scans_find_their_path_vertices_in_order() {
        let region =
            |v: Point| VisibilityRegion { viewpoint: v, polygon: vec![], boundary: vec![] };
        let tally = |moves| Tally { scans: 0, moves, distance: 0.0 };
        let path = [[0.0, 0.0], [1.0, 0.0], [0.0, 0.0], [2.0, 0.0]];
        let scans = [region([0.0, 0.0]), region([0.0, 0.0]), region([2.0, 0.1])];
        let steps = [tally(0), tally(2), tally(3)];
        assert_eq!(scan_vertices(&path, &scans, &steps), vec![0, 2, 3]);
    }
}
