//! MCAP recordings of runs for Foxglove (`--mcap FILE`): every message is JSON with a
//! Foxglove schema (`foxglove.SceneUpdate`, `foxglove.PosesInFrame`, `foxglove.FrameTransform`,
//! `foxglove.LaserScan`, `foxglove.Log`; schema encoding `jsonschema`), so that a run opens in
//! Foxglove with no set-up. Written with the `mcap` crate, uncompressed.
//!
//! Times are the run's own clock under its cost model: the run starts at 0 (1970-01-01 in a
//! viewer). Between two scans a robot's time along its path is interpolated by distance, so it
//! is exact at every scan (and everywhere when moves cost no fixed time). Geometry is in the
//! frame the run was computed in, `map`; the `stopscan` metadata record gives the offset to the
//! input's coordinates (`frame_origin`) besides the version, seed, strategy, cost model and
//! sensor, and the whole run record.
//!
//! Topics of an exploration ([`polygon_mcap`]):
//! - `/map` (SceneUpdate, once): the walls, and the configuration space when the robot has a
//!   footprint;
//! - `/scans` (SceneUpdate, one per scan): the region seen, as it is taken;
//! - `/frontiers` (SceneUpdate, one per scan): the frontiers still open after it;
//! - `/path` (PosesInFrame, one per scan): the path driven so far;
//! - `/tf` (FrameTransform): `map → base_link` at every vertex of the path, and for a raw-scan
//!   run `map → base_link_estimate` at every stop (the pose believed after ICP);
//! - `/lidar` (LaserScan, one per scan, raw-scan runs only): the scan as the lidar returned it,
//!   placed at the true pose;
//! - `/log` (Log): every scan, and how the run ended.
//!
//! Topics of a grid mission ([`roi_mcap`]): `/map` (the region's cells, as one flat box per run
//! of cells along a row), `/cells` (SceneUpdate: the cells first reached at each moment),
//! `/tf` (`map → robot_<i>` at every cell a robot reaches, in the region's frame), `/flights`
//! (SceneUpdate, once at the end: every robot's flight) and `/log`.

use std::collections::BTreeMap;
use std::io::{Cursor, Seek, Write};

use serde_json::{Value, json};

use super::report::{PolygonReplay, row_runs, scan_vertices};
use crate::kernel::Point;
use crate::protocol::grid::Cell;
use crate::protocol::laser::Pose;
use crate::run_record::{GridRunRecord, RunRecord};
use crate::world::grid::GridRoi;

/// Why a recording could not be made.
#[derive(Debug, thiserror::Error)]
#[error("cannot write the MCAP recording: {0}")]
pub struct McapError(String);

impl From<mcap::McapError> for McapError {
    fn from(e: mcap::McapError) -> Self {
        Self(e.to_string())
    }
}

const FRAME: &str = "map";

/// The Foxglove schemas a recording may use.
pub const SCHEMAS: [&str; 5] = [
    "foxglove.SceneUpdate",
    "foxglove.PosesInFrame",
    "foxglove.FrameTransform",
    "foxglove.LaserScan",
    "foxglove.Log",
];

/// The JSON Schemas of the Foxglove messages written here (`$defs` shared).
mod schema {
    use serde_json::{Value, json};

