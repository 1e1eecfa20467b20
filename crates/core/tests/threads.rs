//! A run is the same plan, bit for bit, on one thread or on several (issue 12): swarms are
//! evaluated in parallel ([`swarmplan_core::optim::Evaluator::evaluate_rows`]) but used in
//! row order, and evaluation is pure.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{build_world, load_spec};

use swarmplan_core::method::{Method, PRESETS};
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_core::run::{run, RunRequest, RunResult};
use swarmplan_core::world::World;

fn run_on(threads: usize, world: &World, req: &RunRequest) -> RunResult {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap()
        .install(|| run(world, req, &mut |_| {}))
}

#[test]
fn every_preset_plans_the_same_on_one_and_on_three_threads() {
    let world = build_world(&load_spec("paper-case2").unwrap(), None).unwrap();
    for preset in PRESETS {
        let req = RunRequest {
            method: Method::preset(preset.name).unwrap(),
            params: OptimizerParams::default(),
            budget: Budget::evaluations(1200),
            seed: 17,
        };
        let one = run_on(1, &world, &req);
        let three = run_on(3, &world, &req);
        assert_eq!(one.outcome.best_x, three.outcome.best_x, "{}", preset.name);
        assert_eq!(one.outcome.trace, three.outcome.trace, "{}", preset.name);
        assert_eq!(
            one.outcome.evaluations, three.outcome.evaluations,
            "{}",
            preset.name
        );
        assert_eq!(
            one.assessment.total.to_bits(),
            three.assessment.total.to_bits(),
            "{}",
            preset.name
        );
    }
}
