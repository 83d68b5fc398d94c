//! `stopscan roi`: a team of robots explores a region of interest (Algorithm 1 of the ROI
//! paper), optionally with the field pipeline (camera, lawn-mowing search, battery), writing
//! the mission state as it goes so that `--resume` carries on after a crash. The mission, its
//! state file and its loop are the library's ([`stopscan::pipeline::mission`]); this module
//! checks the arguments and the soft limits and prints the summary.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, bail};
use stopscan::kernel::Num;
use stopscan::pipeline::mission::{MissionRun, MissionSpec, MissionState, RegionSource};
use stopscan::protocol::CostModel;
use stopscan::protocol::grid::Cell;
use stopscan::run_record::GridRunRecord;
use stopscan::sim::Recording;
use stopscan::sim::grid::{MAX_FRAMES, Search};
use stopscan::world::grid::camera::CameraModel;
use stopscan::world::grid::{Drift, GridSensor};

use crate::cli::{Format, Global, RoiArgs};
use crate::limits;
use crate::output::{Spinner, Table, num};

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
    let cells = Search { launch: [r0, c0], min: [r0, c0], max: [r1, c1] }.cells();
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

/// A fresh mission from the command line: the arguments checked (and the soft limits), the
/// region loaded.
fn fresh(a: &RoiArgs, g: &Global) -> anyhow::Result<MissionRun> {
    let start = a.start.as_deref().map(|s| parse_cell(s, "--start")).transpose()?;
    check_size(g, "--random", a.random.unwrap_or(0), a.robots)?;
    if a.camera && !(1..=MAX_FRAMES).contains(&a.frames) {
        bail!(
            "--frames must be between 1 and {MAX_FRAMES} (the paper votes 3 of 5), got {}",
            a.frames
        );
    }
    let source = match (&a.grid, a.random) {
        (Some(p), None) => RegionSource::File {
            path: std::path::absolute(p).unwrap_or_else(|_| p.clone()),
            cell_size: a.cell_m,
            cell_px: a.cell_px,
            start,
            invert: a.invert_mask,
        },
        (None, Some(c)) => RegionSource::Random { cells: c, seed: g.seed, cell_size: a.cell_m },
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
    let roi = source.load()?;
    if a.camera {
        let frames = limits::camera_frames(roi.len(), search.as_ref(), a.frames);
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
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("roi-run.json"));
    let spec = MissionSpec {
        source,
        drift,
        sensor,
        robots: a.robots,
        cost,
        battery_s: a.battery_s,
        search,
        recording: if a.no_paths { Recording::NONE } else { Recording::PATHS },
        seed: g.seed,
        svg: a.svg.clone().unwrap_or_else(|| out.with_extension("svg")),
        report: a.report.clone(),
        mcap: a.mcap.clone(),
        out,
        trace: a.trace.clone(),
    };
    Ok(MissionRun::start(spec, roi)?)
}

pub(crate) fn run(a: &RoiArgs, g: &Global) -> anyhow::Result<()> {
    if g.format == Format::Svg {
        bail!("--format svg is only available for `stopscan visibility`");
    }
    let (mission, state) = match &a.resume {
        Some(p) => {
            let mut f = MissionState::read(p)?;
            f.redirect(
                g.out.as_deref(),
                a.svg.as_deref(),
                a.report.as_deref(),
                a.mcap.as_deref(),
                a.trace.as_deref(),
            )?;
            (f.resume()?, Some(p.clone()))
        }
        None => (fresh(a, g)?, a.state.clone()),
    };
    let spinner = Spinner::new();
    let end = mission.fly(state.as_deref(), &mut |m| spinner.show(m))?;
    drop(spinner);
    let record = &end.record;
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == Format::Json {
        writeln!(w, "{}", serde_json::to_string_pretty(record)?)?;
    } else {
        summary(&mut w, record)?;
        writeln!(w, "wrote {}", end.out.display())?;
        writeln!(w, "wrote {}", end.svg.display())?;
        for p in [&end.report, &end.mcap].into_iter().flatten() {
            writeln!(w, "wrote {}", p.display())?;
        }
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
        ("exploration time (s)", num(Some(m.totals.time), 3)),
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
        ("scans / moves", format!("{} / {}", m.totals.scans, m.totals.moves)),
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
