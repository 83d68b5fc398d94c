//! `stopscan explore`: one environment, a sweep of a folder, and `generate` to make inputs.

use crate::common;

use serde_json::Value;

use common::{f, fails, json, stopscan, temp};

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

/// `-o /dev/stdout` pipes a file output on; a rename over it (or over `/dev/null`) would have
/// replaced the device, as root, with a regular file.
#[cfg(unix)]
#[test]
fn a_file_output_can_be_standard_output() {
    let g = stopscan(&["generate", "spiral", "--size", "5", "-o", "/dev/stdout"]);
    assert!(g.status.success(), "{}", String::from_utf8_lossy(&g.stderr));
    // The GeoJSON first, then the summary line.
    let mut values = serde_json::Deserializer::from_slice(&g.stdout).into_iter::<Value>();
    let geojson = values.next().expect("GeoJSON on standard output").unwrap();
    assert_eq!(geojson["type"], "Feature", "{geojson}");
    let rest = String::from_utf8_lossy(&g.stdout[values.byte_offset()..]).into_owned();
    assert!(rest.contains("/dev/stdout: 14 vertices"), "{rest}");
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
    // A robot in a folder sweep is refused, not silently ignored.
    for robot in [["--robot-radius", "0.2"], ["--min-window", "0.5"]] {
        let r = stopscan(&[
            "explore",
            "--env",
            dir.to_str().unwrap(),
            "--strategy",
            "all",
            robot[0],
            robot[1],
            "--out",
            csv_path.to_str().unwrap(),
        ]);
        assert!(!r.status.success());
        let e = String::from_utf8_lossy(&r.stderr);
        assert!(e.contains("a folder sweep runs a point robot") && e.contains(robot[0]), "{e}");
    }
    let b = json(&["bench", "explore", "--n", "20"]);
    assert_eq!(b["runs_failing_checks"], 0, "{b}");
    assert_eq!(b["n"], 20);
    let bad = stopscan(&["explore", "--env", env.to_str().unwrap(), "--strategy", "teleport"]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("unknown strategy"));
    let bad = stopscan(&["explore", "--env", env.to_str().unwrap(), "--start", "1000,1000"]);
    assert!(String::from_utf8_lossy(&bad.stderr).contains("outside the free space"));
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

/// `--simplify` reaches the ROS map loader, for one file and for a sweep; bad values name
/// the flag.
#[test]
fn explore_simplifies_ros_maps_as_map_import_does() {
    let dir = temp("simplify");
    std::fs::create_dir_all(&dir).unwrap();
    let map = common::fixture("ros-maps/turtlebot3_world.yaml");
    let out = dir.join("run.json");
    let quick = ["--optimum-seconds", "0", "--bounds-seconds", "0", "--greedy-max-vertices", "0"];
    let vertices = |tol: Option<&str>| {
        let geo = dir.join("m.geojson");
        let mut import = vec!["map", "import", &map, "-o", geo.to_str().unwrap()];
        // Without the rule's pocket term, whose share of a 20 m² map is 0.1 m².
        let mut run =
            vec!["explore", "--env", &map, "--out", out.to_str().unwrap(), "--min-pocket", "0"];
        run.extend(quick);
        if let Some(t) = tol {
            import.extend(["--simplify", t]);
            run.extend(["--simplify", t]);
        }
        let (i, r) = (json(&import), json(&run));
        assert_eq!(r["environment"]["vertices"], i["vertices"], "{tol:?}");
        // The default window rule on a map closes windows shorter than two cells (pixel
        // steps of a traced wall), so a little is left unseen without simplification.
        assert!(f(&r["metrics"], "coverage") > 0.999, "{tol:?}");
        i["vertices"].as_u64().unwrap()
    };
    let (default, traced, wide) = (vertices(None), vertices(Some("0")), vertices(Some("0.15")));
    assert!(wide < default && default < traced, "{wide} < {default} < {traced}");
    // A start a hair from a wall stays inside the free space (the loader protects it).
    let r = json(&[
        "explore",
        "--env",
        &map,
        "--out",
        out.to_str().unwrap(),
        "--start",
        "-2,-0.5",
        "--simplify",
        "0.2",
        "--optimum-seconds",
        "0",
        "--bounds-seconds",
        "0",
    ]);
    assert_eq!(r["robots"][0]["path"][0], serde_json::json!([-2.0, -0.5]));
    // A sweep reads its maps with the flag too.
    let sweep_dir = dir.join("maps");
    std::fs::create_dir_all(&sweep_dir).unwrap();
    for f in ["turtlebot3_world.yaml", "turtlebot3_world.pgm"] {
        std::fs::copy(common::fixture(&format!("ros-maps/{f}")), sweep_dir.join(f)).unwrap();
    }
    let reflex = |tol: &str| {
        let csv = dir.join(format!("sweep-{tol}.csv"));
        let mut args =
            vec!["explore", "--env", sweep_dir.to_str().unwrap(), "--out", csv.to_str().unwrap()];
        args.extend(["--simplify", tol, "--bounds-seconds", "0"]);
        let o = stopscan(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read_to_string(csv).unwrap()
    };
    assert_ne!(reflex("0"), reflex("0.15"));
    for bad in ["-1", "nan", "inf", "-inf"] {
        fails(
            &["explore", "--env", &map, "--simplify", bad],
            &["--simplify must be a finite non-negative number of metres"],
        );
        fails(
            &["explore", "--env", sweep_dir.to_str().unwrap(), "--simplify", bad],
            &["--simplify must be a finite non-negative number of metres"],
        );
    }
}

/// A robot with a footprint on a real map: the record states the footprint, the sensor and
/// its window rule, and the unreachable area; the path keeps the radius from the walls
/// (checked by the simulator against the configuration space).
#[test]
fn explore_with_a_footprint_and_a_window_rule() {
    let map = common::fixture("ros-maps/turtlebot3_world.yaml");
    // The records go to a temporary folder, not to run.json in the crate's directory.
    let dir = temp("footprint-rule");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.json");
    let r = json(&[
        "--out",
        out.to_str().unwrap(),
        "explore",
        "--env",
        &map,
        "--robot-radius",
        "0.2",
        "--beams",
        "720",
        "--range",
        "20",
        "--strategy",
        "cost_aware",
        "--optimum-seconds",
        "0",
        "--bounds-seconds",
        "1",
    ]);
    assert!(r.get("error").is_none(), "{r}");
    let robot = &r["robot"];
    assert_eq!(robot["footprint"]["kind"], "disc");
    assert!(f(robot, "clearance") > 0.2);
    let (vis, lost) = (f(robot, "visible_from_reachable_area"), f(robot, "unreachable_area"));
    assert!(vis > 0.0 && lost >= 0.0);
    assert!(f(robot, "coverage_of_reachable") > 0.9, "{robot}");
    // What is left unseen splits into the body space and crevices narrower than the robot.
    let (cov, body_cov) = (f(robot, "coverage_of_reachable"), f(robot, "coverage_of_body_space"));
    let crevices = f(robot, "unseen_in_crevices");
    assert!(body_cov <= 1.0 && f(robot, "body_space_area") > 0.0, "{robot}");
    assert!(crevices >= 0.0 && crevices <= (1.0 - cov) * vis + 1e-6, "{robot}");
    // Never more than what the run left unseen of the visible area, as the metrics count it.
    let unseen = vis - f(&r["metrics"], "covered_area");
    assert!(crevices <= unseen + 1e-9, "{r}");
    // min_window defaults to the robot's width (the map's two cells are 0.1 m).
    assert_eq!(f(&r["sensor"], "min_window"), 0.4);
    assert_eq!(r["sensor"]["beams"], 720);
    assert!(r["sensor"]["window_rule"].as_str().unwrap().contains("d·2π/720"));
    // The pocket term is on by default on a map: 0.5% of the area seen, at most 2 m², and
    // the pockets left hold at most 1% of it in all.
    assert_eq!(f(&r["sensor"], "min_pocket"), 0.005);
    assert_eq!(f(&r["sensor"], "pocket_cap"), 2.0);
    assert_eq!(f(&r["sensor"], "pocket_budget"), 0.01);
    assert!(r["sensor"]["windows_into_small_pockets"].is_u64(), "{r}");
    assert!(r["sensor"]["window_rule"].as_str().unwrap().contains("(pocket_cap)"));
    assert!(r["sensor"]["window_rule"].as_str().unwrap().contains("0.01 of the area seen"));
    // Without a footprint on a polygon, nothing is added to the record.
    let plain = json(&[
        "--out",
        out.to_str().unwrap(),
        "explore",
        "--env",
        &common::fixture("office.geojson"),
    ]);
    assert!(plain.get("robot").is_none());
    assert!(plain["sensor"].get("window_rule").is_none());
    assert!(plain["sensor"].get("min_pocket").is_none());
}

#[test]
fn footprint_flags_are_checked() {
    let map = common::fixture("office.geojson");
    fails(&["explore", "--env", &map, "--robot-radius", "-1"], &["--robot-radius", "-1"]);
    fails(
        &["explore", "--env", &map, "--footprint", "[[0,0],[1,0]]"],
        &["--footprint", "at least 3"],
    );
    fails(&["explore", "--env", &map, "--footprint", "square"], &["--footprint", "[[x, y]"]);
    fails(&["explore", "--env", &map, "--min-window", "-2"], &["--min-window", "-2"]);
    fails(&["explore", "--env", &map, "--min-pocket", "1.5"], &["--min-pocket", "1.5"]);
    fails(&["explore", "--env", &map, "--pocket-cap", "-1"], &["--pocket-cap", "-1"]);
    fails(&["explore", "--env", &map, "--pocket-budget", "2"], &["--pocket-budget", "2"]);
    fails(&["explore", "--env", &map, "--pocket-budget", "NaN"], &["--pocket-budget", "NaN"]);
    fails(&["explore", "--env", &map, "--beams", "0"], &["--beams"]);
    // A robot too big for the start the file gives.
    fails(
        &["explore", "--env", &map, "--robot-radius", "3"],
        &["office.geojson", "footprint", "fit"],
    );
    // One that fits nowhere on a map without a start.
    let ros = common::fixture("ros-maps/turtlebot3_world.yaml");
    fails(
        &["explore", "--env", &ros, "--robot-radius", "3"],
        &["turtlebot3_world.yaml", "fits nowhere"],
    );
}

#[test]
fn raw_scans_from_a_simulated_lidar() {
    let map = common::fixture("ros-maps/turtlebot3_world.yaml");
    let dir = temp("raw-scans");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.json");
    let run = |seed: &str| {
        let args = [
            "--seed",
            seed,
            "explore",
            "--env",
            &map,
            "--robot-radius",
            "0.2",
            "--sensor",
            "lidar:beams=360,sigma=0.01,dropout=0.02",
            "--odometry-drift",
            "0.01",
            "--out",
            out.to_str().unwrap(),
        ];
        // The table on standard output; the record from the file.
        let printed = stopscan(&args);
        assert!(printed.status.success(), "{}", String::from_utf8_lossy(&printed.stderr));
        (String::from_utf8(printed.stdout).unwrap(), std::fs::read(&out).unwrap())
    };
    let (text, bytes) = run("5");
    let r: Value = serde_json::from_slice(&bytes).unwrap();
    let raw = &r["raw_scans"];
    assert_eq!(raw["lidar"]["beams"], 360);
    assert_eq!(f(&raw["lidar"], "dropout"), 0.02);
    assert_eq!(f(raw, "odometry_drift"), 0.01);
    assert_eq!(
        raw["stops"].as_array().unwrap().len() as u64,
        r["metrics"]["scans"].as_u64().unwrap()
    );
    assert!(raw["cleaning"]["dropouts"].as_u64().unwrap() > 0, "{raw}");
    // The sensor's range and beams are the lidar's; the record measures the ground truth.
    assert_eq!(f(&r["sensor"], "range"), 20.0);
    assert_eq!(r["sensor"]["beams"], 360);
    // The rule states how walls seen apart by noise close windows, at the planning margin.
    let rule = r["sensor"]["window_rule"].as_str().unwrap();
    assert!(rule.contains("wall_tolerance"), "{rule}");
    assert!(rule.contains(&format!("{} m", f(raw, "planning_margin"))), "{rule}");
    assert!(f(&r["robot"], "coverage_of_reachable") > 0.99, "{r}");
    // Byte-identical for the same seed.
    assert_eq!(run("5").1, bytes);
    // The table prints the worst and mean position error at a stop: those of the stops'
    // true and believed poses in the record, recomputed here from the poses themselves.
    let errors: Vec<f64> = raw["stops"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let (t, e) = (&s["truth"], &s["estimate"]);
            (f(e, "x") - f(t, "x")).hypot(f(e, "y") - f(t, "y"))
        })
        .collect();
    let max = errors.iter().copied().fold(0.0, f64::max);
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    let value = |name: &str| -> String {
        let line = text.lines().find(|l| l.starts_with(name)).unwrap_or_else(|| panic!("{text}"));
        line.split_whitespace().last().unwrap().to_string()
    };
    assert_eq!(value("position error at a stop, max (m)"), format!("{max:.3}"), "{text}");
    assert_eq!(value("position error at a stop, mean (m)"), format!("{mean:.3}"), "{text}");
    assert_eq!(
        value("scan matches tied into the pose graph"),
        raw["graph_links"].to_string(),
        "{text}"
    );
}

/// On raw scans the window strategies close window parts that open onto small pockets behind
/// walls seen, or onto a wall seen right behind them (noise left a window a few centimetres in
/// front of a wall another scan saw), count them in the record and the table, and still see
/// the map; with an exact sensor they do not.
#[test]
fn window_strategies_close_slivers_in_front_of_walls_seen_and_say_so() {
    for (strategy, seed) in [("cost_aware", "2"), ("depth_first", "3")] {
        slivers_in_front_of_walls_seen_are_closed(strategy, seed);
    }
}

fn slivers_in_front_of_walls_seen_are_closed(strategy: &str, seed: &str) {
    let (map, out) = depot_and_record(&format!("walled-pockets-{strategy}"));
    // `strategy` on depot with the flags `extra`: the table and the record.
    let run = |extra: &[&str]| {
        let mut args = vec!["--seed", seed, "explore", "--env", &map, "--strategy", strategy];
        args.extend(["--robot-radius", "0.2", "--out", out.to_str().unwrap()]);
        args.extend(["--optimum-seconds", "0", "--bounds-seconds", "0"]);
        args.extend(["--greedy-max-vertices", "0"]);
        args.extend(extra);
        let printed = stopscan(&args);
        assert!(printed.status.success(), "{}", String::from_utf8_lossy(&printed.stderr));
        let r: Value = serde_json::from_slice(&std::fs::read(&out).unwrap()).unwrap();
        (String::from_utf8(printed.stdout).unwrap(), r)
    };
    let (text, r) =
        run(&["--sensor", "lidar:beams=720,sigma=0.02,dropout=0.01", "--odometry-drift", "0.01"]);
    // Each count is in the record, at least 1, and on the table's row of that label.
    let counted = |key: &str, label: &str| {
        let n = r["sensor"][key].as_u64().unwrap_or(0);
        assert!(n >= 1, "{key}: {}", r["sensor"]);
        let row = text
            .lines()
            .find(|l| l.starts_with(label))
            .unwrap_or_else(|| panic!("{label}: {text}"));
        assert_eq!(row.split_whitespace().last(), Some(n.to_string().as_str()), "{text}");
    };
    counted("windows_into_walled_pockets", "window parts into small pockets behind walls");
    // Gaps in a wall seen at a slant, read as the wall.
    counted("windows_as_gaps_in_a_wall", "windows read as gaps in a wall seen at a slant");
    assert!(f(&r["robot"], "coverage_of_reachable") > 0.99, "{}", r["robot"]);
    // With an exact sensor both rules are off (such pockets are real spaces there, and its
    // walls have no gaps).
    let (_, r) = run(&["--range", "20"]);
    assert!(r["sensor"]["windows_into_small_pockets"].is_u64(), "{}", r["sensor"]);
    assert!(r["sensor"].get("windows_into_walled_pockets").is_none(), "{}", r["sensor"]);
    assert!(r["sensor"].get("windows_as_gaps_in_a_wall").is_none(), "{}", r["sensor"]);
}

/// The depot fixture, and where a run's record goes in a fresh directory named `name`.
fn depot_and_record(name: &str) -> (String, std::path::PathBuf) {
    let dir = temp(name);
    std::fs::create_dir_all(&dir).unwrap();
    (common::fixture("ros-maps/depot.yaml"), dir.join("run.json"))
}

/// `cost_aware` on `map` from raw scans, with `bench floors`' robot and the lidar and
/// drift: the run record, written to `out`.
fn raw_cost_aware_run(map: &str, seed: &str, extra: &[&str], out: &std::path::Path) -> Value {
    raw_run(map, "cost_aware", seed, extra, out)
}

/// [`raw_cost_aware_run`] with another strategy.
fn raw_run(map: &str, strategy: &str, seed: &str, extra: &[&str], out: &std::path::Path) -> Value {
    let mut args = vec!["--seed", seed, "explore", "--env", map, "--strategy", strategy];
    args.extend(extra);
    args.extend(["--robot-radius", "0.2", "--range", "20", "--scan-time", "30"]);
    args.extend(["--speed", "0.5", "--optimum-seconds", "0", "--bounds-seconds", "0"]);
    args.extend(["--greedy-max-vertices", "0", "--odometry-drift", "0.01"]);
    args.extend(["--sensor", "lidar:beams=720,max=20,sigma=0.02,dropout=0.01"]);
    args.extend(["--out", out.to_str().unwrap()]);
    let printed = stopscan(&args);
    assert!(printed.status.success(), "{}", String::from_utf8_lossy(&printed.stderr));
    serde_json::from_slice(&std::fs::read(out).unwrap()).unwrap()
}

/// Relays. On depot `range_limited`'s first trip runs along the hall, to where the first
/// scan's walls are little more than the hall's long sides: ICP cannot place the scan there
/// along the hall, and it kept odometry's pose, 0.2 to 0.3 m off, and every later stop
/// aligned to the walls it put in the wrong place. With relays the robot stops on the way
/// where a scan is predicted to be placed, and every stop stays within 0.1 m. The record
/// counts the relay among the scans, flags its stop, and lists it among the scans taken.
/// (`cost_aware` made that trip too until window parts onto walls seen were closed: the
/// window it went for was a sliver along a wall.)
#[test]
fn raw_scans_relay_on_a_trip_to_where_a_scan_cannot_be_placed() {
    let (map, out) = depot_and_record("relays");
    for seed in ["3", "4"] {
        let on = raw_run(&map, "range_limited", seed, &[], &out);
        let off = raw_run(&map, "range_limited", seed, &["--relay", "0"], &out);
        let stops = |r: &Value| r["raw_scans"]["stops"].as_array().unwrap().clone();
        let flagged = |r: &Value| stops(r).iter().filter(|s| s["relay"] == true).count();
        let relays = on["raw_scans"]["relays"].as_u64().unwrap() as usize;
        assert!(relays >= 1, "seed {seed}");
        assert_eq!(flagged(&on), relays, "seed {seed}");
        assert_eq!((off["raw_scans"]["relays"].as_u64(), flagged(&off)), (Some(0), 0));
        assert_eq!(on["raw_scans"]["relay"].as_f64(), Some(stopscan::sim::lidar::RELAY));
        for r in [&on, &off] {
            // Every stop, relays included, is a scan of the record.
            assert_eq!(stops(r).len() as u64, r["metrics"]["scans"].as_u64().unwrap());
            assert_eq!(stops(r).len(), r["robots"][0]["scans"].as_array().unwrap().len());
        }
        let worst = |r: &Value| {
            stops(r).iter().map(|s| s["position_error"].as_f64().unwrap()).fold(0.0, f64::max)
        };
        assert!(worst(&on) <= 0.1, "seed {seed}: {} with relays", worst(&on));
        assert!(worst(&off) > 0.1, "seed {seed}: {} without", worst(&off));
    }
    // A relay threshold must be a length.
    let bad = stopscan(&[
        "explore",
        "--env",
        &map,
        "--sensor",
        "lidar",
        "--relay",
        "-1",
        "--robot-radius",
        "0.2",
    ]);
    assert!(!bad.status.success());
    assert!(String::from_utf8_lossy(&bad.stderr).contains("relay"));
}

/// On raw scans `cost_aware` drives to a viewpoint planned at the clearance along its roads,
/// not back along the tree of moves: a route's last leg may keep the clearance inside one
/// view's region. Before, it had to keep it in the union of the regions, where such a
/// viewpoint could stand a rounding error too near a wall; on depot these seeds then drove
/// 30 m for a hop of 2.2 m (seed 2) and 62 m for 2.4 m (seed 35). Measured from the record's
/// path: between two scans the robot drives at most 2.5 times the straight line plus 20 m.
/// Without relays, which change the runs: these are the runs the defect was seen in (with
/// relays, seed 35 now falls back to the tree of moves elsewhere: see the README). Since
/// alignments are refined, seed 2 ends a trip at a viewpoint no safe cell near it leads on
/// to, and drove 37.7 m back through the tree of moves for a hop of 2 m; the roads now lead
/// to the last waypoint of the tree they reach, and the tree's moves on from there.
#[test]
fn cost_aware_on_raw_scans_takes_no_long_way_round_for_a_short_hop() {
    let (map, out) = depot_and_record("short-hops");
    for seed in ["2", "35"] {
        let r = raw_cost_aware_run(&map, seed, &["--relay", "0"], &out);
        let xy = |p: &Value| [p[0].as_f64().unwrap(), p[1].as_f64().unwrap()];
        let path: Vec<[f64; 2]> =
            r["robots"][0]["path"].as_array().unwrap().iter().map(xy).collect();
        let scans: Vec<[f64; 2]> =
            r["robots"][0]["scans"].as_array().unwrap().iter().map(|s| xy(&s["at"])).collect();
        let d = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        // Each scan where the path first reaches its place after the one before.
        let mut at = Vec::new();
        let mut i = 0;
        for s in &scans {
            while d(path[i], *s) > 1e-6 {
                i += 1;
            }
            at.push(i);
        }
        for k in 1..scans.len() {
            let driven: f64 = (at[k - 1]..at[k]).map(|j| d(path[j], path[j + 1])).sum();
            let hop = d(scans[k - 1], scans[k]);
            assert!(driven <= 2.5 * hop + 20.0, "seed {seed}: {driven} m for a hop of {hop} m");
        }
        assert!(f(&r["robot"], "coverage_of_reachable") > 0.99, "{}", r["robot"]);
    }
}

#[test]
fn cost_aware_on_raw_scans_scans_no_twice_in_one_place_for_a_window_it_cannot_close() {
    // depot imported to GeoJSON, as the checks explore it. With the seeds below,
    // candidates predicted to see nothing were weighed at their floor, and the nearest won:
    // a second scan within a few centimetres of the one before, for a window far off.
    let dir = temp("no-twice");
    std::fs::create_dir_all(&dir).unwrap();
    let map = dir.join("depot.geojson");
    let map = map.to_str().unwrap();
    let yaml = common::fixture("ros-maps/depot.yaml");
    let imported = stopscan(&["map", "import", &yaml, "-o", map]);
    assert!(imported.status.success(), "{}", String::from_utf8_lossy(&imported.stderr));
    let out = dir.join("run.json");
    for seed in ["21", "28"] {
        let r = raw_cost_aware_run(map, seed, &[], &out);
        // Where the scans were truly taken.
        let truth: Vec<[f64; 2]> = r["raw_scans"]["stops"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| [f(&s["truth"], "x"), f(&s["truth"], "y")])
            .collect();
        assert!(truth.len() > 5);
        for k in 1..truth.len() {
            let d = (truth[k][0] - truth[k - 1][0]).hypot(truth[k][1] - truth[k - 1][1]);
            assert!(d > 0.15, "seed {seed}: scans {k} and {} {d} m apart", k + 1);
        }
        assert!(f(&r["robot"], "coverage_of_reachable") > 0.99, "{}", r["robot"]);
    }
}

#[test]
fn raw_scan_flags_are_checked() {
    let map = common::fixture("office.geojson");
    fails(&["explore", "--env", &map, "--sensor", "camera"], &["--sensor", "lidar"]);
    fails(&["explore", "--env", &map, "--sensor", "lidar:beams=4"], &["--sensor", "beams"]);
    fails(&["explore", "--env", &map, "--sensor", "lidar:sigma=x"], &["--sensor", "sigma"]);
    fails(&["explore", "--env", &map, "--sensor", "lidar:fov=2"], &["--sensor", "fov"]);
    fails(
        &["explore", "--env", &map, "--odometry-drift", "0.01"],
        &["--odometry-drift", "--sensor"],
    );
    fails(
        &["explore", "--env", &map, "--sensor", "lidar", "--odometry-drift", "0.9"],
        &["--odometry-drift", "0.9"],
    );
    fails(
        &["explore", "--env", &map, "--sensor", "lidar", "--range", "8"],
        &["--range", "lidar's max"],
    );
    let dir = common::fixture("ros-maps");
    fails(&["explore", "--env", &dir, "--sensor", "lidar"], &["raw scans", "one environment"]);
}

#[test]
fn a_sweep_in_shards_merges_into_the_whole_sweep_byte_for_byte() {
    let dir = temp("shards");
    let envs = dir.join("envs");
    std::fs::create_dir_all(&envs).unwrap();
    for (k, (family, size)) in
        [("comb", "3"), ("comb", "5"), ("spiral", "3"), ("star", "5"), ("office", "2")]
            .iter()
            .enumerate()
    {
        let out = envs.join(format!("e{k}.geojson"));
        let o = stopscan(&["generate", family, "--size", size, "--output", out.to_str().unwrap()]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let sweep = |extra: &[&str], out: &str| {
        let mut args = vec!["explore", "--env", envs.to_str().unwrap(), "--strategy", "all"];
        args.extend_from_slice(extra);
        let out = path(out);
        args.extend(["--out", out.as_str()]);
        let o = stopscan(&args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    sweep(&[], "whole.csv");
    for k in 1..=3 {
        sweep(&["--shard", &format!("{k}/3")], &format!("part{k}.csv"));
    }
    // Two files each for shards 1 and 2, one for shard 3; 7 of 7 has none.
    sweep(&["--shard", "7/7"], "empty.csv");
    let whole = std::fs::read_to_string(dir.join("whole.csv")).unwrap();
    let lines = |name: &str| std::fs::read_to_string(dir.join(name)).unwrap().lines().count();
    let strategies = whole.lines().count() / 5;
    assert_eq!(lines("part1.csv"), 1 + 2 * strategies);
    assert_eq!(lines("part3.csv"), 1 + strategies);
    assert_eq!(lines("empty.csv"), 0);
    // The parts in any order, the empty one too: the whole sweep's bytes.
    let merged = path("merged.csv");
    let parts = [path("part3.csv"), path("empty.csv"), path("part1.csv"), path("part2.csv")];
    let mut args = vec!["merge", "--out", merged.as_str()];
    args.extend(parts.iter().map(String::as_str));
    let o = stopscan(&args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(std::fs::read_to_string(&merged).unwrap(), whole);
    // A part given twice is refused, naming both places.
    let p1 = path("part1.csv");
    fails(
        &["merge", p1.as_str(), p1.as_str(), "--out", merged.as_str()],
        &["is also in", "line 2"],
    );
    // --shard needs a folder, and 1 <= I <= N.
    let file = envs.join("e0.geojson");
    fails(&["explore", "--env", file.to_str().unwrap(), "--shard", "1/2"], &["folder sweep"]);
    for bad in ["0/2", "3/2", "2"] {
        fails(&["explore", "--env", envs.to_str().unwrap(), "--shard", bad], &["--shard"]);
    }
}

#[test]
fn max_scans_cuts_a_run_short_and_says_so() {
    let map = common::fixture("ros-maps/turtlebot3_world.yaml");
    let dir = temp("max-scans");
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("run.json");
    let out = out.to_str().unwrap();
    let args = || {
        let mut a = vec!["explore", "--env", &map, "--strategy", "cost_aware"];
        a.extend(["--robot-radius", "0.2", "--range", "20", "--out", out]);
        a.extend(["--greedy-max-vertices", "0", "--optimum-seconds", "0"]);
        a.into_iter().map(String::from).collect::<Vec<_>>()
    };
    let run = |a: &[String]| {
        let a: Vec<&str> = a.iter().map(String::as_str).collect();
        let o = stopscan(&a);
        let v: Value = serde_json::from_str(&std::fs::read_to_string(out).unwrap()).unwrap();
        (o, v)
    };
    let (o, whole) = run(&args());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let n = whole["metrics"]["scans"].as_u64().unwrap();
    let fewer = (n - 1).to_string();
    let mut a = args();
    a.extend(["--max-scans".to_string(), fewer.clone()]);
    let (o, cut) = run(&a);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(&format!("scan limit ({fewer} scans, --max-scans)")), "{err}");
    assert_eq!(cut["metrics"]["scans"].as_u64(), Some(n - 1));
    assert!(cut["error"].as_str().unwrap().contains("--max-scans"));
    let mut a = args();
    a.extend(["--max-scans".to_string(), n.to_string()]);
    let (o, same) = run(&a);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(same["metrics"], whole["metrics"]);
    fails(&["explore", "--env", &map, "--max-scans", "0"], &["--max-scans"]);
    // A folder sweep's rows are whole runs: the limit is refused there, not ignored.
    let sweep = dir.join("sweep");
    std::fs::create_dir_all(&sweep).unwrap();
    std::fs::copy(&map, sweep.join("tb3.yaml")).unwrap();
    let pgm = common::fixture("ros-maps/turtlebot3_world.pgm");
    std::fs::copy(pgm, sweep.join("turtlebot3_world.pgm")).unwrap();
    let s = sweep.to_str().unwrap();
    fails(
        &["explore", "--env", s, "--max-scans", "3"],
        &["--max-scans applies to one environment"],
    );
}
