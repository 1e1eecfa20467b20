//! L-SHADE: success-history adaptive differential evolution with linear population size
//! reduction (Tanabe & Fukunaga 2014, IEEE CEC, 1658-1665, doi:10.1109/CEC.2014.6900380;
//! SHADE: Tanabe & Fukunaga 2013, IEEE CEC, doi:10.1109/CEC.2013.6557555), the winner of
//! the CEC 2014 competition and the root of jSO and most later winners. Here as a modern
//! baseline: Shehadeh & Kudela (2025, arXiv 2501.14503) find such methods ahead of PSO
//! variants on UAV path planning.
//!
//! One generation, for every individual x_i of the N in the population:
//!
//! ```text
//! r ~ U{1..H};  CR_i ~ N(M_CR[r], 0.1) clipped to [0, 1] (0 when M_CR[r] is terminal);
//! F_i ~ Cauchy(M_F[r], 0.1), redrawn while <= 0, cut to 1
//! v = x_i + F_i (x_pbest - x_i) + F_i (x_r1 - x_r2)      (current-to-pbest/1)
//!     x_pbest: one of the best max(2, round(p N)); r1 from P, r2 from P and archive A,
//!     all distinct from i and each other
//! v_j outside [lo, hi] -> (lo + x_ij) / 2 or (hi + x_ij) / 2   (periodic bounds wrap)
//! u_j = v_j if U(0,1) <= CR_i or j = j_rand, else x_ij          (binomial crossover)
//! ```
//!
//! then, once every trial is evaluated, u_i replaces x_i when it is no worse; a strictly
//! better trial sends x_i to the archive (random members are dropped beyond
//! round(r_arc N)) and records CR_i, F_i with weight |f(x_i) - f(u_i)|. Memory slot k
//! (cyclic) takes the weighted Lehmer means of the successes (`M_CR[k]` turns terminal when
//! every successful CR was 0). The population then shrinks linearly with the budget
//! fraction, N = round(N_init + (N_min - N_init) fraction), dropping the worst.
//!
//! Defaults are the paper's (r_N_init = 18, N_min = 4, H = 6, r_arc = 2.6, p = 0.11), with
//! one budget adaptation: N_init = 18 D is capped at `max_population` (100). The paper
//! sizes N_init for 10,000 D evaluations; at the 38,700 evaluations of the paper cases
//! (D = 150, about 258 D) 18 D = 2,700 individuals would leave about 14 generations.
//! Candidates are compared by cost (penalty included), as the paper's methods are.

use rand::Rng as _;
use rand_distr::{Cauchy, Distribution, Normal};
use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::swarm::{row, row_mut, BestSoFar};
use super::{Evaluator, Optimizer};
use crate::problem::{Bound, Evaluation};
use crate::rng::Rng;

/// Parameters of L-SHADE.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LshadeParams {
    /// Initial population per dimension, r_N_init (18).
    pub population_per_dimension: f64,
    /// Cap on the initial population (100; see the module docs).
    pub max_population: usize,
    /// Final population N_min (4).
    pub min_population: usize,
    /// Memory size H (6).
    pub memory: usize,
    /// Archive size per individual, r_arc (2.6).
    pub archive_rate: f64,
    /// Share of the population that pbest is drawn from, p (0.11).
    pub p_best: f64,
}

impl LshadeParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        population_per_dimension: 18.0,
        max_population: 100,
        min_population: 4,
        memory: 6,
        archive_rate: 2.6,
        p_best: 0.11,
    };

    /// Checks every field; the error names the first bad one.
    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            self.population_per_dimension.is_finite() && self.population_per_dimension > 0.0,
            "population_per_dimension",
            "a positive number",
            self.population_per_dimension,
        )?;
        check(
            (4..=100_000).contains(&self.min_population),
            "min_population",
            "a whole number in [4, 100000]",
            self.min_population,
        )?;
        check(
            self.max_population >= self.min_population && self.max_population <= 100_000,
            "max_population",
            "a whole number in [min_population, 100000]",
            self.max_population,
        )?;
        check(
            (1..=1000).contains(&self.memory),
            "memory",
            "a whole number in [1, 1000]",
            self.memory,
        )?;
        check(
            self.archive_rate.is_finite() && (0.0..=100.0).contains(&self.archive_rate),
            "archive_rate",
            "a number in [0, 100]",
            self.archive_rate,
        )?;
        check(
            self.p_best > 0.0 && self.p_best <= 1.0,
            "p_best",
            "a number in (0, 1]",
            self.p_best,
        )
    }
}

