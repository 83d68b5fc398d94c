//! `stopscan reproduce`: paper tables and figures through [`stopscan::pipeline::reproduce`],
//! printed as tables or JSON; where the benchmark data is looked for.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::bail;
use stopscan::experiment::Reproduction;
use stopscan::pipeline::reproduce::ReproductionOutput;

use crate::cli::{self, Global};
use crate::limits;
use crate::output::{Table, num};

pub(crate) fn run(a: &cli::ReproduceArgs, g: &Global) -> anyhow::Result<()> {
    limits::soft(
        g,
        a.samples as f64,
        limits::SAMPLES,
        || format!("--samples {}", a.samples),
        "about 2 µs per sample and strategy",
        "",
    )?;
    let bar = std::cell::OnceCell::new();
    let outs = stopscan::pipeline::reproduce::reproduce(
        &a.id,
        a.samples,
        g.seed,
        &mut || data_dir(a.data.as_deref()).map_err(|e| e.to_string()),
        g.out.as_deref(),
        &mut |e| eprintln!("views-benchmarks skipped: {e}"),
        &mut |p| {
            let bar = bar.get_or_init(|| crate::output::bar(p.total as u64, "reproductions"));
            bar.set_position(p.index as u64);
            bar.set_message(p.id.to_string());
        },
    )?;
    if let Some(b) = bar.get() {
        b.finish_and_clear();
    }
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    if g.format == cli::Format::Json {
        // One object for one ID, an array for `all`.
        let text = match outs.as_slice() {
            [one] if a.id != "all" => serde_json::to_string_pretty(one)?,
            all => serde_json::to_string_pretty(all)?,
        };
        writeln!(w, "{text}")?;
        return Ok(());
    }
    for ReproductionOutput { reproduction: r, files, .. } in &outs {
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
    Ok(())
}

/// The rows of a reproduction as a table; other readings of the paper get one column each,
/// `=` where they equal ours.
fn rows_table(r: &Reproduction) -> Table {
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

#[cfg(test)]
mod tests {
    use super::*;

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
