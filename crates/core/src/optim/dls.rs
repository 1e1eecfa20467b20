//! DLS-SMPSO: the PSO of [`super::pso`] (SPSO settings) plus a dimensional learning
//! strategy (DLS), in two modes.
//!
//! **Paper mode** (default; DLS-SMPSO paper, Eqs. 18-21 and Algorithm 1). The velocity gets
//! a deterministic pull towards gbest,
//!
//! ```text
//! v_ij <- w v_ij + c1 r1 (pbest_ij - x_ij) + c2 r2 (gbest_j - x_ij) + lambda (gbest_j - x_ij)
//! ```
//!
//! then clamped, moved and mirrored exactly as in PSO. Each particle keeps a stagnation
//! counter c_i: +1 after an evaluation that did not improve pbest_i, reset to 0 by one that
//! did (so it counts *consecutive* failures: the paper's pseudo-code never resets it on an
//! improvement, which would make "stagnation" fire on old failures). When c_i exceeds d it
//! is reset and pbest_i learns from gbest dimension by dimension: for j = 1..D with
//! pbest_ij != gbest_j, S = pbest_i with S_j = gbest_j is evaluated and kept (cumulatively)
//! only if its cost is strictly lower. (The paper's pseudo-code writes that assignment
//! backwards, and runs the substitution in the `else` branch of `c_i > d`; we follow its
//! prose.) An improved pbest_i is offered to gbest. Cost: at most D evaluations per
//! substitution pass. Left unbounded, passes fire for about one particle in d + 1 at every
//! iteration (up to N D / (d + 1) = 1250 extra evaluations per iteration for N = 50,
//! D = 150, d = 5: twenty times PSO's budget). The paper gives no figure, so we bound it:
//! at most `max_passes_per_iteration` passes per iteration (default 1, at most D extra
//! evaluations, typically far fewer since dimensions equal to gbest cost nothing); a
//! stagnant particle that finds the quota spent keeps its counter and goes next time.
//!
//! **Exemplar mode** (Xu et al. 2019, "Particle swarm optimization based on dimensional
//! learning strategy", Swarm Evol. Comput. 45:33-51; their public code wucg/TSLPSO). Every
//! time pbest_i improves (and once at initialisation, as in their code) an exemplar x_dl is
//! built from pbest_i by the same greedy substitution ([`build_exemplar`]) and used in
//! place of pbest_i in the velocity: `v <- w v + c1 r1 (x_dl - x) + c2 r2 (gbest - x)`
//! (no lambda term). The learning source is gbest, except when pbest_i *is* gbest: then it
//! is the best pbest among the particle's nearest neighbours (the `neighbour_fraction` x N
//! particles, at least one, closest to x_i in Euclidean distance of current positions, as
//! in their code). An exemplar better than gbest becomes gbest (pbest_i is left alone, as
//! in their code). When no dimension was accepted, one random dimension j of the exemplar
//! is re-drawn uniformly within the range the swarm currently spans in j,
//! [min_k x_kj, max_k x_kj] (their code means this but writes `rand*(rmin+rmax)-pe(d1)`
//! with a linear index, which is a bug). That perturbed exemplar is not evaluated.
//! Exemplar updates happen at once, within the iteration (consistent with the asynchronous
//! gbest); their code batches them after the swarm moved.
//!
//! Every DLS evaluation goes through the [`Evaluator`] and counts in the budget; when the
//! budget runs out during a substitution, the substitutions accepted so far are kept.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::params::{check, ParamsError};
use super::pso::{PsoParams, Swarm};
use super::swarm::{row, row_mut};
use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// Which dimensional learning strategy DLS-SMPSO uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum DlsMode {
    /// The DLS-SMPSO paper: lambda pull plus stagnation-triggered substitution.
    Paper,
    /// Xu et al. 2019 (TSLPSO): exemplar built whenever pbest improves.
    Exemplar,
}

impl DlsMode {
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Paper => "paper",
            Self::Exemplar => "exemplar",
        }
    }
}

impl std::fmt::Display for DlsMode {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl std::str::FromStr for DlsMode {
    type Err = ParamsError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        [Self::Paper, Self::Exemplar]
            .into_iter()
            .find(|m| m.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| ParamsError {
                field: "mode".to_owned(),
                expected: "paper or exemplar".to_owned(),
                got: s.to_owned(),
            })
    }
}

/// Parameters of DLS-SMPSO.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DlsParams {
    /// The underlying PSO (SPSO's settings: N = 50, w = 1 damped 0.98, c1 = c2 = 1.5).
    pub pso: PsoParams,
    /// Learning strategy (paper).
    pub mode: DlsMode,
    /// DLS learning rate lambda of Eq. 21 (0.5; the paper gives no value). Paper mode only.
    pub lambda: f64,
    /// Stagnation threshold d: substitution runs when a particle's counter exceeds it (5;
    /// the paper gives no value). Paper mode only.
    pub stagnation: usize,
    /// Substitution passes allowed per iteration (1). Paper mode only.
    pub max_passes_per_iteration: usize,
    /// Share of the swarm taken as a particle's nearest neighbours when it is itself gbest
    /// (0.2, TSLPSO's `floor(0.2 N)`; at least one). Exemplar mode only.
    pub neighbour_fraction: f64,
}

