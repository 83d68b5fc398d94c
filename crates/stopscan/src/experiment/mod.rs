//! Sweeps, Monte Carlo and paper reproductions: seeded, parallel, deterministic.
//!
//! - [`corner`]: the corner and circle papers' tables and figures, and the corner demo;
//! - [`polygon`]: the discrete-visibility paper's worst cases and the benchmark sweeps;
//! - [`grid`]: Fig. 7 of the ROI paper;
//! - [`scans`]: the raw-scan pipeline's speed and ICP's convergence on scan pairs;
//! - here: [`reproduce`] by id ([`ids`]), [`Reproduction`] with its rows, and Monte Carlo
//!   summaries.

pub mod corner;
pub mod grid;
pub mod polygon;
pub mod scans;

/// Every reproduction identifier, of all families.
pub fn ids() -> Vec<&'static str> {
    corner::IDS.iter().chain(polygon::IDS).chain(grid::IDS).copied().collect()
}

/// Runs any reproduction by identifier; `views-benchmarks` reads [`SHARED_DATA`].
///
/// # Errors
/// [`ExperimentError::UnknownId`] for an unknown identifier; model errors otherwise.
pub fn reproduce(id: &str, samples: usize, seed: u64) -> Result<Reproduction, ExperimentError> {
    reproduce_with_data(id, samples, seed, std::path::Path::new(SHARED_DATA))
}

/// The shared benchmark data beside the checkout this crate was built from (fixed at compile
/// time, so it does not depend on the current directory).
pub const SHARED_DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../../shared/data");

/// Trials per point of `roi-fig-7` (the paper's 100); `--samples` lowers it.
pub const ROI_TRIALS: usize = 100;

/// The shared benchmark data beside a clone, relative to the current directory (the CLI's last
/// guess when `--data` is not given).
pub const DEFAULT_DATA: &str = "../shared/data";

/// [`reproduce`], with the folder of benchmark environments for `views-benchmarks`.
///
/// # Errors
/// [`ExperimentError::UnknownId`] for an unknown identifier; model errors otherwise (no
/// benchmark files below `data`, for one).
pub fn reproduce_with_data(
    id: &str,
    samples: usize,
    seed: u64,
    data: &std::path::Path,
) -> Result<Reproduction, ExperimentError> {
    if polygon::IDS.contains(&id) {
        return polygon::reproduce(id, data);
    }
    if grid::IDS.contains(&id) {
        return grid::reproduce(samples.min(ROI_TRIALS), seed);
    }
    corner::reproduce(id, samples, seed).map_err(|e| match e {
        ExperimentError::UnknownId(i, _) => ExperimentError::UnknownId(i, ids().join(", ")),
        other => other,
    })
}

use serde::{Deserialize, Serialize};

use crate::render::LineChart;
use crate::strategy::corner::mdp::StateAction;

/// One compared number: the paper's value beside ours.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// What is compared.
    pub label: String,
    /// The paper's value, when the paper prints one.
    pub paper: Option<f64>,
    /// Our value (exact where the quantity is an expectation).
    pub ours: f64,
    /// `(ours − paper) / |paper|`.
    pub rel_diff: Option<f64>,
    /// Our Monte Carlo estimate with the paper's sample count, when the paper's value is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub monte_carlo: Option<MonteCarlo>,
    /// The same quantity under other readings of the paper, shown beside the declared one
    /// (`ours`); each changes one choice of the reproduction's declared reading.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub other_readings: Vec<OtherReading>,
}

/// A compared number under a reading other than the declared one.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OtherReading {
    /// The reading, named by the one choice it changes (`capped last step`).
    pub reading: String,
    /// Our value under it.
    pub ours: f64,
    /// `(ours − paper) / |paper|`.
    pub rel_diff: Option<f64>,
    /// Our Monte Carlo estimate under it, when the row has one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub monte_carlo: Option<MonteCarlo>,
}

impl Row {
    /// A row; `rel_diff` is computed.
    pub fn new(label: impl Into<String>, paper: Option<f64>, ours: f64) -> Self {
        let rel_diff = paper.map(|p| (ours - p) / p.abs());
        Self {
            label: label.into(),
            paper,
            ours,
            rel_diff,
            monte_carlo: None,
            other_readings: Vec::new(),
        }
    }

    /// Adds the value under another reading; `rel_diff` is computed against the same paper value.
    #[must_use]
    pub fn with_other_reading(
        mut self,
        reading: impl Into<String>,
        ours: f64,
        monte_carlo: Option<MonteCarlo>,
    ) -> Self {
        let rel_diff = self.paper.map(|p| (ours - p) / p.abs());
        self.other_readings.push(OtherReading {
            reading: reading.into(),
            ours,
            rel_diff,
            monte_carlo,
        });
        self
    }

    /// Attaches a Monte Carlo estimate.
    #[must_use]
    pub fn with_monte_carlo(mut self, mc: MonteCarlo) -> Self {
        self.monte_carlo = Some(mc);
        self
    }
}

/// A Monte Carlo mean with its standard error.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct MonteCarlo {
    /// Sample mean.
    pub mean: f64,
    /// Standard error of the mean.
    pub std_err: f64,
    /// Number of samples.
    pub samples: usize,
}

/// A reproduced table or figure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reproduction {
    /// The identifier (`corner-table-2`, …).
    pub id: String,
    /// The model choices made, one sentence each.
    pub model: Vec<String>,
    /// The compared numbers.
    pub rows: Vec<Row>,
    /// Findings and explanations where numbers differ.
    pub notes: Vec<String>,
    /// Charts to write with `--out`.
    #[serde(skip)]
    pub charts: Vec<NamedChart>,
    /// Policy images to write with `--out`.
    #[serde(skip)]
    pub images: Vec<PolicyImage>,
    /// Tables to write with `--out`.
    #[serde(skip)]
    pub tables: Vec<CsvTable>,
}

