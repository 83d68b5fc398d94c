//! `stopscan map import`.

use crate::common;

use std::path::PathBuf;

use serde_json::Value;

use common::{f, fails, json, stopscan, temp};

#[test]
fn map_import_then_visibility_on_the_geojson() {
    let dir = temp("import");
    std::fs::create_dir_all(&dir).unwrap();
    let map = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/ros-maps/turtlebot3_world.yaml");
    let out = dir.join("tb3.geojson");
    let v = json(&[
        "map",
        "import",
        map.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--start",
        "-2,-0.5",
    ]);
    assert!(v["holes"].as_u64().unwrap() >= 5);
    assert!(f(&v, "free_area") > 10.0);
    let geo: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(geo["geometry"]["type"], "Polygon");
    assert_eq!(geo["properties"]["start"], serde_json::json!([-2.0, -0.5]));
    let r =
        json(&["visibility", "--env", out.to_str().unwrap(), "--at", "-2,-0.5", "--range", "1.5"]);
    assert!(f(&r, "area") > 0.0 && f(&r, "area") <= std::f64::consts::PI * 1.5 * 1.5 + 1e-9);
    assert!(r["boundary"].as_array().unwrap().iter().any(|b| b["kind"] == "arc"));
    let bad = stopscan(&["map", "import", "/no/such.yaml", "-o", out.to_str().unwrap()]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("/no/such.yaml"));
}

#[test]
fn map_import_simplifies_within_the_tolerance_and_reports_the_area_change() {
    let dir = temp("simplify");
    std::fs::create_dir_all(&dir).unwrap();
    let map = common::fixture("ros-maps/turtlebot3_world.yaml");
    let out = dir.join("tb3.geojson");
    let import = |extra: &[&str]| {
        let mut args = vec!["map", "import", &map, "-o", out.to_str().unwrap()];
        args.extend(extra);
        json(&args)
    };
    // The default: 1.5 cells of 5 cm.
    let v = import(&[]);
    let s = &v["simplification"];
    assert_eq!(f(s, "tolerance"), 1.5 * 0.05);
    assert_eq!(f(s, "tolerance_used"), f(s, "tolerance"));
    assert_eq!(f(s, "resolution"), 0.05);
    assert_eq!(s["vertices"], v["vertices"]);
    assert_eq!(s["reflex_vertices"], v["reflex_vertices"]);
    assert_eq!(f(s, "area"), f(&v, "free_area"));
    let (before, after) = (s["traced_vertices"].as_u64().unwrap(), s["vertices"].as_u64().unwrap());
    assert!(after * 3 < before, "{before} -> {after} vertices");
    let change = (f(s, "area") - f(s, "traced_area")).abs();
    assert!((f(s, "area_change") - change).abs() < 1e-12);
    assert!((f(s, "relative_area_change") - change / f(s, "traced_area")).abs() < 1e-15);
    assert!(f(s, "relative_area_change") < 0.01);
    // 0: the traced boundary itself.
    let v = import(&["--simplify", "0"]);
    let s = &v["simplification"];
    assert_eq!(s["vertices"], s["traced_vertices"]);
    assert_eq!(f(s, "area_change"), 0.0);
    assert_eq!(f(s, "traced_area"), f(&v, "free_area"));
    // A wider tolerance removes more.
    let v = import(&["--simplify", "0.15"]);
    assert!(v["simplification"]["vertices"].as_u64().unwrap() < after);
    // The table says it on a line of its own.
    let t = stopscan(&["map", "import", &map, "-o", out.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&t.stdout);
    assert!(text.contains("simplified within 0.075 m (1.50 cells of 0.050 m)"), "{text}");
    assert!(text.contains("area 19.737 -> "), "{text}");
    // Bad values name the flag.
    for bad in ["-0.1", "nan", "inf", "-inf"] {
        fails(
            &["map", "import", &map, "-o", out.to_str().unwrap(), "--simplify", bad],
            &["--simplify must be a finite non-negative number of metres"],
        );
    }
    // Other formats are read as they are: no simplification to report.
    let v = json(&[
        "map",
        "import",
        out.to_str().unwrap(),
        "-o",
        dir.join("again.geojson").to_str().unwrap(),
    ]);
    assert!(v.get("simplification").is_none(), "{v}");
}

#[test]
fn the_geojson_written_may_be_named_by_out_as_for_every_other_command() {
    let dir = temp("import-out");
    std::fs::create_dir_all(&dir).unwrap();
    let map = common::fixture("ros-maps/turtlebot3_world.yaml");
    let (a, b) = (dir.join("a.geojson"), dir.join("b.geojson"));
    let (a, b) = (a.to_str().unwrap(), b.to_str().unwrap());
    let v = json(&["map", "import", &map, "--out", a]);
    assert_eq!(v["output"], a);
    let geo: Value = serde_json::from_str(&std::fs::read_to_string(a).unwrap()).unwrap();
    assert_eq!(geo["geometry"]["type"], "Polygon");
    let g = stopscan(&["generate", "office", "--size", "2", "--out", b]);
    assert!(g.status.success(), "{}", String::from_utf8_lossy(&g.stderr));
    assert!(std::fs::read_to_string(b).unwrap().contains("\"start\""));
    // The same file twice is one file; two files, or none, are refused before any work.
    json(&["map", "import", &map, "-o", a, "--out", a]);
    fails(&["map", "import", &map, "-o", a, "--out", b], &["two files to write", "a.geojson"]);
    fails(&["map", "import", &map], &["-o/--output FILE"]);
    fails(&["generate", "comb"], &["-o/--output FILE"]);
}
