//! `--mcap FILE`: the recordings read back by an independent reader, Python's `mcap` package
//! (`tests/python/read_mcap.py`), which also validates every message against its channel's
//! JSON Schema with jsonschema. The channels, schemas and message counts are checked against
//! the run record.
//!
//! Without python3 and its `mcap` package the tests are skipped with a message, unless
//! `STOPSCAN_CI` is set (as `.ci/run` sets it, after installing them), when they fail.

use crate::common;

use serde_json::Value;

use common::{
    fixture, mcap_count as count, mcap_topic as topic, read_mcap as read, stopscan, temp,
};

fn nanos(seconds: f64) -> u64 {
    (seconds * 1e9).round() as u64
}

#[test]
fn an_exploration_on_raw_scans_opens_in_foxglove() {
    let dir = temp("mcap-explore");
    std::fs::create_dir_all(&dir).unwrap();
    let (json, mcap) = (dir.join("run.json"), dir.join("run.mcap"));
    let office = fixture("office.geojson");
    let out = stopscan(&[
        "explore",
        "--env",
        &office,
        "--sensor",
        "lidar",
        "--strategy",
        "nearest_frontier",
        "--seed",
        "3",
        "--out",
        json.to_str().unwrap(),
        "--mcap",
        mcap.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains(&format!("wrote {}", mcap.display())));
    let record: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let Some(v) = read(&mcap) else { return };
    let schemas = [
        ("/map", "foxglove.SceneUpdate"),
        ("/scans", "foxglove.SceneUpdate"),
        ("/frontiers", "foxglove.SceneUpdate"),
        ("/path", "foxglove.PosesInFrame"),
        ("/tf", "foxglove.FrameTransform"),
        ("/lidar", "foxglove.LaserScan"),
        ("/log", "foxglove.Log"),
    ];
    assert_eq!(v["topics"].as_object().unwrap().len(), schemas.len());
    for (t, s) in schemas {
        assert_eq!(topic(&v, t)["schema"], s, "{t}");
    }
    let scans = record["metrics"]["scans"].as_u64().unwrap();
    let robot = &record["robots"][0];
    let path = robot["path"].as_array().unwrap().len() as u64;
    for t in ["/scans", "/frontiers", "/path", "/lidar"] {
        assert_eq!(count(&v, t), scans, "{t}: one message per scan");
    }
    assert_eq!(count(&v, "/map"), 1);
    assert_eq!(count(&v, "/log"), scans + 1, "one line per scan, and the end");
    assert_eq!(count(&v, "/tf"), path + scans, "every path vertex, and every stop's estimate");
    // Each scan's region is published when the scan began.
    let want: Vec<u64> = robot["scans"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| nanos(s["time"].as_f64().unwrap()))
        .collect();
    let got: Vec<u64> = topic(&v, "/scans")["log_times"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_u64().unwrap())
        .collect();
    assert_eq!(got, want);
    // The raw scans are the lidar's: its beam count, placed where the scan was taken.
    let beams = record["raw_scans"]["lidar"]["beams"].as_u64().unwrap();
    let stops = record["raw_scans"]["stops"].as_array().unwrap();
    for (scan, stop) in topic(&v, "/lidar")["messages"].as_array().unwrap().iter().zip(stops) {
        assert_eq!(scan["ranges"].as_array().unwrap().len() as u64, beams);
        let p = &scan["pose"]["position"];
        let truth = &stop["truth"];
        assert!((p["x"].as_f64().unwrap() - truth["x"].as_f64().unwrap()).abs() < 1e-12);
        assert!((p["y"].as_f64().unwrap() - truth["y"].as_f64().unwrap()).abs() < 1e-12);
    }
    // The path grows by the scans' vertices, and ends where the last scan was taken.
    let last_path = topic(&v, "/path")["messages"].as_array().unwrap().last().unwrap();
    let last_pose = &last_path["poses"].as_array().unwrap().last().unwrap()["position"];
    let last_scan = &robot["scans"].as_array().unwrap().last().unwrap()["at"];
    assert!((last_pose["x"].as_f64().unwrap() - last_scan[0].as_f64().unwrap()).abs() < 1e-9);
    assert!((last_pose["y"].as_f64().unwrap() - last_scan[1].as_f64().unwrap()).abs() < 1e-9);
    // The frontiers open after the last scan are the record's windows left open.
    let last = topic(&v, "/frontiers")["messages"].as_array().unwrap().last().unwrap();
    let lines = last["entities"][0]["lines"].as_array().unwrap();
    let parts: usize = lines.iter().map(|l| l["points"].as_array().unwrap().len() / 2).sum();
    assert_eq!(parts as u64, record["metrics"]["open_windows"].as_u64().unwrap());
    // The metadata: what the run was.
    let meta = &v["metadata"]["stopscan"];
    assert_eq!(meta["seed"], "3");
    assert_eq!(meta["stopscan_version"], record["stopscan_version"]);
    let cost: Value = serde_json::from_str(meta["cost_model"].as_str().unwrap()).unwrap();
    assert_eq!(cost, record["cost_model"]);
    let embedded: Value = serde_json::from_str(meta["run_record"].as_str().unwrap()).unwrap();
    assert_eq!(embedded, record);
    let end = topic(&v, "/log")["messages"].as_array().unwrap().last().unwrap();
    assert!(end["message"].as_str().unwrap().starts_with("done: "), "{end}");
}

#[test]
fn a_team_mission_opens_in_foxglove() {
    let dir = temp("mcap-roi");
    std::fs::create_dir_all(&dir).unwrap();
    let (json, mcap) = (dir.join("roi.json"), dir.join("roi.mcap"));
    let out = stopscan(&[
        "roi",
        "--random",
        "150",
        "--robots",
        "3",
        "--seed",
        "2",
        "--out",
        json.to_str().unwrap(),
        "--mcap",
        mcap.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let record: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let Some(v) = read(&mcap) else { return };
    let robots = record["robots"].as_array().unwrap();
    let flown: u64 = robots.iter().map(|r| r["cells"].as_array().unwrap().len() as u64).sum();
    assert_eq!(count(&v, "/map"), 1);
    assert_eq!(count(&v, "/tf"), flown, "one transform per cell reached");
    assert_eq!(count(&v, "/flights"), 1);
    assert_eq!(count(&v, "/log"), robots.len() as u64 + 1);
    // Cells marked: every region cell once, at the first time a robot reached it.
    let mut first = std::collections::BTreeMap::new();
    for r in robots {
        for (c, t) in r["cells"].as_array().unwrap().iter().zip(r["times"].as_array().unwrap()) {
            let c = (c[0].as_i64().unwrap(), c[1].as_i64().unwrap());
            let t = nanos(t.as_f64().unwrap());
            let e = first.entry(c).or_insert(t);
            *e = (*e).min(t);
        }
    }
    let cells = topic(&v, "/cells");
    let marked: usize = cells["messages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m["entities"][0]["cubes"].as_array().unwrap().len())
        .sum();
    assert_eq!(marked as u64, record["metrics"]["visited_cells"].as_u64().unwrap());
    let mut times: Vec<u64> = first.values().copied().collect();
    times.sort_unstable();
    times.dedup();
    let got: Vec<u64> =
        cells["log_times"].as_array().unwrap().iter().map(|t| t.as_u64().unwrap()).collect();
    assert_eq!(got, times, "a /cells message at each moment a cell is first reached");
    let meta = &v["metadata"]["stopscan"];
    assert_eq!(meta["seed"], "2");
}

#[test]
fn a_sweep_refuses_mcap() {
    let dir = temp("mcap-sweep");
    std::fs::create_dir_all(&dir).unwrap();
    let out = stopscan(&["explore", "--env", dir.to_str().unwrap(), "--mcap", "r.mcap"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--mcap records one run"));
}
