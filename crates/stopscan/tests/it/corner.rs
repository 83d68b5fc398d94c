//! The corner papers' own numbers, checked end to end.

use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

use stopscan::experiment::corner::{monte_carlo, paper_setup};
use stopscan::offline::corner::optimal::{OptimalScans, optimal_scans, plane_ratio};
use stopscan::offline::corner::{expected, limit_ratio, worst_case};
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use stopscan::strategy::corner::circle::{self, Outcome};
use stopscan::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use stopscan::strategy::corner::{ExprecReading, exprec, unirec};

fn unit(d: f64) -> CornerSetup {
    CornerSetup::new(d, CostModel::default()).unwrap()
}

fn six(x: f64) -> f64 {
    (x * 1e6).round() / 1e6
}

#[test]
fn circle_table_1_to_all_printed_digits() {
    let paper = [
        (0.618_034, 1.618_034),
        (1.530_414, 2.040_287),
        (2.799_395, 2.155_363),
        (4.400_876, 2.168_544),
        (6.316_892, 2.147_994),
        (8.514_200, 2.118_498),
    ];
    for (t, (d, c)) in circle::thresholds(6).iter().zip(paper) {
        assert_eq!(six(t.distance), d, "{t:?}");
        assert_eq!(six(t.ratio), c, "{t:?}");
    }
}

#[test]
fn c40_and_figure_4_brackets() {
    assert!(matches!(circle::run(40.0, 2.0016), Outcome::Reached(_)));
    assert!(matches!(circle::run(40.0, 2.0015), Outcome::Collapsed(_)));
    // "c = 2.001525..." (truncated in the paper).
    assert_eq!((circle::ratio(40.0).unwrap() * 1e6).floor(), 2_001_525.0);
}

#[test]
fn maximum_of_c_is_the_third_threshold() {
    let t = circle::thresholds(4)[3];
    assert_eq!(six(t.ratio), 2.168_544);
    assert!((t.distance - 4.400_875).abs() < 1.5e-6);
    // No sampled distance exceeds it.
    for i in 1..=4000 {
        let d = 20.0 * f64::from(i) / 4000.0;
        assert!(circle::ratio(d).unwrap() <= t.ratio + 1e-9, "d = {d}");
    }
}

/// The optima the tests below share (each search takes seconds in a debug build).
fn optima() -> &'static [OptimalScans; 3] {
    static OPTIMA: std::sync::OnceLock<[OptimalScans; 3]> = std::sync::OnceLock::new();
    OPTIMA.get_or_init(|| {
        [optimal_scans(1.0, 1, 0), optimal_scans(4.4, 3, 0), optimal_scans(4.4, 5, 0)]
            .map(Result::unwrap)
    })
}

#[test]
fn global_optimum_at_d1_and_beating_the_circle() {
    let [one, three, at_most_five] = optima();
    assert_eq!(six(one.ratio), 1.808_201);
    assert!(one.ratio < one.circle_ratio);
    // d = 4.4: the circle strategy gives 2.1685 with 3 scans; the optimum with 3 is lower, and
    // with 4 lower still, about 1% below the paper's ≈ 2.12 (an independent optimiser finds
    // 2.09777). A fifth point does not help: the optimum with at most 5 uses 4.
    assert!((three.circle_ratio - 2.1685).abs() < 1e-4);
    assert!(three.ratio < three.circle_ratio - 0.03, "{three:?}");
    assert_eq!(at_most_five.scans, 4, "{at_most_five:?}");
    assert!((at_most_five.ratio - 2.097_77).abs() < 2e-5, "{at_most_five:?}");
    assert_eq!(at_most_five.ratio_by_scans[4], at_most_five.ratio);
    assert!(at_most_five.ratio_by_scans.windows(2).all(|w| w[1] <= w[0]));
    // Every claimed ratio is that of the printed points.
    for o in optima() {
        assert_eq!(o.ratio, plane_ratio(o.distance, &o.scan_points));
        let sup = brute_force_exact(o.distance, &o.scan_points);
        assert!((o.ratio - sup).abs() <= 1e-12 * sup, "{} vs {sup}", o.ratio);
    }
}

/// Whether a scan at `p` sees the edge leaving the corner `(d, 0)` at angle `theta` from the
/// line back to the start, written from the geometry (not from the code under test): the
/// edge's direction is `u = (−cos θ, sin θ)`, and `p`, on the open side (`y ≥ 0`), sees it when
/// it lies on or beyond the edge's line, `u × (p − B) ≤ 0`. The corner (`p = B`) sees all.
fn sees(d: f64, p: [f64; 2], theta: f64) -> bool {
    let (vx, vy) = (p[0] - d, p[1]);
    p[1] >= 0.0 && (-theta.cos()) * vy - theta.sin() * vx <= 0.0
}

