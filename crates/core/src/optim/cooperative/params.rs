//! The cooperative optimizer's parameters: sizes, the inner PSO's constants and the
//! switches of each of its ideas (docs/results.md measures each one as an ablation).

use serde::{Deserialize, Serialize};

use super::switches::{self, Blocks, Comparison, Spread, Transplant, Updates};
use super::Cooperative;
use crate::optim::config::{check, ParamsError};
use crate::optim::Optimizer;

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
    /// How candidates are compared: Deb's feasibility rules or penalised cost alone (an
    /// ablation, docs/results.md). Old spelling `feasibility_first = true / false`.
    #[serde(alias = "feasibility_first", deserialize_with = "switches::read")]
    pub compare: Comparison,
    /// Adapt each block's spread per visit, or keep `perturbation` (an ablation). Old
    /// spelling `adaptive_spread`.
    #[serde(alias = "adaptive_spread", deserialize_with = "switches::read")]
    pub spread: Spread,
    /// Search one UAV at a time, or the whole plan as one block (an ablation: a restarting
    /// PSO on the joint vector). Old spelling `decompose`.
    #[serde(alias = "decompose", deserialize_with = "switches::read")]
    pub blocks: Blocks,
    /// Share of the visits of an infeasible context that go to a UAV holding a violation
    /// (its own, or its half of a separation), taken in turn; the other visits continue
    /// the cyclic order over every UAV, so a UAV whose move would repair another's violation
    /// (a relay) is still searched. 0 visits every UAV in turn, feasible or not (1.0;
    /// measured in docs/results.md: on the five hardest 20-UAV instances 22 of 25 runs
    /// feasible at 1.0, 20 at 0.5, 12 at 0; level on the paper cases).
    pub focus: f64,
    /// Evaluate a sub-swarm's particles together, in parallel, against the gbest and
    /// context of the step's start, or one after the other with gbest and the context
    /// following each (the method as measured before issue 12). Either way a run is the same
    /// for any thread count. Old spelling `synchronous = true / false`.
    #[serde(alias = "synchronous", deserialize_with = "switches::read")]
    pub updates: Updates,
    /// In a visit of a block that holds a violation of an infeasible context, make one
    /// particle a *transplant*: another block's path (one without a violation of its own,
    /// drawn at random, if any), perturbed like the others. UAVs of one fleet fly from
    /// nearby starts to one goal, so a way round the threats that one UAV has found is
    /// usually open to another whose own sector search is stuck on the wrong side.
    ///
    /// With [`Transplant::ShiftedWhenStuck`], once a round has passed without progress (an
    /// infeasible context whose violation did not drop by `restart_drop`), the transplant is
    /// a *shifted copy* ([`crate::optim::Evaluator::shifted_copy`]): the donor's path moved
    /// as a whole, in a planning problem by 1.5 to 3 separation distances sideways in a
    /// random direction and a Gaussian of one in height. Under common arrival the copy and
    /// its donor are at the same share of their routes at every instant, so they fly side
    /// by side about that far apart, where a perturbed copy flies on top of its donor.
    /// Measured in docs/results.md ("Shifted copies"; there `shifted_copies = false` is
    /// `"perturbed"`).
    #[serde(deserialize_with = "switches::read")]
    pub transplant: Transplant,
    /// Particles of a visit of a violating block (infeasible context) that are the
    /// problem's local move of the context's block ([`crate::optim::Evaluator::nudge`]; in a planning
    /// problem one free waypoint moved by a few separation distances), taken from the
    /// perturbed ones (4: at the default population all of them but one, or two when there
    /// is no transplant; 0: none, and no random draw for them). Measured in
    /// docs/results.md ("Nudges").
    pub nudges: usize,
    /// Share of the nudges aimed at where the block's violations are
    /// ([`crate::optim::Evaluator::hot_spots`]: in a planning problem the free waypoints next to the
    /// UAV's violations, and its departure delay when delays are free, drawn in proportion
    /// to their measure); the rest, and every nudge when the hot spots weigh nothing, move a
    /// waypoint drawn uniformly. Finding the hot spots assesses the context once per visit,
    /// counted as an evaluation. 0: no aim, and neither that evaluation nor a random draw
    /// for it.
    pub aimed_nudges: f64,
}

impl CoopParams {
    /// The defaults (one place, used by `Default` and serde).
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
        compare: Comparison::FeasibilityFirst,
        spread: Spread::Adaptive,
        blocks: Blocks::PerUav,
        focus: 1.0,
        updates: Updates::Synchronous,
        transplant: Transplant::ShiftedWhenStuck,
        nudges: 4,
        aimed_nudges: 1.0,
    };

    /// Checks every field that has limits; the error names the first bad one.
    pub fn validate(&self) -> Result<(), ParamsError> {
        check(
            crate::optim::config::POPULATION_RANGE.contains(&self.population),
            "population",
            crate::optim::config::POPULATION_EXPECTED,
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

impl crate::optim::config::OptimizerConfig for CoopParams {
    fn population(&self) -> usize {
        self.population
    }

    fn set_population(&mut self, n: usize) {
        self.population = n;
    }

    fn build(&self) -> Box<dyn Optimizer> {
        Box::new(Cooperative::new(*self))
    }

    /// `coop`'s iterations are sub-swarm steps of 10 evaluations, so its default budget is
    /// the paper's mean evaluations instead of 200 iterations.
    fn default_budget(&self) -> crate::optim::Budget {
        crate::optim::Budget::evaluations(crate::optim::PAPER_EVALUATIONS)
    }
}
