//! `stopscan bench serve`: what a step of the protocol costs. A simulated robot
//! ([`SimClient`]) explores a map through a server, and the bench times:
//! - the server's work per step (parse, read and align the scan, plan, reply), in process;
//! - the round trip per step over TCP on loopback (the robot's write to its read of the
//!   reply), the server in a thread;
//! - the journal's write per step, flushed to the operating system, and with `fsync`;
//! - resuming from the finished journal (replaying every step).
//!
//! Each session runs the same requests (the robot is seeded), so the figures are of the same
//! steps.

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::time::Instant;

use serde::Serialize;
use serde_json::Value;

use super::client::SimClient;
use super::{ServeError, ServeOptions, Server, serve_lines};
use crate::kernel::Point;
use crate::sim::lidar::SimRobot;
use crate::world::lidar::Lidar;
use crate::world::polygon::PolygonWorld;

/// The median and 95th percentile of a set of timings, milliseconds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Spread {
    /// How many.
    pub n: usize,
    /// The median.
    pub median_ms: f64,
    /// The 95th percentile.
    pub p95_ms: f64,
}

impl Spread {
    fn of(mut ms: Vec<f64>) -> Self {
        ms.sort_by(f64::total_cmp);
        let at = |q: f64| {
            if ms.is_empty() { 0.0 } else { ms[((ms.len() - 1) as f64 * q).round() as usize] }
        };
        Self { n: ms.len(), median_ms: at(0.5), p95_ms: at(0.95) }
    }
}

/// Timings split by what the robot sent: scans, and the rest (start, arrivals, failures).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ByKind {
    /// Steps answering a scan.
    pub scan: Spread,
    /// The other steps.
    pub other: Spread,
}

/// What `stopscan bench serve` prints.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ServeBench {
    /// The strategy.
    pub strategy: String,
    /// Steps in the session (requests answered).
    pub steps: u64,
    /// Scans in it.
    pub scans: usize,
    /// The server's work per step, in process.
    pub server: ByKind,
    /// The robot's round trip per step over TCP on loopback.
    pub round_trip_tcp: ByKind,
    /// The journal's write per step, flushed to the operating system, microseconds (mean).
    pub journal_write_us: f64,
    /// The same with `fsync`, microseconds (mean).
    pub journal_fsync_us: f64,
    /// The journal's size, bytes per step (scans dominate: their ranges are kept).
    pub journal_bytes_per_step: f64,
    /// Resuming from the finished journal: every step replayed and checked, seconds.
    pub resume_seconds: f64,
}

