//! Online strategies, one family per folder. They see observations only, never the world.

pub mod corner;
pub mod grid;
pub mod polygon;
