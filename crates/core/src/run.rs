//! One planning run: an algorithm on an encoding of a world, from a seed, to an assessed
//! plan. The CLI's `plan` and the experiment runner both go through here, so a run is the
//! same thing wherever it happens.

use std::sync::Arc;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::cost::Assessment;
use crate::encoding::init::line_corridor_give_up;
use crate::method::Method;
use crate::optim::thinned::Thinned;
use crate::optim::{
    build, solve_watching, Budget, GiveUp, IterationRecord, OptimizerParams, Outcome, Termination,
};
use crate::plan::Plan;
use crate::planning::PlanningProblem;
use crate::problem::Problem;
use crate::rng::rng_from_seed;
use crate::world::World;

/// What to run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRequest {
    /// Optimizer, encoding and initialisation.
    pub method: Method,
    /// The optimizer's parameters.
    pub params: OptimizerParams,
    /// When to stop.
    pub budget: Budget,
    /// Seed of the run's random generator.
    pub seed: u64,
}

/// What a run produced.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunResult {
    /// The method that ran, as requested.
    pub method: Method,
    /// The seed it ran from, as requested.
    pub seed: u64,
    /// The optimizer's result: best point, evaluations, termination and trace.
    pub outcome: Outcome,
    /// The best point decoded into paths.
    pub plan: Plan,
    /// Full assessment of the best plan, with its violations.
    pub assessment: Assessment,
    /// Wall time of the optimisation (assessment excluded), seconds.
    pub seconds: f64,
}

impl RunResult {
    /// Judges the plan against `world` instead of the world it was searched on (a world
    /// grown by a flight margin, [`crate::world::flight_margin`]): the assessment becomes
    /// the one on `world`; returns the one the search made.
    pub fn judge_on(&mut self, world: &World) -> Assessment {
        let on_world = crate::cost::assess(world, &self.plan);
        std::mem::replace(&mut self.assessment, on_world)
    }
}

/// Runs `req` on `world`, calling `observer` after initialisation and every iteration.
#[must_use]
pub fn run(
    world: &World,
    req: &RunRequest,
    observer: &mut dyn FnMut(&IterationRecord),
) -> RunResult {
    let start = Instant::now();
    let (problem, outcome) = staged_search(world, req, &mut |r, _, _| observer(r));
    finish(world, req, &problem, outcome, start.elapsed().as_secs_f64())
}

/// The optimisation itself: the request's optimizer from its seed, on `problem`, within
/// `budget`, continuing `rng`.
fn search(
    problem: &dyn Problem,
    req: &RunRequest,
    budget: Budget,
    rng: &mut crate::rng::Rng,
    observer: &mut dyn FnMut(&IterationRecord, &[f64]),
) -> Outcome {
    let mut optimizer = build(req.method.optimizer, &req.params);
    solve_watching(problem, optimizer.as_mut(), budget, rng, observer)
}

/// An observer of a staged run: each record, the best point, and the problem it is a point
/// of (the stage's).
type StageObserver<'a> = dyn FnMut(&IterationRecord, &[f64], &PlanningProblem) + 'a;

/// The search of `req`, staged for the `line-corridor` and `line-band` starts: the line run,
/// given up when it is still far from feasible at half its evaluation budget
/// ([`line_corridor_give_up`]), then a corridor (or band, [`InitKind::after_line`]) run with
/// the evaluations left, the same generator going on; the better
/// of the two by Deb's rules is kept, with the problem that decodes it. Records of the
/// second stage count on from the first's evaluations and iterations. Any other start is
/// one stage.
fn staged_search<'w>(
    world: &'w World,
    req: &RunRequest,
    observer: &mut StageObserver<'_>,
) -> (PlanningProblem<'w>, Outcome) {
    let mut rng = rng_from_seed(req.seed);
    // One clock for the time limit over both stages and the problems' set-up (the
    // corridor's route search).
    let started = Some(req.budget.started.unwrap_or_else(Instant::now));
    let first = PlanningProblem::new(world, req.method.encoding, req.method.init);
    let after_line = req.method.init.after_line();
    let staged = after_line.is_some();
    let mut budget = req.budget;
    budget.started = started;
    if let (true, Some(total)) = (staged, budget.evaluations) {
        budget.give_up = Some(GiveUp {
            after_evaluations: total / 2,
            above_violation: line_corridor_give_up(world.uav_count()),
        });
    }
    let outcome = search(&first, req, budget, &mut rng, &mut |r, x| {
        observer(r, x, &first)
    });
    let next = match (outcome.termination, after_line) {
        (Termination::GaveUp, Some(next)) => next,
        _ => return (first, outcome),
    };
    let second = PlanningProblem::new(world, req.method.encoding, next);
    let mut rest = req.budget;
    rest.started = started;
    rest.evaluations = req
        .budget
        .evaluations
        .map(|t| t.saturating_sub(outcome.evaluations));
    rest.iterations = req
        .budget
        .iterations
        .map(|i| i.saturating_sub(outcome.iterations));
    let (spent, steps) = (outcome.evaluations, outcome.iterations);
    let later = search(&second, req, rest, &mut rng, &mut |r, x| {
        let shifted = IterationRecord {
            iteration: r.iteration + steps,
            evaluations: r.evaluations + spent,
            ..*r
        };
        observer(&shifted, x, &second);
    });
    let mut trace = outcome.trace;
    trace.extend(later.trace.iter().map(|r| IterationRecord {
        iteration: r.iteration + steps,
        evaluations: r.evaluations + spent,
        ..*r
    }));
    let merged = |best_x: Vec<f64>, best| Outcome {
        best_x,
        best,
        evaluations: spent + later.evaluations,
        iterations: steps + later.iterations,
        termination: later.termination,
        trace,
        restarted_after: Some(spent),
    };
    if later.best.better_than(&outcome.best) {
        (second, merged(later.best_x.clone(), later.best))
    } else {
        (first, merged(outcome.best_x, outcome.best))
    }
}

