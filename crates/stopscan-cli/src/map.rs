//! `stopscan map import`: any environment to GeoJSON.

use anyhow::bail;
use serde_json::json;

use crate::cli::{Global, ImportArgs, parse_point};
use crate::output::{emit, num};

/// A `--simplify` tolerance is a finite, non-negative number of metres.
pub(crate) fn check_simplify(simplify: Option<f64>) -> anyhow::Result<()> {
    if let Some(t) = simplify
        && !(t.is_finite() && t >= 0.0)
    {
        bail!(
            "--simplify must be a finite non-negative number of metres, got {}",
            stopscan::kernel::Num(t)
        );
    }
    Ok(())
}

pub(crate) fn import(a: &ImportArgs, g: &Global) -> anyhow::Result<()> {
    let output = crate::output::geojson_output(a.output.as_deref(), g)?;
    let start = a.start.as_deref().map(parse_point).transpose()?;
    if !(a.min_speck_area.is_finite() && a.min_speck_area >= 0.0) {
        bail!("--min-speck-area must be a non-negative number");
    }
    check_simplify(a.simplify)?;
    let is_map = a
        .file
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("yaml") || e.eq_ignore_ascii_case("yml"));
    let (env, report) = if is_map {
        let opts = stopscan::io::ros_map::RosMapOptions {
            start,
            min_speck_area: a.min_speck_area,
            simplify: a.simplify,
        };
        let m = stopscan::io::ros_map::read_with_report(&a.file, &opts)?;
        (m.environment, Some(m.report))
    } else {
        (stopscan::io::read_environment(&a.file)?, None)
    };
    let start = start.map(|s| env.frame.to_local(s)).or_else(|| env.default_start());
    let geo = stopscan::io::text_formats::to_geojson_in(&env.domain, start, &env.frame);
    stopscan::io::atomic::write_json(output, &geo)?;
    let d = &env.domain;
    let mut value = json!({
        "input": a.file, "output": output, "vertices": d.vertex_count(), "holes": d.holes().len(),
        "reflex_vertices": d.reflex_vertices().len(), "free_area": d.area(),
    });
    if let Some(r) = &report {
        value["simplification"] = serde_json::to_value(r)?;
    }
    emit(g, &value, false, |w| {
        writeln!(
            w,
            "{} -> {}: {} vertices, {} holes, {} reflex, free area {}",
            a.file.display(),
            output.display(),
            d.vertex_count(),
            d.holes().len(),
            d.reflex_vertices().len(),
            num(Some(d.area()), 3)
        )?;
        if let Some(r) = &report {
            writeln!(
                w,
                "simplified within {} m ({} cells of {} m): {} -> {} vertices, {} -> {} reflex, area {} -> {} m² (change {} m², {} %)",
                num(Some(r.tolerance_used), 3),
                num(Some(r.tolerance_used / r.resolution), 2),
                num(Some(r.resolution), 3),
                r.traced_vertices,
                r.vertices,
                r.traced_reflex_vertices,
                r.reflex_vertices,
                num(Some(r.traced_area), 3),
                num(Some(r.area), 3),
                num(Some(r.area_change), 3),
                num(Some(100.0 * r.relative_area_change), 3),
            )?;
        }
        Ok(())
    })
}
