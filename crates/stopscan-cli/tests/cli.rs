//! Every command, run as a user would, with its output checked.

use std::path::PathBuf;
use std::process::{Command, Output};

use serde_json::Value;

fn stopscan(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stopscan")).args(args).output().expect("the binary runs")
}

fn json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.extend(["--format", "json"]);
    let out = stopscan(&all);
    assert!(out.status.success(), "{args:?}: {}", String::from_utf8_lossy(&out.stderr));
    serde_json::from_slice(&out.stdout)
        .unwrap_or_else(|e| panic!("{args:?}: {e}: {}", String::from_utf8_lossy(&out.stdout)))
}

fn f(v: &Value, key: &str) -> f64 {
    v[key].as_f64().unwrap_or_else(|| panic!("{key} missing in {v}"))
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stopscan-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// No temporary file (`*.tmp`, `*.json.tmp`, …) is left in `dir`.
fn assert_no_temporary_files(dir: &std::path::Path) {
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.contains(".tmp"))
        .collect();
    assert!(leftovers.is_empty(), "temporary files left: {leftovers:?}");
}

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

#[test]
fn explore_trace_range_and_determinism() {
    let dir = temp("trace");
    std::fs::create_dir_all(&dir).unwrap();
    let env = dir.join("spiral.geojson");
    let g = stopscan(&["generate", "spiral", "--size", "5", "-o", env.to_str().unwrap()]);
    assert!(g.status.success());
    // The event trace: one line per move and scan, then the tally; byte-identical on a rerun,
    // as is the run record.
    let trace = |name: &str| {
        let (t, o) = (dir.join(format!("{name}.jsonl")), dir.join(format!("{name}.json")));
        let r = stopscan(&[
            "explore",
            "--env",
            env.to_str().unwrap(),
            "--strategy",
            "greedy_nbv",
            "--trace",
            t.to_str().unwrap(),
            "--out",
            o.to_str().unwrap(),
        ]);
        assert!(r.status.success(), "{}", String::from_utf8_lossy(&r.stderr));
        let out = (std::fs::read(&t).unwrap(), std::fs::read(&o).unwrap());
        std::fs::remove_file(t).unwrap();
        std::fs::remove_file(o).unwrap();
        out
    };
    let (t1, r1) = trace("a");
    let (t2, r2) = trace("b");
    assert_eq!(t1, t2, "the trace is deterministic");
    assert_eq!(r1, r2, "the run record is deterministic");
    let rec: Value = serde_json::from_slice(&r1).unwrap();
    let lines: Vec<Value> =
        String::from_utf8(t1).unwrap().lines().map(|l| serde_json::from_str(l).unwrap()).collect();
    let m = &rec["metrics"];
    assert_eq!(lines.len() as u64, m["scans"].as_u64().unwrap() + m["moves"].as_u64().unwrap() + 1);
    assert_eq!(lines.last().unwrap()["event"], "finish");
    assert_eq!(lines[0]["event"], "scan");
    // With a range limit: the paper's range-limited algorithm, Lemma 4's bound, area / πR².
    let vr = json(&[
        "explore",
        "--env",
        env.to_str().unwrap(),
        "--range",
        "1.5",
        "--strategy",
        "range_limited",
        "--out",
        dir.join("range.json").to_str().unwrap(),
    ]);
    assert_eq!(vr["sensor"]["range"], 1.5);
    assert!(vr["bounds"]["scans_upper_rule"].as_str().unwrap().contains("Lemma 4"));
    assert!(
        vr["metrics"]["scans"].as_u64().unwrap() <= vr["bounds"]["scans_upper"].as_u64().unwrap()
    );
    assert!(
        vr["metrics"]["scans"].as_u64().unwrap() >= vr["bounds"]["scans_lower"].as_u64().unwrap()
    );
    assert_eq!(vr["metrics"]["open_windows"], 0);
    assert!(f(&vr["metrics"], "coverage") >= 1.0 - 1e-6);
    let bad = stopscan(&["explore", "--env", env.to_str().unwrap(), "--range", "0"]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--range must be a positive"));
}

#[test]
fn explore_and_generate() {
    let dir = temp("explore");
    std::fs::create_dir_all(&dir).unwrap();
    let env = dir.join("spiral.geojson");
    let g = stopscan(&["generate", "spiral", "--size", "5", "-o", env.to_str().unwrap()]);
    assert!(g.status.success());
    let out = dir.join("run.json");
    let v = json(&[
        "explore",
        "--env",
        env.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--svg",
        dir.join("s.svg").to_str().unwrap(),
        "--scan-time",
        "2",
        "--speed",
        "0.5",
    ]);
    assert_eq!(v["metrics"]["scans"], 6, "a spiral with 5 turns needs r + 1 = 6 views");
    assert_eq!(v["cost_model"]["scan_time"], 2.0);
    // The offline optimum (integer programming) is r + 1 too: the algorithm is optimal here.
    assert_eq!(v["bounds"]["optimum"], 6, "{}", v["bounds"]);
    assert_eq!(v["bounds"]["competitive_ratio"], 1.0);
    assert!((f(&v["metrics"], "scan_time_total") - 12.0).abs() < 1e-12);
    assert!(dir.join("s.svg").exists() && out.exists());
    // A folder: a sweep with every strategy, as CSV.
    let csv_path = dir.join("sweep.csv");
    let g2 = stopscan(&[
        "generate",
        "comb",
        "--size",
        "3",
        "-o",
        dir.join("comb.geojson").to_str().unwrap(),
    ]);
    assert!(g2.status.success());
    std::fs::remove_file(dir.join("s.svg")).unwrap();
    std::fs::remove_file(&out).unwrap();
    let sweep = stopscan(&[
        "explore",
        "--env",
        dir.to_str().unwrap(),
        "--strategy",
        "all",
        "--out",
        csv_path.to_str().unwrap(),
    ]);
    assert!(sweep.status.success(), "{}", String::from_utf8_lossy(&sweep.stderr));
    let csv_text = std::fs::read_to_string(&csv_path).unwrap();
    assert_eq!(
        csv_text.lines().count(),
        1 + 2 * stopscan::strategy::polygon::REGISTRY.len(),
        "header + 2 environments × every strategy:\n{csv_text}"
    );
    assert!(csv_text.lines().next().unwrap().contains("scans_upper"));
    let b = json(&["bench", "explore", "--n", "20"]);
    assert_eq!(b["runs_failing_checks"], 0, "{b}");
    assert_eq!(b["n"], 20);
    let bad = stopscan(&["explore", "--env", env.to_str().unwrap(), "--strategy", "teleport"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("unknown strategy"));
    let bad = stopscan(&["explore", "--env", env.to_str().unwrap(), "--start", "1000,1000"]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("outside the free space"));
}

#[test]
fn corner_demo_writes_its_outputs() {
    let dir = temp("demo");
    let out = stopscan(&["corner", "demo", "--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let text = String::from_utf8_lossy(&out.stdout);
    for s in ["Circle strategy", "UNIREC", "EXPREC", "POLICY1", "POLICY2", "1.839287"] {
        assert!(text.contains(s), "missing {s} in\n{text}");
    }
    for f in ["corner-demo.json", "circle-ratio.svg", "circle-ratio.png"] {
        assert!(dir.join(f).metadata().unwrap().len() > 100, "{f}");
    }
    let run: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("corner-demo.json")).unwrap())
            .unwrap();
    assert_eq!(run["corner"]["strategies"].as_array().unwrap().len(), 4);
}

#[test]
fn corner_circle() {
    let v = json(&["corner", "circle", "--distance", "40"]);
    assert_eq!((f(&v, "ratio") * 1e6).floor(), 2_001_525.0);
    let scans = v["scans"].as_u64().unwrap() as usize;
    assert_eq!(v["steps"].as_array().unwrap().len(), scans + 1);
    assert_eq!(v["scan_points"].as_array().unwrap().len(), scans + 1);
    assert_eq!(f(&v, "distance"), 40.0);
}

#[test]
fn corner_thresholds() {
    let v = json(&["corner", "thresholds", "--count", "6"]);
    let t = v["thresholds"].as_array().unwrap();
    assert_eq!(t.len(), 6);
    assert!((f(&t[3], "distance") - 4.400_876).abs() < 1e-6);
    assert!((f(&t[3], "ratio") - 2.168_544).abs() < 1e-6);
    assert_eq!(t[5]["scans"], 5);
}

#[test]
fn corner_optimal() {
    let v = json(&["corner", "optimal", "--distance", "1", "--scans", "1"]);
    assert!((f(&v, "ratio") - 1.808_201).abs() < 1e-6);
    assert_eq!(v["scan_points"].as_array().unwrap().len(), 1);
    assert_eq!(v["scans"], 1);
}

#[test]
fn corner_ratio_keys_and_values() {
    let v = json(&["corner", "ratio", "--strategy", "unirec", "--delta", "0.000001"]);
    for k in ["strategy", "delta", "worst_ratio", "theta_at_worst", "asymptotic_ratio"] {
        assert!(!v[k].is_null(), "{k}");
    }
    assert!((f(&v, "worst_ratio") - std::f64::consts::PI).abs() < 1e-4);
    let c = json(&["corner", "ratio", "--strategy", "circle", "--delta", "0.025"]);
    assert!((f(&c, "worst_ratio") - 2.001_525).abs() < 1e-5);
    let s =
        json(&["corner", "ratio", "--strategy", "stops", "--delta", "0.1", "--stops-deg", "30,60"]);
    assert_eq!(s["stops"], 3);
    let e = json(&[
        "corner",
        "ratio",
        "--strategy",
        "exprec",
        "--delta",
        "0.1",
        "--exprec",
        "appendix",
    ]);
    assert!(f(&e, "worst_ratio") >= 1.0);
}

#[test]
fn corner_collapse() {
    let v = json(&["corner", "collapse", "--ratio", "1.99"]);
    assert_eq!(v["reached"], false);
    assert!(f(&v, "farthest") <= f(&v, "bound"));
}

#[test]
fn corner_policy_with_images_and_both_solvers() {
    let dir = temp("policy");
    let v = json(&[
        "corner",
        "policy",
        "--belief",
        "normal:60,5",
        "--memory",
        "last",
        "--solver",
        "general",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert_eq!(v["general_solver"]["agrees_with_backward_induction"], true);
    assert_eq!(v["stops"], 18);
    assert!(dir.join("policy-mdp2.png").exists() && dir.join("policy-mdp2.svg").exists());
    let m1 = json(&[
        "corner",
        "policy",
        "--belief",
        "uniform:0,180",
        "--memory",
        "none",
        "--step-deg",
        "1",
    ]);
    assert_eq!(m1["stops"], 90);
    assert!(f(&m1, "expected_time") > 0.0);
}

#[test]
fn corner_simulate_is_seeded() {
    let args = [
        "corner",
        "simulate",
        "--strategy",
        "all",
        "--belief",
        "normal:60,5",
        "--truth",
        "uniform:0,180",
        "--samples",
        "500",
        "--seed",
        "3",
    ];
    let a = json(&args);
    let b = json(&args);
    assert_eq!(a, b, "the same seed gives the same output");
    let r = a["results"].as_array().unwrap();
    assert_eq!(r.len(), 5);
    for x in r {
        let (e, mc, se) =
            (f(x, "expected_time"), f(&x["monte_carlo"], "mean"), f(&x["monte_carlo"], "std_err"));
        assert!((e - mc).abs() <= 5.0 * se + 1e-9, "{x}");
    }
    let mut other = args.to_vec();
    let last = other.len() - 1;
    other[last] = "4";
    assert_ne!(json(&other), a);
}

#[test]
fn reproduce_every_id() {
    let dir = temp("repro");
    let ids = stopscan::experiment::ids();
    // The issue's list.
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

#[test]
fn table_output_is_stable() {
    let a = stopscan(&["corner", "thresholds", "--count", "3"]);
    let text = String::from_utf8(a.stdout).unwrap();
    assert_eq!(
        text,
        "scans  maximal d  c at upper bound\n-----  ---------  ----------------\n0       0.618034          1.618034\n1       1.530414          2.040287\n2       2.799395          2.155363\n"
    );
}

#[test]
fn out_file_gets_the_json() {
    let dir = temp("outfile");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("t.json");
    let out = stopscan(&["corner", "thresholds", "--count", "2", "--out", path.to_str().unwrap()]);
    assert!(out.status.success());
    let v: Value = serde_json::from_str(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(v["thresholds"].as_array().unwrap().len(), 2);
}

#[test]
fn bad_input_is_a_clear_error() {
    let dir = temp("bad");
    std::fs::create_dir_all(&dir).unwrap();
    let hist = dir.join("hist.txt");
    std::fs::write(&hist, "0 90 1\n90 oops 2\n").unwrap();
    let spec = format!("histogram:{}", hist.display());
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec!["corner", "circle", "--distance", "-1"], "--distance"),
        (vec!["corner", "circle", "--distance", "nan"], "--distance"),
        (vec!["corner", "ratio", "--strategy", "unirec", "--delta", "0"], "--delta"),
        (
            vec![
                "corner",
                "ratio",
                "--strategy",
                "stops",
                "--delta",
                "0.1",
                "--stops-deg",
                "60,30",
            ],
            "stop 2 (30°) is not above stop 1 (60°)",
        ),
        (vec!["corner", "policy", "--belief", "normal:60"], "normal:60"),
        (vec!["corner", "policy", "--belief", "beta:1,2"], "unknown kind"),
        (vec!["corner", "policy", "--belief", &spec], "hist.txt:2"),
        (vec!["corner", "policy", "--belief", "histogram:/no/such/file"], "/no/such/file"),
        (vec!["corner", "policy", "--belief", "uniform:0,180", "--step-deg", "0"], "step"),
        (vec!["corner", "policy", "--belief", "uniform:0,180", "--speed", "0"], "speed"),
        (vec!["corner", "simulate", "--strategy", "warp"], "unknown strategy"),
        (vec!["corner", "optimal", "--distance", "1", "--scans", "99"], "--scans"),
        (vec!["reproduce", "table-99"], "unknown reproduction"),
        (
            vec![
                "corner",
                "ratio",
                "--strategy",
                "unirec",
                "--delta",
                "0.1",
                "--route",
                "chord",
                "--last-step",
                "nominal",
            ],
            "arc route only",
        ),
    ];
    for (args, needle) in cases {
        let out = stopscan(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?} should fail");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{args:?}: {err:?} should mention {needle:?}");
        assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    }
}

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

/// `stopscan roi` on a text grid: every cell visited, everyone home, within Lemma 1, and a
/// replay with one animated robot per robot.
#[test]
fn roi_explores_a_grid_and_writes_record_and_replay() {
    let dir = temp("roi");
    std::fs::create_dir_all(&dir).unwrap();
    let grid = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/roi/lake.txt");
    let out = dir.join("lake.json");
    let trace = dir.join("lake.jsonl");
    let r = json(&[
        "roi",
        "--grid",
        grid.to_str().unwrap(),
        "--robots",
        "3",
        "--roi-speed",
        "0.25",
        "--roi-heading-deg",
        "90",
        "--out",
        out.to_str().unwrap(),
        "--trace",
        trace.to_str().unwrap(),
    ]);
    let events: Vec<Value> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let moves = events.iter().filter(|e| e["event"] == "move").count() as u64;
    assert_eq!(moves, r["metrics"]["moves"].as_u64().unwrap());
    assert_eq!(events.last().unwrap()["event"], "finish");
    assert!(events.iter().filter(|e| e["event"] != "finish").all(|e| e["robot"].is_u64()));
    assert_eq!(r["cells"], 53);
    assert_eq!(r["metrics"]["visited_cells"], 53);
    assert_eq!(r["metrics"]["all_home"], true);
    assert_eq!(r["bounds"]["within_lemma1"], true);
    assert!(f(&r["metrics"], "time") <= f(&r["bounds"], "lemma1_upper"));
    assert_eq!(r["robots"].as_array().unwrap().len(), 3);
    for robot in r["robots"].as_array().unwrap() {
        let cells = robot["cells"].as_array().unwrap();
        assert_eq!(cells.first(), cells.last(), "robot returns to the start");
        assert_eq!(cells.len(), robot["times"].as_array().unwrap().len());
    }
    let on_disk: Value = serde_json::from_str(&std::fs::read_to_string(&out).unwrap()).unwrap();
    assert_eq!(on_disk, r);
    let svg = std::fs::read_to_string(dir.join("lake.svg")).unwrap();
    assert_eq!(svg.matches("<animateMotion").count(), 3);
}

#[test]
fn roi_random_runs_are_seeded() {
    let dir = temp("roi-seed");
    std::fs::create_dir_all(&dir).unwrap();
    let run = |seed: &str, name: &str| {
        let p = dir.join(name);
        let o = stopscan(&[
            "roi",
            "--random",
            "150",
            "--robots",
            "4",
            "--seed",
            seed,
            "--out",
            p.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(p).unwrap()
    };
    assert_eq!(run("7", "a.json"), run("7", "b.json"), "same seed, same bytes");
    assert_ne!(run("7", "a.json"), run("8", "c.json"));
}

#[test]
fn roi_reports_bad_input_clearly() {
    let dir = temp("roi-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("bad.txt");
    std::fs::write(&bad, "S##\n#?#\n").unwrap();
    let o = stopscan(&["roi", "--grid", bad.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("bad.txt:2: unexpected '?' at column 2"), "{err}");
    let o = stopscan(&["roi", "--random", "20", "--robot-speed", "1", "--roi-speed", "1"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("must exceed the region's speed"));
    let o = stopscan(&["roi", "--random", "20", "--robots", "0"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("expected a whole number of at least 1"));
    let o = stopscan(&["roi"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("--grid FILE or --random CELLS"));
    let o = stopscan(&["roi", "--resume", "m.json", "--robots", "3"]);
    assert!(String::from_utf8_lossy(&o.stderr).contains("cannot be used with '--robots"));
    let state = dir.join("not-a-state.json");
    std::fs::write(&state, "{\"format\": 3}").unwrap();
    let o = stopscan(&["roi", "--resume", state.to_str().unwrap()]);
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("not-a-state.json:1:"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The field pipeline end to end: a runway-like rectangle (a polygon, explored through its
/// outer grid approximation), found by a lawn-mowing search, sensed by the synthetic camera
/// with a 3-of-5 vote, with a battery that forces swaps.
#[test]
fn roi_field_pipeline_finds_and_maps_a_runway() {
    let dir = temp("roi-field");
    std::fs::create_dir_all(&dir).unwrap();
    let runway = dir.join("runway.geojson");
    // 92 m × 21 m, rotated by 20°, centred on the start.
    let (c, s) = (20f64.to_radians().cos(), 20f64.to_radians().sin());
    let ring: Vec<[f64; 2]> =
        [(-46.0, -10.5), (46.0, -10.5), (46.0, 10.5), (-46.0, 10.5), (-46.0, -10.5)]
            .iter()
            .map(|&(x, y)| [x * c - y * s, x * s + y * c])
            .collect();
    let geo = serde_json::json!({"type": "Feature", "properties": {"start": [0.0, 0.0]},
        "geometry": {"type": "Polygon", "coordinates": [ring]}});
    std::fs::write(&runway, geo.to_string()).unwrap();
    let out = dir.join("field.json");
    let r = json(&[
        "roi",
        "--grid",
        runway.to_str().unwrap(),
        "--cell-m",
        "4",
        "--camera",
        "--search-box",
        "-12,-14,0,14",
        "--launch",
        "-12,-14",
        "--battery-s",
        "720",
        "--out",
        out.to_str().unwrap(),
    ]);
    let m = &r["metrics"];
    assert_eq!(m["all_home"], true);
    assert!(
        r["robots"][0]["battery_swaps"].as_u64().unwrap() >= 1,
        "12-minute batteries do not last"
    );
    assert!(f(m, "iou") > 0.7, "IoU {}", m["iou"]);
    assert!(m["c_out"].as_u64().unwrap() > m["c_in"].as_u64().unwrap());
    assert!(r["failures"].as_array().unwrap().is_empty());
}

/// Terminate a mission mid-way (SIGKILL), resume it from its state file: the run finishes
/// with exactly the record of an uninterrupted run (nothing lost, nothing repeated).
#[test]
fn roi_mission_survives_kill_and_resume() {
    let dir = temp("roi-kill");
    std::fs::create_dir_all(&dir).unwrap();
    let state = dir.join("mission.json");
    let whole = dir.join("whole.json");
    let resumed = dir.join("resumed.json");
    let (whole_trace, trace) = (dir.join("whole.jsonl"), dir.join("resumed.jsonl"));
    let args =
        ["roi", "--random", "400", "--robots", "3", "--roi-speed", "0.2", "--battery-s", "150"];
    let o = stopscan(
        &[&args[..], &["--out", whole.to_str().unwrap(), "--trace", whole_trace.to_str().unwrap()]]
            .concat(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // The state after every step, so that the kill lands mid-mission; the trace goes on past
    // the last state written.
    let mut child = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(args)
        .args(["--state", state.to_str().unwrap(), "--out", resumed.to_str().unwrap()])
        .args(["--state-interval", "0", "--trace", trace.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .spawn()
        .unwrap();
    // Wait for some steps to be written, then kill.
    let steps = |p: &PathBuf| -> u64 {
        std::fs::read_to_string(p)
            .ok()
            .and_then(|t| serde_json::from_str::<Value>(&t).ok())
            .and_then(|v| v["mission"]["team"]["steps"].as_u64())
            .unwrap_or(0)
    };
    let t0 = std::time::Instant::now();
    while steps(&state) < 40 {
        assert!(t0.elapsed().as_secs() < 120, "the mission never wrote its state");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let at_kill = steps(&state);
    let saved: Value = serde_json::from_str(&std::fs::read_to_string(&state).unwrap()).unwrap();
    let done =
        saved["mission"]["team"]["robots"].as_array().unwrap().iter().all(|r| r["done"] == true);
    assert!(
        !done,
        "killed after the mission ended ({at_kill} steps); the test needs a longer mission"
    );
    assert!(!resumed.exists(), "no run record before the end");
    // From another directory and without --trace: the state remembers both.
    let o = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(["roi", "--resume", state.to_str().unwrap()])
        .current_dir(std::env::temp_dir())
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read(&whole).unwrap(),
        std::fs::read(&resumed).unwrap(),
        "the resumed mission differs from the uninterrupted one (killed at step {at_kill})"
    );
    assert_eq!(
        std::fs::read_to_string(&whole_trace).unwrap(),
        std::fs::read_to_string(&trace).unwrap(),
        "the resumed trace differs from the uninterrupted one: events lost or repeated"
    );
    assert!(steps(&state) > at_kill);
    assert_no_temporary_files(&dir);
}

/// With the default interval the state is written at most once a second and at the end; a
/// mission resumed from its final state ends with the same record.
#[test]
fn roi_state_is_written_sparingly_and_at_the_end() {
    let dir = temp("roi-interval");
    std::fs::create_dir_all(&dir).unwrap();
    let (state, a, b) = (dir.join("s.json"), dir.join("a.json"), dir.join("b.json"));
    let args = ["roi", "--random", "3000", "--robots", "4"];
    let o = stopscan(
        &[&args[..], &["--state", state.to_str().unwrap(), "--out", a.to_str().unwrap()]].concat(),
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let saved: Value = serde_json::from_str(&std::fs::read_to_string(&state).unwrap()).unwrap();
    assert!(
        saved["mission"]["team"]["robots"].as_array().unwrap().iter().all(|r| r["done"] == true)
    );
    let o = stopscan(&["roi", "--resume", state.to_str().unwrap(), "--out", b.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
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

/// A failed command: exit status 2, the needles in standard error, no panic.
fn fails(args: &[&str], needles: &[&str]) -> String {
    let out = stopscan(args);
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{args:?} should fail: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: {err:?} should mention {n:?}");
    }
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    err
}

fn fixture(path: &str) -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures")
        .join(path)
        .to_str()
        .unwrap()
        .to_string()
}

/// Work above a limit is refused at once, before anything is allocated, with the limit and
/// the way around it.
#[test]
fn size_limits_are_checked_before_any_work() {
    let dir = temp("limits");
    std::fs::create_dir_all(&dir).unwrap();
    let obs = dir.join("obs.txt");
    std::fs::write(&obs, "30\n60\n").unwrap();
    let sq = dir.join("sq.wkt");
    std::fs::write(&sq, "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0))\n").unwrap();
    let (obs, sq, lake) = (obs.to_str().unwrap(), sq.to_str().unwrap(), fixture("roi/lake.txt"));
    let observed = format!("observed:{obs},1e-9");
    let out = dir.join("x.geojson");
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (vec!["corner", "policy", "--belief", &observed], vec!["at least 0.01°", "18000"]),
        (
            vec!["corner", "ratio", "--strategy", "unirec", "--delta", "1e-9"],
            vec!["1,570,796,327 UNIREC stops", "10,000,000", "--allow-large"],
        ),
        (
            vec![
                "visibility",
                "--env",
                sq,
                "--at",
                "5,5",
                "--range",
                "1",
                "--arc-tolerance",
                "1e-15",
            ],
            vec!["--arc-tolerance 1e-15 is below R·1e-9"],
        ),
        (
            vec![
                "visibility",
                "--env",
                sq,
                "--at",
                "5,5",
                "--range",
                "1",
                "--arc-tolerance",
                "1e-300",
            ],
            vec!["--arc-tolerance 1e-300 is below R·1e-9"],
        ),
        (
            vec!["corner", "simulate", "--strategy", "unirec", "--samples", "100000000000"],
            vec!["--samples 100000000000", "10,000,000", "--allow-large"],
        ),
        (
            vec!["corner", "simulate", "--strategy", "unirec", "--distance", "1e9"],
            vec!["UNIREC stops", "--allow-large"],
        ),
        (
            vec![
                "corner",
                "policy",
                "--belief",
                "uniform:0,180",
                "--memory",
                "none",
                "--step-deg",
                "1e-9",
            ],
            vec!["MDP1 handles at most 1000000"],
        ),
        (vec!["roi", "--grid", &lake, "--camera", "--frames", "100000"], vec!["between 1 and 99"]),
        (
            vec![
                "roi",
                "--grid",
                &lake,
                "--search-box=-1000000,-1000000,1000000,1000000",
                "--launch",
                "0,0",
            ],
            vec!["4,000,004,000,001 cells", "the limit is 4,000,000", "--allow-large"],
        ),
        (vec!["roi", "--random", "50", "--robots", "100000000000"], vec!["the limit is 10,000"]),
        (vec!["roi", "--random", "1000000000"], vec!["the limit is 4,000,000"]),
        (vec!["bench", "circle", "--n", "10000000000"], vec!["the limit is 1,000,000"]),
        (vec!["bench", "ratio", "--n", "1000000000"], vec!["the limit is 10,000,000"]),
        (vec!["bench", "explore", "--n", "1000000"], vec!["the limit is 10,000"]),
        (vec!["bench", "roi", "--n", "1e9"], vec!["the limit is 4,000,000"]),
        (
            vec!["generate", "spiral", "--size", "100000000", "-o", out.to_str().unwrap()],
            vec!["--size 100000000", "the limit is 10,000"],
        ),
        (
            vec!["generate", "office", "--size", "100000", "-o", out.to_str().unwrap()],
            vec!["the limit is 10,000"],
        ),
    ];
    for (args, needles) in cases {
        let t = std::time::Instant::now();
        fails(&args, &needles);
        assert!(t.elapsed().as_secs() < 20, "{args:?} took {:?}", t.elapsed());
    }
}

/// `--allow-large` lifts a soft limit.
#[test]
fn allow_large_lifts_a_soft_limit() {
    let dir = temp("allow-large");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("office.geojson");
    let args =
        ["generate", "office", "--size", "1", "--desks", "10001", "-o", out.to_str().unwrap()];
    fails(&args, &["--desks 10001", "the limit is 10,000"]);
    // One room holds a few desks: the others are skipped, quickly.
    let o = stopscan(&[&args[..], &["--allow-large"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// Monte Carlo runs in fixed chunks merged in order: the estimate depends on the seed only,
/// not on the number of threads.
#[test]
fn monte_carlo_does_not_depend_on_the_thread_count() {
    let args =
        ["corner", "simulate", "--strategy", "unirec", "--samples", "70000", "--format", "json"];
    let run = |threads: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_stopscan"))
            .args(args)
            .env("RAYON_NUM_THREADS", threads)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        o.stdout
    };
    assert_eq!(run("1"), run("3"));
}

/// Inputs that used to be accepted or ignored without a word.
#[test]
fn malformed_or_ignored_inputs_are_errors() {
    let dir = temp("ignored");
    std::fs::create_dir_all(&dir).unwrap();
    let o = dir.join("o.geojson");
    let o = o.to_str().unwrap();
    for start in [r#""here""#, "[1]", "null", r#"["1","2"]"#, "[1,2,3]"] {
        let f = dir.join("start.geojson");
        std::fs::write(
            &f,
            format!(
                r#"{{"type":"Feature","properties":{{"start":{start}}},"geometry":{{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,10],[0,10]]]}}}}"#
            ),
        )
        .unwrap();
        fails(
            &["map", "import", f.to_str().unwrap(), "-o", o],
            &["start.geojson: properties.start must be [x, y]", start],
        );
    }
    let wkt = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_str().unwrap().to_string()
    };
    let two =
        wkt("two.wkt", "POLYGON ((0 0, 10 0, 10 10, 0 0))\nPOLYGON ((20 0, 30 0, 30 10, 20 0))\n");
    fails(&["map", "import", &two, "-o", o], &["two.wkt:2: unexpected text after the POLYGON"]);
    let tail = wkt("tail.wkt", "POLYGON ((0 0, 10 0, 10 10, 0 0)) garbage\n");
    fails(&["map", "import", &tail, "-o", o], &["tail.wkt:1: unexpected text", "garbage"]);
    // ROS maps: occupied_thresh is read and checked.
    let yaml = std::fs::read_to_string(fixture("ros-maps/turtlebot3_world.yaml")).unwrap();
    std::fs::copy(fixture("ros-maps/turtlebot3_world.pgm"), dir.join("turtlebot3_world.pgm"))
        .unwrap();
    for (name, value, needle) in [
        ("nan.yaml", ".nan", "occupied_thresh: expected a number"),
        ("low.yaml", "0.1", "occupied_thresh 0.1 is not above free_thresh 0.196"),
    ] {
        let edited: String = yaml
            .lines()
            .map(|l| {
                if l.starts_with("occupied_thresh") {
                    format!("occupied_thresh: {value}\n")
                } else {
                    format!("{l}\n")
                }
            })
            .collect();
        let p = dir.join(name);
        std::fs::write(&p, edited).unwrap();
        fails(&["map", "import", p.to_str().unwrap(), "-o", o], &[name, needle]);
    }
    // --start and the grid's S; --start with a polygon or a random region.
    let g = wkt("g.txt", "S##\n###\n");
    fails(&["roi", "--grid", &g, "--start", "1,2"], &["g.txt:1:", "disagree"]);
    let sq = wkt("sq.wkt", "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0))\n");
    fails(&["roi", "--grid", &sq, "--start", "1,2"], &["applies to masks and text grids"]);
    fails(&["roi", "--random", "30", "--start", "1,2"], &["--start applies to --grid"]);
    // range_limited needs a range; the camera needs frames; --frames needs the camera.
    fails(&["explore", "--env", &sq, "--strategy", "range_limited"], &["needs --range"]);
    let lake = fixture("roi/lake.txt");
    fails(&["roi", "--grid", &lake, "--camera", "--frames", "0"], &["'--frames <FRAMES>'"]);
    fails(&["roi", "--grid", &lake, "--frames", "7"], &["--camera"]);
    fails(&["visibility", "--env", &sq, "--at", "5,5", "--arc-tolerance", "0.1"], &["--range"]);
}

/// Every output is written atomically, checked before any work, and named in errors; file
/// outputs need their directory, directory outputs are created one level deep.
#[test]
fn outputs_are_checked_first_and_written_atomically() {
    let dir = temp("outputs");
    std::fs::create_dir_all(dir.join("envs")).unwrap();
    std::fs::write(dir.join("envs/a.wkt"), "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0))\n").unwrap();
    let d = dir.join("taken");
    std::fs::create_dir_all(&d).unwrap();
    let ds = d.to_str().unwrap();
    let envs = dir.join("envs");
    for args in [
        vec!["corner", "thresholds", "--out", ds],
        vec!["roi", "--random", "30", "--state", ds],
        vec!["explore", "--env", envs.to_str().unwrap(), "--out", ds],
    ] {
        fails(&args, &[&format!("cannot write {ds}: it is a directory")]);
    }
    fails(
        &["corner", "optimal", "--distance", "3", "--scans", "1", "--out", "/nonexistent/d/x.json"],
        &["cannot write /nonexistent/d/x.json: directory /nonexistent/d does not exist"],
    );
    fails(&["roi", "--random", "30", "--state", "/nonexistent/s.json"], &["does not exist"]);
    let nested = dir.join("a/b");
    fails(
        &["corner", "circle", "--distance", "3", "--out", nested.to_str().unwrap()],
        &["cannot create output directory", "does not exist"],
    );
    let new = dir.join("new");
    let o = stopscan(&["corner", "circle", "--distance", "3", "--out", new.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(new.join("circle.svg").exists() && new.join("circle.json").exists());
    // The user's extension is kept whole.
    let ab = dir.join("a.b");
    assert!(stopscan(&["corner", "thresholds", "--out", ab.to_str().unwrap()]).status.success());
    assert!(ab.exists());
    fails(&["map", "import", "x.wkt", "-o", "y.geojson", "--out", "z"], &["--out is not used"]);
    assert_no_temporary_files(&dir);
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

/// A file of a sweep that does not load is a row with its error and a warning; the sweep
/// goes on.
#[test]
fn a_bad_file_does_not_end_a_sweep() {
    let dir = temp("sweep-bad");
    std::fs::create_dir_all(dir.join("envs")).unwrap();
    std::fs::write(dir.join("envs/a.wkt"), "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0))\n").unwrap();
    std::fs::write(dir.join("envs/c.wkt"), "POLYGON ((0 0, 10 0, 0 0))\n").unwrap();
    let csv_path = dir.join("sweep.csv");
    let o = stopscan(&[
        "explore",
        "--env",
        dir.join("envs").to_str().unwrap(),
        "--out",
        csv_path.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stderr).contains("warning: c.wkt"));
    let text = std::fs::read_to_string(&csv_path).unwrap();
    let mut rows = csv::Reader::from_reader(text.as_bytes());
    let header = rows.headers().unwrap().clone();
    let err = header.iter().position(|h| h == "error").unwrap();
    let rows: Vec<csv::StringRecord> = rows.records().map(Result::unwrap).collect();
    assert_eq!(rows.len(), 2);
    assert!(rows[0][0].starts_with("a.wkt") && rows[0][err].is_empty(), "{text}");
    assert!(rows[1][0].starts_with("c.wkt") && rows[1][err].contains("ring 0"), "{text}");
    fails(
        &["explore", "--env", dir.join("envs").to_str().unwrap(), "--strategy", "range_limited"],
        &["needs --range"],
    );
}

/// Messages echo numbers compactly, name the line, one cause at a time, in the user's units.
#[test]
fn messages_are_compact_and_precise() {
    let dir = temp("messages");
    std::fs::create_dir_all(&dir).unwrap();
    let sq = dir.join("sq.wkt");
    std::fs::write(&sq, "POLYGON ((0 0, 10 0, 10 10, 0 10, 0 0))\n").unwrap();
    let sq = sq.to_str().unwrap();
    let err = fails(&["visibility", "--env", sq, "--at", "1e300,5"], &["(1e300, 5)"]);
    assert!(err.len() < 200, "{err}");
    fails(&["corner", "circle", "--distance=-1e300"], &["got -1e300"]);
    fails(
        &["roi", "--random", "50", "--robots", "-1"],
        &["'--robots <ROBOTS>'", "expected a whole number of at least 1"],
    );
    fails(&["corner", "simulate", "--samples", "-5"], &["at least 1"]);
    let hist = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        format!("histogram:{}", p.display())
    };
    let e = fails(
        &["corner", "policy", "--belief", &hist("h1.txt", "0 90 1\n80 180 1\n")],
        &["h1.txt:2: bucket [80, 180] overlaps [0, 90] of line 1"],
    );
    assert!(!e.contains(":0:"), "{e}");
    fails(
        &["corner", "policy", "--belief", &hist("h2.txt", "0 90 -1\n90 180 1\n")],
        &["h2.txt:1: bucket [0, 90]: weight -1 is negative"],
    );
    let e = fails(
        &["corner", "policy", "--belief", &hist("h4.txt", "0 90 0\n")],
        &["h4.txt: the weights sum to 0"],
    );
    assert!(!e.contains(":0:"), "{e}");
    let e = fails(
        &["corner", "policy", "--belief", &hist("h5.txt", "# nothing\n")],
        &["h5.txt: the histogram has no buckets"],
    );
    assert!(!e.contains(":0:"), "{e}");
    for (stops, needle) in [
        ("30,20", "--stops-deg: stop 2 (20°) is not above stop 1 (30°)"),
        ("-5", "--stops-deg: stop 1 is -5°"),
        ("30,95,120", "stop 3 (120°) follows stop 2 (95°), which already reaches the corner"),
    ] {
        fails(
            &["corner", "ratio", "--strategy", "stops", "--delta", "0.1", "--stops-deg", stops],
            &[needle],
        );
    }
    let png = dir.join("bad.png");
    std::fs::write(&png, b"\x89QNG\r\n\x1a\nnot an image").unwrap();
    let e = fails(&["roi", "--grid", png.to_str().unwrap()], &["not a PGM (P5/P2) or PNG"]);
    assert!(!e.contains("UTF-8"), "{e}");
    let empty = dir.join("empty.txt");
    std::fs::write(&empty, "").unwrap();
    for cmd in ["bench", "visibility"] {
        let mut args =
            if cmd == "bench" { vec!["bench", "visibility"] } else { vec!["visibility"] };
        args.extend(["--env", sq, "--queries", empty.to_str().unwrap()]);
        fails(&args, &["empty.txt: no query points"]);
    }
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
