//! `stopscan visibility` and `stopscan bench visibility`.

use std::io::Write;
use std::time::Instant;

use anyhow::{Context, bail};
use serde_json::json;
use stopscan::algorithm::visibility::range::MIN_ARC_TOLERANCE;
use stopscan::algorithm::visibility::range::{RangeRegion, clip};
use stopscan::algorithm::visibility::{
    BoundaryPiece, Visibility, VisibilityError, VisibilityRegion, expansion,
};
use stopscan::kernel::{Num, Point};

use crate::cli::{BenchArgs, Format, Global, VisibilityArgs, parse_point};
use crate::output::{Table, emit, num};

fn range_json(r: &RangeRegion, tolerance: f64) -> serde_json::Value {
    json!({
        "viewpoint": r.viewpoint,
        "range": r.radius,
        "area": r.area(),
        "polygon": r.to_polygon(tolerance),
        "arc_tolerance": tolerance,
        "boundary": r.boundary,
        "arcs": r.arcs().count(),
    })
}

fn check_range(range: Option<f64>, tol: Option<f64>) -> anyhow::Result<Option<(f64, f64)>> {
    let Some(r) = range else {
        if tol.is_some() {
            bail!("--arc-tolerance applies to range-limited regions: give --range R too");
        }
        return Ok(None);
    };
    if !(r.is_finite() && r > 0.0) {
        bail!("--range must be a finite positive distance, got {}", Num(r));
    }
    let t = tol.unwrap_or(r * 1e-4);
    if !(t.is_finite() && t > 0.0) {
        bail!("--arc-tolerance must be a finite positive distance, got {}", Num(t));
    }
    let min = r * MIN_ARC_TOLERANCE;
    if t < min {
        bail!(
            "--arc-tolerance {} is below R·1e-9 = {}: a full circle would need more than 70,000 vertices; give at least {} (the exact arcs are in \"boundary\" whatever the tolerance)",
            Num(t),
            Num(min),
            Num(min)
        );
    }
    Ok(Some((r, t)))
}

fn region_json(r: &VisibilityRegion) -> serde_json::Value {
    json!({
        "viewpoint": r.viewpoint,
        "area": r.area(),
        "polygon": r.polygon,
        "boundary": r.boundary,
        "windows": r.windows().count(),
    })
}

pub(crate) fn run(a: &VisibilityArgs, g: &Global) -> anyhow::Result<()> {
    let range = check_range(a.range, a.arc_tolerance)?;
    let env = stopscan::io::read_environment(&a.env)?;
    let frame = env.frame;
    let input = |p: Point| frame.to_input(p);
    let vis = Visibility::new(env.domain)?;
    if let Some(file) = &a.queries {
        let points = stopscan::io::read_points(file)?;
        if points.is_empty() {
            bail!("{}: no query points (one \"x y\" per line)", file.display());
        }
        let stdout = std::io::stdout();
        let mut w = stdout.lock();
        let mut scratch = expansion::Scratch::default();
        let mut region = VisibilityRegion::default();
        for (i, &q) in points.iter().enumerate() {
            vis.query_into(frame.to_local(q), &mut scratch, &mut region).with_context(|| {
                format!("{}:{}: query ({}, {})", file.display(), i + 1, Num(q[0]), Num(q[1]))
            })?;
            let v = match range {
                Some((r, t)) => range_json(&clip(&region, r).mapped(input), t),
                None => region_json(&region.mapped(input)),
            };
            writeln!(w, "{}", serde_json::to_string(&v)?)?;
        }
        return Ok(());
    }
    let Some(at) = &a.at else {
        bail!("give the viewpoint with --at X,Y or many with --queries FILE")
    };
    let q = parse_point(at)?;
    let r = vis.query(frame.to_local(q)).map_err(|e| match e {
        // The message names the viewpoint as given.
        VisibilityError::Outside(..) => VisibilityError::Outside(q[0], q[1]),
        e => e,
    })?;
    if let Some((radius, tol)) = range {
        let rr = clip(&r, radius);
        if g.format == Format::Svg {
            let approx = VisibilityRegion {
                viewpoint: r.viewpoint,
                polygon: rr.to_polygon(tol),
                boundary: vec![],
            };
            return write_svg(g, &vis, &approx);
        }
        let value = range_json(&rr.mapped(input), tol);
        return emit(g, &value, true, |w| {
            writeln!(
                w,
                "viewpoint ({}, {}) within {}: area {} (exact), {} pieces, {} arcs",
                Num(q[0]),
                Num(q[1]),
                Num(radius),
                num(Some(rr.area()), 6),
                rr.boundary.len(),
                rr.arcs().count()
            )
        });
    }
    if g.format == Format::Svg {
        return write_svg(g, &vis, &r);
    }
    let r = r.mapped(input);
    let value = region_json(&r);
    emit(g, &value, true, |w| {
        writeln!(
            w,
            "viewpoint ({}, {}): area {}, {} vertices, {} windows",
            Num(q[0]),
            Num(q[1]),
            num(Some(r.area()), 6),
            r.polygon.len(),
            r.windows().count()
        )?;
        let mut t = Table::new(&["piece", "kind", "from", "to"]);
        for (i, b) in r.boundary.iter().enumerate() {
            let kind = match b {
                BoundaryPiece::Edge { edge, .. } => format!("edge r{}e{}", edge.ring, edge.index),
                BoundaryPiece::Partial { edge, .. } => {
                    format!("partial r{}e{}", edge.ring, edge.index)
                }
                BoundaryPiece::Window { .. } => "window".into(),
                BoundaryPiece::Wall { .. } => "wall".into(),
                BoundaryPiece::Frontier { .. } => "range chord".into(),
            };
            let (f, to) = b.ends();
            t.row(vec![
                (i + 1).to_string(),
                kind,
                format!("({}, {})", num(Some(f[0]), 4), num(Some(f[1]), 4)),
                format!("({}, {})", num(Some(to[0]), 4), num(Some(to[1]), 4)),
            ]);
        }
        t.write(w)
    })
}

