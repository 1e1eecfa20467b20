//! Particle swarm optimization: the velocity form of Kennedy & Eberhart (1995, Proc. ICNN,
//! doi:10.1109/ICNN.1995.488968) with the inertia weight of Shi & Eberhart (1998, Proc. IEEE
//! ICEC, doi:10.1109/ICEC.1998.699146), in the variant of SPSO's public code (Phung & Ha
//! 2021, Appl. Soft Comput. 107:107376, doi:10.1016/j.asoc.2021.107376).
//!
//! For particle i and every dimension j, with fresh r1, r2 ~ U(0, 1) per element:
//!
//! ```text
//! v_ij <- w v_ij + c1 r1 (pbest_ij - x_ij) + c2 r2 (gbest_j - x_ij)
//! v_ij <- clamp(v_ij, -vmax_j, vmax_j),     vmax_j = velocity_clamp * (hi_j - lo_j)
//! x_ij <- x_ij + v_ij
//! if x_ij left [lo_j, hi_j]: v_ij <- -v_ij (mirror), x_ij <- clamp(x_ij)
//! w  = w0 * inertia_damping^(K p)           (p: budget fraction spent, K = schedule_iterations)
//! ```
//!
//! SPSO damps w by 0.98 after every iteration of its 200. Here that schedule is defined over
//! the budget ([`super::Progress`]): w falls from w0 to w0 * 0.98^200 over whatever budget
//! the run has, so a run given five times the budget keeps searching for five times longer
//! instead of freezing at iteration 200. At 200 iterations (K = 200) the exponent is the
//! integer number of steps done and w is the same product of factors as SPSO's, bit for bit;
//! between integers (other budgets) the fractional part is applied with `powf`.
//!
//! Periodic bounds wrap instead of clamping and mirroring. Velocities start at zero (as in
//! SPSO's code). pbest moves only on a strict improvement; with `asynchronous` gbest follows
//! at once, so later particles of the same iteration already see it (SPSO); otherwise it is
//! updated after the whole swarm moved. When `initial_redraws > 0` and no particle of the
//! initial swarm has a finite cost, the whole swarm is drawn again (SPSO does this until one
//! does; here at most `initial_redraws` times), every draw counted in the budget.
//!
//! PSO (cartesian encoding), APSO (angle encoding) and SPSO (spherical encoding) are this
//! one optimizer with the same parameters; only the encoding differs. DLS-SMPSO
//! ([`super::dls_paper`], [`super::dls_exemplar`]) reuses the swarm machinery below.

use serde::{Deserialize, Serialize};

use super::config::{check, ParamsError};
use super::swarm::{move_coordinate, row, row_mut, BestSoFar, VelocityRule};
use super::{Evaluator, Optimizer, Progress};
use crate::problem::{Bound, Evaluation};
use crate::rng::Rng;

/// Parameters of PSO / APSO / SPSO (defaults: the paper's and SPSO's settings). In TOML the
/// paper's symbols are accepted too: `w`, `wdamp`, `c1`, `c2`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PsoParams {
    /// Swarm size nPop (50).
    pub population: usize,
    /// Initial inertia weight w (1.0).
    #[serde(alias = "w")]
    pub inertia: f64,
    /// Factor applied to w per nominal iteration, wdamp (0.98; 1 keeps w constant).
    #[serde(alias = "wdamp")]
    pub inertia_damping: f64,
    /// Nominal iterations K over which the damping schedule is defined (200, SPSO's run):
    /// w reaches w0 * wdamp^K at the end of the budget, whatever its size.
    pub schedule_iterations: u64,
    /// Cognitive coefficient c1 (1.5).
    #[serde(alias = "c1")]
    pub cognitive: f64,
    /// Social coefficient c2 (1.5).
    #[serde(alias = "c2")]
    pub social: f64,
    /// Velocity limit as a fraction of each bound's width, alpha (0.5); `inf` disables it.
    pub velocity_clamp: f64,
    /// Negate a velocity component whose position left its bound, before clamping (true).
    pub mirror_velocity: bool,
    /// Update gbest as soon as a particle improves, within the iteration (true).
    pub asynchronous: bool,
    /// Maximum number of re-draws of the initial swarm while no particle has a finite cost
    /// (1000; 0 disables). Each draw spends `population` evaluations.
    pub initial_redraws: usize,
}

