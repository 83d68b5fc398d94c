//! `stopscan generate`: a generated instance as GeoJSON.

use std::io::Write;

use stopscan::generate::{self, Instance};

use crate::cli::{Family, GenerateArgs, Global};
use crate::limits;

pub(crate) fn run(a: &GenerateArgs, g: &Global) -> anyhow::Result<()> {
    let output = crate::output::geojson_output(a.output.as_deref(), g)?;
    let n = a.size;
    let (max, what) = match a.family {
        Family::Forest => {
            (limits::PILLARS, "pillars (a 30 m × 20 m rectangle holds a few hundred)")
        }
        Family::Star => (limits::SPIKES, "the star's checks grow with the square of its spikes"),
        _ => (limits::SIZE, "the work grows with the size, and with desks quadratically"),
    };
    limits::soft(g, n as f64, max, || format!("--size {n}"), what, "")?;
    limits::soft(
        g,
        a.desks as f64,
        limits::SIZE,
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
    stopscan::io::atomic::write_json(output, &geo)?;
    let d = &inst.domain;
    writeln!(
        std::io::stdout().lock(),
        "{}: {} vertices, {} holes, {} reflex",
        output.display(),
        d.vertex_count(),
        d.holes().len(),
        d.reflex_vertices().len()
    )?;
    Ok(())
}
