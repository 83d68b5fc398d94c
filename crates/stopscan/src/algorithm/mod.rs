//! General algorithms with no robot concepts in them.
//!
//! - [`triangulation`]: the free space's constrained Delaunay triangulation (spade), copied into
//!   compact arrays;
//! - [`visibility`]: visibility regions by triangular expansion, full or range-limited, and an
//!   independent sweep that checks them;
//! - [`cover`]: which parts of a segment have a polygon beyond them (the exact window test);
//! - [`region`]: union, difference, intersection and area of polygons (i_overlay), a
//!   footprint's configuration space (a Minkowski sum through the overlay), and the
//!   clipping of a ring to a box;
//! - [`shortest_path`]: shortest paths in the free space (bitangent graph of the reflex vertices,
//!   A*);
//! - [`mdp`]: sparse finite MDPs with costs, solved by policy iteration;
//! - [`nelder_mead`]: derivative-free minimisation with restarts;
//! - [`frame`]: the ROI paper's classifier of 3 × 3 camera frames (section 7).

pub mod cover;
pub mod frame;
pub mod mdp;
pub mod nelder_mead;
pub mod region;
pub mod shortest_path;
pub mod triangulation;
pub mod visibility;
