//! Cooperative coevolution with feasibility-first particle swarms: swarmplan's own
//! optimizer, the `swarmplan` method's.
//!
//! Why: the paper's methods search one 150-dimensional vector for five UAVs at once, so a
//! move that repairs one UAV's threat crossing usually breaks another's separation, and the
//! swarm converges before any plan is feasible. Cooperative coevolution (Potter & De Jong
//! 1994, PPSN III; for PSO van den Bergh & Engelbrecht 2004, IEEE TEC 8(3):225-239)
//! searches one block (one UAV's path) at a time inside a *context*: the best whole plan so
//! far, whose other blocks stay fixed. Candidates are compared by Deb's feasibility rules
//! ([`Evaluation::better_feasibility_first`]) instead of by penalised cost, so the search
//! first drives the violation to zero and only then lowers the cost, and it never gives a
//! feasible incumbent away.
//!
//! One step is one iteration of a sub-swarm of `population` particles on the current block:
//!
//! ```text
//! visit of block b (every block_iterations steps the next block, cyclically):
//!   particle 0 = context_b; the others = context_b + N(0, (s_b w_j)^2) per dimension j
//!   (w_j the bound's width), or, for a share `fresh` of them, block b of a new point from
//!   the method's initialisation; all clamped into the bounds and evaluated. The spread s_b
//!   of block b starts at `perturbation` and adapts per visit: x 2 after a visit that
//!   improved the context, x 1/2 after one that did not (within [1e-9, 0.5]), so visits
//!   explore while they pay and refine once the context is good (in the spirit of
//!   Rechenberg's success rule)
//! step:  v <- w v + c1 r1 (pbest - x) + c2 r2 (gbest - x); clamp |v| <= 0.5 w_j; x += v
//!        (mirrored and clamped at the bounds as in SPSO); evaluate context with block b = x;
//!        pbest, gbest and the context follow feasibility-first improvements at once
//! ```
//!
//! The inner PSO uses Clerc & Kennedy's constriction-equivalent constants (w = 0.7298,
//! c1 = c2 = 1.49618; IEEE TEC 6(1):58-73, 2002), which converge within the short visits
//! without a schedule. Every evaluation goes through the [`Evaluator`] and counts.

use rand::Rng as _;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use super::params::{check, ParamsError};
use super::swarm::into_bound;
use super::{Evaluator, Optimizer};
use crate::problem::{Bound, Evaluation};
use crate::rng::Rng;

/// Parameters of the cooperative optimizer.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CoopParams {
    /// Particles of a sub-swarm, and points drawn for the first context (20).
    pub population: usize,
    /// Steps spent on one block before the next (10).
    pub block_iterations: usize,
    /// Inertia weight w of the sub-swarms (0.7298).
    pub inertia: f64,
    /// Cognitive coefficient c1 (1.49618).
    pub cognitive: f64,
    /// Social coefficient c2 (1.49618).
    pub social: f64,
    /// Initial spread of a visit's particles around the context, as a share of each bound's
    /// width (0.1); adapted per block afterwards.
    pub perturbation: f64,
    /// Share of a visit's particles drawn afresh from the initialisation (0.25).
    pub fresh: f64,
}

impl CoopParams {
    pub const DEFAULT: Self = Self {
        population: 20,
        block_iterations: 10,
        inertia: 0.7298,
        cognitive: 1.49618,
        social: 1.49618,
        perturbation: 0.1,
        fresh: 0.25,
    };

    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            (2..=100_000).contains(&self.population),
            "population",
            "a whole number in [2, 100000]",
            self.population,
        )?;
        check(
            self.block_iterations >= 1,
            "block_iterations",
            "at least 1",
            self.block_iterations,
        )?;
        for (v, name) in [
            (self.inertia, "inertia"),
            (self.cognitive, "cognitive"),
            (self.social, "social"),
        ] {
            check(v.is_finite() && v >= 0.0, name, "a finite number >= 0", v)?;
        }
        check(
            self.perturbation.is_finite() && self.perturbation > 0.0,
            "perturbation",
            "a positive number",
            self.perturbation,
        )?;
        check(
            (0.0..=1.0).contains(&self.fresh),
            "fresh",
            "a number in [0, 1]",
            self.fresh,
        )
    }
}

