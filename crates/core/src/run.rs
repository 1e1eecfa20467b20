//! One planning run: an algorithm on an encoding of a world, from a seed, to an assessed
//! plan. The CLI's `plan` and the experiment runner both go through here, so a run is the
//! same thing wherever it happens.

use std::sync::Mutex;
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::cost::Assessment;
use crate::encoding::EncodingKind;
use crate::optim::{build, solve, Algorithm, AlgorithmParams, Budget, IterationRecord, Outcome};
use crate::plan::Plan;
use crate::planning::PlanningProblem;
use crate::problem::{Bound, Evaluation, Problem};
use crate::rng::rng_from_seed;
use crate::world::World;

/// The encoding each algorithm uses by default: PSO on waypoint coordinates and APSO on
/// phase angles, as their sources define them; SPSO and DLS-SMPSO on spherical motion
/// vectors. The paper does not say what QPSO, GWO and ABC search over; its Tables 4-5 put
/// them within 30 % of DLS-SMPSO's cost, which on this problem only the motion encoding
/// comes near (on coordinates their best plans cost 30-80 times more, see
/// docs/results.md), so they default to the spherical encoding too. `--encoding` overrides.
#[must_use]
pub fn default_encoding(alg: Algorithm) -> EncodingKind {
    match alg {
        Algorithm::Spso
        | Algorithm::DlsSmpso
        | Algorithm::Qpso
        | Algorithm::Gwo
        | Algorithm::Abc => EncodingKind::Spherical,
        Algorithm::Apso => EncodingKind::Angle,
        Algorithm::Pso => EncodingKind::Cartesian,
    }
}

/// What to run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRequest {
    pub algorithm: Algorithm,
    /// `None`: the algorithm's paper pairing ([`default_encoding`]).
    pub encoding: Option<EncodingKind>,
    pub params: AlgorithmParams,
    pub budget: Budget,
    pub seed: u64,
}

/// What a run produced.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RunResult {
    pub algorithm: Algorithm,
    pub encoding: EncodingKind,
    pub seed: u64,
    pub outcome: Outcome,
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
    let problem = PlanningProblem::new(world, encoding_of(req));
    let start = Instant::now();
    let outcome = search(&problem, req, observer);
    finish(world, req, &problem, outcome, start.elapsed().as_secs_f64())
}

fn encoding_of(req: &RunRequest) -> EncodingKind {
    req.encoding
        .unwrap_or_else(|| default_encoding(req.algorithm))
}

/// The optimisation itself, on `searched` (the planning problem or a wrapper of it).
fn search(
    searched: &dyn Problem,
    req: &RunRequest,
    observer: &mut dyn FnMut(&IterationRecord),
) -> Outcome {
    let mut optimizer = build(req.algorithm, &req.params);
    let mut rng = rng_from_seed(req.seed);
    solve(searched, optimizer.as_mut(), req.budget, &mut rng, observer)
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
        algorithm: req.algorithm,
        encoding: problem.encoding(),
        seed: req.seed,
        outcome,
        plan,
        assessment,
        seconds,
    }
}

/// A problem that remembers the best point evaluated so far (every optimizer's best is the
/// best it evaluated), so an observer can look at it between iterations.
struct BestTracker<'a> {
    inner: &'a dyn Problem,
    best: Mutex<(Evaluation, Vec<f64>)>,
}

impl Problem for BestTracker<'_> {
    fn bounds(&self) -> &[Bound] {
        self.inner.bounds()
    }

    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let e = self.inner.evaluate(x);
        let mut best = self
            .best
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        if best.1.is_empty() || e.better_than(&best.0) {
            best.0 = e;
            best.1.clear();
            best.1.extend_from_slice(x);
        }
        e
    }
}

/// [`run`], also recording after initialisation and every iteration each UAV's cost (its
/// weighted terms, without the penalty) in the best plan so far: `trace[k][i]` for
/// iteration k and UAV i. The optimizer sees exactly the same evaluations; the extra
/// assessments are left out of `seconds`.
#[must_use]
pub fn run_with_uav_trace(world: &World, req: &RunRequest) -> (RunResult, Vec<Vec<f64>>) {
    let problem = PlanningProblem::new(world, encoding_of(req));
    let tracker = BestTracker {
        inner: &problem,
        best: Mutex::new((Evaluation::worst(), Vec::new())),
    };
    let mut trace = Vec::new();
    let mut observing = std::time::Duration::ZERO;
    let mut observer = |_: &IterationRecord| {
        let t0 = Instant::now();
        let x = tracker
            .best
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
            .1
            .clone();
        if !x.is_empty() {
            let a = crate::cost::assess(world, &problem.decode(&x), false);
            trace.push(a.per_uav.iter().map(|u| u.cost).collect());
        }
        observing += t0.elapsed();
    };
    let start = Instant::now();
    let outcome = search(&tracker, req, &mut observer);
    let seconds = (start.elapsed() - observing).as_secs_f64();
    (finish(world, req, &problem, outcome, seconds), trace)
}