    fn defs() -> Value {
        let num = json!({"type": "number"});
        let xyz = json!({"type": "object", "properties": {"x": num, "y": num, "z": num}});
        json!({
            "time": {"type": "object", "title": "time", "properties": {
                "sec": {"type": "integer", "minimum": 0}, "nsec": {"type": "integer", "minimum": 0}}},
            "duration": {"type": "object", "title": "duration", "properties": {
                "sec": {"type": "integer"}, "nsec": {"type": "integer", "minimum": 0}}},
            "vector3": xyz,
            "point3": xyz,
            "quaternion": {"type": "object", "properties": {"x": num, "y": num, "z": num, "w": num}},
            "pose": {"type": "object", "properties": {
                "position": {"$ref": "#/$defs/vector3"}, "orientation": {"$ref": "#/$defs/quaternion"}}},
            "color": {"type": "object", "properties": {"r": num, "g": num, "b": num, "a": num}},
            "line": {"type": "object", "title": "foxglove.LinePrimitive", "properties": {
                "type": {"type": "integer", "enum": [0, 1, 2], "description": "0 LINE_STRIP, 1 LINE_LOOP, 2 LINE_LIST"},
                "pose": {"$ref": "#/$defs/pose"}, "thickness": num, "scale_invariant": {"type": "boolean"},
                "points": {"type": "array", "items": {"$ref": "#/$defs/point3"}},
                "color": {"$ref": "#/$defs/color"},
                "colors": {"type": "array", "items": {"$ref": "#/$defs/color"}},
                "indices": {"type": "array", "items": {"type": "integer", "minimum": 0}}}},
            "triangles": {"type": "object", "title": "foxglove.TriangleListPrimitive", "properties": {
                "pose": {"$ref": "#/$defs/pose"},
                "points": {"type": "array", "items": {"$ref": "#/$defs/point3"}},
                "color": {"$ref": "#/$defs/color"},
                "colors": {"type": "array", "items": {"$ref": "#/$defs/color"}},
                "indices": {"type": "array", "items": {"type": "integer", "minimum": 0}}}},
            "cube": {"type": "object", "title": "foxglove.CubePrimitive", "properties": {
                "pose": {"$ref": "#/$defs/pose"}, "size": {"$ref": "#/$defs/vector3"},
                "color": {"$ref": "#/$defs/color"}}},
            "entity": {"type": "object", "title": "foxglove.SceneEntity", "properties": {
                "timestamp": {"$ref": "#/$defs/time"}, "frame_id": {"type": "string"},
                "id": {"type": "string"}, "lifetime": {"$ref": "#/$defs/duration"},
                "frame_locked": {"type": "boolean"},
                "metadata": {"type": "array", "items": {"type": "object", "properties": {
                    "key": {"type": "string"}, "value": {"type": "string"}}}},
                "arrows": {"type": "array"}, "cubes": {"type": "array", "items": {"$ref": "#/$defs/cube"}},
                "spheres": {"type": "array"}, "cylinders": {"type": "array"},
                "lines": {"type": "array", "items": {"$ref": "#/$defs/line"}},
                "triangles": {"type": "array", "items": {"$ref": "#/$defs/triangles"}},
                "texts": {"type": "array"}, "models": {"type": "array"}}},
        })
    }

    fn document(title: &str, properties: &Value) -> Vec<u8> {
        let required: Vec<&String> =
            properties.as_object().map(|o| o.keys().collect()).unwrap_or_default();
        let s = json!({
            "$schema": "https://json-schema.org/draft/2020-12/schema",
            "title": title,
            "type": "object",
            "properties": properties,
            "required": required,
            "$defs": defs(),
        });
        serde_json::to_vec(&s).unwrap_or_default()
    }

    pub(super) fn scene_update() -> Vec<u8> {
        document(
            "foxglove.SceneUpdate",
            &json!({
                "deletions": {"type": "array", "items": {"type": "object", "properties": {
                    "timestamp": {"$ref": "#/$defs/time"}, "type": {"type": "integer", "enum": [0, 1]},
                    "id": {"type": "string"}}}},
                "entities": {"type": "array", "items": {"$ref": "#/$defs/entity"}},
            }),
        )
    }

    pub(super) fn poses_in_frame() -> Vec<u8> {
        document(
            "foxglove.PosesInFrame",
            &json!({
                "timestamp": {"$ref": "#/$defs/time"}, "frame_id": {"type": "string"},
                "poses": {"type": "array", "items": {"$ref": "#/$defs/pose"}},
            }),
        )
    }

    pub(super) fn frame_transform() -> Vec<u8> {
        document(
            "foxglove.FrameTransform",
            &json!({
                "timestamp": {"$ref": "#/$defs/time"}, "parent_frame_id": {"type": "string"},
                "child_frame_id": {"type": "string"}, "translation": {"$ref": "#/$defs/vector3"},
                "rotation": {"$ref": "#/$defs/quaternion"},
            }),
        )
    }

    pub(super) fn laser_scan() -> Vec<u8> {
        document(
            "foxglove.LaserScan",
            &json!({
                "timestamp": {"$ref": "#/$defs/time"}, "frame_id": {"type": "string"},
                "pose": {"$ref": "#/$defs/pose"}, "start_angle": {"type": "number"},
                "end_angle": {"type": "number"},
                "ranges": {"type": "array", "items": {"type": ["number", "null"]}},
                "intensities": {"type": "array", "items": {"type": "number"}},
            }),
        )
    }

