//! Artificial bee colony (Karaboga 2005, Tech. Rep. TR06, Erciyes Univ.; Karaboga & Akay
//! 2009, Appl. Math. Comput. 214:108-132, doi:10.1016/j.amc.2009.03.090).
//!
//! SN = population / 2 food sources x_i, each with a trial counter. One iteration (cycle):
//!
//! - *Employed bees*: for every source i, pick a dimension j and a partner k != i at random
//!   and try `v = x_i` with `v_j = x_ij + U(-1, 1) (x_ij - x_kj)` (projected into the
//!   bound). Greedy selection: v replaces x_i if its cost is strictly lower (trial_i = 0),
//!   else trial_i += 1.
//! - *Onlooker bees*: SN moves as above, each on a source drawn by roulette with
//!   probability fit_i / sum fit, `fit = 1 / (1 + f)` for f >= 0 and `1 + |f|` for f < 0
//!   (probabilities computed once, after the employed phase; uniform if the fitness sum is
//!   not a positive finite number, e.g. when every cost is infinite).
//! - *Scout*: the source with the largest trial counter, if that counter is above `limit`,
//!   is replaced by a uniform random position (evaluated; trial reset). One per cycle.
//!
//! The best position ever evaluated is remembered separately, so scouting never loses it.
//!
//! **Choice of `limit` (100).** Karaboga & Akay set limit = SN x D, i.e. 3750 for the
//! paper's 25 sources and D = 150. A counter grows by one per employed move and per
//! onlooker visit, so in 200 cycles it reaches at most a few hundred and no scout would ever
//! fire: ABC would silently lose its exploration operator. 100 is the default of Karaboga's
//! public reference implementation and fires after about 50 unproductive cycles of an
//! average source, several times in a 200-cycle run.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::swarm::{into_bound, row, row_mut, BestSoFar};
use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// Parameters of ABC.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AbcParams {
    /// Colony size NP: employed plus onlooker bees (50, i.e. SN = 25 food sources; at
    /// least 4).
    pub population: usize,
    /// Trials without improvement after which a source is abandoned, limit (100; see the
    /// module docs for why not SN x D).
    pub limit: usize,
}

impl AbcParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        population: 50,
        limit: 100,
    };

    /// Checks the colony size; the error names the field.
    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            super::config::POPULATION_RANGE.contains(&self.population),
            "population",
            super::config::POPULATION_EXPECTED,
            self.population,
        )
    }

    /// Number of food sources SN.
    #[must_use]
    pub fn sources(&self) -> usize {
        (self.population / 2).max(2)
    }
}

impl Default for AbcParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for AbcParams {
    fn population(&self) -> usize {
        self.population
    }

    fn set_population(&mut self, n: usize) {
        self.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Abc::new(*self))
    }
}

/// ABC's fitness of a cost: 1 / (1 + f) for f >= 0, 1 + |f| below.
#[must_use]
pub fn fitness(cost: f64) -> f64 {
    if cost >= 0.0 {
        1.0 / (1.0 + cost)
    } else {
        1.0 + cost.abs()
    }
}

/// ABC.
#[derive(Debug, Clone)]
pub struct Abc {
    params: AbcParams,
    sn: usize,
    dim: usize,
    x: Vec<f64>,
    eval: Vec<Evaluation>,
    trial: Vec<usize>,
    /// Roulette weights (fitness), recomputed once per cycle.
    fit: Vec<f64>,
    /// Scratch for the scout's new position.
    scratch: Vec<f64>,
    best: BestSoFar,
    scouts: u64,
}

impl Abc {
    /// ABC with `params`; the colony is drawn at initialisation.
    #[must_use]
    pub fn new(params: AbcParams) -> Self {
        Self {
            params,
            sn: params.sources(),
            dim: 0,
            x: Vec::new(),
            eval: Vec::new(),
            trial: Vec::new(),
            fit: Vec::new(),
            scratch: Vec::new(),
            best: BestSoFar::new(0),
            scouts: 0,
        }
    }

    /// The parameters it runs with.
    #[must_use]
    pub fn params(&self) -> &AbcParams {
        &self.params
    }

    /// Scouts sent so far.
    #[must_use]
    pub fn scouts(&self) -> u64 {
        self.scouts
    }

    /// One neighbour move on source i with greedy selection; `None` when the budget is
    /// spent (source unchanged).
    fn try_move(&mut self, i: usize, ev: &mut Evaluator<'_>, rng: &mut Rng) -> Option<()> {
        let dim = self.dim;
        if dim == 0 {
            return Some(());
        }
        let j = rng.random_range(0..dim);
        let mut k = rng.random_range(0..self.sn - 1);
        if k >= i {
            k += 1;
        }
        let phi = 2.0 * rng.random::<f64>() - 1.0;
        let xkj = self.x[k * dim + j];
        let x = row_mut(&mut self.x, i, dim);
        let old = x[j];
        x[j] = into_bound(&ev.bounds()[j], old + phi * (old - xkj));
        // The candidate matters only if it beats source i, which costs no less than the best
        // so far, so the evaluation may stop once its cost is known to exceed source i's (or
        // to be +inf when source i's is: `cutoff_to_beat`). It
        // is one coordinate away from source i, so it is evaluated on source i's buffers.
        let Some(e) = ev.evaluate_cost_bounded_in(x, self.eval[i].cutoff_to_beat(), i) else {
            x[j] = old;
            return None;
        };
        self.best.offer(x, e);
        if e.better_than(&self.eval[i]) {
            self.eval[i] = e;
            self.trial[i] = 0;
        } else {
            x[j] = old;
            self.trial[i] += 1;
        }
        Some(())
    }

