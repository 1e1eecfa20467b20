//! CMA-ES with IPOP restarts: the covariance matrix adaptation evolution strategy (Hansen &
//! Ostermeier 2001, Evol. Comput. 9(2):159-195, doi:10.1162/106365601750190398; the update
//! as in Hansen's tutorial, arXiv:1604.00772), restarted with a doubled population when it
//! stagnates (Auger & Hansen 2005, IEEE CEC, doi:10.1109/CEC.2005.1554902). A modern
//! baseline beside L-SHADE.
//!
//! The search runs in the unit cube: coordinate j of a point y maps to
//! lo_j + y_j (hi_j - lo_j), so bounds of different widths (metres, radians) share one step
//! size. One generation:
//!
//! ```text
//! y_k = m + sigma B D z_k, z_k ~ N(0, I), k = 1..lambda; each y_k is projected into the
//! cube (clamped; periodic coordinates wrapped) and the projection is what is evaluated and
//! what the update uses
//! m' = sum_i w_i y_(i)                                 (the mu best, log weights)
//! p_s = (1 - c_s) p_s + sqrt(c_s (2 - c_s) mu_eff) C^(-1/2) (m' - m) / sigma
//! p_c = (1 - c_c) p_c + h_s sqrt(c_c (2 - c_c) mu_eff) (m' - m) / sigma
//! C = (1 - c_1 - c_mu) C + c_1 (p_c p_c' + (1 - h_s) c_c (2 - c_c) C)
//!     + c_mu sum_i w_i (y_(i) - m)(y_(i) - m)' / sigma^2
//! sigma = sigma exp(min(1, c_s / d_s (|p_s| / E|N(0, I)| - 1)))   (capped as pycma does)
//! ```
//!
//! with the tutorial's default constants, lambda = 4 + floor(3 ln n), mu = lambda / 2,
//! sigma_0 = 0.3 and the first mean drawn from the method's initialisation. B and D are
//! refreshed when lambda / (c_1 + c_mu) / n / 10 evaluations have passed (the tutorial's
//! lazy update). A restart (new mean, lambda doubled) comes when sigma times the largest
//! axis falls below 1e-12, the condition number of C passes 1e14, or the best value of
//! the last 10 + 30 n / lambda generations varies by less than 1e-12 relative. Candidates are
//! compared by cost (penalty included), as the paper's methods are.

use nalgebra::{DMatrix, DVector, SymmetricEigen};
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

use super::params::{check, ParamsError};
use super::swarm::BestSoFar;
use super::{Evaluator, Optimizer};
use crate::problem::{Bound, Evaluation};
use crate::rng::Rng;

/// Parameters of CMA-ES.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CmaesParams {
    /// Initial step size in the unit cube (0.3).
    pub sigma: f64,
    /// Offspring per generation of the first run; 0 means 4 + floor(3 ln n) (0).
    pub population: usize,
    /// Restart with a doubled population on stagnation (true).
    pub ipop: bool,
}

impl CmaesParams {
    pub const DEFAULT: Self = Self {
        sigma: 0.3,
        population: 0,
        ipop: true,
    };

    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            self.sigma.is_finite() && self.sigma > 0.0 && self.sigma <= 1.0,
            "sigma",
            "a number in (0, 1]",
            self.sigma,
        )?;
        check(
            self.population == 0 || super::params::POPULATION_RANGE.contains(&self.population),
            "population",
            "0 (automatic) or a whole number in [4, 100000]",
            self.population,
        )
    }
}

impl Default for CmaesParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// The strategy's state for one (re)start.
#[derive(Debug, Clone)]
struct State {
    lambda: usize,
    weights: Vec<f64>,
    mu_eff: f64,
    c_s: f64,
    d_s: f64,
    c_c: f64,
    c_1: f64,
    c_mu: f64,
    chi_n: f64,
    mean: DVector<f64>,
    sigma: f64,
    p_s: DVector<f64>,
    p_c: DVector<f64>,
    c: DMatrix<f64>,
    b: DMatrix<f64>,
    d: DVector<f64>,
    /// Evaluations since B and D were refreshed.
    since_eigen: u64,
    generation: u64,
    /// Best cost of each recent generation (for the stagnation test).
    history: Vec<f64>,
}

