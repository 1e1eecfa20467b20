//! Cooperative coevolution with feasibility-first particle swarms: swarmplan's own
//! optimizer, the `swarmplan` method's.
//!
//! Why: the paper's methods search one 150-dimensional vector for five UAVs at once, so a
//! move that repairs one UAV's threat crossing usually breaks another's separation, and the
//! swarm converges before any plan is feasible. Cooperative coevolution (Potter & De Jong
//! 1994, PPSN III; for PSO van den Bergh & Engelbrecht 2004, IEEE TEC 8(3):225-239)
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
//! **Synchronous** (`synchronous`, the default since issue 12): a visit's particles, and
//! each step's, are made against the gbest and context of the step's start and evaluated
//! together on every core ([`Evaluator::evaluate_rows_blocks`]); their results are then
//! taken in particle order. With `synchronous = false` each particle is evaluated as soon as
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
//! **Transplants** (`transplant`). A visit of a UAV that holds a violation of an infeasible
//! context makes its last particle another UAV's path: the block of a UAV without a
//! violation of its own (drawn uniformly; any other UAV if every one has one), perturbed
//! like the other particles. The fleet flies from one start, or nearby ones, to one goal,
//! so a way between the threats that one UAV has found is open to the others; a UAV's own
//! sub-swarm searches near its current path and rarely crosses to the other side of a
//! threat cluster. On the outside instances (docs/results.md, paired seeds) 33 of 80 runs
//! were feasible with transplants against 24 without; the perturbation, the spread, the
//! nudges and, where free, the departure delays then separate the copy from its donor.
//! Once a round has passed without progress the transplant is a *shifted copy*
//! (`shifted_copies`, [`Evaluator::shifted_copy`]): the donor's path moved as a whole a few
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

use rand::Rng as _;
use rand_distr::{Distribution, Normal};
use serde::{Deserialize, Serialize};

use super::params::{check, ParamsError};
use super::swarm::into_bound;
use super::{Evaluator, Optimizer};
use crate::problem::{Bound, Evaluation};
use crate::rng::Rng;

