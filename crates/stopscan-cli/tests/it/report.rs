//! `report.html`, the browser replay: its embedded data checked against the run record and
//! against the definitions (brute force), then the page itself in headless Chromium: stepped,
//! played, read back from the DOM, and photographed.
//!
//! The browser tests need Chromium (`chromium`, `chromium-browser` or `google-chrome` on the
//! PATH, or the binary named by `STOPSCAN_CHROMIUM`). Without one they are skipped with a
//! message, unless `STOPSCAN_CI` is set (as `.ci/run` sets it, after installing
//! Debian's chromium), when they fail.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use common::{fixture, stopscan, temp};

/// The run data embedded in a report.
fn embedded(html: &str) -> Value {
    let open = r#"<script type="application/json" id="run-data">"#;
    let start = html.find(open).expect("the page embeds its data") + open.len();
    let end = start + html[start..].find("</script>").expect("the data element is closed");
    serde_json::from_str(&html[start..end]).expect("the embedded data is JSON")
}

fn num(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("not a number: {v}"))
}

fn points(flat: &Value) -> Vec<[f64; 2]> {
    let v: Vec<f64> = flat.as_array().unwrap().iter().map(num).collect();
    v.chunks(2).map(|c| [c[0], c[1]]).collect()
}

fn pair(v: &Value) -> [f64; 2] {
    [num(&v[0]), num(&v[1])]
}

/// Even-odd point in polygon, written from the definition (a ray to +x crosses the boundary
/// an odd number of times).
fn inside_ring(p: [f64; 2], ring: &[[f64; 2]]) -> bool {
    let mut inside = false;
    for i in 0..ring.len() {
        let (a, b) = (ring[i], ring[(i + 1) % ring.len()]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                inside = !inside;
            }
        }
    }
    inside
}

fn in_domain(p: [f64; 2], rings: &[Vec<[f64; 2]>]) -> bool {
    rings.iter().filter(|r| inside_ring(p, r)).count() % 2 == 1
}

/// Writes a report of `args` (an explore command line) and returns its data beside the record.
fn explore_report(name: &str, args: &[&str]) -> (Value, Value, PathBuf) {
    let dir = temp(name);
    std::fs::create_dir_all(&dir).unwrap();
    let (json, html) = (dir.join("run.json"), dir.join("report.html"));
    let mut all = args.to_vec();
    all.extend(["--out", json.to_str().unwrap(), "--report", html.to_str().unwrap()]);
    let out = stopscan(&all);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stdout).contains(&format!("wrote {}", html.display())));
    let record: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let data = embedded(&std::fs::read_to_string(&html).unwrap());
    (data, record, html)
}

/// The frames: scans counted one by one, each step's time is its terms priced by the cost
/// model, and the last step is the record's totals.
fn check_frames(data: &Value, record: &Value) {
    let frames = data["frames"].as_array().unwrap();
    let n = data["scans"].as_array().unwrap().len();
    let cost = &record["cost_model"];
    let (scan, mv, speed) = (num(&cost["scan_time"]), num(&cost["move_time"]), num(&cost["speed"]));
    assert_eq!(frames[0]["scans"], 0);
    assert_eq!(num(&frames[0]["time"]), 0.0);
    let mut last_distance = 0.0;
    for (k, f) in frames.iter().enumerate() {
        if k <= n {
            assert_eq!(f["scans"].as_u64().unwrap() as usize, k, "frame {k}");
        }
        let (scans, moves, d) = (num(&f["scans"]), num(&f["moves"]), num(&f["distance"]));
        assert!(d >= last_distance, "the distance never shrinks");
        last_distance = d;
        let terms = [scans * scan, moves * mv, d / speed];
        for (key, want) in
            ["scan_time_total", "move_time_total", "travel_time_total"].iter().zip(terms)
        {
            assert!((num(&f[key]) - want).abs() <= 1e-9 * want.max(1.0), "frame {k} {key}");
        }
        let total: f64 = terms.iter().sum();
        assert!((num(&f["time"]) - total).abs() <= 1e-9 * total.max(1.0), "frame {k} time");
    }
    let last = frames.last().unwrap();
    let m = &record["metrics"];
    for key in ["scans", "moves"] {
        assert_eq!(last[key], m[key], "the last step's {key} is the record's");
    }
    for key in ["distance", "time", "scan_time_total", "move_time_total", "travel_time_total"] {
        let (got, want) = (num(&last[key]), num(&m[key]));
        assert!((got - want).abs() <= 1e-9 * want.max(1.0), "last step {key}: {got} vs {want}");
    }
    // Each scan stands where the record says it was taken (to the embedded rounding), and the
    // path drawn at its step ends there.
    let [x0, y0, x1, y1] = [0, 1, 2, 3].map(|i| num(&data["bounds"][i]));
    let tol = 2e-6 * (x1 - x0).max(y1 - y0);
    let path = points(&data["path"]);
    for (i, s) in data["scans"].as_array().unwrap().iter().enumerate() {
        let (at, want) = (pair(&s["at"]), pair(&record["robots"][0]["scans"][i]["at"]));
        assert!((at[0] - want[0]).abs() <= tol && (at[1] - want[1]).abs() <= tol, "scan {i}");
        let drawn = frames[i + 1]["path"].as_u64().unwrap() as usize;
        let end = path[drawn - 1];
        assert!((end[0] - at[0]).abs() <= tol && (end[1] - at[1]).abs() <= tol, "path at {i}");
    }
}

