//! The solve loop: budget, observer, evaluation count and termination reason.
//!
//! As in argmin's executor, an optimizer only knows how to start and how to take one step;
//! [`solve`] owns everything around that. It records the best cost after initialisation
//! (iteration 0) and after every step, hands each record to an observer (progress output,
//! convergence curves) and keeps them in the [`Outcome`].

use serde::{Deserialize, Serialize};

use super::{Evaluator, Optimizer};
use crate::problem::{Evaluation, Problem};
use crate::rng::Rng;

/// Iterations of a run when no budget is given (the paper's setting).
pub const DEFAULT_ITERATIONS: usize = 200;

/// When to stop. Either limit may be absent; with both absent the run does
/// [`DEFAULT_ITERATIONS`] iterations. In a file, a missing field means "no such limit"
/// (so `evaluations = 10000` alone is a pure evaluation budget, for comparisons at equal
/// evaluations), and an empty table means the default.
///
/// Two further stops serve anytime planning: a wall-clock limit (checked between
/// iterations; a run stopped by it is *not* reproducible, since how far it got depends on
/// the machine, and records say so by their termination reason) and a stop at the first
/// feasible best plan.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Budget {
    /// Maximum number of steps after initialisation (200).
    #[serde(default)]
    pub iterations: Option<usize>,
    /// Maximum number of evaluations, initialisation included (none). Never exceeded: the
    /// step that reaches it is cut short.
    #[serde(default)]
    pub evaluations: Option<u64>,
    /// Wall-clock limit in milliseconds (none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub time_limit_ms: Option<u64>,
    /// Stop as soon as the best plan is feasible (false).
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub until_feasible: bool,
    /// Give the run up once it has spent this many evaluations with a best plan whose
    /// violation measure is still above the given one (none): a staged run then goes on
    /// from another start ([`crate::run`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub give_up: Option<GiveUp>,
    /// A flag that stops the run between iterations ([`super::cancel`]; none).
    #[serde(skip)]
    pub cancel: super::cancel::Cancel,
    /// When the wall-clock limit's clock started (none: when the search's iterations
    /// start). A command sets it when it begins, so that loading the scenario, the route
    /// layer's searches, both stages of a staged run and every attempt count in one limit.
    #[serde(skip)]
    pub started: Option<std::time::Instant>,
}

/// When a run is given up ([`Budget::give_up`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct GiveUp {
    /// Evaluations spent before the check.
    pub after_evaluations: u64,
    /// The best plan's violation measure above which the run is given up (every violation
    /// counts at least 1, so this is about a number of violations).
    pub above_violation: u32,
}

impl Budget {
    /// [`DEFAULT_ITERATIONS`] iterations, no other limit.
    pub const DEFAULT: Self = Self::new(Some(DEFAULT_ITERATIONS), None);

    /// A budget of at most `iterations` and at most `evaluations` (`None`: no such limit).
    #[must_use]
    pub const fn new(iterations: Option<usize>, evaluations: Option<u64>) -> Self {
        Self {
            iterations,
            evaluations,
            time_limit_ms: None,
            until_feasible: false,
            give_up: None,
            cancel: super::cancel::Cancel::NONE,
            started: None,
        }
    }

    /// A budget of `n` iterations and unlimited evaluations.
    #[must_use]
    pub const fn iterations(n: usize) -> Self {
        Self::new(Some(n), None)
    }

    /// A budget of `n` evaluations and unlimited iterations.
    #[must_use]
    pub const fn evaluations(n: u64) -> Self {
        Self::new(None, Some(n))
    }

    /// The iteration limit actually applied (the default when neither limit is given).
    #[must_use]
    pub fn max_iterations(&self) -> Option<usize> {
        match (self.iterations, self.evaluations) {
            (None, None) => Some(DEFAULT_ITERATIONS),
            (it, _) => it,
        }
    }

