//! `stopscan serve`: a simulated robot (noisy lidar, drifting odometry, a navigation stack
//! that refuses goals it cannot reach) drives the server over standard input and output and
//! over TCP; malformed messages get errors naming the field; `kill -9` at random moments,
//! with `--resume`, ends with the same journal, byte for byte, as an uninterrupted run.

use crate::common;

use std::io::{BufRead, BufReader, Write};
use std::path::Path;
use std::process::{Child, ChildStdin, ChildStdout, Command, Stdio};

use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::{Value, json};
use stopscan::kernel::Point;
use stopscan::pipeline::serve::client::SimClient;
use stopscan::protocol::CostModel;
use stopscan::protocol::polygon::Footprint;
use stopscan::sim::Recording;
use stopscan::sim::lidar::SimRobot;
use stopscan::world::grid::{Drift, GridRoi, GridSensor, GridWorld};
use stopscan::world::lidar::Lidar;
use stopscan::world::polygon::PolygonWorld;

use common::{mcap_count, mcap_topic, read_mcap, temp};

#[path = "../../../stopscan/tests/it/support/seen.rs"]
mod seen;
use seen::seen_share;

/// A small generated office (two rows of three rooms) and its start.
fn office() -> (PolygonWorld, Point) {
    let inst = stopscan::generate::office(2, 3, 4).unwrap();
    let world = PolygonWorld::with_robot(
        inst.domain,
        None,
        &Footprint::disc(0.2).unwrap(),
        Some(inst.start),
    )
    .unwrap();
    (world, inst.start)
}

/// The robot's side of the protocol: a simulated robot (360-beam lidar, 1% drift) that
/// answers each reply with its next request.
fn client<'a>(world: &'a PolygonWorld, start: Point, strategy: &str, seed: u64) -> SimClient<'a> {
    let lidar = Lidar { beams: 360, ..Lidar::default() };
    let setup = json!({
        "strategy": strategy, "cost": {"scan_time": 30.0, "speed": 0.5},
        "robot": {"radius": 0.2}, "sensor": {"sigma": 0.02}, "odometry_drift": 0.01,
    });
    SimClient::new(
        SimRobot::new(world, start, lidar, 0.01, seed),
        setup.as_object().unwrap().clone(),
    )
}

/// A server process on pipes.
struct Server {
    child: Child,
    input: ChildStdin,
    output: BufReader<ChildStdout>,
}

impl Server {
    fn spawn(args: &[&str]) -> Self {
        let mut child = Command::new(env!("CARGO_BIN_EXE_stopscan"))
            .arg("serve")
            .args(args)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        let input = child.stdin.take().unwrap();
        let output = BufReader::new(child.stdout.take().unwrap());
        Self { child, input, output }
    }

    /// Sends a line and reads the reply; `None` if the server died first.
    fn ask(&mut self, line: &str) -> Option<Value> {
        if writeln!(self.input, "{line}").is_err() {
            return None;
        }
        let mut reply = String::new();
        match self.output.read_line(&mut reply) {
            Ok(n) if n > 0 => Some(serde_json::from_str(&reply).unwrap()),
            _ => None,
        }
    }

    fn kill(mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }

    fn finish(mut self) {
        drop(self.input);
        assert!(self.child.wait().unwrap().success());
    }
}

/// Drives a whole session over one server process: the final reply.
fn run_session(
    world: &PolygonWorld,
    start: Point,
    strategy: &str,
    journal: &Path,
) -> (Value, Vec<Point>) {
    run_session_with(world, start, strategy, &["--journal", journal.to_str().unwrap()])
}

/// [`run_session`] with the server's arguments.
fn run_session_with(
    world: &PolygonWorld,
    start: Point,
    strategy: &str,
    args: &[&str],
) -> (Value, Vec<Point>) {
    let mut server = Server::spawn(args);
    let mut client = client(world, start, strategy, 7);
    let mut line = client.start();
    loop {
        let reply = server.ask(&line).expect("the server answers");
        let Some(next) = client.answer(&reply).unwrap() else {
            server.finish();
            return (reply, client.truth);
        };
        line = next;
    }
}

#[test]
fn a_simulated_robot_explores_an_office_over_standard_input() {
    let (world, start) = office();
    let dir = temp("serve-stdio");
    std::fs::create_dir_all(&dir).unwrap();
    for strategy in ["cost_aware", "explore_lite"] {
        let journal = dir.join(format!("{strategy}.jsonl"));
        let (done, truth) = run_session(&world, start, strategy, &journal);
        assert_eq!(done["type"], "done", "{done}");
        assert_eq!(done["reason"], "explored", "{done}");
        let summary = &done["summary"];
        assert_eq!(summary["strategy"], strategy);
        assert_eq!(summary["scans"].as_u64().unwrap() as usize, truth.len());
        // The time is the cost model's price of the tally it reports.
        let expect =
            30.0 * summary["scans"].as_f64().unwrap() + summary["distance"].as_f64().unwrap() / 0.5;
        assert!((summary["time"].as_f64().unwrap() - expect).abs() < 1e-6, "{summary}");
        let share = seen_share(world.domain(), &truth, f64::INFINITY, 0.25);
        assert!(share > 0.97, "{strategy}: {share} of the free space seen");
        // The journal: a header, then one line per step, each request with its reply.
        let text = std::fs::read_to_string(&journal).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        let header: Value = serde_json::from_str(lines[0]).unwrap();
        assert_eq!(header["format"], "stopscan-journal/1");
        assert_eq!(lines.len() as u64 - 1, done["seq"].as_u64().unwrap() + 1);
        let last: Value = serde_json::from_str(lines[lines.len() - 1]).unwrap();
        assert_eq!(last["reply"], done);
    }
    check_schema(&[dir.join("cost_aware.jsonl"), dir.join("explore_lite.jsonl")]);
}

