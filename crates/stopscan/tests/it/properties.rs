//! Property tests: invariants the papers imply, on random inputs.

use proptest::prelude::*;
use stopscan::offline::corner::{expected, worst_case};
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use stopscan::strategy::corner::circle::{self, Outcome};
use stopscan::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use stopscan::strategy::corner::{ExprecReading, StopList, exprec, unirec};

fn belief() -> impl Strategy<Value = AngleDistribution> {
    let normal = (0.0..180.0f64, 2.0..60.0f64).prop_map(|(m, s)| format!("normal:{m},{s}"));
    let uniform = (0.0..170.0f64, 5.0..180.0f64)
        .prop_map(|(a, w)| format!("uniform:{a},{}", (a + w).min(180.0)));
    let one = prop_oneof![normal, uniform];
    prop::collection::vec((0.05..1.0f64, one), 1..4).prop_map(|parts| {
        let spec = parts.iter().map(|(w, s)| format!("{w}*{s}")).collect::<Vec<_>>().join("+");
        AngleDistribution::parse(&format!("mix:{spec}")).unwrap()
    })
}

fn setup() -> impl Strategy<Value = CornerSetup> {
    (1.0..50.0f64, 0.1..20.0f64, 0.0..3.0f64, 0.1..3.0f64).prop_map(|(d, tau, mt, v)| {
        CornerSetup::new(d, CostModel::new(tau, mt, v).unwrap()).unwrap()
    })
}

proptest! {
    // A fixed seed: the same cases on every run and every machine.
    #![proptest_config(ProptestConfig {
        cases: 64,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x5709_5CA7),
        ..ProptestConfig::default()
    })]

    #[test]
    fn policy_iteration_equals_backward_induction(b in belief(), s in setup(), step in 2.0..15.0f64, mdp2 in any::<bool>(), literal in any::<bool>()) {
        let m = CornerMdp {
            setup: s,
            step: step.to_radians(),
            memory: if mdp2 { Memory::Last } else { Memory::None },
            reading: if literal { Reading::Literal } else { Reading::Conditional },
            belief: b,
        };
        let exact = m.solve().unwrap().model_value;
        let (general, _) = m.solve_general().unwrap();
        prop_assert!((exact - general).abs() <= 1e-9 * (1.0 + exact.abs()), "{exact} vs {general}");
    }

    #[test]
    fn optimal_mdp2_beats_unirec_and_exprec_on_the_same_grid(b in belief(), s in setup(), grid_deg in 1.0..6.0f64, m in 1usize..6) {
        let grid = grid_deg.to_radians();
        let delta = grid * m as f64;
        let p = CornerMdp { setup: s, step: grid, memory: Memory::Last, reading: Reading::Conditional, belief: b.clone() }
            .solve().unwrap();
        let best = expected(&p.stop_list, &s, &b).time;
        for list in [
            unirec(delta, Route::Arc, LastStep::Capped).unwrap(),
            exprec(delta, ExprecReading::TableI, Route::Arc, LastStep::Capped).unwrap(),
            exprec(delta, ExprecReading::Appendix, Route::Arc, LastStep::Capped).unwrap(),
        ] {
            // On the grid means every stop below the corner is a multiple of the grid step.
            prop_assume!(delta <= 1.0);
            let other = expected(&list, &s, &b).time;
            prop_assert!(best <= other + 1e-9 * other, "MDP2 {best} > {other}");
        }
    }

    #[test]
    fn policy2_never_worse_than_policy1(b in belief(), s in setup(), step in 2.0..15.0f64) {
        let solve = |memory| CornerMdp { setup: s, step: step.to_radians(), memory, reading: Reading::Conditional, belief: b.clone() }.solve().unwrap();
        let (p1, p2) = (solve(Memory::None), solve(Memory::Last));
        prop_assert!(expected(&p2.stop_list, &s, &b).time <= expected(&p1.stop_list, &s, &b).time + 1e-9);
    }

    #[test]
    fn every_worst_case_ratio_is_at_least_one(s in setup(), raw in prop::collection::vec(0.001..1.6f64, 0..30), chord in any::<bool>()) {
        let mut a = raw;
        a.sort_by(f64::total_cmp);
        a.dedup();
        let route = if chord { Route::Chord } else { Route::Arc };
        let list = StopList::from_nominal(&a, route, LastStep::Capped).unwrap();
        let w = worst_case(&list, &s);
        prop_assert!(w.worst_ratio >= 1.0, "{w:?}");
        prop_assert!(w.worst_ratio >= w.asymptotic_ratio);
    }

    #[test]
    fn c_is_at_least_two_for_large_d_and_tends_to_two(d in 1.6..5000.0f64) {
        let c = circle::ratio(d).unwrap();
        prop_assert!(c >= 2.0, "c({d}) = {c}");
        prop_assert!(c <= 2.168_545);
        // Theorem 1 for the circle strategy: c(d) > 2 − 1/d; Theorem 2: c(d) → 2.
        if d >= 100.0 {
            prop_assert!(c - 2.0 < 1e-3, "c({d}) = {c}");
        }
    }

    #[test]
    fn c_is_above_the_theorem_1_bound_everywhere(d in 0.01..100.0f64) {
        prop_assert!(circle::ratio(d).unwrap() > 2.0 - 1.0 / d);
    }

    #[test]
    fn reaching_is_monotone_in_c(d in 0.1..200.0f64, a in 1.0..3.0f64, b in 1.0..3.0f64) {
        let (lo, hi) = if a < b { (a, b) } else { (b, a) };
        if matches!(circle::run(d, lo), Outcome::Reached(_)) {
            prop_assert!(matches!(circle::run(d, hi), Outcome::Reached(_)));
        }
    }

    #[test]
    fn the_ratio_is_tight(d in 0.001..300.0f64) {
        let e = circle::ratio_excess(d).unwrap();
        prop_assert!(matches!(circle::run_excess(d, e), Outcome::Reached(_)));
        prop_assert!(!matches!(circle::run_excess(d, e * (1.0 - 1e-9)), Outcome::Reached(_)));
    }
}
