//! `stopscan roi`: a team of robots explores a region of interest (Algorithm 1 of the ROI
//! paper), optionally with the field pipeline (camera, lawn-mowing search, battery), writing
//! the mission state as it goes so that `--resume` carries on after a crash.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use serde::{Deserialize, Serialize};
use stopscan::io::grid::GridOptions;
use stopscan::kernel::Num;
use stopscan::protocol::CostModel;
use stopscan::protocol::grid::Cell;
use stopscan::run_record::GridRunRecord;
use stopscan::sim::grid::{MAX_FRAMES, Mission, MissionPlan, Search};
use stopscan::sim::{Flow, NoObserver, Recording};
use stopscan::world::grid::camera::CameraModel;
use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};

use crate::cli::{Format, Global, RoiArgs};
use crate::limits;
use crate::output::{Table, check_file, num, write_atomic, write_json_atomic};

/// Where the region comes from, so that a resumed mission rebuilds the same world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
enum Source {
    /// `GridRoi::random(cells, seed)` with cells of `cell_size` metres.
    Random { cells: usize, seed: u64, cell_size: f64 },
    /// A file (text grid, mask or polygon).
    File { path: PathBuf, cell_size: f64, cell_px: usize, start: Option<Cell>, invert: bool },
}

/// Everything a resumed mission needs (`--state`, `--resume`). Paths are absolute, so that a
/// mission resumes from any directory.
#[derive(Debug, Clone, Serialize, Deserialize)]
struct MissionFile {
    format: String,
    source: Source,
    drift: Drift,
    sensor: GridSensor,
    seed: u64,
    out: PathBuf,
    svg: PathBuf,
    /// The event trace, if the mission writes one.
    trace: Option<PathBuf>,
    /// The trace's length in bytes when this state was taken: a resumed mission cuts the
    /// trace back to it, so that the events after the state are not written twice.
    trace_len: u64,
    mission: Mission,
}

/// `/2`: the trace and its length are recorded; a search's lawn is computed, not listed.
const MISSION_FORMAT: &str = "stopscan-mission/2";

fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// The soft limits on a mission's size: robots and cells (of a random region, or `bench roi`).
pub(crate) fn check_size(
    g: &Global,
    flag: &str,
    cells: usize,
    robots: usize,
) -> anyhow::Result<()> {
    limits::soft(
        g,
        robots as f64,
        limits::ROBOTS,
        || format!("--robots {robots}"),
        "each robot keeps its own strategy and path, and the team loop scans them all",
        "",
    )?;
    limits::soft(
        g,
        cells as f64,
        limits::CELLS,
        || format!("{flag} {cells} (cells)"),
        "about 300 bytes and 2.5 µs per cell",
        "",
    )
}

fn load(source: &Source) -> anyhow::Result<GridRoi> {
    Ok(match source {
        Source::Random { cells, seed, cell_size } => {
            GridRoi::random(*cells, *seed)?.with_cell_size(*cell_size)?
        }
        Source::File { path, cell_size, cell_px, start, invert } => {
            let opts = GridOptions {
                cell_size: *cell_size,
                cell_px: *cell_px,
                start: *start,
                invert: *invert,
            };
            stopscan::io::grid::read_roi(path, &opts)?
        }
    })
}

fn world_of(roi: GridRoi, drift: Drift, sensor: GridSensor, seed: u64, search: bool) -> GridWorld {
    if search {
        GridWorld::without_root(roi, drift, sensor, seed)
    } else {
        GridWorld::new(roi, drift, sensor, seed)
    }
}

fn parse_cell(s: &str, what: &str) -> anyhow::Result<Cell> {
    let v: Vec<&str> = s.split(',').map(str::trim).collect();
    match v.as_slice() {
        [r, c] => Ok([
            r.parse().with_context(|| format!("{what}: bad row {r:?}"))?,
            c.parse().with_context(|| format!("{what}: bad column {c:?}"))?,
        ]),
        _ => bail!("{what} must be ROW,COL, got {s:?}"),
    }
}

