//! `stopscan bench`: the JSON contract of every benchmark.

mod common;

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
