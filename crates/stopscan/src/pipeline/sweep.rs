//! Every environment file of a folder explored with one or every polygon strategy, in
//! parallel (`stopscan explore --env DIR`). A file that does not load does not end the sweep:
//! it is reported as a warning, and it gets one row per strategy with its error.

use std::path::{Path, PathBuf};

use super::explore::{ExploreError, ExploreOptions, check_budgets, check_range, check_simplify};
use crate::experiment::polygon::{SweepInput, SweepRow};
use crate::io::ros_map::RosMapOptions;
use crate::strategy::UnknownStrategy;
use crate::strategy::polygon::REGISTRY;

/// The extensions of the files a sweep reads (other files in the folder are left alone).
pub const EXTENSIONS: &[&str] = &["geojson", "json", "wkt", "pol", "yaml", "yml", "txt"];

/// Something the caller should tell the user; the sweep goes on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum SweepWarning {
    /// `range_limited` runs without a range (it then explores like the unlimited algorithm).
    #[error("range_limited runs with unlimited range (no --range)")]
    UnlimitedRange,
    /// A file did not load: its rows carry the error.
    #[error("{file}: not swept: {error}")]
    NotSwept {
        /// The file's name.
        file: String,
        /// Why, with its causes ([`super::error_message`]).
        error: String,
    },
}

/// What a sweep tells its caller as it goes (from several threads: the callback is `Sync`).
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum SweepEvent<'a> {
    /// A warning, before the runs start.
    Warning(&'a SweepWarning),
    /// The runs start: this many (files that loaded times strategies).
    Started {
        /// The number of runs.
        runs: u64,
    },
    /// One run finished.
    RunDone,
}

/// The environment files of `dir` (one level, by [`EXTENSIONS`]), sorted by path.
///
/// # Errors
/// [`ExploreError::ReadDir`] or, for a folder without any, [`ExploreError::NoFiles`].
pub fn environment_files(dir: &Path) -> Result<Vec<PathBuf>, ExploreError> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|source| ExploreError::ReadDir { path: dir.to_path_buf(), source })?
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().and_then(|x| x.to_str()).is_some_and(|x| EXTENSIONS.contains(&x)))
        .collect();
    files.sort();
    if files.is_empty() {
        return Err(ExploreError::NoFiles(dir.to_path_buf()));
    }
    Ok(files)
}

/// One part of a sweep split across machines: shard `index` of `count` (from 1) takes every
/// `count`-th environment file, starting with file `index` (files sorted by path). Any
/// scheduler can run the parts; their CSV files join in `stopscan merge`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which part, from 1.
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

impl Shard {
    /// Reads `I/N` (1 ≤ I ≤ N).
    ///
    /// # Errors
    /// A message naming what is wrong.
    pub fn parse(s: &str) -> Result<Self, String> {
        let (i, n) =
            s.split_once('/').ok_or_else(|| format!("expected I/N (such as 2/8), got {s:?}"))?;
        let number =
            |t: &str| t.trim().parse::<usize>().map_err(|_| format!("{t:?} is not a whole number"));
        let (index, count) = (number(i)?, number(n)?);
        if count == 0 || index == 0 || index > count {
            return Err(format!("the shard I/N needs 1 <= I <= N, got {index}/{count}"));
        }
        Ok(Self { index, count })
    }

    /// Whether the `k`-th file (from 0, in path order) is this shard's.
    pub fn takes(&self, k: usize) -> bool {
        k % self.count == self.index - 1
    }
}

/// The strategies `name` stands for: every registered one for `all`, else the one.
///
/// # Errors
/// [`ExploreError::Strategy`] for an unknown name (the message offers `all` too).
pub fn strategies(name: &str) -> Result<Vec<&'static str>, ExploreError> {
    if name == "all" {
        return Ok(REGISTRY.names().collect());
    }
    match REGISTRY.get(name) {
        Ok(e) => Ok(vec![e.name]),
        Err(e) => Err(UnknownStrategy { known: format!("{}, or all", e.known), ..e }.into()),
    }
}