impl State {
    fn new(n: usize, lambda: usize, mean: DVector<f64>, sigma: f64) -> Self {
        let nf = n as f64;
        let mu = lambda / 2;
        let raw: Vec<f64> = (0..mu)
            .map(|i| ((lambda as f64 + 1.0) / 2.0).ln() - ((i + 1) as f64).ln())
            .collect();
        let sum: f64 = raw.iter().sum();
        let weights: Vec<f64> = raw.iter().map(|w| w / sum).collect();
        let mu_eff = 1.0 / weights.iter().map(|w| w * w).sum::<f64>();
        let c_s = (mu_eff + 2.0) / (nf + mu_eff + 5.0);
        let d_s = 1.0 + 2.0 * (((mu_eff - 1.0) / (nf + 1.0)).sqrt() - 1.0).max(0.0) + c_s;
        let c_c = (4.0 + mu_eff / nf) / (nf + 4.0 + 2.0 * mu_eff / nf);
        let c_1 = 2.0 / ((nf + 1.3).powi(2) + mu_eff);
        let c_mu =
            (1.0 - c_1).min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((nf + 2.0).powi(2) + mu_eff));
        let chi_n = nf.sqrt() * (1.0 - 1.0 / (4.0 * nf) + 1.0 / (21.0 * nf * nf));
        Self {
            lambda,
            weights,
            mu_eff,
            c_s,
            d_s,
            c_c,
            c_1,
            c_mu,
            chi_n,
            mean,
            sigma,
            p_s: DVector::zeros(n),
            p_c: DVector::zeros(n),
            c: DMatrix::identity(n, n),
            b: DMatrix::identity(n, n),
            d: DVector::from_element(n, 1.0),
            since_eigen: 0,
            generation: 0,
            history: Vec::new(),
        }
    }

    /// Refreshes B and D from C (symmetrised); false when C is no longer usable.
    fn refresh_eigen(&mut self) -> bool {
        let sym = (&self.c + self.c.transpose()) * 0.5;
        let eig = SymmetricEigen::new(sym);
        if eig.eigenvalues.iter().any(|v| !v.is_finite()) {
            return false;
        }
        self.d = eig.eigenvalues.map(|v| v.max(1e-300).sqrt());
        self.b = eig.eigenvectors;
        self.since_eigen = 0;
        true
    }

    /// Whether this run should end (IPOP's stop conditions).
    fn stagnated(&self, n: usize) -> bool {
        let max_d = self.d.max();
        let min_d = self.d.min();
        let axis = self.sigma * max_d;
        if axis.is_nan() || axis < 1e-12 || max_d * max_d > 1e14 * min_d * min_d {
            return true;
        }
        let window = 10 + (30 * n).div_ceil(self.lambda);
        if self.history.len() >= window {
            let recent = &self.history[self.history.len() - window..];
            let hi = recent.iter().copied().fold(f64::MIN, f64::max);
            let lo = recent.iter().copied().fold(f64::MAX, f64::min);
            if hi.is_finite() && hi - lo <= 1e-12 * hi.abs().max(1e-300) {
                return true;
            }
        }
        false
    }
}

/// CMA-ES with IPOP restarts.
#[derive(Debug, Clone)]
pub struct Cmaes {
    params: CmaesParams,
    n: usize,
    state: Option<State>,
    restarts: u64,
    /// Scratch: a candidate in the problem's coordinates.
    point: Vec<f64>,
    best: BestSoFar,
}

impl Cmaes {
    #[must_use]
    pub fn new(params: CmaesParams) -> Self {
        Self {
            params,
            n: 0,
            state: None,
            restarts: 0,
            point: Vec::new(),
            best: BestSoFar::new(0),
        }
    }

    /// Restarts so far.
    #[must_use]
    pub fn restarts(&self) -> u64 {
        self.restarts
    }

    fn default_lambda(n: usize) -> usize {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let l = 4 + (3.0 * (n.max(1) as f64).ln()).floor() as usize;
        l
    }

    /// A new start with `lambda` offspring around a mean drawn from the initialisation.
    fn start(&mut self, ev: &Evaluator<'_>, rng: &mut Rng, lambda: usize) {
        let bounds = ev.bounds();
        let mut x = vec![0.0; self.n];
        ev.sample_initial(rng, &mut x);
        let mean =
            DVector::from_iterator(self.n, x.iter().zip(bounds).map(|(v, b)| to_unit(b, *v)));
        self.state = Some(State::new(self.n, lambda, mean, self.params.sigma));
    }
}

