//! `stopscan roi`: a team of robots explores a region of interest (Algorithm 1 of the ROI
//! paper), optionally with the field pipeline (camera, lawn-mowing search, battery), writing
//! the mission state after every step so that `--resume` carries on after a crash.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use serde::{Deserialize, Serialize};
use stopscan::io::grid::GridOptions;
use stopscan::io::run_record::GridRunRecord;
use stopscan::protocol::CostModel;
use stopscan::protocol::grid::Cell;
use stopscan::sim::grid::{Mission, MissionPlan, Search};
use stopscan::sim::{Flow, NoObserver, Recording};
use stopscan::world::grid::camera::CameraModel;
use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};

use crate::cli::{Format, Global, RoiArgs};
use crate::output::{Table, num, write_json_atomic};

/// Where the region comes from, so that a resumed mission rebuilds the same world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
enum Source {
    /// `GridRoi::random(cells, seed)` with cells of `cell_size` metres.
    Random { cells: usize, seed: u64, cell_size: f64 },
    /// A file (text grid, mask or polygon).
    File { path: PathBuf, cell_size: f64, cell_px: usize, start: Option<Cell>, invert: bool },
}

/// Everything a resumed mission needs (`--state`, `--resume`).
#[derive(Debug, Clone, Serialize, Deserialize)]
struct MissionFile {
    format: String,
    source: Source,
    drift: Drift,
    sensor: GridSensor,
    seed: u64,
    out: PathBuf,
    svg: PathBuf,
    mission: Mission,
}

const MISSION_FORMAT: &str = "stopscan-mission/1";

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

fn parse_box(s: &str) -> anyhow::Result<(Cell, Cell)> {
    let v: Vec<i32> = s
        .split(',')
        .map(|x| x.trim().parse::<i32>())
        .collect::<Result<_, _>>()
        .with_context(|| format!("--search-box must be ROW0,COL0,ROW1,COL1, got {s:?}"))?;
    match v.as_slice() {
        &[r0, c0, r1, c1] if r0 <= r1 && c0 <= c1 => Ok(([r0, c0], [r1, c1])),
        _ => bail!(
            "--search-box must be ROW0,COL0,ROW1,COL1 with ROW0 ≤ ROW1 and COL0 ≤ COL1, got {s:?}"
        ),
    }
}

/// A fresh mission from the command line.
fn fresh(a: &RoiArgs, g: &Global) -> anyhow::Result<MissionFile> {
    let start = a.start.as_deref().map(|s| parse_cell(s, "--start")).transpose()?;
    let source = match (&a.grid, a.random) {
        (Some(p), None) => Source::File {
            path: std::path::absolute(p).unwrap_or_else(|_| p.clone()),
            cell_size: a.cell_m,
            cell_px: a.cell_px,
            start,
            invert: a.invert_mask,
        },
        (None, Some(c)) => Source::Random { cells: c, seed: g.seed, cell_size: a.cell_m },
        _ => bail!("give the region with --grid FILE or --random CELLS (or --resume STATE)"),
    };
    if !(a.roi_speed.is_finite() && a.roi_speed >= 0.0) {
        bail!("--roi-speed must be a non-negative number of m/s, got {}", a.roi_speed);
    }
    if !a.roi_heading_deg.is_finite() {
        bail!("--roi-heading-deg must be finite, got {}", a.roi_heading_deg);
    }
    let drift = Drift { speed: a.roi_speed, heading_deg: a.roi_heading_deg };
    let sensor = if a.camera {
        GridSensor::Camera(CameraModel { frames: a.frames, ..CameraModel::default() })
    } else {
        GridSensor::Ideal
    };
    let search = match (&a.search_box, &a.launch) {
        (Some(b), Some(l)) => {
            let (min, max) = parse_box(b)?;
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
        out,
        svg,
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

/// Writes the state atomically: a temporary file beside it, then a rename.
fn write_state(path: &Path, m: &MissionFile) -> anyhow::Result<()> {
    let tmp = path.with_extension("tmp");
    let text = serde_json::to_vec(m)?;
    std::fs::write(&tmp, text).with_context(|| format!("cannot write {}", tmp.display()))?;
    std::fs::rename(&tmp, path)
        .with_context(|| format!("cannot move {} to {}", tmp.display(), path.display()))
}

pub(crate) fn run(a: &RoiArgs, g: &Global) -> anyhow::Result<()> {
    if g.format == Format::Svg {
        bail!("--format svg is only available for `stopscan visibility`");
    }
    let (mut file, state) = match &a.resume {
        Some(p) => {
            let mut f = read_state(p)?;
            if let Some(o) = &g.out {
                f.out.clone_from(o);
                f.svg = a.svg.clone().unwrap_or_else(|| o.with_extension("svg"));
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
    let mut trace = match &a.trace {
        Some(p) => {
            // A fresh mission starts the trace; a resumed one carries it on.
            let resuming = a.resume.is_some();
            let f = std::fs::OpenOptions::new()
                .create(true)
                .write(true)
                .append(resuming)
                .truncate(!resuming)
                .open(p)
                .with_context(|| format!("cannot write {}", p.display()))?;
            Some(stopscan::sim::JsonLinesTrace::new(std::io::BufWriter::new(f)))
        }
        None => None,
    };
    let limit = file.mission.step_limit(&world);
    loop {
        if file.mission.team.steps >= limit {
            bail!("the mission did not finish within {limit} steps");
        }
        let flow = match trace.as_mut() {
            Some(t) => file.mission.step(&mut world, t)?,
            None => file.mission.step(&mut world, &mut NoObserver)?,
        };
        if let Some(e) = trace.as_mut().and_then(|t| t.error.take()) {
            let p = a.trace.as_deref().unwrap_or(Path::new("trace"));
            return Err(anyhow::Error::from(e).context(format!("cannot write {}", p.display())));
        }
        if let Some(p) = &state {
            file.mission.snapshot(&world);
            write_state(p, &file)?;
        }
        if file.mission.team.steps % 256 == 0 {
            bar.set_message(format!(
                "{} steps, {:.1} s of mission",
                file.mission.team.steps,
                file.mission.team.makespan()
            ));
            bar.tick();
        }
        if flow != Flow::Continue {
            break;
        }
    }
    bar.finish_and_clear();
    let record = GridRunRecord::new(&world, &file.mission, file.seed);
    write_json_atomic(&file.out, &record)?;
    let mapped = file.mission.plan.map.then(|| file.mission.marks.positive());
    let svg = stopscan::render::roi_svg(world.roi(), mapped.as_deref(), &record);
    if let Some(dir) = file.svg.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    std::fs::write(&file.svg, svg)
        .with_context(|| format!("cannot write {}", file.svg.display()))?;
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
        e.cell_size,
        r.robots.len(),
        r.cost_model.speed,
        e.drift.speed,
        e.drift.heading_deg
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
