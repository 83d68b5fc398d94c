//! # stopscan
//!
//! Where a robot (or a team) should stop and scan while it explores or searches an unknown
//! environment, when every scan costs time. The four papers in the repository's `shared/papers`
//! are the specification; this crate implements them with exact evaluation.
//!
//! ## Catalogue
//! **Protocol and cost** — [`protocol::CostModel`] (`T = scan_time·scans + move_time·moves +
//! distance/speed`), the shared [`protocol::Action`] vocabulary, and the corner family's
//! setup, observations and beliefs ([`protocol::corner`]).
//!
//! **Looking around a corner**
//! - UNIREC and EXPREC (corner paper, Table I): [`strategy::corner::unirec`],
//!   [`strategy::corner::exprec`].
//! - The circle strategy, its ratio `c(d)`, Table 1 thresholds and Theorem 1
//!   (circle paper): [`strategy::corner::circle`].
//! - MDP1 / MDP2 optimal policies, solved exactly: [`strategy::corner::mdp`].
//! - Exact worst-case ratios and expected times: [`offline::corner`]; the global optimum over
//!   the plane: [`offline::corner::optimal`].
//! - Simulation with Monte Carlo: [`sim::corner`], [`world::corner`].
//! - Paper reproductions: [`experiment::corner`].
//!
//! **Multi-robot exploration of a region of interest**
//! - Regions (text grids, masks, shapes through their outer grid approximation, random),
//!   static or drifting, and the camera sensor: [`world::grid`].
//! - Algorithm 1 with R robots, the lawn-mowing search and batteries: [`strategy::grid`].
//! - Lemma 1, Lemma 2, Theorems 1 and 2, bound (8), the lawn mower: [`offline::grid`].
//! - Missions that resume, on the one team loop: [`sim::grid`], [`sim::Team`].
//! - Fig. 7: [`experiment::grid`]; the frame classifier: [`algorithm::frame`].
//!
//! **General algorithms** — sparse MDPs with policy iteration ([`algorithm::mdp`]),
//! Nelder–Mead ([`algorithm::nelder_mead`]).
//!
//! **Pictures** — line charts and policy images as SVG and PNG ([`render`]).
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
pub mod sim;
pub mod strategy;
pub mod world;

/// The crate version, recorded in every output.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");