/// The open frontiers at `step`: (frontier, its open parameter intervals).
fn open_at(data: &Value, step: usize) -> Vec<(&Value, Vec<[f64; 2]>)> {
    let mut out = Vec::new();
    for f in data["frontiers"].as_array().unwrap() {
        if f["scan"].as_u64().unwrap() as usize + 1 > step {
            continue;
        }
        let entry = f["open"].as_array().unwrap().iter().rfind(|e| num(&e[0]) <= step as f64);
        let Some(e) = entry else { continue };
        let v: Vec<f64> = e.as_array().unwrap()[1..].iter().map(num).collect();
        out.push((f, v.chunks(2).map(|c| [c[0], c[1]]).collect()));
    }
    out
}

/// The frontiers the page highlights at each step, against the definition: just beyond the
/// middle of every open part lies free space that none of the scans taken so far sees, and
/// just beyond the middle of every long enough closed part lies space another scan taken so
/// far sees (or no free space at all). At the last step, the open parts are the record's
/// windows left open.
fn check_open_frontiers(data: &Value, record: &Value) {
    let [x0, y0, x1, y1] = [0, 1, 2, 3].map(|i| num(&data["bounds"][i]));
    // Ten times the embedded rounding.
    let eps = 1e-5 * (x1 - x0).max(y1 - y0);
    let domain: Vec<Vec<[f64; 2]>> =
        data["domain"].as_array().unwrap().iter().map(points).collect();
    let polys: Vec<Vec<[f64; 2]>> =
        data["scans"].as_array().unwrap().iter().map(|s| points(&s["poly"])).collect();
    let steps = data["frames"].as_array().unwrap().len();
    let (mut checked_open, mut checked_closed) = (0, 0);
    for step in 1..steps {
        let taken = step.min(polys.len());
        for (f, open) in open_at(data, step) {
            let (a, b) = (pair(&f["a"]), pair(&f["b"]));
            let own = f["scan"].as_u64().unwrap() as usize;
            let len = (b[0] - a[0]).hypot(b[1] - a[1]);
            let n = [(b[1] - a[1]) / len, -(b[0] - a[0]) / len];
            let probe = |t: f64| {
                [a[0] + t * (b[0] - a[0]) + eps * n[0], a[1] + t * (b[1] - a[1]) + eps * n[1]]
            };
            let seen_by_other = |p| (0..taken).any(|j| j != own && inside_ring(p, &polys[j]));
            for &[t0, t1] in &open {
                if (t1 - t0) * len < 10.0 * eps {
                    continue;
                }
                let p = probe(0.5 * (t0 + t1));
                if !in_domain(p, &domain) {
                    continue;
                }
                assert!(!seen_by_other(p), "step {step}: an open part of {f} is seen at {p:?}");
                checked_open += 1;
            }
            // The closed parts: the complement of the open ones.
            let mut at = 0.0;
            for &[t0, t1] in open.iter().chain(std::iter::once(&[1.0, 1.0])) {
                if (t0 - at) * len >= 20.0 * eps {
                    let p = probe(0.5 * (at + t0));
                    assert!(
                        seen_by_other(p) || !in_domain(p, &domain),
                        "step {step}: a closed part of {f} is unseen at {p:?}"
                    );
                    checked_closed += 1;
                }
                at = f64::max(at, t1);
            }
        }
    }
    assert!(checked_open > 0 && checked_closed > 0, "{checked_open} open, {checked_closed} closed");
    let open_parts: usize = open_at(data, steps - 1).iter().map(|(_, o)| o.len()).sum();
    assert_eq!(open_parts as u64, record["metrics"]["open_windows"].as_u64().unwrap());
}

