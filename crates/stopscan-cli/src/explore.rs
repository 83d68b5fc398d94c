//! `stopscan explore`, `stopscan generate` and the main job.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use stopscan::experiment::polygon::{SweepInput, SweepRow};
use stopscan::generate::{self, Instance};
use stopscan::geometry::{Domain, Frame};
use stopscan::io::run_record::RunRecord;
use stopscan::kernel::{Num, Point};
use stopscan::offline::polygon::ReferenceLimits;
use stopscan::protocol::CostModel;
use stopscan::sim::polygon::Reframe;
use stopscan::world::polygon::PolygonWorld;

use crate::cli::{ExploreArgs, Family, Format, GenerateArgs, Global};
use crate::output::{Table, ensure_dir, num, write_atomic, write_json_atomic};
use crate::visibility::parse_point;

/// The built-in office floor (`stopscan generate office --size 6 --desks 16`), embedded.
const OFFICE: &str = include_str!("../../../fixtures/office.geojson");

struct Outcome {
    record: RunRecord,
    svg: String,
    /// Why the run was ended before the strategy was done; the record is the run so far.
    failure: Option<anyhow::Error>,
}

/// One exploration to run.
struct Job<'a> {
    name: &'a str,
    domain: &'a Domain,
    /// The domain's frame: `domain` and `start` are local, results are reported in the input's.
    frame: Frame,
    start: Point,
    strategy: &'a str,
    cost: CostModel,
    range: Option<f64>,
    limits: ReferenceLimits,
    seed: u64,
    /// Where to write the event trace (JSON lines), if anywhere.
    trace: Option<&'a Path>,
}

/// A spinner that counts scans and metres as the run goes (hidden when not a terminal).
struct Progress {
    bar: indicatif::ProgressBar,
    scans: u64,
    metres: f64,
}

impl Progress {
    fn new() -> Self {
        Self { bar: crate::output::spinner(), scans: 0, metres: 0.0 }
    }
}

impl<O> stopscan::sim::Observer<Point, O> for Progress {
    fn on_move(&mut self, _robot: usize, _to: &Point, metres: f64) -> std::ops::ControlFlow<()> {
        self.metres += metres;
        std::ops::ControlFlow::Continue(())
    }
    fn on_scan(&mut self, _robot: usize, _at: &Point, _o: &O) -> std::ops::ControlFlow<()> {
        self.scans += 1;
        self.bar.set_message(format!("{} scans, {:.1} m", self.scans, self.metres));
        self.bar.tick();
        std::ops::ControlFlow::Continue(())
    }
    fn on_finish(&mut self, _tally: &stopscan::protocol::Tally) {
        self.bar.finish_and_clear();
    }
}

