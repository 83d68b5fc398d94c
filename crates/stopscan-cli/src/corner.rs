//! The corner commands, the demo and `reproduce`.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::bail;
use serde::Serialize;
use serde_json::json;
use stopscan::experiment::corner::{self as exp, LineupOptions};
use stopscan::kernel::Num;
use stopscan::offline::corner::{expected, limit_ratio, optimal::optimal_scans_with, worst_case};
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use stopscan::render::{LineChart, Series, write_chart, write_policy_image};
use stopscan::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use stopscan::strategy::corner::registry;
use stopscan::strategy::corner::{ExprecReading, StopList, circle, unirec_stops};

use crate::cli::{self, CornerCommand, Global, RatioStrategy, Readings};
use crate::limits;
use crate::output::{
    Table, emit, ensure_dir, num, write_atomic, write_json_atomic, write_stem_atomic,
};

pub(crate) fn run(command: &CornerCommand, g: &Global) -> anyhow::Result<()> {
    match command {
        CornerCommand::Demo => demo(g),
        CornerCommand::Circle { distance } => circle_cmd(*distance, g),
        CornerCommand::Thresholds { count } => thresholds(*count, g),
        CornerCommand::Optimal { distance, scans } => optimal(*distance, *scans, g),
        CornerCommand::Collapse { ratio, distance } => collapse(*ratio, *distance, g),
        CornerCommand::Ratio(a) => ratio(a, g),
        CornerCommand::Policy(a) => policy(a, g),
        CornerCommand::Simulate(a) => simulate(a, g),
    }
}

fn positive(name: &str, v: f64) -> anyhow::Result<f64> {
    if !(v.is_finite() && v > 0.0) {
        bail!("--{name} must be a finite positive number, got {}", Num(v));
    }
    Ok(v)
}

/// A directory for pictures from `--out`, or `None` when no pictures are wanted.
fn picture_dir(g: &Global) -> anyhow::Result<Option<PathBuf>> {
    match &g.out {
        None => Ok(None),
        Some(p) => {
            ensure_dir(p)?;
            Ok(Some(p.clone()))
        }
    }
}

