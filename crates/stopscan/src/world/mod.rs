//! Ground truth, and the sensors that turn it into observations. Strategies never see it.
//!
//! - [`corner`]: the hidden edge behind a known corner;
//! - [`polygon`]: the true domain and its sensor (full or range-limited);
//! - [`lidar`]: a simulated 2D lidar in a polygon world (noise, dropouts, spurious returns);
//! - [`grid`]: the region of interest, its drift, the camera and the records on the cells.

pub mod corner;
pub mod grid;
pub mod lidar;
pub mod polygon;
