//! Quantum-behaved PSO (Sun, Feng, Xu 2004, Proc. IEEE CEC, doi:10.1109/CEC.2004.1330875;
//! Sun et al. 2012, Evol. Comput. 20(3):349-393, doi:10.1162/EVCO_a_00049). No velocity: each particle is re-sampled around a random local
//! attractor, at a distance scaled by its gap to the mean best position.
//!
//! At the start of iteration t, mbest = (1/N) sum_i pbest_i. Then for particle i and every
//! dimension j, with fresh phi, u ~ U(0, 1) and a fair sign:
//!
//! ```text
//! p_ij  = phi pbest_ij + (1 - phi) gbest_j
//! x_ij <- p_ij +/- beta_t |mbest_j - x_ij| ln(1/u)
//! beta_t = beta_start - (beta_start - beta_end) t / (T - 1),  t = 0 .. T-1
//! ```
//!
//! (u is drawn in (0, 1], so ln(1/u) is finite.) The new position is projected into the
//! bounds (clamped; periodic bounds wrapped), evaluated, and pbest_i and gbest updated on
//! strict improvement, gbest at once. The schedule runs over the budget
//! ([`super::Progress::fraction_to_last`]): t / (T - 1) of an iteration budget (the form
//! above, unchanged at the paper's 200 iterations), the share of evaluations spent under an
//! evaluation budget.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::swarm::{into_bound, row, row_mut, BestSoFar};
use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// Parameters of QPSO.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct QpsoParams {
    /// Swarm size N (50).
    pub population: usize,
    /// Contraction-expansion coefficient beta at the first iteration (1.0).
    pub beta_start: f64,
    /// Contraction-expansion coefficient beta at the last planned iteration (0.5).
    pub beta_end: f64,
}

impl QpsoParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        population: 50,
        beta_start: 1.0,
        beta_end: 0.5,
    };

    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            super::config::POPULATION_RANGE.contains(&self.population),
            "population",
            super::config::POPULATION_EXPECTED,
            self.population,
        )?;
        check(
            self.beta_start.is_finite() && self.beta_start > 0.0,
            "beta_start",
            "a positive number",
            self.beta_start,
        )?;
        check(
            self.beta_end.is_finite() && self.beta_end > 0.0,
            "beta_end",
            "a positive number",
            self.beta_end,
        )
    }

    /// beta at budget fraction `frac` ([`super::Progress::fraction_to_last`]): linear from
    /// `beta_start` at the first step to `beta_end` at the last.
    #[must_use]
    pub fn beta(&self, frac: f64) -> f64 {
        self.beta_start + (self.beta_end - self.beta_start) * frac
    }
}

impl Default for QpsoParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for QpsoParams {
    fn population(&self) -> usize {
        self.population
    }

    fn set_population(&mut self, n: usize) {
        self.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Qpso::new(*self))
    }
}

/// QPSO.
#[derive(Debug, Clone)]
pub struct Qpso {
    params: QpsoParams,
    n: usize,
    dim: usize,
    x: Vec<f64>,
    pbest: Vec<f64>,
    pbest_eval: Vec<Evaluation>,
    gbest: BestSoFar,
    mbest: Vec<f64>,
    /// The beta of the last step.
    beta: f64,
}

impl Qpso {
    /// QPSO with `params`; the swarm is drawn at initialisation.
    #[must_use]
    pub fn new(params: QpsoParams) -> Self {
        Self {
            params,
            n: params.population.max(1),
            dim: 0,
            x: Vec::new(),
            pbest: Vec::new(),
            pbest_eval: Vec::new(),
            gbest: BestSoFar::new(0),
            mbest: Vec::new(),
            beta: params.beta_start,
        }
    }

    /// The parameters it runs with.
    #[must_use]
    pub fn params(&self) -> &QpsoParams {
        &self.params
    }

    /// The beta the last step used.
    #[must_use]
    pub fn current_beta(&self) -> f64 {
        self.beta
    }
}