/// The name a file's rows carry: its file name.
fn file_name(path: &Path) -> String {
    path.file_name().and_then(|n| n.to_str()).unwrap_or("?").to_string()
}

/// Checks a sweep's options and returns the strategies it runs ([`strategies`] of
/// `options.strategy`). A robot (a footprint or a window rule) is refused:
/// [`ExploreError::RobotInSweep`], as the rows are a point robot's; so is a scan limit
/// ([`ExploreError::LimitInSweep`]), as they are whole runs.
///
/// # Errors
/// [`ExploreError`] for an unknown strategy or bad options.
pub fn sweep_strategies(options: &ExploreOptions) -> Result<Vec<&'static str>, ExploreError> {
    let strategies = strategies(&options.strategy)?;
    check_range(&options.strategy, options.range)?;
    check_budgets(&options.limits)?;
    check_simplify(options.simplify)?;
    // The rows are a point robot's (coverage of the whole free space, the paper's bounds):
    // a robot's options would be silently ignored, so they are refused.
    if !options.footprint.is_point() {
        return Err(ExploreError::RobotInSweep("a footprint (--robot-radius, --footprint)"));
    }
    if options.max_scans.is_some() {
        return Err(ExploreError::LimitInSweep);
    }
    if options.lidar.is_some() {
        return Err(ExploreError::RobotInSweep("raw scans (--sensor, --odometry-drift)"));
    }
    if options.beams.is_some()
        || options.min_feature > 0.0
        || options.min_window.is_some()
        || options.min_pocket.is_some()
        || options.pocket_cap != super::explore::DEFAULT_POCKET_CAP
        || options.pocket_budget != super::explore::DEFAULT_POCKET_BUDGET
    {
        return Err(ExploreError::RobotInSweep(
            "a window rule (--beams, --min-feature, --min-window, --min-pocket, --pocket-cap, \
             --pocket-budget)",
        ));
    }
    Ok(strategies)
}

/// One file of a sweep loaded (a ROS map simplified within `simplify`), named by its file
/// name; or why it does not load, with its causes.
///
/// # Errors
/// The message a sweep's rows carry for a file that does not load.
pub fn load_input(file: &Path, simplify: Option<f64>) -> Result<SweepInput, String> {
    let map = RosMapOptions { simplify, ..RosMapOptions::default() };
    let (env, start) =
        crate::io::sweep::read_with_start(file, &map).map_err(|e| super::error_message(&e))?;
    Ok(SweepInput { name: file_name(file), domain: env.domain, start })
}

/// One run of a sweep, on its own: the row [`sweep_dir`] gives `strategy` on `input` with
/// `options` (checked by [`sweep_strategies`]) when the lower bounds have a budget of steps
/// (`options.limits.bounds_steps`), or finish within `options.limits.bounds_seconds` in
/// both. A sweep spread over machines runs these.
#[must_use]
pub fn sweep_run(input: &SweepInput, strategy: &str, options: &ExploreOptions) -> SweepRow {
    crate::experiment::polygon::sweep_single(
        input,
        strategy,
        &options.cost,
        options.range,
        options.limits.bounds(),
    )
}

/// Writes a sweep's rows as its CSV file (a header, then one line per row).
///
/// # Errors
/// What writing to `w` gives.
pub fn write_csv(rows: &[SweepRow], w: impl std::io::Write) -> std::io::Result<()> {
    let mut csv = csv::Writer::from_writer(w);
    for r in rows {
        csv.serialize(r.csv_row()).map_err(std::io::Error::other)?;
    }
    csv.flush()
}