/// The scene as SVG, to `--out` or standard output.
fn write_svg(g: &Global, vis: &Visibility, region: &VisibilityRegion) -> anyhow::Result<()> {
    let svg = stopscan::render::scene_svg(vis.domain(), std::slice::from_ref(region));
    match &g.out {
        Some(path) => Ok(stopscan::io::atomic::write_bytes(path, svg.as_bytes())?),
        None => Ok(std::io::stdout().lock().write_all(svg.as_bytes())?),
    }
}

pub(crate) fn bench(a: &BenchArgs, g: &Global) -> anyhow::Result<()> {
    let Some(path) = &a.env else { bail!("bench visibility needs --env FILE") };
    let env = stopscan::io::read_environment(path)?;
    let queries = match &a.queries {
        Some(f) => {
            let q = stopscan::io::read_points(f)?;
            if q.is_empty() {
                bail!("{}: no query points (one \"x y\" per line)", f.display());
            }
            q.into_iter().map(|q| env.frame.to_local(q)).collect()
        }
        None => env.queries.clone(),
    };
    if queries.is_empty() {
        bail!("{} has no QUERIES section; give --queries FILE", path.display());
    }
    let vertices = env.domain.vertex_count();
    let mut pre = Vec::new();
    let mut vis = None;
    for _ in 0..a.repeat.clamp(1, 5) {
        let t = Instant::now();
        let v = Visibility::new(env.domain.clone())?;
        pre.push(t.elapsed().as_secs_f64());
        vis = Some(v);
    }
    let vis = vis.expect("at least one build");
    let mut scratch = expansion::Scratch::default();
    let mut region = VisibilityRegion::default();
    let range = check_range(a.range, None)?.map(|r| r.0);
    let mut total_vertices = 0usize;
    for &q in &queries {
        vis.query_into(q, &mut scratch, &mut region)?;
        total_vertices += match range {
            Some(r) => clip(&region, r).boundary.len(),
            None => region.polygon.len(),
        };
    }
    let runs: Vec<f64> = (0..a.repeat.max(1))
        .map(|_| {
            let t = Instant::now();
            for &q in &queries {
                let _ = vis.query_into(q, &mut scratch, &mut region);
                if let Some(r) = range {
                    std::hint::black_box(clip(&region, r));
                }
                std::hint::black_box(&region);
            }
            t.elapsed().as_secs_f64()
        })
        .collect();
    let secs = crate::bench::median(runs);
    let value = json!({
        "name": if range.is_some() { "visibility-range-limited" } else { "visibility-triangular-expansion" },
        "range": range,
        "vertices": vertices,
        "queries": queries.len(),
        "preprocess_seconds": crate::bench::median(pre),
        "queries_per_second": queries.len() as f64 / secs,
        "mean_output_vertices": total_vertices as f64 / queries.len() as f64,
        "repeat": a.repeat,
    });
    emit(g, &value, true, |w| writeln!(w, "{}", serde_json::to_string(&value).unwrap_or_default()))
}
