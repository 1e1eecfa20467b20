//! Bounded evaluations change no run (issue 12, docs/performance.md): every preset on the
//! planning problem, which gives up evaluations that cannot beat what they are compared
//! with, makes the same run as on the same problem evaluated in full every time.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{build_world, load_spec};

use swarmplan_core::method::PRESETS;
use swarmplan_core::optim::{build, solve, Budget, OptimizerParams, Outcome};
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::BlockProblem;
use swarmplan_core::problem::{Bound, Evaluation, Problem};
use swarmplan_core::rng::{rng_from_seed, Rng};

/// A problem evaluated in full every time: everything delegated but the bounded
/// evaluations, which keep the trait's defaults.
struct Full<'a>(&'a PlanningProblem<'a>);

impl Problem for Full<'_> {
    fn bounds(&self) -> &[Bound] {
        self.0.bounds()
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        self.0.evaluate(x)
    }
    fn sample_initial(&self, rng: &mut Rng, out: &mut [f64]) {
        self.0.sample_initial(rng, out);
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for Full<'_> {
    fn nudge(
        &self,
        x: &[f64],
        block: usize,
        site: Option<usize>,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        self.0.nudge(x, block, site, rng, out)
    }

    fn hot_spots(&self, x: &[f64], block: usize, out: &mut Vec<f64>) -> bool {
        self.0.hot_spots(x, block, out)
    }

    fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
        self.0.evaluate_blocks(x, by_block)
    }

    fn block_size(&self) -> usize {
        self.0.block_size()
    }
}

fn outcome(problem: &dyn Problem, preset: &str) -> Outcome {
    let method = swarmplan_core::method::Method::preset(preset).unwrap();
    let mut optimizer = build(method.optimizer, &OptimizerParams::default());
    solve(
        problem,
        optimizer.as_mut(),
        Budget::evaluations(2500),
        &mut rng_from_seed(11),
        &mut |_| {},
    )
}

#[test]
fn every_preset_runs_the_same_with_bounded_evaluations() {
    for case in ["paper-case2", "tiny"] {
        let world = build_world(&load_spec(case).unwrap(), None).unwrap();
        for preset in PRESETS {
            let m = preset.method;
            let problem = PlanningProblem::new(&world, m.encoding, m.init);
            let bounded = outcome(&problem, preset.name);
            let full = outcome(&Full(&problem), preset.name);
            assert_eq!(bounded.best_x, full.best_x, "{case} {}", preset.name);
            assert_eq!(bounded.trace, full.trace, "{case} {}", preset.name);
            assert_eq!(
                bounded.evaluations, full.evaluations,
                "{case} {}",
                preset.name
            );
        }
    }
}

/// The test above must see evaluations given up: a cost cutoff below a plan's cost gives it
/// up, one at its cost does not and returns the full evaluation.
#[test]
fn cost_bounded_evaluations_give_up_below_the_cost_and_not_at_it() {
    let world = build_world(&load_spec("paper-case2").unwrap(), None).unwrap();
    let m = swarmplan_core::method::Method::preset("pso").unwrap();
    let problem = PlanningProblem::new(&world, m.encoding, m.init);
    let mut x = vec![0.0; problem.dimension()];
    for seed in 0..5 {
        problem.sample_initial(&mut rng_from_seed(seed), &mut x);
        let full = problem.evaluate(&x);
        assert!(problem.evaluate_cost_bounded(&x, 0.5 * full.cost).is_none());
        let kept = problem.evaluate_cost_bounded(&x, full.cost).unwrap();
        assert_eq!(kept.cost.to_bits(), full.cost.to_bits());
        assert_eq!(kept.violation.to_bits(), full.violation.to_bits());
    }
}
