//! # stopscan
//!
//! Where a robot (or a team) should stop and scan while it explores or searches an unknown
//! environment, when every scan costs time. The four papers in the repository's `shared/papers`
//! are the specification; this crate implements them with exact evaluation. Every run is priced
//! by one [`protocol::CostModel`]: `T = scan_time·scans + move_time·moves + distance/speed`.
//!
//! ## The papers
//!
//! **Looking around a corner** — the corner paper (*Looking around a corner with reconstruction
//! cost*) and the circle paper (Fekete, Klein, Nüchter, *Online searching with an autonomous
//! robot*). The setup, stops and beliefs: [`protocol::corner`].
//! - UNIREC and EXPREC (corner paper, Table I): [`strategy::corner::unirec`],
//!   [`strategy::corner::exprec`]; every corner strategy is a [`strategy::corner::StopList`].
//! - The circle strategy, its ratio `c(d)`, Table 1 thresholds and Theorem 1 (circle paper,
//!   §3.3): [`strategy::corner::circle`].
//! - MDP1 / MDP2 optimal policies (corner paper, §III), solved exactly:
//!   [`strategy::corner::mdp`].
//! - Exact worst-case ratios and expected times: [`offline::corner`]; the global optimum over
//!   the plane (circle paper, §3.2): [`offline::corner::optimal`].
//! - Simulation with Monte Carlo: [`sim::corner`], [`world::corner`].
//! - Paper reproductions (Tables II–IV, Figs. 4–8; Table 1, Fig. 7): [`experiment::corner`].
//!
//! **Exploring an unknown polygon with discrete visibility** — the discrete-visibility paper
//! (Ghosh, Burdick, Bhattacharya, Sarkar, *Online algorithms with discrete visibility: exploring
//! unknown polygonal environments*). A scan's observation: [`protocol::polygon`].
//! - What one scan sees, with its windows (the paper's constructed edges) labelled:
//!   [`algorithm::visibility`] ([`algorithm::visibility::Visibility`]); with a range limit:
//!   [`algorithm::visibility::range`].
//! - The paper's exploration algorithm (at most r + 1 scans):
//!   [`strategy::polygon::DepthFirst`]; with a range restriction (Lemma 4):
//!   [`strategy::polygon::RangeLimited`]; three baselines: [`strategy::polygon::NearestFrontier`],
//!   [`strategy::polygon::GreedyNbv`] and explore_lite's frontier explorer on an occupancy
//!   raster, [`strategy::polygon::ExploreLite`]; all in [`strategy::polygon`].
//! - Offline references (the paper's offline problem): lower bounds for any exploration
//!   ([`offline::polygon::bounds`]), Lemma 4's upper bound ([`offline::polygon::upper_bound`]),
//!   the greedy connected views ([`offline::polygon::greedy`]) and the exact optimum by integer
//!   programming ([`offline::polygon::optimum`](mod@offline::polygon::optimum)); all in
//!   [`offline::polygon`].
//! - Running an exploration: [`sim::polygon::run`] in the true world [`world::polygon`]; the
//!   exact coverage certificate: [`algorithm::cover`]; the run record: [`run_record::RunRecord`].
//! - The paper's worst cases (spiral, star) and the benchmark sweeps: [`experiment::polygon`];
//!   the instance families: [`generate`].
//!
//! **Multi-robot exploration of a region of interest** — the ROI paper (Sung and Tokekar).
//! - Regions (text grids, masks, shapes through their outer grid approximation, random),
//!   static or drifting, and the camera sensor: [`world::grid`]; region files: [`io::grid`].
//! - Algorithm 1 with R robots, the lawn-mowing search and batteries: [`strategy::grid`].
//! - Lemma 1, Lemma 2, Theorems 1 and 2, bound (8), the lawn mower: [`offline::grid`].
//! - Missions that resume, on the one team loop: [`sim::grid`], [`sim::Team`]; the record:
//!   [`run_record::GridRunRecord`]; the replay: [`render::roi_svg`].
//! - Fig. 7: [`experiment::grid`]; the frame classifier (section 7): [`algorithm::frame`].
//!
//! ## The modules, lowest layer first
//!
//! A module imports only the ones above it in this list (ARCHITECTURE.md; checked by
//! `tests/it/layers.rs`).
//! - [`kernel`]: exact predicates (the only caller of `robust`);
//! - [`geometry`]: the validated [`geometry::Domain`] (a polygon with holes) and its frame;
//! - [`algorithm`]: triangulation, visibility, window cover, regions, shortest paths, MDPs,
//!   Nelder–Mead, the frame classifier: no robot concepts;
//! - [`protocol`]: what a driver and a strategy say to each other, and the cost model;
//! - [`world`]: ground truth and sensors, per family;
//! - [`generate`]: seeded instance families (spiral, star, comb, office, pillar forest);
//! - [`io`]: environment and region files (GeoJSON, WKT, `.pol`, ROS maps, benchmark format,
//!   text grids, masks);
//! - [`strategy`]: online strategies, per family;
//! - [`offline`]: optima and bounds, per family;
//! - [`sim`]: the stop-scan-plan-go loop and its observers;
//! - [`run_record`]: the run records written after a run;
//! - [`render`]: charts, policy images, SVG scenes and replays;
//! - [`experiment`]: Monte Carlo, sweeps and paper reproductions.
#![deny(rustdoc::broken_intra_doc_links)]

pub mod algorithm;
pub mod experiment;
pub mod generate;
pub mod geometry;
pub mod io;
pub mod kernel;
pub mod offline;
pub mod pipeline;
pub mod protocol;
pub mod render;
pub mod run_record;
pub mod sensing;
pub mod sim;
pub mod strategy;
pub mod world;

/// The crate version, recorded in every output.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