/// A chart of a [`Reproduction`], written as `<stem>.svg` and `<stem>.png`.
#[derive(Debug, Clone, PartialEq)]
pub struct NamedChart {
    /// The file stem.
    pub stem: String,
    /// The chart.
    pub chart: LineChart,
}

impl NamedChart {
    /// A chart under a file stem.
    pub fn new(stem: impl Into<String>, chart: LineChart) -> Self {
        Self { stem: stem.into(), chart }
    }
}

/// A policy image of a [`Reproduction`]: the action in every MDP state, drawn as a picture.
#[derive(Debug, Clone, PartialEq)]
pub struct PolicyImage {
    /// The file stem.
    pub stem: String,
    /// The picture's title.
    pub title: String,
    /// The action in each state, one row per robot stop.
    pub actions: Vec<Vec<StateAction>>,
}

/// A table of a [`Reproduction`], written as CSV.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvTable {
    /// The file name, with its `.csv` extension.
    pub file: String,
    /// The CSV text.
    pub csv: String,
}

impl Reproduction {
    /// A reproduction: its identifier, the model choices made (one sentence each), the
    /// compared numbers and the findings. Charts, policy images and tables are added with
    /// [`with_charts`](Self::with_charts), [`with_images`](Self::with_images) and
    /// [`with_tables`](Self::with_tables).
    pub fn new(
        id: impl Into<String>,
        model: Vec<String>,
        rows: Vec<Row>,
        notes: Vec<String>,
    ) -> Self {
        Self {
            id: id.into(),
            model,
            rows,
            notes,
            charts: Vec::new(),
            images: Vec::new(),
            tables: Vec::new(),
        }
    }

    /// Sets the charts to write with `--out`.
    #[must_use]
    pub fn with_charts(mut self, charts: Vec<NamedChart>) -> Self {
        self.charts = charts;
        self
    }

    /// Sets the policy images to write with `--out`.
    #[must_use]
    pub fn with_images(mut self, images: Vec<PolicyImage>) -> Self {
        self.images = images;
        self
    }

    /// Sets the tables to write with `--out`.
    #[must_use]
    pub fn with_tables(mut self, tables: Vec<CsvTable>) -> Self {
        self.tables = tables;
        self
    }
}

/// Why an experiment could not run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExperimentError {
    /// The identifier is not known; the message lists the known ones.
    #[error("unknown reproduction {0:?}; known: {1}")]
    UnknownId(String, String),
    /// A simulated corner strategy misbehaved.
    #[error(transparent)]
    Sim(#[from] crate::sim::corner::CornerRunError),
    /// A corner setup (distance, cost model) was rejected.
    #[error(transparent)]
    Setup(#[from] crate::protocol::corner::InvalidCornerSetup),
    /// A belief or a truth was rejected.
    #[error(transparent)]
    Distribution(#[from] crate::protocol::corner::InvalidDistribution),
    /// UNIREC or EXPREC rejected its parameters.
    #[error(transparent)]
    StopList(#[from] crate::strategy::corner::InvalidStopList),
    /// A corner strategy could not be built by name.
    #[error(transparent)]
    Strategy(#[from] crate::strategy::corner::registry::BuildError),
    /// A corner MDP could not be built or solved.
    #[error(transparent)]
    Mdp(#[from] crate::strategy::corner::mdp::CornerMdpError),
    /// Fig. 5 of the corner paper has distributions 1 to 4 only.
    #[error("Fig. 5 has distributions 1 to 4, not {0}")]
    NoSuchFig5Distribution(usize),
    /// The MDP's policy did not go straight to the corner for any scan time up to 10⁶ s (the
    /// search for the scan time from which it does gave up).
    #[error("the policy never goes straight to the corner")]
    NeverStraight,
    /// A generated environment was rejected.
    #[error(transparent)]
    Environment(#[from] crate::geometry::InvalidEnvironment),
    /// An environment file could not be loaded.
    #[error(transparent)]
    Load(#[from] crate::io::LoadError),
    /// No benchmark environment was found below the data folder.
    #[error(
        "no benchmark environments (*.pol, ROS *.yaml) below {}; pass --data DIR",
        .0.display()
    )]
    NoBenchmarks(
        /// The folder searched.
        std::path::PathBuf,
    ),
    /// The visibility structure or a scan failed.
    #[error(transparent)]
    Visibility(#[from] crate::algorithm::visibility::VisibilityError),
    /// A polygon exploration was cut short.
    #[error(transparent)]
    Exploration(#[from] crate::sim::polygon::PolygonRunError),
    /// A region of interest was rejected.
    #[error(transparent)]
    Roi(#[from] crate::world::grid::InvalidRoi),
    /// A region-of-interest mission failed.
    #[error(transparent)]
    Mission(#[from] crate::sim::grid::GridRunError),
    /// The circle strategy rejected a distance.
    #[error(transparent)]
    Circle(#[from] crate::strategy::corner::circle::CircleError),
    /// The global corner optimum rejected its parameters.
    #[error(transparent)]
    Optimal(#[from] crate::offline::corner::optimal::OptimalError),
    /// A benchmark environment could not be loaded or given a start.
    #[error(transparent)]
    SweepLoad(#[from] crate::io::sweep::SweepLoadError),
}

/// Seeds one sample's generator from the run seed and the sample index, so results do not
/// depend on how samples are spread over threads.
pub fn sample_seed(seed: u64, index: u64) -> u64 {
    // SplitMix64 finaliser over the pair.
    let mut z =
        seed ^ index.wrapping_mul(0x9E37_79B9_7F4A_7C15).wrapping_add(0xD1B5_4A32_D192_ED03);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}