fn save_chart(dir: &Path, name: &str, chart: &LineChart) -> anyhow::Result<Vec<String>> {
    Ok(write_stem_atomic(&dir.join(name), |stem| write_chart(chart, stem))?
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

fn save_policy_image(
    dir: &Path,
    name: &str,
    title: &str,
    image: &[Vec<stopscan::strategy::corner::mdp::Cell>],
) -> anyhow::Result<Vec<String>> {
    Ok(write_stem_atomic(&dir.join(name), |stem| write_policy_image(image, title, stem))?
        .iter()
        .map(|p| p.display().to_string())
        .collect())
}

/// Refuses (unless `--allow-large`) a UNIREC stop list above [`limits::STOPS`] before it is
/// built; the other strategies have logarithmically many stops.
fn check_unirec(g: &Global, flag: &str, delta: f64) -> anyhow::Result<()> {
    let stops = unirec_stops(delta);
    limits::soft(
        g,
        stops,
        limits::STOPS,
        || format!("{flag} gives {} UNIREC stops", limits::count(stops)),
        "16 bytes and about 45 ns per stop",
        &format!(
            "use δ ≥ {}",
            limits::at_least(std::f64::consts::FRAC_PI_2 / limits::STOPS as f64)
        ),
    )
}

fn circle_cmd(d: f64, g: &Global) -> anyhow::Result<()> {
    let d = positive("distance", d)?;
    let s = circle::solve(d);
    let mut files = Vec::new();
    if let Some(dir) = picture_dir(g)? {
        let mut path = vec![(0.0, 0.0)];
        path.extend(s.scan_points.iter().map(|p| (p[0], p[1])));
        let arc: Vec<(f64, f64)> = (0..=200)
            .map(|k| {
                let a = std::f64::consts::FRAC_PI_2 * f64::from(k) / 200.0;
                (d * a.sin().powi(2), d * a.sin() * a.cos())
            })
            .collect();
        let chart = LineChart {
            title: format!("Circle strategy at d = {}: c = {:.6}", Num(d), s.ratio),
            subtitle: String::new(),
            x_label: "x (start at 0, corner at d)".into(),
            y_label: "y".into(),
            series: vec![
                Series::line("semicircle", arc).dashed(),
                Series::line("path and scan points", path).with_markers(),
            ],
        };
        files = save_chart(&dir, "circle", &chart)?;
        write_json_atomic(&dir.join("circle.json"), &s)?;
    }
    let value = json!({
        "distance": s.distance, "ratio": s.ratio, "scans": s.scans, "total_scans": s.scans + 1,
        "steps": s.steps, "scan_points": s.scan_points, "angles_deg": s.angles.iter().map(|a| a.to_degrees()).collect::<Vec<_>>(),
        "units": "scan cost 1, speed 1; 'scans' counts intermediate scans, the corner scan is extra", "files": files,
    });
    emit(g, &value, false, |w| {
        writeln!(
            w,
            "circle strategy at d = {}: ratio c = {:.6}, {} intermediate scans (+1 at the corner)",
            Num(d),
            s.ratio,
            s.scans
        )?;
        let mut t = Table::new(&["scan", "step", "x", "y", "angle at corner (deg)"]);
        for (k, ((x, p), a)) in s.steps.iter().zip(&s.scan_points).zip(&s.angles).enumerate() {
            let label = if k == s.scans { "corner".to_string() } else { (k + 1).to_string() };
            t.row(vec![
                label,
                num(Some(*x), 6),
                num(Some(p[0]), 6),
                num(Some(p[1]), 6),
                num(Some(a.to_degrees()), 4),
            ]);
        }
        t.write(w)
    })
}

fn thresholds(count: usize, g: &Global) -> anyhow::Result<()> {
    if count == 0 || count > 60 {
        bail!("--count must be between 1 and 60, got {count}");
    }
    let rows = circle::thresholds(count);
    let value = json!({ "thresholds": rows });
    emit(g, &value, true, |w| {
        let mut t = Table::new(&["scans", "maximal d", "c at upper bound"]);
        for r in &rows {
            t.row(vec![r.scans.to_string(), num(Some(r.distance), 6), num(Some(r.ratio), 6)]);
        }
        t.write(w)
    })
}

fn optimal(d: f64, k: usize, g: &Global) -> anyhow::Result<()> {
    let d = positive("distance", d)?;
    if k > 12 {
        bail!("--scans must be at most 12 (the optimisation is over 2·scans coordinates), got {k}");
    }
    let bar = crate::output::spinner();
    let o = optimal_scans_with(d, k, g.seed, &mut |j, r| {
        bar.set_message(format!("searched {j} of {k} points: best ratio {r:.6}"));
    });
    bar.finish_and_clear();
    let value = json!({
        "distance": o.distance, "max_scans": o.max_scans, "scans": o.scans, "ratio": o.ratio,
        "scan_points": o.scan_points, "ratio_by_scans": o.ratio_by_scans,
        "circle_ratio": o.circle_ratio, "circle_scans": o.circle_scans,
        "improvement_over_circle": o.circle_ratio - o.ratio,
    });
    emit(g, &value, true, |w| {
        writeln!(
            w,
            "global optimum at d = {} with at most {k} intermediate scans: ratio {:.6} with {} (exact for the points below)",
            Num(d),
            o.ratio,
            o.scans
        )?;
        writeln!(
            w,
            "circle strategy at d = {}: ratio {:.6} with {} scans",
            Num(d),
            o.circle_ratio,
            o.circle_scans
        )?;
        let mut t = Table::new(&["scan", "x", "y"]);
        for (i, p) in o.scan_points.iter().enumerate() {
            t.row(vec![(i + 1).to_string(), num(Some(p[0]), 9), num(Some(p[1]), 9)]);
        }
        t.row(vec!["corner".into(), num(Some(d), 9), num(Some(0.0), 9)]);
        t.write(w)
    })
}

fn collapse(c: f64, d: Option<f64>, g: &Global) -> anyhow::Result<()> {
    let c = positive("ratio", c)?;
    if c <= 1.0 {
        bail!("--ratio must exceed 1, got {}", Num(c));
    }
    let d = match d {
        Some(d) => positive("distance", d)?,
        None if c < 2.0 => 10.0 / (2.0 - c),
        None => 100.0,
    };
    let r = circle::collapse(d, c);
    emit(g, &r, true, |w| {
        writeln!(
            w,
            "c = {} at d = {}: {} after {} steps; farthest from the start {:.6} (Theorem 1 bound 1/(2 − c) = {})",
            Num(c),
            Num(d),
            if r.reached { "reaches the corner" } else { "collapses" },
            r.steps,
            r.farthest,
            num(Some(r.bound), 6)
        )
    })
}

fn build_options(r: Readings) -> registry::BuildOptions {
    registry::BuildOptions {
        last_step: match r.last_step {
            cli::LastStepArg::Capped => LastStep::Capped,
            cli::LastStepArg::Nominal => LastStep::Nominal,
        },
        exprec: match r.exprec {
            cli::ExprecArg::TableI => ExprecReading::TableI,
            cli::ExprecArg::Appendix => ExprecReading::Appendix,
        },
        route: match r.route {
            cli::RouteArg::Arc => Route::Arc,
            cli::RouteArg::Chord => Route::Chord,
        },
        ..registry::BuildOptions::default()
    }
}

/// `--stops-deg` checked in degrees, as given: each stop positive, finite and above the one
/// before, and none after one that already reaches the corner (90°). Positions are 1-based.
fn check_stops_deg(stops: &[f64]) -> anyhow::Result<()> {
    for (k, &a) in stops.iter().enumerate() {
        if !(a.is_finite() && a > 0.0) {
            bail!("--stops-deg: stop {} is {}°; stops must be finite and positive", k + 1, Num(a));
        }
        if k > 0 {
            let prev = stops[k - 1];
            if prev >= 90.0 {
                bail!(
                    "--stops-deg: stop {} ({}°) follows stop {k} ({}°), which already reaches the corner (90°); end the list there",
                    k + 1,
                    Num(a),
                    Num(prev)
                );
            }
            if a <= prev {
                bail!(
                    "--stops-deg: stop {} ({}°) is not above stop {k} ({}°); give increasing angles",
                    k + 1,
                    Num(a),
                    Num(prev)
                );
            }
        }
    }
    Ok(())
}

fn stop_list(
    strategy: RatioStrategy,
    delta: f64,
    stops_deg: &[f64],
    r: Readings,
) -> anyhow::Result<StopList> {
    let o = build_options(r);
    // Only δ matters for these: normalise τ = v = 1, D = 1/δ.
    let unit = CornerSetup::new(1.0 / delta, CostModel::default())?;
    let none = AngleDistribution::uniform(0.0, std::f64::consts::PI)?;
    Ok(match strategy {
        RatioStrategy::Unirec => registry::build("unirec", &unit, &none, &o)?,
        RatioStrategy::Exprec => registry::build("exprec", &unit, &none, &o)?,
        RatioStrategy::Circle => registry::build("circle", &unit, &none, &o)?,
        RatioStrategy::Stops => {
            if stops_deg.is_empty() {
                bail!("--strategy stops needs --stops-deg A,B,C (degrees, increasing)");
            }
            check_stops_deg(stops_deg)?;
            let rad: Vec<f64> = stops_deg.iter().map(|d| d.to_radians()).collect();
            StopList::from_nominal(&rad, o.route, o.last_step)?
        }
    })
}

fn ratio(a: &cli::RatioArgs, g: &Global) -> anyhow::Result<()> {
    let delta = positive("delta", a.delta)?;
    if a.strategy == RatioStrategy::Unirec {
        check_unirec(g, &format!("--delta {}", Num(delta)), delta)?;
    }
    let list = stop_list(a.strategy, delta, &a.stops_deg, a.readings)?;
    // Only δ matters: normalise τ = v = 1, D = 1/δ.
    let setup = CornerSetup::new(1.0 / delta, CostModel::default())?;
    let w = worst_case(&list, &setup);
    let name = format!("{:?}", a.strategy).to_lowercase();
    let value = json!({
        "strategy": name, "delta": delta, "stops": list.len(),
        "worst_ratio": w.worst_ratio, "theta_at_worst": w.theta_at_worst, "theta_at_worst_deg": w.theta_at_worst.to_degrees(),
        "asymptotic_ratio": w.asymptotic_ratio, "theta_at_asymptotic": w.theta_at_asymptotic,
        "additive_constant": w.additive_constant, "limit_ratio": limit_ratio(&name),
        "explanation": "worst_ratio is the strict supremum of cost/OPT over θ in (0, π], approached as θ decreases to theta_at_worst (radians); asymptotic_ratio is the smallest c with cost ≤ c·OPT + b for all θ, with the additive constant b = sqrt(τ·D/v) in units of τ, which absorbs a bounded number of scans near θ = 0 and vanishes against OPT as δ → 0; limit_ratio is the papers' closed-form value as δ → 0",
    });
    emit(g, &value, true, |w2| {
        writeln!(w2, "{name} at δ = {} ({} stops)", Num(delta), list.len())?;
        let mut t = Table::new(&["quantity", "value", "θ (deg)"]);
        t.row(vec![
            "worst ratio (strict sup over θ > 0)".into(),
            num(Some(w.worst_ratio), 6),
            num(Some(w.theta_at_worst.to_degrees()), 4),
        ]);
        t.row(vec![
            format!("asymptotic ratio (b = {:.3}τ)", w.additive_constant),
            num(Some(w.asymptotic_ratio), 6),
            num(Some(w.theta_at_asymptotic.to_degrees()), 4),
        ]);
        t.row(vec!["limit as δ → 0 (papers)".into(), num(limit_ratio(&name), 6), "-".into()]);
        t.write(w2)
    })
}

fn setup_of(s: cli::SetupArgs) -> anyhow::Result<CornerSetup> {
    Ok(CornerSetup::new(s.distance, CostModel::new(s.scan_time, s.move_time, s.speed)?)?)
}

fn policy(a: &cli::PolicyArgs, g: &Global) -> anyhow::Result<()> {
    let setup = setup_of(a.setup)?;
    let belief = AngleDistribution::parse(&a.belief)?;
    let memory = match a.memory {
        cli::MemoryArg::None => Memory::None,
        cli::MemoryArg::Last => Memory::Last,
    };
    let reading = match a.reading {
        cli::ReadingArg::Conditional => Reading::Conditional,
        cli::ReadingArg::Literal => Reading::Literal,
    };
    let mdp =
        CornerMdp { setup, step: a.step_deg.to_radians(), memory, reading, belief: belief.clone() };
    let p = mdp.solve()?;
    let general = match a.solver {
        cli::SolverArg::Backward => None,
        cli::SolverArg::General => {
            let (v, sol) = mdp.solve_general()?;
            Some(
                json!({"model_value": v, "iterations": sol.iterations, "agrees_with_backward_induction": (v - p.model_value).abs() < 1e-9}),
            )
        }
    };
    let truth = match &a.truth {
        Some(t) => AngleDistribution::parse(t)?,
        None => belief.clone(),
    };
    let e = expected(&p.stop_list, &setup, &truth);
    let mut files = Vec::new();
    if let Some(dir) = picture_dir(g)? {
        let name = if memory == Memory::Last { "policy-mdp2" } else { "policy-mdp1" };
        let title = format!(
            "{} optimal policy, belief {}, δ = {}°",
            if memory == Memory::Last { "MDP2" } else { "MDP1" },
            a.belief,
            Num(a.step_deg)
        );
        files = save_policy_image(&dir, name, &title, &p.image)?;
    }
    let value = json!({
        "memory": format!("{:?}", a.memory).to_lowercase(), "belief": belief, "truth": truth, "step_deg": a.step_deg, "stops": p.stops, "states": p.states,
        "reading": format!("{reading:?}").to_lowercase(), "model_value": p.model_value,
        "expected_time": e.time, "expected_scans": e.scans, "expected_distance": e.distance,
        "scan_stops": p.scan_stops, "scan_angles_deg": p.stop_list.angles().iter().map(|x| x.to_degrees()).collect::<Vec<_>>(),
        "general_solver": general, "cost_model": setup.cost, "distance": setup.distance, "files": files,
    });
    emit(g, &value, false, |w| {
        writeln!(
            w,
            "{} policy, {} stops ({} states), belief {}",
            if memory == Memory::Last { "MDP2" } else { "MDP1" },
            p.stops,
            p.states,
            a.belief
        )?;
        writeln!(
            w,
            "expected time {:.4} s (MDP value {:.4} s), expected scans {:.3}",
            e.time, p.model_value, e.scans
        )?;
        let angles: Vec<String> =
            p.stop_list.angles().iter().map(|x| format!("{:.1}", x.to_degrees())).collect();
        writeln!(w, "scans at (deg) while unseen: {}", angles.join(", "))
    })
}

fn simulate(a: &cli::SimulateArgs, g: &Global) -> anyhow::Result<()> {
    let setup = setup_of(a.setup)?;
    let belief = AngleDistribution::parse(&a.belief)?;
    let truth = match &a.truth {
        Some(t) => AngleDistribution::parse(t)?,
        None => belief.clone(),
    };
    limits::soft(
        g,
        a.samples as f64,
        limits::SAMPLES,
        || format!("--samples {} per strategy", a.samples),
        "about 2 µs per sample; the exact expectation is printed beside the estimate",
        "",
    )?;
    let mut names: Vec<String> = a.strategy.iter().map(|s| s.trim().to_lowercase()).collect();
    if names.iter().any(|n| n == "all") {
        names = registry::names().map(String::from).collect();
    }
    let opts =
        registry::BuildOptions { mdp_step: a.step_deg.to_radians(), ..build_options(a.readings) };
    let delta = setup.delta();
    if names.iter().any(|n| n == "unirec") {
        check_unirec(g, &format!("unirec at δ = τv/D = {}", Num(delta)), delta)?;
    }
    let bar = crate::output::bar((a.samples * names.len()) as u64, "samples");
    let mut results = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let list = registry::build(name, &setup, &belief, &opts)?;
        let e = expected(&list, &setup, &truth);
        let mc = exp::monte_carlo_with(
            &list,
            &setup,
            &truth,
            a.samples,
            stopscan::experiment::sample_seed(g.seed, k as u64),
            &|n| bar.inc(n),
        )?;
        let wc = worst_case(&list, &setup);
        results.push(json!({
            "strategy": name, "expected_time": e.time, "expected_scans": e.scans, "expected_distance": e.distance,
            "monte_carlo": mc, "worst_ratio": wc.worst_ratio, "stops": list.len(),
        }));
    }
    bar.finish_and_clear();
    let value = json!({
        "belief": belief, "truth": truth, "samples": a.samples, "seed": g.seed, "distance": setup.distance,
        "cost_model": setup.cost, "delta": delta, "results": results, "stopscan_version": stopscan::VERSION,
    });
    emit(g, &value, true, |w| {
        let mut t = Table::new(&[
            "strategy",
            "exact E[time] (s)",
            "Monte Carlo (s)",
            "± s.e.",
            "E[scans]",
            "worst ratio",
        ]);
        for r in &results {
            t.row(vec![
                r["strategy"].as_str().unwrap_or("").into(),
                num(r["expected_time"].as_f64(), 3),
                num(r["monte_carlo"]["mean"].as_f64(), 3),
                num(r["monte_carlo"]["std_err"].as_f64(), 3),
                num(r["expected_scans"].as_f64(), 3),
                num(r["worst_ratio"].as_f64(), 4),
            ]);
        }
        writeln!(
            w,
            "{} samples, seed {}, D = {} m, τ = {} s, v = {} m/s, δ = {}",
            a.samples,
            g.seed,
            Num(setup.distance),
            Num(setup.cost.scan_time),
            Num(setup.cost.speed),
            num(Some(delta), 4)
        )?;
        t.write(w)
    })
}

#[derive(Serialize)]
struct ReproduceOut<'a> {
    #[serde(flatten)]
    r: &'a stopscan::experiment::Reproduction,
    files: Vec<String>,
    seed: u64,
    stopscan_version: &'static str,
}

