//! The tolerances shared by several modules, each named after what it absorbs.
//!
//! The predicates of [`crate::kernel`] are exact and need none. Numbers constructed in floating
//! point (quotients, areas, times, a solver's output) are compared with some slack, and that
//! slack is a decision: these constants state it once. A tolerance used by one module only is
//! a named constant of that module, beside its use; [`super::rounding`] is the slack of
//! constructed coordinates, which grows with their magnitude.

/// Slack when a computed quotient is rounded up to a count: `(x - COUNT_SLACK).ceil()`. A
/// quotient that should be a whole number can come out a hair above it (π over 0.03° in
/// radians is 6000.000000000001), and a plain `ceil` would add a sliver of a bucket, a stop or a
/// tick. Used for histogram buckets, MDP stops and chart ticks.
pub const COUNT_SLACK: f64 = 1e-9;

/// Relative tolerance under which two values of one quantity, computed along different paths,
/// are the same number: a run's time against the closed form of its bound (Lemma 1), a scan's
/// time replayed from a path, a candidate's cost against the best so far (a candidate must be
/// better by more than this to count as an improvement).
pub const SAME_VALUE_REL: f64 = 1e-12;

/// Slack on an angle in radians compared with 0, π/2 or π: an angle given in degrees and
/// converted (`180f64.to_radians()`) may pass the limit by rounding, and touching buckets may
/// overlap by as much.
pub const ANGLE_SLACK: f64 = 1e-12;

/// Relative tolerance of an area computed by clipping or by polygon overlay against the whole
/// it should equal: a coverage, or a cell's overlap with a shape, within this of the whole is
/// complete.
pub const AREA_REL: f64 = 1e-9;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn count_slack_absorbs_the_rounding_of_a_whole_quotient() {
        let q = std::f64::consts::PI / 0.03f64.to_radians();
        assert!(q > 6000.0, "the example of the documentation: {q}");
        assert_eq!((q - COUNT_SLACK).ceil(), 6000.0);
    }

    #[test]
    fn the_area_tolerance_prints_as_the_reproduction_notes_state_it() {
        assert_eq!(crate::kernel::Num(AREA_REL).to_string(), "1e-9");
    }
}
