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
    for f in ["run.json", "circle-ratio.svg", "circle-ratio.png"] {
        assert!(dir.join(f).metadata().unwrap().len() > 100, "{f}");
    }
    let run: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("run.json")).unwrap()).unwrap();
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
            "not finite, positive and above",
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
    assert!(String::from_utf8_lossy(&o.stderr).contains("at least one robot"));
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
    let args =
        ["roi", "--random", "400", "--robots", "3", "--roi-speed", "0.2", "--battery-s", "150"];
    let o = stopscan(&[&args[..], &["--out", whole.to_str().unwrap()]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let mut child = Command::new(env!("CARGO_BIN_EXE_stopscan"))
        .args(args)
        .args(["--state", state.to_str().unwrap(), "--out", resumed.to_str().unwrap()])
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
    let o = stopscan(&["roi", "--resume", state.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(
        std::fs::read(&whole).unwrap(),
        std::fs::read(&resumed).unwrap(),
        "the resumed mission differs from the uninterrupted one (killed at step {at_kill})"
    );
    assert!(steps(&state) > at_kill);
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
