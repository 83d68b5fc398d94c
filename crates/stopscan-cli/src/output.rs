//! Writing results: aligned tables for people, JSON for programs, files written atomically.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, bail};
use serde::Serialize;

use crate::cli::{Format, Global};

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

    pub(crate) fn write(&self, w: &mut dyn Write) -> std::io::Result<()> {
        let n = self.header.len();
        let mut width = vec![0; n];
        for r in std::iter::once(&self.header).chain(&self.rows) {
            for (k, c) in r.iter().enumerate().take(n) {
                width[k] = width[k].max(c.chars().count());
            }
        }
        let line = |w: &mut dyn Write, r: &[String]| -> std::io::Result<()> {
            let cells: Vec<String> = r
                .iter()
                .enumerate()
                .map(|(k, c)| {
                    let pad = width[k].saturating_sub(c.chars().count());
                    if k == 0 {
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

/// A spinner showing a message and the elapsed time on a terminal (hidden otherwise); it
/// ticks by itself, so it moves while a long computation runs.
pub(crate) fn spinner() -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new_spinner();
    bar.set_style(
        indicatif::ProgressStyle::with_template("{spinner} {msg} {elapsed}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
    );
    bar.enable_steady_tick(std::time::Duration::from_millis(200));
    bar
}

/// A progress bar of `len` units with the elapsed time and an estimate of the time left, on
/// a terminal only (hidden otherwise, as indicatif does).
pub(crate) fn bar(len: u64, unit: &str) -> indicatif::ProgressBar {
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template(&format!(
            "{{bar:40}} {{pos}}/{{len}} {unit} {{elapsed}}, about {{eta}} left"
        ))
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    bar
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

/// Writes `value` as pretty JSON to `path` atomically ([`write_atomic`]).
pub(crate) fn write_json_atomic<T: Serialize>(path: &Path, value: &T) -> anyhow::Result<()> {
    write_atomic(path, |w| {
        serde_json::to_writer_pretty(&mut *w, value)?;
        w.write_all(b"\n")
    })
}

/// The directory a file path lives in (`.` for a bare file name).
fn parent_of(path: &Path) -> &Path {
    path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."))
}

/// The temporary sibling of `path` that [`write_atomic`] writes first: hidden, the whole file
/// name kept (`.run.json.PID.tmp`), unique per process.
fn temp_sibling(path: &Path, pid: u32) -> Option<PathBuf> {
    let name = path.file_name()?.to_string_lossy();
    Some(parent_of(path).join(format!(".{name}.{pid}.tmp")))
}

/// Removes a temporary file unless it was renamed into place (on errors and panics alike).
struct TempGuard(Option<PathBuf>);

impl Drop for TempGuard {
    fn drop(&mut self) {
        if let Some(p) = self.0.take() {
            let _ = std::fs::remove_file(p);
        }
    }
}

/// Removes temporary siblings of `path` left by processes that no longer run (a SIGKILL cannot
/// be cleaned up after). Only where `/proc` tells which processes run.
fn remove_stale_temps(path: &Path) {
    let (Some(name), true) = (path.file_name(), Path::new("/proc/self").exists()) else {
        return;
    };
    let prefix = format!(".{}.", name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(parent_of(path)) else { return };
    for e in entries.flatten() {
        let file = e.file_name();
        let file = file.to_string_lossy();
        let Some(pid) = file.strip_prefix(&prefix).and_then(|r| r.strip_suffix(".tmp")) else {
            continue;
        };
        if pid.parse::<u32>().is_ok_and(|p| !Path::new(&format!("/proc/{p}")).exists()) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Writes a file atomically: `write` fills a temporary sibling ([`temp_sibling`]), which is
/// then renamed over `path`, so that a crash never leaves a half-written file in place of a
/// good one. The temporary file is removed on every failure; errors name `path`. Not
/// fsync'ed: a power cut may lose the newest write, never mix two.
pub(crate) fn write_atomic(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    check_file(path)?;
    remove_stale_temps(path);
    let tmp = temp_sibling(path, std::process::id())
        .with_context(|| format!("cannot write {}: not a file name", path.display()))?;
    let mut guard = TempGuard(Some(tmp.clone()));
    let io = (|| -> std::io::Result<()> {
        let mut w = std::io::BufWriter::new(std::fs::File::create(&tmp)?);
        write(&mut w)?;
        w.into_inner().map_err(std::io::IntoInnerError::into_error)?;
        std::fs::rename(&tmp, path)
    })();
    io.with_context(|| format!("cannot write {}", path.display()))?;
    guard.0 = None;
    Ok(())
}

/// Runs a library writer that writes `STEM.svg`, `STEM.png`, … atomically: it writes beside
/// them under a temporary stem, and each file is then renamed to `final_stem` with its
/// extension. Returns the final paths.
pub(crate) fn write_stem_atomic<E: std::fmt::Display>(
    final_stem: &Path,
    write: impl FnOnce(&Path) -> Result<Vec<PathBuf>, E>,
) -> anyhow::Result<Vec<PathBuf>> {
    let tmp_stem = temp_sibling(final_stem, std::process::id())
        .with_context(|| format!("cannot write {}: not a file name", final_stem.display()))?;
    let written = write(&tmp_stem);
    let mut guards: Vec<TempGuard> =
        ["svg", "png"].iter().map(|e| TempGuard(Some(tmp_stem.with_extension(e)))).collect();
    // Errors name the final files, not the temporary ones.
    let written = written.map_err(|e| {
        let tmp = tmp_stem.with_extension("").display().to_string();
        let fin = final_stem.with_extension("").display().to_string();
        anyhow::anyhow!("{}", e.to_string().replace(&tmp, &fin))
    })?;
    let mut out = Vec::new();
    for tmp in written {
        let fin = match tmp.extension() {
            Some(e) => final_stem.with_extension(e),
            None => final_stem.to_path_buf(),
        };
        guards.push(TempGuard(Some(tmp.clone())));
        std::fs::rename(&tmp, &fin).with_context(|| format!("cannot write {}", fin.display()))?;
        out.push(fin);
    }
    Ok(out)
}

/// A file output (`--out FILE`, `-o`, `--svg`, `--state`, `--trace`) can be written: it is not
/// a directory and its directory exists. stopscan never creates a file's directories.
pub(crate) fn check_file(path: &Path) -> anyhow::Result<()> {
    if path.is_dir() {
        bail!("cannot write {}: it is a directory", path.display());
    }
    let dir = parent_of(path);
    if !dir.is_dir() {
        bail!("cannot write {}: directory {} does not exist", path.display(), dir.display());
    }
    Ok(())
}

/// A directory output (`--out DIR` of commands that draw pictures, `stopscan-out`): created if
/// it is missing, as one level only (like `mkdir DIR`); its parent must exist.
pub(crate) fn ensure_dir(path: &Path) -> anyhow::Result<()> {
    if path.is_dir() {
        return Ok(());
    }
    if path.exists() {
        bail!(
            "cannot use {} as the output directory: it exists and is not a directory",
            path.display()
        );
    }
    let parent = parent_of(path);
    if !parent.is_dir() {
        bail!(
            "cannot create output directory {}: {} does not exist",
            path.display(),
            parent.display()
        );
    }
    std::fs::create_dir(path)
        .with_context(|| format!("cannot create output directory {}", path.display()))
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
        write_json_atomic(path, value)?;
    }
    Ok(())
}
