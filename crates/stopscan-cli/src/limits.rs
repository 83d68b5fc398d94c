//! Soft size limits: work above them is refused before anything is allocated, with a message
//! that names the flag, what it implies, the limit with its cost, and the way out
//! (`--allow-large`). The limits themselves are the library's ([`stopscan::pipeline::limits`]),
//! which the Python bindings apply too. Hard limits, which no flag lifts, live in the library beside the code
//! they protect (`MAX_STOPS`, `MAX_BUCKETS`, `MAX_STOPS_MDP1/2`, `MAX_FRAMES`,
//! `MIN_ARC_TOLERANCE`). The README's "Limits" table lists both, with measurements.

use anyhow::bail;

use crate::cli::Global;

pub(crate) use stopscan::pipeline::limits::{
    CELLS, DISTANCES, FLOORS, FRAMES, PILLARS, ROBOTS, SAMPLES, SIZE, SPIKES, STOPS, camera_frames,
};

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
