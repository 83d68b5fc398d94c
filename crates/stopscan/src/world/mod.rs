//! Ground truth, and the sensors that turn it into observations. Strategies never see it.
//!
//! - [`corner`]: the hidden edge behind a known corner;
//! - [`polygon`]: the true domain and its sensor (full or range-limited);
//! - [`grid`]: the region of interest, its drift, the camera and the records on the cells.

pub mod corner;
pub mod grid;
pub mod polygon;
