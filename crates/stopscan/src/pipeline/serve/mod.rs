//! `stopscan serve`: a robot drives a strategy over line-delimited JSON (protocol
//! `stopscan/1`, documented in `docs/protocol.md` with a JSON Schema beside it).
//!
//! The robot sends its start, its scans with the poses odometry gave, its arrivals and its
//! failed moves; stopscan answers each with the next goal, a scan request, done, or an
//! error naming the field at fault. Every request carries a sequence number `seq`, counted
//! from 0 by the robot; the reply echoes it. A session runs one polygon robot, one corner
//! search, or a whole ROI team (`roi`: one connection reports for every robot, by index,
//! and gets every robot's orders back).
//!
//! **Resumable.** With a journal, every answered step is appended to it (the request and the
//! reply, one JSON line) and written to the operating system before the reply is sent. After
//! a crash, [`Server::resume`] replays the journal through a fresh session (checking that
//! every reply comes out the same) and goes on. A robot that got no reply sends the same
//! request again with the same `seq`: a step the journal holds is answered from it, never
//! taken twice; a step it does not hold is taken now. So nothing is lost or repeated, and a
//! run interrupted by `kill -9` any number of times ends with the same journal, byte for
//! byte, as one that never was.
//!
//! The transport (standard input and output, or TCP) is the caller's: a [`Server`] turns one
//! request line into one reply line.

pub mod bench;
pub mod client;
pub mod message;
pub mod recording;
mod roi;
mod session;

use std::hash::{DefaultHasher, Hash, Hasher};
use std::io::{BufRead, Read, Write};
use std::path::{Path, PathBuf};

use crate::io::journal::{self, Journal};

pub use message::{
    DoneReason, MAX_LINE, PROTOCOL, ProtocolError, Reply, ReplyBody, Request, parse,
};
pub use session::{
    DEFAULT_BELIEF, DEFAULT_CORNER_STRATEGY, DEFAULT_DRIFT, DEFAULT_POLYGON_STRATEGY,
    DEFAULT_SIGMA, Session,
};

/// The journal's first line names the format.
pub const JOURNAL_FORMAT: &str = "stopscan-journal/1";

/// How a server runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ServeOptions {
    /// The most scans a session may take; then it is done ([`DoneReason::Limit`]).
    pub max_scans: u64,
    /// Whether each journal line is also synced to the disk (`fsync`) before the reply: safe
    /// against a power cut, not only a crash, at about a millisecond per step.
    pub fsync: bool,
    /// Whether the session is kept for an MCAP recording ([`Server::mcap`]).
    pub record: bool,
}

impl Default for ServeOptions {
    fn default() -> Self {
        Self { max_scans: crate::sim::lidar::MAX_SCANS, fsync: false, record: false }
    }
}

/// Why a server could not go on.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ServeError {
    /// The journal could not be created, read or written.
    #[error("journal {path}: {source}")]
    Io {
        /// The journal.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// The journal exists already (a new session must not overwrite one).
    #[error("journal {0} exists already; resume it with --resume, or choose another file")]
    Exists(PathBuf),
    /// The journal is not one this server wrote, or does not replay to the same replies.
    #[error("journal {path}, line {line}: {problem}")]
    Journal {
        /// The journal.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// What is wrong.
        problem: String,
    },
}

/// One answered step, as the journal holds it.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
struct Entry {
    seq: u64,
    request: serde_json::Value,
    reply: serde_json::Value,
}

/// A session with its journal: one request line in, one reply line out.
#[derive(Debug)]
pub struct Server {
    session: Session,
    journal: Option<Journal>,
    /// Each answered step's request (hashed) and reply line, by `seq`.
    answered: Vec<(u64, String)>,
    /// The steps kept for an MCAP recording, when asked for.
    recording: Option<recording::SessionRecording>,
}

fn digest(canonical: &str) -> u64 {
    let mut h = DefaultHasher::new();
    canonical.hash(&mut h);
    h.finish()
}

impl Server {
    /// A server with no journal.
    pub fn new(options: ServeOptions) -> Self {
        Self {
            session: Session::new(options.max_scans),
            journal: None,
            answered: Vec::new(),
            recording: options.record.then(recording::SessionRecording::default),
        }
    }

