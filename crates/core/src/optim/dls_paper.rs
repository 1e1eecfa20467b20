//! DLS-SMPSO, paper mode (the DLS-SMPSO paper, Guo, Gan, Hu 2024, Drones 8(11):654,
//! doi:10.3390/drones8110654, Eqs. 18-21 and Algorithm 1): the PSO of
//! [`super::pso`] with SPSO's settings, a deterministic pull towards gbest and
//! stagnation-triggered dimensional learning ([`super::dimensional`]).
//!
//! ```text
//! v_ij <- w v_ij + c1 r1 (pbest_ij - x_ij) + c2 r2 (gbest_j - x_ij) + lambda (gbest_j - x_ij)
//! ```
//!
//! then clamped, moved and mirrored exactly as in PSO, with the inertia schedule over the
//! budget. Each particle keeps a stagnation counter c_i: +1 after an evaluation that did not
//! improve pbest_i, reset to 0 by one that did (so it counts *consecutive* failures: the
//! paper's pseudo-code never resets it on an improvement, which would make "stagnation" fire
//! on old failures). A particle is *stagnant* when c_i exceeds d. After the swarm has moved,
//! stagnant particles are served substitution passes: for j = 1..D with pbest_ij !=
//! gbest_j, S = pbest_i with S_j = gbest_j is evaluated and kept (cumulatively) only if its
//! cost is strictly lower (the paper's pseudo-code writes that assignment backwards, and runs
//! the substitution in the `else` branch of `c_i > d`; we follow its prose). An improved
//! pbest_i is offered to gbest and a served particle's counter is reset.
//!
//! **Budget of the passes.** Left unbounded, passes fire for about one particle in d + 1 at
//! every iteration (up to N D / (d + 1) = 1250 extra evaluations per iteration for N = 50,
//! D = 150, d = 5: twenty times PSO's budget). The paper gives no figure, so at most
//! `max_passes_per_iteration` passes run per iteration (default 1: at most D extra
//! evaluations, fewer since dimensions equal to gbest cost nothing).
//!
//! **Fair allocation.** The passes go round robin: a cursor walks the swarm, each pass
//! serves the first stagnant particle at or after it (cyclically) and moves the cursor past
//! it. A stagnant particle that is not served keeps its counter and waits for its turn, so
//! every stagnant particle is served within N passes. (The first build served the
//! lowest-index stagnant particle in each iteration, so particles near the end of the swarm
//! almost never learned.)
//!
//! Every DLS evaluation goes through the [`Evaluator`] and counts in the budget; when the
//! budget runs out during a pass, the substitutions accepted so far are kept.

use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::dimensional::build_exemplar_into;
use super::pso::{PsoParams, Swarm};
use super::swarm::{row, row_mut};
use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// Parameters of DLS-SMPSO in paper mode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DlsPaperParams {
    /// The underlying PSO (SPSO's settings: N = 50, w = 1 damped 0.98, c1 = c2 = 1.5).
    pub pso: PsoParams,
    /// DLS learning rate lambda of Eq. 21 (0.5; the paper gives no value).
    pub lambda: f64,
    /// Stagnation threshold d: a particle whose counter exceeds it is stagnant (5; the
    /// paper gives no value).
    pub stagnation: usize,
    /// Substitution passes allowed per iteration (1).
    pub max_passes_per_iteration: usize,
}

impl DlsPaperParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        pso: PsoParams::DEFAULT,
        lambda: 0.5,
        stagnation: 5,
        max_passes_per_iteration: 1,
    };

    /// Checks the PSO section and `lambda`; the error names the first bad field.
    pub fn validate(&self) -> Result<(), ParamsError> {
        self.pso.validate().map_err(|e| e.within("pso"))?;
        check(
            self.lambda.is_finite() && self.lambda >= 0.0,
            "lambda",
            "a finite number >= 0",
            self.lambda,
        )
    }
}

impl Default for DlsPaperParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for DlsPaperParams {
    fn population(&self) -> usize {
        self.pso.population
    }

    fn set_population(&mut self, n: usize) {
        self.pso.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(DlsPaper::new(*self))
    }
}

/// DLS-SMPSO, paper mode.
#[derive(Debug, Clone)]
pub struct DlsPaper {
    params: DlsPaperParams,
    swarm: Swarm,
    /// Consecutive non-improving evaluations per particle.
    stagnation: Vec<usize>,
    /// Where the round robin of substitution passes resumes.
    cursor: usize,
    /// Scratch row for a substitution pass.
    scratch: Vec<f64>,
    /// Evaluations spent by dimensional learning so far.
    dls_evaluations: u64,
    /// Passes served to each particle so far.
    served: Vec<u64>,
}

impl DlsPaper {
    /// DLS-SMPSO in paper mode with `params`; the swarm is drawn at initialisation.
    #[must_use]
    pub fn new(params: DlsPaperParams) -> Self {
        Self {
            params,
            swarm: Swarm::new(params.pso, &[]),
            stagnation: Vec::new(),
            cursor: 0,
            scratch: Vec::new(),
            dls_evaluations: 0,
            served: Vec::new(),
        }
    }