/// `m` with column j multiplied by `d[j]`: `m * diag(d)` in n^2 instead of a dense n^3
/// product (and the same numbers, since the product only adds exact zeros).
fn scale_columns(m: &DMatrix<f64>, d: &DVector<f64>) -> DMatrix<f64> {
    let mut out = m.clone();
    for (j, mut col) in out.column_iter_mut().enumerate() {
        col *= d[j];
    }
    out
}

/// `v` in the unit coordinate of `b`.
fn to_unit(b: &Bound, v: f64) -> f64 {
    let w = b.hi - b.lo;
    if w > 0.0 {
        ((v - b.lo) / w).clamp(0.0, 1.0)
    } else {
        0.0
    }
}

/// Unit coordinate `u` brought into [0, 1] (wrapped when `b` is periodic).
fn project_unit(b: &Bound, u: f64) -> f64 {
    if u.is_nan() {
        0.5
    } else if b.periodic {
        u.rem_euclid(1.0)
    } else {
        u.clamp(0.0, 1.0)
    }
}

impl Optimizer for Cmaes {
    fn evaluations_per_iteration(&self) -> u64 {
        self.state.as_ref().map_or_else(
            || {
                if self.params.population > 0 {
                    self.params.population as u64
                } else {
                    Self::default_lambda(self.n) as u64
                }
            },
            |s| s.lambda as u64,
        )
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.n = ev.dimension();
        self.restarts = 0;
        self.best = BestSoFar::new(self.n);
        self.point = vec![0.0; self.n];
        let lambda = if self.params.population > 0 {
            self.params.population
        } else {
            Self::default_lambda(self.n)
        };
        self.start(ev, rng, lambda);
        // The first mean is evaluated, so a best exists from the start.
        let bounds = ev.bounds();
        if let Some(s) = &self.state {
            for (j, b) in bounds.iter().enumerate() {
                self.point[j] = b.lo + s.mean[j] * (b.hi - b.lo);
            }
            if let Some(e) = ev.evaluate(&self.point) {
                self.best.offer(&self.point, e);
            }
        }
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let n = self.n;
        let Some(mut s) = self.state.take() else {
            return;
        };
        if n == 0 {
            return;
        }
        let bounds = ev.bounds();
        let mut ys: Vec<DVector<f64>> = Vec::with_capacity(s.lambda);
        let bd = scale_columns(&s.b, &s.d);
        let mut points = vec![0.0; s.lambda * n];
        for k in 0..s.lambda {
            let z = DVector::from_iterator(n, (0..n).map(|_| StandardNormal.sample(rng)));
            let mut y = &s.mean + (&bd * z) * s.sigma;
            for (j, b) in bounds.iter().enumerate() {
                y[j] = project_unit(b, y[j]);
                points[k * n + j] = b.lo + y[j] * (b.hi - b.lo);
            }
            ys.push(y);
        }
        // The generation is sampled from a fixed state, so it is evaluated in parallel.
        let mut evals = Vec::with_capacity(s.lambda);
        ev.evaluate_rows(&points, s.lambda, &mut evals);
        ys.truncate(evals.len());
        let mut costs: Vec<f64> = Vec::with_capacity(s.lambda);
        for (k, e) in evals.iter().enumerate() {
            self.best.offer(&points[k * n..(k + 1) * n], *e);
            costs.push(e.cost);
        }
        let mu = s.weights.len();
        if ys.len() < s.lambda || mu == 0 {
            self.state = Some(s);
            return; // the budget ended inside the generation
        }
        let mut order: Vec<usize> = (0..ys.len()).collect();
        order.sort_by(|&a, &b| costs[a].total_cmp(&costs[b]).then(a.cmp(&b)));
        s.history.push(costs[order[0]]);

        let old = s.mean.clone();
        let mut mean = DVector::zeros(n);
        for (w, &k) in s.weights.iter().zip(&order) {
            mean += &ys[k] * *w;
        }
        let step = (&mean - &old) / s.sigma;
        // C^(-1/2) step = B D^-1 B' step.
        let inv_d = s.d.map(|v| 1.0 / v);
        let whitened = scale_columns(&s.b, &inv_d) * (s.b.transpose() * &step);
        s.p_s = &s.p_s * (1.0 - s.c_s) + whitened * (s.c_s * (2.0 - s.c_s) * s.mu_eff).sqrt();
        let gen = s.generation as f64 + 1.0;
        let ps_norm = s.p_s.norm();
        #[allow(clippy::cast_precision_loss)]
        let h_s = ps_norm / (1.0 - (1.0 - s.c_s).powf(2.0 * gen)).sqrt()
            < (1.4 + 2.0 / (n as f64 + 1.0)) * s.chi_n;
        let h = if h_s { 1.0 } else { 0.0 };
        s.p_c = &s.p_c * (1.0 - s.c_c) + &step * (h * (s.c_c * (2.0 - s.c_c) * s.mu_eff).sqrt());
        let mut rank_mu = DMatrix::zeros(n, n);
        for (w, &k) in s.weights.iter().zip(&order) {
            let d = (&ys[k] - &old) / s.sigma;
            for j in 0..n {
                for i in 0..n {
                    rank_mu[(i, j)] += d[i] * d[j] * *w;
                }
            }
        }
        let rank_one = &s.p_c * s.p_c.transpose();
        s.c = &s.c * (1.0 - s.c_1 - s.c_mu + (1.0 - h) * s.c_1 * s.c_c * (2.0 - s.c_c))
            + rank_one * s.c_1
            + rank_mu * s.c_mu;
        s.sigma *= ((s.c_s / s.d_s) * (ps_norm / s.chi_n - 1.0)).min(1.0).exp();
        s.mean = mean;
        s.generation += 1;
        s.since_eigen += s.lambda as u64;
        #[allow(clippy::cast_precision_loss)]
        let lazy = s.lambda as f64 / (s.c_1 + s.c_mu) / n as f64 / 10.0;
        let mut usable = true;
        if s.since_eigen as f64 >= lazy {
            usable = s.refresh_eigen();
        }
        if !usable || s.stagnated(n) {
            if self.params.ipop {
                self.restarts += 1;
                let lambda = s.lambda.saturating_mul(2).min(100_000);
                self.start(ev, rng, lambda);
            } else {
                // Without IPOP: start again at the same size.
                self.restarts += 1;
                self.start(ev, rng, s.lambda);
            }
            return;
        }
        self.state = Some(s);
    }

