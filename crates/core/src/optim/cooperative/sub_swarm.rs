//! The sub-swarm's PSO step on the current block, on the velocity kernel every swarm
//! here shares ([`crate::optim::swarm::move_coordinate`]), and the evaluation of its
//! particles in the context.

use super::{Comparison, Cooperative};
use crate::optim::swarm::{move_coordinate, VelocityRule};
use crate::optim::Evaluator;
use crate::rng::Rng;

impl Cooperative {
    /// One PSO iteration of the sub-swarm.
    pub(super) fn move_swarm(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let b = self.current;
        let r = self.range(b);
        let len = r.len();
        let rule = VelocityRule {
            inertia: self.params.inertia,
            cognitive: self.params.cognitive,
            social: self.params.social,
            pull: None,
            mirror: true,
        };
        let n = self.params.population;
        let mut from = 0;
        while from < n {
            let to = (from + self.chunk()).min(n);
            for i in from..to {
                for (k, j) in r.clone().enumerate() {
                    let bj = &bounds[j];
                    let idx = i * len + k;
                    move_coordinate(
                        &mut self.x[idx],
                        &mut self.v[idx],
                        self.pbest[idx],
                        self.gbest[k],
                        0.5 * bj.width(),
                        bj,
                        &rule,
                        rng,
                    );
                }
            }
            // A moved particle counts only if it beats its pbest, which (feasibility first)
            // it cannot once its violation passes the pbest's: such evaluations stop there.
            let bounded = self.params.compare == Comparison::FeasibilityFirst;
            self.evaluate_particles(b, from, to, bounded, ev);
            let got = self.evals.len();
            for k in 0..got {
                self.take_particle(b, from + k, k, false);
            }
            if got < to - from {
                return; // the budget is spent
            }
            from = to;
        }
    }

    /// Evaluates particles `from..to` of the sub-swarm (their rows of `self.x`) in the
    /// context with block `b` replaced, in parallel, into `self.evals` / `self.row_shares`.
    /// With `bounded`, a particle that cannot beat its pbest may come back as
    /// [`Evaluation::worst`] instead (see [`Cooperative::move_swarm`]).
    pub(super) fn evaluate_particles(
        &mut self,
        b: usize,
        from: usize,
        to: usize,
        bounded: bool,
        ev: &mut Evaluator<'_>,
    ) {
        let r = self.range(b);
        let (len, dim) = (r.len(), self.dim);
        self.rows.resize((to - from) * dim, 0.0);
        for (k, i) in (from..to).enumerate() {
            let row = &mut self.rows[k * dim..(k + 1) * dim];
            row.copy_from_slice(&self.context);
            row[r.clone()].copy_from_slice(&self.x[i * len..(i + 1) * len]);
        }
        if bounded {
            self.cutoffs.clear();
            self.cutoffs
                .extend(self.pbest_eval[from..to].iter().map(|p| p.violation));
            ev.evaluate_rows_blocks_bounded(
                &self.rows,
                to - from,
                &self.cutoffs,
                &mut self.evals,
                &mut self.row_shares,
            );
        } else {
            ev.evaluate_rows_blocks(&self.rows, to - from, &mut self.evals, &mut self.row_shares);
        }
    }

    /// Takes the evaluation of particle i (the k-th of its batch) as its pbest (always, or
    /// when better), then offers it to gbest and the context (feasibility first).
    pub(super) fn take_particle(&mut self, b: usize, i: usize, k: usize, always: bool) {
        let len = self.range(b).len();
        let e = self.evals[k];
        if !always && !self.better(&e, &self.pbest_eval[i]) {
            return;
        }
        let row = i * len..(i + 1) * len;
        self.pbest[row.clone()].copy_from_slice(&self.x[row.clone()]);
        self.pbest_eval[i] = e;
        if self.better(&e, &self.gbest_eval) {
            self.gbest.copy_from_slice(&self.x[row.clone()]);
            self.gbest_eval = e;
        }
        if self.better(&e, &self.context_eval) {
            let r = self.range(b);
            self.context[r].copy_from_slice(&self.x[row]);
            self.context_eval = e;
            std::mem::swap(&mut self.context_shares, &mut self.row_shares[k]);
        }
    }
}
