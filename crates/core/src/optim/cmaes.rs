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
//!
//! In high dimension the full covariance matrix is the cost: n^2 per sample and an n^3
//! eigendecomposition every few generations (a 100-UAV fleet has 3,000 coordinates; one
//! run of 3,870 evaluations took 250 s and 445 MB, over 250 times PSO's). pycma's own scope is
//! "dimension between, say, 5 and (a few) 100". Above [`AUTO_DIAGONAL_ABOVE`] coordinates
//! (`covariance = "auto"`, the default) the run is therefore sep-CMA-ES (Ros & Hansen 2008,
//! PPSN X, LNCS 5199:296-305, doi:10.1007/978-3-540-87700-4_30): C is kept diagonal, so
//! B = I and D = sqrt(diag C), every step is linear in n, and the covariance learning rates
//! c_1 and c_mu are multiplied by (n + 2) / 3, as that paper prescribes:
//!
//! ```text
//! C_jj = (1 - c_1 - c_mu + (1 - h_s) c_1 c_c (2 - c_c)) C_jj + c_1 p_c,j^2
//!        + c_mu sum_i w_i ((y_(i),j - m_j) / sigma)^2
//! ```

use nalgebra::{DMatrix, DVector, SymmetricEigen};
use rand_distr::{Distribution, StandardNormal};
use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
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
    /// Full or diagonal (sep-CMA-ES) covariance; `auto` (the default) is diagonal above
    /// [`AUTO_DIAGONAL_ABOVE`] coordinates.
    pub covariance: Covariance,
}

/// Which covariance matrix CMA-ES adapts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Covariance {
    /// Full up to [`AUTO_DIAGONAL_ABOVE`] coordinates, diagonal above.
    #[default]
    Auto,
    /// The full matrix (Hansen & Ostermeier 2001).
    Full,
    /// A diagonal matrix (sep-CMA-ES, Ros & Hansen 2008).
    Diagonal,
}

/// Above this many coordinates `covariance = "auto"` runs sep-CMA-ES (module docs).
pub const AUTO_DIAGONAL_ABOVE: usize = 1000;

impl Covariance {
    /// Whether a problem of `n` coordinates gets the diagonal matrix.
    #[must_use]
    pub fn is_diagonal(self, n: usize) -> bool {
        match self {
            Self::Auto => n > AUTO_DIAGONAL_ABOVE,
            Self::Full => false,
            Self::Diagonal => true,
        }
    }
}

