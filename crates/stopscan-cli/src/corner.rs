//! The corner commands, the demo and `reproduce`.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use serde::Serialize;
use serde_json::json;
use stopscan::experiment::corner::{self as exp, LineupOptions};
use stopscan::offline::corner::{expected, limit_ratio, optimal::optimal_scans_with, worst_case};
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use stopscan::render::{LineChart, Series, write_chart, write_policy_image};
use stopscan::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use stopscan::strategy::corner::registry;
use stopscan::strategy::corner::{ExprecReading, StopList, circle};

use crate::cli::{self, CornerCommand, Global, RatioStrategy, Readings};
use crate::output::{Table, emit, num, write_json_atomic};

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
        bail!("--{name} must be a finite positive number, got {v}");
    }
    Ok(v)
}

/// A directory for pictures from `--out`, or `None` when no pictures are wanted.
fn picture_dir(g: &Global) -> anyhow::Result<Option<PathBuf>> {
    match &g.out {
        None => Ok(None),
        Some(p) => {
            std::fs::create_dir_all(p)
                .with_context(|| format!("cannot create output directory {}", p.display()))?;
            Ok(Some(p.clone()))
        }
    }
}

fn save_chart(dir: &Path, name: &str, chart: &LineChart) -> anyhow::Result<Vec<String>> {
    Ok(write_chart(chart, &dir.join(name))?.iter().map(|p| p.display().to_string()).collect())
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
            title: format!("Circle strategy at d = {d}: c = {:.6}", s.ratio),
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
            "circle strategy at d = {d}: ratio c = {:.6}, {} intermediate scans (+1 at the corner)",
            s.ratio, s.scans
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
            "global optimum at d = {d} with at most {k} intermediate scans: ratio {:.6} with {} (exact for the points below)",
            o.ratio, o.scans
        )?;
        writeln!(
            w,
            "circle strategy at d = {d}: ratio {:.6} with {} scans",
            o.circle_ratio, o.circle_scans
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
        bail!("--ratio must exceed 1, got {c}");
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
            "c = {c} at d = {d}: {} after {} steps; farthest from the start {:.6} (Theorem 1 bound 1/(2 − c) = {})",
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
            let rad: Vec<f64> = stops_deg.iter().map(|d| d.to_radians()).collect();
            StopList::from_nominal(&rad, o.route, o.last_step)?
        }
    })
}

fn ratio(a: &cli::RatioArgs, g: &Global) -> anyhow::Result<()> {
    let delta = positive("delta", a.delta)?;
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
        writeln!(w2, "{name} at δ = {delta} ({} stops)", list.len())?;
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
            a.step_deg
        );
        files = write_policy_image(&p.image, &title, &dir.join(name))?
            .iter()
            .map(|p| p.display().to_string())
            .collect();
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
    if a.samples == 0 {
        bail!("--samples must be positive");
    }
    let mut names: Vec<String> = a.strategy.iter().map(|s| s.trim().to_lowercase()).collect();
    if names.iter().any(|n| n == "all") {
        names = registry::names().map(String::from).collect();
    }
    let opts =
        registry::BuildOptions { mdp_step: a.step_deg.to_radians(), ..build_options(a.readings) };
    let delta = setup.delta();
    let mut results = Vec::new();
    for (k, name) in names.iter().enumerate() {
        let list = registry::build(name, &setup, &belief, &opts)?;
        let e = expected(&list, &setup, &truth);
        let mc = exp::monte_carlo(
            &list,
            &setup,
            &truth,
            a.samples,
            stopscan::experiment::sample_seed(g.seed, k as u64),
        )?;
        let wc = worst_case(&list, &setup);
        results.push(json!({
            "strategy": name, "expected_time": e.time, "expected_scans": e.scans, "expected_distance": e.distance,
            "monte_carlo": mc, "worst_ratio": wc.worst_ratio, "stops": list.len(),
        }));
    }
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
            "{} samples, seed {}, D = {} m, τ = {} s, v = {} m/s, δ = {:.4}",
            a.samples, g.seed, setup.distance, setup.cost.scan_time, setup.cost.speed, delta
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

pub(crate) fn reproduce(a: &cli::ReproduceArgs, g: &Global) -> anyhow::Result<()> {
    let ids: Vec<&str> =
        if a.id == "all" { stopscan::experiment::ids() } else { vec![a.id.as_str()] };
    let mut outs = Vec::new();
    for id in ids {
        let r = match stopscan::experiment::reproduce_with_data(id, a.samples, g.seed, &a.data) {
            Ok(r) => r,
            // `all` without the benchmark data still reproduces everything else.
            Err(e) if a.id == "all" && id == "views-benchmarks" => {
                eprintln!("views-benchmarks skipped: {e}");
                continue;
            }
            Err(e) => return Err(e.into()),
        };
        let mut files = Vec::new();
        if let Some(dir) = picture_dir(g)? {
            for (name, chart) in &r.charts {
                files.extend(save_chart(&dir, name, chart)?);
            }
            for (name, title, image) in &r.images {
                files.extend(
                    write_policy_image(image, title, &dir.join(name))?
                        .iter()
                        .map(|p| p.display().to_string()),
                );
            }
            for (name, text) in &r.tables {
                let path = dir.join(name);
                std::fs::write(&path, text)
                    .with_context(|| format!("cannot write {}", path.display()))?;
                files.push(path.display().to_string());
            }
            let path = dir.join(format!("{id}.json"));
            write_json_atomic(
                &path,
                &ReproduceOut {
                    r: &r,
                    files: files.clone(),
                    seed: g.seed,
                    stopscan_version: stopscan::VERSION,
                },
            )?;
            files.push(path.display().to_string());
        }
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

pub(crate) fn demo(g: &Global) -> anyhow::Result<()> {
    let exp::Demo { circles, strategies: four, chart } = exp::demo()?;
    let dir = g.out.clone().unwrap_or_else(|| PathBuf::from("stopscan-out"));
    std::fs::create_dir_all(&dir)
        .with_context(|| format!("cannot create output directory {}", dir.display()))?;
    let files = save_chart(&dir, "circle-ratio", &chart)?;
    let setup = exp::paper_setup(2.0);
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
    write_json_atomic(&dir.join("run.json"), &value)?;
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
    writeln!(w, "\nwrote {}", dir.join("run.json").display())?;
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
}