    /// The number of iterations the run is expected to last, for schedules that need it
    /// (QPSO's beta, GWO's a). Under an evaluation budget it is estimated from the nominal
    /// evaluations per iteration, counting initialisation as one iteration's worth; an
    /// optimizer that spends extra evaluations (DLS) then ends before its schedule does.
    #[must_use]
    pub fn planned_iterations(&self, evaluations_per_iteration: u64) -> usize {
        let by_evaluations = self.evaluations.map(|e| {
            let per = evaluations_per_iteration.max(1);
            usize::try_from((e / per).saturating_sub(1))
                .unwrap_or(usize::MAX)
                .max(1)
        });
        match (self.max_iterations(), by_evaluations) {
            (Some(i), Some(e)) => i.min(e),
            (Some(i), None) => i,
            (None, Some(e)) => e,
            (None, None) => DEFAULT_ITERATIONS,
        }
        .max(1)
    }
}

impl Default for Budget {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The state of a run after initialisation (iteration 0) or after a step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct IterationRecord {
    /// 0 after initialisation, then the number of steps taken.
    pub iteration: usize,
    /// Evaluations spent so far, initialisation included.
    pub evaluations: u64,
    /// Cost of the optimizer's best point so far.
    pub best_cost: f64,
    /// Violation of the optimizer's best point so far (0 when feasible).
    pub best_violation: f64,
}

/// Why a run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Termination {
    /// The iteration limit was reached.
    MaxIterations,
    /// The evaluation limit was reached.
    MaxEvaluations,
    /// The wall-clock limit was reached (the run is not reproducible).
    TimeLimit,
    /// The best plan became feasible and the budget asked to stop there.
    Feasible,
    /// Under an evaluations-only budget a step spent no evaluation, so the run could never
    /// end by budget. The built-in optimizers never do this; the guard protects the loop
    /// from a faulty custom optimizer.
    Stalled,
    /// Stopped from outside ([`super::cancel`]): an interrupted call, whose result is not
    /// kept.
    Cancelled,
    /// Given up by [`Budget::give_up`]: too far from feasible after the evaluations set.
    GaveUp,
}

/// Result of one run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// The best point found.
    pub best_x: Vec<f64>,
    /// Its cost and violation.
    pub best: Evaluation,
    /// Evaluations spent, initialisation included; never more than the budget.
    pub evaluations: u64,
    /// Steps taken after initialisation (the last may have been cut short by the budget).
    pub iterations: usize,
    /// Why the run stopped.
    pub termination: Termination,
    /// One record after initialisation and one per step; past
    /// [`TRACE_CAP`](super::thinned::TRACE_CAP) steps, every s-th (s a power of two), the
    /// first feasible and the last ([`super::thinned`]).
    pub trace: Vec<IterationRecord>,
    /// Of a staged run ([`crate::run`]): the evaluations after which it left its first
    /// start for the next (`None`: one stage).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restarted_after: Option<u64>,
}

/// Runs `optimizer` on `problem` until the budget is spent, calling `observer` after
/// initialisation and after every step. Same seed, same result: nothing here is parallel.
pub fn solve(
    problem: &dyn Problem,
    optimizer: &mut dyn Optimizer,
    budget: Budget,
    rng: &mut Rng,
    observer: &mut dyn FnMut(&IterationRecord),
) -> Outcome {
    solve_watching(problem, optimizer, budget, rng, &mut |r, _| observer(r))
}