/// Writes a reproduction's charts, images, tables and JSON into `dir`; returns their paths.
fn write_reproduction(
    dir: &Path,
    id: &str,
    r: &stopscan::experiment::Reproduction,
    seed: u64,
) -> anyhow::Result<Vec<String>> {
    let mut files = Vec::new();
    for (name, chart) in &r.charts {
        files.extend(save_chart(dir, name, chart)?);
    }
    for (name, title, image) in &r.images {
        files.extend(save_policy_image(dir, name, title, image)?);
    }
    for (name, text) in &r.tables {
        let path = dir.join(name);
        write_atomic(&path, |w| w.write_all(text.as_bytes()))?;
        files.push(path.display().to_string());
    }
    let path = dir.join(format!("{id}.json"));
    let out = ReproduceOut { r, files: files.clone(), seed, stopscan_version: stopscan::VERSION };
    write_json_atomic(&path, &out)?;
    files.push(path.display().to_string());
    Ok(files)
}

pub(crate) fn reproduce(a: &cli::ReproduceArgs, g: &Global) -> anyhow::Result<()> {
    let ids: Vec<&str> =
        if a.id == "all" { stopscan::experiment::ids() } else { vec![a.id.as_str()] };
    limits::soft(
        g,
        a.samples as f64,
        limits::SAMPLES,
        || format!("--samples {}", a.samples),
        "about 2 µs per sample and strategy",
        "",
    )?;
    let mut outs = Vec::new();
    for id in ids {
        let data =
            if id == "views-benchmarks" { data_dir(a.data.as_deref()) } else { Ok(PathBuf::new()) };
        let r = match data.and_then(|d| {
            stopscan::experiment::reproduce_with_data(id, a.samples, g.seed, &d)
                .map_err(anyhow::Error::from)
        }) {
            Ok(r) => r,
            // `all` without the benchmark data still reproduces everything else.
            Err(e) if a.id == "all" && id == "views-benchmarks" => {
                eprintln!("views-benchmarks skipped: {e}");
                continue;
            }
            Err(e) => return Err(e),
        };
        let files = match picture_dir(g)? {
            Some(dir) => write_reproduction(&dir, id, &r, g.seed)?,
            None => Vec::new(),
        };
        outs.push((r, files));
    }
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == cli::Format::Json {
        let all: Vec<ReproduceOut> = outs
            .iter()
            .map(|(r, files)| ReproduceOut {
                r,
                files: files.clone(),
                seed: g.seed,
                stopscan_version: stopscan::VERSION,
            })
            .collect();
        // One object for one ID, an array for `all`.
        let text = if a.id == "all" {
            serde_json::to_string_pretty(&all)?
        } else {
            serde_json::to_string_pretty(&all[0])?
        };
        writeln!(w, "{text}")?;
        return Ok(());
    }
    for (r, files) in &outs {
        match g.format {
            cli::Format::Json => unreachable!("handled above"),
            cli::Format::Table | cli::Format::Svg => {
                writeln!(w, "== {} ==", r.id)?;
                for m in &r.model {
                    writeln!(w, "model: {m}")?;
                }
                rows_table(r).write(&mut w)?;
                for n in &r.notes {
                    writeln!(w, "note: {n}")?;
                }
                for f in files {
                    writeln!(w, "wrote {f}")?;
                }
                writeln!(w)?;
            }
        }
    }
    Ok(())
}