/// Parameters of the cooperative optimizer.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CoopParams {
    /// Particles of a sub-swarm, and points drawn for a new context (10). Measured on the
    /// paper cases (docs/results.md): 10 and 20 are level within the noise of 60 runs
    /// (paper-case1 60/60 and 59/60 feasible, paper-case2 55/60 and 54/60); 10 visits the
    /// blocks twice as often.
    pub population: usize,
    /// Steps spent on one block before the next (10).
    pub block_iterations: usize,
    /// Inertia weight w of the sub-swarms (0.7298).
    pub inertia: f64,
    /// Cognitive coefficient c1 (1.49618).
    pub cognitive: f64,
    /// Social coefficient c2 (1.49618).
    pub social: f64,
    /// Initial spread of a visit's particles around the context, as a share of each bound's
    /// width (0.1); adapted per block afterwards.
    pub perturbation: f64,
    /// Share of a visit's particles drawn afresh from the initialisation (0.25).
    pub fresh: f64,
    /// Rounds without improvement of an infeasible context before a restart (3; 0 never).
    pub restart_after: usize,
    /// The drop of an infeasible context's violation over a round, as a share of it, that
    /// counts as improvement for `restart_after` (0.05): the measure is continuous, so some
    /// tiny drop is nearly always found, and a context that only creeps is stuck.
    pub restart_drop: f64,
    /// Budget fraction from which restarts stop and the best plan so far is refined (0.85;
    /// 0.7 before the flown path of issue 15, measured in docs/results.md).
    pub refine_from: f64,
    /// Compare candidates by Deb's feasibility rules (true) or by penalised cost alone
    /// (false; an ablation, docs/results.md).
    pub feasibility_first: bool,
    /// Adapt each block's spread per visit (true) or keep `perturbation` (false; an
    /// ablation).
    pub adaptive_spread: bool,
    /// Search one UAV at a time (true) or the whole plan as one block (false; an ablation:
    /// a restarting PSO on the joint vector).
    pub decompose: bool,
    /// Share of the visits of an infeasible context that go to a UAV holding a violation
    /// (its own, or its half of a separation), taken in turn; the other visits continue
    /// the cyclic order over every UAV, so a UAV whose move would repair another's violation
    /// (a relay) is still searched. 0 visits every UAV in turn, feasible or not (1.0;
    /// measured in docs/results.md: on the five hardest 20-UAV instances 22 of 25 runs
    /// feasible at 1.0, 20 at 0.5, 12 at 0; level on the paper cases).
    pub focus: f64,
    /// Evaluate a sub-swarm's particles together, in parallel, against the gbest and
    /// context of the step's start (true), or one after the other with gbest and the context
    /// following each (false: the method as measured before issue 12). Either way a run is
    /// the same for any thread count.
    pub synchronous: bool,
    /// In a visit of a block that holds a violation of an infeasible context, make one
    /// particle a *transplant*: another block's path (one without a violation of its own,
    /// drawn at random, if any), perturbed like the others. UAVs of one fleet fly from
    /// nearby starts to one goal, so a way round the threats that one UAV has found is
    /// usually open to another whose own sector search is stuck on the wrong side.
    pub transplant: bool,
    /// Particles of a visit of a violating block (infeasible context) that are the
    /// problem's local move of the context's block ([`Evaluator::nudge`]; in a planning
    /// problem one free waypoint moved by a few separation distances), taken from the
    /// perturbed ones (4: at the default population all of them but one, or two when there
    /// is no transplant; 0: none, and no random draw for them). Measured in
    /// docs/results.md ("Nudges").
    pub nudges: usize,
    /// Once a round has passed without progress (an infeasible context whose violation did
    /// not drop by `restart_drop`), make the transplant a *shifted copy*
    /// ([`Evaluator::shifted_copy`]): the donor's path moved as a whole, in a planning
    /// problem by 1.5 to 3 separation distances sideways in a random direction and a
    /// Gaussian of one in height. Under common arrival the copy and its donor are at the
    /// same share of their routes at every instant, so they fly side by side about that
    /// far apart, where a perturbed copy flies on top of its donor. Measured in
    /// docs/results.md ("Shifted copies").
    pub shifted_copies: bool,
    /// Share of the nudges aimed at where the block's violations are
    /// ([`Evaluator::hot_spots`]: in a planning problem the free waypoints next to the
    /// UAV's violations, and its departure delay when delays are free, drawn in proportion
    /// to their measure); the rest, and every nudge when the hot spots weigh nothing, move a
    /// waypoint drawn uniformly. Finding the hot spots assesses the context once per visit,
    /// counted as an evaluation. 0: no aim, and neither that evaluation nor a random draw
    /// for it.
    pub aimed_nudges: f64,
}