impl Default for LshadeParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for LshadeParams {
    fn population(&self) -> usize {
        self.max_population
    }

    fn set_population(&mut self, n: usize) {
        self.max_population = n.max(self.min_population);
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Lshade::new(*self))
    }
}

/// The memory value that marks "CR = 0 from now on" (the paper's terminal value).
const TERMINAL: f64 = -1.0;

/// L-SHADE.
#[derive(Debug, Clone)]
pub struct Lshade {
    params: LshadeParams,
    dim: usize,
    n_init: usize,
    /// Population (rows of `dim`) and its evaluations; `n` rows in use.
    x: Vec<f64>,
    eval: Vec<Evaluation>,
    n: usize,
    /// Trial vectors of the generation and their parameters.
    trial: Vec<f64>,
    cr: Vec<f64>,
    f: Vec<f64>,
    archive: Vec<f64>,
    archive_len: usize,
    m_cr: Vec<f64>,
    m_f: Vec<f64>,
    slot: usize,
    best: BestSoFar,
}

impl Lshade {
    /// L-SHADE with `params`; the population is sized and drawn at initialisation.
    #[must_use]
    pub fn new(params: LshadeParams) -> Self {
        Self {
            params,
            dim: 0,
            n_init: 0,
            x: Vec::new(),
            eval: Vec::new(),
            n: 0,
            trial: Vec::new(),
            cr: Vec::new(),
            f: Vec::new(),
            archive: Vec::new(),
            archive_len: 0,
            m_cr: Vec::new(),
            m_f: Vec::new(),
            slot: 0,
            best: BestSoFar::new(0),
        }
    }

    /// The initial population for dimension `dim`.
    #[must_use]
    pub fn initial_population(params: &LshadeParams, dim: usize) -> usize {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let by_dim = (params.population_per_dimension * dim as f64).round() as usize;
        by_dim
            .min(params.max_population)
            .max(params.min_population.max(4))
    }

    /// Current population size.
    #[must_use]
    pub fn population(&self) -> usize {
        self.n
    }

    fn archive_capacity(&self) -> usize {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let cap = (self.params.archive_rate * self.n as f64).round() as usize;
        cap
    }

    /// Indices 0..n sorted best first (by cost; ties by index, so the order is defined).
    fn ranking(&self) -> Vec<usize> {
        let mut idx: Vec<usize> = (0..self.n).collect();
        idx.sort_by(|&a, &b| {
            self.eval[a]
                .cost
                .total_cmp(&self.eval[b].cost)
                .then(a.cmp(&b))
        });
        idx
    }

    /// Draws CR_i and F_i from memory slot `r`.
    fn draw_parameters(&self, rng: &mut Rng, r: usize) -> (f64, f64) {
        let cr = if self.m_cr[r] == TERMINAL {
            0.0
        } else {
            Normal::new(self.m_cr[r], 0.1)
                .map_or(self.m_cr[r], |d| d.sample(rng))
                .clamp(0.0, 1.0)
        };
        let cauchy = Cauchy::new(self.m_f[r], 0.1).ok();
        let mut f = 0.0;
        for _ in 0..1000 {
            f = cauchy.map_or(self.m_f[r], |d| d.sample(rng));
            if f > 0.0 {
                break;
            }
        }
        (cr, f.clamp(f64::MIN_POSITIVE, 1.0))
    }

    /// Adds `x` to the archive, replacing a random member when full.
    fn archive_push(&mut self, rng: &mut Rng, i: usize) {
        let cap = self.archive_capacity();
        if cap == 0 {
            return;
        }
        let dim = self.dim;
        let slot = if self.archive_len < cap {
            self.archive_len += 1;
            if self.archive.len() < self.archive_len * dim {
                self.archive.resize(self.archive_len * dim, 0.0);
            }
            self.archive_len - 1
        } else {
            rng.random_range(0..self.archive_len)
        };
        let (src, dst) = (i * dim..(i + 1) * dim, slot * dim..(slot + 1) * dim);
        self.archive[dst].copy_from_slice(&self.x[src]);
    }