    /// A server that journals to `path`, a new file.
    ///
    /// # Errors
    /// [`ServeError::Exists`] if the file exists and is not empty; [`ServeError::Io`] if it
    /// cannot be created.
    pub fn with_journal(path: &Path, options: ServeOptions) -> Result<Self, ServeError> {
        let io = |source| ServeError::Io { path: path.to_path_buf(), source };
        if std::fs::metadata(path).is_ok_and(|m| m.len() > 0) {
            return Err(ServeError::Exists(path.to_path_buf()));
        }
        let mut journal = Journal::append_to(path, options.fsync).map_err(io)?;
        let header = serde_json::json!({
            "format": JOURNAL_FORMAT,
            "protocol": PROTOCOL,
            "stopscan_version": env!("CARGO_PKG_VERSION"),
        });
        journal.append(&header.to_string()).map_err(io)?;
        Ok(Self { journal: Some(journal), ..Self::new(options) })
    }

    /// A server that goes on from the journal at `path`: its steps are replayed through a
    /// fresh session, each reply checked against the one recorded. A last line torn by a
    /// crash (no newline at its end) is cut off: its reply was never sent.
    ///
    /// # Errors
    /// [`ServeError::Io`] if the journal cannot be read or written; [`ServeError::Journal`]
    /// naming the line that is not a step of this protocol or whose reply differs.
    pub fn resume(path: &Path, options: ServeOptions) -> Result<Self, ServeError> {
        let io = |source| ServeError::Io { path: path.to_path_buf(), source };
        let bad = |line: usize, problem: String| ServeError::Journal {
            path: path.to_path_buf(),
            line,
            problem,
        };
        let (lines, whole) = journal::read(path).map_err(io)?;
        let Some(first) = lines.first() else {
            return Err(bad(1, "empty: no journal header".into()));
        };
        let header: serde_json::Value = serde_json::from_str(first)
            .map_err(|e| bad(1, format!("not a journal header: {e}")))?;
        if header["format"] != JOURNAL_FORMAT {
            return Err(bad(1, format!("not a {JOURNAL_FORMAT} journal")));
        }
        let mut server = Self::new(options);
        for (i, line) in lines.iter().enumerate().skip(1) {
            let number = i + 1;
            let entry: Entry = serde_json::from_str(line)
                .map_err(|e| bad(number, format!("not a journal step: {e}")))?;
            let (replayed, step) = server.step_line(&entry.request.to_string());
            if step.is_none() {
                return Err(bad(
                    number,
                    format!("step {} is not a step any more: {replayed}", entry.seq),
                ));
            }
            let same = serde_json::from_str::<serde_json::Value>(&replayed)
                .is_ok_and(|v| v == entry.reply);
            if !same {
                let recorded = entry.reply.to_string();
                return Err(bad(
                    number,
                    format!(
                        "replaying step {} gives a different reply (a journal from another \
                         stopscan version?): recorded {recorded}, now {replayed}",
                        entry.seq
                    ),
                ));
            }
        }
        server.journal = Some(journal::reopen(path, whole, options.fsync).map_err(io)?);
        Ok(server)
    }

    /// Whether the session is over.
    pub fn is_done(&self) -> bool {
        self.session.over().is_some()
    }

    /// The last reply of a step taken (after a resume: what the robot was last asked to do).
    pub fn last_reply(&self) -> Option<&str> {
        self.answered.last().map(|(_, r)| r.as_str())
    }

    /// Seconds spent writing the journal so far.
    pub fn journal_seconds(&self) -> f64 {
        self.journal.as_ref().map_or(0.0, |j| j.spent().as_secs_f64())
    }

    /// The session so far as an MCAP recording for Foxglove, when the server keeps one
    /// ([`ServeOptions::record`]).
    ///
    /// # Errors
    /// [`crate::render::McapError`] if the recording cannot be made.
    pub fn mcap(&self) -> Option<Result<Vec<u8>, crate::render::McapError>> {
        self.recording.as_ref().map(recording::SessionRecording::mcap)
    }