impl Default for CoopParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Cooperative coevolution over blocks with feasibility-first sub-swarms.
#[derive(Debug, Clone)]
pub struct Cooperative {
    params: CoopParams,
    dim: usize,
    block: usize,
    /// The best whole vector so far and its evaluation.
    context: Vec<f64>,
    context_eval: Evaluation,
    /// Block being searched, and steps spent on it in this visit.
    current: usize,
    spent: usize,
    /// Sub-swarm state, `population` rows of one block each.
    x: Vec<f64>,
    v: Vec<f64>,
    pbest: Vec<f64>,
    pbest_eval: Vec<Evaluation>,
    gbest: Vec<f64>,
    gbest_eval: Evaluation,
    /// A whole vector to evaluate.
    full: Vec<f64>,
    /// Spread s_b of each block's visits.
    spread: Vec<f64>,
    /// The context's evaluation when the current visit started.
    visit_start: Evaluation,
}

impl Cooperative {
    #[must_use]
    pub fn new(params: CoopParams) -> Self {
        Self {
            params,
            dim: 0,
            block: 1,
            context: Vec::new(),
            context_eval: Evaluation::worst(),
            current: 0,
            spent: 0,
            x: Vec::new(),
            v: Vec::new(),
            pbest: Vec::new(),
            pbest_eval: Vec::new(),
            gbest: Vec::new(),
            gbest_eval: Evaluation::worst(),
            full: Vec::new(),
            spread: Vec::new(),
            visit_start: Evaluation::worst(),
        }
    }

    fn blocks(&self) -> usize {
        self.dim.div_ceil(self.block).max(1)
    }

    /// The bounds of block `b`.
    fn range(&self, b: usize) -> std::ops::Range<usize> {
        let lo = b * self.block;
        lo..(lo + self.block).min(self.dim)
    }

    /// Evaluates the context with block `b` replaced by `x` (a whole block).
    fn evaluate_in_context(
        &mut self,
        b: usize,
        x: &[f64],
        ev: &mut Evaluator<'_>,
    ) -> Option<Evaluation> {
        let r = self.range(b);
        self.full.copy_from_slice(&self.context);
        self.full[r].copy_from_slice(x);
        ev.evaluate(&self.full)
    }

    /// Offers a candidate block to the context (feasibility first).
    fn offer_context(&mut self, b: usize, x: &[f64], e: Evaluation) {
        if e.better_feasibility_first(&self.context_eval) {
            let r = self.range(b);
            self.context[r].copy_from_slice(x);
            self.context_eval = e;
        }
    }

    /// Starts a visit of the current block: a fresh sub-swarm around the context.
    fn start_visit(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let b = self.current;
        let r = self.range(b);
        let len = r.len();
        let n = self.params.population;
        self.x.resize(n * len, 0.0);
        self.v.clear();
        self.v.resize(n * len, 0.0);
        self.pbest.resize(n * len, 0.0);
        self.pbest_eval.clear();
        self.pbest_eval.resize(n, Evaluation::worst());
        self.gbest.clear();
        self.gbest.extend_from_slice(&self.context[r.clone()]);
        self.gbest_eval = self.context_eval;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let fresh = ((self.params.fresh * n as f64).round() as usize).min(n - 1);
        let mut sample = vec![0.0; self.dim];
        self.visit_start = self.context_eval;
        let spread = self.spread[b];
        for i in 0..n {
            let row = i * len..(i + 1) * len;
            if i == 0 {
                self.x[row.clone()].copy_from_slice(&self.context[r.clone()]);
            } else if i <= fresh {
                ev.sample_initial(rng, &mut sample);
                self.x[row.clone()].copy_from_slice(&sample[r.clone()]);
            } else {
                for (k, j) in r.clone().enumerate() {
                    let bj: &Bound = &bounds[j];
                    let sd = (spread * bj.width()).max(f64::MIN_POSITIVE);
                    let noise = Normal::new(0.0, sd).map_or(0.0, |d| d.sample(rng));
                    self.x[i * len + k] = into_bound(bj, self.context[j] + noise);
                }
            }
            let candidate: Vec<f64> = self.x[row.clone()].to_vec();
            let e = if i == 0 {
                self.context_eval
            } else {
                match self.evaluate_in_context(b, &candidate, ev) {
                    Some(e) => e,
                    None => return,
                }
            };
            self.pbest[row].copy_from_slice(&candidate);
            self.pbest_eval[i] = e;
            if e.better_feasibility_first(&self.gbest_eval) {
                self.gbest.copy_from_slice(&candidate);
                self.gbest_eval = e;
            }
            self.offer_context(b, &candidate, e);
        }
    }

