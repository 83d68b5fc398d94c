//! A region-of-interest mission as `stopscan roi` flies it: a team explores a region
//! (Algorithm 1, optionally with the field pipeline's camera, lawn-mowing search and battery),
//! journaling every step so that it can be resumed after a crash, and ending with the run
//! record and the SVG replay.
//!
//! The state file (format [`MISSION_FORMAT`]) is an append-only journal. Its first line is the
//! state the mission started (or resumed) from: where the region comes from, the drift, the
//! sensor, the seed, the output paths, the event trace and its length, and the mission itself
//! ([`Mission`]). Then one short line per step, `{"steps":N,"trace_len":B}`, written before
//! the next step begins. The mission is deterministic given its state, so a resumed mission
//! rebuilds the state of the first line and replays the steps the journal records; a line torn
//! by a crash is cut off. A resumed mission ends with the same record, and the same trace, as
//! an uninterrupted one.

use std::cell::Cell as Shared;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::rc::Rc;

use serde::{Deserialize, Serialize};

use super::Progress;
use crate::io::LoadError;
use crate::io::atomic::{self, WriteError};
use crate::io::grid::GridOptions;
use crate::io::journal::{self, Journal};
use crate::protocol::CostModel;
use crate::protocol::grid::Cell;
use crate::run_record::GridRunRecord;
use crate::sim::grid::{Mission, MissionError, MissionPlan, Search};
use crate::sim::{Flow, JsonLinesTrace, NoObserver, Recording, SimError};
use crate::world::grid::{Drift, GridRoi, GridSensor, GridWorld, InvalidRoi};

/// The state file's format. `/2`: the trace and its length are recorded; a search's lawn is
/// computed, not listed. `/3`: a journal (the state, then one line per step) instead of the
/// whole state rewritten (about 4 ms per write at 3,000 cells).
pub const MISSION_FORMAT: &str = "stopscan-mission/3";

/// Where the region comes from, so that a resumed mission rebuilds the same world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum RegionSource {
    /// `GridRoi::random(cells, seed)` with cells of `cell_size` metres.
    Random {
        /// Cells.
        cells: usize,
        /// The seed it is grown from.
        seed: u64,
        /// The side of a cell, metres.
        cell_size: f64,
    },
    /// A file (text grid, mask or polygon), read with [`crate::io::grid::read_roi`].
    File {
        /// The file (absolute).
        path: PathBuf,
        /// The side of a cell, metres.
        cell_size: f64,
        /// Pixels per cell side, for masks.
        cell_px: usize,
        /// The start cell, for masks and text grids without `S`.
        start: Option<Cell>,
        /// For masks: the region is dark.
        invert: bool,
    },
    /// A text grid given in place (`#` region, `.` outside, `S` start; see
    /// [`crate::io::grid::parse_text_grid`]), as the Python bindings hand over an array: the
    /// state keeps the text, so the mission resumes without the caller's data.
    Grid {
        /// The region's name (the run record's).
        name: String,
        /// The text grid.
        text: String,
        /// The side of a cell, metres.
        cell_size: f64,
        /// The start cell, for a grid without `S`.
        start: Option<Cell>,
    },
}

impl RegionSource {
    /// The region.
    ///
    /// # Errors
    /// [`MissionRunError`]: the file does not load, or the region is invalid.
    pub fn load(&self) -> Result<GridRoi, MissionRunError> {
        Ok(match self {
            Self::Random { cells, seed, cell_size } => {
                GridRoi::random(*cells, *seed)?.with_cell_size(*cell_size)?
            }
            Self::File { path, cell_size, cell_px, start, invert } => {
                let opts = GridOptions {
                    cell_size: *cell_size,
                    cell_px: *cell_px,
                    start: *start,
                    invert: *invert,
                };
                crate::io::grid::read_roi(path, &opts)?
            }
            Self::Grid { name, text, cell_size, start } => {
                let opts =
                    GridOptions { cell_size: *cell_size, start: *start, ..GridOptions::default() };
                crate::io::grid::parse_text_grid(text, name, name, &opts)?
            }
        })
    }
}

