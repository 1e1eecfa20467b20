//! The counting gate between an optimizer and its problem.
//!
//! Optimizers never call [`Problem::evaluate`] themselves: they hold an [`Evaluator`], which
//! the solve loop owns. That makes every evaluation count (initial swarms and their
//! re-draws, dimensional-learning probes, ABC scouts) and lets a budget be enforced exactly:
//! once the budget is spent the evaluator refuses, returning `None` without evaluating or
//! counting, and remembers that it refused so the loop can stop with the right reason.
//!
//! [`Evaluator::evaluate_rows`] evaluates a whole swarm at once on every thread of the rayon
//! pool. Evaluation is pure, so the results, and with them every run, are the same bit for
//! bit whatever the thread count: only the order in which an optimizer *uses* the results
//! matters, and that stays the row order. Optimizers call it where their update is
//! synchronous (a generation evaluated against a fixed state).

use rayon::prelude::*;

use super::progress::Progress;
use crate::problem::{Bound, Evaluation, Problem};

mod blocks;
use crate::rng::Rng;

/// Counts evaluations of one problem and refuses them past an optional budget.
pub struct Evaluator<'a> {
    problem: &'a dyn Problem,
    bounds: &'a [Bound],
    count: u64,
    limit: Option<u64>,
    exhausted: bool,
    iteration: u64,
    max_iterations: Option<u64>,
}

impl<'a> Evaluator<'a> {
    /// An evaluator that allows at most `limit` evaluations (`None`: unlimited).
    #[must_use]
    pub fn new(problem: &'a dyn Problem, limit: Option<u64>) -> Self {
        Self {
            problem,
            bounds: problem.bounds(),
            count: 0,
            limit,
            exhausted: false,
            iteration: 0,
            max_iterations: None,
        }
    }

    /// Tells the evaluator which step the run is at (set by the solve loop before every
    /// step), so [`Evaluator::progress`] can serve schedules.
    pub(crate) fn set_iteration(&mut self, iteration: u64, max_iterations: Option<u64>) {
        self.iteration = iteration;
        self.max_iterations = max_iterations;
    }

    /// How far the run is through its budget (steps completed, or evaluations spent).
    #[must_use]
    pub fn progress(&self) -> Progress {
        Progress::of(self.iteration, self.max_iterations, self.count, self.limit)
    }

    /// Draws a starting point by the problem's initialisation (not an evaluation: nothing
    /// is counted).
    pub fn sample_initial(&self, rng: &mut Rng, out: &mut [f64]) {
        self.problem.sample_initial(rng, out);
    }

