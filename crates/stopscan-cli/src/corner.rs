//! The corner commands and the demo: the arguments go to [`stopscan::pipeline::corner`], the
//! typed reports come back as tables or JSON.

use std::io::Write;
use std::path::PathBuf;

use anyhow::bail;
use serde::Serialize;
use stopscan::kernel::Num;
use stopscan::pipeline::corner::{self as pipeline, CornerError, PolicyOptions, Simulation};
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{CornerSetup, LastStep, Route};
use stopscan::strategy::corner::mdp::{Memory, Reading};
use stopscan::strategy::corner::registry::BuildOptions;
use stopscan::strategy::corner::{ExprecReading, unirec_stops};

use crate::cli::{self, CornerCommand, Global, RatioStrategy, Readings};
use crate::limits;
use crate::output::{Spinner, Table, emit, finite, flag_error, num};

pub(crate) fn run(command: &CornerCommand, g: &Global) -> anyhow::Result<()> {
    match command {
        CornerCommand::Demo => demo(g),
        CornerCommand::Circle { distance } => circle(*distance, g),
        CornerCommand::Thresholds { count } => thresholds(*count, g),
        CornerCommand::Optimal { distance, scans } => optimal(*distance, *scans, g),
        CornerCommand::Collapse { ratio, distance } => collapse(*ratio, *distance, g),
        CornerCommand::Ratio(a) => ratio(a, g),
        CornerCommand::Policy(a) => policy(a, g),
        CornerCommand::Simulate(a) => simulate(a, g),
    }
}

/// A corner error in the words of the command line.
fn corner_error(e: CornerError) -> anyhow::Error {
    match e {
        CornerError::Parameter(p) => flag_error(&p),
        CornerError::StopsNeeded => {
            anyhow::anyhow!("--strategy stops needs --stops-deg A,B,C (degrees, increasing)")
        }
        CornerError::Stops(e) => anyhow::anyhow!("--stops-deg: {e}"),
        e => e.into(),
    }
}

/// A report as JSON with its keys sorted, as the corner commands have always printed it.
fn sorted<T: Serialize>(report: &T) -> anyhow::Result<serde_json::Value> {
    Ok(serde_json::to_value(report)?)
}

fn circle(d: f64, g: &Global) -> anyhow::Result<()> {
    let s = pipeline::circle(d, g.out.as_deref()).map_err(corner_error)?;
    emit(g, &sorted(&s)?, false, |w| {
        writeln!(
            w,
            "circle strategy at d = {}: ratio c = {:.6}, {} intermediate scans (+1 at the corner)",
            Num(d),
            s.ratio,
            s.scans
        )?;
        let mut t = Table::new(&["scan", "step", "x", "y", "angle at corner (deg)"]);
        for (k, ((x, p), a)) in s.steps.iter().zip(&s.scan_points).zip(&s.angles_deg).enumerate() {
            let label = if k == s.scans { "corner".to_string() } else { (k + 1).to_string() };
            t.row(vec![
                label,
                num(Some(*x), 6),
                num(Some(p[0]), 6),
                num(Some(p[1]), 6),
                num(Some(*a), 4),
            ]);
        }
        t.write(w)
    })
}

fn thresholds(count: usize, g: &Global) -> anyhow::Result<()> {
    let r = pipeline::thresholds(count).map_err(corner_error)?;
    emit(g, &sorted(&r)?, true, |w| {
        let mut t = Table::new(&["scans", "maximal d", "c at upper bound"]);
        for r in &r.thresholds {
            t.row(vec![r.scans.to_string(), num(Some(r.distance), 6), num(Some(r.ratio), 6)]);
        }
        t.write(w)
    })
}

