//! The soft and hard size limits of every command, and `--allow-large`.

use crate::common;

use common::{fails, fixture, stopscan, temp};

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
