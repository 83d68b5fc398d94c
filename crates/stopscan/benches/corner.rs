//! Criterion benchmarks of the corner family, at the sizes the targets name. Each
//! checks the value it computes while it is timed: the MDP values against the independent
//! general solver, the circle ratios against Theorem 1's bracket, the worst case against its
//! closed-form bound.
//!
//! `cargo bench -p stopscan --bench corner`; `stopscan bench mdp|circle|ratio` prints the same
//! measurements as JSON.

use std::f64::consts::{FRAC_PI_2, PI};
use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use rand::{RngExt, SeedableRng};
use stopscan::offline::corner::worst_case;
use stopscan::protocol::CostModel;
use stopscan::protocol::corner::{AngleDistribution, CornerSetup, LastStep, Route};
use stopscan::strategy::corner::mdp::{CornerMdp, Memory, Reading};
use stopscan::strategy::corner::{circle, unirec};

fn mdp(n: usize) -> CornerMdp {
    CornerMdp {
        setup: CornerSetup::new(10.0, CostModel::new(2.0, 0.0, 0.5).unwrap()).unwrap(),
        step: FRAC_PI_2 / n as f64,
        memory: Memory::Last,
        reading: Reading::Conditional,
        belief: AngleDistribution::parse("mix:0.5*normal:30,3+0.5*normal:90,3").unwrap(),
    }
}

fn mdp2(c: &mut Criterion) {
    let mut g = c.benchmark_group("mdp2");
    g.sample_size(20);
    for n in [900, 1800] {
        let m = mdp(n);
        // The general sparse solver (policy iteration) is an independent check of the exact
        // backward sweep that is timed.
        let want = m.solve_general().unwrap().0;
        g.bench_with_input(BenchmarkId::new("backward_induction", n), &m, |b, m| {
            b.iter(|| {
                let v = m.solve().unwrap().model_value;
                assert!((v - want).abs() <= 1e-9 * want, "n = {n}: {v} vs {want}");
                black_box(v)
            });
        });
    }
    let m = mdp(180);
    // The start-state value at n = 180 (pymdptoolbox agrees to 8e-8, see the README), here
    // from the backward sweep.
    let want = m.solve().unwrap().model_value;
    assert!((want - 25.228_313_6).abs() < 1e-7, "{want}");
    g.bench_with_input(BenchmarkId::new("policy_iteration", 180), &m, |b, m| {
        b.iter(|| {
            let v = m.solve_general().unwrap().0;
            assert!((v - want).abs() <= 1e-9 * want, "{v} vs {want}");
            black_box(v)
        });
    });
    g.finish();
}

fn circle_ratio(c: &mut Criterion) {
    let mut g = c.benchmark_group("circle");
    g.sample_size(10);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
    let ds: Vec<f64> = (0..100_000).map(|_| rng.random_range(0.01..100.0)).collect();
    // Table 1 of the circle paper: c(40) = 2.001525 to its six digits.
    assert_eq!((circle::ratio(40.0).unwrap() * 1e6).floor(), 2_001_525.0);
    g.bench_function("ratio/n=100000", |b| {
        b.iter(|| {
            let sum = ds
                .iter()
                .map(|&d| {
                    let c = circle::ratio(d).unwrap();
                    // Theorem 1 (c > 2 − 1/d) and driving straight to the corner (c ≤ 1 + d).
                    assert!(c > 2.0 - 1.0 / d && c <= 1.0 + d, "c({d}) = {c}");
                    c
                })
                .sum::<f64>();
            black_box(sum)
        });
    });
    g.finish();
}

fn ratio(c: &mut Criterion) {
    let delta = FRAC_PI_2 / 1000.0;
    let setup = CornerSetup::new(1.0 / delta, CostModel::default()).unwrap();
    let list = unirec(delta * (1.0 - 1e-9), Route::Arc, LastStep::Capped).unwrap();
    assert_eq!(list.len(), 1001);
    // UNIREC's worst case lies below (π + 2δ)/(1 + δ) and tends to π as δ → 0.
    let bound = (PI + 2.0 * delta) / (1.0 + delta);
    c.bench_function("worst_case/stops=1001", |b| {
        b.iter(|| {
            let w = worst_case(&list, &setup);
            assert!(w.worst_ratio <= bound && w.worst_ratio > PI - 0.01, "{w:?}");
            black_box(w)
        });
    });
}

criterion_group!(benches, mdp2, circle_ratio, ratio);
criterion_main!(benches);
