//! The library's integration tests, one module per subject, linked into one test binary: each
//! binary links the whole library and its dependencies again (about 45 MiB at the dev profile),
//! and thirty of them once filled CI's disk. `offline.rs` stays a binary of its own, because CI
//! builds it a second time with the CBC solver (`--features cbc`).

mod corner;
mod exploration;
mod explore_lite;
mod footprint;
mod io;
mod layers;
mod loop_closure;
mod properties;
mod raw_scans;
mod regression;
mod render;
mod robustness;
mod roi;
mod scan_ingestion;
mod visibility;