fn parse_box(s: &str, g: &Global) -> anyhow::Result<(Cell, Cell)> {
    let v: Vec<i32> = s
        .split(',')
        .map(|x| x.trim().parse::<i32>())
        .collect::<Result<_, _>>()
        .with_context(|| {
            format!(
                "--search-box must be ROW0,COL0,ROW1,COL1 (whole numbers within ±2^31), got {s:?}"
            )
        })?;
    let &[r0, c0, r1, c1] = v.as_slice() else {
        bail!("--search-box must be ROW0,COL0,ROW1,COL1, got {s:?}");
    };
    if !(r0 <= r1 && c0 <= c1) {
        bail!(
            "--search-box must be ROW0,COL0,ROW1,COL1 with ROW0 ≤ ROW1 and COL0 ≤ COL1, got {s:?}"
        );
    }
    let cells = (f64::from(r1) - f64::from(r0) + 1.0) * (f64::from(c1) - f64::from(c0) + 1.0);
    limits::soft(
        g,
        cells,
        limits::CELLS,
        || format!("--search-box {s} covers {} cells", limits::count(cells)),
        "about 70 bytes and 0.5 µs per cell, more with --camera",
        "narrow the box",
    )?;
    Ok(([r0, c0], [r1, c1]))
}

/// A fresh mission from the command line.
fn fresh(a: &RoiArgs, g: &Global) -> anyhow::Result<MissionFile> {
    let start = a.start.as_deref().map(|s| parse_cell(s, "--start")).transpose()?;
    check_size(g, "--random", a.random.unwrap_or(0), a.robots)?;
    if a.camera && !(1..=MAX_FRAMES).contains(&a.frames) {
        bail!(
            "--frames must be between 1 and {MAX_FRAMES} (the paper votes 3 of 5), got {}",
            a.frames
        );
    }
    if !(a.state_interval.is_finite() && a.state_interval >= 0.0) {
        bail!(
            "--state-interval must be a non-negative number of seconds, got {}",
            Num(a.state_interval)
        );
    }
    let source = match (&a.grid, a.random) {
        (Some(p), None) => Source::File {
            path: absolute(p),
            cell_size: a.cell_m,
            cell_px: a.cell_px,
            start,
            invert: a.invert_mask,
        },
        (None, Some(c)) => Source::Random { cells: c, seed: g.seed, cell_size: a.cell_m },
        _ => bail!("give the region with --grid FILE or --random CELLS (or --resume STATE)"),
    };
    if start.is_some() && a.random.is_some() {
        bail!("--start applies to --grid files; a random region starts where it was grown");
    }
    if !(a.roi_speed.is_finite() && a.roi_speed >= 0.0) {
        bail!("--roi-speed must be a non-negative number of m/s, got {}", Num(a.roi_speed));
    }
    if !a.roi_heading_deg.is_finite() {
        bail!("--roi-heading-deg must be finite, got {}", Num(a.roi_heading_deg));
    }
    let drift = Drift { speed: a.roi_speed, heading_deg: a.roi_heading_deg };
    let sensor = if a.camera {
        GridSensor::Camera(CameraModel { frames: a.frames, ..CameraModel::default() })
    } else {
        GridSensor::Ideal
    };
    let search = match (&a.search_box, &a.launch) {
        (Some(b), Some(l)) => {
            let (min, max) = parse_box(b, g)?;
            Some(Search { launch: parse_cell(l, "--launch")?, min, max })
        }
        (None, None) => None,
        _ => bail!("a lawn-mowing search needs both --search-box and --launch"),
    };
    let cost = CostModel::new(a.scan_time, a.move_time, a.robot_speed)?;
    let plan = MissionPlan {
        robots: a.robots,
        cost,
        battery_s: a.battery_s,
        search,
        map: a.camera || search.is_some() || matches!(source, Source::File { .. }),
    };
    let roi = load(&source)?;
    if a.camera {
        // Every region cell is scanned about once, and a third of the search box's cells.
        let scans = roi.len() as f64
            + search.map_or(0.0, |s| {
                (f64::from(s.max[0]) - f64::from(s.min[0]) + 1.0)
                    * (f64::from(s.max[1]) - f64::from(s.min[1]) + 1.0)
                    / 3.0
            });
        let frames = scans * a.frames as f64;
        limits::soft(
            g,
            frames,
            limits::FRAMES,
            || {
                format!(
                    "--camera with {} frames per scan on {} region cells renders about {} frames",
                    a.frames,
                    limits::count(roi.len() as f64),
                    limits::count(frames)
                )
            },
            "about 0.6 ms per frame",
            "give fewer --frames or a coarser --cell-m",
        )?;
    }
    let world = world_of(roi, drift, sensor.clone(), g.seed, search.is_some());
    let recording = if a.no_paths { Recording::NONE } else { Recording::PATHS };
    let mission = Mission::new(&world, plan, recording)?;
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("roi-run.json"));
    let svg = a.svg.clone().unwrap_or_else(|| out.with_extension("svg"));
    Ok(MissionFile {
        format: MISSION_FORMAT.into(),
        source,
        drift,
        sensor,
        seed: g.seed,
        out: absolute(&out),
        svg: absolute(&svg),
        trace: a.trace.as_deref().map(absolute),
        trace_len: 0,
        mission,
    })
}

