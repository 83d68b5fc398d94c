//! `stopscan map import`.

mod common;

use std::path::PathBuf;

use serde_json::Value;

use common::{f, json, stopscan, temp};

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
