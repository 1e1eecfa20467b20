//! One full evaluation (decode + every cost term + every constraint) of a 5-UAV plan in the
//! paper's cases. Target (issue 2): <= 20 us on the project's 2-core machine.

use criterion::{criterion_group, criterion_main, Criterion};
use rand::Rng as _;
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::Problem;
use swarmplan_core::rng::rng_from_seed;
use swarmplan_io::scenario::{build_world, load_spec};

fn bench(c: &mut Criterion) {
    for case in ["paper-case1", "paper-case2"] {
        let loaded = load_spec(case).expect("built-in scenario");
        let world = build_world(&loaded, None).expect("built-in world");
        for kind in [EncodingKind::Spherical, EncodingKind::Cartesian] {
            let problem = PlanningProblem::new(&world, kind, InitKind::Uniform);
            let mut rng = rng_from_seed(42);
            // 64 random candidates, cycled: a mix of what optimizers evaluate.
            let xs: Vec<Vec<f64>> = (0..64)
                .map(|_| {
                    problem
                        .bounds()
                        .iter()
                        .map(|b| b.lo + rng.random::<f64>() * b.width())
                        .collect()
                })
                .collect();
            let mut i = 0;
            c.bench_function(&format!("evaluate/{case}/{kind}"), |b| {
                b.iter(|| {
                    i = (i + 1) % xs.len();
                    std::hint::black_box(problem.evaluate(std::hint::black_box(&xs[i])))
                });
            });
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
