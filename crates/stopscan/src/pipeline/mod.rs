//! The pipelines the `stopscan` commands run, as library calls, so that bindings, a robot
//! node or a replay run exactly what the CLI runs: load the inputs, drive the simulation,
//! measure against the offline references, build the records and write the output files.
//! The CLI is left with parsing arguments, showing progress and printing.
//!
//! This is the top layer: it may import every other module of the library, and none of them
//! imports it.
//!
//! - [`explore`]: one exploration of a polygon environment (the main job and `explore`):
//!   the run record, the scene, the event trace;
//! - [`sweep`]: every environment file of a folder with one or every polygon strategy,
//!   a file that does not load becoming rows with its error (`explore --env DIR`);
//! - [`floors`]: every strategy side by side on real maps and office floors, for a robot
//!   with a footprint (`bench floors`);
//! - [`mission`]: a region-of-interest mission and its state file (`stopscan-mission/2`),
//!   stepped, saved and resumed (`roi`);
//! - [`limits`]: the soft size limits the CLI and the bindings share;
//! - [`corner`]: the corner commands' results as typed, serialisable reports;
//! - [`reproduce`]: running paper reproductions and writing their files.
//!
//! Progress is reported through a [`Progress`] callback (one line of text, for a spinner).

pub mod corner;
pub mod explore;
pub mod floors;
pub mod limits;
pub mod mission;
pub mod reproduce;
pub mod serve;
pub mod sweep;

/// What a pipeline is doing, one short line at a time, for a progress display (the same
/// callback as the offline references').
pub use crate::offline::polygon::Progress;

/// A parameter outside what a pipeline accepts, named as the CLI's flag is (without its
/// dashes; `_` where the flag has `-`): `distance must be a finite positive number, got -1`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{name} must {requirement}, got {value}")]
pub struct InvalidParameter {
    /// The parameter.
    pub name: &'static str,
    /// What it must do (`be a finite positive number`, `exceed 1`).
    pub requirement: String,
    /// What it was, as given.
    pub value: String,
}

impl InvalidParameter {
    /// `name` must `requirement`, got `value`.
    pub fn new(
        name: &'static str,
        requirement: impl Into<String>,
        value: &dyn std::fmt::Display,
    ) -> Self {
        Self { name, requirement: requirement.into(), value: value.to_string() }
    }
}

/// An error and its causes on one line, each cause once (library errors often repeat their
/// source in their own message): `cannot write run.json: No space left on device`.
pub fn error_message(err: &(dyn std::error::Error + 'static)) -> String {
    let mut msg = err.to_string();
    let mut cause = err.source();
    while let Some(c) = cause {
        let text = c.to_string();
        if !msg.contains(&text) {
            msg = format!("{msg}: {text}");
        }
        cause = c.source();
    }
    msg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn causes_are_appended_once() {
        let io = std::io::Error::other("disk full");
        let e = crate::io::atomic::WriteError::Io { path: "run.json".into(), source: io };
        assert_eq!(error_message(&e), "cannot write run.json: disk full");
        let repeated = crate::io::LoadError::Io {
            file: "a.wkt".into(),
            source: std::io::Error::other("gone"),
        };
        assert_eq!(error_message(&repeated), "a.wkt: gone");
    }
}