    /// The parameters it runs with.
    #[must_use]
    pub fn params(&self) -> &DlsPaperParams {
        &self.params
    }

    /// Evaluations spent by dimensional learning (included in the run's total).
    #[must_use]
    pub fn dls_evaluations(&self) -> u64 {
        self.dls_evaluations
    }

    /// Substitution passes served to each particle.
    #[must_use]
    pub fn passes_served(&self) -> &[u64] {
        &self.served
    }

    /// Substitutes gbest's dimensions into pbest_i, keeping improvements.
    fn substitute(&mut self, i: usize, ev: &mut Evaluator<'_>) {
        let s = &mut self.swarm;
        let dim = s.dim;
        let stats = build_exemplar_into(
            &mut |x, cost| ev.evaluate_cost_bounded(x, cost),
            row(&s.pbest, i, dim),
            s.pbest_eval[i],
            &s.gbest.x,
            &mut self.scratch,
        );
        self.dls_evaluations += stats.evaluations;
        self.served[i] += 1;
        if stats.accepted > 0 {
            row_mut(&mut s.pbest, i, dim).copy_from_slice(&self.scratch);
            s.pbest_eval[i] = stats.eval;
            s.offer_pbest(i);
        }
    }

    /// Serves up to `max_passes_per_iteration` stagnant particles, round robin.
    fn serve_stagnant(&mut self, ev: &mut Evaluator<'_>) {
        let n = self.swarm.n;
        let d = self.params.stagnation;
        for _ in 0..self.params.max_passes_per_iteration {
            let Some(i) = (0..n)
                .map(|k| (self.cursor + k) % n)
                .find(|&i| self.stagnation[i] > d)
            else {
                return;
            };
            if ev.is_exhausted() {
                return;
            }
            self.stagnation[i] = 0;
            self.cursor = (i + 1) % n;
            self.substitute(i, ev);
        }
    }
}

impl Optimizer for DlsPaper {
    fn evaluations_per_iteration(&self) -> u64 {
        self.swarm.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.swarm = Swarm::new(self.params.pso, ev.bounds());
        let (n, dim) = (self.swarm.n, self.swarm.dim);
        self.stagnation = vec![0; n];
        self.served = vec![0; n];
        self.cursor = 0;
        self.dls_evaluations = 0;
        self.scratch = vec![0.0; dim];
        self.swarm.initialize(ev, rng);
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        self.swarm.schedule(ev.progress());
        let mut cut = false;
        for i in 0..self.swarm.n {
            self.swarm
                .move_particle(i, None, self.params.lambda, bounds, rng);
            match self.swarm.evaluate_particle(i, ev) {
                None => {
                    cut = true;
                    break;
                }
                Some(true) => self.stagnation[i] = 0,
                Some(false) => self.stagnation[i] += 1,
            }
        }
        if !cut {
            self.serve_stagnant(ev);
        }
        self.swarm.end_iteration();
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (&self.swarm.gbest.x, self.swarm.gbest.eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::test_problems::{Flat, Sphere};
    use crate::optim::{solve, Budget};
    use crate::problem::Bound;
    use crate::rng::rng_from_seed;

    fn run(iterations: usize) -> (DlsPaper, crate::optim::Outcome) {
        let p = Sphere(vec![Bound::new(-10.0, 10.0); 10]);
        let mut opt = DlsPaper::new(DlsPaperParams {
            pso: PsoParams {
                population: 10,
                ..PsoParams::DEFAULT
            },
            ..DlsPaperParams::DEFAULT
        });
        let out = solve(
            &p,
            &mut opt,
            Budget::iterations(iterations),
            &mut rng_from_seed(5),
            &mut |_| {},
        );
        (opt, out)
    }

    #[test]
    fn spends_extra_evaluations_and_counts_them() {
        let (opt, out) = run(50);
        assert!(opt.dls_evaluations() > 0);
        assert_eq!(out.evaluations, 10 + 50 * 10 + opt.dls_evaluations());
        assert!(out.best.cost < 1.0, "{}", out.best.cost);
    }

    #[test]
    fn passes_go_round_robin_to_every_particle() {
        // On a flat function nothing ever improves, so every particle is stagnant whenever
        // its counter allows: round robin serves them in turn, none more than once ahead.
        let p = Flat(vec![Bound::new(-1.0, 1.0); 4]);
        let mut opt = DlsPaper::new(DlsPaperParams {
            pso: PsoParams {
                population: 10,
                ..PsoParams::DEFAULT
            },
            ..DlsPaperParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut opt,
            Budget::iterations(300),
            &mut rng_from_seed(5),
            &mut |_| {},
        );
        let served = opt.passes_served();
        let lo = served.iter().min().copied().unwrap_or(0);
        let hi = served.iter().max().copied().unwrap_or(0);
        assert!(lo >= 25 && hi - lo <= 1, "unfair allocation: {served:?}");
        // On sphere, where particles improve at different rates, every one still learns.
        let (opt, _) = run(300);
        assert!(
            opt.passes_served().iter().all(|&k| k >= 1),
            "{:?}",
            opt.passes_served()
        );
    }
}
