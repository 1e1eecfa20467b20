//! Cooperative coevolution with feasibility-first particle swarms: swarmplan's own
//! optimizer, the `swarmplan` method's.
//!
//! Why: the paper's methods search one 150-dimensional vector for five UAVs at once, so a
//! move that repairs one UAV's threat crossing usually breaks another's separation, and the
//! swarm converges before any plan is feasible. Cooperative coevolution (Potter & De Jong
//! 1994, PPSN III, doi:10.1007/3-540-58484-6_269; for PSO van den Bergh & Engelbrecht 2004,
//! IEEE TEC 8(3):225-239, doi:10.1109/TEVC.2004.826069)
//! searches one block (one UAV's path) at a time inside a *context*: the best whole plan so
//! far, whose other blocks stay fixed. Candidates are compared by Deb's feasibility rules
//! ([`Evaluation::better_feasibility_first`]) instead of by penalised cost, so the search
//! first drives the violation to zero and only then lowers the cost, and it never gives a
//! feasible incumbent away.
//!
//! One step is one iteration of a sub-swarm of `population` particles on the current block:
//!
//! ```text
//! visit of block b (every block_iterations steps the next block, cyclically):
//!   particle 0 = context_b; the others = context_b + N(0, (s_b w_j)^2) per dimension j
//!   (w_j the bound's width), or, for a share `fresh` of them, block b of a new point from
//!   the method's initialisation; all clamped into the bounds and evaluated. The spread s_b
//!   of block b starts at `perturbation` and adapts per visit: x 2 after a visit that
//!   improved the context, x 1/2 after one that did not (within [1e-9, 0.5]), so visits
//!   explore while they pay and refine once the context is good (in the spirit of
//!   Rechenberg's success rule)
//! step:  v <- w v + c1 r1 (pbest - x) + c2 r2 (gbest - x); clamp |v| <= 0.5 w_j; x += v
//!        (mirrored and clamped at the bounds as in SPSO); evaluate context with block b = x;
//!        pbest, gbest and the context follow feasibility-first improvements
//! ```
//!
//! **Synchronous** (`updates = "synchronous"`, the default since issue 12): a visit's particles, and
//! each step's, are made against the gbest and context of the step's start and evaluated
//! together on every core ([`Evaluator::evaluate_rows_blocks`]); their results are then
//! taken in particle order. With `updates = "sequential"` each particle is evaluated as soon as
//! it moves and gbest and the context follow it at once (the method as measured before).
//! Only block b changes within a visit, so an evaluation never depends on that choice; the
//! centre of a visit's perturbations and the gbest of a step do. docs/performance.md
//! measures both: feasibility is level.
//!
//! **Focus.** While the context is infeasible, the next visit goes to the next UAV (in
//! turn) that holds a hard violation, its own or its half of a separation, as the problem
//! reports through [`Evaluator::evaluate_blocks`] (`focus` sets the share of such visits).
//! In a 20-UAV plan with two UAVs left in violation, a round of visits over every UAV spends
//! nine tenths of its evaluations on paths that are already fine.
//!
//! **Transplants** (`transplant = "perturbed"`). A visit of a UAV that holds a violation of an infeasible
//! context makes its last particle another UAV's path: the block of a UAV without a
//! violation of its own (drawn uniformly; any other UAV if every one has one), perturbed
//! like the other particles. The fleet flies from one start, or nearby ones, to one goal,
//! so a way between the threats that one UAV has found is open to the others; a UAV's own
//! sub-swarm searches near its current path and rarely crosses to the other side of a
//! threat cluster. On the outside instances (docs/results.md, paired seeds) 33 of 80 runs
//! were feasible with transplants against 24 without; the perturbation, the spread, the
//! nudges and, where free, the departure delays then separate the copy from its donor.
//! Once a round has passed without progress the transplant is a *shifted copy*
//! (`transplant = "shifted-when-stuck"`, the default; [`Evaluator::shifted_copy`]): the donor's path moved as a whole a few
//! separation distances aside, so that it flies beside its donor rather than on top of it
//! (held out on the outside instances: 168 of 320 runs feasible against 146).
//!
//! **Nudges** (`nudges`). In the same visits, up to `nudges` of the perturbed particles are
//! the problem's local move of the context's path ([`Evaluator::nudge`]): one free waypoint
//! moved by a Gaussian offset of two separation distances sideways and one in height, the
//! rest of the path kept. A perturbation of every value of a motion-encoded path moves all
//! of it; what is left near feasibility is local (two UAVs converging at the edge of the
//! landing zone, a corner clipping a threat), and one waypoint moved fixes it without
//! breaking the rest. The waypoint is drawn where the violations are (`aimed_nudges`,
//! [`Evaluator::hot_spots`]): next to the places of the UAV's own violations and its
//! separation losses, in proportion to their measure, found by one assessment of the
//! context per visit that counts as an evaluation. Drawn uniformly, the first free
//! waypoint, which sets the bearing at which a UAV leaves the take-off zone, was moved in
//! one nudge of ten, yet most runs left infeasible on the outside instances held a single
//! separation loss at a zone's edge (docs/results.md, "Aimed nudges"). In a planning
//! problem, a nudge of the first or last free waypoint of a UAV that shares its take-off
//! zone (or UGV0's landing zone) is a *zone move*: the waypoint goes near the zone, at a
//! bearing clear of the other UAVs' there and a height drawn in the band, since a long leg
//! turned by a nudge hardly moves where it crosses the zone's edge (docs/results.md, "Zone
//! moves").
//!
//! **Restarts.** A context can be stuck in a state no single block can repair (all UAVs out
//! of contact in an interference window, where only a joint move makes a relay chain; a
//! path wedged against a threat). When `restart_after` rounds (a visit of every block) in a
//! row leave an infeasible context without a drop of its violation by `restart_drop` (5 %),
//! a new context is drawn as at the start (`population` evaluations) and the spreads reset;
//! the best plan ever seen is kept apart and is what the run returns. A feasible context is
//! never restarted. From the budget fraction `refine_from` on, restarts stop and the search
//! goes back to the best plan seen, to refine it (a near-feasible plan found early is not
//! left for a fresh random one).
//!
//! **Bounded evaluations.** A moved particle matters only if it beats its pbest, which by
//! Deb's rules it cannot once its violation exceeds the pbest's; its evaluation is therefore
//! [bounded](Evaluator::evaluate_rows_blocks_bounded) by that violation and may stop early
//! (docs/performance.md, "Bounded evaluations"). It still counts as an evaluation, and the
//! run is the same bits as with full evaluations (test
//! `giving_up_bounded_evaluations_changes_nothing_in_a_run`).
//!
//! The inner PSO uses Clerc & Kennedy's constriction-equivalent constants (w = 0.7298,
//! c1 = c2 = 1.49618; IEEE TEC 6(1):58-73, 2002), which converge within the short visits
//! without a schedule. Every evaluation goes through the [`Evaluator`] and counts.