/// `serve --mcap`: the session recorded for Foxglove, read back by an independent reader and
/// counted against the journal; a resumed session's recording is the same file, byte for
/// byte.
#[test]
fn a_session_is_recorded_for_foxglove() {
    let (world, start) = office();
    let dir = temp("serve-mcap");
    std::fs::create_dir_all(&dir).unwrap();
    let (journal, mcap) = (dir.join("j.jsonl"), dir.join("live.mcap"));
    let args = ["--journal", journal.to_str().unwrap(), "--mcap", mcap.to_str().unwrap()];
    let (done, _) = run_session_with(&world, start, "cost_aware", &args);
    assert_eq!(done["type"], "done", "{done}");
    // After the fact, from the journal alone.
    let again = dir.join("resumed.mcap");
    let out = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(["serve", "--resume", journal.to_str().unwrap(), "--mcap", again.to_str().unwrap()])
        .stdin(Stdio::null())
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert_eq!(std::fs::read(&mcap).unwrap(), std::fs::read(&again).unwrap());
    let Some(v) = read_mcap(&mcap) else { return };
    // Counted from the journal: one log line per step, a transform per reported pose and per
    // localised scan, a laser scan per scan sent, a goal per goal replied.
    let text = std::fs::read_to_string(&journal).unwrap();
    let steps: Vec<Value> =
        text.lines().skip(1).map(|l| serde_json::from_str(l).unwrap()).collect();
    let scans = steps.iter().filter(|s| s["request"]["scan"].is_object()).count() as u64;
    let localised = steps.iter().filter(|s| s["reply"]["localised"].is_object()).count() as u64;
    let goals = steps.iter().filter(|s| s["reply"]["type"] == "goal").count() as u64;
    assert!(scans > 5 && goals > 5);
    assert_eq!(mcap_count(&v, "/log"), steps.len() as u64);
    assert_eq!(mcap_count(&v, "/lidar"), scans);
    assert_eq!(mcap_count(&v, "/goal"), goals);
    assert_eq!(mcap_count(&v, "/tf"), steps.len() as u64 + localised);
    for (t, schema) in [
        ("/log", "foxglove.Log"),
        ("/lidar", "foxglove.LaserScan"),
        ("/goal", "foxglove.PosesInFrame"),
        ("/tf", "foxglove.FrameTransform"),
    ] {
        assert_eq!(mcap_topic(&v, t)["schema"], schema);
    }
    // The clock: scans cost 30 s each and travel 2 s a metre, so the last step's time is at
    // least the scans' time, and time never goes back.
    let times: Vec<u64> = mcap_topic(&v, "/log")["log_times"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_u64().unwrap())
        .collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]));
    assert!(*times.last().unwrap() as f64 >= 30e9 * (scans - 1) as f64);
    let end = mcap_topic(&v, "/log")["messages"].as_array().unwrap().last().unwrap().clone();
    assert!(end["message"].as_str().unwrap().contains("done (explored)"), "{end}");
}

