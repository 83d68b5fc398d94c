//! Helpers shared by the CLI's test files (one per command): run the binary as a user would
//! and check what it prints and writes.
// Each test file uses some of these helpers, never all.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use serde_json::Value;

pub(crate) fn stopscan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stopscan")).args(args).output().expect("the binary runs")
}

pub(crate) fn json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.extend(["--format", "json"]);
    let out = stopscan(&all);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: {e}: {}", String::from_utf8_lossy(&out.stdout)))
}

pub(crate) fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} missing in {v}"))
}

pub(crate) fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stopscan-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// No temporary file (`*.tmp`, `*.json.tmp`, …) is left in `dir`.
pub(crate) fn assert_no_temporary_files(dir: &std::path::Path) {
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

/// A failed command: exit status 2, the needles in standard error, no panic.
pub(crate) fn fails(args: &[&str], needles: &[&str]) -> String {
    let out = stopscan(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?} should fail: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err:?} should mention {n:?}");
    }
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    err
}

pub(crate) fn fixture(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(path)
        .to_str()
        .unwrap()
        .to_string()
}

/// What the independent reader found in `file`, or `None` when it may be skipped.
pub(crate) fn read_mcap(file: &Path) -> Option<Value> {
    let has = Command::new("python3").args(["-c", "import mcap, jsonschema"]).output();
    if !has.is_ok_and(|o| o.status.success()) {
        assert!(
            std::env::var_os("STOPSCAN_CI").is_none(),
            "STOPSCAN_CI is set but python3 cannot import mcap and jsonschema"
        );
        eprintln!("skipped: needs python3 with mcap and jsonschema (pip install mcap jsonschema)");
        return None;
    }
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/python/read_mcap.py");
    let out = Command::new("python3").arg(script).arg(file).output().unwrap();
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["validated"], true);
    assert_eq!(v["errors"].as_array().unwrap().len(), 0, "schema errors: {}", v["errors"]);
    // The summary's counts are the messages there are.
    for (topic, t) in v["topics"].as_object().unwrap() {
        assert_eq!(t["count"], v["summary_counts"][topic], "{topic}");
        assert_eq!(t["message_encoding"], "json", "{topic}");
        assert_eq!(t["schema_encoding"], "jsonschema", "{topic}");
    }
    Some(v)
}

pub(crate) fn mcap_topic<'a>(v: &'a Value, name: &str) -> &'a Value {
    let t = &v["topics"][name];
    assert!(t.is_object(), "no topic {name} in {:?}", v["topics"].as_object().unwrap().keys());
    t
}

pub(crate) fn mcap_count(v: &Value, name: &str) -> u64 {
    mcap_topic(v, name)["count"].as_u64().unwrap()
}