/// The rows of a reproduction as a table; other readings of the paper get one column each,
/// `=` where they equal ours.
fn rows_table(r: &stopscan::experiment::Reproduction) -> Table {
    // Other readings of the paper: one column each, "=" where equal to ours.
    let mut others: Vec<&str> = Vec::new();
    for o in r.rows.iter().flat_map(|row| &row.other_readings) {
        if !others.contains(&o.reading.as_str()) {
            others.push(&o.reading);
        }
    }
    let mut head = vec!["row", "paper", "ours", "rel diff", "monte carlo"];
    head.extend(&others);
    let mut t = Table::new(&head);
    for row in &r.rows {
        let mc =
            row.monte_carlo.map_or("-".into(), |m| format!("{:.2} ± {:.2}", m.mean, m.std_err));
        let mut cells = vec![
            row.label.clone(),
            num(row.paper, 6),
            num(Some(row.ours), 6),
            row.rel_diff.map_or("-".into(), |d| format!("{:+.2}%", 100.0 * d)),
            mc,
        ];
        cells.extend(others.iter().map(|name| {
            row.other_readings.iter().find(|o| o.reading == *name).map_or("-".into(), |o| {
                match o.rel_diff {
                    _ if o.ours == row.ours => "=".into(),
                    Some(d) => format!("{:.2} ({:+.1}%)", o.ours, 100.0 * d),
                    None => num(Some(o.ours), 6),
                }
            })
        }));
        t.row(cells);
    }
    t
}