#[test]
fn the_main_job_writes_a_small_report_whose_steps_are_the_run() {
    let dir = temp("report-main");
    let out = stopscan(&["--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let html = std::fs::read_to_string(dir.join("report.html")).unwrap();
    assert!(html.len() < 1_000_000, "report.html is {} bytes", html.len());
    // Self-contained: nothing is fetched.
    for needle in ["http://", "https://", "src=", "href="] {
        let outside_namespace = html.replace("http://www.w3.org/2000/svg", "");
        assert!(!outside_namespace.contains(needle), "report.html refers to {needle}");
    }
    let record: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("run.json")).unwrap()).unwrap();
    let data = embedded(&html);
    assert_eq!(data["record"], record, "the page embeds the run record");
    check_frames(&data, &record);
    check_open_frontiers(&data, &record);
}

#[test]
fn a_footprint_run_reports_its_open_windows_and_configuration_space() {
    let office = fixture("office.geojson");
    let (data, record, _) =
        explore_report("report-footprint", &["explore", "--env", &office, "--robot-radius", "0.3"]);
    assert!(record["metrics"]["open_windows"].as_u64().unwrap() > 0, "windows stay open");
    assert!(data["cspace"].is_array(), "the configuration space is drawn");
    check_frames(&data, &record);
    check_open_frontiers(&data, &record);
}

#[test]
fn a_raw_scan_run_reports_the_ground_truth() {
    let office = fixture("office.geojson");
    let (data, record, _) = explore_report(
        "report-lidar",
        &["explore", "--env", &office, "--sensor", "lidar", "--strategy", "nearest_frontier"],
    );
    check_frames(&data, &record);
}

#[test]
fn a_sweep_refuses_report() {
    let dir = temp("report-sweep");
    std::fs::create_dir_all(&dir).unwrap();
    let out = stopscan(&["explore", "--env", dir.to_str().unwrap(), "--report", "r.html"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("--report records one run"));
}

/// The browser, or `None` (with the reason printed) when the test may be skipped.
fn chromium() -> Option<PathBuf> {
    if let Ok(p) = std::env::var("STOPSCAN_CHROMIUM") {
        return Some(PathBuf::from(p));
    }
    let found = ["chromium", "chromium-browser", "google-chrome"].iter().find_map(|name| {
        std::env::var_os("PATH").and_then(|paths| {
            std::env::split_paths(&paths).map(|d| d.join(name)).find(|p| p.is_file())
        })
    });
    if found.is_none() {
        assert!(
            std::env::var_os("STOPSCAN_CI").is_none(),
            "STOPSCAN_CI is set but no chromium is on the PATH"
        );
        eprintln!(
            "skipped: no chromium on the PATH (Debian: apt-get install chromium; or set STOPSCAN_CHROMIUM)"
        );
    }
    found
}

/// Runs headless Chromium on `file` with `fragment`, networking off; `extra` adds switches
/// (`--dump-dom`, `--screenshot=…`). Returns stdout.
fn browse(browser: &Path, file: &Path, fragment: &str, extra: &[&str]) -> String {
    // A profile of its own per start: tests run in parallel.
    static STARTS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = STARTS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let profile = temp(&format!("chromium-profile-{n}"));
    let url = format!("file://{}{fragment}", file.canonicalize().unwrap().display());
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--disable-extensions",
            // Networking off: every host resolves nowhere.
            "--host-resolver-rules=MAP * ~NOTFOUND",
            "--window-size=1400,1000",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(extra)
        .arg(&url)
        .output()
        .expect("chromium runs");
    let _ = std::fs::remove_dir_all(&profile);
    assert!(out.status.success(), "chromium failed: {}", String::from_utf8_lossy(&out.stderr));
    String::from_utf8(out.stdout).unwrap()
}

/// The page's DOM before its scripts (whose source mentions the elements it makes).
fn drawn(dom: &str) -> &str {
    &dom[..dom.find("<script").expect("the page has scripts")]
}

fn body_attr<'a>(dom: &'a str, name: &str) -> &'a str {
    let key = format!("{name}=\"");
    let start = dom.find(&key).unwrap_or_else(|| panic!("no {name} on the page")) + key.len();
    &dom[start..start + dom[start..].find('"').unwrap()]
}

