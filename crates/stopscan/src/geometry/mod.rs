//! Geometry with no robot concepts: the validated [`Domain`] (a polygon with holes).

mod domain;

pub use crate::kernel::Point;
pub use domain::{Domain, EdgeId, InvalidEnvironment, Location};

/// Signed area of a ring (positive when counter-clockwise).
pub fn signed_area_of(ring: &[Point]) -> f64 {
    domain::signed_area(ring)
}
