//! Whole runs at paper settings (population 50, 200 iterations). Targets (issue 3): one
//! single-UAV SPSO run with the `spso-mycost` objective <= 20 ms (issue 12: <= 10 ms); one
//! DLS-SMPSO run of a 5-UAV paper case <= 0.25 s. SPSO's DEM is used when `../shared/data/spso` has it, else the
//! procedural terrain. And one run of swarmplan's own method, `plan`'s default, at its
//! default budget (38,700 evaluations), seed 1 every time.

// criterion_group! makes a public function that cannot carry a doc comment.
#![allow(missing_docs)]

use criterion::{criterion_group, criterion_main, Criterion};
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_core::run::{run, RunRequest};
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

fn request(method: &str, seed: u64) -> RunRequest {
    RunRequest {
        method: Method::preset(method).expect("a preset"),
        params: OptimizerParams::default(),
        budget: Budget::iterations(200),
        seed,
    }
}

fn bench(c: &mut Criterion) {
    let dem = swarmplan_io::reference_data::shared_dir().join("data/spso/ChrismasTerrain.tif");
    let dem = dem.exists().then_some(dem);
    let mut group = c.benchmark_group("run");
    group.sample_size(10);
    let spso =
        build_world(&load_spec("spso-case1").expect("built-in"), dem.as_deref()).expect("world");
    let mut seed = 0;
    group.bench_function("spso/spso-case1", |b| {
        b.iter(|| {
            seed += 1;
            run(&spso, &request("spso", seed), &mut |_| {})
                .assessment
                .total
        });
    });
    for case in ["paper-case1", "paper-case2"] {
        let world = build_world(&load_spec(case).expect("built-in"), None).expect("world");
        group.bench_function(format!("dls-smpso/{case}"), |b| {
            b.iter(|| {
                seed += 1;
                run(&world, &request("dls-smpso", seed), &mut |_| {})
                    .assessment
                    .total
            });
        });
    }
    for case in ["paper-case1", "paper-case2"] {
        let world = build_world(&load_spec(case).expect("built-in"), None).expect("world");
        let method = Method::preset("swarmplan").expect("a preset");
        let req = RunRequest {
            method,
            params: OptimizerParams::default(),
            budget: method.optimizer.default_budget(),
            seed: 1,
        };
        group.bench_function(format!("swarmplan/{case}"), |b| {
            b.iter(|| run(&world, &req, &mut |_| {}).assessment.total);
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
