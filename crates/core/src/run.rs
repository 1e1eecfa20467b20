//! One planning run: an algorithm on an encoding of a world, from a seed, to an assessed
//! plan. The CLI's `plan` and the experiment runner both go through here, so a run is the
//! same thing wherever it happens.

use std::sync::Arc;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::cost::Assessment;
use crate::method::Method;
use crate::optim::thinned::Thinned;
use crate::optim::{build, solve_watching, Budget, IterationRecord, OptimizerParams, Outcome};
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

/// Runs `req` on `world`, calling `observer` after initialisation and every iteration.
#[must_use]
pub fn run(
    world: &World,
    req: &RunRequest,
    observer: &mut dyn FnMut(&IterationRecord),
) -> RunResult {
    let problem = PlanningProblem::new(world, req.method.encoding, req.method.init);
    let start = Instant::now();
    let outcome = search(&problem, req, &mut |r, _| observer(r));
    finish(world, req, &problem, outcome, start.elapsed().as_secs_f64())
}

/// The optimisation itself: the request's optimizer from its seed.
fn search(
    problem: &dyn Problem,
    req: &RunRequest,
    observer: &mut dyn FnMut(&IterationRecord, &[f64]),
) -> Outcome {
    let mut optimizer = build(req.method.optimizer, &req.params);
    let mut rng = rng_from_seed(req.seed);
    solve_watching(problem, optimizer.as_mut(), req.budget, &mut rng, observer)
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
    let assessment = crate::cost::assess(world, &plan, true);
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
    let problem = PlanningProblem::new(world, req.method.encoding, req.method.init);
    let mut trace: Thinned<Arc<[f64]>> = Thinned::default();
    let mut previous: Option<Arc<[f64]>> = None;
    let mut observing = std::time::Duration::ZERO;
    // The best plan changes in few iterations (and under coevolution in one UAV at a
    // time): an unchanged best repeats its row, and the buffers persist so that proximity
    // re-sweeps only the pairs whose motion changed. Both are exact (same bits as a fresh
    // assessment; `crates/io/tests/incremental.rs`).
    let mut last_best: Vec<f64> = Vec::new();
    let mut scratch = crate::cost::Scratch::default();
    let mut observer = |r: &IterationRecord, best_x: &[f64]| {
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
    let outcome = search(&problem, req, &mut observer);
    let seconds = (start.elapsed() - observing).as_secs_f64();
    (
        finish(world, req, &problem, outcome, seconds),
        trace.into_vec(),
    )
}