    /// Shrinks the population to the size the budget fraction `frac` calls for, dropping
    /// the worst, and the archive to its new capacity, dropping random members.
    fn reduce(&mut self, rng: &mut Rng, frac: f64) {
        let n_min = self.params.min_population.max(4) as f64;
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let target = (self.n_init as f64 + (n_min - self.n_init as f64) * frac)
            .round()
            .max(n_min) as usize;
        if target < self.n {
            let keep = self.ranking();
            let dim = self.dim;
            let mut x = vec![0.0; target * dim];
            let mut eval = Vec::with_capacity(target);
            for (k, &i) in keep.iter().take(target).enumerate() {
                x[k * dim..(k + 1) * dim].copy_from_slice(row(&self.x, i, dim));
                eval.push(self.eval[i]);
            }
            self.x = x;
            self.eval = eval;
            self.n = target;
        }
        let cap = self.archive_capacity();
        while self.archive_len > cap {
            let k = rng.random_range(0..self.archive_len);
            let last = self.archive_len - 1;
            let dim = self.dim;
            if k != last {
                let (a, b) = self.archive.split_at_mut(last * dim);
                a[k * dim..(k + 1) * dim].copy_from_slice(&b[..dim]);
            }
            self.archive_len -= 1;
        }
    }
}

/// The trial coordinate `v` brought into `b`: the midpoint towards the parent `parent` for
/// a plain bound (L-SHADE's rule), a wrap for a periodic one.
fn repair(b: &Bound, v: f64, parent: f64) -> f64 {
    if v.is_nan() {
        return parent;
    }
    if b.periodic {
        return b.project(v);
    }
    if v < b.lo {
        0.5 * (b.lo + parent)
    } else if v > b.hi {
        0.5 * (b.hi + parent)
    } else {
        v
    }
}

/// Weighted Lehmer mean sum w s^2 / sum w s (the weights need not be normalised).
fn lehmer(values: &[f64], weights: &[f64]) -> Option<f64> {
    let num: f64 = values.iter().zip(weights).map(|(s, w)| w * s * s).sum();
    let den: f64 = values.iter().zip(weights).map(|(s, w)| w * s).sum();
    (den > 0.0 && num.is_finite()).then(|| num / den)
}

