//! Online strategies, one family per folder. They see observations only, never the world.
//!
//! - [`corner`]: stop lists: UNIREC, EXPREC, the circle strategy, the MDP policies;
//! - [`polygon`]: the discrete-visibility paper's algorithms and two baselines;
//! - [`grid`]: Algorithm 1 of the ROI paper, with its search and battery wrappers.

pub mod corner;
pub mod grid;
pub mod polygon;