impl Optimizer for Qpso {
    fn evaluations_per_iteration(&self) -> u64 {
        self.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let (n, dim) = (self.n, bounds.len());
        self.dim = dim;
        self.x = vec![0.0; n * dim];
        self.pbest_eval = vec![Evaluation::worst(); n];
        self.gbest = BestSoFar::new(dim);
        self.mbest = vec![0.0; dim];
        self.beta = self.params.beta_start;
        for i in 0..n {
            ev.sample_initial(rng, row_mut(&mut self.x, i, dim));
        }
        let mut evals = Vec::with_capacity(n);
        ev.evaluate_rows(&self.x, n, &mut evals);
        for i in 0..n {
            let e = evals.get(i).copied().unwrap_or(Evaluation::worst());
            self.pbest_eval[i] = e;
            self.gbest.offer(row(&self.x, i, dim), e);
        }
        self.pbest.clone_from(&self.x);
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let (n, dim) = (self.n, self.dim);
        let beta = self.params.beta(ev.progress().fraction_to_last());
        self.beta = beta;

        self.mbest.fill(0.0);
        for i in 0..n {
            for (m, p) in self.mbest.iter_mut().zip(row(&self.pbest, i, dim)) {
                *m += p;
            }
        }
        #[allow(clippy::cast_precision_loss)]
        let inv_n = 1.0 / n as f64;
        for m in &mut self.mbest {
            *m *= inv_n;
        }

        for i in 0..n {
            let x = row_mut(&mut self.x, i, dim);
            let pb = row(&self.pbest, i, dim);
            for j in 0..dim {
                let phi: f64 = rng.random();
                let u = 1.0 - rng.random::<f64>();
                let attractor = phi * pb[j] + (1.0 - phi) * self.gbest.x[j];
                let spread = beta * (self.mbest[j] - x[j]).abs() * (1.0 / u).ln();
                let moved = if rng.random::<bool>() {
                    attractor + spread
                } else {
                    attractor - spread
                };
                x[j] = into_bound(&bounds[j], moved);
            }
            // Only a strict improvement on pbest_i matters (gbest is offered nothing else),
            // so the evaluation may stop once the cost is known to exceed pbest_i's (or to
            // be +inf when pbest_i's is).
            let Some(e) = ev.evaluate_cost_bounded(x, self.pbest_eval[i].cutoff_to_beat()) else {
                break;
            };
            if e.better_than(&self.pbest_eval[i]) {
                row_mut(&mut self.pbest, i, dim).copy_from_slice(x);
                self.pbest_eval[i] = e;
                self.gbest.offer(x, e);
            }
        }
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (&self.gbest.x, self.gbest.eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::{solve, Budget};
    use crate::problem::{Bound, Problem};
    use crate::rng::rng_from_seed;

    #[test]
    fn beta_goes_linearly_from_start_to_end() {
        let p = QpsoParams::DEFAULT;
        assert_eq!(p.beta(0.0), 1.0);
        assert_eq!(p.beta(1.0), 0.5);
        assert!((p.beta(0.5) - 0.75).abs() < 1e-12);
    }

    struct Flat(Vec<Bound>);

    impl Problem for Flat {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, _: &[f64]) -> Evaluation {
            Evaluation::new(0.0, 0.0)
        }
    }

    #[test]
    fn the_schedule_follows_the_budget() {
        let p = Flat(vec![Bound::new(0.0, 1.0)]);
        let mut q = Qpso::new(QpsoParams {
            population: 2,
            ..QpsoParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut q,
            Budget::iterations(11),
            &mut rng_from_seed(0),
            &mut |_| {},
        );
        // 11 steps taken: the last one used the end value.
        assert_eq!(q.current_beta(), 0.5);
        let mut q = Qpso::new(QpsoParams {
            population: 2,
            ..QpsoParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut q,
            Budget::evaluations(2 * 11),
            &mut rng_from_seed(0),
            &mut |_| {},
        );
        // Ten steps of two evaluations after two for initialisation: the last starts with
        // 20 of 22 spent.
        assert!((q.current_beta() - (1.0 - 0.5 * 20.0 / 22.0)).abs() < 1e-15);
        let mut q = Qpso::new(QpsoParams::DEFAULT);
        let _ = solve(
            &p,
            &mut q,
            Budget::new(Some(5), Some(50 * 11)),
            &mut rng_from_seed(0),
            &mut |_| {},
        );
        // The iteration limit is the nearer one: after 5 steps beta reached 0.5.
        assert_eq!(q.current_beta(), 0.5);
    }
}
