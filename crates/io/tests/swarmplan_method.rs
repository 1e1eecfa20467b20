//! swarmplan's own method (cooperative coevolution, feasibility first): deterministic per
//! seed, and feasible on `tiny` and on a small generated scenario within small budgets, for
//! every seed tried.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_core::run::{run, RunRequest};
use swarmplan_core::world::World;
use swarmplan_io::generate::{generate, GenerateRequest};
use swarmplan_io::scenario::{build_world, LoadedSpec};

use swarmplan_io::catalog::load_spec;

fn request(evaluations: u64, seed: u64) -> RunRequest {
    RunRequest {
        method: Method::preset("swarmplan").unwrap(),
        params: OptimizerParams::default(),
        budget: Budget::evaluations(evaluations),
        seed,
    }
}

fn generated() -> World {
    let spec = generate(&GenerateRequest {
        seed: 2,
        uavs: 3,
        threats: 4,
        shared_start: false,
        comm_windows: 0,
        terrain: None,
        free_pace: false,
        free_delays: false,
        slots: false,
    })
    .unwrap();
    let loaded = LoadedSpec {
        spec,
        origin: "generated".into(),
        base_dir: ".".into(),
        text: String::new(),
    };
    build_world(&loaded, None).unwrap()
}

#[test]
fn the_same_seed_gives_the_same_plan() {
    let world = build_world(&load_spec("tiny").unwrap(), None).unwrap();
    let a = run(&world, &request(1500, 9), &mut |_| {});
    let b = run(&world, &request(1500, 9), &mut |_| {});
    assert_eq!(a.outcome.best_x, b.outcome.best_x);
    assert_eq!(a.outcome.trace, b.outcome.trace);
    let c = run(&world, &request(1500, 10), &mut |_| {});
    assert_ne!(a.outcome.best_x, c.outcome.best_x);
}

#[test]
fn feasible_on_tiny_for_every_seed_within_3000_evaluations() {
    let world = build_world(&load_spec("tiny").unwrap(), None).unwrap();
    for seed in 1..=6 {
        let r = run(&world, &request(3000, seed), &mut |_| {});
        assert!(
            r.assessment.feasible(),
            "seed {seed}: {:?}",
            r.assessment.violations
        );
        assert_eq!(r.outcome.evaluations, 3000);
    }
}

#[test]
fn feasible_on_a_small_generated_scenario_within_6000_evaluations() {
    let world = generated();
    for seed in 1..=3 {
        let r = run(&world, &request(6000, seed), &mut |_| {});
        assert!(
            r.assessment.feasible(),
            "seed {seed}: {:?}",
            r.assessment.violations
        );
    }
}

#[test]
fn a_problem_rebuilt_with_earlier_corridors_samples_as_the_original() {
    // The Python binding rebuilds its planning problem per call from the corridors it
    // searched once; that must be the same problem.
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::PlanningProblem;
    use swarmplan_core::problem::Problem as _;
    let world = generated();
    let first = PlanningProblem::new(&world, EncodingKind::Spherical, InitKind::Corridor);
    assert!(first.corridors().iter().all(|c| c.len() >= 2));
    let again = PlanningProblem::with_corridors(
        &world,
        EncodingKind::Spherical,
        InitKind::Corridor,
        first.corridors().to_vec(),
    );
    let sample = |p: &PlanningProblem<'_>| {
        let mut rng = swarmplan_core::rng::rng_from_seed(9);
        let mut x = vec![0.0; p.bounds().len()];
        p.sample_initial(&mut rng, &mut x);
        x
    };
    let (a, b) = (sample(&first), sample(&again));
    assert_eq!(a, b);
    assert_eq!(first.evaluate(&a), again.evaluate(&b));
}