/// [`solve`], with the observer also shown the optimizer's best position after each step
/// (for traces of the best plan itself).
pub fn solve_watching(
    problem: &dyn Problem,
    optimizer: &mut dyn Optimizer,
    budget: Budget,
    rng: &mut Rng,
    observer: &mut dyn FnMut(&IterationRecord, &[f64]),
) -> Outcome {
    let max_iterations = budget.max_iterations();
    let planned = budget.planned_iterations(optimizer.evaluations_per_iteration());
    let mut ev = Evaluator::new(problem, budget.evaluations);
    let max_steps = max_iterations.map(|m| m as u64);
    ev.set_iteration(0, max_steps);
    optimizer.init(&mut ev, rng);

    let mut trace = super::thinned::Thinned::default();
    trace.reserve(max_iterations.unwrap_or(planned).saturating_add(1));
    let mut emit = |iteration: usize, ev: &Evaluator<'_>, opt: &dyn Optimizer| {
        let (best_x, best) = opt.best();
        let rec = IterationRecord {
            iteration,
            evaluations: ev.count(),
            best_cost: best.cost,
            best_violation: best.violation,
        };
        observer(&rec, best_x);
        trace.push(&rec, rec);
    };
    emit(0, &ev, optimizer);

    let started = budget.started.unwrap_or_else(std::time::Instant::now);
    let mut iteration = 0;
    let termination = loop {
        if budget.until_feasible && optimizer.best().1.feasible() {
            break Termination::Feasible;
        }
        if budget.give_up.is_some_and(|g| {
            ev.count() >= g.after_evaluations
                && optimizer.best().1.violation > f64::from(g.above_violation)
        }) {
            break Termination::GaveUp;
        }
        if budget
            .time_limit_ms
            .is_some_and(|ms| started.elapsed().as_millis() >= u128::from(ms))
        {
            break Termination::TimeLimit;
        }
        if ev.is_exhausted() {
            break Termination::MaxEvaluations;
        }
        if max_iterations.is_some_and(|m| iteration >= m) {
            break Termination::MaxIterations;
        }
        if ev.remaining() == Some(0) {
            break Termination::MaxEvaluations;
        }
        // Last: a run whose budget is spent ends as it would have, cancelled or not.
        if budget.cancel.requested() {
            break Termination::Cancelled;
        }
        let before = ev.count();
        ev.set_iteration(iteration as u64, max_steps);
        optimizer.step(&mut ev, rng);
        iteration += 1;
        emit(iteration, &ev, optimizer);
        if max_iterations.is_none() && ev.count() == before && !ev.is_exhausted() {
            break Termination::Stalled;
        }
    };

    let (best_x, best) = optimizer.best();
    Outcome {
        best_x: best_x.to_vec(),
        best,
        evaluations: ev.count(),
        iterations: iteration,
        termination,
        trace: trace.into_vec(),
        restarted_after: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn planned_iterations_follow_the_tighter_limit() {
        assert_eq!(Budget::default().planned_iterations(50), 200);
        assert_eq!(Budget::new(None, None).planned_iterations(50), 200);
        // 10,000 evaluations at 50 per iteration: 50 for initialisation, 199 steps.
        assert_eq!(Budget::evaluations(10_000).planned_iterations(50), 199);
        let both = Budget::new(Some(100), Some(10_000));
        assert_eq!(both.planned_iterations(50), 100);
        assert_eq!(Budget::evaluations(3).planned_iterations(50), 1);
    }

    /// Evaluates one fixed point at init and nothing afterwards.
    struct Idle;

    impl Optimizer for Idle {
        fn evaluations_per_iteration(&self) -> u64 {
            1
        }
        fn init(&mut self, ev: &mut Evaluator<'_>, _: &mut Rng) {
            let _ = ev.evaluate(&[0.0]);
        }
        fn step(&mut self, _: &mut Evaluator<'_>, _: &mut Rng) {}
        fn best(&self) -> (&[f64], Evaluation) {
            (&[0.0], Evaluation::new(0.0, 0.0))
        }
    }

    struct Zero(Vec<crate::problem::Bound>);

    impl Problem for Zero {
        fn bounds(&self) -> &[crate::problem::Bound] {
            &self.0
        }
        fn evaluate(&self, _: &[f64]) -> Evaluation {
            Evaluation::new(0.0, 0.0)
        }
    }

    #[test]
    fn a_step_without_evaluations_cannot_loop_forever() {
        let p = Zero(vec![crate::problem::Bound::new(-1.0, 1.0)]);
        let mut rng = crate::rng::rng_from_seed(0);
        let mut seen = Vec::new();
        let out = solve(&p, &mut Idle, Budget::evaluations(10), &mut rng, &mut |r| {
            seen.push(r.iteration);
        });
        assert_eq!(out.termination, Termination::Stalled);
        assert_eq!((out.iterations, out.evaluations), (1, 1));
        assert_eq!(seen, vec![0, 1]);
        let out = solve(&p, &mut Idle, Budget::iterations(4), &mut rng, &mut |_| {});
        assert_eq!(out.termination, Termination::MaxIterations);
        assert_eq!(out.trace.len(), 5);
    }

    #[test]
    fn a_long_run_keeps_a_bounded_trace_that_ends_at_its_last_iteration() {
        use super::super::thinned::TRACE_CAP;
        let p = Zero(vec![crate::problem::Bound::new(-1.0, 1.0)]);
        let mut rng = crate::rng::rng_from_seed(0);
        let steps = 3 * TRACE_CAP + 7;
        let mut seen = 0;
        let out = solve(
            &p,
            &mut Idle,
            Budget::iterations(steps),
            &mut rng,
            &mut |_| {
                seen += 1;
            },
        );
        assert_eq!(seen, steps + 1, "the observer still sees every iteration");
        assert!(out.trace.len() <= TRACE_CAP + 1, "{}", out.trace.len());
        assert!(out.trace.len() >= TRACE_CAP / 2, "{}", out.trace.len());
        assert_eq!(out.trace.first().map(|r| r.iteration), Some(0));
        assert_eq!(out.trace.last().map(|r| r.iteration), Some(steps));
        assert!(out
            .trace
            .windows(2)
            .all(|w| w[0].iteration < w[1].iteration));
    }

    #[test]
    fn a_raised_cancel_flag_stops_the_run_between_iterations() {
        use std::sync::atomic::AtomicBool;
        static RAISED: AtomicBool = AtomicBool::new(true);
        static LOWERED: AtomicBool = AtomicBool::new(false);
        let p = Zero(vec![crate::problem::Bound::new(-1.0, 1.0)]);
        let mut rng = crate::rng::rng_from_seed(0);
        let with = |flag: &'static AtomicBool| Budget {
            cancel: super::super::cancel::Cancel::on(flag),
            ..Budget::iterations(5)
        };
        let out = solve(&p, &mut Idle, with(&RAISED), &mut rng, &mut |_| {});
        assert_eq!(
            (out.termination, out.iterations),
            (Termination::Cancelled, 0)
        );
        let out = solve(&p, &mut Idle, with(&LOWERED), &mut rng, &mut |_| {});
        assert_eq!(
            (out.termination, out.iterations),
            (Termination::MaxIterations, 5)
        );
        // A flag is no part of what a budget allows.
        assert_eq!(with(&RAISED), Budget::iterations(5));
    }

    #[test]
    fn the_run_stops_at_the_first_feasible_best_when_asked() {
        // Zero is feasible everywhere: stop right after initialisation.
        let p = Zero(vec![crate::problem::Bound::new(-1.0, 1.0)]);
        let mut rng = crate::rng::rng_from_seed(0);
        let budget = Budget {
            until_feasible: true,
            ..Budget::iterations(50)
        };
        let out = solve(&p, &mut Idle, budget, &mut rng, &mut |_| {});
        assert_eq!(
            (out.termination, out.iterations),
            (Termination::Feasible, 0)
        );
        let budget = Budget {
            time_limit_ms: Some(0),
            ..Budget::iterations(50)
        };
        let out = solve(&p, &mut Idle, budget, &mut rng, &mut |_| {});
        assert_eq!(
            (out.termination, out.iterations),
            (Termination::TimeLimit, 0)
        );
    }

    #[test]
    fn a_missing_limit_in_a_file_means_no_such_limit() {
        let b: Budget = serde_json::from_str(r#"{"evaluations": 10000}"#).expect("parses");
        assert_eq!(b, Budget::evaluations(10_000));
        let b: Budget = serde_json::from_str("{}").expect("parses");
        assert_eq!(b.max_iterations(), Some(DEFAULT_ITERATIONS));
        assert!(serde_json::from_str::<Budget>(r#"{"iters": 3}"#).is_err());
    }
}
