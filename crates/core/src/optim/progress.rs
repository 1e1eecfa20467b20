//! How far a run is through its budget, for schedules.
//!
//! Schedules (SPSO's inertia damping, QPSO's beta, GWO's a) are defined over the *budget
//! fraction*, not over a fixed iteration count: a run given five times the budget stretches
//! its schedule five-fold and keeps searching instead of freezing after the paper's 200
//! iterations. Progress is kept as an exact ratio of integers (`done / total`) so that at
//! the paper's 200-iteration budget every schedule reproduces its per-iteration form bit for
//! bit (`200 * done / 200 == done` exactly in floating point).

/// What `done` and `total` count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgressUnit {
    /// Steps completed out of the iteration limit.
    Iterations,
    /// Evaluations spent out of the evaluation limit.
    Evaluations,
}

/// `done` out of `total` (`total >= 1`) in `unit`. Under a budget with both limits it is the
/// limit that is nearer to being reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Progress {
    /// Amount spent so far.
    pub done: u64,
    /// Amount the limit allows (at least 1).
    pub total: u64,
    /// Whether steps or evaluations are counted.
    pub unit: ProgressUnit,
}

impl Progress {
    /// The progress of a run that completed `iterations` steps and spent `evaluations`,
    /// under at most `max_iterations` steps and `max_evaluations` evaluations (with neither,
    /// the default iteration budget).
    #[must_use]
    pub fn of(
        iterations: u64,
        max_iterations: Option<u64>,
        evaluations: u64,
        max_evaluations: Option<u64>,
    ) -> Self {
        let by_iterations = Self {
            done: iterations,
            total: max_iterations
                .unwrap_or(super::DEFAULT_ITERATIONS as u64)
                .max(1),
            unit: ProgressUnit::Iterations,
        };
        let Some(limit) = max_evaluations else {
            return by_iterations;
        };
        let by_evaluations = Self {
            done: evaluations,
            total: limit.max(1),
            unit: ProgressUnit::Evaluations,
        };
        if max_iterations.is_none() {
            return by_evaluations;
        }
        // The larger fraction, compared exactly: a/b > c/d iff a d > c b.
        let lhs = u128::from(by_evaluations.done) * u128::from(by_iterations.total);
        let rhs = u128::from(by_iterations.done) * u128::from(by_evaluations.total);
        if lhs > rhs {
            by_evaluations
        } else {
            by_iterations
        }
    }

    /// `done / total`, at most 1.
    #[must_use]
    pub fn fraction(&self) -> f64 {
        (self.done.min(self.total) as f64) / self.total as f64
    }

    /// The fraction that reaches 1 at the *last* step: `t / (T - 1)` for iterations (a
    /// schedule that goes from its start value at the first step to its end value at the
    /// last), `done / total` for evaluations.
    #[must_use]
    pub fn fraction_to_last(&self) -> f64 {
        match self.unit {
            ProgressUnit::Iterations if self.total > 1 => {
                (self.done.min(self.total - 1) as f64) / (self.total - 1) as f64
            }
            ProgressUnit::Iterations => 0.0,
            ProgressUnit::Evaluations => self.fraction(),
        }
    }

    /// `reference * done / total`: how many of a schedule's `reference` nominal iterations
    /// have elapsed. Exact when `total == reference`, so a per-iteration schedule defined
    /// over `reference` iterations is reproduced bit for bit at that budget.
    #[must_use]
    pub fn elapsed_of(&self, reference: u64) -> f64 {
        let done = self.done.min(self.total);
        let num = u128::from(reference) * u128::from(done);
        if num % u128::from(self.total) == 0 {
            (num / u128::from(self.total)) as f64
        } else {
            num as f64 / self.total as f64
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn picks_the_nearer_limit_exactly() {
        let p = Progress::of(10, Some(200), 400, Some(10_000));
        assert_eq!(
            (p.done, p.total, p.unit),
            (10, 200, ProgressUnit::Iterations)
        );
        let p = Progress::of(10, Some(200), 600, Some(1_000));
        assert_eq!(p.unit, ProgressUnit::Evaluations);
        let p = Progress::of(3, None, 0, None);
        assert_eq!((p.done, p.total), (3, 200));
        let p = Progress::of(3, None, 50, Some(100));
        assert_eq!((p.fraction(), p.unit), (0.5, ProgressUnit::Evaluations));
    }

    #[test]
    fn elapsed_is_exact_at_the_reference_and_scales_with_the_budget() {
        for done in 0..200 {
            let p = Progress::of(done, Some(200), 0, None);
            assert_eq!(p.elapsed_of(200), done as f64);
        }
        let p = Progress::of(500, Some(1000), 0, None);
        assert_eq!(p.elapsed_of(200), 100.0);
        let p = Progress::of(0, None, 18_000, Some(36_000));
        assert_eq!(p.elapsed_of(200), 100.0);
        let p = Progress::of(1, Some(3), 0, None);
        assert!((p.elapsed_of(200) - 200.0 / 3.0).abs() < 1e-12);
    }

    #[test]
    fn fraction_to_last_reaches_one_at_the_last_step() {
        let p = Progress::of(199, Some(200), 0, None);
        assert_eq!(p.fraction_to_last(), 1.0);
        let p = Progress::of(99, Some(199), 0, None);
        assert!((p.fraction_to_last() - 99.0 / 198.0).abs() < 1e-15);
        assert_eq!(Progress::of(0, Some(1), 0, None).fraction_to_last(), 0.0);
    }
}
