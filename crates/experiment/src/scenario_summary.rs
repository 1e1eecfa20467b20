//! What an experiment's records say of one scenario and parameter set: per method the
//! feasible share and cost statistics, and the tests that settle comparisons there
//! (rank-sum against DLS-SMPSO with Holm's correction, Fisher's exact test on feasibility,
//! Friedman's test with average ranks over runs as blocks). [`crate::ranking`] ranks methods
//! across a suite's scenarios from these; [`crate::summary`] puts both together.
//!
//! **Friedman's blocks.** Friedman's test ranks the methods within blocks, so a block must
//! pair something. Here a block is a run index k of one scenario: the matrix gives run k of
//! every method the same seed (common random numbers, [`crate::matrix`]). The summary checks
//! that (every method's record of block k carries the same seed) and lists the blocks it
//! used; blocks where a method is missing are left out, and if the seeds of a block differ
//! (records from another seeding scheme) no Friedman test is reported, with the reason.

use serde::{Deserialize, Serialize};
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::method::Method;
use swarmplan_core::optim::OptimizerKind;

use crate::record::RunRecord;
use crate::stats::{
    fisher_exact, friedman, holm, rank_sum, summarize, FriedmanTest, RankSumMethod, Summary,
};

/// One method (with one parameter set) on one scenario.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GroupSummary {
    /// The method's label (a preset name, or `optimizer/encoding/init`).
    pub method: Method,
    /// The method's optimizer.
    pub optimizer: OptimizerKind,
    /// The method's encoding.
    pub encoding: EncodingKind,
    /// The method's initialisation.
    pub init: InitKind,
    /// Name of the parameter set.
    pub param_set: String,
    /// Number of runs recorded.
    pub runs: usize,
    /// Number of feasible runs.
    pub feasible: usize,
    /// Feasibility ratio, percent.
    #[serde(with = "crate::stats::json_f64")]
    pub fr_percent: f64,
    /// Infeasible runs whose best plan has at most [`NEAR_MISS_VIOLATIONS`] hard violations.
    #[serde(default)]
    pub near_misses: usize,
    /// Cost per UAV over all runs.
    pub cost: Option<Summary>,
    /// Cost per UAV over feasible runs only.
    pub cost_feasible: Option<Summary>,
    /// Evaluations spent per run, mean.
    #[serde(with = "crate::stats::json_f64")]
    pub mean_evaluations: f64,
    /// Median, over the feasible runs that record it, of the evaluations spent when the
    /// best plan first became feasible (`plan --until-feasible` would stop there).
    #[serde(default)]
    #[serde(with = "crate::stats::json_f64::option")]
    pub median_first_feasible_evaluations: Option<f64>,
    /// Wall time per run (not in summary.json: it varies between executions).
    #[serde(skip)]
    #[serde(with = "crate::stats::json_f64")]
    pub mean_seconds: f64,
    /// Against the reference method (absent for the reference itself).
    pub versus_reference: Option<Versus>,
}

/// An infeasible run with at most this many hard violations (counted over UAVs and kinds)
/// is a near miss: a plan one or two local repairs away from flying.
pub const NEAR_MISS_VIOLATIONS: usize = 2;

/// Tests of one method against the reference (DLS-SMPSO).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Versus {
    /// Mann-Whitney U of this method's costs against the reference's.
    #[serde(with = "crate::stats::json_f64")]
    pub rank_sum_u: f64,
    /// Two-sided p-value of the rank-sum test.
    #[serde(with = "crate::stats::json_f64")]
    pub rank_sum_p: f64,
    /// Exact (small samples without ties) or normal approximation.
    pub rank_sum_method: RankSumMethod,
    /// Holm-adjusted over the methods of the scenario.
    #[serde(with = "crate::stats::json_f64")]
    pub rank_sum_p_holm: f64,
    /// Fisher's exact test on (feasible, infeasible) counts.
    #[serde(with = "crate::stats::json_f64")]
    pub fisher_p: f64,
}

/// Everything about one scenario and parameter set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScenarioSummary {
    /// The scenario, as the experiment names it.
    pub scenario: String,
    /// Name of the parameter set.
    pub param_set: String,
    /// The method the others are tested against ([`reference_method`]), if it was run here.
    pub reference: Option<Method>,
    /// One per method, sorted by method.
    pub groups: Vec<GroupSummary>,
    /// Ranks the methods within blocks (run indices with a common seed).
    pub friedman: Option<FriedmanTest>,
    /// The run indices used as Friedman blocks.
    pub friedman_blocks: Vec<usize>,
    /// What the blocks are, or why there is no Friedman test.
    pub friedman_note: String,
}

/// The method others are compared with, when it is part of the experiment: DLS-SMPSO.
#[must_use]
pub fn reference_method() -> Method {
    Method::preset("dls-smpso").expect("dls-smpso is a preset")
}