mod params;
mod sub_swarm;
pub mod switches;
#[cfg(test)]
mod tests;
mod visit;

use rand::Rng as _;

pub use params::CoopParams;
pub use switches::{Blocks, Comparison, Spread, Transplant, Updates};

use super::{Evaluator, Optimizer};
use crate::problem::Evaluation;
use crate::rng::Rng;

/// An index drawn in proportion to `weights` (non-negative, some positive).
fn weighted_pick(weights: &[f64], rng: &mut Rng) -> usize {
    let total: f64 = weights.iter().sum();
    let mut left = rng.random::<f64>() * total;
    for (k, &w) in weights.iter().enumerate() {
        if left < w {
            return k;
        }
        left -= w;
    }
    weights.iter().rposition(|&w| w > 0.0).unwrap_or(0)
}

/// `a` better than `b` under `params`' comparison.
fn better(params: CoopParams, a: &Evaluation, b: &Evaluation) -> bool {
    if params.compare == Comparison::FeasibilityFirst {
        a.better_feasibility_first(b)
    } else {
        a.better_than(b)
    }
}

/// Cooperative coevolution over blocks with feasibility-first sub-swarms.
#[derive(Debug, Clone)]
pub struct Cooperative {
    params: CoopParams,
    dim: usize,
    block: usize,
    /// The best whole vector so far and its evaluation.
    context: Vec<f64>,
    context_eval: Evaluation,
    /// Block being searched, and steps spent on it in this visit.
    current: usize,
    spent: usize,
    /// Sub-swarm state, `population` rows of one block each.
    x: Vec<f64>,
    v: Vec<f64>,
    pbest: Vec<f64>,
    pbest_eval: Vec<Evaluation>,
    gbest: Vec<f64>,
    gbest_eval: Evaluation,
    /// Whole vectors to evaluate together, with their evaluations and block shares, and
    /// the violation each must not exceed to matter (bounded evaluations).
    rows: Vec<f64>,
    cutoffs: Vec<f64>,
    evals: Vec<Evaluation>,
    row_shares: Vec<Vec<f64>>,
    /// A point of the initialisation (fresh particles take one block of it).
    scratch: Vec<f64>,
    /// Weights over the current block's nudge sites ([`Evaluator::hot_spots`]).
    spots: Vec<f64>,
    /// Spread s_b of each block's visits.
    spread: Vec<f64>,
    /// The context's evaluation when the current visit started.
    visit_start: Evaluation,
    /// The context's evaluation when the current round started, and rounds in a row
    /// without improvement.
    round_start: Evaluation,
    stale_rounds: usize,
    /// The best vector ever evaluated (across restarts).
    best: Vec<f64>,
    best_eval: Evaluation,
    restarts: u64,
    /// Each block's share of the violation in the context, in the best vector, and in the
    /// last evaluation ([`Evaluator::evaluate_blocks`]; empty when the problem does not say).
    context_shares: Vec<f64>,
    best_shares: Vec<f64>,
    /// Block of the last visit in the cyclic order, visits since the round began, and the
    /// credit that decides the next focused visit.
    cyclic: usize,
    visits: usize,
    focus_credit: f64,
}

