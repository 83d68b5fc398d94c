//! The soft size limits of the command line (lifted by `--allow-large`) and of the Python
//! bindings (lifted by `allow_large=True`): work above them is refused before anything is
//! allocated. Each says what one unit costs. Hard limits, which nothing lifts, live beside
//! the code they protect (`MAX_STOPS`, `MAX_FRAMES`, ...); the README's "Limits" table lists
//! both, with measurements.

/// Monte Carlo samples per strategy (`corner simulate`, `reproduce`): about 2 µs each.
pub const SAMPLES: u64 = 10_000_000;
/// UNIREC stops (`corner ratio`, `corner simulate`, `bench ratio`): 16 bytes and ~45 ns each.
pub const STOPS: u64 = 10_000_000;
/// Robots of a region-of-interest mission (`roi`, `bench roi`).
pub const ROBOTS: u64 = 10_000;
/// Cells of a region or of a search box (`roi --random`, `--search-box`, `bench roi --n`):
/// about 300 bytes and 2.5 µs each.
pub const CELLS: u64 = 4_000_000;
/// Camera frames a mission may render and classify, estimated as frames per scan times the
/// region's cells and a third of the search box (`roi --camera --frames`): ~0.6 ms each.
pub const FRAMES: u64 = 250_000;
/// Distances of `bench circle --n`: ~7 µs each per timed repetition (and one warm-up).
pub const DISTANCES: u64 = 1_000_000;
/// Office floors of `bench explore --n`: ~2.5 ms each.
pub const FLOORS: u64 = 10_000;
/// `generate --size` (turns, teeth, rooms per side) and `--desks`: 0.8–10 s at the limit.
pub const SIZE: u64 = 10_000;
/// `generate star --size` (spikes): the star's validation grows quadratically (3,000
/// spikes: 9 s).
pub const SPIKES: u64 = 1_000;
/// `generate forest --size` (pillars in a 30 m × 20 m rectangle: a few hundred fit).
pub const PILLARS: u64 = 1_000;

/// The camera frames a mission renders, estimated for [`FRAMES`]: every region cell is scanned
/// about once, and a third of the search box's cells, each with `frames` frames.
#[must_use]
pub fn camera_frames(
    region_cells: usize,
    search: Option<&crate::sim::grid::Search>,
    frames: usize,
) -> f64 {
    (region_cells as f64 + search.map_or(0.0, |s| s.cells() / 3.0)) * frames as f64
}