impl DlsParams {
    pub const DEFAULT: Self = Self {
        pso: PsoParams::DEFAULT,
        mode: DlsMode::Paper,
        lambda: 0.5,
        stagnation: 5,
        max_passes_per_iteration: 1,
        neighbour_fraction: 0.2,
    };

    pub fn validate(&self) -> Result<(), ParamsError> {
        self.pso.validate().map_err(|e| e.within("pso"))?;
        check(
            self.lambda.is_finite() && self.lambda >= 0.0,
            "lambda",
            "a finite number >= 0",
            self.lambda,
        )?;
        check(
            (0.0..=1.0).contains(&self.neighbour_fraction),
            "neighbour_fraction",
            "a number in [0, 1]",
            self.neighbour_fraction,
        )
    }
}

impl Default for DlsParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What a greedy dimension-by-dimension substitution produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExemplarStats {
    /// Evaluation of the resulting vector (that of pbest when nothing was accepted).
    pub eval: Evaluation,
    /// Evaluations spent.
    pub evaluations: u64,
    /// Dimensions taken from the guide.
    pub accepted: usize,
}

/// An exemplar and how it was obtained.
#[derive(Debug, Clone, PartialEq)]
pub struct Exemplar {
    pub x: Vec<f64>,
    pub stats: ExemplarStats,
}

/// Greedy dimensional learning (Xu et al. 2019): starting from `pbest` (evaluation
/// `pbest_eval`), for each dimension j where the current vector differs from `guide`, try
/// the vector with j set to `guide[j]` and keep it if its cost is strictly lower. At most
/// D evaluations; never worse than `pbest`. `evaluate` returning `None` (budget spent)
/// stops the pass, keeping what was accepted. Writes the result into `out`.
pub fn build_exemplar_into(
    evaluate: &mut impl FnMut(&[f64]) -> Option<Evaluation>,
    pbest: &[f64],
    pbest_eval: Evaluation,
    guide: &[f64],
    out: &mut [f64],
) -> ExemplarStats {
    out.copy_from_slice(pbest);
    let mut stats = ExemplarStats {
        eval: pbest_eval,
        evaluations: 0,
        accepted: 0,
    };
    for (j, &gj) in guide.iter().enumerate() {
        let old = out[j];
        if old == gj {
            continue;
        }
        out[j] = gj;
        let Some(e) = evaluate(out) else {
            out[j] = old;
            break;
        };
        stats.evaluations += 1;
        if e.better_than(&stats.eval) {
            stats.eval = e;
            stats.accepted += 1;
        } else {
            out[j] = old;
        }
    }
    stats
}

/// [`build_exemplar_into`] returning a new vector.
#[must_use]
pub fn build_exemplar(
    mut evaluate: impl FnMut(&[f64]) -> Option<Evaluation>,
    pbest: &[f64],
    pbest_eval: Evaluation,
    guide: &[f64],
) -> Exemplar {
    let mut x = vec![0.0; pbest.len()];
    let stats = build_exemplar_into(&mut evaluate, pbest, pbest_eval, guide, &mut x);
    Exemplar { x, stats }
}

/// DLS-SMPSO.
#[derive(Debug, Clone)]
pub struct DlsSmpso {
    params: DlsParams,
    swarm: Swarm,
    /// Paper mode: consecutive non-improving evaluations per particle.
    stagnation: Vec<usize>,
    /// Exemplar mode: one exemplar per particle (row-major); paper mode: one scratch row.
    exemplar: Vec<f64>,
    /// Exemplar mode: (distance, index) scratch for the neighbour search.
    neighbours: Vec<(f64, usize)>,
    /// Evaluations spent by dimensional learning so far.
    dls_evaluations: u64,
}

impl DlsSmpso {
    #[must_use]
    pub fn new(params: DlsParams) -> Self {
        Self {
            params,
            swarm: Swarm::new(params.pso, &[]),
            stagnation: Vec::new(),
            exemplar: Vec::new(),
            neighbours: Vec::new(),
            dls_evaluations: 0,
        }
    }

    #[must_use]
    pub fn params(&self) -> &DlsParams {
        &self.params
    }

    /// Evaluations spent by dimensional learning (included in the run's total).
    #[must_use]
    pub fn dls_evaluations(&self) -> u64 {
        self.dls_evaluations
    }

    /// Paper mode: substitutes gbest's dimensions into pbest_i, keeping improvements.
    fn substitute(&mut self, i: usize, ev: &mut Evaluator<'_>) {
        let s = &mut self.swarm;
        let dim = s.dim;
        let stats = build_exemplar_into(
            &mut |x| ev.evaluate(x),
            row(&s.pbest, i, dim),
            s.pbest_eval[i],
            &s.gbest.x,
            &mut self.exemplar,
        );
        self.dls_evaluations += stats.evaluations;
        if stats.accepted > 0 {
            row_mut(&mut s.pbest, i, dim).copy_from_slice(&self.exemplar);
            s.pbest_eval[i] = stats.eval;
            s.offer_pbest(i);
        }
    }