/// Decodes and fully assesses the best point of `outcome`.
fn finish(
    world: &World,
    req: &RunRequest,
    problem: &PlanningProblem,
    outcome: Outcome,
    seconds: f64,
) -> RunResult {
    let plan = problem.decode(&outcome.best_x);
    let assessment = crate::cost::assess(world, &plan);
    RunResult {
        method: req.method,
        seed: req.seed,
        outcome,
        plan,
        assessment,
        seconds,
    }
}

/// Per iteration, each UAV's cost in the best plan so far (see [`run_with_uav_trace`]),
/// row k beside record k of the outcome's trace (thinned alike past
/// [`TRACE_CAP`](crate::optim::thinned::TRACE_CAP) iterations). An iteration that keeps the
/// best shares the row before it, so memory holds one row per change of the best (a row
/// per kept iteration would be 52 MB at 100 UAVs and the cap's 65,537 rows).
pub type UavTrace = Vec<Arc<[f64]>>;

/// [`run`], also recording after initialisation and every iteration each UAV's cost (its
/// weighted terms, without the penalty) in the best plan so far: `trace[k][i]` for UAV i
/// at the iteration of record k of the outcome's trace (iteration k unless the run passed
/// [`TRACE_CAP`](crate::optim::thinned::TRACE_CAP) iterations). The optimizer sees exactly
/// the same evaluations; the extra assessments are left out of `seconds`.
/// `progress` is called after initialisation and every iteration too (for progress output).
#[must_use]
pub fn run_with_uav_trace(
    world: &World,
    req: &RunRequest,
    progress: &mut dyn FnMut(&IterationRecord),
) -> (RunResult, UavTrace) {
    let mut trace: Thinned<Arc<[f64]>> = Thinned::default();
    let mut previous: Option<Arc<[f64]>> = None;
    let mut observing = std::time::Duration::ZERO;
    // The best plan changes in few iterations (and under coevolution in one UAV at a
    // time): an unchanged best repeats its row, and the buffers persist so that proximity
    // re-sweeps only the pairs whose motion changed. Both are exact (same bits as a fresh
    // assessment; `crates/io/tests/incremental.rs`).
    let mut last_best: Vec<f64> = Vec::new();
    let mut scratch = crate::cost::Scratch::default();
    let mut observer = |r: &IterationRecord, best_x: &[f64], problem: &PlanningProblem| {
        let t0 = Instant::now();
        // Every record gets a row (none when there is no best yet), so that this trace
        // thins exactly as the loop's and row k stays beside record k.
        let row: Arc<[f64]> = if best_x.is_empty() {
            Arc::from(Vec::new())
        } else {
            match &previous {
                Some(row) if last_best.as_slice() == best_x => Arc::clone(row),
                _ => {
                    let mut sink =
                        crate::feasibility::ViolationSink::new(world.spec().planning.profile);
                    let plan = problem.decode(best_x);
                    let _ = crate::cost::assess_into(world, &plan, &mut scratch, &mut sink, false);
                    last_best.clear();
                    last_best.extend_from_slice(best_x);
                    scratch.reports().iter().map(|u| u.cost).collect()
                }
            }
        };
        previous = Some(Arc::clone(&row));
        trace.push(r, row);
        progress(r);
        observing += t0.elapsed();
    };
    let start = Instant::now();
    let (problem, outcome) = staged_search(world, req, &mut observer);
    let seconds = (start.elapsed() - observing).as_secs_f64();
    (
        finish(world, req, &problem, outcome, seconds),
        trace.into_vec(),
    )
}