fn read_state(path: &Path) -> anyhow::Result<MissionFile> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let m: MissionFile = serde_json::from_str(&text).map_err(|e| {
        anyhow::anyhow!("{}:{}:{}: not a mission state: {e}", path.display(), e.line(), e.column())
    })?;
    if m.format != MISSION_FORMAT {
        bail!("{}: format {:?}, expected {MISSION_FORMAT:?}", path.display(), m.format);
    }
    Ok(m)
}

/// Writes the state atomically (a crash leaves the previous state or this one).
fn write_state(path: &Path, m: &MissionFile) -> anyhow::Result<()> {
    write_atomic(path, |w| serde_json::to_writer(w, m).map_err(std::io::Error::from))
}

/// Counts the bytes written through it (the trace's length, for the state file).
struct Counting<W> {
    inner: W,
    bytes: std::rc::Rc<std::cell::Cell<u64>>,
}

impl<W: Write> Write for Counting<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.bytes.set(self.bytes.get() + n as u64);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// Opens the trace: a fresh mission (or a new file given on resume) starts it empty; a
/// resumed one cuts its own trace back to the length recorded with the state and appends.
fn open_trace(path: &Path, keep: u64) -> anyhow::Result<std::fs::File> {
    let cannot = || format!("cannot write {}", path.display());
    let f = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .read(true)
        .write(true)
        .open(path)
        .with_context(cannot)?;
    let len = f.metadata().with_context(cannot)?.len();
    if len < keep {
        bail!(
            "{}: the trace has {len} bytes, fewer than the {keep} the mission state recorded; it was changed since (give --trace NEW to start a new one)",
            path.display()
        );
    }
    f.set_len(keep).with_context(cannot)?;
    let mut f = f;
    std::io::Seek::seek(&mut f, std::io::SeekFrom::End(0)).with_context(cannot)?;
    Ok(f)
}

pub(crate) fn run(a: &RoiArgs, g: &Global) -> anyhow::Result<()> {
    if g.format == Format::Svg {
        bail!("--format svg is only available for `stopscan visibility`");
    }
    let (mut file, state) = match &a.resume {
        Some(p) => {
            let mut f = read_state(p)?;
            if let Some(o) = &g.out {
                f.out = absolute(o);
                f.svg = absolute(&a.svg.clone().unwrap_or_else(|| o.with_extension("svg")));
            } else if let Some(s) = &a.svg {
                f.svg = absolute(s);
            }
            check_file(&f.out)?;
            check_file(&f.svg)?;
            if let Some(t) = &a.trace {
                // A trace named now replaces the recorded one and starts empty.
                let t = absolute(t);
                if f.trace.as_ref() != Some(&t) {
                    f.trace = Some(t);
                    f.trace_len = 0;
                }
            }
            (f, Some(p.clone()))
        }
        None => (fresh(a, g)?, a.state.clone()),
    };
    let roi = load(&file.source)?;
    let search = file.mission.plan.search.is_some();
    let mut world = world_of(roi, file.drift, file.sensor.clone(), file.seed, search);
    if file.mission.team.steps > 0 {
        world = file.mission.restore(world);
    }
    let bar = crate::output::spinner();
    let bytes = std::rc::Rc::new(std::cell::Cell::new(file.trace_len));
    let mut trace = match &file.trace {
        Some(p) => {
            let f = open_trace(p, file.trace_len)?;
            let out = Counting { inner: std::io::BufWriter::new(f), bytes: bytes.clone() };
            Some(stopscan::sim::JsonLinesTrace::new(out))
        }
        None => None,
    };
    let limit = file.mission.step_limit(&world);
    let interval = std::time::Duration::from_secs_f64(a.state_interval.max(0.0));
    let mut last_write: Option<std::time::Instant> = None;
    loop {
        if file.mission.team.steps >= limit {
            bail!("the mission did not finish within {limit} steps");
        }
        let flow = match trace.as_mut() {
            Some(t) => file.mission.step(&mut world, t)?,
            None => file.mission.step(&mut world, &mut NoObserver)?,
        };
        if let Some(e) = trace.as_mut().and_then(|t| t.error.take()) {
            let p = file.trace.as_deref().unwrap_or(Path::new("trace"));
            return Err(anyhow::Error::from(e).context(format!("cannot write {}", p.display())));
        }
        // The state, at most once per interval and at the end: each write costs time in
        // proportion to the mission. Every step's state is consistent, so a resume from any
        // of them ends with the same record.
        let done = flow != Flow::Continue;
        if let Some(p) = &state
            && (done || last_write.is_none_or(|t| t.elapsed() >= interval))
        {
            file.mission.snapshot(&world);
            file.trace_len = bytes.get();
            write_state(p, &file)?;
            last_write = Some(std::time::Instant::now());
        }
        if file.mission.team.steps % 256 == 0 {
            bar.set_message(format!(
                "{} steps, {:.1} s of mission",
                file.mission.team.steps,
                file.mission.team.makespan()
            ));
            bar.tick();
        }
        if done {
            break;
        }
    }
    bar.finish_and_clear();
    let record = GridRunRecord::new(&world, &file.mission, file.seed);
    write_json_atomic(&file.out, &record)?;
    let mapped = file.mission.plan.map.then(|| file.mission.marks.positive());
    let svg = stopscan::render::roi_svg(world.roi(), mapped.as_deref(), &record);
    write_atomic(&file.svg, |w| w.write_all(svg.as_bytes()))?;
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == Format::Json {
        writeln!(w, "{}", serde_json::to_string_pretty(&record)?)?;
    } else {
        summary(&mut w, &record)?;
        writeln!(w, "wrote {}", file.out.display())?;
        writeln!(w, "wrote {}", file.svg.display())?;
        if let Some(p) = &state {
            writeln!(w, "wrote {}", p.display())?;
        }
    }
    if !record.failures.is_empty() {
        bail!("the mission did not complete: {}", record.failures.join("; "));
    }
    Ok(())
}