    /// Steps answered so far (the next `seq`).
    pub fn steps(&self) -> u64 {
        self.answered.len() as u64
    }

    /// The reply to one request line (without its newline); a step it takes is journaled
    /// before this returns.
    ///
    /// # Errors
    /// [`ServeError::Io`] if the journal cannot be written: the step is then not answered,
    /// and the server should stop (the robot sends the request again to a resumed one).
    pub fn handle(&mut self, line: &str) -> Result<String, ServeError> {
        let (reply, entry) = self.step_line(line);
        if let (Some(entry), Some(journal)) = (entry, &mut self.journal) {
            journal
                .append(&entry)
                .map_err(|source| ServeError::Io { path: journal.path().to_path_buf(), source })?;
        }
        Ok(reply)
    }

    /// The reply to one request line, and the journal line of the step it took, if it took
    /// one.
    fn step_line(&mut self, line: &str) -> (String, Option<String>) {
        let parsed = match parse(line) {
            Ok(p) => p,
            Err((seq, e)) => return (Reply::error(seq, e).to_line(), None),
        };
        let next = self.answered.len() as u64;
        let hash = digest(&parsed.canonical);
        if parsed.seq < next {
            let (h, reply) = &self.answered[parsed.seq as usize];
            if *h == hash {
                return (reply.clone(), None);
            }
            let e = ProtocolError::field(
                "seq",
                format!(
                    "step {} was answered already, for a different request; the next step is {next}",
                    parsed.seq
                ),
            );
            return (Reply::error(Some(parsed.seq), e).to_line(), None);
        }
        if parsed.seq > next {
            let e = ProtocolError::field(
                "seq",
                format!(
                    "expected {next} (steps are numbered from 0 without gaps), got {}",
                    parsed.seq
                ),
            );
            return (Reply::error(Some(parsed.seq), e).to_line(), None);
        }
        match self.session.step(&parsed.request) {
            Err(e) => (Reply::error(Some(parsed.seq), e).to_line(), None),
            Ok((body, localised)) => {
                let reply = Reply { protocol: PROTOCOL, seq: Some(parsed.seq), body, localised };
                let line = reply.to_line();
                if let Some(r) = &mut self.recording {
                    r.push(parsed.request, reply);
                }
                let reply = line;
                let entry = format!(
                    "{{\"seq\":{},\"request\":{},\"reply\":{}}}",
                    parsed.seq, parsed.canonical, reply
                );
                self.answered.push((hash, reply.clone()));
                (reply, Some(entry))
            }
        }
    }
}

/// Answers every line of `input` on `output` (each reply flushed) until the input ends: the
/// transport of `stopscan serve` on standard input and output, and on each TCP connection.
/// A line longer than [`MAX_LINE`] is skipped and gets an error reply, as does one that is not
/// UTF-8; blank lines are ignored.
///
/// # Errors
/// [`ServeError`] if the journal cannot be written (stop the server), or an I/O error of
/// the input or output (a dropped connection).
pub fn serve_lines(
    server: &mut Server,
    mut input: impl BufRead,
    mut output: impl Write,
) -> Result<(), TransportError> {
    let mut buf = Vec::new();
    loop {
        buf.clear();
        let n = Read::take(&mut input, MAX_LINE as u64 + 1).read_until(b'\n', &mut buf)?;
        if n == 0 {
            return Ok(());
        }
        let reply = if buf.len() > MAX_LINE {
            // Skip the rest of the line.
            while !buf.ends_with(b"\n") {
                buf.clear();
                if Read::take(&mut input, MAX_LINE as u64).read_until(b'\n', &mut buf)? == 0 {
                    break;
                }
            }
            let e = ProtocolError {
                field: None,
                message: format!("line longer than {MAX_LINE} bytes; it was skipped"),
            };
            Reply::error(None, e).to_line()
        } else {
            match std::str::from_utf8(&buf) {
                Ok(line) => {
                    let line = line.trim_end_matches(['\n', '\r']);
                    if line.trim().is_empty() {
                        continue;
                    }
                    server.handle(line)?
                }
                Err(e) => {
                    let e = ProtocolError { field: None, message: format!("not UTF-8: {e}") };
                    Reply::error(None, e).to_line()
                }
            }
        };
        // One write per reply: split writes meet Nagle's algorithm and delayed ACKs on TCP
        // (40 ms a step).
        let mut bytes = reply.into_bytes();
        bytes.push(b'\n');
        output.write_all(&bytes)?;
        output.flush()?;
    }
}

