//! The command line's integration tests, one module per command, linked into one test binary
//! (each binary links the library again, and thirty of them once filled CI's disk). Every test
//! runs the built `stopscan` as a user would, through the helpers in `common`.

mod common;

mod bench;
mod corner;
mod errors;
mod explore;
mod limits;
mod main_job;
mod map;
mod mcap;
mod offline_and_frames;
mod report;
mod reproduce;
mod roi;
mod serve;
mod shell;
mod visibility;
