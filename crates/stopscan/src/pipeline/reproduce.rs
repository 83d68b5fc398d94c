//! Paper reproductions as `stopscan reproduce` runs them: one identifier or all of them, each
//! with its charts, policy images, tables and JSON written into a folder.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::corner::{save_chart, save_policy_image};
use crate::experiment::{ExperimentError, Reproduction};
use crate::io::atomic::{self, WriteError};

/// One reproduction as the CLI prints it and writes it (`ID.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ReproductionOutput {
    /// The reproduction.
    #[serde(flatten)]
    pub reproduction: Reproduction,
    /// The files written (none without an output folder).
    pub files: Vec<String>,
    /// The seed.
    pub seed: u64,
    /// The library version.
    pub stopscan_version: String,
}

/// Why reproductions could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ReproduceError {
    /// The benchmark data of `views-benchmarks` could not be found; the message says where
    /// it was looked for.
    #[error("{0}")]
    Data(String),
    /// A reproduction failed (or the identifier is unknown).
    #[error(transparent)]
    Experiment(#[from] ExperimentError),
    /// A file could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// Writes a reproduction's charts, images, tables and JSON (`ID.json`) into `dir`; returns
/// their paths as text, the JSON last.
///
/// # Errors
/// [`WriteError`] naming the file.
pub fn write_files(
    dir: &Path,
    id: &str,
    r: &Reproduction,
    seed: u64,
) -> Result<Vec<String>, WriteError> {
    // A ReproductionOutput, borrowed.
    #[derive(Serialize)]
    struct Output<'a> {
        #[serde(flatten)]
        reproduction: &'a Reproduction,
        files: &'a [String],
        seed: u64,
        stopscan_version: &'a str,
    }
    let mut files = Vec::new();
    for c in &r.charts {
        files.extend(save_chart(dir, &c.stem, &c.chart)?);
    }
    for i in &r.images {
        files.extend(save_policy_image(dir, &i.stem, &i.title, &i.actions)?);
    }
    for t in &r.tables {
        let path = dir.join(&t.file);
        atomic::write_bytes(&path, t.csv.as_bytes())?;
        files.push(path.display().to_string());
    }
    let path = dir.join(format!("{id}.json"));
    let out = Output { reproduction: r, files: &files, seed, stopscan_version: crate::VERSION };
    atomic::write_json(&path, &out)?;
    files.push(path.display().to_string());
    Ok(files)
}

/// Which reproduction starts now: `index` (from 0) of `total`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ReproduceProgress<'a> {
    /// Its place, from 0.
    pub index: usize,
    /// How many in all.
    pub total: usize,
    /// Its ID.
    pub id: &'a str,
}

/// Runs the reproduction `id` (`all`: every one of [`crate::experiment::ids`]) with `samples`
/// Monte Carlo samples and `seed`, writing the files of each into `out` (created if missing)
/// when given. `data` finds the benchmark folder of `views-benchmarks` when it is run; under
/// `all`, a failure there skips that reproduction (`skipped` hears why) rather than ending
/// the others. `progress` hears each reproduction as it starts.
///
/// # Errors
/// [`ReproduceError`]: an unknown identifier, a reproduction that fails, missing benchmark
/// data for `views-benchmarks` asked by name, or a file that cannot be written.
pub fn reproduce(
    id: &str,
    samples: usize,
    seed: u64,
    data: &mut dyn FnMut() -> Result<PathBuf, String>,
    out: Option<&Path>,
    skipped: &mut dyn FnMut(&ReproduceError),
    progress: &mut dyn FnMut(ReproduceProgress),
) -> Result<Vec<ReproductionOutput>, ReproduceError> {
    let all = id == "all";
    let ids: Vec<&str> = if all { crate::experiment::ids() } else { vec![id] };
    let mut outs = Vec::new();
    let total = ids.len();
    for (index, id) in ids.into_iter().enumerate() {
        progress(ReproduceProgress { index, total, id });
        let dir = if id == "views-benchmarks" {
            data().map_err(ReproduceError::Data)
        } else {
            Ok(PathBuf::new())
        };
        let r = match dir
            .and_then(|d| Ok(crate::experiment::reproduce_with_data(id, samples, seed, &d)?))
        {
            Ok(r) => r,
            // `all` without the benchmark data still reproduces everything else.
            Err(e) if all && id == "views-benchmarks" => {
                skipped(&e);
                continue;
            }
            Err(e) => return Err(e),
        };
        let files = match out {
            Some(dir) => {
                atomic::ensure_dir(dir)?;
                write_files(dir, id, &r, seed)?
            }
            None => Vec::new(),
        };
        outs.push(ReproductionOutput {
            reproduction: r,
            files,
            seed,
            stopscan_version: crate::VERSION.into(),
        });
    }
    Ok(outs)
}
