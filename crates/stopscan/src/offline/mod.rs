//! Optima and bounds against which online strategies are measured.
//!
//! - [`corner`]: exact worst-case ratios and expected times of corner strategies, and the global
//!   optimum over the plane;
//! - [`polygon`]: lower bounds, the greedy reference and the exact optimum of polygon
//!   exploration;
//! - [`grid`]: the ROI paper's bounds (Lemmas 1 and 2, Theorems 1 and 2, bound (8)) and the lawn
//!   mower.

pub mod corner;
pub mod grid;
pub mod polygon;