impl PsoParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        population: 50,
        inertia: 1.0,
        inertia_damping: 0.98,
        schedule_iterations: 200,
        cognitive: 1.5,
        social: 1.5,
        velocity_clamp: 0.5,
        mirror_velocity: true,
        asynchronous: true,
        initial_redraws: 1000,
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
            self.inertia.is_finite(),
            "inertia",
            "a finite number",
            self.inertia,
        )?;
        check(
            self.inertia_damping > 0.0 && self.inertia_damping <= 1.0,
            "inertia_damping",
            "a number in (0, 1]",
            self.inertia_damping,
        )?;
        check(
            (1..=1_000_000).contains(&self.schedule_iterations),
            "schedule_iterations",
            "a whole number in [1, 1000000]",
            self.schedule_iterations,
        )?;
        check(
            self.cognitive.is_finite() && self.cognitive >= 0.0,
            "cognitive",
            "a finite number >= 0",
            self.cognitive,
        )?;
        check(
            self.social.is_finite() && self.social >= 0.0,
            "social",
            "a finite number >= 0",
            self.social,
        )?;
        check(
            self.velocity_clamp > 0.0,
            "velocity_clamp",
            "a positive number (inf disables the clamp)",
            self.velocity_clamp,
        )
    }
}

impl Default for PsoParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

impl super::config::OptimizerConfig for PsoParams {
    fn population(&self) -> usize {
        self.population
    }

    fn set_population(&mut self, n: usize) {
        self.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Pso::new(*self))
    }
}

/// The state of a particle swarm, shared by [`Pso`] and DLS-SMPSO.
#[derive(Debug, Clone)]
pub(crate) struct Swarm {
    pub params: PsoParams,
    pub n: usize,
    pub dim: usize,
    pub x: Vec<f64>,
    pub v: Vec<f64>,
    pub pbest: Vec<f64>,
    pub pbest_eval: Vec<Evaluation>,
    pub gbest: BestSoFar,
    vmax: Vec<f64>,
    /// Current inertia weight.
    pub w: f64,
    /// w0 times the damping factor once per whole nominal iteration elapsed so far.
    w_whole: f64,
    /// Whole nominal iterations already folded into `w_whole`.
    whole_applied: u64,
    /// Evaluations of the last parallel batch (a reused buffer).
    evals: Vec<Evaluation>,
}

impl Swarm {
    pub fn new(params: PsoParams, bounds: &[Bound]) -> Self {
        let n = params.population.max(1);
        let dim = bounds.len();
        Self {
            params,
            n,
            dim,
            x: vec![0.0; n * dim],
            v: vec![0.0; n * dim],
            pbest: vec![0.0; n * dim],
            pbest_eval: vec![Evaluation::worst(); n],
            gbest: BestSoFar::new(dim),
            evals: Vec::with_capacity(n),
            // abs and the NaN guard only matter for unvalidated parameters or a zero-width
            // bound with an infinite clamp; `f64::clamp` would panic on them.
            vmax: bounds
                .iter()
                .map(|b| {
                    let m = (params.velocity_clamp * b.width()).abs();
                    if m.is_nan() {
                        0.0
                    } else {
                        m
                    }
                })
                .collect(),
            w: params.inertia,
            w_whole: params.inertia,
            whole_applied: 0,
        }
    }

    /// Sets the inertia weight for the step about to run from the budget fraction spent.
    pub fn schedule(&mut self, progress: Progress) {
        let k = self.params.schedule_iterations;
        let elapsed = progress.elapsed_of(k).min(k as f64);
        // Truncation is the floor: elapsed is finite and in [0, K].
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let whole = elapsed.floor() as u64;
        while self.whole_applied < whole {
            self.w_whole *= self.params.inertia_damping;
            self.whole_applied += 1;
        }
        let part = elapsed - whole as f64;
        self.w = if part == 0.0 {
            self.w_whole
        } else {
            self.w_whole * self.params.inertia_damping.powf(part)
        };
    }

    /// Draws and evaluates the initial swarm, re-drawing it while no particle has a finite
    /// cost (up to `initial_redraws` times). Particles the budget could not evaluate keep
    /// their position with the worst evaluation.
    pub fn initialize(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let dim = self.dim;
        let mut evals = Vec::with_capacity(self.n);
        for _draw in 0..=self.params.initial_redraws {
            self.gbest.clear();
            for i in 0..self.n {
                ev.sample_initial(rng, row_mut(&mut self.x, i, dim));
                row_mut(&mut self.v, i, dim).fill(0.0);
            }
            ev.evaluate_rows(&self.x, self.n, &mut evals);
            for i in 0..self.n {
                let x = row(&self.x, i, dim);
                let e = evals.get(i).copied().unwrap_or(Evaluation::worst());
                row_mut(&mut self.pbest, i, dim).copy_from_slice(x);
                self.pbest_eval[i] = e;
                self.gbest.offer(x, e);
            }
            if self.gbest.eval.cost.is_finite() || ev.is_exhausted() {
                break;
            }
        }
    }

