//! Loading the environments of a sweep: each file with the start its runs begin at.

use std::path::Path;

use super::ros_map::RosMapOptions;
use super::{Environment, LoadError, read_environment_with};
use crate::algorithm::visibility::VisibilityError;
use crate::kernel::Point;
use crate::world::polygon::PolygonWorld;

/// Why an environment could not be loaded for a run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum SweepLoadError {
    /// The file does not load ([`read_environment_with`]).
    #[error(transparent)]
    Load(#[from] LoadError),
    /// Its free space could not be triangulated for the default start.
    #[error(transparent)]
    Visibility(#[from] VisibilityError),
}

/// Where a run in `env` starts when no start is given: [`Environment::default_start`] (the
/// file's start, else its first query point), else the centroid of the first triangle of its
/// free space. Local frame.
///
/// # Errors
/// [`VisibilityError`] if the free space cannot be triangulated.
pub fn default_start(env: &Environment) -> Result<Point, VisibilityError> {
    match env.default_start() {
        Some(p) => Ok(p),
        None => Ok(PolygonWorld::new(env.domain.clone())?.interior_point()),
    }
}

/// Reads one environment of a sweep (a ROS map with `map`, see [`read_environment_with`]) and
/// its [`default_start`]. Its free space is triangulated whether or not the file gives a
/// start, so that a file that cannot be explored fails here, before the sweep.
///
/// # Errors
/// [`SweepLoadError`]: the file does not load, or its free space cannot be triangulated.
pub fn read_with_start(
    path: &Path,
    map: &RosMapOptions,
) -> Result<(Environment, Point), SweepLoadError> {
    let env = read_environment_with(path, map)?;
    let world = PolygonWorld::new(env.domain.clone())?;
    let start = env.default_start().unwrap_or_else(|| world.interior_point());
    Ok((env, start))
}
