//! `stopscan bench`: median wall-clock time of repeated runs, as JSON.

use std::time::Instant;

use anyhow::bail;
use rand::{RngExt, SeedableRng};
use serde_json::json;
use stopscan::experiment::polygon::SweepInput;
use stopscan::kernel::tolerance::AREA_REL;
use stopscan::offline::corner::worst_case;
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use stopscan::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use stopscan::strategy::corner::{circle, unirec};

use crate::cli::{BenchArgs, BenchTarget, Global, SolverArg};
use crate::limits;
use crate::output::emit;

pub(crate) fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 { v[n / 2] } else { 0.5 * (v[n / 2 - 1] + v[n / 2]) }
}

fn time<T>(repeat: usize, mut f: impl FnMut() -> T) -> f64 {
    let _ = std::hint::black_box(f()); // warm-up
    median(
        (0..repeat.max(1))
            .map(|_| {
                let t = Instant::now();
                std::hint::black_box(f());
                t.elapsed().as_secs_f64()
            })
            .collect(),
    )
}

pub(crate) fn run(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    if a.repeat > 1000 {
        bail!("--repeat must be at most 1,000, got {}", a.repeat);
    }
    match a.target {
        BenchTarget::Visibility => return crate::visibility::bench(a, g),
        BenchTarget::Explore => return bench_explore(a, g),
        BenchTarget::Roi => return bench_roi(a, g),
        BenchTarget::Floors => return bench_floors(a, g),
        BenchTarget::Scans => return bench_scans(a, g),
        BenchTarget::Serve => return bench_serve(a, g),
        _ => {}
    }
    let (name, n, secs, ops) = match a.target {
        BenchTarget::Mdp => {
            let general = a.solver == SolverArg::General;
            let n = a.n.unwrap_or(if general { 180 } else { 900 });
            if n == 0 || n > 20_000 {
                bail!("--n (stops) must be between 1 and 20000 for mdp, got {n}");
            }
            let mdp = CornerMdp {
                setup: CornerSetup::new(10.0, CostModel::new(2.0, 0.0, 0.5)?)?,
                step: std::f64::consts::FRAC_PI_2 / n as f64,
                memory: Memory::Last,
                reading: Reading::Conditional,
                belief: AngleDistribution::parse("mix:0.5*normal:30,3+0.5*normal:90,3")?,
            };
            if general {
                (
                    "mdp2-policy-iteration",
                    n,
                    time(a.repeat, || mdp.solve_general().map(|s| s.0)),
                    1.0,
                )
            } else {
                (
                    "mdp2-backward-induction",
                    n,
                    time(a.repeat, || mdp.solve().map(|p| p.model_value)),
                    1.0,
                )
            }
        }
        BenchTarget::Circle => {
            let n = a.n.unwrap_or(100_000);
            limits::soft(
                g,
                n as f64,
                limits::DISTANCES,
                || format!("--n {n}"),
                "8 bytes and about 7 µs per distance and repetition",
                "",
            )?;
            let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(g.seed);
            let ds: Vec<f64> = (0..n).map(|_| rng.random_range(0.01..100.0)).collect();
            (
                "circle-ratio",
                n,
                time(a.repeat, || {
                    ds.iter().map(|&d| circle::ratio(d).unwrap_or(f64::NAN)).sum::<f64>()
                }),
                n as f64,
            )
        }
        BenchTarget::Ratio => {
            let n = a.n.unwrap_or(1000);
            if n < 2 {
                bail!("--n (stops) must be at least 2");
            }
            limits::soft(
                g,
                n as f64,
                limits::STOPS.min(stopscan::strategy::corner::MAX_STOPS as u64),
                || format!("--n {n} UNIREC stops"),
                "16 bytes and about 45 ns per stop",
                "",
            )?;
            if n > stopscan::strategy::corner::MAX_STOPS {
                bail!(
                    "--n must be at most {} stops for ratio, got {n}",
                    limits::count(stopscan::strategy::corner::MAX_STOPS as f64)
                );
            }
            let delta = std::f64::consts::FRAC_PI_2 / n as f64;
            let setup = CornerSetup::new(1.0 / delta, CostModel::default())?;
            let list = unirec(delta * (1.0 - 1e-9), Route::Arc, LastStep::Capped)?;
            (
                "worst-case-ratio",
                list.len(),
                time(a.repeat.max(101), || worst_case(&list, &setup).worst_ratio),
                1.0,
            )
        }
        _ => unreachable!("handled above"),
    };
    let value = json!({"name": name, "n": n, "seconds_median": secs, "per_second": ops / secs, "repeat": a.repeat});
    emit(g, &value, true, |w| writeln!(w, "{}", serde_json::to_string(&value).unwrap_or_default()))
}