impl Cooperative {
    #[must_use]
    /// A population below 2 (which validation refuses) is raised to 2 rather than
    /// panicking, as for the other optimizers.
    pub fn new(params: CoopParams) -> Self {
        let params = CoopParams {
            population: params.population.max(2),
            ..params
        };
        Self {
            params,
            dim: 0,
            block: 1,
            context: Vec::new(),
            context_eval: Evaluation::worst(),
            current: 0,
            spent: 0,
            x: Vec::new(),
            v: Vec::new(),
            pbest: Vec::new(),
            pbest_eval: Vec::new(),
            gbest: Vec::new(),
            gbest_eval: Evaluation::worst(),
            rows: Vec::new(),
            cutoffs: Vec::new(),
            evals: Vec::new(),
            row_shares: Vec::new(),
            scratch: Vec::new(),
            spots: Vec::new(),
            spread: Vec::new(),
            visit_start: Evaluation::worst(),
            round_start: Evaluation::worst(),
            stale_rounds: 0,
            best: Vec::new(),
            best_eval: Evaluation::worst(),
            restarts: 0,
            context_shares: Vec::new(),
            best_shares: Vec::new(),
            cyclic: 0,
            visits: 0,
            focus_credit: 0.0,
        }
    }

    /// The block of the next visit: a violating one when focus is due, else the next in
    /// the cyclic order.
    fn next_block(&mut self) -> usize {
        let n = self.blocks();
        let shares_known = self.context_shares.len() == n;
        if self.params.focus > 0.0
            && !self.context_eval.feasible()
            && shares_known
            && self.context_shares.iter().any(|&v| v > 0.0)
        {
            self.focus_credit += self.params.focus;
            if self.focus_credit >= 1.0 - 1e-9 {
                self.focus_credit -= 1.0;
                if let Some(b) = (1..=n)
                    .map(|k| (self.current + k) % n)
                    .find(|&b| self.context_shares[b] > 0.0)
                {
                    return b;
                }
            }
        }
        self.cyclic = (self.cyclic + 1) % n;
        self.cyclic
    }

    /// The comparison of the run: feasibility first, or penalised cost (an ablation).
    fn better(&self, a: &Evaluation, b: &Evaluation) -> bool {
        better(self.params, a, b)
    }

    /// Restarts so far.
    #[must_use]
    pub fn restarts(&self) -> u64 {
        self.restarts
    }