/// The cost of finding an edge at `theta`: scans and metres until the first point that sees
/// it, the corner last.
fn cost_at(d: f64, pts: &[[f64; 2]], theta: f64) -> f64 {
    let mut len = 0.0;
    let mut prev = [0.0, 0.0];
    for (i, &p) in pts.iter().chain(&[[d, 0.0]]).enumerate() {
        len += (p[0] - prev[0]).hypot(p[1] - prev[1]);
        prev = p;
        if i == pts.len() || sees(d, p, theta) {
            return (i + 1) as f64 + len;
        }
    }
    unreachable!()
}

/// The optimum for an edge at `theta`: one scan at the nearest point that sees it.
fn opt_at(d: f64, theta: f64) -> f64 {
    1.0 + if theta <= FRAC_PI_2 { d * theta.sin() } else { d }
}

/// An independent oracle: the worst ratio over `n` edge angles spread over (0, π], and an
/// upper bound on how far the supremum can lie above it (the cost is piecewise constant and
/// the optimum `d`-Lipschitz, so between grid angles the ratio exceeds the next grid value by
/// at most `cost · d · h`).
fn brute_force(d: f64, pts: &[[f64; 2]], n: u32) -> (f64, f64) {
    let h = PI / f64::from(n);
    let mut worst = 0.0_f64;
    let mut slack = 0.0_f64;
    for k in 1..=n {
        let theta = h * f64::from(k);
        let c = cost_at(d, pts, theta);
        worst = worst.max(c / opt_at(d, theta));
        slack = slack.max(c * d * h);
    }
    (worst, slack)
}

/// The supremum itself, from the geometry: each point sees the edges up to the angle where
/// [`sees`] turns false, found by bisection (below 1e-12 it counts as seeing none; rounding in
/// `sees` blurs smaller angles); the cost is constant between these angles, so the supremum is
/// approached just past one of them, where the first point (in order) seeing further is the
/// one that finds the edge.
fn brute_force_exact(d: f64, pts: &[[f64; 2]]) -> f64 {
    let limit: Vec<f64> = pts
        .iter()
        .map(|&p| {
            if sees(d, p, PI) {
                return PI;
            }
            let (mut lo, mut hi) = (0.0, PI);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if sees(d, p, mid) { lo = mid } else { hi = mid }
            }
            if lo < 1e-12 { 0.0 } else { lo }
        })
        .collect();
    let mut path = Vec::new();
    let mut len = 0.0;
    let mut prev = [0.0, 0.0];
    for &p in pts.iter().chain(&[[d, 0.0]]) {
        len += (p[0] - prev[0]).hypot(p[1] - prev[1]);
        prev = p;
        path.push(len);
    }
    std::iter::once(0.0)
        .chain(limit.iter().copied())
        .filter(|&b| b < PI)
        .map(|b| {
            let i = limit.iter().position(|&l| l > b).unwrap_or(pts.len());
            ((i + 1) as f64 + path[i]) / opt_at(d, b)
        })
        .fold(0.0, f64::max)
}