    /// A source drawn with probability proportional to `fit`.
    fn roulette(&self, total: f64, rng: &mut Rng) -> usize {
        if !(total.is_finite() && total > 0.0) {
            return rng.random_range(0..self.sn);
        }
        let mut r = rng.random::<f64>() * total;
        for (i, f) in self.fit.iter().enumerate() {
            r -= f;
            if r < 0.0 {
                return i;
            }
        }
        // Rounding left a sliver at the end: the last source with any weight takes it.
        self.fit
            .iter()
            .rposition(|f| *f > 0.0)
            .unwrap_or(self.sn - 1)
    }

    /// Replaces the most-tried source if its counter exceeds `limit`.
    fn scout(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let Some((i, &t)) = self
            .trial
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.cmp(b.1).then(b.0.cmp(&a.0)))
        else {
            return;
        };
        if t <= self.params.limit {
            return;
        }
        ev.sample_initial(rng, &mut self.scratch);
        let Some(e) = ev.evaluate(&self.scratch) else {
            return;
        };
        row_mut(&mut self.x, i, self.dim).copy_from_slice(&self.scratch);
        self.eval[i] = e;
        self.trial[i] = 0;
        self.best.offer(&self.scratch, e);
        self.scouts += 1;
    }
}

impl Optimizer for Abc {
    fn evaluations_per_iteration(&self) -> u64 {
        2 * self.sn as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let (sn, dim) = (self.sn, bounds.len());
        self.dim = dim;
        self.x = vec![0.0; sn * dim];
        self.eval = vec![Evaluation::worst(); sn];
        self.trial = vec![0; sn];
        self.fit = vec![0.0; sn];
        self.scratch = vec![0.0; dim];
        self.best = BestSoFar::new(dim);
        self.scouts = 0;
        for i in 0..sn {
            ev.sample_initial(rng, row_mut(&mut self.x, i, dim));
        }
        let mut evals = Vec::with_capacity(sn);
        ev.evaluate_rows(&self.x, sn, &mut evals);
        for i in 0..sn {
            let e = evals.get(i).copied().unwrap_or(Evaluation::worst());
            self.eval[i] = e;
            self.best.offer(row(&self.x, i, dim), e);
        }
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        for i in 0..self.sn {
            if self.try_move(i, ev, rng).is_none() {
                return;
            }
        }
        let mut total = 0.0;
        for (f, e) in self.fit.iter_mut().zip(&self.eval) {
            *f = fitness(e.cost);
            total += *f;
        }
        for _ in 0..self.sn {
            let i = self.roulette(total, rng);
            if self.try_move(i, ev, rng).is_none() {
                return;
            }
        }
        self.scout(ev, rng);
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (&self.best.x, self.best.eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::{solve, Budget};
    use crate::problem::{Bound, Problem};
    use crate::rng::rng_from_seed;

    #[test]
    fn fitness_is_karabogas() {
        assert_eq!(fitness(0.0), 1.0);
        assert_eq!(fitness(3.0), 0.25);
        assert_eq!(fitness(-2.0), 3.0);
        assert_eq!(fitness(f64::INFINITY), 0.0);
    }

    /// Nothing ever improves: every move fails, so counters grow until scouts fire.
    struct Flat(Vec<Bound>);

    impl Problem for Flat {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, _: &[f64]) -> Evaluation {
            Evaluation::new(1.0, 0.0)
        }
    }

    #[test]
    fn scout_fires_once_the_limit_is_passed_and_counts() {
        let p = Flat(vec![Bound::new(0.0, 1.0); 3]);
        let params = AbcParams {
            population: 4,
            limit: 6,
        };
        // SN = 2; each cycle gives every source one employed trial and the two onlookers
        // two more between them: after 2 cycles a counter is at most 2 + 4 = 6 (no scout
        // yet), and over 20 cycles the 80 failed trials must push counters past 6 often.
        let mut abc = Abc::new(params);
        let out = solve(
            &p,
            &mut abc,
            Budget::iterations(2),
            &mut rng_from_seed(9),
            &mut |_| {},
        );
        assert_eq!(abc.scouts(), 0);
        assert_eq!(out.evaluations, 2 + 2 * 4);
        let mut abc = Abc::new(params);
        let out = solve(
            &p,
            &mut abc,
            Budget::iterations(20),
            &mut rng_from_seed(9),
            &mut |_| {},
        );
        assert!(abc.scouts() >= 3, "scouts {}", abc.scouts());
        assert_eq!(out.evaluations, 2 + 20 * 4 + abc.scouts());
        // At most one scout per cycle.
        assert!(abc.scouts() <= 20);
    }
}