/// Why the bench could not run.
#[derive(Debug, thiserror::Error)]
pub enum BenchError {
    /// The server failed.
    #[error(transparent)]
    Serve(#[from] ServeError),
    /// The session went wrong.
    #[error("{0}")]
    Session(String),
    /// A file or socket failed.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// The start message's set-up for the bench's robot: 0.2 m radius, 30 s scans at 0.5 m/s,
/// σ = 0.02 m, 1% drift.
fn setup(strategy: &str) -> serde_json::Map<String, Value> {
    let v = serde_json::json!({
        "strategy": strategy,
        "cost": {"scan_time": 30.0, "speed": 0.5},
        "robot": {"radius": 0.2},
        "sensor": {"sigma": 0.02},
        "odometry_drift": 0.01,
    });
    v.as_object().expect("an object").clone()
}

/// Runs one session in process: each step's request kind and the server's time for it.
fn in_process(
    server: &mut Server,
    client: &mut SimClient<'_>,
) -> Result<Vec<(bool, f64)>, BenchError> {
    let mut out = Vec::new();
    let mut line = client.start();
    loop {
        let is_scan = line.contains("\"type\":\"scan\"");
        let t = Instant::now();
        let reply = server.handle(&line)?;
        out.push((is_scan, t.elapsed().as_secs_f64() * 1e3));
        let reply: Value =
            serde_json::from_str(&reply).map_err(|e| BenchError::Session(e.to_string()))?;
        match client.answer(&reply).map_err(BenchError::Session)? {
            Some(next) => line = next,
            None => return Ok(out),
        }
    }
}

fn split(steps: &[(bool, f64)]) -> ByKind {
    let pick = |scan: bool| steps.iter().filter(|s| s.0 == scan).map(|s| s.1).collect();
    ByKind { scan: Spread::of(pick(true)), other: Spread::of(pick(false)) }
}

/// Times a session of `strategy` in `world` from `start` (journals go to `dir`).
///
/// # Errors
/// [`BenchError`] if a journal cannot be written, a socket fails, or the session goes wrong.
pub fn bench(
    world: &PolygonWorld,
    start: Point,
    strategy: &str,
    seed: u64,
    dir: &Path,
) -> Result<ServeBench, BenchError> {
    let client = || {
        SimClient::new(SimRobot::new(world, start, Lidar::default(), 0.01, seed), setup(strategy))
    };
    // In process, no journal.
    let mut c = client();
    let steps = in_process(&mut Server::new(ServeOptions::default()), &mut c)?;
    let scans = c.truth.len();
    // Journaled: flushed, then synced.
    let journal = |fsync: bool| -> Result<(f64, u64, std::path::PathBuf), BenchError> {
        let path = dir.join(if fsync { "bench-fsync.jsonl" } else { "bench.jsonl" });
        let _ = std::fs::remove_file(&path);
        let mut s = Server::with_journal(&path, ServeOptions { fsync, ..ServeOptions::default() })?;
        in_process(&mut s, &mut client())?;
        Ok((s.journal_seconds() * 1e6 / s.steps() as f64, s.steps(), path))
    };
    let (write_us, n, path) = journal(false)?;
    let bytes = std::fs::metadata(&path)?.len();
    let (fsync_us, _, fsync_path) = journal(true)?;
    let t = Instant::now();
    let resumed = Server::resume(&path, ServeOptions::default())?;
    let resume_seconds = t.elapsed().as_secs_f64();
    if resumed.steps() != n {
        return Err(BenchError::Session(format!("resumed {} of {n} steps", resumed.steps())));
    }
    let _ = std::fs::remove_file(&path);
    let _ = std::fs::remove_file(&fsync_path);
    Ok(ServeBench {
        strategy: strategy.into(),
        steps: n,
        scans,
        server: split(&steps),
        round_trip_tcp: tcp(&mut client())?,
        journal_write_us: write_us,
        journal_fsync_us: fsync_us,
        journal_bytes_per_step: bytes as f64 / n as f64,
        resume_seconds,
    })
}

/// One session over TCP on loopback, the server in a thread: the round trip of each step.
fn tcp(client: &mut SimClient<'_>) -> Result<ByKind, BenchError> {
    let listener = std::net::TcpListener::bind("127.0.0.1:0")?;
    let addr = listener.local_addr()?;
    let server = std::thread::spawn(move || -> Result<(), BenchError> {
        let (stream, _) = listener.accept()?;
        stream.set_nodelay(true)?;
        let mut s = Server::new(ServeOptions::default());
        serve_lines(&mut s, BufReader::new(stream.try_clone()?), stream)
            .map_err(|e| BenchError::Session(e.to_string()))
    });
    let stream = std::net::TcpStream::connect(addr)?;
    stream.set_nodelay(true)?;
    let mut reader = BufReader::new(stream.try_clone()?);
    let mut writer = stream;
    let mut out = Vec::new();
    let mut line = client.start();
    let mut reply = String::new();
    loop {
        let is_scan = line.contains("\"type\":\"scan\"");
        let t = Instant::now();
        writer.write_all(format!("{line}\n").as_bytes())?;
        reply.clear();
        reader.read_line(&mut reply)?;
        out.push((is_scan, t.elapsed().as_secs_f64() * 1e3));
        let v: Value =
            serde_json::from_str(&reply).map_err(|e| BenchError::Session(e.to_string()))?;
        match client.answer(&v).map_err(BenchError::Session)? {
            Some(next) => line = next,
            None => break,
        }
    }
    drop((reader, writer));
    server.join().map_err(|_| BenchError::Session("the server thread panicked".into()))??;
    Ok(split(&out))
}
