//! Writing results: aligned tables for people, JSON for programs, and the progress display.

use std::io::Write;

use serde::Serialize;

use crate::cli::{Format, Global};

/// The longest cell of a table's last column that sets its width (characters).
const LONG_CELL: usize = 24;

/// A plain aligned text table.
pub(crate) struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    pub(crate) fn new(header: &[&str]) -> Self {
        Self { header: header.iter().map(|s| (*s).to_string()).collect(), rows: Vec::new() }
    }

    pub(crate) fn row(&mut self, cells: Vec<String>) {
        self.rows.push(cells);
    }

    /// Writes the table: the first column left-aligned, the others right-aligned. In the last
    /// column a cell longer than [`LONG_CELL`] characters (a sentence, such as why a reference
    /// was not computed) starts where the column starts and does not widen it, so that the
    /// numbers stay beside their names.
    pub(crate) fn write(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let n = self.header.len();
        let long = |k: usize, c: &str| n > 1 && k == n - 1 && c.chars().count() > LONG_CELL;
        let mut width = vec![0; n];
        for r in std::iter::once(&self.header).chain(&self.rows) {
            for (k, c) in r.iter().enumerate().take(n) {
                if !long(k, c) {
                    width[k] = width[k].max(c.chars().count());
                }
            }
        }
        let line = |w: &mut dyn Write, r: &[String]| -> std::io::Result<()> {
            let cells: Vec<String> = r
                .iter()
                .enumerate()
                .map(|(k, c)| {
                    let pad = width[k].saturating_sub(c.chars().count());
                    if k == 0 || long(k, c) {
                        format!("{c}{}", " ".repeat(pad))
                    } else {
                        format!("{}{c}", " ".repeat(pad))
                    }
                })
                .collect();
            writeln!(w, "{}", cells.join("  ").trim_end())
        };
        line(w, &self.header)?;
        writeln!(w, "{}", width.iter().map(|&x| "-".repeat(x)).collect::<Vec<_>>().join("  "))?;
        for r in &self.rows {
            line(w, r)?;
        }
        Ok(())
    }
}

/// The progress spinner: the library's progress lines and the elapsed time, on a terminal
/// only (hidden otherwise, as indicatif does). It ticks by itself, so it moves while a long
/// computation runs, and it is cleared when dropped, on success and error alike.
pub(crate) struct Spinner(indicatif::ProgressBar);

impl Spinner {
    pub(crate) fn new() -> Self {
        let bar = indicatif::ProgressBar::new_spinner();
        bar.set_style(
            indicatif::ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
        );
        bar.enable_steady_tick(std::time::Duration::from_millis(200));
        Self(bar)
    }

    /// Shows one progress line (a library `Progress` callback calls this).
    pub(crate) fn show(&self, line: &str) {
        self.0.set_message(line.to_string());
    }
}

impl Drop for Spinner {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}

/// A progress bar of `len` units with the elapsed time and an estimate of the time left, on
/// a terminal only (hidden otherwise, as indicatif does).
pub(crate) fn bar(len: u64, unit: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {unit} {{elapsed}}, about {{eta}} left {{msg}}"
        ))
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
}

/// The GeoJSON file a command that writes one (`map import`, `generate`) writes: its
/// `-o/--output`, or the global `--out`, every other command's output flag, when that is
/// given instead.
///
/// # Errors
/// Neither given, or both naming different files.
pub(crate) fn geojson_output<'a>(
    output: Option<&'a std::path::Path>,
    g: &'a Global,
) -> anyhow::Result<&'a std::path::Path> {
    match (output, g.out.as_deref()) {
        (Some(o), Some(u)) if o != u => {
            anyhow::bail!(
                "two files to write: -o/--output {} and --out {}",
                o.display(),
                u.display()
            )
        }
        (Some(o), _) | (None, Some(o)) => Ok(o),
        (None, None) => anyhow::bail!("say where to write the GeoJSON: -o/--output FILE"),
    }
}

/// Formats a float with `digits` decimals (in scientific notation from 1e15 on, so that a
/// huge number stays readable), `-` for missing values, `inf` and `-inf`.
pub(crate) fn num(v: Option<f64>, digits: usize) -> String {
    match v {
        Some(x) if x.is_finite() && x.abs() >= 1e15 => format!("{x:.digits$e}"),
        Some(x) if x.is_finite() => format!("{x:.digits$}"),
        Some(x) if x.is_infinite() => {
            if x > 0.0 {
                "inf".into()
            } else {
                "-inf".into()
            }
        }
        _ => "-".into(),
    }
}

/// A library parameter error in the words of the command line: `--NAME must …`.
pub(crate) fn flag_error(p: &stopscan::pipeline::InvalidParameter) -> anyhow::Error {
    anyhow::anyhow!("--{} must {}, got {}", p.name.replace('_', "-"), p.requirement, p.value)
}

/// `x` when it is finite: a table prints `-` where the JSON has `null`.
pub(crate) fn finite(x: f64) -> Option<f64> {
    x.is_finite().then_some(x)
}

/// Prints a result as JSON or as a table, and writes the JSON to `--out` for commands whose
/// `--out` is a file.
pub(crate) fn emit<T: Serialize>(
    g: &Global,
    value: &T,
    out_is_file: bool,
    table: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let stdout = std::io::stdout();
    let mut w = stdout.lock();
    match g.format {
        Format::Json => writeln!(w, "{}", serde_json::to_string_pretty(value)?)?,
        Format::Table | Format::Svg => table(&mut w)?,
    }
    w.flush()?;
    if out_is_file && let Some(path) = &g.out {
        stopscan::io::atomic::write_json(path, value)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sentence_in_the_last_column_does_not_push_the_numbers_away() {
        let mut t = Table::new(&["quantity", "value"]);
        t.row(vec!["scans".into(), "44".into()]);
        t.row(vec!["optimum".into(), "not attempted: 164 vertices, above the limit".into()]);
        t.row(vec!["distance (m)".into(), "346.951".into()]);
        let mut out = Vec::new();
        t.write(&mut out).unwrap();
        let text = String::from_utf8(out).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "quantity        value");
        assert_eq!(lines[1], "------------  -------");
        assert_eq!(lines[2], "scans              44");
        assert_eq!(lines[3], "optimum       not attempted: 164 vertices, above the limit");
        assert_eq!(lines[4], "distance (m)  346.951");
    }
}