    /// One PSO iteration of the sub-swarm.
    fn move_swarm(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let b = self.current;
        let r = self.range(b);
        let len = r.len();
        let CoopParams {
            inertia: w,
            cognitive: c1,
            social: c2,
            ..
        } = self.params;
        let mut candidate = vec![0.0; len];
        for i in 0..self.params.population {
            for (k, j) in r.clone().enumerate() {
                let bj = &bounds[j];
                let idx = i * len + k;
                let r1: f64 = rng.random();
                let r2: f64 = rng.random();
                let vmax = 0.5 * bj.width();
                let vj = (w * self.v[idx]
                    + c1 * r1 * (self.pbest[idx] - self.x[idx])
                    + c2 * r2 * (self.gbest[k] - self.x[idx]))
                    .clamp(-vmax, vmax);
                let moved = self.x[idx] + vj;
                self.v[idx] = if !bj.periodic && !bj.contains(moved) {
                    -vj
                } else {
                    vj
                };
                self.x[idx] = into_bound(bj, moved);
                candidate[k] = self.x[idx];
            }
            let Some(e) = self.evaluate_in_context(b, &candidate, ev) else {
                return;
            };
            if e.better_feasibility_first(&self.pbest_eval[i]) {
                self.pbest[i * len..(i + 1) * len].copy_from_slice(&candidate);
                self.pbest_eval[i] = e;
                if e.better_feasibility_first(&self.gbest_eval) {
                    self.gbest.copy_from_slice(&candidate);
                    self.gbest_eval = e;
                }
                self.offer_context(b, &candidate, e);
            }
        }
    }
}

impl Optimizer for Cooperative {
    fn evaluations_per_iteration(&self) -> u64 {
        self.params.population as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.dim = ev.dimension();
        self.block = ev.block_size();
        self.context = vec![0.0; self.dim];
        self.context_eval = Evaluation::worst();
        self.full = vec![0.0; self.dim];
        self.current = 0;
        self.spent = 0;
        self.spread = vec![self.params.perturbation; self.blocks()];
        let mut x = vec![0.0; self.dim];
        for i in 0..self.params.population.max(1) {
            ev.sample_initial(rng, &mut x);
            let Some(e) = ev.evaluate(&x) else { break };
            if i == 0 || e.better_feasibility_first(&self.context_eval) {
                self.context.copy_from_slice(&x);
                self.context_eval = e;
            }
        }
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        if self.dim == 0 {
            return;
        }
        if self.spent == 0 {
            self.start_visit(ev, rng);
        } else {
            self.move_swarm(ev, rng);
        }
        self.spent += 1;
        if self.spent > self.params.block_iterations {
            let s = &mut self.spread[self.current];
            *s = if self
                .context_eval
                .better_feasibility_first(&self.visit_start)
            {
                (*s * 2.0).min(0.5)
            } else {
                (*s * 0.5).max(1e-9)
            };
            self.spent = 0;
            self.current = (self.current + 1) % self.blocks();
        }
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (&self.context, self.context_eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::{solve, Budget};
    use crate::problem::Problem;
    use crate::rng::rng_from_seed;

    /// Sphere in blocks of 3, with a "constraint" x_0 >= 1 (violation 1 - x_0).
    struct Constrained(Vec<Bound>);

    impl Problem for Constrained {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            let violation = (1.0 - x[0]).max(0.0);
            Evaluation::new(
                x.iter().map(|v| v * v).sum::<f64>() + 1e3 * violation,
                violation,
            )
        }
        fn block_size(&self) -> usize {
            3
        }
    }

    #[test]
    fn finds_the_constrained_optimum_block_by_block() {
        let p = Constrained(vec![Bound::new(-5.0, 5.0); 9]);
        let mut opt = Cooperative::new(CoopParams::DEFAULT);
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(6000),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        assert!(out.best.feasible(), "{:?}", out.best);
        // Optimum: x_0 = 1, the rest 0, cost 1.
        assert!((out.best.cost - 1.0).abs() < 1e-2, "{}", out.best.cost);
        assert_eq!(out.evaluations, 6000);
    }
}
