//! The staged `line-corridor` start ([`swarmplan_core::run`]): a run that is near feasible
//! at half its budget is the `line` run bit for bit; one far from it goes on from the
//! corridor with the evaluations left, within the budget, and is the same for the same seed.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{build_world, load_spec};

use swarmplan_core::encoding::init::InitKind;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams, Termination};
use swarmplan_core::run::{run, RunRequest};
use swarmplan_core::world::World;

fn world(name: &str) -> World {
    build_world(&load_spec(name).unwrap(), None).unwrap()
}

fn request(init: InitKind, evaluations: u64) -> RunRequest {
    let mut method = Method::preset("swarmplan").unwrap();
    method.init = init;
    RunRequest {
        method,
        params: OptimizerParams::default(),
        budget: Budget::evaluations(evaluations),
        seed: 7,
    }
}

#[test]
fn a_run_near_feasible_at_half_budget_is_the_line_run() {
    let w = world("tiny");
    let line = run(&w, &request(InitKind::Line, 2000), &mut |_| {});
    let staged = run(&w, &request(InitKind::LineCorridor, 2000), &mut |_| {});
    assert_eq!(staged.outcome.restarted_after, None);
    assert_eq!(staged.outcome.best_x, line.outcome.best_x);
    assert_eq!(staged.outcome.trace, line.outcome.trace);
    assert_eq!(
        staged.assessment.total.to_bits(),
        line.assessment.total.to_bits()
    );
}

#[test]
fn a_run_far_from_feasible_at_half_budget_goes_on_from_the_corridor() {
    // Case 2 after 200 evaluations still has more than twenty violations.
    let w = world("paper-case2");
    let req = request(InitKind::LineCorridor, 400);
    let staged = run(&w, &req, &mut |_| {});
    assert_eq!(staged.outcome.restarted_after, Some(200));
    assert_eq!(staged.outcome.evaluations, 400);
    assert_eq!(staged.outcome.termination, Termination::MaxEvaluations);
    // The records count on across the stages.
    let evals: Vec<u64> = staged.outcome.trace.iter().map(|r| r.evaluations).collect();
    assert!(evals.windows(2).all(|w| w[0] <= w[1]), "{evals:?}");
    assert_eq!(*evals.last().unwrap(), 400);
    // The kept plan is the better stage's, decoded by its own stage: its assessment is
    // the outcome's evaluation.
    assert_eq!(
        staged.assessment.total.to_bits(),
        staged.outcome.best.cost.to_bits()
    );
    // The same seed gives the same run.
    let again = run(&w, &req, &mut |_| {});
    assert_eq!(again.outcome.best_x, staged.outcome.best_x);
    assert_eq!(again.outcome.trace, staged.outcome.trace);
}

#[test]
fn the_time_limit_runs_on_one_clock_from_when_the_budget_says_it_started() {
    use std::time::{Duration, Instant};
    let w = world("paper-case2");
    let mut req = request(InitKind::LineCorridor, 400);
    // A clock started two seconds ago with a one-second limit: no iteration runs, in either
    // stage, whatever is left of the evaluations.
    req.budget.time_limit_ms = Some(1000);
    req.budget.started = Some(Instant::now().checked_sub(Duration::from_secs(2)).unwrap());
    let out = run(&w, &req, &mut |_| {});
    assert_eq!(out.outcome.termination, Termination::TimeLimit);
    assert_eq!(out.outcome.iterations, 0, "{:?}", out.outcome.trace);
    // Without a start the clock starts with the search: the same request runs to its end.
    req.budget.started = None;
    req.budget.time_limit_ms = Some(600_000);
    let out = run(&w, &req, &mut |_| {});
    assert_eq!(out.outcome.termination, Termination::MaxEvaluations);
    // Attempts share one clock too: a spent limit stops after the first attempt.
    req.budget.time_limit_ms = Some(1000);
    req.budget.started = Some(Instant::now().checked_sub(Duration::from_secs(2)).unwrap());
    let attempts = swarmplan_core::attempts::run_attempts(&w, &req, 3, &mut |_, _| {}, &mut |_| {});
    assert_eq!(attempts.records.len(), 1);
}