    /// Moves particle i. `guide` replaces pbest_i in the cognitive term (DLS exemplar);
    /// `lambda` adds the deterministic pull lambda (gbest - x) of DLS-SMPSO (Eq. 21).
    pub fn move_particle(
        &mut self,
        i: usize,
        guide: Option<&[f64]>,
        lambda: f64,
        bounds: &[Bound],
        rng: &mut Rng,
    ) {
        let dim = self.dim;
        let rule = VelocityRule {
            inertia: self.w,
            cognitive: self.params.cognitive,
            social: self.params.social,
            pull: Some(lambda),
            mirror: self.params.mirror_velocity,
        };
        let x = row_mut(&mut self.x, i, dim);
        let v = row_mut(&mut self.v, i, dim);
        let p = guide.unwrap_or(row(&self.pbest, i, dim));
        let g = &self.gbest.x;
        for j in 0..dim {
            move_coordinate(
                &mut x[j],
                &mut v[j],
                p[j],
                g[j],
                self.vmax[j],
                &bounds[j],
                &rule,
                rng,
            );
        }
    }

    /// Evaluates particle i where it stands and updates pbest_i (strict improvement) and,
    /// when asynchronous, gbest. `None` when the budget is spent (nothing changed), else
    /// whether pbest_i improved.
    pub fn evaluate_particle(&mut self, i: usize, ev: &mut Evaluator<'_>) -> Option<bool> {
        let dim = self.dim;
        let x = row(&self.x, i, dim);
        // Only a strict improvement on pbest_i matters, so the evaluation may stop once the
        // cost is known to exceed pbest_i's, or to be +inf when pbest_i's is (the same run,
        // for less; docs/performance.md).
        let e = ev.evaluate_cost_bounded(x, self.pbest_eval[i].cutoff_to_beat())?;
        if !e.better_than(&self.pbest_eval[i]) {
            return Some(false);
        }
        row_mut(&mut self.pbest, i, dim).copy_from_slice(x);
        self.pbest_eval[i] = e;
        if self.params.asynchronous {
            self.gbest.offer(x, e);
        }
        Some(true)
    }

    /// Evaluates every particle where it stands, in parallel, and updates each pbest_i (strict
    /// improvement); gbest waits for [`Swarm::end_iteration`] (synchronous updates only).
    pub fn evaluate_swarm(&mut self, ev: &mut Evaluator<'_>) {
        debug_assert!(!self.params.asynchronous);
        let dim = self.dim;
        let mut evals = std::mem::take(&mut self.evals);
        ev.evaluate_rows(&self.x, self.n, &mut evals);
        for (i, e) in evals.iter().enumerate() {
            if e.better_than(&self.pbest_eval[i]) {
                let x = row(&self.x, i, dim);
                row_mut(&mut self.pbest, i, dim).copy_from_slice(x);
                self.pbest_eval[i] = *e;
            }
        }
        self.evals = evals;
    }

    /// Offers pbest_i to gbest.
    pub fn offer_pbest(&mut self, i: usize) -> bool {
        self.gbest
            .offer(row(&self.pbest, i, self.dim), self.pbest_eval[i])
    }

    /// End of an iteration (also when the budget cut it short): synchronous gbest update.
    pub fn end_iteration(&mut self) {
        if !self.params.asynchronous {
            for i in 0..self.n {
                self.offer_pbest(i);
            }
        }
    }
}

/// PSO / APSO / SPSO.
#[derive(Debug, Clone)]
pub struct Pso {
    swarm: Swarm,
}

impl Pso {
    /// PSO with `params`; the swarm is drawn at initialisation.
    #[must_use]
    pub fn new(params: PsoParams) -> Self {
        Self {
            swarm: Swarm::new(params, &[]),
        }
    }

    /// The parameters it runs with.
    #[must_use]
    pub fn params(&self) -> &PsoParams {
        &self.swarm.params
    }

    /// The inertia weight the last step used.
    #[must_use]
    pub fn inertia(&self) -> f64 {
        self.swarm.w
    }
}

impl Optimizer for Pso {
    fn evaluations_per_iteration(&self) -> u64 {
        self.swarm.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.swarm = Swarm::new(self.swarm.params, ev.bounds());
        self.swarm.initialize(ev, rng);
    }

