//! `stopscan bench`: the JSON contract of every benchmark.

use crate::common;

use common::{f, json};

#[test]
fn bench_prints_the_contract() {
    for (t, n) in [("mdp", "90"), ("circle", "1000"), ("ratio", "100")] {
        let v = json(&["bench", t, "--n", n, "--repeat", "1"]);
        for k in ["name", "n", "seconds_median", "per_second"] {
            assert!(!v[k].is_null(), "{t}: {k}");
        }
        assert!(f(&v, "per_second") > 0.0);
    }
    let g = json(&["bench", "mdp", "--solver", "general", "--n", "30", "--repeat", "1"]);
    assert_eq!(g["name"], "mdp2-policy-iteration");
}

/// `bench floors` on the repository's maps and one office: every requested strategy per map,
/// totals that add up, and a chart.
#[test]
fn bench_floors_on_small_inputs() {
    let dir = common::temp("floors");
    std::fs::create_dir_all(&dir).unwrap();
    let maps = dir.join("maps");
    std::fs::create_dir_all(&maps).unwrap();
    for f in ["turtlebot3_world.yaml", "turtlebot3_world.pgm"] {
        std::fs::copy(common::fixture(&format!("ros-maps/{f}")), maps.join(f)).unwrap();
    }
    let chart = dir.join("floors.svg");
    let r = common::json(&[
        "bench",
        "floors",
        "--data",
        maps.to_str().unwrap(),
        "--offices",
        "1",
        "--strategies",
        "depth_first,cost_aware",
        "--chart",
        chart.to_str().unwrap(),
    ]);
    let m = r["maps"].as_array().unwrap();
    assert_eq!(m.len(), 2);
    assert_eq!(m[0]["name"], "turtlebot3_world");
    for map in m {
        assert_eq!(map["runs"].as_array().unwrap().len(), 2);
    }
    for t in r["totals"].as_array().unwrap() {
        let s = t["strategy"].as_str().unwrap();
        let sum: f64 = m
            .iter()
            .flat_map(|x| x["runs"].as_array().unwrap())
            .filter(|x| x["strategy"] == s)
            .map(|x| x["time"].as_f64().unwrap())
            .sum();
        assert!((t["time"].as_f64().unwrap() - sum).abs() < 1e-6);
    }
    assert!(chart.exists() && chart.with_extension("png").exists());
    common::fails(
        &["bench", "floors", "--data", "/no/such/folder"],
        &["--data", "/no/such/folder", "no such folder"],
    );
}

/// `bench scans`: pairs as far apart as asked, the errors after alignment, a bad distance
/// refused.
#[test]
fn bench_scans_takes_pairs_as_far_apart_as_asked() {
    let v = json(&["bench", "scans", "--n", "12", "--pairs-within", "6"]);
    assert_eq!(v["pairs_within_m"], 6.0);
    let r = &v["result"];
    assert_eq!(r["trials"], 12);
    for k in ["position_error", "heading_error"] {
        let (median, p95) = (f(r, &format!("{k}_median")), f(r, &format!("{k}_p95")));
        assert!(0.0 <= median && median <= p95, "{k}: {median} {p95}");
    }
    // Converged pairs are within 1°: the median pair's heading error is below it.
    assert!(f(r, "heading_error_median") < 1f64.to_radians());
    for bad in ["0", "-1", "nan", "1e9"] {
        common::fails(&["bench", "scans", "--n", "2", "--pairs-within", bad], &["--pairs-within"]);
    }
}
