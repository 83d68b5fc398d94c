//! `stopscan explore`, `stopscan generate` and the main job.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use stopscan::generate::{self, Instance};
use stopscan::geometry::{Domain, Frame};
use stopscan::io::run_record::RunRecord;
use stopscan::kernel::Point;
use stopscan::offline::polygon::ReferenceLimits;
use stopscan::protocol::CostModel;
use stopscan::sim::polygon::Reframe;
use stopscan::world::polygon::PolygonWorld;

use crate::cli::{ExploreArgs, Family, Format, GenerateArgs, Global};
use crate::output::{Table, num, write_json_atomic};
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
    let Some(mut strat) = stopscan::strategy::polygon::by_name(j.strategy, &j.cost) else {
        let names: Vec<&str> = stopscan::strategy::polygon::REGISTRY.iter().map(|r| r.0).collect();
        bail!("unknown strategy {:?}; use one of: {}", j.strategy, names.join(", "));
    };
    if let Some(r) = j.range
        && !(r.is_finite() && r > 0.0)
    {
        bail!("--range must be a positive number of metres, got {r}");
    }
    let world = PolygonWorld::with_range(j.domain.clone(), j.range)?;
    let input = |p: Point| j.frame.to_input(p);
    if world.scan(j.start).is_err() {
        let s = input(j.start);
        bail!("the start ({}, {}) is outside the free space", s[0], s[1]);
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
        "{}: {} vertices, {} holes, r = {} reflex, free area {:.2} m²; strategy {}",
        e.name, e.vertices, e.holes, e.reflex_vertices, e.free_area, o.strategy.name
    )?;
    let mut t = Table::new(&["quantity", "value"]);
    let b = &o.bounds;
    let opt = |v: Option<usize>, why: &str| v.map_or_else(|| why.to_string(), |v| v.to_string());
    let optimum = match (b.optimum, b.optimum_best) {
        (Some(v), _) => format!("{v} (proven in {:.2} s, {})", b.optimum_seconds, b.optimum_solver),
        (None, Some(best)) => format!(
            "between {} and {best} (gap {}; {} after {:.2} s, {})",
            b.optimum_lower,
            best.saturating_sub(b.optimum_lower),
            b.optimum_note,
            b.optimum_seconds,
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
        if let Some(dir) = p.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        std::fs::write(p, &o.svg).with_context(|| format!("cannot write {}", p.display()))?;
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
        limits: ReferenceLimits::default(),
        seed: g.seed,
        trace: None,
    })?;
    let dir = g.out.clone().unwrap_or_else(|| PathBuf::from("stopscan-out"));
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    finish(g, &o, &dir.join("run.json"), Some(&dir.join("scene.svg")))
}

fn sweep_dir(a: &ExploreArgs, g: &Global) -> anyhow::Result<()> {
    use indicatif::{ProgressBar, ProgressStyle};
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
    let mut inputs = Vec::new();
    for f in &files {
        let env = stopscan::io::read_environment(f)?;
        let world = PolygonWorld::new(env.domain.clone())?;
        let start = env.queries.first().copied().unwrap_or_else(|| world.interior_point());
        let name = f.file_name().and_then(|n| n.to_str()).unwrap_or("?").to_string();
        inputs.push((name, env.domain, start));
    }
    let all: Vec<&str> = stopscan::strategy::polygon::REGISTRY.iter().map(|r| r.0).collect();
    let strategies: Vec<&str> = if a.strategy == "all" {
        all
    } else if all.contains(&a.strategy.as_str()) {
        vec![a.strategy.as_str()]
    } else {
        bail!("unknown strategy {:?}; use one of: {}, or all", a.strategy, all.join(", "));
    };
    let bar = ProgressBar::new((inputs.len() * strategies.len()) as u64);
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} runs {elapsed}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let cost = cost_of(a.scan_time, a.move_time, a.speed)?;
    let limits = limits_of(a)?;
    let rows = stopscan::experiment::polygon::sweep(
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
    let out = g.out.clone().unwrap_or_else(|| PathBuf::from("sweep.csv"));
    let tmp = out.with_extension("csv.tmp");
    {
        let mut w = csv::Writer::from_path(&tmp)
            .with_context(|| format!("cannot write {}", tmp.display()))?;
        for r in &rows {
            w.serialize(r)?;
        }
        w.flush()?;
    }
    std::fs::rename(&tmp, &out)?;
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
    for r in &rows {
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
        bounds_seconds: a.bounds_seconds,
        solver: stopscan::offline::polygon::Solver::by_name(&a.solver)
            .map_err(|e| anyhow::anyhow!("--solver: {e}"))?,
    })
}

pub(crate) fn run(a: &ExploreArgs, g: &Global) -> anyhow::Result<()> {
    if a.env.is_dir() {
        return sweep_dir(a, g);
    }
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