/// Every request and reply of the journals matches docs/protocol.schema.json, checked by an
/// independent validator (Python's jsonschema, which .ci/run installs).
fn check_schema(journals: &[std::path::PathBuf]) {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/check_protocol_schema.py");
    let has = Command::new("python3").args(["-c", "import jsonschema"]).output();
    if !has.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: the schema check needs python3 with jsonschema (.ci/run installs it)");
        return;
    }
    let out = Command::new("python3").arg(script).args(journals).output().unwrap();
    assert!(
        out.status.success(),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn kill_9_at_random_moments_then_resume_ends_byte_identical() {
    let (world, start) = office();
    let dir = temp("serve-crash");
    std::fs::create_dir_all(&dir).unwrap();
    let clean = dir.join("clean.jsonl");
    let (done, _) = run_session(&world, start, "nearest_frontier", &clean);
    let steps = done["seq"].as_u64().unwrap();

    let journal = dir.join("crashed.jsonl");
    let j = journal.to_str().unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut server = Server::spawn(&["--journal", j]);
    let mut client = client(&world, start, "nearest_frontier", 7);
    let mut line = client.start();
    let mut kills = 0;
    let last = loop {
        // Now and then, kill the server while it reads, works or writes.
        if kills < 12 && rng.random_bool(6.0 / steps as f64) {
            writeln!(server.input, "{line}").unwrap();
            std::thread::sleep(std::time::Duration::from_micros(rng.random_range(0..3000)));
            server.kill();
            kills += 1;
            server = Server::spawn(&["--resume", j]);
        }
        // A robot that gets no reply sends the same request again, to a resumed server.
        let Some(reply) = server.ask(&line) else {
            server.kill();
            server = Server::spawn(&["--resume", j]);
            continue;
        };
        match client.answer(&reply).unwrap() {
            Some(next) => line = next,
            None => break reply,
        }
    };
    server.finish();
    assert!(kills >= 3, "only {kills} kills");
    assert_eq!(last, done);
    assert_eq!(std::fs::read(&journal).unwrap(), std::fs::read(&clean).unwrap());
}

/// Georeferenced odometry: a session whose every reported pose is moved by UTM-sized offsets
/// gets the same replies, moved by the same offsets. The simulated robot's poses are rounded
/// to 2⁻²⁰ m so that both sessions' poses are exact, and the offsets are whole multiples of
/// the 1,024 m grid the server's local frame is rounded to; the server then computes the same
/// numbers in both, and only the output's rounding differs. (Computed in place, the
/// strategies' tolerances grew with the coordinates: this session once ended as "explored"
/// after its first scan at x = 5e6.)
#[test]
fn odometry_far_from_its_origin_gets_the_same_goals_moved() {
    let (world, start) = office();
    // Whole multiples of the local frame's 1,024 m grid: the two sessions compute the same.
    let shift = [4_500_480.0, -5_300_224.0];
    let xy = |v: &Value, k: usize| v[["x", "y"][k]].as_f64().unwrap();
    let (mut near, mut far) = (Server::spawn(&[]), Server::spawn(&[]));
    let mut client = client(&world, start, "cost_aware", 7);
    let mut line = client.start();
    let mut goals = 0;
    loop {
        let mut request: Value = serde_json::from_str(&line).unwrap();
        let seq = request["seq"].clone();
        let grid = f64::from(1 << 20);
        for k in 0..2 {
            let v = (xy(&request["pose"], k) * grid).round() / grid;
            request["pose"][["x", "y"][k]] = json!(v);
        }
        let want = near.ask(&request.to_string()).unwrap();
        for (k, d) in shift.iter().enumerate() {
            let v = xy(&request["pose"], k) + d;
            request["pose"][["x", "y"][k]] = json!(v);
        }
        let got = far.ask(&request.to_string()).unwrap();
        assert_eq!(got["type"], want["type"], "step {seq}: {got} against {want}");
        let mut poses = vec!["goal", "map_goal"];
        if !want["localised"].is_null() {
            poses.push("localised.pose");
            assert_eq!(got["localised"]["placement_sd"], want["localised"]["placement_sd"]);
            if !want["localised"]["alignment"].is_null() {
                poses.extend(["localised.alignment.guess", "localised.alignment.pose"]);
            }
        }
        for path in poses {
            let (g, w) = path.split('.').fold((&got, &want), |(g, w), key| (&g[key], &w[key]));
            if w.is_null() {
                continue;
            }
            goals += usize::from(path == "goal");
            for (k, s) in shift.iter().enumerate() {
                let d = xy(g, k) - s - xy(w, k);
                assert!(d.abs() < 1e-8, "step {seq}: {path} off by {d}");
            }
            // Headings on the circle (a goal straight behind is at ±π); a goal's is computed
            // from where the robot stands, which the far odometry holds to 1e-9 m.
            let dt = g["theta"].as_f64().unwrap() - w["theta"].as_f64().unwrap();
            let dt = dt.sin().atan2(dt.cos());
            assert!(dt.abs() < 1e-8, "step {seq}: {path} heading off by {dt}");
        }
        let Some(next) = client.answer(&want).unwrap() else {
            assert_eq!(want["reason"], "explored", "{want}");
            assert_eq!(got["summary"]["scans"], want["summary"]["scans"]);
            break;
        };
        line = next;
    }
    near.finish();
    far.finish();
    assert!(goals > 10, "{goals} goals compared");
}

#[test]
fn the_same_session_over_tcp() {
    let (world, start) = office();
    let mut child = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(["serve", "--listen", "127.0.0.1:0"])
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut err = BufReader::new(child.stderr.take().unwrap());
    let mut first = String::new();
    err.read_line(&mut first).unwrap();
    let addr = first.trim().strip_prefix("listening on ").expect(&first).to_string();
    let connect = || {
        let s = std::net::TcpStream::connect(&addr).unwrap();
        (BufReader::new(s.try_clone().unwrap()), s)
    };
    let (mut reader, mut writer) = connect();
    let mut client = client(&world, start, "depth_first", 3);
    let mut line = client.start();
    let mut reconnected = false;
    loop {
        writeln!(writer, "{line}").unwrap();
        let mut reply = String::new();
        reader.read_line(&mut reply).unwrap();
        let reply: Value = serde_json::from_str(&reply).unwrap();
        // Halfway, connect again while the old connection still looks open (a half-open
        // socket after a lost link): the new one takes over and the session goes on.
        if !reconnected && reply["seq"] == 20 {
            let old = (reader, writer);
            (reader, writer) = connect();
            let mut stale = old.0;
            let mut rest = String::new();
            // The server shut the old connection down.
            assert_eq!(stale.read_line(&mut rest).unwrap_or(0), 0, "{rest}");
            reconnected = true;
            // The last request again, on the new connection: the same reply, not a new step.
            writeln!(writer, "{line}").unwrap();
            let mut again = String::new();
            reader.read_line(&mut again).unwrap();
            assert_eq!(serde_json::from_str::<Value>(&again).unwrap(), reply);
        }
        let Some(next) = client.answer(&reply).unwrap() else {
            assert_eq!(reply["reason"], "explored", "{reply}");
            break;
        };
        line = next;
    }
    drop((reader, writer));
    assert!(child.wait().unwrap().success(), "the server exits once the session is over");
    assert!(reconnected);
}

/// Every malformed message gets an error reply naming the field, and leaves the session as
/// it was: the well-formed session that follows runs as if they had not been sent.
#[test]
fn malformed_messages_get_errors_that_name_the_field() {
    let mut server = Server::spawn(&[]);
    let start = json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0.0, "y": 0.0, "theta": 0.0}});
    let cases: Vec<(String, Option<&str>, &str)> = vec![
        ("{not json".into(), None, "not valid JSON"),
        ("[1, 2]".into(), None, "not a JSON object"),
        (json!({"type": "start"}).to_string(), Some("seq"), "missing"),
        (json!({"seq": -1, "type": "start"}).to_string(), Some("seq"), "integer"),
        (json!({"seq": 0}).to_string(), Some("type"), "missing"),
        (json!({"seq": 0, "type": 7}).to_string(), Some("type"), "string"),
        (json!({"seq": 0, "type": "warp"}).to_string(), Some("type"), "unknown message type"),
        (json!({"seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), Some("protocol"), "missing"),
        (json!({"protocol": "stopscan/9", "seq": 0, "type": "start"}).to_string(), Some("protocol"), "stopscan/1"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start"}).to_string(), Some("pose"), "missing field"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": "a", "y": 0, "theta": 0}}).to_string(), Some("pose.x"), "invalid type"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 1e308, "theta": 0}}).to_string(), Some("pose.y"), "within ±1000000000 m"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "speed": 2}).to_string(), Some("speed"), "unknown field"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "strategy": "warp"}).to_string(), Some("strategy"), "unknown strategy"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "cost": {"scan_time": -1, "speed": 1}}).to_string(), Some("cost"), "scan_time"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "robot": {"radius": -0.2}}).to_string(), Some("robot.radius"), "radius"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "family": "corner"}).to_string(), Some("corner"), "distance"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "relay": -0.1}).to_string(), Some("relay"), "finite number >= 0"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "relay": "on"}).to_string(), Some("relay"), "invalid type"),
        (json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "pose": {"x": 0, "y": 0, "theta": 0}, "family": "corner", "corner": {"distance": 2}, "relay": 0.05}).to_string(), Some("relay"), "polygon"),
        (json!({"seq": 0, "type": "arrived", "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), Some("type"), "expected \"start\""),
        (json!({"seq": 3, "type": "arrived", "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), Some("seq"), "expected 0"),
    ];
    expect_errors(&mut server, &cases);
    // Now the start, then out-of-order and malformed scans.
    let reply = server.ask(&start.to_string()).unwrap();
    assert_eq!(reply["type"], "scan", "{reply}");
    let scan = |ranges: Value, extra: Value| {
        let mut m = json!({"seq": 1, "type": "scan", "pose": {"x": 0.0, "y": 0.0, "theta": 0.0},
            "scan": {"angle_min": -3.0, "angle_increment": 0.0175, "range_min": 0.05, "range_max": 20.0, "ranges": ranges}});
        for (k, v) in extra.as_object().unwrap() {
            m["scan"][k] = v.clone();
        }
        m.to_string()
    };
    let cases: Vec<(String, &str, &str)> = vec![
        (json!({"seq": 1, "type": "arrived", "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), "type", "expected \"scan\""),
        (json!({"seq": 1, "type": "scan", "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), "scan", "missing"),
        (json!({"seq": 1, "type": "scan", "robot": 1, "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), "robot", "roi family"),
        (json!({"seq": 1, "type": "scan", "time": 1.0, "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(), "time", "roi family"),
        (scan(json!([1.0, "x", 2.0]), json!({})), "scan.ranges", "range 1 is"),
        (scan(json!([1.0, 1.0, 1.0]), json!({"angle_increment": 0.0})), "scan.angle_increment", "zero"),
        (scan(json!([1.0, 1.0, 1.0]), json!({"range_max": 0.01})), "scan.range_max", ""),
        (scan(json!(vec![Value::Null; 360]), json!({})), "scan", "valid"),
        (json!({"seq": 0, "type": "start", "protocol": "stopscan/1", "pose": {"x": 1, "y": 0, "theta": 0}}).to_string(), "seq", "different request"),
    ];
    expect_errors(&mut server, &cases);
    // The start sent again is answered again, the same way.
    assert_eq!(server.ask(&start.to_string()).unwrap(), reply);
    // A clear scan of an empty disc: explored at once.
    let ok = server
        .ask(&scan(
            json!(vec![5.0; 360]),
            json!({"angle_increment": std::f64::consts::TAU / 360.0}),
        ))
        .unwrap();
    assert_eq!(ok["type"], "done", "{ok}");
    assert_eq!(ok["localised"]["pose"]["x"], 0.0);
    let after = server
        .ask(
            &json!({"seq": 2, "type": "arrived", "pose": {"x": 0, "y": 0, "theta": 0}}).to_string(),
        )
        .unwrap();
    assert!(after["message"].as_str().unwrap().contains("the session is over"), "{after}");
    server.finish();
}

#[test]
fn a_corner_search_ends_when_the_robot_finds_the_target() {
    let dir = temp("serve-corner");
    std::fs::create_dir_all(&dir).unwrap();
    let journal = dir.join("corner.jsonl");
    let mut server = Server::spawn(&["--journal", journal.to_str().unwrap()]);
    let start = json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "family": "corner",
        "strategy": "unirec", "pose": {"x": 1.0, "y": 2.0, "theta": 0.5},
        "cost": {"scan_time": 2.0, "speed": 0.5}, "corner": {"distance": 10.0}});
    let goal = server.ask(&start.to_string()).unwrap();
    assert_eq!(goal["type"], "goal", "{goal}");
    // UNIREC's first stop is at δ = τv/D = 0.1 rad on the circle through the robot and the
    // corner, in the corner frame (robot at the origin facing the corner at (D, 0)).
    let stop = &goal["stop"];
    assert!((stop["angle"].as_f64().unwrap() - 0.1).abs() < 1e-12, "{goal}");
    let (s, c) = 0.1f64.sin_cos();
    let map = &goal["map_goal"];
    assert!((map["x"].as_f64().unwrap() - 10.0 * s * s).abs() < 1e-9);
    assert!((map["y"].as_f64().unwrap() - 10.0 * s * c).abs() < 1e-9);
    // In the robot's frame: the start pose applied to the corner frame's point.
    let g = &goal["goal"];
    let (x, y) = (10.0 * s * s, 10.0 * s * c);
    let (sn, cs) = 0.5f64.sin_cos();
    assert!((g["x"].as_f64().unwrap() - (1.0 + cs * x - sn * y)).abs() < 1e-9, "{goal}");
    assert!((g["y"].as_f64().unwrap() - (2.0 + sn * x + cs * y)).abs() < 1e-9, "{goal}");
    let pose = g.clone();
    let scan = server.ask(&json!({"seq": 1, "type": "arrived", "pose": pose}).to_string()).unwrap();
    assert_eq!(scan["type"], "scan");
    let next = server
        .ask(&json!({"seq": 2, "type": "scan", "pose": pose, "edge": null}).to_string())
        .unwrap();
    assert_eq!(next["type"], "goal");
    let done = server.ask(&json!({"seq": 3, "type": "found", "pose": pose}).to_string()).unwrap();
    assert_eq!(done["type"], "done");
    assert_eq!(done["reason"], "found");
    assert_eq!(done["summary"]["scans"], 1);
    assert_eq!(done["summary"]["strategy"], "unirec");
    server.finish();
    check_schema(&[journal]);
}

/// A region of `n` cells grown at random from `[0, 0]` (4-connected, with the holes and
/// cycles growth leaves).
fn blob(n: usize, seed: u64) -> Vec<[i32; 2]> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut cells = vec![[0, 0]];
    while cells.len() < n {
        let c = cells[rng.random_range(0..cells.len())];
        let d = [[-1, 0], [0, 1], [1, 0], [0, -1]][rng.random_range(0..4)];
        let next = [c[0] + d[0], c[1] + d[1]];
        if !cells.contains(&next) {
            cells.push(next);
        }
    }
    cells.sort_unstable();
    cells
}

/// How a team is flown in [`ground_station`].
struct Flight {
    robots: usize,
    cell_size: f64,
    speed: f64,
    scan_time: f64,
    /// The region's speed and heading (degrees).
    drift: (f64, f64),
    start: [f64; 3],
    /// Each leg and scan takes up to this share longer, at random.
    jitter: f64,
    /// The chance that a goal fails (the robot stays over the cell it left).
    fail: f64,
    seed: u64,
}

/// What a team's session did, as the ground station saw it.
struct Flown {
    done: Value,
    visited: std::collections::BTreeSet<[i32; 2]>,
    scans: u64,
    ends: Vec<[i32; 2]>,
    last_time: f64,
}

/// Checks a goal order for a robot over `from` that leaves at `t`, and returns its arrival
/// time: the leg in the region's frame flown at `speed` against the drift, and the goal the
/// cell's centre moved by the drift until then, in the odometry frame of the start pose.
fn goal_eta(o: &Value, f: &Flight, from: [i32; 2], t: f64) -> f64 {
    let (h, vp) = (f.drift.1.to_radians(), f.drift.0);
    let cell = [o["cell"][0].as_i64().unwrap() as i32, o["cell"][1].as_i64().unwrap() as i32];
    let dx = f64::from(cell[1] - from[1]) * f.cell_size;
    let dy = -f64::from(cell[0] - from[0]) * f.cell_size;
    let len = dx.hypot(dy);
    let a = vp * (h.cos() * dx + h.sin() * dy) / len;
    let rel = -a + (a * a + f.speed * f.speed - vp * vp).sqrt();
    let eta = t + len / rel;
    assert!((o["eta"].as_f64().unwrap() - eta).abs() < 1e-6 * eta.max(1.0), "{o}");
    let (x, y) = (
        f64::from(cell[1]) * f.cell_size + vp * eta * h.cos(),
        -f64::from(cell[0]) * f.cell_size + vp * eta * h.sin(),
    );
    let (s, c) = f.start[2].sin_cos();
    let g = &o["goal"];
    assert!((g["x"].as_f64().unwrap() - (f.start[0] + c * x - s * y)).abs() < 1e-6, "{o}");
    assert!((g["y"].as_f64().unwrap() - (f.start[1] + s * x + c * y)).abs() < 1e-6, "{o}");
    eta
}

/// Sends each line and checks that the reply is an error naming `field` (`None`: no field)
/// with `needle` in its message.
fn expect_errors<'a, F: Into<Option<&'a str>> + Copy>(
    server: &mut Server,
    cases: &[(String, F, &str)],
) {
    for (line, field, needle) in cases {
        let reply = server.ask(line).expect("the server answers");
        assert_eq!(reply["type"], "error", "{line}: {reply}");
        assert_eq!(reply["field"].as_str(), (*field).into(), "{line}: {reply}");
        assert!(reply["message"].as_str().unwrap().contains(needle), "{line}: {reply}");
    }
}

/// A ground station written from docs/protocol.md alone: it passes each robot its orders and
/// reports for them in the order their orders finish on its own clock. The robots fly straight
/// at `speed` relative to the drifting region (so a leg of `d` metres takes the time the
/// drift allows), and a scan reports the truth of the cell and its neighbours.
fn ground_station(region: &[[i32; 2]], f: &Flight, server: &mut Server) -> Flown {
    let truth: std::collections::HashSet<[i32; 2]> = region.iter().copied().collect();
    let mut rng = ChaCha8Rng::seed_from_u64(f.seed);
    let n = f.robots;
    let start = json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "family": "roi",
        "pose": {"x": f.start[0], "y": f.start[1], "theta": f.start[2]},
        "cost": {"scan_time": f.scan_time, "speed": f.speed},
        "roi": {"robots": n, "cell_size": f.cell_size,
                "drift": {"speed": f.drift.0, "heading_deg": f.drift.1}}});
    // Per robot: its cell, its order out (kind, target cell, when it finishes).
    let mut at = vec![[0, 0]; n];
    let mut out: Vec<Option<(String, [i32; 2], f64)>> = vec![None; n];
    let mut clock = vec![0.0f64; n];
    let mut ends = vec![[i32::MAX, i32::MAX]; n];
    let mut visited: std::collections::BTreeSet<[i32; 2]> = [[0, 0]].into();
    let (mut scans, mut seq, mut last_time) = (0u64, 0u64, 0.0f64);
    let mut reply = server.ask(&start.to_string()).expect("the server answers");
    loop {
        if reply["type"] == "done" {
            // Done for the whole team: every robot ends where it stands.
            for (e, a) in ends.iter_mut().zip(&at) {
                if e[0] == i32::MAX {
                    *e = *a;
                }
            }
            return Flown { done: reply, visited, scans, ends, last_time };
        }
        assert_eq!(reply["type"], "orders", "{reply}");
        for o in reply["orders"].as_array().unwrap() {
            let i = o["robot"].as_u64().unwrap() as usize;
            let cell =
                [o["cell"][0].as_i64().unwrap() as i32, o["cell"][1].as_i64().unwrap() as i32];
            let kind = o["type"].as_str().unwrap().to_string();
            let stretch = 1.0 + f.jitter * rng.random::<f64>();
            // Robots sent off together leave together, when the last of them has reported:
            // the report just answered, the latest so far (reports go in time order).
            let t = clock[i].max(last_time);
            let finish = match kind.as_str() {
                "scan" => {
                    assert_eq!(cell, at[i], "a scan where the robot stands");
                    t + f.scan_time * stretch
                }
                "goal" => t + (goal_eta(o, f, at[i], t) - t) * stretch,
                "done" => {
                    ends[i] = at[i];
                    continue;
                }
                other => panic!("unknown order {other}"),
            };
            assert!(out[i].is_none(), "robot {i} got a second order while one is out");
            out[i] = Some((kind, cell, finish));
        }
        // The next report: the order that finishes first (the lowest robot among equals).
        let i = (0..n)
            .filter(|&i| out[i].is_some())
            .min_by(|&a, &b| {
                let (ta, tb) = (out[a].as_ref().unwrap().2, out[b].as_ref().unwrap().2);
                ta.total_cmp(&tb).then(a.cmp(&b))
            })
            .expect("a team that is not done has an order out");
        let (kind, cell, finish) = out[i].take().unwrap();
        clock[i] = finish;
        last_time = last_time.max(finish);
        seq += 1;
        let pose = json!({"x": 0.0, "y": 0.0, "theta": 0.0});
        let request = match kind.as_str() {
            "scan" => {
                scans += 1;
                let is = |c: [i32; 2]| truth.contains(&c);
                let [r, k] = at[i];
                let frame = json!({"centre": is([r, k]),
                    "sides": [is([r - 1, k]), is([r, k + 1]), is([r + 1, k]), is([r, k - 1])]});
                json!({"seq": seq, "type": "scan", "robot": i, "time": finish, "pose": pose,
                    "frames": [frame]})
            }
            _ if rng.random::<f64>() < f.fail => json!({"seq": seq, "type": "move_failed",
                "robot": i, "time": finish, "pose": pose, "reason": "blocked"}),
            _ => {
                at[i] = cell;
                visited.insert(cell);
                json!({"seq": seq, "type": "arrived", "robot": i, "time": finish, "pose": pose})
            }
        };
        reply = server.ask(&request.to_string()).expect("the server answers");
    }
}

#[test]
fn a_team_maps_a_drifting_region_through_one_ground_station() {
    let dir = temp("serve-team");
    std::fs::create_dir_all(&dir).unwrap();
    let region = blob(70, 3);
    let mut journals = Vec::new();
    for (k, (robots, jitter, drift)) in
        [(1, 0.0, (0.0, 0.0)), (3, 0.0, (0.3, 30.0)), (4, 0.5, (0.3, 30.0)), (5, 0.8, (0.0, 0.0))]
            .into_iter()
            .enumerate()
    {
        let journal = dir.join(format!("team-{k}.jsonl"));
        let mut server = Server::spawn(&["--journal", journal.to_str().unwrap()]);
        let flight = Flight {
            robots,
            cell_size: 2.0,
            speed: 1.0,
            scan_time: 3.0,
            drift,
            start: [5.0, -3.0, 0.4],
            jitter,
            fail: 0.0,
            seed: k as u64,
        };
        let flown = ground_station(&region, &flight, &mut server);
        server.finish();
        let done = &flown.done;
        let case = format!("{robots} robots, jitter {jitter}, drift {drift:?}");
        assert_eq!(done["reason"], "explored", "{case}: {done}");
        // Algorithm 1 stands on every cell of a connected region, and the team comes home.
        let all: std::collections::BTreeSet<[i32; 2]> = region.iter().copied().collect();
        assert!(flown.visited.is_superset(&all), "{case}: cells never visited");
        assert!(flown.ends.iter().all(|&e| e == [0, 0]), "{case}: {:?}", flown.ends);
        let team = &done["summary"]["team"];
        assert_eq!(team["robots"], robots);
        assert_eq!(team["cells_visited"].as_u64().unwrap() as usize, flown.visited.len());
        // An exact camera: the map is the region.
        let map: Vec<[i32; 2]> = serde_json::from_value(team["map"].clone()).unwrap();
        assert_eq!(map, region, "{case}");
        assert_eq!(done["summary"]["scans"].as_u64().unwrap(), flown.scans, "{case}");
        let time = done["summary"]["time"].as_f64().unwrap();
        assert!((time - flown.last_time).abs() < 1e-9, "{case}: {time} vs {}", flown.last_time);
        if jitter == 0.0 {
            // Robots that fly exactly as the time model says do what the simulator's do.
            let roi = GridRoi::new("blob", region.iter().copied(), [0, 0], 2.0).unwrap();
            let drift = Drift { speed: drift.0, heading_deg: drift.1 };
            let mut world = GridWorld::new(roi, drift, GridSensor::Ideal, 1);
            let cost = CostModel::new(3.0, 0.0, 1.0).unwrap();
            let sim =
                stopscan::sim::grid::explore(&mut world, robots, cost, Recording::NONE).unwrap();
            assert_eq!(sim.team.tally().scans, flown.scans, "{case}");
            assert!((sim.team.makespan() - time).abs() < 1e-6, "{case}: {time}");
        }
        journals.push(journal);
    }
    // Goals that fail: the child is dropped, a way back up is flown again, and the team
    // still ends, at home, with a map of region cells only.
    for seed in 0..4 {
        let mut server = Server::spawn(&[]);
        let flight = Flight {
            robots: 3,
            cell_size: 1.0,
            speed: 2.0,
            scan_time: 1.0,
            drift: (0.0, 0.0),
            start: [0.0, 0.0, 0.0],
            jitter: 0.3,
            fail: 0.15,
            seed,
        };
        let flown = ground_station(&region, &flight, &mut server);
        server.finish();
        let done = &flown.done;
        let reason = done["reason"].as_str().unwrap();
        assert!(reason == "explored" || reason == "stuck", "seed {seed}: {done}");
        let map: Vec<[i32; 2]> =
            serde_json::from_value(done["summary"]["team"]["map"].clone()).unwrap();
        assert!(map.iter().all(|c| region.contains(c)), "seed {seed}");
        if reason == "explored" {
            assert!(flown.ends.iter().all(|&e| e == [0, 0]), "seed {seed}: {:?}", flown.ends);
        }
    }
    check_schema(&journals);
}

#[test]
fn a_team_session_refuses_what_it_cannot_take() {
    let mut server = Server::spawn(&[]);
    let pose = json!({"x": 0.0, "y": 0.0, "theta": 0.0});
    let start = |extra: Value| {
        let mut m = json!({"protocol": "stopscan/1", "seq": 0, "type": "start", "family": "roi",
            "pose": pose, "cost": {"scan_time": 2.0, "speed": 1.0}});
        for (k, v) in extra.as_object().unwrap() {
            m[k] = v.clone();
        }
        m.to_string()
    };
    let cases: Vec<(String, &str, &str)> = vec![
        (start(json!({})), "roi", "missing"),
        (start(json!({"roi": {"robots": 0}})), "roi.robots", "1 to 1024"),
        (start(json!({"roi": {"robots": 2, "cell_size": 0}})), "roi.cell_size", "above 0"),
        (start(json!({"roi": {"robots": 2, "cell_size": 1e308}})), "roi.cell_size", "at most"),
        (start(json!({"roi": {"robots": 2, "drift": {"speed": 1.5}}})), "cost.speed", "faster"),
        (
            start(json!({"roi": {"robots": 2, "drift": {"sped": 0.5}}})),
            "roi.drift.sped",
            "unknown field",
        ),
        (
            start(json!({"roi": {"robots": 2, "search": {"min": [3, 0], "max": [0, 5]}}})),
            "roi.search",
            "min",
        ),
        (start(json!({"roi": {"robots": 2}, "robot": {"radius": 0.2}})), "robot", "polygon family"),
        (
            start(json!({"roi": {"robots": 2}, "strategy": "depth_first"})),
            "strategy",
            "recursive_dfs",
        ),
        (start(json!({"family": "polygon", "roi": {"robots": 2}})), "roi", "roi family"),
    ];
    expect_errors(&mut server, &cases);
    let first = server
        .ask(&start(json!({"roi": {"robots": 2, "drift": {"speed": 0.2, "heading_deg": 90}}})))
        .unwrap();
    assert_eq!(first["type"], "orders", "{first}");
    let orders = first["orders"].as_array().unwrap();
    assert_eq!(orders.len(), 2, "{first}");
    assert!(orders.iter().all(|o| o["type"] == "scan" && o["cell"] == json!([0, 0])), "{first}");
    let frame = json!({"centre": true, "sides": [false, true, false, false]});
    let scan = |seq: u64, extra: Value| {
        let mut m = json!({"seq": seq, "type": "scan", "pose": pose});
        for (k, v) in extra.as_object().unwrap() {
            m[k] = v.clone();
        }
        m.to_string()
    };
    let cases: Vec<(String, &str, &str)> = vec![
        (
            json!({"seq": 1, "type": "arrived", "robot": 0, "time": 1.0, "pose": pose}).to_string(),
            "type",
            "robot 0: expected \"scan\"",
        ),
        (scan(1, json!({"frames": [frame]})), "robot", "missing"),
        (scan(1, json!({"robot": 5, "time": 1.0, "frames": [frame]})), "robot", "robots 0 to 1"),
        (scan(1, json!({"robot": 0, "frames": [frame]})), "time", "drifting"),
        (scan(1, json!({"robot": 0, "time": -1.0, "frames": [frame]})), "time", "between 0 and"),
        (scan(1, json!({"robot": 0, "time": 2e9, "frames": [frame]})), "time", "between 0 and"),
        (scan(1, json!({"robot": 0, "time": 2.0})), "frames", "missing"),
        (scan(1, json!({"robot": 0, "time": 2.0, "frames": []})), "frames", "1 to 99"),
        (
            scan(
                1,
                json!({"robot": 0, "time": 2.0, "frames": [{"centre": true, "sides": [true]}]}),
            ),
            "frames[0].sides",
            "",
        ),
        (
            scan(1, json!({"robot": 0, "time": 2.0, "frames": [frame], "edge": 0.3})),
            "edge",
            "corner family",
        ),
    ];
    expect_errors(&mut server, &cases);
    // Robot 0's scan: it waits for robot 1, scanning with it.
    let wait = server.ask(&scan(1, json!({"robot": 0, "time": 2.0, "frames": [frame]}))).unwrap();
    assert_eq!(wait, json!({"protocol": "stopscan/1", "seq": 1, "type": "orders", "orders": []}));
    let again = server.ask(&scan(2, json!({"robot": 0, "time": 2.5, "frames": [frame]}))).unwrap();
    assert!(again["message"].as_str().unwrap().contains("waits"), "{again}");
    let back = server.ask(&scan(2, json!({"robot": 1, "time": 1.0, "frames": [frame]}))).unwrap();
    assert_eq!(back["type"], "orders", "{back}");
    // Both go east together, the only neighbour seen; robot 1 says the drift moved it.
    let orders = back["orders"].as_array().unwrap();
    assert_eq!(orders.len(), 2, "{back}");
    for o in orders {
        assert_eq!(o["type"], "goal", "{back}");
        assert_eq!(o["cell"], json!([0, 1]), "{back}");
    }
    let stop = server
        .ask(&json!({"seq": 3, "type": "stop", "robot": 1, "time": 3.0, "pose": pose}).to_string())
        .unwrap();
    assert_eq!(stop["reason"], "stopped", "{stop}");
    assert_eq!(stop["summary"]["team"]["map"], json!([[0, 0], [0, 1]]), "{stop}");
    server.finish();
}
