//! `stopscan visibility` (and `bench visibility`).

use crate::common;

use serde_json::Value;

use common::{f, json, stopscan, temp};

const ROOM: &str =
    "OUTER 4\n0 0\n4 0\n4 4\n0 4\nHOLES 1\n4\n1 1\n1 2\n2 2\n2 1\nQUERIES 2\n3 3\n0.5 3.5\n";

#[test]
fn visibility_json_svg_and_many_queries() {
    let dir = temp("vis");
    std::fs::create_dir_all(&dir).unwrap();
    let env = dir.join("room.txt");
    std::fs::write(&env, ROOM).unwrap();
    let e = env.to_str().unwrap();
    let v = json(&["visibility", "--env", e, "--at", "3,3"]);
    assert!(f(&v, "area") > 0.0 && f(&v, "area") < 15.0);
    let kinds: Vec<&str> =
        v["boundary"].as_array().unwrap().iter().map(|b| b["kind"].as_str().unwrap()).collect();
    assert!(kinds.contains(&"window") && kinds.contains(&"edge"), "{kinds:?}");
    assert!(v["polygon"].as_array().unwrap().len() >= 3);
    let svg = stopscan(&["visibility", "--env", e, "--at", "3,3", "--format", "svg"]);
    assert!(svg.status.success());
    assert!(String::from_utf8_lossy(&svg.stdout).starts_with("<svg"));
    let pts = dir.join("q.txt");
    std::fs::write(&pts, "3 3\n0.5,3.5\n").unwrap();
    let out = stopscan(&["visibility", "--env", e, "--queries", pts.to_str().unwrap()]);
    let lines: Vec<Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(lines.len(), 2);
    assert_eq!(lines[0]["area"], v["area"]);
    let b = json(&["bench", "visibility", "--env", e, "--repeat", "1"]);
    for k in
        ["vertices", "queries", "preprocess_seconds", "queries_per_second", "mean_output_vertices"]
    {
        assert!(!b[k].is_null(), "{k}");
    }
    assert_eq!(b["queries"], 2);
    // Errors name the problem and the place.
    let bad = stopscan(&["visibility", "--env", e, "--at", "1.5,1.5"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("outside the free space"));
    std::fs::write(dir.join("broken.txt"), "OUTER 4\n0 0\n4 0\n4 x\n").unwrap();
    let bad =
        stopscan(&["visibility", "--env", dir.join("broken.txt").to_str().unwrap(), "--at", "1,1"]);
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("broken.txt:4"),
        "{}",
        String::from_utf8_lossy(&bad.stderr)
    );
    let bad = stopscan(&["corner", "thresholds", "--format", "svg"]);
    assert_eq!(bad.status.code(), Some(2));
}