#[test]
fn the_report_replays_in_a_real_browser() {
    let Some(browser) = chromium() else { return };
    let dir = temp("report-browser");
    let out = stopscan(&["--out", dir.to_str().unwrap()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let file = dir.join("report.html");
    let data = embedded(&std::fs::read_to_string(&file).unwrap());
    let frames = data["frames"].as_array().unwrap();
    let last = frames.len() - 1;
    let scans = data["scans"].as_array().unwrap().len();

    // Stepped to 5: five scan regions, five scan points, the step's numbers.
    let dom = browse(&browser, &file, "#step=5", &["--dump-dom"]);
    let page = drawn(&dom);
    assert_eq!(page.matches(r#"class="scan""#).count(), 5);
    assert_eq!(page.matches(r#"class="stop""#).count(), 5);
    assert_eq!(body_attr(page, "data-step"), "5");
    assert!(page.contains(&format!("step 5 of {last}: 5 scans")), "the label names the step");
    let time = format!("{:.3}", num(&frames[5]["time"]));
    assert!(page.contains(&format!(r#"<td class="v">{time}</td>"#)), "the step's time {time}");
    let ms: f64 = body_attr(page, "data-first-frame-ms").parse().unwrap();
    assert!(ms > 0.0, "the first frame was drawn");

    // Opened plainly: the finished run, every scan.
    let dom = browse(&browser, &file, "", &["--dump-dom"]);
    let page = drawn(&dom);
    assert_eq!(page.matches(r#"class="scan""#).count(), scans);
    assert_eq!(body_attr(page, "data-step"), last.to_string());
    assert!(page.contains("windows left open"));
    assert!(page.contains("certified ratio (time / lower bound)"));

    // Played (from the start, in virtual time): it stops partway, with the step's scans.
    let dom = browse(&browser, &file, "#play", &["--dump-dom", "--virtual-time-budget=3000"]);
    let page = drawn(&dom);
    let step: usize = body_attr(page, "data-step").parse().unwrap();
    assert!(step > 0 && step < last, "played to step {step} of {last}");
    let want = frames[step]["scans"].as_u64().unwrap() as usize;
    assert_eq!(page.matches(r#"class="scan""#).count(), want);
    assert_eq!(body_attr(page, "data-playing"), "true");

    // A screenshot of step 20.
    let png = dir.join("step20.png");
    browse(&browser, &file, "#step=20", &[&format!("--screenshot={}", png.display())]);
    let bytes = std::fs::read(&png).expect("the screenshot was taken");
    assert!(
        bytes.starts_with(b"\x89PNG\r\n\x1a\n") && bytes.len() > 20_000,
        "{} bytes",
        bytes.len()
    );
}

#[test]
fn the_roi_report_marks_the_cells_as_the_robots_reach_them() {
    let dir = temp("report-roi");
    std::fs::create_dir_all(&dir).unwrap();
    let (json, html) = (dir.join("roi.json"), dir.join("roi.html"));
    let out = stopscan(&[
        "roi",
        "--random",
        "200",
        "--robots",
        "3",
        "--roi-speed",
        "0.3",
        "--seed",
        "4",
        "--out",
        json.to_str().unwrap(),
        "--report",
        html.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let record: Value = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let data = embedded(&std::fs::read_to_string(&html).unwrap());
    assert_eq!(data["record"], record);
    let runs: Vec<i64> =
        data["runs"].as_array().unwrap().iter().map(|v| v.as_i64().unwrap()).collect();
    let cells: usize = runs.chunks(3).map(|r| (r[2] - r[1] + 1) as usize).sum();
    assert_eq!(cells as u64, record["cells"].as_u64().unwrap());
    // Cells marked by time t, from the record alone: region cells some robot reached by t.
    let region: std::collections::HashSet<(i64, i64)> =
        runs.chunks(3).flat_map(|r| (r[1]..=r[2]).map(move |c| (r[0], c))).collect();
    let marked_by = |t: f64| {
        let mut seen = std::collections::HashSet::new();
        for r in record["robots"].as_array().unwrap() {
            for (c, time) in
                r["cells"].as_array().unwrap().iter().zip(r["times"].as_array().unwrap())
            {
                let c = (c[0].as_i64().unwrap(), c[1].as_i64().unwrap());
                if num(time) <= t && region.contains(&c) {
                    seen.insert(c);
                }
            }
        }
        seen.len()
    };
    assert_eq!(
        marked_by(f64::INFINITY) as u64,
        record["metrics"]["visited_cells"].as_u64().unwrap()
    );
    let Some(browser) = chromium() else { return };
    for step in [0usize, 40, 100] {
        let dom = browse(&browser, &html, &format!("#step={step}"), &["--dump-dom"]);
        let page = drawn(&dom);
        assert_eq!(body_attr(page, "data-step"), step.to_string());
        let label = page.split("step-label\">").nth(1).unwrap();
        let t: f64 =
            label.split("t = ").nth(1).unwrap().split(' ').next().unwrap().parse().unwrap();
        // The label rounds t to a millisecond: count at the rounded time's bracket.
        let marked: usize = body_attr(page, "data-marked").parse().unwrap();
        let (lo, hi) = (marked_by(t - 5e-4), marked_by(t + 5e-4));
        assert!(lo <= marked && marked <= hi, "step {step}: {marked} marked, {lo}..={hi} at {t}");
    }
    let dom = browse(&browser, &html, "", &["--dump-dom"]);
    let marked: usize = body_attr(drawn(&dom), "data-marked").parse().unwrap();
    assert_eq!(marked as u64, record["metrics"]["visited_cells"].as_u64().unwrap());
}
