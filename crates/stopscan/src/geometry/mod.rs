//! Geometry with no robot concepts: the validated [`Domain`] (a polygon with holes).

mod domain;

pub use crate::kernel::Point;
pub use domain::{Domain, EdgeId, InvalidEnvironment, Location};
