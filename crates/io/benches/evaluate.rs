//! One full evaluation (decode + every cost term + every constraint) of a plan, as the
//! optimizers call it. Targets (issue 12, docs/performance.md): <= 10 us for the paper
//! cases' 5 UAVs, <= 1 ms for 100 UAVs, on the project's 2-core machine.
//!
//! Three kinds of input:
//! - `evaluate/<case>/<encoding>`: 64 uniform random vectors of the box (sharp turns
//!   everywhere, the worst case for the flown path's arcs);
//! - `evaluate/<case>/planned`: 64 small perturbations (1 % of each bound's width) of a plan
//!   found by a short swarmplan run, what a search evaluates once it has found the corridor;
//! - `scale/<n>`: generated scenarios `gen-s1-u<n>-t12` with 5 to 100 UAVs, 64 vectors from
//!   the swarmplan method's initialisation.
//!
//! And their incremental counterparts (`incremental/<case>`, `scale-incremental/<n>`): the
//! same vectors, each followed by itself with one UAV's block perturbed (the UAV in turn),
//! so every evaluation differs from the one before in one UAV, what the cooperative
//! optimizer's visits and the dimensional-learning probes evaluate. The buffers keep the
//! pair results of the UAVs that did not move (target: <= 3 us at 5 UAVs).

// criterion_group! makes a public function that cannot carry a doc comment.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use rand::Rng as _;
use rand_distr::{Distribution, Normal};
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::BlockProblem;
use swarmplan_core::problem::Problem;
use swarmplan_core::rng::rng_from_seed;
use swarmplan_core::run::{run, RunRequest};
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

/// Evaluates the vectors `xs` in turn.
fn cycle(c: &mut Criterion, name: &str, problem: &PlanningProblem<'_>, xs: &[Vec<f64>]) {
    let mut i = 0;
    c.bench_function(name, |b| {
        b.iter(|| {
            i = (i + 1) % xs.len();
            std::hint::black_box(problem.evaluate(std::hint::black_box(&xs[i])))
        });
    });
}

/// `base`, `base` with block 0 moved, `base`, `base` with block 1 moved, ... (`len` moves,
/// the blocks in turn): every entry, the first after the last included, differs from the
/// one before in one block.
fn one_block_walk(problem: &PlanningProblem<'_>, base: &[f64], len: usize) -> Vec<Vec<f64>> {
    let block = problem.block_size();
    let blocks = problem.dimension() / block;
    let mut rng = rng_from_seed(45);
    let mut out = Vec::with_capacity(2 * len);
    for k in 0..len {
        let b = k % blocks;
        let mut moved = base.to_vec();
        for (j, x) in moved.iter_mut().enumerate().skip(b * block).take(block) {
            let bound = problem.bounds()[j];
            let noise = Normal::new(0.0, 0.01 * bound.width()).map_or(0.0, |d| d.sample(&mut rng));
            *x = bound.project(*x + noise);
        }
        out.push(base.to_vec());
        out.push(moved);
    }
    out
}

fn paper_cases(c: &mut Criterion) {
    for case in ["paper-case1", "paper-case2"] {
        let loaded = load_spec(case).expect("built-in scenario");
        let world = build_world(&loaded, None).expect("built-in world");
        for kind in [EncodingKind::Spherical, EncodingKind::Cartesian] {
            let problem = PlanningProblem::new(&world, kind, InitKind::Uniform);
            let mut rng = rng_from_seed(42);
            let xs: Vec<Vec<f64>> = (0..64)
                .map(|_| {
                    problem
                        .bounds()
                        .iter()
                        .map(|b| b.lo + rng.random::<f64>() * b.width())
                        .collect()
                })
                .collect();
            cycle(c, &format!("evaluate/{case}/{kind}"), &problem, &xs);
        }
        // The uniform start these inputs were measured with (docs/performance.md), pinned so
        // that `swarmplan`'s own start changing does not change what is timed.
        let method = Method::preset("swarmplan-uniform").expect("a preset");
        let found = run(
            &world,
            &RunRequest {
                method,
                params: OptimizerParams::default(),
                budget: Budget::evaluations(4000),
                seed: 1,
            },
            &mut |_| {},
        );
        let problem = PlanningProblem::new(&world, method.encoding, method.init);
        let mut rng = rng_from_seed(43);
        let xs: Vec<Vec<f64>> = (0..64)
            .map(|_| {
                found
                    .outcome
                    .best_x
                    .iter()
                    .zip(problem.bounds())
                    .map(|(x, b)| {
                        let noise =
                            Normal::new(0.0, 0.01 * b.width()).map_or(0.0, |d| d.sample(&mut rng));
                        b.project(x + noise)
                    })
                    .collect()
            })
            .collect();
        cycle(c, &format!("evaluate/{case}/planned"), &problem, &xs);
        let walk = one_block_walk(&problem, &xs[0], 64);
        cycle(c, &format!("incremental/{case}"), &problem, &walk);
    }
}

/// One benchmark per generated fleet size, each cycling through the inputs that `inputs`
/// makes for that problem.
fn scale_group(
    c: &mut Criterion,
    name: &str,
    inputs: impl Fn(&PlanningProblem<'_>) -> Vec<Vec<f64>>,
) {
    let mut group = c.benchmark_group(name);
    group.sample_size(20);
    for n in [5, 10, 20, 50, 100] {
        let loaded = load_spec(&format!("gen-s1-u{n}-t12")).expect("a generated scenario");
        let world = build_world(&loaded, None).expect("a generated world");
        let method = Method::preset("swarmplan-uniform").expect("a preset");
        let problem = PlanningProblem::new(&world, method.encoding, method.init);
        let xs = inputs(&problem);
        let mut i = 0;
        group.bench_with_input(BenchmarkId::from_parameter(n), &n, |b, _| {
            b.iter(|| {
                i = (i + 1) % xs.len();
                std::hint::black_box(problem.evaluate(std::hint::black_box(&xs[i])))
            });
        });
    }
    group.finish();
}

/// A vector of the uniform initialisation the scale benches measure, from `rng`.
fn initial(problem: &PlanningProblem<'_>, rng: &mut swarmplan_core::rng::Rng) -> Vec<f64> {
    let mut x = vec![0.0; problem.dimension()];
    problem.sample_initial(rng, &mut x);
    x
}

fn scale(c: &mut Criterion) {
    scale_group(c, "scale", |problem| {
        let mut rng = rng_from_seed(44);
        (0..64).map(|_| initial(problem, &mut rng)).collect()
    });
}

fn scale_incremental(c: &mut Criterion) {
    scale_group(c, "scale-incremental", |problem| {
        let mut rng = rng_from_seed(44);
        one_block_walk(problem, &initial(problem, &mut rng), 64)
    });
}

criterion_group!(benches, paper_cases, scale, scale_incremental);
criterion_main!(benches);
