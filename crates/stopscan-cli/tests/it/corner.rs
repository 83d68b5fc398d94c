//! `stopscan corner …`: demo, circle, thresholds, optimal, collapse, ratio, policy, simulate.

use crate::common;

use std::process::Command;

use serde_json::Value;

use common::{f, json, stopscan, temp};

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
