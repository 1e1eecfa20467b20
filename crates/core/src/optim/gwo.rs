//! Grey wolf optimizer (Mirjalili, Mirjalili, Lewis 2014, Adv. Eng. Softw. 69:46-61,
//! doi:10.1016/j.advengsoft.2013.12.007).
//!
//! The pack follows its three leaders alpha, beta, delta. At step t (0-based) of T,
//! a = 2 - 2 t / T (T: the budget; under an evaluation budget t / T is the share of
//! evaluations spent, [`super::Progress::fraction`]); each wolf X moves, for every dimension j, to
//!
//! ```text
//! for L in {alpha, beta, delta}:  A = 2 a r1 - a,  C = 2 r2,
//!                                 D = |C X_L,j - X_j|,  X'_L = X_L,j - A D
//! X_j <- clamp((X'_alpha + X'_beta + X'_delta) / 3)
//! ```
//!
//! with fresh r1, r2 ~ U(0, 1) per leader and dimension. All wolves move with the leaders
//! fixed, then all are evaluated (the order of the reference code). The leaders are the
//! best three *distinct* positions seen so far: a better wolf demotes alpha to beta and
//! beta to delta. The widely copied reference code overwrites alpha without demoting it,
//! and can hold the same position twice; we keep a proper top three. Until three distinct
//! positions exist, missing leaders are replaced by the last one present.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::swarm::{into_bound, row, row_mut};
use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// Parameters of GWO.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GwoParams {
    /// Pack size N (50).
    pub population: usize,
}

impl GwoParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self { population: 50 };

    /// Checks the pack size; the error names the field.
    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            super::config::POPULATION_RANGE.contains(&self.population),
            "population",
            super::config::POPULATION_EXPECTED,
            self.population,
        )
    }
}

impl Default for GwoParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for GwoParams {
    fn population(&self) -> usize {
        self.population
    }

    fn set_population(&mut self, n: usize) {
        self.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Gwo::new(*self))
    }
}

/// The best three distinct positions seen, best first.
#[derive(Debug, Clone)]
pub(crate) struct Leaders {
    x: [Vec<f64>; 3],
    eval: [Evaluation; 3],
    len: usize,
}

impl Leaders {
    fn new(dim: usize) -> Self {
        Self {
            x: [vec![0.0; dim], vec![0.0; dim], vec![0.0; dim]],
            eval: [Evaluation::worst(); 3],
            len: 0,
        }
    }

    /// Inserts `x` at its rank (an empty slot takes anything; otherwise strictly better
    /// than the leader it displaces), demoting the ones below. A position already held by
    /// a leader is ignored.
    fn offer(&mut self, x: &[f64], e: Evaluation) {
        if self.x[..self.len].iter().any(|l| l.as_slice() == x) {
            return;
        }
        let rank = (0..self.len)
            .find(|&k| e.better_than(&self.eval[k]))
            .unwrap_or(self.len);
        if rank >= 3 {
            return;
        }
        let last = self.len.min(2);
        // Rotating moves the displaced buffers down without allocating; the old last
        // leader's buffer comes up to `rank` and is overwritten.
        self.x[rank..=last].rotate_right(1);
        self.eval[rank..=last].rotate_right(1);
        self.x[rank].copy_from_slice(x);
        self.eval[rank] = e;
        self.len = (self.len + 1).min(3);
    }

    /// Leader k (0 alpha, 1 beta, 2 delta), or the last present one.
    fn get(&self, k: usize) -> &[f64] {
        &self.x[k.min(self.len.saturating_sub(1))]
    }
}

/// GWO.
#[derive(Debug, Clone)]
pub struct Gwo {
    params: GwoParams,
    n: usize,
    dim: usize,
    x: Vec<f64>,
    leaders: Leaders,
}

impl Gwo {
    /// GWO with `params`; the pack is drawn at initialisation.
    #[must_use]
    pub fn new(params: GwoParams) -> Self {
        Self {
            params,
            n: params.population.max(1),
            dim: 0,
            x: Vec::new(),
            leaders: Leaders::new(0),
        }
    }

    /// The parameters it runs with.
    #[must_use]
    pub fn params(&self) -> &GwoParams {
        &self.params
    }

    /// a = 2 - 2 t / T at budget fraction `frac = t / T` ([`super::Progress::fraction`]), never
    /// below 0.
    #[must_use]
    pub fn a(frac: f64) -> f64 {
        (2.0 - 2.0 * frac).max(0.0)
    }

