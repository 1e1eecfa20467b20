//! DLS-SMPSO, exemplar mode: SPSO's PSO learning from exemplars built by the original
//! dimensional learning strategy of Xu et al. 2019 ("Particle swarm optimization based on
//! dimensional learning strategy", Swarm Evol. Comput. 45:33-51; their public code
//! wucg/TSLPSO).
//!
//! Every time pbest_i improves (and once at initialisation, as in their code) an exemplar
//! x_dl is built from pbest_i by the greedy substitution of [`super::dimensional`] and used in
//! place of pbest_i in the velocity: `v <- w v + c1 r1 (x_dl - x) + c2 r2 (gbest - x)` (no
//! lambda term; inertia schedule over the budget as in [`super::pso`]). The learning source
//! is gbest, except when pbest_i *is* gbest: then it is the best pbest among the particle's
//! nearest neighbours (the `neighbour_fraction` x N particles, at least one, closest to x_i
//! in Euclidean distance of current positions, as in their code). An exemplar better than
//! gbest becomes gbest (pbest_i is left alone, as in their code). When no dimension was
//! accepted, one random dimension j of the exemplar is re-drawn uniformly within the range
//! the swarm currently spans in j, [min_k x_kj, max_k x_kj] (their code means this but
//! writes `rand*(rmin+rmax)-pe(d1)` with a linear index, which is a bug). That perturbed
//! exemplar is not evaluated. Exemplar updates happen at once, within the iteration
//! (consistent with the asynchronous gbest); their code batches them after the swarm moved.
//!
//! Every DLS evaluation goes through the [`Evaluator`] and counts in the budget.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::dimensional::build_exemplar_into;
use super::pso::{PsoParams, Swarm};
use super::swarm::{row, row_mut};
use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// Parameters of DLS-SMPSO in exemplar mode.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DlsExemplarParams {
    /// The underlying PSO (SPSO's settings).
    pub pso: PsoParams,
    /// Share of the swarm taken as a particle's nearest neighbours when it is itself gbest
    /// (0.2, TSLPSO's `floor(0.2 N)`; at least one).
    pub neighbour_fraction: f64,
}

impl DlsExemplarParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        pso: PsoParams::DEFAULT,
        neighbour_fraction: 0.2,
    };

    /// Checks the PSO section and `neighbour_fraction`; the error names the first bad field.
    pub fn validate(&self) -> Result<(), ParamsError> {
        self.pso.validate().map_err(|e| e.within("pso"))?;
        check(
            (0.0..=1.0).contains(&self.neighbour_fraction),
            "neighbour_fraction",
            "a number in [0, 1]",
            self.neighbour_fraction,
        )
    }
}

impl Default for DlsExemplarParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for DlsExemplarParams {
    fn population(&self) -> usize {
        self.pso.population
    }

    fn set_population(&mut self, n: usize) {
        self.pso.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(DlsExemplar::new(*self))
    }
}

/// DLS-SMPSO, exemplar mode.
#[derive(Debug, Clone)]
pub struct DlsExemplar {
    params: DlsExemplarParams,
    swarm: Swarm,
    /// One exemplar per particle (row-major).
    exemplar: Vec<f64>,
    /// (distance, index) scratch for the neighbour search.
    neighbours: Vec<(f64, usize)>,
    /// Evaluations spent by dimensional learning so far.
    dls_evaluations: u64,
}

impl DlsExemplar {
    /// DLS-SMPSO in exemplar mode with `params`; the swarm is drawn at initialisation.
    #[must_use]
    pub fn new(params: DlsExemplarParams) -> Self {
        Self {
            params,
            swarm: Swarm::new(params.pso, &[]),
            exemplar: Vec::new(),
            neighbours: Vec::new(),
            dls_evaluations: 0,
        }
    }

    /// The parameters it runs with.
    #[must_use]
    pub fn params(&self) -> &DlsExemplarParams {
        &self.params
    }

    /// Evaluations spent by dimensional learning (included in the run's total).
    #[must_use]
    pub fn dls_evaluations(&self) -> u64 {
        self.dls_evaluations
    }