fn explore(j: &Job) -> anyhow::Result<Outcome> {
    let mut strat = stopscan::strategy::polygon::build(j.strategy, &j.cost)?;
    if let Some(r) = j.range
        && !(r.is_finite() && r > 0.0)
    {
        bail!("--range must be a positive number of metres, got {r}");
    }
    let world = PolygonWorld::with_range(j.domain.clone(), j.range)?;
    let input = |p: Point| j.frame.to_input(p);
    if world.scan(j.start).is_err() {
        let s = input(j.start);
        bail!("the start ({}, {}) is outside the free space", Num(s[0]), Num(s[1]));
    }
    let mut progress = Progress::new();
    let result = match j.trace {
        None => {
            stopscan::sim::polygon::run(&world, j.start, &j.cost, strat.as_mut(), &mut progress)
        }
        Some(path) => {
            let file = std::fs::File::create(path)
                .with_context(|| format!("cannot write {}", path.display()))?;
            let mut trace = stopscan::sim::JsonLinesTrace::new(std::io::BufWriter::new(file));
            let result = {
                let mut reframed = Reframe { inner: &mut trace, frame: j.frame };
                let mut all = stopscan::sim::Fanout(vec![&mut reframed, &mut progress]);
                stopscan::sim::polygon::run(&world, j.start, &j.cost, strat.as_mut(), &mut all)
            };
            if let Some(e) = trace.error {
                return Err(
                    anyhow::Error::from(e).context(format!("cannot write {}", path.display()))
                );
            }
            result
        }
    };
    let (run, failure) = match result {
        Ok(run) => (run, None),
        Err(e) => (*e.partial, Some(anyhow::Error::from(e.error.map_places(input)))),
    };
    // A run cut short is not measured against the offline references (they take time, and a
    // ratio of an unfinished run means nothing); its record says why it ended.
    let limits = if failure.is_some() { ReferenceLimits::BOUNDS_ONLY } else { j.limits };
    let refs = {
        let bar = crate::output::spinner();
        let refs = stopscan::offline::polygon::references(
            world.visibility(),
            j.start,
            j.range,
            limits,
            &mut |stage| bar.set_message(format!("offline: {stage}")),
        );
        bar.finish_and_clear();
        refs?
    };
    let regions: Vec<_> = run.scans.iter().map(|s| s.region.clone()).collect();
    let svg = stopscan::render::exploration_svg(j.domain, &regions, &run.path);
    let mut record = RunRecord::polygon(j.name, &world, j.strategy, &j.cost, &run, &refs, j.seed)
        .in_frame(&j.frame);
    record.error = failure.as_ref().map(ToString::to_string);
    Ok(Outcome { record, svg, failure })
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
    let rows: Vec<(&str, String)> = vec![
        ("scans", m.scans.to_string()),
        ("moves", m.moves.to_string()),
        ("distance (m)", num(Some(m.distance), 3)),
        ("scan time (s)", num(Some(m.scan_time_total), 3)),
        ("move time (s)", num(Some(m.move_time_total), 3)),
        ("travel time (s)", num(Some(m.travel_time_total), 3)),
        ("total time (s)", num(Some(m.time), 3)),
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
    t.write(w)
}

fn cost_of(scan: f64, mv: f64, speed: f64) -> anyhow::Result<CostModel> {
    Ok(CostModel::new(scan, mv, speed)?)
}

fn finish(
    g: &Global,
    o: &Outcome,
    json_path: &Path,
    svg_path: Option<&Path>,
) -> anyhow::Result<()> {
    write_json_atomic(json_path, &o.record)?;
    if let Some(p) = svg_path {
        write_atomic(p, |w| w.write_all(o.svg.as_bytes()))?;
    }
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == Format::Json {
        writeln!(w, "{}", serde_json::to_string_pretty(&o.record)?)?;
    } else {
        summary(&mut w, &o.record)?;
        writeln!(w, "wrote {}", json_path.display())?;
        if let Some(p) = svg_path {
            writeln!(w, "wrote {}", p.display())?;
        }
    }
    match &o.failure {
        Some(e) => bail!("{e}; the record of the run so far is in {}", json_path.display()),
        None => Ok(()),
    }
}

pub(crate) fn main_job(g: &Global) -> anyhow::Result<()> {
    let env = stopscan::io::text_formats::parse_geojson(OFFICE, "built-in office floor")?;
    let start = env.queries.first().copied().context("the built-in office has a start")?;
    let o = explore(&Job {
        name: "office (built-in)",
        domain: &env.domain,
        frame: env.frame,
        start,
        strategy: "depth_first",
        cost: CostModel::default(),
        range: None,
        // The office (164 vertices) is beyond what the exact search proves within a few
        // seconds, and a search cut short by the clock would make the main job's output
        // depend on the machine: it is left to `explore`.
        limits: ReferenceLimits { optimum_max_vertices: 100, ..ReferenceLimits::default() },
        seed: g.seed,
        trace: None,
    })?;
    let dir = g.out.clone().unwrap_or_else(|| PathBuf::from("stopscan-out"));
    ensure_dir(&dir)?;
    finish(g, &o, &dir.join("run.json"), Some(&dir.join("scene.svg")))
}

fn sweep_dir(a: &ExploreArgs, g: &Global) -> anyhow::Result<()> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(&a.env)
        .with_context(|| format!("cannot read {}", a.env.display()))?
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            matches!(
                p.extension().and_then(|x| x.to_str()),
                Some("geojson" | "json" | "wkt" | "pol" | "yaml" | "yml" | "txt")
            )
        })
        .collect();
    files.sort();
    if files.is_empty() {
        bail!("{} holds no environment files (.geojson, .wkt, .pol, .yaml, .txt)", a.env.display());
    }
    let all: Vec<&str> = stopscan::strategy::polygon::REGISTRY.names().collect();
    let strategies: Vec<&str> = if a.strategy == "all" {
        all
    } else if all.contains(&a.strategy.as_str()) {
        vec![a.strategy.as_str()]
    } else {
        bail!("unknown strategy {:?}; use one of: {}, or all", a.strategy, all.join(", "));
    };
    check_range(&a.strategy, a.range)?;
    if a.range.is_none() && strategies.contains(&"range_limited") {
        eprintln!("warning: range_limited runs with unlimited range (no --range)");
    }
    let cost = cost_of(a.scan_time, a.move_time, a.speed)?;
    let limits = limits_of(a)?;
    let (inputs, loaded) = load_all(&files);
    let bar = crate::output::bar((inputs.len() * strategies.len()) as u64, "runs");
    let swept = stopscan::experiment::polygon::sweep(
        &inputs,
        &strategies,
        &cost,
        a.range,
        limits.bounds_seconds,
        &|| {
            bar.inc(1);
        },
    );
    bar.finish_and_clear();
    // Rows in file order; a file that did not load has one row per strategy with its error.
    let k = strategies.len();
    let mut rows = Vec::new();
    for (f, l) in files.iter().zip(&loaded) {
        match l {
            Ok(i) => rows.extend_from_slice(&swept[i * k..(i + 1) * k]),
            Err(e) => {
                let name = f.file_name().and_then(|n| n.to_str()).unwrap_or("?");
                rows.extend(strategies.iter().map(|s| SweepRow::failed(name, s, e.clone())));
            }
        }
    }
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("sweep.csv"));
    write_atomic(&out, |w| {
        let mut csv = csv::Writer::from_writer(w);
        for r in &rows {
            csv.serialize(r)?;
        }
        csv.flush()
    })?;
    print_sweep(&rows, &out)
}