impl CmaesParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        sigma: 0.3,
        population: 0,
        ipop: true,
        covariance: Covariance::Auto,
    };

    /// Checks `sigma` and `population`; the error names the first bad one.
    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            self.sigma.is_finite() && self.sigma > 0.0 && self.sigma <= 1.0,
            "sigma",
            "a number in (0, 1]",
            self.sigma,
        )?;
        check(
            self.population == 0 || super::config::POPULATION_RANGE.contains(&self.population),
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

impl super::config::OptimizerConfig for CmaesParams {
    fn population(&self) -> usize {
        self.population
    }

    fn set_population(&mut self, n: usize) {
        self.population = n.max(4);
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Cmaes::new(*self))
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
    shape: Shape,
    /// Square roots of C's eigenvalues (of its diagonal in sep-CMA-ES).
    d: DVector<f64>,
    /// Evaluations since B and D were refreshed.
    since_eigen: u64,
    generation: u64,
    /// Best cost of each recent generation (for the stagnation test).
    history: Vec<f64>,
}

/// The covariance matrix C and its eigenvectors B, or C's diagonal alone (B = I).
#[derive(Debug, Clone)]
enum Shape {
    Full { c: DMatrix<f64>, b: DMatrix<f64> },
    Diagonal { c: DVector<f64> },
}

impl State {
    /// Draws the generation's lambda points from N(mean, sigma^2 C) in the unit cube
    /// (projected into it), and the same points in the problem's box, row after row.
    fn sample_generation(&self, bounds: &[Bound], rng: &mut Rng) -> (Vec<DVector<f64>>, Vec<f64>) {
        let n = bounds.len();
        let mut ys: Vec<DVector<f64>> = Vec::with_capacity(self.lambda);
        // B D, the map from N(0, I) to a step (D alone when C is diagonal).
        let bd = match &self.shape {
            Shape::Full { b, .. } => Some(scale_columns(b, &self.d)),
            Shape::Diagonal { .. } => None,
        };
        let mut points = vec![0.0; self.lambda * n];
        for k in 0..self.lambda {
            let z = DVector::from_iterator(n, (0..n).map(|_| StandardNormal.sample(rng)));
            let mut y = match &bd {
                Some(bd) => &self.mean + (bd * z) * self.sigma,
                None => &self.mean + z.component_mul(&self.d) * self.sigma,
            };
            for (j, b) in bounds.iter().enumerate() {
                y[j] = project_unit(b, y[j]);
                points[k * n + j] = b.lo + y[j] * (b.hi - b.lo);
            }
            ys.push(y);
        }
        (ys, points)
    }

    fn new(n: usize, lambda: usize, mean: DVector<f64>, sigma: f64, diagonal: bool) -> Self {
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
        // sep-CMA-ES learns a diagonal (n + 2) / 3 times faster (Ros & Hansen 2008).
        let rate = if diagonal { (nf + 2.0) / 3.0 } else { 1.0 };
        let c_1 = (2.0 / ((nf + 1.3).powi(2) + mu_eff) * rate).min(1.0);
        let c_mu = (1.0 - c_1)
            .min(2.0 * (mu_eff - 2.0 + 1.0 / mu_eff) / ((nf + 2.0).powi(2) + mu_eff) * rate);
        let shape = if diagonal {
            Shape::Diagonal {
                c: DVector::from_element(n, 1.0),
            }
        } else {
            Shape::Full {
                c: DMatrix::identity(n, n),
                b: DMatrix::identity(n, n),
            }
        };
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
            shape,
            d: DVector::from_element(n, 1.0),
            since_eigen: 0,
            generation: 0,
            history: Vec::new(),
        }
    }

    /// Refreshes B and D from C (symmetrised); false when C is no longer usable.
    fn refresh_eigen(&mut self) -> bool {
        match &mut self.shape {
            Shape::Full { c, b } => {
                let sym = (&*c + c.transpose()) * 0.5;
                let eig = SymmetricEigen::new(sym);
                if eig.eigenvalues.iter().any(|v| !v.is_finite()) {
                    return false;
                }
                self.d = eig.eigenvalues.map(|v| v.max(1e-300).sqrt());
                *b = eig.eigenvectors;
            }
            Shape::Diagonal { c } => {
                if c.iter().any(|v| !v.is_finite()) {
                    return false;
                }
                self.d = c.map(|v| v.max(1e-300).sqrt());
            }
        }
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
    /// CMA-ES with `params`; the strategy is sized to the problem at initialisation.
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
        let diagonal = self.params.covariance.is_diagonal(self.n);
        self.state = Some(State::new(
            self.n,
            lambda,
            mean,
            self.params.sigma,
            diagonal,
        ));
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
        let (mut ys, points) = s.sample_generation(ev.bounds(), rng);
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
        let whitened = match &s.shape {
            Shape::Full { b, .. } => scale_columns(b, &inv_d) * (b.transpose() * &step),
            Shape::Diagonal { .. } => step.component_mul(&inv_d),
        };
        s.p_s = &s.p_s * (1.0 - s.c_s) + whitened * (s.c_s * (2.0 - s.c_s) * s.mu_eff).sqrt();
        let gen = s.generation as f64 + 1.0;
        let ps_norm = s.p_s.norm();
        #[allow(clippy::cast_precision_loss)]
        let h_s = ps_norm / (1.0 - (1.0 - s.c_s).powf(2.0 * gen)).sqrt()
            < (1.4 + 2.0 / (n as f64 + 1.0)) * s.chi_n;
        let h = if h_s { 1.0 } else { 0.0 };
        s.p_c = &s.p_c * (1.0 - s.c_c) + &step * (h * (s.c_c * (2.0 - s.c_c) * s.mu_eff).sqrt());
        let decay = 1.0 - s.c_1 - s.c_mu + (1.0 - h) * s.c_1 * s.c_c * (2.0 - s.c_c);
        let steps = s
            .weights
            .iter()
            .zip(&order)
            .map(|(w, &k)| (*w, (&ys[k] - &old) / s.sigma));
        match &mut s.shape {
            Shape::Full { c, .. } => {
                let mut rank_mu = DMatrix::zeros(n, n);
                for (w, d) in steps {
                    for j in 0..n {
                        for i in 0..n {
                            rank_mu[(i, j)] += d[i] * d[j] * w;
                        }
                    }
                }
                let rank_one = &s.p_c * s.p_c.transpose();
                *c = &*c * decay + rank_one * s.c_1 + rank_mu * s.c_mu;
            }
            Shape::Diagonal { c } => {
                let mut rank_mu: DVector<f64> = DVector::zeros(n);
                for (w, d) in steps {
                    for j in 0..n {
                        rank_mu[j] += d[j] * d[j] * w;
                    }
                }
                for j in 0..n {
                    c[j] = c[j] * decay + s.p_c[j] * s.p_c[j] * s.c_1 + rank_mu[j] * s.c_mu;
                }
            }
        }
        s.sigma *= ((s.c_s / s.d_s) * (ps_norm / s.chi_n - 1.0)).min(1.0).exp();
        s.mean = mean;
        s.generation += 1;
        s.since_eigen += s.lambda as u64;
        #[allow(clippy::cast_precision_loss)]
        let lazy = s.lambda as f64 / (s.c_1 + s.c_mu) / n as f64 / 10.0;
        let mut usable = true;
        // A diagonal's square roots are n operations: taken every generation.
        if s.since_eigen as f64 >= lazy || matches!(s.shape, Shape::Diagonal { .. }) {
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
        let s = State::new(10, 10, DVector::zeros(10), 0.3, false);
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
    fn auto_covariance_is_diagonal_only_above_the_threshold() {
        assert!(!Covariance::Auto.is_diagonal(AUTO_DIAGONAL_ABOVE));
        assert!(Covariance::Auto.is_diagonal(AUTO_DIAGONAL_ABOVE + 1));
        assert!(!Covariance::Full.is_diagonal(5000));
        assert!(Covariance::Diagonal.is_diagonal(5));
        let full = State::new(30, 14, DVector::zeros(30), 0.3, false);
        let sep = State::new(30, 14, DVector::zeros(30), 0.3, true);
        // Ros & Hansen's learning rates: (n + 2) / 3 times the full ones.
        assert!((sep.c_1 / full.c_1 - 32.0 / 3.0).abs() < 1e-9);
        assert!((sep.c_mu / full.c_mu - 32.0 / 3.0).abs() < 1e-9);
    }

    /// sum 10^(6 j / (n - 1)) x_j^2 on [-1, 1]^n: separable, condition number 1e6.
    struct Ellipsoid(Vec<Bound>);

    impl crate::problem::Problem for Ellipsoid {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            let n = x.len() as f64;
            let f = x
                .iter()
                .enumerate()
                .map(|(j, v)| 10f64.powf(6.0 * j as f64 / (n - 1.0)) * v * v)
                .sum();
            Evaluation::new(f, 0.0)
        }
    }

    fn run(
        problem: &dyn crate::problem::Problem,
        covariance: Covariance,
        evals: u64,
    ) -> (f64, Cmaes) {
        use crate::optim::solve;
        use crate::optim::Budget;
        let mut opt = Cmaes::new(CmaesParams {
            covariance,
            ..CmaesParams::DEFAULT
        });
        let out = solve(
            problem,
            &mut opt,
            Budget::evaluations(evals),
            &mut crate::rng::rng_from_seed(3),
            &mut |_| {},
        );
        assert_eq!(out.evaluations, evals);
        (out.best.cost, opt)
    }

    #[test]
    fn sep_cma_learns_the_scales_of_a_separable_ellipsoid() {
        let p = Ellipsoid(vec![Bound::new(-1.0, 1.0); 20]);
        let (cost, opt) = run(&p, Covariance::Diagonal, 12_000);
        assert!(cost < 1e-10, "{cost}");
        // The axes it learned span most of the 1e3 ratio of the ellipsoid's.
        let s = opt.state.as_ref().expect("running");
        assert!(matches!(s.shape, Shape::Diagonal { .. }));
        assert!(s.d.max() / s.d.min() > 100.0, "{}", s.d.max() / s.d.min());
    }

    #[test]
    fn a_high_dimension_run_is_diagonal_under_auto_and_improves() {
        use crate::optim::test_problems::Sphere;
        let n = AUTO_DIAGONAL_ABOVE + 200;
        let p = Sphere(vec![Bound::new(-1.0, 1.0); n]);
        let (cost, opt) = run(&p, Covariance::Auto, 3000);
        assert!(matches!(
            opt.state.as_ref().expect("running").shape,
            Shape::Diagonal { .. }
        ));
        // A random point of the cube costs n / 3 on average.
        assert!(cost < 0.75 * n as f64 / 3.0, "{cost}");
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