    /// The bounds of the problem (borrowed from the problem, not from the evaluator, so an
    /// optimizer can hold them while it evaluates).
    #[must_use]
    pub fn bounds(&self) -> &'a [Bound] {
        self.bounds
    }

    /// The number of decision variables.
    #[must_use]
    pub fn dimension(&self) -> usize {
        self.bounds.len()
    }

    /// Evaluates `x`, or returns `None` (without evaluating or counting) when the budget is
    /// spent. NaN costs and violations come back as +inf, so a NaN never wins a comparison.
    pub fn evaluate(&mut self, x: &[f64]) -> Option<Evaluation> {
        self.evaluate_cost_bounded(x, f64::INFINITY)
    }

    /// [`Evaluator::evaluate`] for a candidate that only matters if it costs less than
    /// `cutoff` ([`Problem::evaluate_cost_bounded`]): one the problem gives up on comes back
    /// as [`Evaluation::worst`], which no comparison prefers. Counts one evaluation either
    /// way; `None` only when the budget is spent.
    pub fn evaluate_cost_bounded(&mut self, x: &[f64], cutoff: f64) -> Option<Evaluation> {
        self.admit(x)?;
        Some(cost_bounded(self.problem, x, cutoff))
    }

    /// [`Evaluator::evaluate_cost_bounded`] on the problem's buffers for `slot`
    /// ([`Problem::evaluate_cost_bounded_in`]): the same result, counted the same.
    pub fn evaluate_cost_bounded_in(
        &mut self,
        x: &[f64],
        cutoff: f64,
        slot: usize,
    ) -> Option<Evaluation> {
        self.admit(x)?;
        Some(
            self.problem
                .evaluate_cost_bounded_in(x, cutoff, slot)
                .map_or_else(Evaluation::worst, normalised),
        )
    }

    /// Evaluates the first `n` rows of `rows` (each [`Evaluator::dimension`] long) in
    /// parallel, as many as the budget allows (the first ones), into `out` in row order; a
    /// row the budget refused has no entry, so `out.len()` says how many were evaluated.
    /// Equal, row by row, to calling [`Evaluator::evaluate`] on each in turn.
    pub fn evaluate_rows(&mut self, rows: &[f64], n: usize, out: &mut Vec<Evaluation>) {
        self.evaluate_rows_cost_bounded(rows, n, f64::INFINITY, out);
    }

    /// [`Evaluator::evaluate_rows`] for rows that only matter if they cost less than
    /// `cutoff` ([`Problem::evaluate_cost_bounded`]): a row the problem gives up on comes
    /// back as [`Evaluation::worst`]. Each row counts as one evaluation either way.
    pub fn evaluate_rows_cost_bounded(
        &mut self,
        rows: &[f64],
        n: usize,
        cutoff: f64,
        out: &mut Vec<Evaluation>,
    ) {
        self.rows_cost(rows, n, |_| cutoff, out);
    }

    /// [`Evaluator::evaluate_rows_cost_bounded`] with a cutoff per row: row i only matters
    /// if it costs less than `cutoffs[i]` (a trial against its own parent).
    pub fn evaluate_rows_cost_bounded_each(
        &mut self,
        rows: &[f64],
        n: usize,
        cutoffs: &[f64],
        out: &mut Vec<Evaluation>,
    ) {
        assert!(cutoffs.len() >= n, "a cutoff per row");
        self.rows_cost(rows, n, |i| cutoffs[i], out);
    }

    /// Rows bounded in cost, row i by `cutoff(i)` (+inf: evaluated in full).
    fn rows_cost(
        &mut self,
        rows: &[f64],
        n: usize,
        cutoff: impl Fn(usize) -> f64 + Sync,
        out: &mut Vec<Evaluation>,
    ) {
        let problem = self.problem;
        let dim = self.dimension();
        let allowed = self.admit_rows(rows, n);
        out.clear();
        if dim == 0 {
            out.extend((0..allowed).map(|i| cost_bounded(problem, &[], cutoff(i))));
            return;
        }
        rows[..allowed * dim]
            .par_chunks(dim)
            .enumerate()
            .map(|(i, x)| cost_bounded(problem, x, cutoff(i)))
            .collect_into_vec(out);
    }

    /// Counts as many of `n` rows as the budget allows and returns that number; marks the
    /// evaluator exhausted when it refused some.
    fn admit_rows(&mut self, rows: &[f64], n: usize) -> usize {
        let dim = self.dimension();
        assert!(rows.len() >= n * dim, "fewer rows than asked to evaluate");
        let allowed = self
            .remaining()
            .map_or(n, |r| usize::try_from(r).unwrap_or(usize::MAX).min(n));
        if allowed < n {
            self.exhausted = true;
        }
        for i in 0..allowed {
            debug_assert!(
                rows[i * dim..(i + 1) * dim]
                    .iter()
                    .zip(self.bounds)
                    .all(|(v, b)| b.contains(*v)),
                "optimizer evaluated a candidate outside the bounds"
            );
        }
        self.count += allowed as u64;
        allowed
    }

    /// Whether the budget is spent; if so, the evaluator is marked exhausted.
    fn spent(&mut self) -> bool {
        let spent = self.limit.is_some_and(|l| self.count >= l);
        self.exhausted |= spent;
        spent
    }

    /// Counts one evaluation of `x`, or refuses (`None`) when the budget is spent.
    fn admit(&mut self, x: &[f64]) -> Option<()> {
        if self.spent() {
            return None;
        }
        debug_assert_eq!(
            x.len(),
            self.bounds.len(),
            "candidate of the wrong dimension"
        );
        debug_assert!(
            x.iter().zip(self.bounds).all(|(v, b)| b.contains(*v)),
            "optimizer evaluated a candidate outside the bounds"
        );
        self.count += 1;
        Some(())
    }

    /// Evaluations performed so far.
    #[must_use]
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Evaluations left in the budget (`None`: unlimited).
    #[must_use]
    pub fn remaining(&self) -> Option<u64> {
        self.limit.map(|l| l.saturating_sub(self.count))
    }

    /// True once an evaluation has been refused for lack of budget.
    #[must_use]
    pub fn is_exhausted(&self) -> bool {
        self.exhausted
    }
}

