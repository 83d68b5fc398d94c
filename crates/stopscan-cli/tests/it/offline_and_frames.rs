//! `explore` as a user runs it on the inputs that used to hang (starts on walls, georeferenced
//! maps) and with the offline references' budgets and bounds.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

fn stopscan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stopscan")).args(args).output().expect("the binary runs")
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stopscan-offline-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn repo(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").join(path).display().to_string()
}

/// Runs `explore` with `args`, expecting success, and returns the run record.
fn explore(dir: &Path, args: &[&str]) -> Value {
    let out_path = dir.join("run.json");
    let mut all = vec!["explore", "--out", out_path.to_str().unwrap()];
    all.extend(args);
    let out = stopscan(&all);
    assert!(out.status.success(), "{all:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_str(&std::fs::read_to_string(out_path).unwrap()).unwrap()
}

fn fails(args: &[&str], needle: &str) {
    let out = stopscan(args);
    assert_eq!(out.status.code(), Some(2), "{args:?} should fail");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(needle), "{args:?}: {err:?} lacks {needle:?}");
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn a_start_on_a_wall_or_a_vertex_is_explored() {
    let dir = temp("wall");
    let office = repo("fixtures/office.geojson");
    for start in ["0,0", "0,3", "4,0", "1.5,5.2", "25,7.2"] {
        for strategy in [
            vec!["--strategy", "depth_first"],
            vec!["--strategy", "nearest_frontier"],
            vec!["--strategy", "greedy_nbv"],
            vec!["--strategy", "range_limited", "--range", "5"],
        ] {
            let mut args = vec![
                "--env",
                &office,
                "--start",
                start,
                "--optimum-seconds",
                "0",
                "--bounds-seconds",
                "0",
            ];
            args.extend(&strategy);
            let rec = explore(&dir, &args);
            let m = &rec["metrics"];
            assert_eq!(m["open_windows"], 0, "{args:?}");
            assert!((m["coverage"].as_f64().unwrap() - 1.0).abs() < 1e-6, "{args:?}");
            let first = &rec["robots"][0]["path"][0];
            let given: Vec<f64> = start.split(',').map(|v| v.parse().unwrap()).collect();
            assert_eq!(first, &serde_json::json!(given), "the path starts where asked");
            assert!(rec["error"].is_null());
        }
        // A lidar cannot scan from inside a wall: a clear error that names the file.
        let args = ["explore", "--env", &office, "--start", start, "--sensor", "lidar"];
        let out = stopscan(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{args:?}");
        assert!(err.contains("office.geojson") && err.contains("lies on a wall"), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

/// The vendored turtlebot map, written with another origin in its YAML.
fn map_with_origin(dir: &Path, origin: &str) -> String {
    let image = Path::new(&repo("fixtures/ros-maps/turtlebot3_world.pgm")).canonicalize().unwrap();
    let yaml = dir.join(format!("map-{}.yaml", origin.replace([',', ' '], "_")));
    std::fs::write(
        &yaml,
        format!(
            "image: {}\nresolution: 0.05\norigin: [{origin}, 0.0]\nnegate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n",
            image.display()
        ),
    )
    .unwrap();
    yaml.display().to_string()
}

#[test]
fn a_georeferenced_map_explores_as_at_home_and_reports_in_its_own_frame() {
    let dir = temp("utm");
    let home = map_with_origin(&dir, "-10.0, -10.0");
    let base = explore(&dir, &["--env", &home, "--optimum-seconds", "0"]);
    for (origin, shift) in [
        ("4500000.0, 5300000.0", [4_500_010.0, 5_300_010.0]),
        ("1e16, 1e16", [1e16 + 10.0, 1e16 + 10.0]),
    ] {
        let map = map_with_origin(&dir, origin);
        for strategy in ["depth_first", "nearest_frontier"] {
            let rec =
                explore(&dir, &["--env", &map, "--strategy", strategy, "--optimum-seconds", "0"]);
            let want = if strategy == "depth_first" {
                base.clone()
            } else {
                explore(&dir, &["--env", &home, "--strategy", strategy, "--optimum-seconds", "0"])
            };
            assert_eq!(rec["metrics"], want["metrics"], "{origin}, {strategy}");
            assert_eq!(rec["bounds"]["scans_lower"], want["bounds"]["scans_lower"]);
            // Points are in the map's own coordinates: the local path moved by the origin.
            let p = rec["robots"][0]["path"][1].as_array().unwrap();
            let q = want["robots"][0]["path"][1].as_array().unwrap();
            for k in 0..2 {
                let (got, local) = (p[k].as_f64().unwrap(), q[k].as_f64().unwrap());
                let expected = local + shift[k];
                assert!(
                    (got - expected).abs() <= 4.0 * expected.abs() * f64::EPSILON + 1e-9,
                    "{got} vs {expected}"
                );
            }
        }
    }
}

#[test]
fn every_run_record_carries_certified_bounds_and_the_optimum_search_is_budgeted() {
    let dir = temp("bounds");
    let spiral = dir.join("spiral.geojson");
    let g = stopscan(&["generate", "spiral", "--size", "10", "-o", spiral.to_str().unwrap()]);
    assert!(g.status.success());
    let spiral = spiral.to_str().unwrap();
    // The default budget: the optimum of a spiral with 10 turns is proven (r + 1 = 11).
    let rec = explore(&dir, &["--env", spiral]);
    let b = &rec["bounds"];
    assert_eq!(b["optimum_status"], "proven");
    assert_eq!(b["optimum"], 11);
    assert!(b["optimum_lower"].as_u64().unwrap() <= 11);
    let time = rec["metrics"]["time"].as_f64().unwrap();
    let lower = b["time_lower"].as_f64().unwrap();
    assert!(lower > 0.0 && lower <= time);
    assert!((b["certified_ratio"].as_f64().unwrap() - time / lower).abs() < 1e-12);
    assert!(b["scans_lower"].as_u64().unwrap() <= 11 && b["scans_lower"].as_u64().unwrap() >= 2);
    // No budget: the search is skipped and says why; the bounds are still there.
    let rec = explore(&dir, &["--env", spiral, "--optimum-seconds", "0"]);
    assert_eq!(rec["bounds"]["optimum_status"], "skipped");
    assert!(rec["bounds"]["optimum_note"].as_str().unwrap().contains("--optimum-seconds 0"));
    assert!(rec["bounds"]["certified_ratio"].is_number());
    // A budget that runs out reports the best set and the lower bound beside it.
    let office = repo("fixtures/office.geojson");
    let out = stopscan(&[
        "explore",
        "--env",
        &office,
        "--optimum-seconds",
        "0.2",
        "--out",
        dir.join("o.json").to_str().unwrap(),
    ]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("between") && text.contains("time budget ran out"), "{text}");
    let rec: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("o.json")).unwrap()).unwrap();
    let b = &rec["bounds"];
    assert_eq!(b["optimum_status"], "budget_reached");
    assert!(b["optimum"].is_null());
    assert!(b["optimum_lower"].as_u64().unwrap() <= b["optimum_best"].as_u64().unwrap());
}

#[test]
fn bad_budgets_and_solvers_are_clear_errors() {
    let office = repo("fixtures/office.geojson");
    fails(&["explore", "--env", &office, "--optimum-seconds", "-1"], "--optimum-seconds");
    fails(&["explore", "--env", &office, "--bounds-seconds", "nan"], "--bounds-seconds");
    fails(&["explore", "--env", &office, "--solver", "gurobi"], "unknown solver");
    if !cfg!(feature = "cbc") {
        fails(&["explore", "--env", &office, "--solver", "cbc"], "--features cbc");
    }
}
