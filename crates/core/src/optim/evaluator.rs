//! The counting gate between an optimizer and its problem.
//!
//! Optimizers never call [`Problem::evaluate`] themselves: they hold an [`Evaluator`], which
//! the solve loop owns. That makes every evaluation count (initial swarms and their
//! re-draws, dimensional-learning probes, ABC scouts) and lets a budget be enforced exactly:
//! once the budget is spent the evaluator refuses, returning `None` without evaluating or
//! counting, and remembers that it refused so the loop can stop with the right reason.

use super::progress::Progress;
use crate::problem::{Bound, Evaluation, Problem};
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

    #[must_use]
    pub fn dimension(&self) -> usize {
        self.bounds.len()
    }

    /// The problem's block size ([`Problem::block_size`]), at least 1 and at most the
    /// dimension.
    #[must_use]
    pub fn block_size(&self) -> usize {
        self.problem.block_size().clamp(1, self.dimension().max(1))
    }

    /// Evaluates `x`, or returns `None` (without evaluating or counting) when the budget is
    /// spent. NaN costs and violations come back as +inf, so a NaN never wins a comparison.
    pub fn evaluate(&mut self, x: &[f64]) -> Option<Evaluation> {
        self.admit(x)?;
        let e = self.problem.evaluate(x);
        // Problems may build `Evaluation` literally; normalise NaN here once for everyone.
        Some(Evaluation::new(e.cost, e.violation))
    }

    /// Counts one evaluation of `x`, or refuses (`None`) when the budget is spent.
    fn admit(&mut self, x: &[f64]) -> Option<()> {
        if self.limit.is_some_and(|l| self.count >= l) {
            self.exhausted = true;
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

    /// [`Evaluator::evaluate`] with each block's share of the violation in `by_block`
    /// ([`Problem::evaluate_blocks`]); counted the same.
    pub fn evaluate_blocks(&mut self, x: &[f64], by_block: &mut Vec<f64>) -> Option<Evaluation> {
        self.admit(x)?;
        let e = self.problem.evaluate_blocks(x, by_block);
        Some(Evaluation::new(e.cost, e.violation))
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
}