/// Why [`serve_lines`] stopped.
#[derive(Debug, thiserror::Error)]
pub enum TransportError {
    /// The journal failed: the server must stop.
    #[error(transparent)]
    Serve(#[from] ServeError),
    /// Reading a request or writing a reply failed (a dropped connection).
    #[error("connection: {0}")]
    Io(#[from] std::io::Error),
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("stopscan-serve-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir.join("journal.jsonl")
    }

    /// A corner session's requests: start, then arrivals and hidden scans.
    fn requests() -> Vec<String> {
        let pose = r#"{"x":0.0,"y":0.0,"theta":0.0}"#;
        let mut out = vec![format!(
            r#"{{"protocol":"stopscan/1","seq":0,"type":"start","family":"corner","strategy":"unirec","pose":{pose},"cost":{{"scan_time":2,"speed":0.5}},"corner":{{"distance":10}}}}"#
        )];
        for k in 0..4 {
            out.push(format!(r#"{{"seq":{},"type":"arrived","pose":{pose}}}"#, 2 * k + 1));
            out.push(format!(r#"{{"seq":{},"type":"scan","pose":{pose},"edge":null}}"#, 2 * k + 2));
        }
        out
    }

    #[test]
    fn a_torn_last_line_is_cut_and_the_session_goes_on() {
        let path = temp("torn");
        let mut s = Server::with_journal(&path, ServeOptions::default()).unwrap();
        let replies: Vec<String> = requests().iter().map(|r| s.handle(r).unwrap()).collect();
        drop(s);
        let whole = std::fs::read_to_string(&path).unwrap();
        // Cut after step 5, in the middle of step 6's line.
        let lines: Vec<&str> = whole.split_inclusive('\n').collect();
        let cut = format!("{}{}", lines[..7].concat(), &lines[7][..10]);
        std::fs::write(&path, cut).unwrap();
        let mut r = Server::resume(&path, ServeOptions::default()).unwrap();
        assert_eq!(r.steps(), 6);
        assert_eq!(r.last_reply(), Some(replies[5].as_str()));
        // A retry of an answered step gets its reply; the rest goes on as before.
        assert_eq!(r.handle(&requests()[3]).unwrap(), replies[3]);
        for (q, a) in requests().iter().zip(&replies).skip(6) {
            assert_eq!(&r.handle(q).unwrap(), a);
        }
        drop(r);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), whole);
    }

    #[test]
    fn a_damaged_journal_is_refused_naming_the_line() {
        let path = temp("damaged");
        let mut s = Server::with_journal(&path, ServeOptions::default()).unwrap();
        for r in requests() {
            s.handle(&r).unwrap();
        }
        drop(s);
        let whole = std::fs::read_to_string(&path).unwrap();
        let mut lines: Vec<String> = whole.lines().map(String::from).collect();
        lines[3] = "{\"seq\": 2, \"request\": 7}".into();
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        let e = Server::resume(&path, ServeOptions::default()).unwrap_err().to_string();
        assert!(e.contains("line 4") && e.contains("not a journal step"), "{e}");
        // A reply that no longer comes out the same.
        let mut lines: Vec<String> = whole.lines().map(String::from).collect();
        lines[2] = lines[2].replace("\"type\":\"scan\"}", "\"type\":\"scan\",\"extra\":1}");
        std::fs::write(&path, lines.join("\n") + "\n").unwrap();
        let e = Server::resume(&path, ServeOptions::default()).unwrap_err().to_string();
        assert!(e.contains("line 3") && e.contains("different reply"), "{e}");
        // A new journal never overwrites one.
        let e = Server::with_journal(&path, ServeOptions::default()).unwrap_err().to_string();
        assert!(e.contains("exists already"), "{e}");
    }
}