/// Everything a resumed mission needs: the state file. Paths are absolute, so that a mission
/// resumes from any directory.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct MissionState {
    /// [`MISSION_FORMAT`].
    pub format: String,
    /// Where the region comes from.
    pub source: RegionSource,
    /// The region's drift.
    pub drift: Drift,
    /// The sensor.
    pub sensor: GridSensor,
    /// The world's seed.
    pub seed: u64,
    /// Where the run record goes.
    pub out: PathBuf,
    /// Where the SVG replay goes.
    pub svg: PathBuf,
    /// Where the browser replay (`report.html`) goes, if anywhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub report: Option<PathBuf>,
    /// Where the MCAP recording goes, if anywhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mcap: Option<PathBuf>,
    /// The event trace, if the mission writes one.
    pub trace: Option<PathBuf>,
    /// The trace's length in bytes when this state was taken: a resumed mission cuts the
    /// trace back to it, so that the events after the state are not written twice.
    pub trace_len: u64,
    /// The mission.
    pub mission: Mission,
    /// The steps the journal records beyond `mission`'s (replayed on resume).
    #[serde(skip)]
    pub journaled_steps: u64,
}

/// One journal line after the state: the team's step count and the trace's length after it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
struct StepLine {
    steps: u64,
    trace_len: u64,
}

/// What a fresh mission is made of.
#[derive(Debug, Clone, PartialEq)]
pub struct MissionSpec {
    /// Where the region comes from.
    pub source: RegionSource,
    /// The region's drift.
    pub drift: Drift,
    /// The sensor.
    pub sensor: GridSensor,
    /// R, the number of robots.
    pub robots: usize,
    /// Scan time, per-move time and the robots' speed.
    pub cost: CostModel,
    /// Flight seconds per battery (`None`: unlimited).
    pub battery_s: Option<f64>,
    /// A lawn-mowing search first.
    pub search: Option<Search>,
    /// What the run record keeps of each robot.
    pub recording: Recording,
    /// The world's seed.
    pub seed: u64,
    /// Where the run record goes.
    pub out: PathBuf,
    /// Where the SVG replay goes.
    pub svg: PathBuf,
    /// Where the browser replay (`report.html`) goes, if anywhere.
    pub report: Option<PathBuf>,
    /// Where the MCAP recording for Foxglove goes, if anywhere.
    pub mcap: Option<PathBuf>,
    /// Where the event trace goes, if anywhere.
    pub trace: Option<PathBuf>,
}

