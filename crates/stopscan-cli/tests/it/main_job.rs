//! The main job (`stopscan` with no command), run as a user would.

use crate::common;

use std::path::PathBuf;
use std::process::Command;

use serde_json::Value;

use common::{f, stopscan, temp};

#[test]
fn main_job_explores_the_office_and_writes_the_run_record() {
    let dir = temp("main");
    let out = stopscan(&["--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8(out.stdout).unwrap();
    // Snapshot of the summary (paths excluded).
    let summary: String =
        text.lines().filter(|l| !l.starts_with("wrote ")).collect::<Vec<_>>().join("\n");
    let expected = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/main_job.txt"),
    )
    .unwrap();
    assert_eq!(summary.trim_end(), expected.trim_end(), "the main job's summary changed");
    let run: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("run.json")).unwrap()).unwrap();
    for k in [
        "format",
        "environment",
        "strategy",
        "cost_model",
        "sensor",
        "robots",
        "metrics",
        "bounds",
        "seed",
        "stopscan_version",
    ] {
        assert!(!run[k].is_null(), "run.json lacks {k}");
    }
    assert_eq!(run["format"], "stopscan-run/1");
    for k in [
        "scans",
        "moves",
        "distance",
        "time",
        "scan_time_total",
        "move_time_total",
        "travel_time_total",
        "covered_area",
        "coverage",
    ] {
        assert!(run["metrics"][k].is_number(), "metrics.{k}");
    }
    let scans = run["metrics"]["scans"].as_u64().unwrap();
    assert!(scans <= run["bounds"]["scans_upper"].as_u64().unwrap());
    assert!((f(&run["metrics"], "coverage") - 1.0).abs() < 1e-7);
    assert_eq!(run["robots"][0]["scans"].as_array().unwrap().len() as u64, scans);
    let svg = std::fs::read_to_string(dir.join("scene.svg")).unwrap();
    assert!(
        svg.starts_with("<svg")
            && svg.contains("<polyline")
            && svg.matches("<circle").count() as u64 >= scans
    );
}

/// `corner demo` writes corner-demo.json beside the main job's run.json, not over it.
#[test]
fn corner_demo_keeps_the_main_jobs_run_record() {
    let dir = temp("demo-cwd");
    std::fs::create_dir_all(&dir).unwrap();
    for args in [&[][..], &["corner", "demo"][..]] {
        let o = Command::new(env!("CARGO_BIN_EXE_stopscan"))
            .args(args)
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let run: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("stopscan-out/run.json")).unwrap())
            .unwrap();
    assert_eq!(run["format"], "stopscan-run/1");
    assert!(dir.join("stopscan-out/corner-demo.json").exists());
}
