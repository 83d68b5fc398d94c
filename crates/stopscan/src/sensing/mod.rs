//! From a real robot's raw sensor data to the observations strategies consume.
//!
//! - [`ingest`]: one laser scan and its pose become a star-shaped region with labelled walls,
//!   windows and range frontiers (REP 117 cleaning, adaptive breakpoints, split-and-merge);
//! - [`icp`]: point-to-line ICP that aligns a scan to the walls already seen, with a test for
//!   degenerate geometry (a featureless corridor) that falls back to odometry;
//! - [`mapper`]: successive scans read, aligned and placed in one map frame (the walls seen so
//!   far), as the simulator and `stopscan serve` both do;
//! - [`posegraph`]: the stops' poses, odometry and scan matches between them, solved so that a
//!   late correction reaches the stops before it (loop closure).

pub mod icp;
pub mod ingest;
pub mod mapper;
pub mod posegraph;