/// `bench explore`: n generated office floors (seeded sizes and desks), all explored in
/// parallel; reports the runs that fail a check.
/// `bench floors`: every strategy on real maps and office floors, side by side.
fn bench_floors(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    use stopscan::pipeline::floors::{FloorsEvent, FloorsOptions, floors};
    let defaults = FloorsOptions::default();
    let range = a.range.unwrap_or(defaults.range);
    if !(range.is_finite() && range > 0.0) {
        bail!("--range must be a positive number of metres, got {range}");
    }
    let options = FloorsOptions {
        data: Some(a.data.clone()),
        offices: a.offices,
        seed: g.seed,
        strategies: match &a.strategies {
            Some(s) => s.split(',').map(|x| x.trim().to_string()).collect(),
            None => defaults.strategies.clone(),
        },
        footprint: stopscan::protocol::polygon::Footprint::disc(a.robot_radius)
            .map_err(|e| anyhow::anyhow!("--robot-radius: {e}"))?,
        range,
        cost: CostModel::new(a.scan_time, 0.0, a.speed)?,
        ..defaults
    };
    if !a.data.is_dir() {
        bail!(
            "--data {}: no such folder (the shared ROS maps are in ../shared/data/ros-maps beside the repository; the repository's own are in fixtures/ros-maps)",
            a.data.display()
        );
    }
    let bar = std::cell::OnceCell::new();
    let report = floors(&options, &mut |e| match e {
        FloorsEvent::Started { runs } => {
            let _ = bar.set(crate::output::bar(runs, "runs"));
        }
        FloorsEvent::RunDone { .. } => {
            if let Some(b) = bar.get() {
                b.inc(1);
            }
        }
    })
    .map_err(|e| anyhow::anyhow!(e))?;
    if let Some(b) = bar.get() {
        b.finish_and_clear();
    }
    if let Some(path) = &a.chart {
        stopscan::render::write_chart(&report.chart(), &path.with_extension(""))?;
    }
    emit(g, &report, true, |w| {
        let mut t = crate::output::Table::new(&[
            "strategy",
            "scans",
            "mission time (s)",
            "min coverage of reachable",
            "min in body space",
            "failures",
        ]);
        for s in &report.totals {
            t.row(vec![
                s.strategy.clone(),
                s.scans.to_string(),
                crate::output::num(Some(s.time), 1),
                crate::output::num(Some(s.min_coverage_of_reachable), 4),
                crate::output::num(Some(s.min_coverage_of_body_space), 4),
                s.failures.to_string(),
            ]);
        }
        t.write(w)
    })
}

fn bench_explore(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    // n generated office floors (seeded sizes and desks), all explored in parallel.
    let n = a.n.unwrap_or(1000);
    limits::soft(
        g,
        n as f64,
        limits::FLOORS,
        || format!("--n {n} office floors"),
        "all are generated before the timing, about 2.5 ms and 50 kB each",
        "",
    )?;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(g.seed);
    let inputs: Vec<SweepInput> = (0..n)
        .map(|i| {
            let rooms = rng.random_range(2..12);
            let desks = rng.random_range(0..3 * rooms);
            let inst = stopscan::generate::office(rooms, desks, g.seed.wrapping_add(i as u64))?;
            Ok(SweepInput { name: format!("office-{i}"), domain: inst.domain, start: inst.start })
        })
        .collect::<anyhow::Result<_>>()?;
    let bar = crate::output::bar(n as u64, "floors");
    let t = Instant::now();
    let rows = stopscan::experiment::polygon::sweep(
        &inputs,
        &["depth_first"],
        &stopscan::protocol::CostModel::default(),
        None,
        (0.0, None), // no lower bounds: the benchmark times the exploration
        &|| bar.inc(1),
    );
    let secs = t.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let failing: Vec<_> = rows
        .iter()
        .filter(|r| {
            !r.error.is_empty()
                || !r.within_bound
                || r.open_windows > 0
                || r.coverage < 1.0 - AREA_REL
        })
        .collect();
    let details: Vec<_> = failing
        .iter()
        .take(20)
        .map(|r| json!({"environment": r.environment, "scans": r.totals.scans, "scans_upper": r.scans_upper, "coverage": r.coverage, "open_windows": r.open_windows, "error": r.error}))
        .collect();
    let value = json!({
        "name": "explore-office-sweep", "n": n, "seconds_median": secs, "per_second": n as f64 / secs,
        "threads": rayon::current_num_threads(),
        "checks": "no error, scans <= r + 1, no open window, coverage >= 1 - 1e-9",
        "runs_failing_checks": failing.len(), "failing": details,
    });
    emit(g, &value, true, |w| writeln!(w, "{}", serde_json::to_string(&value).unwrap_or_default()))
}