impl CoopParams {
    pub const DEFAULT: Self = Self {
        population: 10,
        block_iterations: 10,
        inertia: 0.7298,
        cognitive: 1.49618,
        social: 1.49618,
        perturbation: 0.1,
        fresh: 0.25,
        restart_after: 3,
        restart_drop: 0.05,
        refine_from: 0.85,
        feasibility_first: true,
        adaptive_spread: true,
        decompose: true,
        focus: 1.0,
        synchronous: true,
        transplant: true,
        nudges: 4,
        shifted_copies: true,
        aimed_nudges: 1.0,
    };

    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            super::params::POPULATION_RANGE.contains(&self.population),
            "population",
            super::params::POPULATION_EXPECTED,
            self.population,
        )?;
        check(
            self.block_iterations >= 1,
            "block_iterations",
            "at least 1",
            self.block_iterations,
        )?;
        for (v, name) in [
            (self.inertia, "inertia"),
            (self.cognitive, "cognitive"),
            (self.social, "social"),
        ] {
            check(v.is_finite() && v >= 0.0, name, "a finite number >= 0", v)?;
        }
        check(
            self.perturbation.is_finite() && self.perturbation > 0.0,
            "perturbation",
            "a positive number",
            self.perturbation,
        )?;
        check(
            (0.0..=1.0).contains(&self.fresh),
            "fresh",
            "a number in [0, 1]",
            self.fresh,
        )?;
        check(
            (0.0..1.0).contains(&self.restart_drop),
            "restart_drop",
            "a number in [0, 1)",
            self.restart_drop,
        )?;
        check(
            (0.0..=1.0).contains(&self.refine_from),
            "refine_from",
            "a number in [0, 1]",
            self.refine_from,
        )?;
        check(
            (0.0..=1.0).contains(&self.focus),
            "focus",
            "a number in [0, 1]",
            self.focus,
        )?;
        check(
            (0.0..=1.0).contains(&self.aimed_nudges),
            "aimed_nudges",
            "a number in [0, 1]",
            self.aimed_nudges,
        )
    }
}