#[test]
fn plane_ratio_agrees_with_a_brute_force_over_every_edge_angle() {
    for o in optima() {
        let (d, k) = (o.distance, o.scans);
        let exact = plane_ratio(d, &o.scan_points);
        let (brute, slack) = brute_force(d, &o.scan_points, 200_000);
        assert!(
            brute <= exact + 1e-12 && exact - brute <= slack,
            "d={d} k={k}: {exact} vs {brute}"
        );
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

    /// Any points, anywhere: before the corner, past its perpendicular, on the line, below it,
    /// on the corner itself.
    #[test]
    fn plane_ratio_is_the_supremum_over_every_edge_angle(
        d in 0.1..20.0f64,
        raw in proptest::collection::vec((-0.5..1.6f64, -0.3..1.0f64, 0u8..8), 0..7),
    ) {
        let pts: Vec<[f64; 2]> = raw
            .iter()
            .map(|&(x, y, snap)| match snap {
                0 => [d, 0.0],                 // the corner
                1 => [x * d, 0.0],             // on the line or its extension
                2 => [d, y.abs() * d],         // on the perpendicular
                _ => [x * d, y * d],
            })
            .collect();
        let exact = plane_ratio(d, &pts);
        let sup = brute_force_exact(d, &pts);
        proptest::prop_assert!((exact - sup).abs() <= 1e-9 * exact, "{exact} vs {sup} for {pts:?}");
        let (grid, slack) = brute_force(d, &pts, 4000);
        proptest::prop_assert!(grid <= exact * (1.0 + 1e-12) && exact - grid <= slack, "{exact} vs {grid}");
    }
}

#[test]
fn unirec_tends_to_pi_and_exprec_to_the_appendix_value() {
    let mut prev = 0.0;
    for k in [2, 3, 4, 5, 6] {
        let delta = 10f64.powi(-k);
        let w =
            worst_case(&unirec(delta, Route::Arc, LastStep::Capped).unwrap(), &unit(1.0 / delta));
        assert!(w.worst_ratio > prev && w.worst_ratio < PI, "{w:?}");
        prev = w.worst_ratio;
    }
    assert!(PI - prev < 1e-5);
    let delta = FRAC_PI_4 / 2f64.powi(36);
    let w = worst_case(
        &exprec(delta, ExprecReading::TableI, Route::Arc, LastStep::Capped).unwrap(),
        &unit(1.0 / delta),
    );
    assert!((w.asymptotic_ratio - limit_ratio("exprec").unwrap()).abs() < 1e-4, "{w:?}");
    assert!((limit_ratio("exprec").unwrap() - 2.22144).abs() < 1e-5);
}

#[test]
fn circle_strategy_is_c_competitive_in_the_corner_model() {
    for d in [0.3, 1.0, 2.5, 4.4, 12.0, 40.0] {
        let s = circle::solve(d).unwrap();
        let w = worst_case(&s.stop_list(), &unit(d));
        assert!((w.worst_ratio - s.ratio).abs() < 1e-9, "d={d}");
    }
}

#[test]
fn mdp2_sizes_of_the_issue() {
    for (n, states) in [(900, 405_450), (1800, 1_620_900)] {
        let m = CornerMdp {
            setup: paper_setup(2.0).unwrap(),
            step: FRAC_PI_2 / f64::from(n),
            memory: Memory::Last,
            reading: Reading::Conditional,
            belief: AngleDistribution::parse("normal:60,5").unwrap(),
        };
        let p = m.solve().unwrap();
        assert_eq!(p.stops, n as usize);
        assert_eq!(p.states, states + n as usize);
    }
}

#[test]
fn exact_mdp2_value_is_the_true_expected_time() {
    for belief in ["uniform:0,180", "normal:60,5", "mix:0.5*normal:30,3+0.5*normal:90,3"] {
        let b = AngleDistribution::parse(belief).unwrap();
        let setup = paper_setup(2.0).unwrap();
        let m = CornerMdp {
            setup,
            step: 1f64.to_radians(),
            memory: Memory::Last,
            reading: Reading::Conditional,
            belief: b.clone(),
        };
        let p = m.solve().unwrap();
        let e = expected(&p.stop_list, &setup, &b).time;
        assert!((e - p.model_value).abs() < 1e-9, "{belief}: {e} vs {}", p.model_value);
    }
}

#[test]
fn monte_carlo_matches_the_exact_expectation_and_is_deterministic() {
    let setup = paper_setup(2.0).unwrap();
    let truth = AngleDistribution::parse("mix:0.5*normal:30,3+0.5*normal:90,3").unwrap();
    let list = unirec(setup.delta(), Route::Arc, LastStep::Nominal).unwrap();
    let e = expected(&list, &setup, &truth).time;
    let mc = monte_carlo(&list, &setup, &truth, 20_000, 7).unwrap();
    assert!((mc.mean - e).abs() < 5.0 * mc.std_err, "{} vs {e} ± {}", mc.mean, mc.std_err);
    assert_eq!(mc, monte_carlo(&list, &setup, &truth, 20_000, 7).unwrap());
    assert_ne!(mc.mean, monte_carlo(&list, &setup, &truth, 20_000, 8).unwrap().mean);
}

#[test]
fn move_time_is_charged_per_move() {
    let with = CornerSetup::new(10.0, CostModel::new(2.0, 1.5, 0.5).unwrap()).unwrap();
    let without = paper_setup(2.0).unwrap();
    let list = unirec(0.1, Route::Arc, LastStep::Capped).unwrap();
    for (k, (a, b)) in list.costs(&with).iter().zip(list.costs(&without)).enumerate() {
        assert!((a - b - 1.5 * (k + 1) as f64).abs() < 1e-9);
    }
}