/// The folder of benchmark environments for `views-benchmarks`: `--data` as given (an error
/// if it is missing), else the first that exists of `$STOPSCAN_DATA`, the shared data beside
/// the checkout this binary was built from, beside the executable (any ancestor's
/// `shared/data`), and `../shared/data` from the current directory. When none exists, the
/// error lists what was tried.
pub(crate) fn data_dir(given: Option<&Path>) -> anyhow::Result<PathBuf> {
    if let Some(d) = given {
        if !d.is_dir() {
            bail!("--data {}: no such directory", d.display());
        }
        return Ok(d.to_path_buf());
    }
    if let Some(d) = std::env::var_os("STOPSCAN_DATA").map(PathBuf::from) {
        if !d.is_dir() {
            bail!("STOPSCAN_DATA={}: no such directory", d.display());
        }
        return Ok(d);
    }
    let built = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
    let exe = std::env::current_exe().and_then(std::fs::canonicalize).ok();
    let beside_exe = exe.iter().flat_map(|e| e.ancestors().skip(1).map(|a| a.join("shared/data")));
    let cwd = PathBuf::from(stopscan::experiment::DEFAULT_DATA);
    if let Some(found) =
        std::iter::once(built.clone()).chain(beside_exe).chain([cwd]).find(|p| p.is_dir())
    {
        return Ok(found);
    }
    bail!(
        "no benchmark data for views-benchmarks: tried $STOPSCAN_DATA (unset), {} (beside the checkout stopscan was built from), shared/data in every folder above {} and {} (from the current directory); pass --data DIR",
        built.display(),
        exe.map_or_else(|| "the executable".into(), |e| e.display().to_string()),
        stopscan::experiment::DEFAULT_DATA
    )
}