    pub(super) fn log() -> Vec<u8> {
        document(
            "foxglove.Log",
            &json!({
                "timestamp": {"$ref": "#/$defs/time"},
                "level": {"type": "integer", "enum": [0, 1, 2, 3, 4, 5], "description": "1 DEBUG, 2 INFO, 3 WARNING, 4 ERROR, 5 FATAL"},
                "message": {"type": "string"}, "name": {"type": "string"}, "file": {"type": "string"},
                "line": {"type": "integer", "minimum": 0},
            }),
        )
    }
}

/// A Foxglove `time` from seconds (negative and non-finite times are 0).
pub fn time(seconds: f64) -> Value {
    let ns = nanos(seconds);
    json!({"sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000})
}

fn nanos(seconds: f64) -> u64 {
    if seconds.is_finite() && seconds > 0.0 {
        // Saturates at u64::MAX, far beyond any run.
        (seconds * 1e9).round() as u64
    } else {
        0
    }
}

fn point(p: Point) -> Value {
    json!({"x": p[0], "y": p[1], "z": 0.0})
}

/// A Foxglove `Pose` in the plane: at `(x, y)`, turned by `theta` about z.
pub fn pose(x: f64, y: f64, theta: f64) -> Value {
    json!({
        "position": {"x": x, "y": y, "z": 0.0},
        "orientation": {"x": 0.0, "y": 0.0, "z": (theta / 2.0).sin(), "w": (theta / 2.0).cos()},
    })
}

fn identity() -> Value {
    pose(0.0, 0.0, 0.0)
}

/// A Foxglove `Color` object.
type Colour = serde_json::Map<String, Value>;

fn colour(r: f64, g: f64, b: f64, a: f64) -> Colour {
    [("r", r), ("g", g), ("b", b), ("a", a)]
        .into_iter()
        .map(|(k, v)| (k.to_string(), json!(v)))
        .collect()
}

/// A scene entity with only `lines`, `triangles` and `cubes` filled in.
fn entity(id: &str, at: f64, lines: Vec<Value>, triangles: Vec<Value>, cubes: Vec<Value>) -> Value {
    json!({
        "timestamp": time(at), "frame_id": FRAME, "id": id,
        "lifetime": {"sec": 0, "nsec": 0}, "frame_locked": false, "metadata": [],
        "arrows": [], "cubes": Value::Array(cubes), "spheres": [], "cylinders": [],
        "lines": Value::Array(lines), "triangles": Value::Array(triangles), "texts": [], "models": [],
    })
}

/// A line primitive: 0 strip, 1 loop, 2 list.
fn line(kind: u8, points: &[Point], thickness: f64, c: Colour) -> Value {
    json!({
        "type": kind, "pose": identity(), "thickness": thickness, "scale_invariant": true,
        "points": points.iter().map(|&p| point(p)).collect::<Vec<_>>(),
        "color": Value::Object(c), "colors": [], "indices": [],
    })
}

/// The triangle fan of a polygon star-shaped from `centre` (a visibility region).
fn fan(centre: Point, ring: &[Point], c: Colour) -> Value {
    let mut points = Vec::with_capacity(3 * ring.len());
    for (i, &a) in ring.iter().enumerate() {
        let b = ring[(i + 1) % ring.len()];
        points.extend([point(centre), point(a), point(b)]);
    }
    json!({"pose": identity(), "points": points, "color": Value::Object(c), "colors": [], "indices": []})
}

fn scene(entities: Vec<Value>) -> Value {
    json!({"deletions": [], "entities": Value::Array(entities)})
}

/// Log levels.
pub const INFO: u8 = 2;
/// See [`INFO`].
pub const WARNING: u8 = 3;
/// See [`INFO`].
pub const ERROR: u8 = 4;

/// A Foxglove `Log` line.
pub fn log(at: f64, level: u8, message: &str) -> Value {
    json!({"timestamp": time(at), "level": level, "message": message, "name": "stopscan", "file": "", "line": 0})
}

/// A recording being written to memory ([`McapWriter::new`]) or any seekable writer: its
/// channels by topic, and their message counts. Channels are made on first use, each with
/// its schema.
pub struct Recording<W: Write + Seek> {
    writer: mcap::Writer<W>,
    schemas: BTreeMap<&'static str, u16>,
    channels: BTreeMap<String, (u16, u32)>,
}

/// A recording in memory.
pub type McapWriter = Recording<Cursor<Vec<u8>>>;

impl McapWriter {
    /// An empty recording in memory.
    ///
    /// # Errors
    /// [`McapError`] if the writer cannot start (only on a bug).
    pub fn in_memory() -> Result<Self, McapError> {
        Self::new(Cursor::new(Vec::new()))
    }

    /// The finished file's bytes.
    ///
    /// # Errors
    /// [`McapError`] if the summary cannot be written (only on a bug).
    pub fn bytes(self) -> Result<Vec<u8>, McapError> {
        Ok(self.finish()?.into_inner())
    }
}

impl<W: Write + Seek> Recording<W> {
    /// A recording written to `w`.
    ///
    /// # Errors
    /// [`McapError`] if the header cannot be written.
    pub fn new(w: W) -> Result<Self, McapError> {
        let options = mcap::WriteOptions::new()
            .profile("")
            .library(format!("stopscan {}", env!("CARGO_PKG_VERSION")));
        Ok(Self { writer: options.create(w)?, schemas: BTreeMap::new(), channels: BTreeMap::new() })
    }

    fn schema(&mut self, name: &'static str) -> Result<u16, McapError> {
        if let Some(&id) = self.schemas.get(name) {
            return Ok(id);
        }
        let data = match name {
            "foxglove.SceneUpdate" => schema::scene_update(),
            "foxglove.PosesInFrame" => schema::poses_in_frame(),
            "foxglove.FrameTransform" => schema::frame_transform(),
            "foxglove.LaserScan" => schema::laser_scan(),
            _ => schema::log(),
        };
        let id = self.writer.add_schema(name, "jsonschema", &data)?;
        self.schemas.insert(name, id);
        Ok(id)
    }

    /// Writes `message` on `topic` (its schema named `schema`, one of [`SCHEMAS`]) at `at`
    /// seconds.
    ///
    /// # Errors
    /// [`McapError`] if the writer fails.
    pub fn write(
        &mut self,
        topic: &str,
        schema: &'static str,
        at: f64,
        message: &Value,
    ) -> Result<(), McapError> {
        let (channel, sequence) = if let Some(&c) = self.channels.get(topic) {
            c
        } else {
            let s = self.schema(schema)?;
            (self.writer.add_channel(s, topic, "json", &BTreeMap::new())?, 0)
        };
        self.channels.insert(topic.to_string(), (channel, sequence + 1));
        let data = serde_json::to_vec(message).map_err(|e| McapError(e.to_string()))?;
        let header = mcap::records::MessageHeader {
            channel_id: channel,
            sequence,
            log_time: nanos(at),
            publish_time: nanos(at),
        };
        self.writer.write_to_known_channel(&header, &data)?;
        Ok(())
    }

    /// Writes the `stopscan` metadata record.
    ///
    /// # Errors
    /// [`McapError`] if the writer fails.
    pub fn metadata(&mut self, entries: BTreeMap<String, String>) -> Result<(), McapError> {
        self.writer.write_metadata(&mcap::records::Metadata {
            name: "stopscan".into(),
            metadata: entries,
        })?;
        Ok(())
    }

    /// Writes the summary and returns the writer.
    ///
    /// # Errors
    /// [`McapError`] if the writer fails.
    pub fn finish(mut self) -> Result<W, McapError> {
        self.writer.finish()?;
        Ok(self.writer.into_inner())
    }
}

/// The metadata every recording carries.
fn common_metadata(
    version: &str,
    seed: u64,
    strategy: &impl serde::Serialize,
    cost: &impl serde::Serialize,
    sensor: &impl serde::Serialize,
    record: &impl serde::Serialize,
) -> BTreeMap<String, String> {
    let text = |v: &dyn erased::Json| v.json();
    let mut m = BTreeMap::new();
    m.insert("stopscan_version".into(), version.to_string());
    m.insert("seed".into(), seed.to_string());
    m.insert("strategy".into(), text(strategy));
    m.insert("cost_model".into(), text(cost));
    m.insert("sensor".into(), text(sensor));
    m.insert("run_record".into(), text(record));
    m.insert("time_origin".into(), "0 s = the start of the run, under its cost model".into());
    m
}

/// Serialisation to a JSON string behind `dyn`.
mod erased {
    pub(super) trait Json {
        fn json(&self) -> String;
    }
    impl<T: serde::Serialize> Json for T {
        fn json(&self) -> String {
            serde_json::to_string(self).unwrap_or_default()
        }
    }
}

/// The time at each vertex of an exploration's path: at a scan's vertex, when the scan began;
/// between scans, interpolated by distance from when the robot left (its last scan ended) to
/// when it began the next; after the last scan, up to the run's end.
fn vertex_times(replay: &PolygonReplay, record: &RunRecord) -> Vec<f64> {
    let path = &replay.path;
    let n = path.len();
    let mut dist = vec![0.0; n];
    for i in 1..n {
        dist[i] = dist[i - 1] + (path[i][0] - path[i - 1][0]).hypot(path[i][1] - path[i - 1][1]);
    }
    let mut times = vec![0.0; n];
    // From vertex `from`, left at `left`, to vertex `to`, reached at `arrive`.
    let mut between = |from: usize, left: f64, to: usize, arrive: f64| {
        let span = dist[to] - dist[from];
        for i in from + 1..=to {
            let u = if span > 0.0 { (dist[i] - dist[from]) / span } else { 1.0 };
            times[i] = left + u * (arrive - left);
        }
    };
    let (mut from, mut left) = (0, 0.0);
    let vertices = scan_vertices(path, &replay.regions, &replay.steps);
    for (k, &v) in vertices.iter().enumerate() {
        let begin = replay.scan_times.get(k).copied().unwrap_or(left);
        if v > from && v < n {
            between(from, left, v, begin);
        }
        from = v;
        left = begin + record.cost_model.scan_time;
    }
    if from + 1 < n {
        between(from, left, n - 1, record.metrics.totals.time.max(left));
    }
    times
}

/// The heading at each path vertex: along the leg that leaves it (the last: the leg that
/// reached it).
fn headings(path: &[Point]) -> Vec<f64> {
    let mut out = Vec::with_capacity(path.len());
    let mut last = 0.0;
    for i in 0..path.len() {
        let (a, b) = match (path.get(i), path.get(i + 1)) {
            (Some(&a), Some(&b)) if a != b => (a, b),
            _ => {
                out.push(last);
                continue;
            }
        };
        last = (b[1] - a[1]).atan2(b[0] - a[0]);
        out.push(last);
    }
    out
}

fn transform(child: &str, at: f64, x: f64, y: f64, theta: f64) -> Value {
    frame_transform(FRAME, child, at, x, y, theta)
}

/// A Foxglove `FrameTransform`: `child` in `parent` at `(x, y)`, turned by `theta`.
pub fn frame_transform(parent: &str, child: &str, at: f64, x: f64, y: f64, theta: f64) -> Value {
    let p = pose(x, y, theta);
    json!({
        "timestamp": time(at), "parent_frame_id": parent, "child_frame_id": child,
        "translation": p["position"], "rotation": p["orientation"],
    })
}

fn laser(at: f64, truth: &Pose, scan: &crate::protocol::laser::LaserScan) -> Value {
    laser_scan(FRAME, at, truth, scan)
}

/// A Foxglove `LaserScan` of `scan` taken at `at` (a pose in `frame`).
pub fn laser_scan(
    frame: &str,
    at_time: f64,
    at: &Pose,
    scan: &crate::protocol::laser::LaserScan,
) -> Value {
    let (at, truth) = (at_time, at);
    let n = scan.ranges.len();
    let end = scan.angle_min + scan.angle_increment * (n.saturating_sub(1)) as f64;
    // Foxglove's LaserScan has no range limits: out-of-range returns (REP 117's ±Inf, NaN, or
    // outside [range_min, range_max]) are sent as null, which it draws as no return.
    let ranges: Vec<Value> = scan
        .ranges
        .iter()
        .map(|&r| {
            if r.is_finite() && r >= scan.range_min && r <= scan.range_max {
                json!(r)
            } else {
                Value::Null
            }
        })
        .collect();
    json!({
        "timestamp": time(at), "frame_id": frame, "pose": pose(truth.x, truth.y, truth.theta),
        "start_angle": scan.angle_min, "end_angle": end, "ranges": ranges, "intensities": [],
    })
}

/// The recording of an exploration (see the module's notes), as bytes.
///
/// # Errors
/// [`McapError`] if the writer fails (it writes to memory, so only on a bug).
pub fn polygon_mcap(replay: &PolygonReplay, record: &RunRecord) -> Result<Vec<u8>, McapError> {
    let mut rec = Recording::new(Cursor::new(Vec::new()))?;
    let mut meta = common_metadata(
        &record.stopscan_version,
        record.seed,
        &record.strategy,
        &record.cost_model,
        &record.sensor,
        record,
    );
    meta.insert("environment".into(), record.environment.name.clone());
    let origin = record.environment.frame_origin.unwrap_or([0.0, 0.0]);
    meta.insert("frame_origin".into(), format!("[{}, {}]", origin[0], origin[1]));
    rec.metadata(meta)?;

    let walls: Vec<Value> =
        replay.domain.rings().iter().map(|r| line(1, r, 2.0, colour(0.1, 0.1, 0.1, 1.0))).collect();
    let mut map = vec![entity("walls", 0.0, walls, vec![], vec![])];
    if let Some(c) = &replay.cspace {
        let rings =
            c.iter().flatten().map(|r| line(1, r, 1.0, colour(0.18, 0.62, 0.27, 0.8))).collect();
        map.push(entity("configuration-space", 0.0, rings, vec![], vec![]));
    }
    rec.write("/map", "foxglove.SceneUpdate", 0.0, &scene(map))?;

    let times = vertex_times(replay, record);
    let heading = headings(&replay.path);
    for (i, p) in replay.path.iter().enumerate() {
        rec.write(
            "/tf",
            "foxglove.FrameTransform",
            times[i],
            &transform("base_link", times[i], p[0], p[1], heading[i]),
        )?;
    }
    let vertices = scan_vertices(&replay.path, &replay.regions, &replay.steps);
    let history = replay.frontier_history();
    for (k, region) in replay.regions.iter().enumerate() {
        let at = replay.scan_times.get(k).copied().unwrap_or(0.0);
        let id = format!("scan-{}", k + 1);
        let tri = fan(region.viewpoint, &region.polygon, colour(0.23, 0.49, 0.85, 0.25));
        let outline = line(1, &region.polygon, 1.0, colour(0.11, 0.31, 0.6, 0.9));
        rec.write(
            "/scans",
            "foxglove.SceneUpdate",
            at,
            &scene(vec![entity(&id, at, vec![outline], vec![tri], vec![])]),
        )?;
        // The frontiers open after this scan: one entity, replaced at each step.
        let open = open_after(history, k + 1);
        let lines = if open.is_empty() {
            vec![]
        } else {
            vec![line(2, &open, 3.0, colour(0.88, 0.19, 0.12, 1.0))]
        };
        rec.write(
            "/frontiers",
            "foxglove.SceneUpdate",
            at,
            &scene(vec![entity("open-frontiers", at, lines, vec![], vec![])]),
        )?;
        let upto = vertices.get(k).map_or(0, |&v| v + 1).min(replay.path.len());
        let poses: Vec<Value> =
            (0..upto).map(|i| pose(replay.path[i][0], replay.path[i][1], heading[i])).collect();
        rec.write(
            "/path",
            "foxglove.PosesInFrame",
            at,
            &json!({"timestamp": time(at), "frame_id": FRAME, "poses": poses}),
        )?;
        let seen = region.area();
        let message = format!(
            "scan {} at ({:.3}, {:.3}) m: {:.3} m² in view, {} frontier parts open after it",
            k + 1,
            region.viewpoint[0] + origin[0],
            region.viewpoint[1] + origin[1],
            seen,
            open.len() / 2
        );
        rec.write("/log", "foxglove.Log", at, &log(at, INFO, &message))?;
        if let Some(raw) = &replay.raw
            && let (Some(scan), Some(truth), Some(estimate)) =
                (raw.laser.get(k), raw.truth.get(k), raw.estimate.get(k))
        {
            rec.write("/lidar", "foxglove.LaserScan", at, &laser(at, truth, scan))?;
            let t = transform("base_link_estimate", at, estimate.x, estimate.y, estimate.theta);
            rec.write("/tf", "foxglove.FrameTransform", at, &t)?;
        }
    }
    let end = record.metrics.totals.time;
    let (level, message) = ending(record);
    rec.write("/log", "foxglove.Log", end, &log(end, level, &message))?;
    Ok(rec.finish()?.into_inner())
}

/// A grid's cells in metres.
#[derive(Clone, Copy)]
struct Grid {
    /// The cell's side.
    s: f64,
}

impl Grid {
    /// Cell `[r, c]`'s centre, `(c·s, −r·s)`.
    fn centre(self, c: Cell) -> Point {
        [f64::from(c[1]) * self.s, -f64::from(c[0]) * self.s]
    }

    /// A flat box over `cols` cells of a row from `c0`.
    fn flat(self, c0: Cell, cols: f64, colour: Colour) -> Value {
        let [x, y] = self.centre(c0);
        json!({
            "pose": pose(x + (cols - 1.0) * self.s / 2.0, y, 0.0),
            "size": {"x": cols * self.s, "y": self.s, "z": 0.01 * self.s},
            "color": Value::Object(colour),
        })
    }
}

/// A grid mission's flights: every arrival in time order (the robot's transform, and the
/// region cells first reached then), then every robot's flight as a line.
fn flights<W: Write + Seek>(
    rec: &mut Recording<W>,
    roi: &GridRoi,
    record: &GridRunRecord,
    g: Grid,
) -> Result<(), McapError> {
    // Every arrival, in time order: the robot's transform, and the region cells first reached.
    let in_region: std::collections::HashSet<Cell> = roi.cells().iter().copied().collect();
    let mut arrivals: Vec<(f64, usize, Cell)> = record
        .robots
        .iter()
        .flat_map(|r| r.times.iter().zip(&r.cells).map(move |(&t, &c)| (t, r.id, c)))
        .collect();
    arrivals.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut marked = std::collections::HashSet::new();
    let mut batch: Vec<Value> = Vec::new();
    let mut batch_time = 0.0;
    let mut batches = 0usize;
    for &(t, id, c) in &arrivals {
        if t != batch_time {
            flush_cells(rec, &mut batch, batch_time, &mut batches)?;
            batch_time = t;
        }
        let [x, y] = g.centre(c);
        rec.write(
            "/tf",
            "foxglove.FrameTransform",
            t,
            &transform(&format!("robot_{id}"), t, x, y, 0.0),
        )?;
        if in_region.contains(&c) && marked.insert(c) {
            batch.push(g.flat(c, 1.0, colour(0.37, 0.62, 0.29, 0.9)));
        }
    }
    flush_cells(rec, &mut batch, batch_time, &mut batches)?;
    let palette = [(0.12, 0.47, 0.71), (0.84, 0.15, 0.16), (0.17, 0.63, 0.17), (1.0, 0.5, 0.05)];
    let lines = record
        .robots
        .iter()
        .map(|r| {
            let (cr, cg, cb) = palette[r.id % palette.len()];
            let pts: Vec<Point> = r.cells.iter().map(|&c| g.centre(c)).collect();
            line(0, &pts, 2.0, colour(cr, cg, cb, 0.8))
        })
        .collect();
    let end = record.metrics.totals.time;
    rec.write(
        "/flights",
        "foxglove.SceneUpdate",
        end,
        &scene(vec![entity("flights", end, lines, vec![], vec![])]),
    )?;
    Ok(())
}

/// How an exploration ended, as a log line.
fn ending(record: &RunRecord) -> (u8, String) {
    let (m, t) = (&record.metrics, &record.metrics.totals);
    match &record.error {
        Some(e) => (ERROR, format!("the run ended early: {e}")),
        None if m.open_windows > 0 => (
            WARNING,
            format!(
                "done: {} scans, {:.3} s ({:.3} scan + {:.3} move + {:.3} travel), coverage {:.6}, {} windows left open",
                t.scans,
                t.time,
                t.scan_time_total,
                t.move_time_total,
                t.travel_time_total,
                m.coverage,
                m.open_windows
            ),
        ),
        None => (
            INFO,
            format!(
                "done: {} scans, {:.3} s ({:.3} scan + {:.3} move + {:.3} travel), coverage {:.6}",
                t.scans,
                t.time,
                t.scan_time_total,
                t.move_time_total,
                t.travel_time_total,
                m.coverage
            ),
        ),
    }
}

/// The open parts of the frontiers after `step` scans, as pairs of segment ends.
fn open_after(history: &[crate::algorithm::cover::FrontierHistory], step: usize) -> Vec<Point> {
    let mut open = Vec::new();
    for h in history.iter().filter(|h| h.scan < step) {
        let Some((_, parts)) = h.open.iter().rev().find(|(s, _)| *s <= step) else { continue };
        let (a, b) = (h.from, h.to);
        for &[t0, t1] in parts {
            open.push([a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1])]);
            open.push([a[0] + t1 * (b[0] - a[0]), a[1] + t1 * (b[1] - a[1])]);
        }
    }
    open
}