fn bench_scans(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    let n = a.n.unwrap_or(1000);
    if n > 100_000 {
        bail!("--n (scan pairs) must be at most 100000 for scans, got {n}");
    }
    let within = a.pairs_within;
    if !(within.is_finite() && within > 0.0 && within <= 1000.0) {
        bail!("--pairs-within must be a distance in metres above 0 and at most 1000, got {within}");
    }
    let (name, domain) = if let Some(path) = &a.env {
        let env = stopscan::io::read_environment(path)?;
        (path.display().to_string(), env.domain)
    } else {
        let text = stopscan::pipeline::explore::OFFICE_GEOJSON;
        let env = stopscan::io::text_formats::parse_geojson(text, "built-in office floor")?;
        ("office (built-in)".to_string(), env.domain)
    };
    let lidar = stopscan::world::lidar::Lidar::default();
    let bar = crate::output::bar(n as u64, "scan pairs");
    let t = Instant::now();
    let r = stopscan::experiment::scans::scan_pairs(
        &domain,
        &lidar,
        n,
        within,
        0.3,
        10f64.to_radians(),
        g.seed,
        &mut || bar.inc(1),
    );
    bar.finish_and_clear();
    let value = json!({
        "name": "raw-scans", "environment": name, "lidar": lidar, "seed": g.seed,
        "pairs_within_m": within, "initial_error": {"shift_m": 0.3, "turn_deg": 10.0},
        "converged_when": {"shift_m": stopscan::experiment::scans::CONVERGED_SHIFT, "turn_deg": 1.0},
        "result": r, "seconds": t.elapsed().as_secs_f64(),
    });
    emit(g, &value, true, |w| {
        writeln!(w, "{}", serde_json::to_string_pretty(&value).unwrap_or_default())
    })
}

fn bench_serve(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    use stopscan::pipeline::mission::{MissionRun, MissionSpec, RegionSource};
    use stopscan::protocol::polygon::Footprint;
    use stopscan::world::polygon::PolygonWorld;
    let (name, env) = if let Some(path) = &a.env {
        (path.display().to_string(), stopscan::io::read_environment(path)?)
    } else {
        let text = stopscan::pipeline::explore::OFFICE_GEOJSON;
        let env = stopscan::io::text_formats::parse_geojson(text, "built-in office floor")?;
        ("office (built-in)".to_string(), env)
    };
    let strategy = a
        .strategies
        .as_deref()
        .and_then(|s| s.split(',').next())
        .unwrap_or("cost_aware")
        .to_string();
    let start = env.start.unwrap_or_else(|| env.domain.rings()[0][0]);
    let world = PolygonWorld::with_robot(env.domain, None, &Footprint::disc(0.2)?, Some(start))?;
    let start = world.reach().map_or(start, stopscan::world::polygon::Reach::start);
    let dir = std::env::temp_dir().join(format!("stopscan-bench-serve-{}", std::process::id()));
    std::fs::create_dir_all(&dir)?;
    let r = stopscan::pipeline::serve::bench::bench(&world, start, &strategy, g.seed, &dir)?;
    // `roi --state`: the same mission with and without its journal.
    let roi_spec = |trace: bool| MissionSpec {
        source: RegionSource::Random { cells: 3000, seed: g.seed, cell_size: 1.0 },
        drift: stopscan::world::grid::Drift::default(),
        sensor: stopscan::world::grid::GridSensor::Ideal,
        robots: 4,
        cost: CostModel::default(),
        battery_s: None,
        search: None,
        recording: stopscan::sim::Recording::PATHS,
        seed: g.seed,
        out: dir.join(if trace { "a.json" } else { "b.json" }),
        svg: dir.join(if trace { "a.svg" } else { "b.svg" }),
        report: None,
        mcap: None,
        trace: None,
    };
    let roi = |journal: bool| -> anyhow::Result<f64> {
        let spec = roi_spec(journal);
        let region = spec.source.load()?;
        let state = dir.join("state.jsonl");
        let t = Instant::now();
        MissionRun::start(spec, region)?.fly(journal.then_some(state.as_path()), &mut |_| {})?;
        Ok(t.elapsed().as_secs_f64())
    };
    let (without, with) = (roi(false)?, roi(true)?);
    let roi_steps = std::fs::read_to_string(dir.join("state.jsonl"))?.lines().count() - 1;
    let _ = std::fs::remove_dir_all(&dir);
    let value = json!({
        "name": "serve", "environment": name, "seed": g.seed, "result": r,
        "roi_state_journal": {
            "cells": 3000, "robots": 4, "steps": roi_steps,
            "seconds_without": without, "seconds_with": with,
            "us_per_step": (with - without) * 1e6 / roi_steps as f64,
        },
    });
    emit(g, &value, true, |w| {
        writeln!(w, "{}", serde_json::to_string_pretty(&value).unwrap_or_default())
    })
}

