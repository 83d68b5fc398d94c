//! Soft size limits: work above them is refused before anything is allocated, with a message
//! that names the flag, what it implies, the limit with its cost, and the way out
//! (`--allow-large`). Hard limits, which no flag lifts, live in the library beside the code
//! they protect (`MAX_STOPS`, `MAX_BUCKETS`, `MAX_STOPS_MDP1/2`, `MAX_FRAMES`,
//! `MIN_ARC_TOLERANCE`). The README's "Limits" table lists both, with measurements.

use anyhow::bail;

use crate::cli::Global;

/// Monte Carlo samples per strategy (`corner simulate`, `reproduce`): about 2 µs each.
pub(crate) const SAMPLES: u64 = 10_000_000;
/// UNIREC stops (`corner ratio`, `corner simulate`, `bench ratio`): 16 bytes and ~45 ns each.
pub(crate) const STOPS: u64 = 10_000_000;
/// Robots of a region-of-interest mission (`roi`, `bench roi`).
pub(crate) const ROBOTS: u64 = 10_000;
/// Cells of a region or of a search box (`roi --random`, `--search-box`, `bench roi --n`):
/// about 300 bytes and 2.5 µs each.
pub(crate) const CELLS: u64 = 4_000_000;
/// Camera frames a mission may render and classify, estimated as frames per scan times the
/// region's cells and a third of the search box (`roi --camera --frames`): ~0.6 ms each.
pub(crate) const FRAMES: u64 = 250_000;
/// Distances of `bench circle --n`: ~7 µs each per timed repetition (and one warm-up).
pub(crate) const DISTANCES: u64 = 1_000_000;
/// Office floors of `bench explore --n`: ~2.5 ms each.
pub(crate) const FLOORS: u64 = 10_000;
/// `generate --size` (turns, teeth, rooms per side) and `--desks`: 0.8–10 s at the limit.
pub(crate) const SIZE: u64 = 10_000;
/// `generate star --size` (spikes): the star's validation grows quadratically (3,000
/// spikes: 9 s).
pub(crate) const SPIKES: u64 = 1_000;
/// `generate forest --size` (pillars in a 30 m × 20 m rectangle: a few hundred fit).
pub(crate) const PILLARS: u64 = 1_000;

/// `x` with four significant digits, rounded up (`1.571e-7`): a smallest allowed value.
pub(crate) fn at_least(x: f64) -> String {
    if !(x.is_finite() && x > 0.0) {
        return stopscan::kernel::Num(x).to_string();
    }
    let unit = 10f64.powf(x.log10().floor() - 3.0);
    format!("{:.3e}", (x / unit).ceil() * unit)
}

/// `n` with thousands separators (`10,000,000`), or in scientific notation beyond 10^18.
pub(crate) fn count(n: f64) -> String {
    if !(n.is_finite() && n.abs() < 1e18) {
        return stopscan::kernel::Num(n).to_string();
    }
    let digits = format!("{:.0}", n.abs());
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    if n < 0.0 { format!("-{out}") } else { out }
}

/// Refuses `demand` above `max` unless `--allow-large` was given. `what` says what was asked
/// (`"--samples 100000000"`, `"--delta 1e-9 needs 1,570,796,327 UNIREC stops"`) and `cost` what
/// one unit costs; `instead` names the alternative within the limit, if there is one.
pub(crate) fn soft(
    g: &Global,
    demand: f64,
    max: u64,
    what: impl FnOnce() -> String,
    cost: &str,
    instead: &str,
) -> anyhow::Result<()> {
    if g.allow_large || demand <= max as f64 {
        return Ok(());
    }
    let instead = if instead.is_empty() { String::new() } else { format!("{instead}, or ") };
    bail!(
        "{}: the limit is {} ({cost}); {instead}pass --allow-large to go beyond it",
        what(),
        count(max as f64)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_read_well() {
        assert_eq!(count(0.0), "0");
        assert_eq!(count(999.0), "999");
        assert_eq!(count(1000.0), "1,000");
        assert_eq!(count(1_570_796_327.0), "1,570,796,327");
        assert_eq!(count(1e300), "1e300");
        assert_eq!(at_least(std::f64::consts::FRAC_PI_2 / 1e7), "1.571e-7");
    }
}