impl Optimizer for Lshade {
    fn evaluations_per_iteration(&self) -> u64 {
        self.n.max(1) as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.dim = ev.dimension();
        self.n_init = Self::initial_population(&self.params, self.dim);
        self.n = self.n_init;
        let dim = self.dim;
        self.x = vec![0.0; self.n * dim];
        self.eval = vec![Evaluation::worst(); self.n];
        self.trial = vec![0.0; self.n * dim];
        self.cr = vec![0.0; self.n];
        self.f = vec![0.0; self.n];
        self.archive.clear();
        self.archive_len = 0;
        self.m_cr = vec![0.5; self.params.memory.max(1)];
        self.m_f = vec![0.5; self.params.memory.max(1)];
        self.slot = 0;
        self.best = BestSoFar::new(dim);
        for i in 0..self.n {
            ev.sample_initial(rng, row_mut(&mut self.x, i, dim));
        }
        let mut evals = Vec::with_capacity(self.n);
        ev.evaluate_rows(&self.x, self.n, &mut evals);
        for (i, e) in evals.into_iter().enumerate() {
            self.eval[i] = e;
            self.best.offer(row(&self.x, i, dim), e);
        }
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let (n, dim) = (self.n, self.dim);
        if n < 4 || dim == 0 {
            return;
        }
        let bounds = ev.bounds();
        let ranked = self.ranking();
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let top = ((self.params.p_best * n as f64).round() as usize).clamp(2, n);
        let memory = self.m_cr.len();
        for i in 0..n {
            let slot = rng.random_range(0..memory);
            let (cr, f) = self.draw_parameters(rng, slot);
            self.cr[i] = cr;
            self.f[i] = f;
            let pbest = ranked[rng.random_range(0..top)];
            // r1 from the population, r2 from population and archive, distinct from i
            // and from each other.
            let r1 = loop {
                let r = rng.random_range(0..n);
                if r != i {
                    break r;
                }
            };
            let r2 = loop {
                let r = rng.random_range(0..n + self.archive_len);
                if r != i && r != r1 {
                    break r;
                }
            };
            let j_rand = rng.random_range(0..dim);
            for j in 0..dim {
                let xi = self.x[i * dim + j];
                let x2 = if r2 < n {
                    self.x[r2 * dim + j]
                } else {
                    self.archive[(r2 - n) * dim + j]
                };
                let u = if j == j_rand || rng.random::<f64>() <= cr {
                    let v =
                        xi + f * (self.x[pbest * dim + j] - xi) + f * (self.x[r1 * dim + j] - x2);
                    repair(&bounds[j], v, xi)
                } else {
                    xi
                };
                self.trial[i * dim + j] = u;
            }
        }
        // Evaluate every trial, then select (the population of this generation is fixed
        // while trials are made, as in the paper). A trial only matters if it costs no more
        // than its parent (one that costs more cannot be the best so far either), so its
        // evaluation may stop once it is known to cost more.
        let mut trial_eval = Vec::with_capacity(n);
        let parents: Vec<f64> = self.eval[..n].iter().map(|e| e.cost).collect();
        ev.evaluate_rows_cost_bounded_each(&self.trial, n, &parents, &mut trial_eval);
        for (i, e) in trial_eval.iter().enumerate() {
            self.best.offer(row(&self.trial, i, dim), *e);
        }
        let (mut s_cr, mut s_f, mut w) = (Vec::new(), Vec::new(), Vec::new());
        for (i, e) in trial_eval.iter().enumerate() {
            let parent = self.eval[i];
            if e.cost <= parent.cost {
                if e.better_than(&parent) {
                    self.archive_push(rng, i);
                    let gain = parent.cost - e.cost;
                    s_cr.push(self.cr[i]);
                    s_f.push(self.f[i]);
                    w.push(if gain.is_finite() { gain } else { 1e300 });
                }
                let (src, dst) = (i * dim..(i + 1) * dim, i * dim..(i + 1) * dim);
                self.x[dst].copy_from_slice(&self.trial[src]);
                self.eval[i] = *e;
            }
        }
        if !s_cr.is_empty() {
            let k = self.slot;
            self.m_cr[k] = if self.m_cr[k] == TERMINAL || s_cr.iter().all(|&c| c == 0.0) {
                TERMINAL
            } else {
                lehmer(&s_cr, &w).unwrap_or(self.m_cr[k])
            };
            self.m_f[k] = lehmer(&s_f, &w).unwrap_or(self.m_f[k]);
            self.slot = (k + 1) % memory;
        }
        self.reduce(rng, ev.progress().fraction());
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (&self.best.x, self.best.eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repair_goes_halfway_back_to_the_parent() {
        let b = Bound::new(0.0, 10.0);
        assert_eq!(repair(&b, -4.0, 2.0), 1.0);
        assert_eq!(repair(&b, 14.0, 8.0), 9.0);
        assert_eq!(repair(&b, 5.0, 8.0), 5.0);
        assert_eq!(repair(&b, f64::NAN, 8.0), 8.0);
    }

    #[test]
    fn lehmer_mean_leans_to_the_large_values() {
        let m = lehmer(&[0.2, 0.8], &[1.0, 1.0]).unwrap();
        assert!((m - 0.68).abs() < 1e-12, "{m}");
        assert_eq!(lehmer(&[0.0], &[1.0]), None);
    }

    #[test]
    fn the_initial_population_follows_the_dimension_within_its_cap() {
        let p = LshadeParams::DEFAULT;
        assert_eq!(Lshade::initial_population(&p, 3), 54);
        assert_eq!(Lshade::initial_population(&p, 150), 100);
        assert_eq!(Lshade::initial_population(&p, 0), 4);
    }

    #[test]
    fn the_population_shrinks_linearly_to_its_minimum() {
        use crate::optim::solve;
        use crate::optim::test_problems::Sphere;
        use crate::optim::Budget;
        let p = Sphere(vec![Bound::new(-5.0, 5.0); 3]);
        let mut opt = Lshade::new(LshadeParams::DEFAULT);
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(2000),
            &mut crate::rng::rng_from_seed(1),
            &mut |_| {},
        );
        assert_eq!(out.evaluations, 2000);
        assert_eq!(opt.population(), 4, "N_min at the end of the budget");
        assert!(out.best.cost < 1e-6, "{}", out.best.cost);
    }
}
