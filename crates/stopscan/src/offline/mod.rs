//! Optima and bounds against which online strategies are measured.

pub mod corner;
pub mod grid;
pub mod polygon;
