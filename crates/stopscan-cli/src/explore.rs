//! `stopscan explore` (one file, or a sweep of a folder) and the main job: the arguments go
//! to the library's pipelines ([`stopscan::pipeline::explore`], [`stopscan::pipeline::sweep`]),
//! the results come back as tables and files.

use std::io::Write;
use std::path::{Path, PathBuf};

use stopscan::experiment::polygon::SweepRow;
use stopscan::io::atomic;
use stopscan::offline::polygon::{ReferenceLimits, Solver};
use stopscan::pipeline::explore::{Exploration, ExploreError, ExploreOptions};
use stopscan::pipeline::sweep::SweepEvent;
use stopscan::protocol::CostModel;
use stopscan::protocol::polygon::Footprint;
use stopscan::run_record::{RunRecord, SensorInfo};

use crate::cli::{ExploreArgs, Format, Global, parse_point};
use crate::output::{Spinner, Table, flag_error, num};

/// An exploration error in the words of the command line.
fn explore_error(e: ExploreError) -> anyhow::Error {
    match e {
        ExploreError::Parameter(p) => flag_error(&p),
        ExploreError::RangeNeeded => anyhow::anyhow!(
            "--strategy range_limited needs --range R (metres); for an unlimited range the paper's algorithm is depth_first"
        ),
        e => e.into(),
    }
}

/// The footprint from `--robot-radius` or `--footprint`.
fn footprint(a: &ExploreArgs) -> anyhow::Result<Footprint> {
    if let Some(r) = a.robot_radius {
        return Footprint::disc(r).map_err(|e| anyhow::anyhow!("--robot-radius: {e}"));
    }
    let Some(text) = &a.footprint else { return Ok(Footprint::Point) };
    let vertices: Vec<[f64; 2]> = serde_json::from_str(text).map_err(|e| {
        anyhow::anyhow!(
            "--footprint: expected \"[[x, y], [x, y], ...]\" (metres, nav2's format), got {text:?}: {e}"
        )
    })?;
    Footprint::convex(vertices).map_err(|e| anyhow::anyhow!("--footprint: {e}"))
}

/// The pipeline's options from the arguments.
fn options(a: &ExploreArgs, g: &Global) -> anyhow::Result<ExploreOptions> {
    Ok(ExploreOptions {
        strategy: a.strategy.clone(),
        cost: CostModel::new(a.scan_time, a.move_time, a.speed)?,
        range: a.range,
        footprint: footprint(a)?,
        beams: a.beams.map(|b| u32::try_from(b).unwrap_or(u32::MAX)),
        min_feature: a.min_feature,
        min_window: a.min_window,
        min_pocket: a.min_pocket,
        pocket_cap: a.pocket_cap,
        pocket_budget: a.pocket_budget,
        limits: ReferenceLimits {
            greedy_max_vertices: a.greedy_max_vertices,
            optimum_max_vertices: a.optimum_max_vertices,
            optimum_seconds: a.optimum_seconds,
            optimum_nodes: a.optimum_nodes.map(|n| n as u64),
            bounds_seconds: a.bounds_seconds,
            bounds_steps: a.bounds_steps.map(|n| n as u64),
            solver: Solver::by_name(&a.solver).map_err(|e| anyhow::anyhow!("--solver: {e}"))?,
        },
        seed: g.seed,
        trace: a.trace.clone(),
        simplify: a.simplify,
        lidar: a.sensor,
        odometry_drift: a.odometry_drift,
        relay: a.relay,
        max_scans: a.max_scans.map(|n| n as u64),
    })
}

pub(crate) fn main_job(g: &Global) -> anyhow::Result<()> {
    let spinner = Spinner::new();
    let o = stopscan::pipeline::explore::office(g.seed, &mut |m| spinner.show(m))
        .map_err(explore_error)?;
    drop(spinner);
    let dir = g.out.clone().unwrap_or_else(|| PathBuf::from("stopscan-out"));
    atomic::ensure_dir(&dir)?;
    finish(
        g,
        &o,
        &dir.join("run.json"),
        Some(&dir.join("scene.svg")),
        Some(&dir.join("report.html")),
        None,
    )
}

pub(crate) fn run(a: &ExploreArgs, g: &Global) -> anyhow::Result<()> {
    let options = options(a, g)?;
    if a.env.is_dir() {
        for (flag, given) in [("--report", a.report.is_some()), ("--mcap", a.mcap.is_some())] {
            if given {
                anyhow::bail!(
                    "{flag} records one run; {} is a folder (explore one of its files with {flag})",
                    a.env.display()
                );
            }
        }
        return sweep(a, g, &options);
    }
    if a.shard.is_some() {
        anyhow::bail!(
            "--shard splits a folder sweep (explore --env DIR); {} is a file",
            a.env.display()
        );
    }
    let start = a.start.as_deref().map(parse_point).transpose()?;
    let spinner = Spinner::new();
    let o = stopscan::pipeline::explore::explore_file(&a.env, start, &options, &mut |m| {
        spinner.show(m);
    })
    .map_err(|e| match e {
        // The robot does not fit this environment, or the start is not where a lidar can
        // scan from: say which file.
        ExploreError::World(w) => anyhow::anyhow!("{}: {w}", a.env.display()),
        e @ ExploreError::StartOnWall(_) => anyhow::anyhow!("{}: {e}", a.env.display()),
        e => explore_error(e),
    })?;
    drop(spinner);
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("run.json"));
    finish(g, &o, &out, a.svg.as_deref(), a.report.as_deref(), a.mcap.as_deref())
}

