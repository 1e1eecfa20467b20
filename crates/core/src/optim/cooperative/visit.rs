//! A visit of one block: a fresh sub-swarm around the context, made of the context itself,
//! fresh draws, nudges (the problem's local moves, aimed at the violations), a transplant
//! or shifted copy of another block's path, and perturbations (module docs of
//! [`super`]).

use rand::Rng as _;
use rand_distr::{Distribution, Normal};

use super::{weighted_pick, Blocks, Cooperative, Transplant};
use crate::optim::swarm::into_bound;
use crate::optim::Evaluator;
use crate::problem::{Bound, Evaluation};
use crate::rng::Rng;

impl Cooperative {
    /// Starts a visit of the current block: a fresh sub-swarm around the context.
    pub(super) fn start_visit(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
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
        self.visit_start = self.context_eval;
        let spread = self.spread[b];
        // Particle 0 is the context itself (already evaluated).
        self.x[..len].copy_from_slice(&self.context[r.clone()]);
        self.pbest[..len].copy_from_slice(&self.context[r.clone()]);
        self.pbest_eval[0] = self.context_eval;
        let mut sample = std::mem::take(&mut self.scratch);
        sample.resize(self.dim, 0.0);
        let donor = self.transplant_donor(b, fresh, rng);
        // Nudges come just before the transplant (the last particle), after the fresh ones.
        let last_perturbed = n - 1 - usize::from(donor.is_some());
        let nudges = if self.violating(b) {
            self.params.nudges.min(last_perturbed.saturating_sub(fresh))
        } else {
            0
        };
        let first_nudge = last_perturbed + 1 - nudges;
        let aim = nudges > 0
            && self.params.aimed_nudges > 0.0
            && ev.hot_spots(&self.context, b, &mut self.spots).is_some()
            && self.spots.iter().any(|&w| w > 0.0);
        // After a round without progress the transplant is a shifted copy.
        let shift =
            self.params.transplant == Transplant::ShiftedWhenStuck && self.stale_rounds >= 1;
        let mut from = 1;
        while from < n {
            let to = (from + self.chunk()).min(n);
            for i in from..to {
                if i <= fresh {
                    ev.sample_initial(rng, &mut sample);
                    self.x[i * len..(i + 1) * len].copy_from_slice(&sample[r.clone()]);
                } else if (first_nudge..=last_perturbed).contains(&i) && {
                    let site = (aim && rng.random::<f64>() < self.params.aimed_nudges)
                        .then(|| weighted_pick(&self.spots, rng));
                    ev.nudge(
                        &self.context,
                        b,
                        site,
                        rng,
                        &mut self.x[i * len..(i + 1) * len],
                    )
                } {
                    // The problem's local move of the context's block.
                } else if i == n - 1
                    && shift
                    && donor.is_some_and(|d| {
                        let out = &mut self.x[i * len..(i + 1) * len];
                        ev.shifted_copy(&self.context, b, d, rng, out)
                    })
                {
                    // The transplant as a shifted copy of the donor's path.
                } else {
                    // The last particle is the transplant when there is one; the centre
                    // of the others is the context's own block.
                    let centre = match donor {
                        Some(d) if i == n - 1 => self.range(d).start,
                        _ => r.start,
                    };
                    for (k, j) in r.clone().enumerate() {
                        let bj: &Bound = &bounds[j];
                        let sd = (spread * bj.width()).max(f64::MIN_POSITIVE);
                        let noise = Normal::new(0.0, sd).map_or(0.0, |d| d.sample(rng));
                        self.x[i * len + k] = into_bound(bj, self.context[centre + k] + noise);
                    }
                }
            }
            self.evaluate_particles(b, from, to, false, ev);
            let got = self.evals.len();
            for k in 0..got {
                self.take_particle(b, from + k, k, true);
            }
            if got < to - from {
                break; // the budget is spent
            }
            from = to;
        }
        self.scratch = sample;
    }

    /// Whether block `b` holds a violation of an infeasible context (and blocks are UAVs).
    pub(super) fn violating(&self, b: usize) -> bool {
        self.params.blocks == Blocks::PerUav
            && !self.context_eval.feasible()
            && self.context_shares.get(b).is_some_and(|&v| v > 0.0)
    }

    /// The block whose path the transplant particle of a visit of block `b` starts from, or
    /// `None` (transplants off, a feasible context, `b` without a violation of its own, a
    /// single block, or no particle left after the context and the fresh ones). A block
    /// without a violation is preferred, drawn uniformly; else any other block.
    pub(super) fn transplant_donor(&self, b: usize, fresh: usize, rng: &mut Rng) -> Option<usize> {
        let blocks = self.blocks();
        let wanted = self.params.transplant.on()
            && blocks > 1
            && fresh + 1 < self.params.population
            && self.violating(b);
        if !wanted || self.range(b).len() != self.block {
            return None;
        }
        let other = |d: &usize| *d != b && self.range(*d).len() == self.block;
        let clean = |d: &usize| self.context_shares[*d] <= 0.0;
        let clean_only = (0..blocks).filter(other).any(|d| clean(&d));
        let eligible = |d: &usize| other(d) && (!clean_only || clean(d));
        let count = (0..blocks).filter(eligible).count();
        if count == 0 {
            return None;
        }
        (0..blocks).filter(eligible).nth(rng.random_range(0..count))
    }
}