/// Loads every file of a sweep. A file that does not load does not end the sweep: it gets a
/// warning, and its error goes into its rows (`Err`); the others are indices into the inputs.
fn load_all(files: &[PathBuf]) -> (Vec<SweepInput>, Vec<Result<usize, String>>) {
    let mut inputs = Vec::new();
    let mut loaded = Vec::new();
    for f in files {
        let name = f.file_name().and_then(|n| n.to_str()).unwrap_or("?").to_string();
        let env = stopscan::io::read_environment(f).map_err(anyhow::Error::from).and_then(|env| {
            let world = PolygonWorld::new(env.domain.clone())?;
            let start = env.queries.first().copied().unwrap_or_else(|| world.interior_point());
            Ok((env.domain, start))
        });
        match env {
            Ok((domain, start)) => {
                loaded.push(Ok(inputs.len()));
                inputs.push((name, domain, start));
            }
            Err(e) => {
                let msg = crate::error_chain(&e);
                eprintln!("warning: {name}: not swept: {msg}");
                loaded.push(Err(msg));
            }
        }
    }
    (inputs, loaded)
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
            r.scans.to_string(),
            r.scans_upper.to_string(),
            if r.error.is_empty() {
                r.within_bound.to_string()
            } else {
                format!("error: {}", r.error)
            },
            num(Some(r.distance), 2),
            num(Some(r.coverage), 9),
        ]);
    }
    t.write(&mut w)?;
    writeln!(w, "wrote {}", out.display())?;
    Ok(())
}

