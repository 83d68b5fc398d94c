//! `stopscan roi`: missions, their state files, resume and the field pipeline.

use crate::common;

use std::path::PathBuf;
use std::process::Command;

use serde_json::Value;

use common::{assert_no_temporary_files, f, json, stopscan, temp};

/// `stopscan roi` on a text grid: every cell visited, everyone home, within Lemma 1, and a
/// replay with one animated robot per robot.
#[test]
fn roi_explores_a_grid_and_writes_record_and_replay() {
    let dir = temp("roi");
    std::fs::create_dir_all(&dir).unwrap();
    let grid = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/roi/lake.txt");
    let out = dir.join("lake.json");
    let trace = dir.join("lake.jsonl");
    let r = json(&[
        "roi",
        "--grid",
        grid.to_str().unwrap(),
        "--robots",
        "3",
        "--roi-speed",
        "0.25",
        "--roi-heading-deg",
        "90",
        "--out",
        out.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let events: Vec<Value> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let moves = events.iter().filter(|e| e["event"] == "move").count() as u64;
    assert_eq!(moves, r["metrics"]["moves"].as_u64().unwrap());
    assert_eq!(events.last().unwrap()["event"], "finish");
    assert!(events.iter().filter(|e| e["event"] != "finish").all(|e| e["robot"].is_u64()));
    assert_eq!(r["cells"], 53);
    assert_eq!(r["metrics"]["visited_cells"], 53);
    assert_eq!(r["metrics"]["all_home"], true);
    assert_eq!(r["bounds"]["within_lemma1"], true);
    assert!(f(&r["metrics"], "time") <= f(&r["bounds"], "lemma1_upper"));
    assert_eq!(r["robots"].as_array().unwrap().len(), 3);
    for robot in r["robots"].as_array().unwrap() {
        let cells = robot["cells"].as_array().unwrap();
        assert_eq!(cells.first(), cells.last(), "robot returns to the start");
        assert_eq!(cells.len(), robot["times"].as_array().unwrap().len());
    }
    let on_disk: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(on_disk, r);
    let svg = std::fs::read_to_string(dir.join("lake.svg")).unwrap();
    assert_eq!(svg.matches("<animateMotion").count(), 3);
}

#[test]
fn roi_random_runs_are_seeded() {
    let dir = temp("roi-seed");
    std::fs::create_dir_all(&dir).unwrap();
    let run = |seed: &str, name: &str| {
        let p = dir.join(name);
        let o = stopscan(&[
            "roi",
            "--random",
            "150",
            "--robots",
            "4",
            "--seed",
            seed,
            "--out",
            p.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(p).unwrap()
    };
    assert_eq!(run("7", "a.json"), run("7", "b.json"), "same seed, same bytes");
    assert_ne!(run("7", "a.json"), run("8", "c.json"));
}

#[test]
fn roi_reports_bad_input_clearly() {
    let dir = temp("roi-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "S##\n#?#\n").unwrap();
    let o = stopscan(&["roi", "--grid", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.txt:2: unexpected '?' at column 2"), "{err}");
    let o = stopscan(&["roi", "--random", "20", "--robot-speed", "1", "--roi-speed", "1"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("must exceed the region's speed"));
    let o = stopscan(&["roi", "--random", "20", "--robots", "0"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected a whole number of at least 1"));
    let o = stopscan(&["roi"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--grid FILE or --random CELLS"));
    let o = stopscan(&["roi", "--resume", "m.json", "--robots", "3"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot be used with '--robots"));
    let state = dir.join("not-a-state.json");
    std::fs::write(&state, "{\"format\": 3}").unwrap();
    let o = stopscan(&["roi", "--resume", state.to_str().unwrap()]);
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("not-a-state.json:1:"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The field pipeline end to end: a runway-like rectangle (a polygon, explored through its
/// outer grid approximation), found by a lawn-mowing search, sensed by the synthetic camera
/// with a 3-of-5 vote, with a battery that forces swaps.
#[test]
fn roi_field_pipeline_finds_and_maps_a_runway() {
    let dir = temp("roi-field");
    std::fs::create_dir_all(&dir).unwrap();
    let runway = dir.join("runway.geojson");
    // 92 m × 21 m, rotated by 20°, centred on the start.
    let (c, s) = (20f64.to_radians().cos(), 20f64.to_radians().sin());
    let ring: Vec<[f64; 2]> =
        [(-46.0, -10.5), (46.0, -10.5), (46.0, 10.5), (-46.0, 10.5), (-46.0, -10.5)]
            .iter()
            .map(|&(x, y)| [x * c - y * s, x * s + y * c])
            .collect();
    let geo = serde_json::json!({"type": "Feature", "properties": {"start": [0.0, 0.0]},
        "geometry": {"type": "Polygon", "coordinates": [ring]}});
    std::fs::write(&runway, geo.to_string()).unwrap();
    let out = dir.join("field.json");
    let r = json(&[
        "roi",
        "--grid",
        runway.to_str().unwrap(),
        "--cell-m",
        "4",
        "--camera",
        "--search-box",
        "-12,-14,0,14",
        "--launch",
        "-12,-14",
        "--battery-s",
        "720",
        "--out",
        out.to_str().unwrap(),
    ]);
    let m = &r["metrics"];
    assert_eq!(m["all_home"], true);
    assert!(
        r["robots"][0]["battery_swaps"].as_u64().unwrap() >= 1,
        "12-minute batteries do not last"
    );
    assert!(f(m, "iou") > 0.7, "IoU {}", m["iou"]);
    assert!(m["c_out"].as_u64().unwrap() > m["c_in"].as_u64().unwrap());
    assert!(r["failures"].as_array().unwrap().is_empty());
}

/// Terminate a mission mid-way (SIGKILL), resume it from its state file: the run finishes
/// with exactly the record of an uninterrupted run (nothing lost, nothing repeated).
#[test]
fn roi_mission_survives_kill_and_resume() {
    let dir = temp("roi-kill");
    std::fs::create_dir_all(&dir).unwrap();
    let state = dir.join("mission.json");
    let whole = dir.join("whole.json");
    let resumed = dir.join("resumed.json");
    let (whole_trace, trace) = (dir.join("whole.jsonl"), dir.join("resumed.jsonl"));
    let args =
        ["roi", "--random", "20000", "--robots", "3", "--roi-speed", "0.2", "--battery-s", "600"];
    let o = stopscan(
        &[&args[..], &["--out", whole.to_str().unwrap(), "--trace", whole_trace.to_str().unwrap()]]
            .concat(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A journal line per step (under a microsecond each): a long mission, so that the kill
    // lands mid-mission; the trace goes on past the last step journaled.
    let mut child = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(args)
        .args(["--state", state.to_str().unwrap(), "--out", resumed.to_str().unwrap()])
        .args(["--trace", trace.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait for some steps to be written, then kill.
    // The journal: the state, then one line per step.
    let steps = |p: &PathBuf| -> u64 {
        std::fs::read_to_string(p).map_or(0, |t| t.lines().count().saturating_sub(1) as u64)
    };
    let t0 = std::time::Instant::now();
    while steps(&state) < 40 {
        assert!(t0.elapsed().as_secs() < 120, "the mission never wrote its state");
        std::thread::sleep(std::time::Duration::from_micros(200));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let at_kill = steps(&state);
    assert!(
        !resumed.exists(),
        "killed after the mission ended ({at_kill} steps); the test needs a longer mission"
    );
    // From another directory and without --trace: the state remembers both.
    let o = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(["roi", "--resume", state.to_str().unwrap()])
        .current_dir(std::env::temp_dir())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read(&whole).unwrap(),
        std::fs::read(&resumed).unwrap(),
        "the resumed mission differs from the uninterrupted one (killed at step {at_kill})"
    );
    assert_eq!(
        std::fs::read_to_string(&whole_trace).unwrap(),
        std::fs::read_to_string(&trace).unwrap(),
        "the resumed trace differs from the uninterrupted one: events lost or repeated"
    );
    // The resumed mission journals on from where it resumed.
    assert!(steps(&state) > 0);
    assert_no_temporary_files(&dir);
}

/// The state journal holds the state the mission started from and one line per step; a
/// mission resumed from its finished journal ends with the same record.
#[test]
fn roi_state_is_a_journal_of_every_step() {
    let dir = temp("roi-journal");
    std::fs::create_dir_all(&dir).unwrap();
    let (state, a, b) = (dir.join("s.jsonl"), dir.join("a.json"), dir.join("b.json"));
    let args = ["roi", "--random", "3000", "--robots", "4"];
    let o = stopscan(
        &[&args[..], &["--state", state.to_str().unwrap(), "--out", a.to_str().unwrap()]].concat(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&state).unwrap();
    let mut lines = text.lines();
    let first: Value = serde_json::from_str(lines.next().unwrap()).unwrap();
    assert_eq!(first["format"], "stopscan-mission/3");
    assert_eq!(first["mission"]["team"]["steps"], 0);
    let steps: Vec<Value> = lines.map(|l| serde_json::from_str(l).unwrap()).collect();
    assert!(steps.len() > 100);
    for (i, s) in steps.iter().enumerate() {
        assert_eq!(s["steps"].as_u64().unwrap(), (i + 1) as u64, "one line per step: {s}");
    }
    let o = stopscan(&["roi", "--resume", state.to_str().unwrap(), "--out", b.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
}