/// Why a mission could not be started, carried on or recorded.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum MissionRunError {
    /// The region's file does not load.
    #[error(transparent)]
    Load(#[from] LoadError),
    /// The region is invalid.
    #[error(transparent)]
    Roi(#[from] InvalidRoi),
    /// The mission cannot start.
    #[error(transparent)]
    Mission(#[from] MissionError),
    /// A strategy asked for something the world refuses.
    #[error(transparent)]
    Sim(#[from] SimError<Cell>),
    /// The mission did not finish within [`Mission::step_limit`] steps.
    #[error("the mission did not finish within {0} steps")]
    StepLimit(u64),
    /// The MCAP recording could not be made.
    #[error("{0}")]
    Mcap(String),
    /// The state file cannot be read.
    #[error("cannot read {}", .path.display())]
    ReadState {
        /// The file.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// The state file is not a mission state.
    #[error("{}:{}:{}: not a mission state: {source}", .path.display(), .source.line(), .source.column())]
    NotAState {
        /// The file.
        path: PathBuf,
        /// Where and why it does not parse.
        source: serde_json::Error,
    },
    /// The state file has another format.
    #[error("{}: format {found:?}, expected {MISSION_FORMAT:?}", .path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// Its format.
        found: String,
    },
    /// The event trace cannot be written.
    #[error("cannot write {}", .path.display())]
    Trace {
        /// The trace file.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// A step line of the journal does not parse.
    #[error("{}, line {line}: not a step of the mission journal: {problem}", .path.display())]
    Journal {
        /// The journal.
        path: PathBuf,
        /// The line, from 1.
        line: usize,
        /// Why.
        problem: String,
    },
    /// The journal cannot be written.
    #[error("cannot write {}", .path.display())]
    WriteJournal {
        /// The journal.
        path: PathBuf,
        /// The system error.
        source: std::io::Error,
    },
    /// The trace is shorter than the state recorded: it was changed since.
    #[error(
        "{}: the trace has {len} bytes, fewer than the {keep} the mission state recorded; it was changed since (give --trace NEW to start a new one)",
        .path.display()
    )]
    TraceShrunk {
        /// The trace file.
        path: PathBuf,
        /// Its length.
        len: u64,
        /// The length the state recorded.
        keep: u64,
    },
    /// An output could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

/// `p` made absolute (as it is if that fails).
fn absolute(p: &Path) -> PathBuf {
    std::path::absolute(p).unwrap_or_else(|_| p.to_path_buf())
}

/// The world of a mission: rebuilt from the same region, drift, sensor and seed.
fn world_of(roi: GridRoi, drift: Drift, sensor: GridSensor, seed: u64, search: bool) -> GridWorld {
    if search {
        GridWorld::without_root(roi, drift, sensor, seed)
    } else {
        GridWorld::new(roi, drift, sensor, seed)
    }
}

impl MissionState {
    /// Reads a state journal: the state on its first line, and the steps recorded after it
    /// (the last complete line; a line torn by a crash is ignored).
    ///
    /// # Errors
    /// [`MissionRunError::ReadState`], [`MissionRunError::NotAState`] (with the line and
    /// column), [`MissionRunError::Format`], or [`MissionRunError::Journal`] for a step line
    /// that does not parse.
    pub fn read(path: &Path) -> Result<Self, MissionRunError> {
        let cannot = |source| MissionRunError::ReadState { path: path.to_path_buf(), source };
        let (mut lines, _) = journal::read(path).map_err(cannot)?;
        if lines.is_empty() {
            // A `/2` state file is one line with no newline after it.
            lines.push(std::fs::read_to_string(path).map_err(cannot)?);
        }
        let first = &lines[0];
        let mut m: Self = serde_json::from_str(first)
            .map_err(|source| MissionRunError::NotAState { path: path.to_path_buf(), source })?;
        // A `/2` state is a `/3` journal's first line with no step after it.
        if m.format != MISSION_FORMAT && m.format != "stopscan-mission/2" {
            return Err(MissionRunError::Format { path: path.to_path_buf(), found: m.format });
        }
        m.format = MISSION_FORMAT.into();
        for (i, line) in lines.iter().enumerate().skip(1) {
            let step: StepLine =
                serde_json::from_str(line).map_err(|e| MissionRunError::Journal {
                    path: path.to_path_buf(),
                    line: i + 1,
                    problem: e.to_string(),
                })?;
            m.journaled_steps = step.steps;
            m.trace_len = step.trace_len;
        }
        Ok(m)
    }

    /// Starts a state journal with this state: one line, written atomically (a crash leaves
    /// the previous journal or this one).
    ///
    /// # Errors
    /// [`WriteError`] naming the file.
    pub fn write(&self, path: &Path) -> Result<(), WriteError> {
        atomic::write(path, |w| {
            serde_json::to_writer(&mut *w, self).map_err(std::io::Error::from)?;
            w.write_all(b"\n")
        })
    }

    /// Sends a resumed mission's outputs elsewhere: `out` (and the replay beside it, with
    /// `.svg`, unless `svg` is given), `svg`, `report`, `mcap`; a `trace` other than the recorded one replaces it
    /// and starts empty. Both outputs are checked ([`atomic::check_file`]).
    ///
    /// # Errors
    /// [`WriteError`] for an output that cannot be written.
    pub fn redirect(
        &mut self,
        out: Option<&Path>,
        svg: Option<&Path>,
        report: Option<&Path>,
        mcap: Option<&Path>,
        trace: Option<&Path>,
    ) -> Result<(), WriteError> {
        if let Some(o) = out {
            self.out = absolute(o);
            self.svg = absolute(&svg.map_or_else(|| o.with_extension("svg"), Path::to_path_buf));
        } else if let Some(s) = svg {
            self.svg = absolute(s);
        }
        if let Some(r) = report {
            self.report = Some(absolute(r));
        }
        if let Some(m) = mcap {
            self.mcap = Some(absolute(m));
        }
        atomic::check_file(&self.out)?;
        atomic::check_file(&self.svg)?;
        for p in [&self.report, &self.mcap].into_iter().flatten() {
            atomic::check_file(p)?;
        }
        if let Some(t) = trace {
            let t = absolute(t);
            if self.trace.as_ref() != Some(&t) {
                self.trace = Some(t);
                self.trace_len = 0;
            }
        }
        Ok(())
    }

    /// The mission ready to carry on: its world rebuilt, its records restored, and the steps
    /// the journal recorded replayed.
    ///
    /// # Errors
    /// [`MissionRunError`] if the region no longer loads or a replayed step fails.
    pub fn resume(mut self) -> Result<MissionRun, MissionRunError> {
        let roi = self.source.load()?;
        let search = self.mission.plan.search.is_some();
        let mut world = world_of(roi, self.drift, self.sensor.clone(), self.seed, search);
        if self.mission.team.steps > 0 {
            world = self.mission.restore(world);
        }
        while self.mission.team.steps < self.journaled_steps {
            if self.mission.step(&mut world, &mut NoObserver)? != Flow::Continue {
                break;
            }
        }
        Ok(MissionRun { state: self, world })
    }
}

/// A mission and its world, ready to fly.
#[derive(Debug)]
pub struct MissionRun {
    /// The state (written to the state file as the mission goes).
    pub state: MissionState,
    /// The world.
    pub world: GridWorld,
}

/// How a mission ended: the run record (written to `out`, the replay to `svg`).
#[derive(Debug, Clone)]
pub struct MissionOutcome {
    /// The run record; `failures` is not empty when robots gave up.
    pub record: GridRunRecord,
    /// Where the record was written.
    pub out: PathBuf,
    /// Where the replay was written.
    pub svg: PathBuf,
    /// Where the browser replay was written, if anywhere.
    pub report: Option<PathBuf>,
    /// Where the MCAP recording was written, if anywhere.
    pub mcap: Option<PathBuf>,
}

/// Counts the bytes written through it (the trace's length, for the state file).
struct Counting<W> {
    inner: W,
    bytes: Rc<Shared<u64>>,
}

impl<W: Write> Write for Counting<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.inner.write(buf)?;
        self.bytes.set(self.bytes.get() + n as u64);
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

/// Opens the trace: a fresh mission (or a new file given on resume) starts it empty; a
/// resumed one cuts its own trace back to the length recorded with the state and appends.
fn open_trace(path: &Path, keep: u64) -> Result<std::fs::File, MissionRunError> {
    let cannot = |source| MissionRunError::Trace { path: path.to_path_buf(), source };
    let mut f = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .read(true)
        .write(true)
        .open(path)
        .map_err(cannot)?;
    let len = f.metadata().map_err(cannot)?.len();
    if len < keep {
        return Err(MissionRunError::TraceShrunk { path: path.to_path_buf(), len, keep });
    }
    f.set_len(keep).map_err(cannot)?;
    std::io::Seek::seek(&mut f, std::io::SeekFrom::End(0)).map_err(cannot)?;
    Ok(f)
}

impl MissionRun {
    /// A fresh mission from `spec` in the region `roi` (loaded from `spec.source`). The
    /// mission builds a map when it has a camera, a search or a region from a file (whose
    /// true shape the map is compared with). Paths are made absolute.
    ///
    /// # Errors
    /// [`MissionRunError::Mission`] for a plan the mission refuses.
    pub fn start(spec: MissionSpec, roi: GridRoi) -> Result<Self, MissionRunError> {
        let map = matches!(spec.sensor, GridSensor::Camera(_))
            || spec.search.is_some()
            || matches!(spec.source, RegionSource::File { .. } | RegionSource::Grid { .. });
        let plan = MissionPlan {
            robots: spec.robots,
            cost: spec.cost,
            battery_s: spec.battery_s,
            search: spec.search,
            map,
        };
        let world =
            world_of(roi, spec.drift, spec.sensor.clone(), spec.seed, spec.search.is_some());
        let mission = Mission::new(&world, plan, spec.recording)?;
        let state = MissionState {
            format: MISSION_FORMAT.into(),
            source: spec.source,
            drift: spec.drift,
            sensor: spec.sensor,
            seed: spec.seed,
            out: absolute(&spec.out),
            svg: absolute(&spec.svg),
            report: spec.report.as_deref().map(absolute),
            mcap: spec.mcap.as_deref().map(absolute),
            trace: spec.trace.as_deref().map(absolute),
            trace_len: 0,
            mission,
            journaled_steps: 0,
        };
        Ok(Self { state, world })
    }

    /// Flies the mission to its end: the trace is streamed as it goes; with a journal `save`,
    /// the state is written to it first (atomically, replacing it: a resumed mission starts a
    /// compact journal from where it stands) and then one line per step, before the next
    /// step; the run record and the replay are written to the state's `out` and `svg` (and
    /// the browser replay and the MCAP recording where the state names them). `progress`
    /// hears the steps and the mission time every 256 steps. A resume from any step ends with
    /// the same record.
    ///
    /// # Errors
    /// [`MissionRunError`]: a strategy misbehaves, the mission exceeds its step limit, or an
    /// output cannot be written. Robots that give up are not an error: see the record's
    /// `failures`.
    pub fn fly(
        mut self,
        save: Option<&Path>,
        progress: Progress,
    ) -> Result<MissionOutcome, MissionRunError> {
        let record = self.fly_record(save, progress)?;
        let file = &self.state;
        atomic::write_json(&file.out, &record)?;
        atomic::write_bytes(&file.svg, self.svg(&record).as_bytes())?;
        if let Some(r) = &file.report {
            atomic::write_bytes(r, self.report(&record).as_bytes())?;
        }
        if let Some(m) = &file.mcap {
            atomic::write_bytes(m, &self.mcap(&record)?)?;
        }
        Ok(MissionOutcome {
            record,
            out: file.out.clone(),
            svg: file.svg.clone(),
            report: file.report.clone(),
            mcap: file.mcap.clone(),
        })
    }

    /// Flies the mission to its end, as [`MissionRun::fly`] does, and returns the run record
    /// without writing it or any picture: only the trace (where the state names one) and the
    /// journal `save` are written. The pictures are [`MissionRun::svg`],
    /// [`MissionRun::report`] and [`MissionRun::mcap`].
    ///
    /// # Errors
    /// As [`MissionRun::fly`], but for the outputs it does not write.
    pub fn fly_record(
        &mut self,
        save: Option<&Path>,
        progress: Progress,
    ) -> Result<GridRunRecord, MissionRunError> {
        let (file, world) = (&mut self.state, &mut self.world);
        let bytes = Rc::new(Shared::new(file.trace_len));
        let mut trace = match &file.trace {
            Some(p) => {
                let f = open_trace(p, file.trace_len)?;
                let out = Counting { inner: std::io::BufWriter::new(f), bytes: bytes.clone() };
                Some(JsonLinesTrace::new(out))
            }
            None => None,
        };
        let mut journal = match save {
            Some(p) => {
                file.mission.snapshot(world);
                file.journaled_steps = file.mission.team.steps;
                file.write(p)?;
                let cannot =
                    |source| MissionRunError::WriteJournal { path: p.to_path_buf(), source };
                Some(Journal::append_to(p, false).map_err(cannot)?)
            }
            None => None,
        };
        let limit = file.mission.step_limit(world);
        loop {
            if file.mission.team.steps >= limit {
                return Err(MissionRunError::StepLimit(limit));
            }
            let flow = match trace.as_mut() {
                Some(t) => file.mission.step(world, t)?,
                None => file.mission.step(world, &mut NoObserver)?,
            };
            if let Some(source) = trace.as_mut().and_then(|t| t.error.take()) {
                let path = file.trace.clone().unwrap_or_else(|| PathBuf::from("trace"));
                return Err(MissionRunError::Trace { path, source });
            }
            if let Some(j) = journal.as_mut() {
                let line = StepLine { steps: file.mission.team.steps, trace_len: bytes.get() };
                let text = format!("{{\"steps\":{},\"trace_len\":{}}}", line.steps, line.trace_len);
                j.append(&text).map_err(|source| MissionRunError::WriteJournal {
                    path: j.path().to_path_buf(),
                    source,
                })?;
            }
            if file.mission.team.steps % 256 == 0 {
                progress(&format!(
                    "{} steps, {:.1} s of mission",
                    file.mission.team.steps,
                    file.mission.team.makespan()
                ));
            }
            if flow != Flow::Continue {
                break;
            }
        }
        Ok(GridRunRecord::new(world, &file.mission, file.seed))
    }

    /// The cells the team mapped as region, for missions that build a map.
    fn mapped(&self) -> Option<Vec<Cell>> {
        self.state.mission.plan.map.then(|| self.state.mission.marks.positive())
    }

    /// The SVG replay of the mission that ended with `record`.
    #[must_use]
    pub fn svg(&self, record: &GridRunRecord) -> String {
        crate::render::roi_svg(self.world.roi(), self.mapped().as_deref(), record)
    }

    /// The browser replay (`report.html`) of the mission that ended with `record`.
    #[must_use]
    pub fn report(&self, record: &GridRunRecord) -> String {
        crate::render::roi_report(self.world.roi(), self.mapped().as_deref(), record)
    }

    /// The MCAP recording of the mission that ended with `record`.
    ///
    /// # Errors
    /// [`MissionRunError::Mcap`] if the recording cannot be made.
    pub fn mcap(&self, record: &GridRunRecord) -> Result<Vec<u8>, MissionRunError> {
        crate::render::roi_mcap(self.world.roi(), self.mapped().as_deref(), record)
            .map_err(|e| MissionRunError::Mcap(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("stopscan-mission-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn spec(dir: &Path) -> MissionSpec {
        MissionSpec {
            source: RegionSource::Random { cells: 300, seed: 3, cell_size: 1.0 },
            drift: Drift::default(),
            sensor: GridSensor::Ideal,
            robots: 3,
            cost: CostModel::new(0.0, 0.0, 1.0).unwrap(),
            battery_s: None,
            search: None,
            recording: Recording::PATHS,
            seed: 3,
            out: dir.join("run.json"),
            svg: dir.join("run.svg"),
            report: None,
            mcap: None,
            trace: Some(dir.join("events.jsonl")),
        }
    }

    #[test]
    fn a_mission_resumed_from_a_midway_state_ends_with_the_same_record_and_trace() {
        let dir = temp("resume");
        let whole = {
            let s = spec(&dir);
            let roi = s.source.load().unwrap();
            MissionRun::start(s, roi).unwrap().fly(None, &mut |_| {}).unwrap()
        };
        let trace = std::fs::read(dir.join("events.jsonl")).unwrap();
        // Fly again, stopping after 40 steps with the state written.
        let s = spec(&dir);
        let roi = s.source.load().unwrap();
        let mut run = MissionRun::start(s, roi).unwrap();
        std::fs::write(dir.join("events.jsonl"), b"").unwrap();
        let state = dir.join("state.json");
        {
            let f = open_trace(&dir.join("events.jsonl"), 0).unwrap();
            let bytes = Rc::new(Shared::new(0));
            let out = Counting { inner: std::io::BufWriter::new(f), bytes: bytes.clone() };
            let mut t = JsonLinesTrace::new(out);
            for _ in 0..40 {
                run.state.mission.step(&mut run.world, &mut t).unwrap();
            }
            drop(t);
            run.state.mission.snapshot(&run.world);
            run.state.trace_len = bytes.get();
            run.state.write(&state).unwrap();
        }
        // Events after the state are cut off on resume.
        std::fs::OpenOptions::new()
            .append(true)
            .open(dir.join("events.jsonl"))
            .unwrap()
            .write_all(b"{\"lost\":1}\n")
            .unwrap();
        let resumed = MissionState::read(&state).unwrap().resume().unwrap();
        assert!(resumed.state.mission.team.steps == 40);
        let end = resumed.fly(Some(&state), &mut |_| {}).unwrap();
        assert_eq!(end.record, whole.record);
        assert_eq!(std::fs::read(dir.join("events.jsonl")).unwrap(), trace);
    }

    /// A journal cut after any step, with a torn line at its end (a crash mid-write), resumes
    /// to the same record and trace; the resumed mission starts a compact journal.
    #[test]
    fn a_journal_cut_by_a_crash_resumes_to_the_same_record_and_trace() {
        let dir = temp("journal");
        let state = dir.join("state.jsonl");
        let whole = {
            let s = spec(&dir);
            let roi = s.source.load().unwrap();
            MissionRun::start(s, roi).unwrap().fly(Some(&state), &mut |_| {}).unwrap()
        };
        let trace = std::fs::read(dir.join("events.jsonl")).unwrap();
        let journal = std::fs::read_to_string(&state).unwrap();
        let lines: Vec<&str> = journal.split_inclusive('\n').collect();
        assert!(lines.len() > 20, "one line per step after the state");
        for keep in [0, 1, 17, lines.len() - 2] {
            let mut cut: String = lines[..=keep].concat();
            cut.push_str(&lines[keep + 1][..5]);
            std::fs::write(&state, cut).unwrap();
            let resumed = MissionState::read(&state).unwrap().resume().unwrap();
            assert_eq!(resumed.state.mission.team.steps, keep as u64);
            let end = resumed.fly(Some(&state), &mut |_| {}).unwrap();
            assert_eq!(end.record, whole.record, "cut after {keep} steps");
            assert_eq!(std::fs::read(dir.join("events.jsonl")).unwrap(), trace);
            let again = std::fs::read_to_string(&state).unwrap();
            assert_eq!(again.lines().count(), lines.len() - keep, "a compact journal");
        }
    }

    #[test]
    fn a_state_of_another_format_is_refused() {
        let dir = temp("format");
        let s = spec(&dir);
        let roi = s.source.load().unwrap();
        let mut run = MissionRun::start(s, roi).unwrap();
        run.state.mission.step(&mut run.world, &mut NoObserver).unwrap();
        run.state.format = "stopscan-mission/1".into();
        let path = dir.join("old.json");
        run.state.write(&path).unwrap();
        let e = MissionState::read(&path).unwrap_err().to_string();
        assert!(
            e.ends_with("format \"stopscan-mission/1\", expected \"stopscan-mission/3\""),
            "{e}"
        );
        // A `/2` state file (one line, no newline) still resumes.
        run.state.format = "stopscan-mission/2".into();
        std::fs::write(&path, serde_json::to_string(&run.state).unwrap()).unwrap();
        let old = MissionState::read(&path).unwrap();
        assert_eq!((old.format.as_str(), old.mission.team.steps), (MISSION_FORMAT, 1));
        std::fs::write(&path, "{\"format\": 3").unwrap();
        let e = MissionState::read(&path).unwrap_err().to_string();
        assert!(e.contains(":1:") && e.contains("not a mission state"), "{e}");
    }
}
