//! Independent attempts: the same run from further seeds until one plan is feasible.
//!
//! Why: on hard instances a run of swarmplan's method ends in one basin and stays there:
//! on the outside benchmark's instance 0 half the seeds end feasible and half end stuck
//! with two UAVs too close at the edge of the take-off zone, and twice the budget in one run
//! does not change that (docs/results.md, "Repairs, a doubled budget, ..."), while another
//! seed succeeds as often as the first. Runs from independent seeds fail independently, so
//! K attempts that each succeed with probability p give a feasible plan with probability
//! 1 - (1 - p)^K, the classic case for restarts of a randomised search (Luby, Sinclair &
//! Zuckerman 1993, "Optimal speedup of Las Vegas algorithms", Information Processing
//! Letters 47(4):173-180, doi:10.1016/0020-0190(93)90029-9).
//!
//! This is more budget, not a better method: each attempt spends the whole budget (unless it
//! stops at its first feasible plan), so benchmarks at equal evaluations never use it, and
//! `plan` reports every attempt's seed and evaluations. Attempt 1 is the run of the request's
//! seed itself, so one attempt is exactly the plain run; attempt k > 1 runs from
//! [`attempt_seed`], and the plan returned carries the seed of the attempt that made it, so
//! `plan --seed` with that seed repeats it on its own.

use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::json_f64;
use crate::optim::IterationRecord;
use crate::rng::derive_seed;
use crate::run::{run_with_uav_trace, RunRequest, RunResult, UavTrace};
use crate::world::World;

/// Most attempts one request may ask for.
pub const MAX_ATTEMPTS: usize = 1000;

/// The seed of attempt `attempt` (1-based) of a request with seed `seed`: the seed itself
/// for the first, a derived one for the others.
#[must_use]
pub fn attempt_seed(seed: u64, attempt: usize) -> u64 {
    if attempt <= 1 {
        seed
    } else {
        derive_seed(seed, &["attempt"], attempt as u64)
    }
}

/// What one attempt gave.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AttemptRecord {
    /// 1-based.
    pub attempt: usize,
    /// The seed it ran from ([`attempt_seed`]).
    pub seed: u64,
    /// Whether its best plan satisfies every hard constraint.
    pub feasible: bool,
    /// The hard-violation measure of its best plan (0 when feasible).
    #[serde(with = "json_f64")]
    pub violation: f64,
    /// Hard violations of its best plan.
    pub violations: usize,
    /// Penalised cost of its best plan.
    #[serde(with = "json_f64")]
    pub cost: f64,
    /// Evaluations it spent, initialisation included.
    pub evaluations: u64,
    /// Wall time of its optimisation, s.
    #[serde(with = "json_f64")]
    pub seconds: f64,
}

impl AttemptRecord {
    fn of(attempt: usize, r: &RunResult) -> Self {
        let a = &r.assessment;
        Self {
            attempt,
            seed: r.seed,
            feasible: a.feasible(),
            violation: a.violation,
            violations: a
                .violations
                .as_deref()
                .map_or(0, |l| l.iter().filter(|v| v.hard).count()),
            cost: a.total,
            evaluations: r.outcome.evaluations,
            seconds: r.seconds,
        }
    }

    /// Better than `other`: feasible first, then the smaller violation, then the cost.
    fn better_than(&self, other: &Self) -> bool {
        (self.violation, self.cost) < (other.violation, other.cost)
    }
}

/// The attempts made, and the best one's run with its per-UAV trace (as
/// [`run_with_uav_trace`] returns it).
#[derive(Debug, Clone)]
pub struct Attempts {
    /// The kept attempt's run: the first feasible one, or else the best infeasible one.
    pub result: RunResult,
    /// Per-iteration cost of each UAV in the kept attempt's run.
    pub uav_trace: UavTrace,
    /// One record per attempt made, in order.
    pub records: Vec<AttemptRecord>,
}

impl Attempts {
    /// The 1-based number of the attempt whose plan was kept.
    #[must_use]
    pub fn chosen(&self) -> usize {
        self.records
            .iter()
            .find(|r| r.seed == self.result.seed)
            .map_or(1, |r| r.attempt)
    }
}

/// Runs `req` up to `attempts` times (at least once), from [`attempt_seed`]s, stopping at the
/// first feasible plan; returns that one, or the best infeasible one (smallest violation,
/// then cost; the earlier on a tie). A time limit in `req.budget` bounds all attempts
/// together: each gets what is left, and none starts once it is spent. `progress` sees every
/// iteration record with its attempt number; `done` sees each attempt's record as it ends.
#[must_use]
pub fn run_attempts(
    world: &World,
    req: &RunRequest,
    attempts: usize,
    progress: &mut dyn FnMut(usize, &IterationRecord),
    done: &mut dyn FnMut(&AttemptRecord),
) -> Attempts {
    let attempts = attempts.clamp(1, MAX_ATTEMPTS);
    let start = req.budget.started.unwrap_or_else(Instant::now);
    let mut best: Option<(RunResult, UavTrace, AttemptRecord)> = None;
    let mut records = Vec::new();
    for attempt in 1..=attempts {
        let mut r = req.clone();
        r.seed = attempt_seed(req.seed, attempt);
        // One clock for every attempt: the limit bounds them together.
        r.budget.started = Some(start);
        if let Some(total) = req.budget.time_limit_ms {
            if attempt > 1 && start.elapsed().as_millis() >= u128::from(total) {
                break;
            }
        }
        let (result, trace) = run_with_uav_trace(world, &r, &mut |rec| progress(attempt, rec));
        let record = AttemptRecord::of(attempt, &result);
        done(&record);
        records.push(record);
        let feasible = record.feasible;
        if best.as_ref().is_none_or(|(_, _, b)| record.better_than(b)) {
            best = Some((result, trace, record));
        }
        if feasible || req.budget.cancel.requested() {
            break;
        }
    }
    let (result, uav_trace, _) = best.expect("at least one attempt runs");
    Attempts {
        result,
        uav_trace,
        records,
    }
}