impl Default for CoopParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

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
    if params.feasibility_first {
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
        if self.params.synchronous {
            self.params.population
        } else {
            1
        }
    }

    /// Evaluates particles `from..to` of the sub-swarm (their rows of `self.x`) in the
    /// context with block `b` replaced, in parallel, into `self.evals` / `self.row_shares`.
    /// With `bounded`, a particle that cannot beat its pbest may come back as
    /// [`Evaluation::worst`] instead (see [`Cooperative::move_swarm`]).
    fn evaluate_particles(
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
    fn take_particle(&mut self, b: usize, i: usize, k: usize, always: bool) {
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

    /// Starts a visit of the current block: a fresh sub-swarm around the context.
    fn start_visit(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
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
        let shift = self.params.shifted_copies && self.stale_rounds >= 1;
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
    fn violating(&self, b: usize) -> bool {
        self.params.decompose
            && !self.context_eval.feasible()
            && self.context_shares.get(b).is_some_and(|&v| v > 0.0)
    }

    /// The block whose path the transplant particle of a visit of block `b` starts from, or
    /// `None` (transplants off, a feasible context, `b` without a violation of its own, a
    /// single block, or no particle left after the context and the fresh ones). A block
    /// without a violation is preferred, drawn uniformly; else any other block.
    fn transplant_donor(&self, b: usize, fresh: usize, rng: &mut Rng) -> Option<usize> {
        let blocks = self.blocks();
        let wanted = self.params.transplant
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

    /// One PSO iteration of the sub-swarm.
    fn move_swarm(&mut self, ev: &mut Evaluator<'_>, rng: &mut Rng) {
        let bounds = ev.bounds();
        let b = self.current;
        let r = self.range(b);
        let len = r.len();
        let CoopParams {
            inertia: w,
            cognitive: c1,
            social: c2,
            ..
        } = self.params;
        let n = self.params.population;
        let mut from = 0;
        while from < n {
            let to = (from + self.chunk()).min(n);
            for i in from..to {
                for (k, j) in r.clone().enumerate() {
                    let bj = &bounds[j];
                    let idx = i * len + k;
                    let r1: f64 = rng.random();
                    let r2: f64 = rng.random();
                    let vmax = 0.5 * bj.width();
                    let vj = (w * self.v[idx]
                        + c1 * r1 * (self.pbest[idx] - self.x[idx])
                        + c2 * r2 * (self.gbest[k] - self.x[idx]))
                        .clamp(-vmax, vmax);
                    let moved = self.x[idx] + vj;
                    self.v[idx] = if !bj.periodic && !bj.contains(moved) {
                        -vj
                    } else {
                        vj
                    };
                    self.x[idx] = into_bound(bj, moved);
                }
            }
            // A moved particle counts only if it beats its pbest, which (feasibility first)
            // it cannot once its violation passes the pbest's: such evaluations stop there.
            self.evaluate_particles(b, from, to, self.params.feasibility_first, ev);
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
        self.block = if self.params.decompose {
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
            *s = if !self.params.adaptive_spread {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::{solve, Budget};
    use crate::problem::Problem;
    use crate::rng::rng_from_seed;

    /// Sphere in blocks of 3, with a "constraint" x_0 >= 1 (violation 1 - x_0).
    struct Constrained(Vec<Bound>);

    impl Problem for Constrained {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            let violation = (1.0 - x[0]).max(0.0);
            Evaluation::new(
                x.iter().map(|v| v * v).sum::<f64>() + 1e3 * violation,
                violation,
            )
        }
        fn block_size(&self) -> usize {
            3
        }
    }

    /// [`Constrained`] that gives up every bounded evaluation it can (and counts them).
    struct GivingUp(Constrained, std::sync::atomic::AtomicUsize);

    impl Problem for GivingUp {
        fn bounds(&self) -> &[Bound] {
            self.0.bounds()
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            self.0.evaluate(x)
        }
        fn block_size(&self) -> usize {
            self.0.block_size()
        }
        fn evaluate_blocks_bounded(
            &self,
            x: &[f64],
            by_block: &mut Vec<f64>,
            cutoff: f64,
        ) -> Option<Evaluation> {
            let e = self.evaluate_blocks(x, by_block);
            if e.violation > cutoff {
                self.1.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                return None;
            }
            Some(e)
        }
    }

    #[test]
    fn giving_up_bounded_evaluations_changes_nothing_in_a_run() {
        let bounds = vec![Bound::new(-5.0, 5.0); 9];
        let run = |p: &dyn Problem| {
            let mut opt = Cooperative::new(CoopParams::DEFAULT);
            solve(
                p,
                &mut opt,
                Budget::evaluations(3000),
                &mut rng_from_seed(4),
                &mut |_| {},
            )
        };
        let plain = run(&Constrained(bounds.clone()));
        let giving_up = GivingUp(Constrained(bounds), std::sync::atomic::AtomicUsize::new(0));
        let bounded = run(&giving_up);
        assert_eq!(plain.best_x, bounded.best_x);
        assert_eq!(plain.trace, bounded.trace);
        assert_eq!(plain.evaluations, bounded.evaluations);
        let given_up = giving_up.1.into_inner();
        assert!(given_up > 100, "only {given_up} evaluations given up");
    }

    /// Violation 1 on a plateau that no local move leaves.
    struct Plateau(Vec<Bound>);

    impl Problem for Plateau {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, _: &[f64]) -> Evaluation {
            Evaluation::new(1e3, 1.0)
        }
        fn block_size(&self) -> usize {
            2
        }
    }

    #[test]
    fn a_stuck_infeasible_context_is_restarted_and_the_best_kept() {
        let p = Plateau(vec![Bound::new(0.0, 1.0); 4]);
        let mut opt = Cooperative::new(CoopParams::DEFAULT);
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(5000),
            &mut rng_from_seed(1),
            &mut |_| {},
        );
        // A round is 2 blocks x 11 steps x 10 evaluations = 220; restart after 3 stale ones.
        assert!(opt.restarts() >= 2, "{}", opt.restarts());
        assert_eq!(out.best.violation, 1.0);
        let mut never = Cooperative::new(CoopParams {
            restart_after: 0,
            ..CoopParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut never,
            Budget::evaluations(5000),
            &mut rng_from_seed(1),
            &mut |_| {},
        );
        assert_eq!(never.restarts(), 0);
    }

    /// Never feasible: violation 1 + x_0 over [0, 1]^4 in blocks of 2, so the context's
    /// violation creeps down towards 1 and no round halves it.
    struct Creeping(Vec<Bound>);

    impl Problem for Creeping {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            Evaluation::new(1e3, 1.0 + x[0])
        }
        fn block_size(&self) -> usize {
            2
        }
    }

    #[test]
    fn restart_drop_sets_what_counts_as_progress() {
        let p = Creeping(vec![Bound::new(0.0, 1.0); 4]);
        let restarts = |restart_drop: f64| {
            let mut opt = Cooperative::new(CoopParams {
                restart_drop,
                refine_from: 1.0,
                ..CoopParams::DEFAULT
            });
            let _ = solve(
                &p,
                &mut opt,
                Budget::evaluations(5000),
                &mut rng_from_seed(3),
                &mut |_| {},
            );
            opt.restarts()
        };
        // Asking for a 90 % drop per round makes every round stale; any drop at all counts
        // as progress while the violation still creeps.
        let (strict, lenient) = (restarts(0.9), restarts(0.0));
        assert!(strict >= 5, "{strict}");
        assert!(lenient < strict, "{lenient} vs {strict}");
        let bad = CoopParams {
            restart_drop: 1.0,
            ..CoopParams::DEFAULT
        };
        assert_eq!(
            bad.validate().expect_err("a 100 % drop").field,
            "restart_drop"
        );
    }

    /// Four blocks of 3; block 3 holds a violation no move removes (x_9 >= 10 in [-5, 5])
    /// and says so through `evaluate_blocks`. Counts the evaluations that changed block 3
    /// alone, i.e. that were spent visiting it.
    struct LastBlockViolated {
        bounds: Vec<Bound>,
        prev: std::sync::Mutex<Vec<f64>>,
        visiting_last: std::sync::atomic::AtomicUsize,
    }

    impl Problem for LastBlockViolated {
        fn bounds(&self) -> &[Bound] {
            &self.bounds
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            let mut prev = self.prev.lock().expect("not poisoned");
            let changed: Vec<usize> = (0..4)
                .filter(|b| x[3 * b..3 * b + 3] != prev[3 * b..3 * b + 3])
                .collect();
            if changed == [3] {
                self.visiting_last
                    .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            }
            prev.copy_from_slice(x);
            Evaluation::new(x.iter().map(|v| v * v).sum(), 10.0 - x[9])
        }
        fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
            let e = self.evaluate(x);
            by_block.clear();
            by_block.extend([0.0, 0.0, 0.0, e.violation]);
            e
        }
        fn block_size(&self) -> usize {
            3
        }
    }

    #[test]
    fn focus_sends_the_visits_of_an_infeasible_context_to_the_violating_block() {
        let share = |focus: f64| {
            let p = LastBlockViolated {
                bounds: vec![Bound::new(-5.0, 5.0); 12],
                prev: std::sync::Mutex::new(vec![f64::NAN; 12]),
                visiting_last: 0.into(),
            };
            let mut opt = Cooperative::new(CoopParams {
                focus,
                restart_after: 0,
                ..CoopParams::DEFAULT
            });
            let out = solve(
                &p,
                &mut opt,
                Budget::evaluations(4000),
                &mut rng_from_seed(2),
                &mut |_| {},
            );
            assert!(!out.best.feasible());
            p.visiting_last.into_inner() as f64 / 4000.0
        };
        let (off, half, full) = (share(0.0), share(0.5), share(1.0));
        assert!((0.2..0.3).contains(&off), "cyclic visits: {off}");
        assert!(full > 0.9, "focused visits: {full}");
        assert!(half > off + 0.2 && half < full, "{off} {half} {full}");
    }

    /// Two blocks of 6 in [0, 1]; block 1 is violated (1, a plateau) unless each of its
    /// values is within 0.05 of block 0's: a gap that only block 0's path knows, found by a
    /// uniform draw once in about 10^6.
    struct NarrowGap(Vec<Bound>);

    impl Problem for NarrowGap {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            let inside = (0..6).all(|k| (x[6 + k] - x[k]).abs() <= 0.05);
            // Only block 0 has a cost (towards 0.9), so block 1's own search has nothing to
            // follow on its plateau.
            let cost = x[..6].iter().map(|v| (v - 0.9).powi(2)).sum();
            Evaluation::new(cost, if inside { 0.0 } else { 1.0 })
        }
        fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
            let e = self.evaluate(x);
            by_block.clear();
            by_block.extend([0.0, e.violation]);
            e
        }
        fn block_size(&self) -> usize {
            6
        }
    }

    #[test]
    fn a_violating_block_finds_the_way_another_block_knows_by_transplant() {
        let run = |transplant: bool, seed: u64| {
            let mut opt = Cooperative::new(CoopParams {
                transplant,
                ..CoopParams::DEFAULT
            });
            solve(
                &NarrowGap(vec![Bound::new(0.0, 1.0); 12]),
                &mut opt,
                Budget::evaluations(3000),
                &mut rng_from_seed(seed),
                &mut |_| {},
            )
            .best
            .feasible()
        };
        for seed in 1..=5 {
            assert!(
                run(true, seed),
                "seed {seed}: transplant did not cross the gap"
            );
            assert!(!run(false, seed), "seed {seed}: crossed without transplant");
        }
    }

    /// [`LastBlockViolated`]'s plateau, counting the nudges asked for per block, and
    /// recording the shifted copies asked for as (block, donor), the hot spots asked for
    /// (per block) and the site of every nudge. Its hot spots put every weight on site 2
    /// of 3.
    struct CountsMoves {
        inner: LastBlockViolated,
        asked: std::sync::Mutex<Vec<usize>>,
        copies: std::sync::Mutex<Vec<(usize, usize)>>,
        spots: std::sync::Mutex<Vec<usize>>,
        sites: std::sync::Mutex<Vec<Option<usize>>>,
        /// Calls of `evaluate` and `evaluate_blocks`.
        evaluated: std::sync::atomic::AtomicU64,
    }

    impl CountsMoves {
        fn new() -> Self {
            Self {
                inner: LastBlockViolated {
                    bounds: vec![Bound::new(-5.0, 5.0); 12],
                    prev: std::sync::Mutex::new(vec![f64::NAN; 12]),
                    visiting_last: 0.into(),
                },
                asked: std::sync::Mutex::new(vec![0; 4]),
                copies: std::sync::Mutex::new(Vec::new()),
                spots: std::sync::Mutex::new(vec![0; 4]),
                sites: std::sync::Mutex::new(Vec::new()),
                evaluated: 0.into(),
            }
        }
    }

    impl Problem for CountsMoves {
        fn bounds(&self) -> &[Bound] {
            self.inner.bounds()
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            self.evaluated
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            self.inner.evaluate(x)
        }
        fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
            self.evaluated
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            self.inner.evaluate_blocks(x, by_block)
        }
        fn block_size(&self) -> usize {
            3
        }
        fn nudge(
            &self,
            x: &[f64],
            block: usize,
            site: Option<usize>,
            _: &mut Rng,
            out: &mut [f64],
        ) -> bool {
            self.asked.lock().expect("not poisoned")[block] += 1;
            self.sites.lock().expect("not poisoned").push(site);
            out.copy_from_slice(&x[3 * block..3 * block + 3]);
            true
        }
        fn shifted_copy(
            &self,
            x: &[f64],
            block: usize,
            donor: usize,
            _: &mut Rng,
            out: &mut [f64],
        ) -> bool {
            self.copies
                .lock()
                .expect("not poisoned")
                .push((block, donor));
            out.copy_from_slice(&x[3 * donor..3 * donor + 3]);
            true
        }
        fn hot_spots(&self, _: &[f64], block: usize, out: &mut Vec<f64>) -> bool {
            self.spots.lock().expect("not poisoned")[block] += 1;
            out.clear();
            out.extend([0.0, 0.0, 1.5]);
            true
        }
    }

    #[test]
    fn nudges_go_to_the_violating_block_only_and_only_when_asked_for() {
        let asked = |nudges: usize| {
            let p = CountsMoves::new();
            let mut opt = Cooperative::new(CoopParams {
                nudges,
                focus: 0.0,
                ..CoopParams::DEFAULT
            });
            let _ = solve(
                &p,
                &mut opt,
                Budget::evaluations(3000),
                &mut rng_from_seed(3),
                &mut |_| {},
            );
            p.asked.into_inner().expect("not poisoned")
        };
        assert_eq!(asked(0), vec![0; 4]);
        let two = asked(2);
        assert_eq!(two[..3], [0, 0, 0], "{two:?}");
        assert!(
            two[3] >= 4 && two[3] % 2 == 0,
            "two per visit of block 3: {two:?}"
        );
    }

    #[test]
    fn aimed_nudges_ask_for_the_hot_spots_once_per_violating_visit_and_move_a_hot_site() {
        let run = |aimed_nudges: f64| {
            let p = CountsMoves::new();
            let mut opt = Cooperative::new(CoopParams {
                aimed_nudges,
                focus: 0.0,
                ..CoopParams::DEFAULT
            });
            let out = solve(
                &p,
                &mut opt,
                Budget::evaluations(3000),
                &mut rng_from_seed(3),
                &mut |_| {},
            );
            // The hot spots are evaluations: the budget holds them too.
            assert_eq!(out.evaluations, 3000);
            let asked = p.asked.into_inner().expect("not poisoned");
            let spots = p.spots.into_inner().expect("not poisoned");
            let looks: usize = spots.iter().sum();
            assert_eq!(
                p.evaluated.into_inner() + looks as u64,
                out.evaluations,
                "every evaluation made, and every look, counted once"
            );
            (asked, spots, p.sites.into_inner().expect("not poisoned"))
        };
        let (asked, spots, sites) = run(0.0);
        assert_eq!(spots, vec![0; 4]);
        assert!(sites.iter().all(Option::is_none) && asked[3] > 0);
        let (asked, spots, sites) = run(1.0);
        assert_eq!(spots[..3], [0, 0, 0], "{spots:?}");
        let per_visit = CoopParams::DEFAULT.nudges;
        // One look per visit (the last visit may be cut short by the budget).
        assert!(
            spots[3] > 0 && asked[3].abs_diff(per_visit * spots[3]) <= per_visit,
            "{asked:?} {spots:?}"
        );
        assert!(sites.iter().all(|s| *s == Some(2)), "{sites:?}");
        let (_, _, sites) = run(0.5);
        let hot = sites.iter().filter(|s| s.is_some()).count();
        assert!(
            sites.iter().all(|s| s.is_none() || *s == Some(2)) && hot > 0 && hot < sites.len(),
            "{sites:?}"
        );
    }

    #[test]
    fn a_problem_without_hot_spots_spends_no_evaluation_on_them() {
        let run = |aimed_nudges: f64| {
            let mut opt = Cooperative::new(CoopParams {
                aimed_nudges,
                ..CoopParams::DEFAULT
            });
            // A block in violation, so nudges (and their aim) are asked for, but neither
            // nudges nor hot spots of its own.
            let p = CountsMoves::new().inner;
            let mut trace = Vec::new();
            let out = solve(
                &p,
                &mut opt,
                Budget::evaluations(2000),
                &mut rng_from_seed(4),
                &mut |s| trace.push((s.evaluations, s.best_cost.to_bits())),
            );
            (out.best_x, trace)
        };
        assert_eq!(run(1.0), run(0.0));
    }

    #[test]
    fn shifted_copies_come_after_a_round_without_progress_for_the_violating_block() {
        let asked = |shifted_copies: bool, evaluations: u64| {
            let p = CountsMoves::new();
            let mut opt = Cooperative::new(CoopParams {
                shifted_copies,
                ..CoopParams::DEFAULT
            });
            let _ = solve(
                &p,
                &mut opt,
                Budget::evaluations(evaluations),
                &mut rng_from_seed(3),
                &mut |_| {},
            );
            p.copies.into_inner().expect("not poisoned")
        };
        assert!(asked(false, 6000).is_empty());
        // A round visits the four blocks, 100 evaluations a visit: none has ended yet.
        assert!(asked(true, 300).is_empty());
        let on = asked(true, 6000);
        assert!(!on.is_empty());
        assert!(
            on.iter().all(|&(b, d)| b == 3 && d < 3),
            "only the violating block, from the others: {on:?}"
        );
    }

    #[test]
    fn an_unvalidated_population_of_zero_does_not_panic() {
        let p = Constrained(vec![Bound::new(-5.0, 5.0); 6]);
        let mut opt = Cooperative::new(CoopParams {
            population: 0,
            ..CoopParams::DEFAULT
        });
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(200),
            &mut rng_from_seed(1),
            &mut |_| {},
        );
        assert_eq!(out.evaluations, 200);
        assert!(out.best.cost.is_finite());
    }

    #[test]
    fn finds_the_constrained_optimum_block_by_block() {
        let p = Constrained(vec![Bound::new(-5.0, 5.0); 9]);
        let mut opt = Cooperative::new(CoopParams::DEFAULT);
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(6000),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        assert!(out.best.feasible(), "{:?}", out.best);
        // Optimum: x_0 = 1, the rest 0, cost 1.
        assert!((out.best.cost - 1.0).abs() < 1e-2, "{}", out.best.cost);
        assert_eq!(out.evaluations, 6000);
    }

    /// The constraint of [`Constrained`] left out of the cost, so only the comparison can
    /// see it.
    struct Unpenalised(Vec<Bound>);

    impl Problem for Unpenalised {
        fn bounds(&self) -> &[Bound] {
            &self.0
        }
        fn evaluate(&self, x: &[f64]) -> Evaluation {
            Evaluation::new(x.iter().map(|v| v * v).sum(), (1.0 - x[0]).max(0.0))
        }
        fn block_size(&self) -> usize {
            3
        }
    }

    #[test]
    fn without_feasibility_first_the_search_follows_the_cost_alone() {
        let p = Unpenalised(vec![Bound::new(-5.0, 5.0); 6]);
        let run = |feasibility_first: bool| {
            let mut opt = Cooperative::new(CoopParams {
                feasibility_first,
                ..CoopParams::DEFAULT
            });
            solve(
                &p,
                &mut opt,
                Budget::evaluations(3000),
                &mut rng_from_seed(5),
                &mut |_| {},
            )
            .best
        };
        assert!(run(true).feasible());
        let blind = run(false);
        assert!(!blind.feasible() && blind.cost < 0.1, "{blind:?}");
    }

    #[test]
    fn each_ablation_switch_changes_the_search_and_still_runs() {
        let p = Constrained(vec![Bound::new(-5.0, 5.0); 9]);
        let run = |params: CoopParams| {
            let mut opt = Cooperative::new(params);
            solve(
                &p,
                &mut opt,
                Budget::evaluations(3000),
                &mut rng_from_seed(5),
                &mut |_| {},
            )
        };
        let base = run(CoopParams::DEFAULT);
        for off in [
            CoopParams {
                adaptive_spread: false,
                ..CoopParams::DEFAULT
            },
            CoopParams {
                decompose: false,
                ..CoopParams::DEFAULT
            },
        ] {
            let out = run(off);
            assert_eq!(out.evaluations, 3000, "{off:?}");
            assert!(out.best.cost.is_finite(), "{off:?}");
            assert_ne!(out.best_x, base.best_x, "{off:?} searched the same way");
        }
    }
}