    fn best(&self) -> (&[f64], Evaluation) {
        (&self.best.x, self.best.eval)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_population_follows_the_tutorial() {
        assert_eq!(Cmaes::default_lambda(10), 10);
        assert_eq!(Cmaes::default_lambda(30), 14);
        assert_eq!(Cmaes::default_lambda(150), 19);
    }

    #[test]
    fn weights_sum_to_one_and_fall() {
        let s = State::new(10, 10, DVector::zeros(10), 0.3);
        let sum: f64 = s.weights.iter().sum();
        assert!((sum - 1.0).abs() < 1e-12);
        assert!(s.weights.windows(2).all(|w| w[0] > w[1]));
        assert!(s.c_1 + s.c_mu <= 1.0 && s.c_s < 1.0 && s.c_c < 1.0);
    }

    #[test]
    fn unit_coordinates_project_into_the_cube() {
        let b = Bound::new(-2.0, 2.0);
        assert_eq!(to_unit(&b, 0.0), 0.5);
        assert_eq!(project_unit(&b, 1.7), 1.0);
        let p = Bound {
            periodic: true,
            ..Bound::new(0.0, 1.0)
        };
        assert!((project_unit(&p, 1.25) - 0.25).abs() < 1e-15);
        assert_eq!(project_unit(&b, f64::NAN), 0.5);
    }

    #[test]
    fn a_flat_function_triggers_ipop_restarts_with_doubled_populations() {
        use crate::optim::solve;
        use crate::optim::test_problems::Flat;
        use crate::optim::Budget;
        let p = Flat(vec![Bound::new(0.0, 1.0); 5]);
        let mut opt = Cmaes::new(CmaesParams::DEFAULT);
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(3000),
            &mut crate::rng::rng_from_seed(1),
            &mut |_| {},
        );
        assert_eq!(out.evaluations, 3000);
        assert!(opt.restarts() >= 2, "{}", opt.restarts());
        // lambda 8 at n = 5, doubled per restart.
        assert!(opt.evaluations_per_iteration() >= 16);
    }
}
