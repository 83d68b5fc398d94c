//! Ground truth, and the sensors that turn it into observations. Strategies never see it.

pub mod corner;
pub mod grid;
pub mod polygon;
