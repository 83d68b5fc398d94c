//! Geometry with no robot concepts: the validated [`Domain`] (a polygon with holes).

mod domain;
mod frame;

pub use crate::kernel::Point;
pub use domain::{Domain, EdgeId, InvalidEnvironment, Location};
pub use frame::Frame;

/// Signed area of a ring (positive when counter-clockwise).
pub fn signed_area_of(ring: &[Point]) -> f64 {
    domain::signed_area(ring)
}