fn optimal(d: f64, k: usize, g: &Global) -> anyhow::Result<()> {
    let spinner = Spinner::new();
    let r = pipeline::optimal(d, k, g.seed, &mut |m| spinner.show(m)).map_err(corner_error)?;
    drop(spinner);
    let o = &r.optimum;
    emit(g, &sorted(&r)?, true, |w| {
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
    let r = pipeline::collapse(c, d).map_err(corner_error)?;
    emit(g, &r, true, |w| {
        writeln!(
            w,
            "c = {} at d = {}: {} after {} steps; farthest from the start {:.6} (Theorem 1 bound 1/(2 − c) = {})",
            Num(r.ratio),
            Num(r.distance),
            if r.reached { "reaches the corner" } else { "collapses" },
            r.steps,
            r.farthest,
            num(Some(r.bound), 6)
        )
    })
}

fn build_options(r: Readings) -> BuildOptions {
    BuildOptions {
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
        ..BuildOptions::default()
    }
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

fn ratio(a: &cli::RatioArgs, g: &Global) -> anyhow::Result<()> {
    // δ is checked here too: the soft limit on UNIREC's stops needs a valid one.
    let delta = a.delta;
    if !(delta.is_finite() && delta > 0.0) {
        bail!("--delta must be a finite positive number, got {}", Num(delta));
    }
    if a.strategy == RatioStrategy::Unirec {
        check_unirec(g, &format!("--delta {}", Num(delta)), delta)?;
    }
    let name = format!("{:?}", a.strategy).to_lowercase();
    let r = pipeline::ratio(&name, delta, &a.stops_deg, &build_options(a.readings))
        .map_err(corner_error)?;
    emit(g, &sorted(&r)?, true, |w| {
        writeln!(w, "{name} at δ = {} ({} stops)", Num(delta), r.stops)?;
        let mut t = Table::new(&["quantity", "value", "θ (deg)"]);
        t.row(vec![
            "worst ratio (strict sup over θ > 0)".into(),
            num(Some(r.worst_ratio), 6),
            num(Some(r.theta_at_worst_deg), 4),
        ]);
        t.row(vec![
            format!("asymptotic ratio (b = {:.3}τ)", r.additive_constant),
            num(Some(r.asymptotic_ratio), 6),
            num(Some(r.theta_at_asymptotic.to_degrees()), 4),
        ]);
        t.row(vec!["limit as δ → 0 (papers)".into(), num(r.limit_ratio, 6), "-".into()]);
        t.write(w)
    })
}

fn setup_of(s: cli::SetupArgs) -> anyhow::Result<CornerSetup> {
    Ok(CornerSetup::new(s.distance, CostModel::new(s.scan_time, s.move_time, s.speed)?)?)
}

fn policy(a: &cli::PolicyArgs, g: &Global) -> anyhow::Result<()> {
    let options = PolicyOptions {
        setup: setup_of(a.setup)?,
        belief: &a.belief,
        truth: a.truth.as_deref(),
        memory: match a.memory {
            cli::MemoryArg::None => Memory::None,
            cli::MemoryArg::Last => Memory::Last,
        },
        reading: match a.reading {
            cli::ReadingArg::Conditional => Reading::Conditional,
            cli::ReadingArg::Literal => Reading::Literal,
        },
        step_deg: a.step_deg,
        general: a.solver == cli::SolverArg::General,
    };
    let p = pipeline::policy(&options, g.out.as_deref()).map_err(corner_error)?;
    emit(g, &sorted(&p)?, false, |w| {
        writeln!(
            w,
            "{} policy, {} stops ({} states), belief {}",
            if p.memory == Memory::Last { "MDP2" } else { "MDP1" },
            p.stops,
            p.states,
            a.belief
        )?;
        writeln!(
            w,
            "expected time {:.4} s (MDP value {:.4} s), expected scans {:.3}",
            p.expected_time, p.model_value, p.expected_scans
        )?;
        let angles: Vec<String> = p.scan_angles_deg.iter().map(|x| format!("{x:.1}")).collect();
        writeln!(w, "scans at (deg) while unseen: {}", angles.join(", "))
    })
}

fn simulate(a: &cli::SimulateArgs, g: &Global) -> anyhow::Result<()> {
    let options = BuildOptions { mdp_step: a.step_deg.to_radians(), ..build_options(a.readings) };
    let sim =
        Simulation::new(setup_of(a.setup)?, &a.belief, a.truth.as_deref(), &a.strategy, options)
            .map_err(corner_error)?;
    limits::soft(
        g,
        a.samples as f64,
        limits::SAMPLES,
        || format!("--samples {} per strategy", a.samples),
        "about 2 µs per sample; the exact expectation is printed beside the estimate",
        "",
    )?;
    let delta = sim.setup.delta();
    if sim.strategies.iter().any(|n| n == "unirec") {
        check_unirec(g, &format!("unirec at δ = τv/D = {}", Num(delta)), delta)?;
    }
    let bar = crate::output::bar((a.samples * sim.strategies.len()) as u64, "samples");
    let report = sim.run(a.samples, g.seed, &|n| bar.inc(n));
    bar.finish_and_clear();
    let report = report.map_err(corner_error)?;
    emit(g, &sorted(&report)?, true, |w| {
        let mut t = Table::new(&[
            "strategy",
            "exact E[time] (s)",
            "Monte Carlo (s)",
            "± s.e.",
            "E[scans]",
            "worst ratio",
        ]);
        for r in &report.results {
            t.row(vec![
                r.strategy.clone(),
                num(finite(r.expected_time), 3),
                num(finite(r.monte_carlo.mean), 3),
                num(finite(r.monte_carlo.std_err), 3),
                num(finite(r.expected_scans), 3),
                num(finite(r.worst_ratio), 4),
            ]);
        }
        writeln!(
            w,
            "{} samples, seed {}, D = {} m, τ = {} s, v = {} m/s, δ = {}",
            a.samples,
            g.seed,
            Num(sim.setup.distance),
            Num(sim.setup.cost.scan_time),
            Num(sim.setup.cost.speed),
            num(Some(delta), 4)
        )?;
        t.write(w)
    })
}

pub(crate) fn demo(g: &Global) -> anyhow::Result<()> {
    let dir = g.out.clone().unwrap_or_else(|| PathBuf::from("stopscan-out"));
    let report = pipeline::demo(&dir).map_err(corner_error)?;
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == cli::Format::Json {
        writeln!(w, "{}", serde_json::to_string_pretty(&sorted(&report)?)?)?;
        return Ok(());
    }
    writeln!(
        w,
        "stopscan {} — looking around a corner when every scan costs time\n",
        stopscan::VERSION
    )?;
    writeln!(w, "Circle strategy (scan cost 1, speed 1; the papers' lower bound is 2):")?;
    let mut t = Table::new(&["distance d", "ratio c(d)", "scans", "first step"]);
    for s in &report.circle {
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
    for s in &report.corner.strategies {
        t.row(vec![s.name.clone(), num(Some(s.expected_time), 3), num(Some(s.worst_ratio), 4)]);
    }
    t.write(&mut w)?;
    writeln!(w, "\nwrote {}", pipeline::demo_json(&dir).display())?;
    for f in &report.files {
        writeln!(w, "wrote {f}")?;
    }
    Ok(())
}