/// `x` evaluated in full (`cutoff` = +inf) or bounded by a cost `cutoff`, normalised; a
/// bounded evaluation given up is [`Evaluation::worst`].
fn cost_bounded(problem: &dyn Problem, x: &[f64], cutoff: f64) -> Evaluation {
    if cutoff == f64::INFINITY {
        normalised(problem.evaluate(x))
    } else {
        problem
            .evaluate_cost_bounded(x, cutoff)
            .map_or_else(Evaluation::worst, normalised)
    }
}

/// Problems may build `Evaluation` literally; NaN is normalised here once for everyone.
fn normalised(e: Evaluation) -> Evaluation {
    Evaluation::new(e.cost, e.violation)
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Sum(Vec<Bound>);

    impl Problem for Sum {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            Evaluation {
                cost: x.iter().sum(),
                violation: f64::NAN,
            }
        }
    }

    #[test]
    fn refuses_past_the_budget_without_counting() {
        let p = Sum(vec![Bound::new(0.0, 1.0); 2]);
        let mut ev = Evaluator::new(&p, Some(2));
        assert!(ev.evaluate(&[0.5, 0.5]).is_some());
        assert!(!ev.is_exhausted());
        assert_eq!(ev.remaining(), Some(1));
        let e = ev.evaluate(&[0.25, 0.5]).expect("within budget");
        assert_eq!(e.cost, 0.75);
        assert_eq!(e.violation, f64::INFINITY, "NaN violation normalised");
        assert!(ev.evaluate(&[0.0, 0.0]).is_none());
        assert!(ev.is_exhausted());
        assert_eq!(ev.count(), 2);
        assert_eq!(ev.remaining(), Some(0));
    }

    #[test]
    fn rows_are_evaluated_in_order_within_the_budget() {
        let p = Sum(vec![Bound::new(0.0, 1.0); 2]);
        let rows = [0.1, 0.2, 0.3, 0.4, 0.5, 0.5];
        let mut ev = Evaluator::new(&p, Some(4));
        let mut out = Vec::new();
        ev.evaluate_rows(&rows, 2, &mut out);
        let sums: Vec<f64> = out.iter().map(|e| e.cost).collect();
        assert_eq!(sums, vec![0.1 + 0.2, 0.3 + 0.4]);
        assert!(!ev.is_exhausted());
        ev.evaluate_rows(&rows, 3, &mut out);
        assert_eq!(out.len(), 2, "the budget allowed two of three");
        assert!(ev.is_exhausted());
        assert_eq!(ev.count(), 4);
        ev.evaluate_rows(&rows, 3, &mut out);
        assert!(out.is_empty());
    }

    /// Gives up whenever the cost exceeds the cutoff.
    struct Bounded(Vec<Bound>);

    impl Problem for Bounded {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            Evaluation::new(x.iter().sum(), 0.0)
        }
        fn evaluate_cost_bounded(&self, x: &[f64], cutoff: f64) -> Option<Evaluation> {
            let e = self.evaluate(x);
            (e.cost <= cutoff).then_some(e)
        }
    }

    #[test]
    fn each_row_is_bounded_by_its_own_cutoff() {
        let p = Bounded(vec![Bound::new(0.0, 1.0); 2]);
        let rows = [0.1, 0.2, 0.3, 0.4, 0.5, 0.5];
        let mut ev = Evaluator::new(&p, Some(3));
        let mut out = Vec::new();
        // Row 0 (0.3) beats 0.5, row 1 (0.7) does not beat 0.6, row 2 (1.0) ties 1.0.
        ev.evaluate_rows_cost_bounded_each(&rows, 3, &[0.5, 0.6, 1.0], &mut out);
        let costs: Vec<f64> = out.iter().map(|e| e.cost).collect();
        assert_eq!(costs, [0.1 + 0.2, f64::INFINITY, 0.5 + 0.5]);
        assert_eq!(out[1], Evaluation::worst());
        assert_eq!(ev.count(), 3, "a row given up still counts");
    }
}