    /// Rebuilds the exemplar of particle i from its (new) pbest.
    fn rebuild_exemplar(&mut self, i: usize, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let dim = self.swarm.dim;
        let is_gbest = row(&self.swarm.pbest, i, dim) == self.swarm.gbest.x.as_slice();
        let guide_index = if is_gbest {
            self.best_neighbour(i)
        } else {
            None
        };
        let s = &mut self.swarm;
        let guide = match guide_index {
            Some(k) => row(&s.pbest, k, dim),
            None => s.gbest.x.as_slice(),
        };
        let out = row_mut(&mut self.exemplar, i, dim);
        let stats = build_exemplar_into(
            &mut |x, cost| ev.evaluate_cost_bounded(x, cost),
            row(&s.pbest, i, dim),
            s.pbest_eval[i],
            guide,
            out,
        );
        self.dls_evaluations += stats.evaluations;
        if stats.accepted > 0 {
            s.gbest.offer(out, stats.eval);
        } else if dim > 0 {
            let j = rng.random_range(0..dim);
            let (lo, hi) = (0..s.n).fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), k| {
                let v = s.x[k * dim + j];
                (lo.min(v), hi.max(v))
            });
            let u: f64 = rng.random();
            out[j] = (lo + u * (hi - lo)).clamp(lo, hi);
        }
    }

    /// The neighbour of particle i (by current position) with the best pbest, among the
    /// `neighbour_fraction` x N nearest (at least one); `None` for a lone particle.
    fn best_neighbour(&mut self, i: usize) -> Option<usize> {
        let s = &self.swarm;
        let dim = s.dim;
        let xi = row(&s.x, i, dim);
        self.neighbours.clear();
        self.neighbours
            .extend((0..s.n).filter(|&k| k != i).map(|k| {
                let d2: f64 = row(&s.x, k, dim)
                    .iter()
                    .zip(xi)
                    .map(|(a, b)| (a - b) * (a - b))
                    .sum();
                (d2, k)
            }));
        self.neighbours
            .sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        // Truncation is intended: TSLPSO uses floor(0.2 N).
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let k = ((self.params.neighbour_fraction * s.n as f64) as usize).max(1);
        let mut best: Option<usize> = None;
        for &(_, k) in self.neighbours.iter().take(k) {
            if best.is_none_or(|b| s.pbest_eval[k].better_than(&s.pbest_eval[b])) {
                best = Some(k);
            }
        }
        best
    }
}

impl Optimizer for DlsExemplar {
    fn evaluations_per_iteration(&self) -> u64 {
        self.swarm.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.swarm = Swarm::new(self.params.pso, ev.bounds());
        let n = self.swarm.n;
        self.dls_evaluations = 0;
        self.swarm.initialize(ev, rng);
        self.exemplar = self.swarm.pbest.clone();
        self.neighbours = Vec::with_capacity(n);
        for i in 0..n {
            if ev.is_exhausted() {
                break;
            }
            self.rebuild_exemplar(i, ev, rng);
        }
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let dim = self.swarm.dim;
        self.swarm.schedule(ev.progress());
        for i in 0..self.swarm.n {
            let guide = row(&self.exemplar, i, dim);
            self.swarm.move_particle(i, Some(guide), 0.0, bounds, rng);
            match self.swarm.evaluate_particle(i, ev) {
                None => break,
                Some(true) => self.rebuild_exemplar(i, ev, rng),
                Some(false) => {}
            }
            if ev.is_exhausted() {
                break;
            }
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
    use crate::optim::test_problems::Sphere;
    use crate::optim::{solve, Budget};
    use crate::problem::Bound;
    use crate::rng::rng_from_seed;

    #[test]
    fn spends_extra_evaluations_and_counts_them() {
        let p = Sphere(vec![Bound::new(-10.0, 10.0); 10]);
        let mut opt = DlsExemplar::new(DlsExemplarParams {
            pso: PsoParams {
                population: 10,
                ..PsoParams::DEFAULT
            },
            ..DlsExemplarParams::DEFAULT
        });
        let out = solve(
            &p,
            &mut opt,
            Budget::iterations(50),
            &mut rng_from_seed(5),
            &mut |_| {},
        );
        assert!(opt.dls_evaluations() > 0);
        assert_eq!(out.evaluations, 10 + 50 * 10 + opt.dls_evaluations());
        assert!(out.best.cost < 1.0, "{}", out.best.cost);
    }
}
