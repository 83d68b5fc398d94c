//! General algorithms with no robot concepts in them.

pub mod cover;
pub mod frame;
pub mod mdp;
pub mod nelder_mead;
pub mod region;
pub mod shortest_path;
pub mod triangulation;
pub mod visibility;
