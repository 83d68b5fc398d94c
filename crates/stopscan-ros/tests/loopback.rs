//! The whole exploration through DDS: a fake robot node (nav2's action server, `/scan` and
//! `/odom` from stopscan's simulated robot) and the explorer node, two processes inside a
//! network namespace that has only loopback (`unshare -n`), DDS limited to 127.0.0.1, so that
//! discovery traffic never leaves the machine.

use std::path::Path;
use std::process::Command;

use serde_json::Value;

#[path = "../../stopscan/tests/it/support/seen.rs"]
mod seen;
use seen::seen_share;

/// Whether this machine lets the test make a network namespace.
fn can_unshare() -> bool {
    Command::new("unshare")
        .args(["-n", "sh", "-c", "ip link set lo up"])
        .output()
        .is_ok_and(|o| o.status.success())
}

#[test]
fn an_office_is_explored_through_dds_on_loopback() {
    if !can_unshare() {
        eprintln!(
            "skipped: `unshare -n` (a network namespace) is not permitted here; run as root, \
             as CI does"
        );
        return;
    }
    let dir = std::env::temp_dir().join(format!("stopscan-ros-loopback-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    // A small office: two rows of three rooms.
    let inst = stopscan::generate::office(2, 3, 4).unwrap();
    let env = dir.join("office.geojson");
    let geo = stopscan::io::text_formats::to_geojson(&inst.domain, Some(inst.start));
    std::fs::write(&env, geo.to_string()).unwrap();
    let (journal, out) = (dir.join("journal.jsonl"), dir.join("done.json"));
    let bin = env!("CARGO_BIN_EXE_stopscan-ros");
    let domain = (std::process::id() % 200).to_string();
    let script = r#"
        set -u
        ip link set lo up
        "$BIN" --localhost --domain "$DOMAIN" fake-robot --env "$ENV" --seed 5 --sensor lidar:beams=360 &
        robot=$!
        "$BIN" --localhost --domain "$DOMAIN" explore --strategy nearest_frontier \
            --journal "$JOURNAL" --out "$OUT" --wait 60 --goal-timeout 60 --return-home
        rc=$?
        kill "$robot"
        wait "$robot" 2>/dev/null
        exit $rc
    "#;
    let o = Command::new("unshare")
        .args(["-n", "sh", "-c", script])
        .env("BIN", bin)
        .env("DOMAIN", &domain)
        .env("ENV", &env)
        .env("JOURNAL", &journal)
        .env("OUT", &out)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "the explorer failed: {err}");
    // The statuses, in order.
    let statuses: Vec<&str> =
        err.lines().filter_map(|l| l.strip_prefix("explore/status: ")).collect();
    assert_eq!(statuses, ["started", "complete", "returning", "returned"], "{err}");
    let done: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(done["type"], "done");
    assert_eq!(done["reason"], "explored", "{done}");
    let scans = done["summary"]["scans"].as_u64().unwrap();
    assert!(scans >= 3, "{done}");
    // Every scan of the journal was placed within the office, and together they saw most of
    // it: the share of grid points in sight of some scan pose, by ray casting.
    let stops = scan_poses(&journal);
    assert_eq!(stops.len() as u64, scans);
    let share = seen_share(&inst.domain, &stops, f64::INFINITY, 0.25);
    assert!(share > 0.95, "{share} of the office seen from the scans placed");
}

/// The map-frame poses the journal placed the scans at.
fn scan_poses(journal: &Path) -> Vec<[f64; 2]> {
    std::fs::read_to_string(journal)
        .unwrap()
        .lines()
        .skip(1)
        .filter_map(|l| {
            let v: Value = serde_json::from_str(l).unwrap();
            let p = &v["reply"]["localised"]["pose"];
            Some([p["x"].as_f64()?, p["y"].as_f64()?])
        })
        .collect()
}