    /// Evaluates the whole pack in parallel and offers each wolf to the leaders in order
    /// (the leaders are fixed while the pack moves, so this is Mirjalili's update).
    fn evaluate_pack(&mut self, ev: &mut Evaluator<'_>) {
        let mut evals = Vec::with_capacity(self.n);
        // With three leaders, a wolf matters only if it costs less than delta, whose cost
        // only falls while the pack is offered: its evaluation may stop above delta's cost
        // at the start, or at +inf when delta's is +inf (the same run, for less;
        // docs/performance.md).
        let cutoff = if self.leaders.len == 3 {
            self.leaders.eval[2].cutoff_to_beat()
        } else {
            f64::INFINITY
        };
        ev.evaluate_rows_cost_bounded(&self.x, self.n, cutoff, &mut evals);
        for (i, e) in evals.into_iter().enumerate() {
            self.leaders.offer(row(&self.x, i, self.dim), e);
        }
    }

    /// The costs of alpha, beta and delta (those present).
    #[must_use]
    pub fn leader_costs(&self) -> Vec<f64> {
        self.leaders.eval[..self.leaders.len]
            .iter()
            .map(|e| e.cost)
            .collect()
    }
}

impl Optimizer for Gwo {
    fn evaluations_per_iteration(&self) -> u64 {
        self.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let dim = bounds.len();
        self.dim = dim;
        self.x = vec![0.0; self.n * dim];
        self.leaders = Leaders::new(dim);
        for i in 0..self.n {
            ev.sample_initial(rng, row_mut(&mut self.x, i, dim));
        }
        self.evaluate_pack(ev);
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        if self.leaders.len == 0 {
            return; // nothing was ever evaluated: the budget is spent
        }
        let bounds = ev.bounds();
        let dim = self.dim;
        let a = Self::a(ev.progress().fraction());
        let leaders = [
            self.leaders.get(0),
            self.leaders.get(1),
            self.leaders.get(2),
        ];
        for i in 0..self.n {
            let x = row_mut(&mut self.x, i, dim);
            for j in 0..dim {
                let mut sum = 0.0;
                for l in &leaders {
                    let r1: f64 = rng.random();
                    let r2: f64 = rng.random();
                    let big_a = 2.0 * a * r1 - a;
                    let c = 2.0 * r2;
                    let d = (c * l[j] - x[j]).abs();
                    sum += l[j] - big_a * d;
                }
                x[j] = into_bound(&bounds[j], sum / 3.0);
            }
        }
        self.evaluate_pack(ev);
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (self.leaders.get(0), self.leaders.eval[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(c: f64) -> Evaluation {
        Evaluation::new(c, 0.0)
    }

    #[test]
    fn keeps_a_proper_top_three() {
        let mut l = Leaders::new(1);
        l.offer(&[5.0], ev(5.0));
        assert_eq!(
            l.get(2),
            &[5.0],
            "a missing leader falls back to the last present"
        );
        l.offer(&[3.0], ev(3.0));
        l.offer(&[4.0], ev(4.0));
        l.offer(&[1.0], ev(1.0));
        // The old alpha (3) is demoted to beta, not overwritten.
        assert_eq!(l.eval.map(|e| e.cost), [1.0, 3.0, 4.0]);
        assert_eq!([l.get(0), l.get(1), l.get(2)], [&[1.0][..], &[3.0], &[4.0]]);
        // A position already held is not taken twice; a worse one does not enter.
        l.offer(&[1.0], ev(1.0));
        l.offer(&[9.0], ev(9.0));
        l.offer(&[f64::NAN], ev(f64::NAN));
        assert_eq!(l.eval.map(|e| e.cost), [1.0, 3.0, 4.0]);
        l.offer(&[2.0], ev(2.0));
        assert_eq!([l.get(0), l.get(1), l.get(2)], [&[1.0][..], &[2.0], &[3.0]]);
    }

    #[test]
    fn a_decreases_linearly_to_zero() {
        assert_eq!(Gwo::a(0.0), 2.0);
        assert_eq!(Gwo::a(0.5), 1.0);
        assert_eq!(Gwo::a(1.0), 0.0);
        assert_eq!(Gwo::a(1.5), 0.0);
    }
}
