//! Criterion benchmarks of the corner family, at the sizes the targets name.
//!
//! `cargo bench -p stopscan --bench corner`; `stopscan bench mdp|circle|ratio` prints the same
//! measurements as JSON.

use std::f64::consts::FRAC_PI_2;
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
        g.bench_with_input(BenchmarkId::new("backward_induction", n), &m, |b, m| {
            b.iter(|| black_box(m.solve().unwrap().model_value));
        });
    }
    let m = mdp(180);
    g.bench_with_input(BenchmarkId::new("policy_iteration", 180), &m, |b, m| {
        b.iter(|| black_box(m.solve_general().unwrap().0));
    });
    g.finish();
}

fn circle_ratio(c: &mut Criterion) {
    let mut g = c.benchmark_group("circle");
    g.sample_size(10);
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
    let ds: Vec<f64> = (0..100_000).map(|_| rng.random_range(0.01..100.0)).collect();
    g.bench_function("ratio/n=100000", |b| {
        b.iter(|| black_box(ds.iter().map(|&d| circle::ratio(d).unwrap_or(f64::NAN)).sum::<f64>()));
    });
    g.finish();
}

fn ratio(c: &mut Criterion) {
    let delta = FRAC_PI_2 / 1000.0;
    let setup = CornerSetup::new(1.0 / delta, CostModel::default()).unwrap();
    let list = unirec(delta * (1.0 - 1e-9), Route::Arc, LastStep::Capped).unwrap();
    c.bench_function("worst_case/stops=1001", |b| b.iter(|| black_box(worst_case(&list, &setup))));
}

criterion_group!(benches, mdp2, circle_ratio, ratio);
criterion_main!(benches);