    /// Draws a new context: the best of `population` points of the initialisation.
    fn draw_context(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.context_eval = Evaluation::worst();
        self.spread = vec![self.params.perturbation; self.blocks()];
        self.current = 0;
        self.cyclic = 0;
        self.visits = 0;
        self.spent = 0;
        // The points are drawn first and evaluated together (in parallel): drawing never
        // depends on an evaluation, so this is the same as one after the other.
        let (pop, dim) = (self.params.population.max(1), self.dim);
        self.rows.resize(pop * dim, 0.0);
        for i in 0..pop {
            ev.sample_initial(rng, &mut self.rows[i * dim..(i + 1) * dim]);
        }
        ev.evaluate_rows_blocks(&self.rows, pop, &mut self.evals, &mut self.row_shares);
        for i in 0..self.evals.len() {
            let e = self.evals[i];
            if i == 0 || self.better(&e, &self.context_eval) {
                self.context
                    .copy_from_slice(&self.rows[i * dim..(i + 1) * dim]);
                self.context_eval = e;
                std::mem::swap(&mut self.context_shares, &mut self.row_shares[i]);
            }
        }
        self.round_start = self.context_eval;
        self.stale_rounds = 0;
        self.keep_best();
    }

    /// Remembers the context if it is the best ever.
    fn keep_best(&mut self) {
        if self.best.is_empty() || self.better(&self.context_eval, &self.best_eval) {
            self.best.clone_from(&self.context);
            self.best_eval = self.context_eval;
            self.best_shares.clone_from(&self.context_shares);
        }
    }

    fn blocks(&self) -> usize {
        self.dim.div_ceil(self.block).max(1)
    }

    /// The bounds of block `b`.
    fn range(&self, b: usize) -> std::ops::Range<usize> {
        let lo = b * self.block;
        lo..(lo + self.block).min(self.dim)
    }

    /// Particles evaluated together: the whole sub-swarm when synchronous (in parallel),
    /// else one at a time.
    fn chunk(&self) -> usize {
        if self.params.updates == Updates::Synchronous {
            self.params.population
        } else {
            1
        }
    }
}

impl Cooperative {
    /// After every block was visited: count a stale round, restart when due.
    fn end_round(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        // Progress is a drop of the violation by at least `restart_drop` over the round.
        let improved = self.context_eval.violation
            < (1.0 - self.params.restart_drop) * self.round_start.violation;
        self.round_start = self.context_eval;
        if ev.progress().fraction() >= self.params.refine_from {
            // Last phase: refine the best plan found instead of exploring anew.
            if self.better(&self.best_eval, &self.context_eval) {
                self.context.clone_from(&self.best);
                self.context_eval = self.best_eval;
                self.context_shares.clone_from(&self.best_shares);
                self.round_start = self.best_eval;
            }
            self.stale_rounds = 0;
            return;
        }
        if improved || self.context_eval.feasible() {
            self.stale_rounds = 0;
            return;
        }
        self.stale_rounds += 1;
        if self.params.restart_after > 0 && self.stale_rounds >= self.params.restart_after {
            self.restarts += 1;
            self.draw_context(ev, rng);
        }
    }
}

impl Optimizer for Cooperative {
    fn evaluations_per_iteration(&self) -> u64 {
        self.params.population as u64
    }

    fn init(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        self.dim = ev.dimension();
        self.block = if self.params.blocks == Blocks::PerUav {
            ev.block_size()
        } else {
            self.dim
        };
        self.context = vec![0.0; self.dim];
        self.context_eval = Evaluation::worst();
        self.best.clear();
        self.best_eval = Evaluation::worst();
        self.best_shares.clear();
        self.context_shares.clear();
        self.restarts = 0;
        self.focus_credit = 0.0;
        self.draw_context(ev, rng);
    }

    fn step(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        if self.dim == 0 {
            return;
        }
        if self.spent == 0 {
            self.start_visit(ev, rng);
        } else {
            self.move_swarm(ev, rng);
        }
        self.spent += 1;
        if self.spent > self.params.block_iterations {
            let improved = better(self.params, &self.context_eval, &self.visit_start);
            let s = &mut self.spread[self.current];
            *s = if self.params.spread == Spread::Fixed {
                *s
            } else if improved {
                (*s * 2.0).min(0.5)
            } else {
                (*s * 0.5).max(1e-9)
            };
            self.spent = 0;
            self.current = self.next_block();
            self.keep_best();
            // A round is as many visits as there are blocks (every block once, unless
            // focused visits went to the violating ones).
            self.visits += 1;
            if self.visits >= self.blocks() {
                self.visits = 0;
                self.end_round(ev, rng);
            }
        }
    }

    fn best(&self) -> (&[f64], Evaluation) {
        // The context may have improved since the last record (a visit cut by the budget).
        if self.best.is_empty() || self.better(&self.context_eval, &self.best_eval) {
            (&self.context, self.context_eval)
        } else {
            (&self.best, self.best_eval)
        }
    }
}