    /// Exemplar mode: rebuilds the exemplar of particle i from its (new) pbest.
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
            &mut |x| ev.evaluate(x),
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

impl Optimizer for DlsSmpso {
    fn evaluations_per_iteration(&self) -> u64 {
        self.swarm.n as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng, _planned_iterations: usize) {
        self.swarm = Swarm::new(self.params.pso, ev.bounds());
        let (n, dim) = (self.swarm.n, self.swarm.dim);
        self.stagnation = vec![0; n];
        self.dls_evaluations = 0;
        self.swarm.initialize(ev, rng);
        match self.params.mode {
            DlsMode::Paper => self.exemplar = vec![0.0; dim],
            DlsMode::Exemplar => {
                self.exemplar = self.swarm.pbest.clone();
                self.neighbours = Vec::with_capacity(n);
                for i in 0..n {
                    if ev.is_exhausted() {
                        break;
                    }
                    self.rebuild_exemplar(i, ev, rng);
                }
            }
        }
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let dim = self.swarm.dim;
        let mut passes = 0;
        for i in 0..self.swarm.n {
            let improved = match self.params.mode {
                DlsMode::Paper => {
                    self.swarm
                        .move_particle(i, None, self.params.lambda, bounds, rng);
                    self.swarm.evaluate_particle(i, ev)
                }
                DlsMode::Exemplar => {
                    let guide = row(&self.exemplar, i, dim);
                    self.swarm.move_particle(i, Some(guide), 0.0, bounds, rng);
                    self.swarm.evaluate_particle(i, ev)
                }
            };
            let Some(improved) = improved else { break };
            match self.params.mode {
                DlsMode::Paper if improved => self.stagnation[i] = 0,
                DlsMode::Paper => {
                    self.stagnation[i] += 1;
                    if self.stagnation[i] > self.params.stagnation
                        && passes < self.params.max_passes_per_iteration
                    {
                        passes += 1;
                        self.stagnation[i] = 0;
                        self.substitute(i, ev);
                    }
                }
                DlsMode::Exemplar if improved => self.rebuild_exemplar(i, ev, rng),
                DlsMode::Exemplar => {}
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
    use crate::optim::{solve, Budget};
    use crate::problem::{Bound, Problem};
    use crate::rng::rng_from_seed;

    fn sphere(x: &[f64]) -> f64 {
        x.iter().map(|v| v * v).sum()
    }

    #[test]
    fn reproduces_the_worked_example_of_xu_et_al() {
        let pbest = [1.0, 0.0, 3.0, 2.0, 4.0];
        let gbest = [2.0, 2.0, 2.0, 4.0, 0.0];
        assert_eq!(sphere(&pbest), 30.0);
        assert_eq!(sphere(&gbest), 28.0);
        let ex = build_exemplar(
            |x| Some(Evaluation::new(sphere(x), 0.0)),
            &pbest,
            Evaluation::new(30.0, 0.0),
            &gbest,
        );
        assert_eq!(ex.x, vec![1.0, 0.0, 2.0, 2.0, 0.0]);
        assert_eq!(ex.stats.eval.cost, 9.0);
        assert_eq!(ex.stats.evaluations, 5);
        assert_eq!(ex.stats.accepted, 2);
    }

    #[test]
    fn equal_dimensions_cost_nothing_and_budget_stops_the_pass() {
        let pbest = [1.0, 5.0, 3.0];
        let guide = [1.0, 0.0, 0.0];
        let mut calls = 0;
        let ex = build_exemplar(
            |x| {
                calls += 1;
                (calls <= 1).then(|| Evaluation::new(sphere(x), 0.0))
            },
            &pbest,
            Evaluation::new(35.0, 0.0),
            &guide,
        );
        // Dimension 0 is skipped, dimension 1 accepted, dimension 2 refused by the budget.
        assert_eq!(ex.x, vec![1.0, 0.0, 3.0]);
        assert_eq!(ex.stats.evaluations, 1);
        assert_eq!(ex.stats.eval.cost, 10.0);
    }

    struct Sphere(Vec<Bound>);

    impl Problem for Sphere {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            Evaluation::new(sphere(x), 0.0)
        }
    }

    #[test]
    fn both_modes_spend_extra_evaluations_and_count_them() {
        let p = Sphere(vec![Bound::new(-10.0, 10.0); 10]);
        for mode in [DlsMode::Paper, DlsMode::Exemplar] {
            let mut opt = DlsSmpso::new(DlsParams {
                mode,
                pso: PsoParams {
                    population: 10,
                    ..PsoParams::DEFAULT
                },
                ..DlsParams::DEFAULT
            });
            let out = solve(
                &p,
                &mut opt,
                Budget::iterations(50),
                &mut rng_from_seed(5),
                &mut |_| {},
            );
            assert!(opt.dls_evaluations() > 0, "{mode}");
            assert_eq!(
                out.evaluations,
                10 + 50 * 10 + opt.dls_evaluations(),
                "{mode}"
            );
            assert!(out.best.cost < 1.0, "{mode}: {}", out.best.cost);
        }
    }
}
