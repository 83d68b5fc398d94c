//! `stopscan map import`: any environment to GeoJSON.

use anyhow::bail;
use serde_json::json;

use crate::cli::{Global, ImportArgs, parse_point};
use crate::output::{emit, num};

pub(crate) fn import(a: &ImportArgs, g: &Global) -> anyhow::Result<()> {
    let start = a.start.as_deref().map(parse_point).transpose()?;
    if !(a.min_speck_area.is_finite() && a.min_speck_area >= 0.0) {
        bail!("--min-speck-area must be a non-negative number");
    }
    let is_map = a
        .file
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("yaml") || e.eq_ignore_ascii_case("yml"));
    let env = if is_map {
        let opts = stopscan::io::ros_map::RosMapOptions {
            start,
            min_speck_area: a.min_speck_area,
            ..stopscan::io::ros_map::RosMapOptions::default()
        };
        stopscan::io::ros_map::read(&a.file, &opts)?
    } else {
        stopscan::io::read_environment(&a.file)?
    };
    let start = start.map(|s| env.frame.to_local(s)).or_else(|| env.default_start());
    let geo = stopscan::io::text_formats::to_geojson_in(&env.domain, start, &env.frame);
    stopscan::io::atomic::write_json(&a.output, &geo)?;
    let d = &env.domain;
    let value = json!({
        "input": a.file, "output": a.output, "vertices": d.vertex_count(), "holes": d.holes().len(),
        "reflex_vertices": d.reflex_vertices().len(), "free_area": d.area(),
    });
    emit(g, &value, false, |w| {
        writeln!(
            w,
            "{} -> {}: {} vertices, {} holes, {} reflex, free area {}",
            a.file.display(),
            a.output.display(),
            d.vertex_count(),
            d.holes().len(),
            d.reflex_vertices().len(),
            num(Some(d.area()), 3)
        )
    })
}