/// Writes the record (and the scene), prints the summary, and fails if the run was ended
/// early (after writing its record so far).
fn finish(
    g: &Global,
    o: &Exploration,
    json_path: &Path,
    svg_path: Option<&Path>,
    report_path: Option<&Path>,
    mcap_path: Option<&Path>,
) -> anyhow::Result<()> {
    atomic::write_json(json_path, &o.record)?;
    if let Some(p) = svg_path {
        atomic::write_bytes(p, o.svg.as_bytes())?;
    }
    if let Some(p) = report_path {
        atomic::write_bytes(p, o.report().as_bytes())?;
    }
    if let Some(p) = mcap_path {
        atomic::write_bytes(p, &o.mcap()?)?;
    }
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == Format::Json {
        writeln!(w, "{}", serde_json::to_string_pretty(&o.record)?)?;
    } else {
        summary(&mut w, &o.record)?;
        writeln!(w, "wrote {}", json_path.display())?;
        for p in [svg_path, report_path, mcap_path].into_iter().flatten() {
            writeln!(w, "wrote {}", p.display())?;
        }
    }
    match &o.failure {
        Some(e) => {
            anyhow::bail!("{e}; the record of the run so far is in {}", json_path.display())
        }
        None => Ok(()),
    }
}

/// The rows of what the sensor rule closed.
fn sensor_rows(t: &mut Table, sensor: &SensorInfo) {
    if let (Some(n), Some(len)) = (sensor.windows_below_rule, sensor.windows_below_rule_length) {
        t.row(vec![
            "windows below the rule (count, m)".into(),
            format!("{n}, {}", num(Some(len), 3)),
        ]);
    }
    if let Some(n) = sensor.windows_into_small_pockets {
        t.row(vec!["window parts into small pockets".into(), n.to_string()]);
    }
    if let Some(n) = sensor.windows_into_walled_pockets {
        t.row(vec!["window parts into small pockets behind walls".into(), n.to_string()]);
    }
    if let Some(n) = sensor.windows_as_gaps_in_a_wall {
        t.row(vec!["windows read as gaps in a wall seen at a slant".into(), n.to_string()]);
    }
    if let Some(n) = sensor.scans_where_stuck {
        t.row(vec!["scans where the robot was stuck".into(), n.to_string()]);
    }
    if let Some(n) = sensor.scans_to_place_again {
        t.row(vec![
            "scans to place the robot again before parts dropped were tried again".into(),
            n.to_string(),
        ]);
    }
    if sensor.gave_up == Some(true) {
        t.row(vec![
            "gave up".into(),
            "yes: stuck again where it had scanned for being stuck; windows were left open".into(),
        ]);
    }
}