fn bench_roi(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    use stopscan::offline::grid::GridBounds;
    use stopscan::sim::Recording;
    use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};
    let cells = a.n.unwrap_or(1_000_000);
    crate::roi::check_size(g, "--n", cells, a.robots)?;
    let spinner = crate::output::Spinner::new();
    spinner.show(&format!("generating a region of {cells} cells"));
    let t = Instant::now();
    let roi = GridRoi::random(cells, g.seed)?;
    let generate = t.elapsed().as_secs_f64();
    let cost = CostModel::new(0.0, 0.0, 1.0)?;
    let mut last = None;
    let mut times = Vec::new();
    for k in 0..a.repeat.max(1) {
        spinner.show(&format!(
            "{} robots explore {cells} cells (run {} of {})",
            a.robots,
            k + 1,
            a.repeat.max(1)
        ));
        let mut world = GridWorld::new(roi.clone(), Drift::default(), GridSensor::Ideal, g.seed);
        let t = Instant::now();
        let m = stopscan::sim::grid::explore(&mut world, a.robots, cost, Recording::NONE)?;
        times.push(t.elapsed().as_secs_f64());
        last = Some((world, m));
    }
    let Some((world, m)) = last else { bail!("no run") };
    let visited = world.visited().len();
    let home = m.team.robots.iter().all(|r| r.done && r.at == roi.start());
    let b = GridBounds::of_world(&world, a.robots, &cost);
    let time = m.team.makespan();
    drop(spinner);
    let bar = crate::output::bar(stopscan::experiment::grid::FIG7_POINTS as u64, "Fig. 7 points");
    let t = Instant::now();
    let rows = stopscan::experiment::grid::fig7_rows(
        stopscan::experiment::ROI_TRIALS,
        g.seed,
        &mut || {
            bar.inc(1);
        },
    )?;
    let fig7 = t.elapsed().as_secs_f64();
    bar.finish_and_clear();
    let trials: usize = rows.iter().map(|r| r.trials).sum();
    let within: usize = rows.iter().map(|r| r.within_upper).sum();
    let value = json!({
        "name": "roi", "cells": cells, "robots": a.robots,
        "generate_seconds": generate,
        "simulate_seconds_median": median(times),
        "repeat": a.repeat.max(1),
        "steps": m.team.steps, "robot_moves": m.team.tally().moves,
        "time": time, "lemma1_upper": b.lemma1_upper, "d_max": b.d_max,
        "checks": {"cells_visited": visited, "all_home": home, "within_lemma1": time <= b.lemma1_upper},
        "fig7_seconds": fig7, "fig7_points": rows.len(), "fig7_trials": trials,
        "fig7_trials_within_lemma1": within,
        "threads": rayon::current_num_threads(),
    });
    emit(g, &value, true, |w| writeln!(w, "{}", serde_json::to_string(&value).unwrap_or_default()))
}