    /// Asynchronous: move and evaluate one particle after the other (gbest moves at once).
    /// Synchronous: move every particle against the same gbest, then evaluate the swarm in
    /// parallel ([`Evaluator::evaluate_rows`]); the same run as one after the other.
    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        self.swarm.schedule(ev.progress());
        if self.swarm.params.asynchronous {
            for i in 0..self.swarm.n {
                self.swarm.move_particle(i, None, 0.0, bounds, rng);
                if self.swarm.evaluate_particle(i, ev).is_none() {
                    break;
                }
            }
        } else {
            for i in 0..self.swarm.n {
                self.swarm.move_particle(i, None, 0.0, bounds, rng);
            }
            self.swarm.evaluate_swarm(ev);
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
    use crate::optim::{solve, Budget};
    use crate::problem::Problem;
    use crate::rng::rng_from_seed;

    /// Infinite cost everywhere except x > 0.9 (a sliver a random draw rarely hits).
    struct Sliver(Vec<Bound>);

    impl Problem for Sliver {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            let c = if x.iter().all(|v| *v > 0.9) {
                1.0
            } else {
                f64::INFINITY
            };
            Evaluation::new(c, 0.0)
        }
    }

    #[test]
    fn initial_swarm_is_redrawn_until_one_particle_is_finite() {
        let p = Sliver(vec![Bound::new(0.0, 1.0); 2]);
        let params = PsoParams {
            population: 5,
            ..PsoParams::DEFAULT
        };
        let mut pso = Pso::new(params);
        let out = solve(
            &p,
            &mut pso,
            Budget::iterations(0),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        assert!(out.best.cost.is_finite());
        // Each of the (several) draws is counted in full.
        assert!(out.evaluations > 5 && out.evaluations.is_multiple_of(5));

        let mut no_redraw = Pso::new(PsoParams {
            initial_redraws: 0,
            ..params
        });
        let out = solve(
            &p,
            &mut no_redraw,
            Budget::iterations(0),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        assert_eq!(out.evaluations, 5);
    }

    fn last_inertia(budget: Budget) -> f64 {
        let p = Sliver(vec![Bound::new(0.0, 1.0); 2]);
        let mut pso = Pso::new(PsoParams {
            population: 3,
            initial_redraws: 0,
            ..PsoParams::DEFAULT
        });
        let _ = solve(&p, &mut pso, budget, &mut rng_from_seed(1), &mut |_| {});
        pso.inertia()
    }

    #[test]
    fn inertia_is_damped_once_per_iteration_at_the_paper_budget() {
        // SPSO's own schedule: w *= 0.98 after each iteration; the last of 200 steps uses
        // 0.98^199, bit for bit the same product.
        let mut w = 1.0_f64;
        for _ in 0..199 {
            w *= 0.98;
        }
        assert_eq!(last_inertia(Budget::iterations(200)).to_bits(), w.to_bits());
    }

    #[test]
    fn the_inertia_schedule_stretches_with_the_budget() {
        // Ten steps cover the whole schedule: the last uses 0.98^(200 * 9 / 10).
        assert!((last_inertia(Budget::iterations(10)) - 0.98_f64.powi(180)).abs() < 1e-12);
        // Five times the paper's budget: at the last step w is where SPSO's is at its last.
        let w = last_inertia(Budget::iterations(1000));
        assert!((w - 0.98_f64.powf(200.0 * 999.0 / 1000.0)).abs() < 1e-12);
        // An evaluation budget: 3 per step, 3 for initialisation, 30 in all -> 9 steps; the
        // last starts with 27 of 30 spent.
        let w = last_inertia(Budget::evaluations(30));
        assert!(
            (w - 0.98_f64.powf(200.0 * 27.0 / 30.0)).abs() < 1e-12,
            "{w}"
        );
    }

    #[test]
    fn velocity_is_mirrored_where_the_position_left_the_box() {
        let bounds = [Bound::new(0.0, 1.0), Bound::periodic(0.0, 1.0)];
        let mut s = Swarm::new(
            PsoParams {
                population: 1,
                inertia: 1.0,
                cognitive: 0.0,
                social: 0.0,
                velocity_clamp: 0.5,
                ..PsoParams::DEFAULT
            },
            &bounds,
        );
        s.x.copy_from_slice(&[0.9, 0.9]);
        s.v.copy_from_slice(&[0.8, 0.3]);
        s.move_particle(0, None, 0.0, &bounds, &mut rng_from_seed(0));
        // Clamped to 0.5, left the box at 1.4: mirrored and clamped.
        assert_eq!(s.v[0], -0.5);
        assert_eq!(s.x[0], 1.0);
        // Periodic: wrapped, velocity kept.
        assert_eq!(s.v[1], 0.3);
        assert!((s.x[1] - 0.2).abs() < 1e-12);
    }
}