fn summary(w: &mut dyn Write, r: &GridRunRecord) -> std::io::Result<()> {
    let e = &r.environment;
    let m = &r.metrics;
    let b = &r.bounds;
    writeln!(
        w,
        "{}: {} cells of {} m, {} robots at {} m/s; region drifting at {} m/s towards {}°",
        e.name,
        r.cells,
        Num(e.cell_size),
        r.robots.len(),
        Num(r.cost_model.speed),
        Num(e.drift.speed),
        Num(e.drift.heading_deg)
    )?;
    let mut t = Table::new(&["quantity", "value"]);
    let opt = |v: Option<f64>, d: usize| v.map_or_else(|| "-".to_string(), |x| num(Some(x), d));
    let rows: Vec<(&str, String)> = vec![
        ("exploration time (s)", num(Some(m.time), 3)),
        ("upper bound, Lemma 1 (s)", num(Some(b.bounds.lemma1_upper), 3)),
        (
            "within Lemma 1",
            b.within_lemma1.map_or("- (not the paper's model)".into(), |x| x.to_string()),
        ),
        ("lower bound on the optimum, Lemma 2 (s)", num(Some(b.bounds.lemma2_lower), 3)),
        ("time / Lemma 2 (competitive ratio estimate)", opt(b.competitive_ratio, 3)),
        ("Theorem 1 ratio", num(Some(b.bounds.theorem1_ratio), 3)),
        ("Theorem 2 ratio (arbitrary shapes)", num(Some(b.bounds.theorem2_ratio), 3)),
        ("single-robot bound (8) (s)", opt(b.bounds.bound8_single, 3)),
        ("lawn mower baseline (s)", num(Some(b.bounds.lawn_mower), 3)),
        (
            "tree depth d_max (start's eccentricity)",
            format!("{} ({})", b.bounds.d_max, b.eccentricity),
        ),
        (
            "cells visited",
            format!("{} of {} ({})", m.visited_cells, r.cells, num(Some(m.coverage), 4)),
        ),
        ("all robots back at the start", m.all_home.to_string()),
        ("scans / moves", format!("{} / {}", m.scans, m.moves)),
        ("battery swaps", r.robots.iter().map(|x| x.battery_swaps).sum::<u32>().to_string()),
        ("mapped cells", m.mapped_cells.map_or("-".into(), |x| x.to_string())),
        ("IoU of the map", opt(m.iou, 4)),
        (
            "C_out / C_in",
            match (m.c_out, m.c_in) {
                (Some(o), Some(i)) => format!("{o} / {i}"),
                _ => "-".into(),
            },
        ),
    ];
    for (k, v) in rows {
        t.row(vec![k.into(), v]);
    }
    t.write(w)
}