pub(crate) fn demo(g: &Global) -> anyhow::Result<()> {
    let exp::Demo { circles, strategies: four, chart } = exp::demo()?;
    let dir = g.out.clone().unwrap_or_else(|| PathBuf::from("stopscan-out"));
    ensure_dir(&dir)?;
    let files = save_chart(&dir, "circle-ratio", &chart)?;
    let setup = exp::paper_setup(2.0)?;
    let value = json!({
        "format": "stopscan-corner-demo/1",
        "circle": circles.iter().map(|s| json!({"distance": s.distance, "ratio": s.ratio, "scans": s.scans, "steps": s.steps, "scan_points": s.scan_points})).collect::<Vec<_>>(),
        "corner": {
            "distance": setup.distance, "cost_model": setup.cost, "delta": setup.delta(),
            "belief": "mix:0.5*normal:30,3+0.5*normal:90,3 on 5° buckets (the corner paper's distribution 4)",
            "mdp_step_deg": LineupOptions::default().mdp_step.to_degrees(),
            "strategies": four.iter().map(|(n, e, r)| json!({"name": n, "expected_time": e, "worst_ratio": r})).collect::<Vec<_>>(),
        },
        "files": files, "stopscan_version": stopscan::VERSION,
    });
    // Not run.json: that is the main job's run record, in the same default folder.
    write_json_atomic(&dir.join("corner-demo.json"), &value)?;
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == cli::Format::Json {
        writeln!(w, "{}", serde_json::to_string_pretty(&value)?)?;
        return Ok(());
    }
    writeln!(
        w,
        "stopscan {} — looking around a corner when every scan costs time\n",
        stopscan::VERSION
    )?;
    writeln!(w, "Circle strategy (scan cost 1, speed 1; the papers' lower bound is 2):")?;
    let mut t = Table::new(&["distance d", "ratio c(d)", "scans", "first step"]);
    for s in &circles {
        t.row(vec![
            num(Some(s.distance), 2),
            num(Some(s.ratio), 6),
            s.scans.to_string(),
            num(Some(s.steps[0]), 4),
        ]);
    }
    t.write(&mut w)?;
    writeln!(
        w,
        "\nCorner paper strategies, D = 10 m, τ = 2 s, v = 0.5 m/s, belief = truth = bimodal 30°/90°:"
    )?;
    let mut t = Table::new(&["strategy", "expected time (s)", "worst-case ratio"]);
    for (n, e, r) in &four {
        t.row(vec![n.clone(), num(Some(*e), 3), num(Some(*r), 4)]);
    }
    t.write(&mut w)?;
    writeln!(w, "\nwrote {}", dir.join("corner-demo.json").display())?;
    for f in &files {
        writeln!(w, "wrote {f}")?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stop_lists_by_name() {
        let r = Readings {
            last_step: cli::LastStepArg::Capped,
            exprec: cli::ExprecArg::TableI,
            route: cli::RouteArg::Arc,
        };
        assert_eq!(stop_list(RatioStrategy::Unirec, 0.5, &[], r).unwrap().len(), 4);
        assert!(stop_list(RatioStrategy::Stops, 0.5, &[], r).is_err());
        assert_eq!(stop_list(RatioStrategy::Stops, 0.5, &[30.0, 60.0], r).unwrap().len(), 3);
    }

    #[test]
    fn the_shared_data_is_found_from_the_checkout() {
        let built = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/data");
        if std::env::var_os("STOPSCAN_DATA").is_none() && built.is_dir() {
            // Whatever the current directory: the path is fixed at compile time.
            assert_eq!(data_dir(None).unwrap(), built);
        }
        let e = data_dir(Some(Path::new("/nonexistent"))).unwrap_err().to_string();
        assert!(e.contains("/nonexistent"), "{e}");
    }
}