fn limits_of(a: &ExploreArgs) -> anyhow::Result<ReferenceLimits> {
    for (flag, v) in
        [("--optimum-seconds", a.optimum_seconds), ("--bounds-seconds", a.bounds_seconds)]
    {
        if !(v.is_finite() && (0.0..=86_400.0).contains(&v)) {
            bail!("{flag} must be between 0 and 86400 seconds, got {v}");
        }
    }
    Ok(ReferenceLimits {
        greedy_max_vertices: a.greedy_max_vertices,
        optimum_max_vertices: a.optimum_max_vertices,
        optimum_seconds: a.optimum_seconds,
        optimum_nodes: a.optimum_nodes.map(|n| n as u64),
        bounds_seconds: a.bounds_seconds,
        solver: stopscan::offline::polygon::Solver::by_name(&a.solver)
            .map_err(|e| anyhow::anyhow!("--solver: {e}"))?,
    })
}

/// `--range` is a positive distance, and `range_limited`, named explicitly, needs one (the
/// paper's algorithm for an unlimited sensor is depth_first).
fn check_range(strategy: &str, range: Option<f64>) -> anyhow::Result<()> {
    if let Some(r) = range
        && !(r.is_finite() && r > 0.0)
    {
        bail!("--range must be a positive number of metres, got {}", Num(r));
    }
    if strategy == "range_limited" && range.is_none() {
        bail!(
            "--strategy range_limited needs --range R (metres); for an unlimited range the paper's algorithm is depth_first"
        );
    }
    Ok(())
}

pub(crate) fn run(a: &ExploreArgs, g: &Global) -> anyhow::Result<()> {
    if a.env.is_dir() {
        return sweep_dir(a, g);
    }
    check_range(&a.strategy, a.range)?;
    let env = stopscan::io::read_environment(&a.env)?;
    let start = match &a.start {
        Some(s) => env.frame.to_local(parse_point(s)?),
        None => match env.queries.first() {
            Some(&p) => p,
            None => PolygonWorld::new(env.domain.clone())?.interior_point(),
        },
    };
    let name = a.env.file_stem().and_then(|s| s.to_str()).unwrap_or("environment");
    let o = explore(&Job {
        name,
        domain: &env.domain,
        frame: env.frame,
        start,
        strategy: &a.strategy,
        cost: cost_of(a.scan_time, a.move_time, a.speed)?,
        range: a.range,
        limits: limits_of(a)?,
        seed: g.seed,
        trace: a.trace.as_deref(),
    })?;
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("run.json"));
    finish(g, &o, &out, a.svg.as_deref())
}

pub(crate) fn generate(a: &GenerateArgs, g: &Global) -> anyhow::Result<()> {
    let n = a.size;
    let (max, what) = match a.family {
        Family::Forest => {
            (crate::limits::PILLARS, "pillars (a 30 m × 20 m rectangle holds a few hundred)")
        }
        Family::Star => {
            (crate::limits::SPIKES, "the star's checks grow with the square of its spikes")
        }
        _ => (crate::limits::SIZE, "the work grows with the size, and with desks quadratically"),
    };
    crate::limits::soft(g, n as f64, max, || format!("--size {n}"), what, "")?;
    crate::limits::soft(
        g,
        a.desks as f64,
        crate::limits::SIZE,
        || format!("--desks {}", a.desks),
        "each desk is tested against every other",
        "",
    )?;
    let inst: Instance = match a.family {
        Family::Spiral => generate::spiral(n)?,
        Family::Star => generate::star(n)?,
        Family::Comb => generate::comb(n)?,
        Family::Office => generate::office(n, a.desks, g.seed)?,
        Family::Forest => generate::pillar_forest(30.0, 20.0, n, g.seed)?,
    };
    let geo = stopscan::io::text_formats::to_geojson(&inst.domain, Some(inst.start));
    write_json_atomic(&a.output, &geo)?;
    let d = &inst.domain;
    writeln!(
        std::io::stdout().lock(),
        "{}: {} vertices, {} holes, {} reflex",
        a.output.display(),
        d.vertex_count(),
        d.holes().len(),
        d.reflex_vertices().len()
    )?;
    Ok(())
}