fn summary(w: &mut dyn Write, o: &RunRecord) -> std::io::Result<()> {
    let m = &o.metrics;
    let e = &o.environment;
    writeln!(
        w,
        "{}: {} vertices, {} holes, r = {} reflex, free area {} m²; strategy {}",
        e.name,
        e.vertices,
        e.holes,
        e.reflex_vertices,
        num(Some(e.free_area), 2),
        o.strategy.name
    )?;
    let mut t = Table::new(&["quantity", "value"]);
    let b = &o.bounds;
    let opt = |v: Option<usize>, why: &str| v.map_or_else(|| why.to_string(), |v| v.to_string());
    let optimum = match (b.optimum, b.optimum_best) {
        (Some(v), _) => format!("{v} (proven, {})", b.optimum_solver),
        (None, Some(best)) => format!(
            "between {} and {best} (gap {}; {} after {} s, {})",
            b.optimum_lower,
            best.saturating_sub(b.optimum_lower),
            b.optimum_note,
            b.optimum_budget_seconds,
            b.optimum_solver
        ),
        (None, None) => b.optimum_note.clone(),
    };
    let tt = &m.totals;
    let rows: Vec<(&str, String)> = vec![
        ("scans", tt.scans.to_string()),
        ("moves", tt.moves.to_string()),
        ("distance (m)", num(Some(tt.distance), 3)),
        ("scan time (s)", num(Some(tt.scan_time_total), 3)),
        ("move time (s)", num(Some(tt.move_time_total), 3)),
        ("travel time (s)", num(Some(tt.travel_time_total), 3)),
        ("total time (s)", num(Some(tt.time), 3)),
        ("coverage", num(Some(m.coverage), 9)),
        ("windows left open", m.open_windows.to_string()),
        ("upper bound (paper)", format!("{} ({})", b.scans_upper, b.scans_upper_rule)),
        ("lower bound: scans", format!("{} ({})", b.scans_lower, b.scans_lower_rule)),
        ("lower bound: distance (m)", num(Some(b.distance_lower), 3)),
        ("lower bound: time (s)", num(Some(b.time_lower), 3)),
        (
            "certified ratio (time / lower bound)",
            b.certified_ratio.map_or("-".into(), |r| {
                let cut =
                    if b.bounds_complete { "" } else { " (bounds cut short by their budget)" };
                format!("{}{cut}", num(Some(r), 3))
            }),
        ),
        ("offline greedy reference (views)", opt(b.greedy_reference, "not computed")),
        ("offline optimum over candidates (views)", optimum),
        ("scans / offline optimum", b.competitive_ratio.map_or("-".into(), |r| num(Some(r), 3))),
        ("sensor range (m)", o.sensor.range.map_or("unlimited".into(), |r| num(Some(r), 3))),
    ];
    for (k, v) in rows {
        t.row(vec![k.into(), v]);
    }
    // What the sensor rule closed without a visit (with a rule).
    sensor_rows(&mut t, &o.sensor);
    if let Some(r) = &o.robot {
        let robot: [(&str, String); 6] = [
            (
                "area visible from the reachable region (m²)",
                num(Some(r.visible_from_reachable_area), 3),
            ),
            ("coverage of it", num(Some(r.coverage_of_reachable), 9)),
            ("coverage of it where the robot's body fits", num(Some(r.coverage_of_body_space), 9)),
            ("unseen in crevices narrower than the robot (m²)", num(Some(r.unseen_in_crevices), 3)),
            ("unreachable area (m²)", num(Some(r.unreachable_area), 3)),
            ("window parts out of reach", r.windows_out_of_reach.to_string()),
        ];
        for (k, v) in robot {
            t.row(vec![k.into(), v]);
        }
    }
    // From raw scans: how far the believed poses were from the truth at the stops (coverage
    // above is measured where the scans were truly taken).
    if let Some(raw) = &o.raw_scans {
        let rows: [(&str, String); 6] = [
            ("position error at a stop, max (m)", num(Some(raw.max_position_error), 3)),
            ("position error at a stop, mean (m)", num(Some(raw.mean_position_error), 3)),
            ("heading error at a stop, max (rad)", num(Some(raw.max_heading_error), 4)),
            (
                "ICP kept odometry (stops; degenerate walls)",
                format!("{}; {}", raw.icp_fallbacks, raw.icp_degenerate),
            ),
            ("scan matches tied into the pose graph", raw.graph_links.to_string()),
            ("relays: scans on the way to place the robot", raw.relays.to_string()),
        ];
        for (k, v) in rows {
            t.row(vec![k.into(), v]);
        }
    }
    t.write(w)
}

/// `--env DIR`: the sweep, its CSV (`--out`, default `sweep.csv`) and its table; a progress
/// bar over the runs.
fn sweep(a: &ExploreArgs, g: &Global, options: &ExploreOptions) -> anyhow::Result<()> {
    let bar = std::sync::OnceLock::new();
    let rows = stopscan::pipeline::sweep::sweep_dir(&a.env, options, a.shard, &|e| match e {
        SweepEvent::Warning(w) => eprintln!("warning: {w}"),
        SweepEvent::Started { runs } => {
            let _ = bar.set(crate::output::bar(runs, "runs"));
        }
        SweepEvent::RunDone => {
            if let Some(b) = bar.get() {
                b.inc(1);
            }
        }
        _ => {}
    })
    .map_err(explore_error)?;
    if let Some(b) = bar.get() {
        b.finish_and_clear();
    }
    if let Some(s) = a.shard
        && rows.is_empty()
    {
        eprintln!(
            "note: shard {}/{} has no files (there are more shards than files); its CSV is empty",
            s.index, s.count
        );
    }
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("sweep.csv"));
    atomic::write(&out, |w| stopscan::pipeline::sweep::write_csv(&rows, w))?;
    print_sweep(&rows, &out)
}

/// The sweep's table.
fn print_sweep(rows: &[SweepRow], out: &Path) -> anyhow::Result<()> {
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    let mut t = Table::new(&[
        "environment",
        "strategy",
        "r",
        "scans",
        "bound",
        "within",
        "distance",
        "coverage",
    ]);
    for r in rows {
        t.row(vec![
            r.environment.clone(),
            r.strategy.clone(),
            r.reflex_vertices.to_string(),
            r.totals.scans.to_string(),
            r.scans_upper.to_string(),
            if r.error.is_empty() {
                r.within_bound.to_string()
            } else {
                format!("error: {}", r.error)
            },
            num(Some(r.totals.distance), 2),
            num(Some(r.coverage), 9),
        ]);
    }
    t.write(&mut w)?;
    writeln!(w, "wrote {}", out.display())?;
    Ok(())
}