/// Writes the cells first reached at `at` (if any) as the entity `marked-<n>`.
fn flush_cells<W: Write + Seek>(
    rec: &mut Recording<W>,
    batch: &mut Vec<Value>,
    at: f64,
    n: &mut usize,
) -> Result<(), McapError> {
    if batch.is_empty() {
        return Ok(());
    }
    *n += 1;
    let e = entity(&format!("marked-{n}"), at, vec![], vec![], std::mem::take(batch));
    rec.write("/cells", "foxglove.SceneUpdate", at, &scene(vec![e]))
}

/// The recording of a grid mission (see the module's notes), as bytes. Above
/// [`MAX_REPORTED_CELLS`](super::MAX_REPORTED_CELLS) flown cells, the flights, the robots'
/// transforms and the cells' marking are left out (and the log says so).
///
/// # Errors
/// As [`polygon_mcap`].
pub fn roi_mcap(
    roi: &GridRoi,
    mapped: Option<&[Cell]>,
    record: &GridRunRecord,
) -> Result<Vec<u8>, McapError> {
    let mut rec = Recording::new(Cursor::new(Vec::new()))?;
    let mut meta = common_metadata(
        &record.stopscan_version,
        record.seed,
        &record.strategy,
        &record.cost_model,
        &record.sensor,
        record,
    );
    meta.insert("environment".into(), record.environment.name.clone());
    meta.insert(
        "cell_frame".into(),
        "cell [row, col] is centred at (col·s, −row·s) metres in the region's frame (drift not applied)".into(),
    );
    rec.metadata(meta)?;
    let g = Grid { s: roi.cell_size() };
    let flat = |c0: Cell, cols: f64, col: Colour| g.flat(c0, cols, col);
    let runs = row_runs(roi.cells());
    let region: Vec<Value> = runs
        .chunks(3)
        .map(|r| flat([r[0], r[1]], f64::from(r[2] - r[1] + 1), colour(0.74, 0.84, 0.69, 0.6)))
        .collect();
    let mut map = vec![entity("region", 0.0, vec![], vec![], region)];
    if let Some(m) = mapped {
        let cubes = m.iter().map(|&c| flat(c, 1.0, colour(0.2, 0.2, 0.2, 0.35))).collect();
        map.push(entity("map", record.metrics.totals.time, vec![], vec![], cubes));
    }
    rec.write("/map", "foxglove.SceneUpdate", 0.0, &scene(map))?;

    let flown: usize = record.robots.iter().map(|r| r.cells.len()).sum();
    if flown <= super::MAX_REPORTED_CELLS {
        flights(&mut rec, roi, record, g)?;
    } else {
        let message = format!("{flown} flown cells: flights, transforms and marking left out");
        rec.write("/log", "foxglove.Log", 0.0, &log(0.0, WARNING, &message))?;
    }
    for r in &record.robots {
        let message =
            format!("robot {} done at {:.3} s: {} scans", r.id, r.finish_time, r.scans.len());
        rec.write("/log", "foxglove.Log", r.finish_time, &log(r.finish_time, INFO, &message))?;
    }
    let m = &record.metrics;
    let end = m.totals.time;
    let (level, message) = if record.failures.is_empty() {
        (
            INFO,
            format!(
                "done: {} robots, {:.3} s, {} of {} cells visited",
                record.robots.len(),
                end,
                m.visited_cells,
                record.cells
            ),
        )
    } else {
        (ERROR, format!("the mission did not complete: {}", record.failures.join("; ")))
    };
    rec.write("/log", "foxglove.Log", end, &log(end, level, &message))?;
    Ok(rec.finish()?.into_inner())
}