/// The summary of one scenario and parameter set from its records (`mine`, sorted by run
/// identity): a group per method, each tested against the reference method when it ran.
#[must_use]
pub fn summarize_scenario(scenario: String, set: String, mine: &[&RunRecord]) -> ScenarioSummary {
    let mut algs: Vec<Method> = mine.iter().map(|r| r.method).collect();
    algs.dedup();
    let costs = |a: Method| -> Vec<f64> {
        mine.iter()
            .filter(|r| r.method == a)
            .map(|r| r.cost_per_uav)
            .collect()
    };
    let reference = Some(reference_method()).filter(|m| algs.contains(m));
    let mut groups: Vec<GroupSummary> =
        algs.iter().map(|&a| group_summary(a, &set, mine)).collect();
    if let Some(rf) = reference {
        test_against_reference(&mut groups, rf, &costs);
    }
    let (friedman, friedman_blocks, friedman_note) = friedman_over_runs(mine, &algs);
    ScenarioSummary {
        scenario,
        param_set: set,
        reference,
        groups,
        friedman,
        friedman_blocks,
        friedman_note,
    }
}

/// One method's group of records on one scenario and parameter set.
fn group_summary(a: Method, set: &str, mine: &[&RunRecord]) -> GroupSummary {
    let rs: Vec<&RunRecord> = mine.iter().filter(|r| r.method == a).copied().collect();
    let n = rs.len();
    let feasible = rs.iter().filter(|r| r.feasible).count();
    let near_misses = rs
        .iter()
        .filter(|r| !r.feasible && r.violations.values().sum::<usize>() <= NEAR_MISS_VIOLATIONS)
        .count();
    let all: Vec<f64> = rs.iter().map(|r| r.cost_per_uav).collect();
    let feas: Vec<f64> = rs
        .iter()
        .filter(|r| r.feasible)
        .map(|r| r.cost_per_uav)
        .collect();
    GroupSummary {
        method: a,
        optimizer: a.optimizer,
        encoding: a.encoding,
        init: a.init,
        param_set: set.to_owned(),
        runs: n,
        feasible,
        fr_percent: 100.0 * feasible as f64 / n as f64,
        near_misses,
        cost: summarize(&all),
        cost_feasible: summarize(&feas),
        mean_evaluations: rs.iter().map(|r| r.evaluations as f64).sum::<f64>() / n as f64,
        median_first_feasible_evaluations: summarize(
            &rs.iter()
                .filter(|r| r.feasible)
                .filter_map(|r| r.first_feasible_evaluations)
                .map(|e| e as f64)
                .collect::<Vec<_>>(),
        )
        .map(|s| s.median),
        mean_seconds: rs.iter().map(|r| r.seconds).sum::<f64>() / n as f64,
        versus_reference: None,
    }
}

/// Tests every group against the reference method `rf`'s: rank-sum on costs (Holm-adjusted
/// over the groups) and Fisher's exact test on feasibility.
fn test_against_reference(
    groups: &mut [GroupSummary],
    rf: Method,
    costs: &dyn Fn(Method) -> Vec<f64>,
) {
    let ref_costs = costs(rf);
    let ref_group = groups
        .iter()
        .find(|g| g.method == rf)
        .expect("reference present");
    let (rf_ok, rf_n) = (ref_group.feasible as u64, ref_group.runs as u64);
    let tests: Vec<(usize, f64, f64, RankSumMethod, f64)> = groups
        .iter()
        .enumerate()
        .filter(|(_, g)| g.method != rf)
        .filter_map(|(i, g)| {
            let t = rank_sum(&costs(g.method), &ref_costs)?;
            let f = fisher_exact(
                g.feasible as u64,
                (g.runs - g.feasible) as u64,
                rf_ok,
                rf_n - rf_ok,
            );
            Some((i, t.u, t.p_value, t.method, f))
        })
        .collect();
    let adjusted = holm(&tests.iter().map(|t| t.2).collect::<Vec<_>>());
    for ((i, u, p, m, f), ph) in tests.into_iter().zip(adjusted) {
        groups[i].versus_reference = Some(Versus {
            rank_sum_u: u,
            rank_sum_p: p,
            rank_sum_method: m,
            rank_sum_p_holm: ph,
            fisher_p: f,
        });
    }
}

/// Friedman's test over the run indices that every method has, each a block of common
/// random numbers; checks that the block's records share one seed.
fn friedman_over_runs(
    mine: &[&RunRecord],
    methods: &[Method],
) -> (Option<FriedmanTest>, Vec<usize>, String) {
    if methods.len() < 2 {
        return (None, Vec::new(), "one method: nothing to rank".into());
    }
    let of = |m: Method, run: usize| mine.iter().find(|r| r.method == m && r.run == run);
    let mut runs: Vec<usize> = mine.iter().map(|r| r.run).collect();
    runs.sort_unstable();
    runs.dedup();
    let common: Vec<usize> = runs
        .into_iter()
        .filter(|&run| methods.iter().all(|&m| of(m, run).is_some()))
        .collect();
    let mut blocks = Vec::with_capacity(common.len());
    for &run in &common {
        let recs: Vec<&RunRecord> = methods
            .iter()
            .filter_map(|&m| of(m, run))
            .copied()
            .collect();
        if recs.iter().any(|r| r.seed != recs[0].seed) {
            return (
                None,
                Vec::new(),
                format!("no Friedman test: the methods' runs {run} have different seeds, so run indices are not blocks"),
            );
        }
        blocks.push(recs.iter().map(|r| r.cost_per_uav).collect::<Vec<f64>>());
    }
    let note = format!(
        "blocks: {} run indices, each run with one seed shared by all {} methods (common random numbers)",
        common.len(),
        methods.len()
    );
    (friedman(&blocks), common, note)
}
