//! Quantum-behaved PSO (Sun, Feng, Xu 2004, Proc. IEEE CEC; Sun et al. 2012, Evol.
//! Comput. 20(3)). No velocity: each particle is re-sampled around a random local
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
//! strict improvement, gbest at once. T is the planned iteration count passed to
//! [`Optimizer::init`]; past it beta stays at `beta_end`.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::params::{check, ParamsError};
use super::swarm::{fill_uniform, into_bound, row, row_mut, BestSoFar};
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
    pub const DEFAULT: Self = Self {
        population: 50,
        beta_start: 1.0,
        beta_end: 0.5,
    };

    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            self.population >= 1,
            "population",
            "at least 1",
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

    /// beta at step `t` (0-based) of `planned` steps: linear from `beta_start` at the first
    /// to `beta_end` at the last, then held.
    #[must_use]
    pub fn beta(&self, t: usize, planned: usize) -> f64 {
        if planned <= 1 {
            return self.beta_start;
        }
        #[allow(clippy::cast_precision_loss)] // iteration counts are far below 2^52
        let frac = t.min(planned - 1) as f64 / (planned - 1) as f64;
        self.beta_start + (self.beta_end - self.beta_start) * frac
    }
}

impl Default for QpsoParams {
    fn default() -> Self {
        Self::DEFAULT
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
    t: usize,
    planned: usize,
}

impl Qpso {
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
            t: 0,
            planned: 1,
        }
    }

    #[must_use]
    pub fn params(&self) -> &QpsoParams {
        &self.params
    }

    /// The beta the next step will use.
    #[must_use]
    pub fn current_beta(&self) -> f64 {
        self.params.beta(self.t, self.planned)
    }
}

impl Optimizer for Qpso {
    fn evaluations_per_iteration(&self) -> u64 {
        self.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng, planned_iterations: usize) {
        let bounds = ev.bounds();
        let (n, dim) = (self.n, bounds.len());
        self.dim = dim;
        self.x = vec![0.0; n * dim];
        self.pbest_eval = vec![Evaluation::worst(); n];
        self.gbest = BestSoFar::new(dim);
        self.mbest = vec![0.0; dim];
        self.t = 0;
        self.planned = planned_iterations.max(1);
        for i in 0..n {
            let x = row_mut(&mut self.x, i, dim);
            fill_uniform(bounds, rng, x);
            let e = ev.evaluate(x).unwrap_or(Evaluation::worst());
            self.pbest_eval[i] = e;
            self.gbest.offer(x, e);
        }
        self.pbest.clone_from(&self.x);
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let (n, dim) = (self.n, self.dim);
        let beta = self.current_beta();
        self.t += 1;

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
            let Some(e) = ev.evaluate(x) else { break };
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
        assert_eq!(p.beta(0, 200), 1.0);
        assert_eq!(p.beta(199, 200), 0.5);
        assert_eq!(p.beta(500, 200), 0.5);
        assert!((p.beta(99, 199) - 0.75).abs() < 1e-12);
        assert_eq!(p.beta(0, 1), 1.0);
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
    fn the_schedule_follows_the_planned_iterations() {
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
        // 11 steps taken (beta 1.0 .. 0.5), the next would stay at the end value.
        assert_eq!(q.current_beta(), 0.5);
        let mut q = Qpso::new(QpsoParams::DEFAULT);
        let _ = solve(
            &p,
            &mut q,
            Budget {
                iterations: Some(5),
                evaluations: Some(50 * 11),
            },
            &mut rng_from_seed(0),
            &mut |_| {},
        );
        // Planned = min(5, 550 / 50 - 1 = 10) = 5: after 5 steps beta reached 0.5.
        assert_eq!(q.current_beta(), 0.5);
    }
}
