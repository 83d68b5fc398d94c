//! Errors across commands: clear messages, no panics, outputs checked before any work.

use crate::common;

use common::{assert_no_temporary_files, fails, fixture, stopscan, temp};

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
    fails(&["map", "import", "x.wkt", "-o", "y.geojson", "--out", "z"], &["two files to write"]);
    assert_no_temporary_files(&dir);
}