/// Explores every environment file of `dir` ([`environment_files`]) with `options.strategy`
/// (or `all`), in parallel; rows come back in file order, strategies in registry order,
/// whatever the thread count. Each file's lower bounds are computed once, within
/// `options.limits.bounds_seconds`; `options.seed` and `options.trace` are not used; ROS maps are
/// read with `options.simplify`. A robot (a footprint or a window rule) is refused:
/// [`ExploreError::RobotInSweep`]. With a `shard`, only its files are explored (it may have
/// none, when there are more shards than files): the rows are the full sweep's rows of those
/// files, in the same order.
///
/// # Errors
/// [`ExploreError`] for a folder that cannot be read or holds no environment file, an unknown
/// strategy, or bad options. Files that do not load are not errors ([`SweepWarning`]).
pub fn sweep_dir(
    dir: &Path,
    options: &ExploreOptions,
    shard: Option<Shard>,
    on: &(dyn Fn(SweepEvent) + Sync),
) -> Result<Vec<SweepRow>, ExploreError> {
    let mut files = environment_files(dir)?;
    if let Some(shard) = shard {
        files = files
            .into_iter()
            .enumerate()
            .filter(|(k, _)| shard.takes(*k))
            .map(|(_, f)| f)
            .collect();
    }
    let strategies = sweep_strategies(options)?;
    if options.range.is_none() && strategies.contains(&"range_limited") {
        on(SweepEvent::Warning(&SweepWarning::UnlimitedRange));
    }
    // Indices into the inputs for the files that loaded, their errors for the others.
    let mut inputs: Vec<SweepInput> = Vec::new();
    let mut loaded: Vec<Result<usize, String>> = Vec::new();
    for f in &files {
        match load_input(f, options.simplify) {
            Ok(input) => {
                loaded.push(Ok(inputs.len()));
                inputs.push(input);
            }
            Err(error) => {
                on(SweepEvent::Warning(&SweepWarning::NotSwept {
                    file: file_name(f),
                    error: error.clone(),
                }));
                loaded.push(Err(error));
            }
        }
    }
    on(SweepEvent::Started { runs: (inputs.len() * strategies.len()) as u64 });
    let swept = crate::experiment::polygon::sweep(
        &inputs,
        &strategies,
        &options.cost,
        options.range,
        options.limits.bounds(),
        &|| on(SweepEvent::RunDone),
    );
    // Rows in file order; a file that did not load has one row per strategy with its error.
    let k = strategies.len();
    let mut rows = Vec::new();
    for (f, l) in files.iter().zip(&loaded) {
        match l {
            Ok(i) => rows.extend_from_slice(&swept[i * k..(i + 1) * k]),
            Err(e) => {
                let name = file_name(f);
                rows.extend(strategies.iter().map(|s| SweepRow::failed(&name, s, e.clone())));
            }
        }
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_that_does_not_load_is_a_warning_and_rows_with_its_error() {
        let dir = std::env::temp_dir().join(format!("stopscan-sweep-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("a.wkt"), "POLYGON ((0 0, 4 0, 4 4, 0 4, 0 0))\n").unwrap();
        std::fs::write(dir.join("b.wkt"), "POLYGON ((0 0, 4 0\n").unwrap();
        std::fs::write(dir.join("notes.md"), "not an environment").unwrap();
        let warnings = std::sync::Mutex::new(Vec::new());
        let options = ExploreOptions { strategy: "all".into(), ..ExploreOptions::default() };
        let rows = sweep_dir(&dir, &options, None, &|e| {
            if let SweepEvent::Warning(w) = e {
                warnings.lock().unwrap().push(w.to_string());
            }
        })
        .unwrap();
        let n = REGISTRY.len();
        assert_eq!(rows.len(), 2 * n);
        assert!(rows[..n].iter().all(|r| r.environment == "a.wkt" && r.error.is_empty()));
        assert!(rows[n..].iter().all(|r| r.environment == "b.wkt" && !r.error.is_empty()));
        let warnings = warnings.into_inner().unwrap();
        assert_eq!(warnings[0], "range_limited runs with unlimited range (no --range)");
        assert!(warnings[1].starts_with("b.wkt: not swept: "), "{warnings:?}");
        // Shard 2 of 2 takes the second file only: its rows are the full sweep's.
        let part = sweep_dir(&dir, &options, Some(Shard::parse("2/2").unwrap()), &|_| {}).unwrap();
        assert_eq!(part, rows[n..]);
        for bad in ["0/2", "3/2", "1/0", "2", "a/b"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        let e = strategies("warp").unwrap_err().to_string();
        assert!(e.ends_with("range_limited, or all"), "{e}");
    }
}
