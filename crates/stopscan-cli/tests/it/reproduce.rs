//! `stopscan reproduce`: every paper table and figure.

use crate::common;

use std::process::Command;

use common::{f, json, stopscan, temp};

#[test]
fn reproduce_every_id() {
    let dir = temp("repro");
    let ids = stopscan::experiment::ids();
    // The list.
    for id in "corner-table-2 corner-table-3 corner-table-4 corner-fig-7 corner-fig-8 circle-table-1 circle-fig-7".split(' ') {
        assert!(ids.contains(&id), "{id}");
    }
    // views-benchmarks reads a folder of benchmark polygons: two small ones of our own.
    let data = temp("repro-data");
    std::fs::create_dir_all(data.join("set")).unwrap();
    std::fs::write(data.join("set/l.pol"), "6 0/1 0/1 4/1 0/1 4/1 1/1 1/1 1/1 1/1 3/1 0/1 3/1\n")
        .unwrap();
    std::fs::write(
        data.join("set/u.pol"),
        "8 0/1 0/1 5/1 0/1 5/1 3/1 4/1 3/1 4/1 1/1 1/1 1/1 1/1 3/1 0/1 3/1\n",
    )
    .unwrap();
    let data_arg = data.to_str().unwrap();
    for &id in &ids {
        let v = json(&["reproduce", id, "--out", dir.to_str().unwrap(), "--data", data_arg]);
        assert_eq!(v["id"], id);
        assert!(!v["model"].as_array().unwrap().is_empty());
        let rows = v["rows"].as_array().unwrap();
        assert!(!rows.is_empty(), "{id}");
        for r in rows {
            assert!(r["label"].is_string() && r["ours"].is_number(), "{id}: {r}");
            assert!(r.get("paper").is_some() && r.get("rel_diff").is_some());
        }
        assert!(dir.join(format!("{id}.json")).exists());
    }
    let all = json(&["reproduce", "all", "--samples", "50", "--data", data_arg]);
    assert_eq!(all.as_array().unwrap().len(), ids.len());
    // Without the data, `all` reproduces everything else and says what it skipped.
    let missing = temp("no-data");
    let out =
        stopscan(&["reproduce", "all", "--samples", "50", "--data", missing.to_str().unwrap()]);
    assert!(out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("views-benchmarks skipped"));
    let out = stopscan(&["reproduce", "views-benchmarks", "--data", missing.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains(missing.to_str().unwrap()) && err.contains("no such directory"), "{err}");
    let empty = temp("empty-data");
    std::fs::create_dir_all(&empty).unwrap();
    let out = stopscan(&["reproduce", "views-benchmarks", "--data", empty.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("no benchmark environments"));
    let t1 = json(&["reproduce", "circle-table-1"]);
    for r in t1["rows"].as_array().unwrap() {
        assert!(f(r, "rel_diff").abs() < 1e-6, "{r}");
    }
    for chart in [
        "corner-fig-7.png",
        "corner-fig-8-left.svg",
        "circle-fig-7-small.png",
        "corner-fig-4-mdp2-conditional.png",
    ] {
        assert!(dir.join(chart).exists(), "{chart}");
    }
}

#[test]
fn reproduce_roi_fig_7_writes_charts_and_csv() {
    let dir = temp("fig7");
    let r = json(&["reproduce", "roi-fig-7", "--samples", "4", "--out", dir.to_str().unwrap()]);
    assert_eq!(r["id"], "roi-fig-7");
    for f in
        ["roi-fig-7b.png", "roi-fig-7b.svg", "roi-fig-7c.png", "roi-fig-7d.svg", "roi-fig-7.csv"]
    {
        assert!(dir.join(f).exists(), "{f} missing");
    }
    let csv = std::fs::read_to_string(dir.join("roi-fig-7.csv")).unwrap();
    assert_eq!(csv.lines().count(), 31, "a header and 30 points");
    assert!(r["notes"][0].as_str().unwrap().starts_with("120 of 120 trials are within"));
}

/// `--data` as given, or found from the checkout, whatever the current directory.
#[test]
fn reproduce_data_does_not_depend_on_the_current_directory() {
    let o = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(["reproduce", "views-benchmarks", "--data", "/nonexistent"])
        .current_dir(std::env::temp_dir())
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--data /nonexistent: no such directory"));
}
