//! One finished run as one flat JSON record (a line of `runs.jsonl`).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};
use swarmplan_core::cost::cost_per_uav;
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::feasibility::FeasibilityProfile;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{OptimizerKind, OptimizerParams};
use swarmplan_core::run::RunResult;

use crate::matrix::RunKey;

/// Everything a statistic or a figure may need about one run. Non-finite numbers are
/// written as everywhere else ([`swarmplan_core::json_f64`]: `"inf"`, `"-inf"`, `"nan"`);
/// records written before issue 44 (costs as `null`, other non-finite values capped at
/// `f64::MAX`) still read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    /// The scenario, as the experiment names it.
    pub scenario: String,
    /// Name of the parameter set.
    pub param_set: String,
    /// The method's label (a preset name, or `optimizer/encoding/init`).
    pub method: Method,
    /// The method's three parts, spelled out.
    pub optimizer: OptimizerKind,
    /// The method's encoding.
    pub encoding: EncodingKind,
    /// The method's initialisation.
    pub init: InitKind,
    /// Run index, 0-based, within its (scenario, parameter set, method).
    pub run: usize,
    /// The experiment's master seed.
    pub master_seed: u64,
    /// The run's seed: from the master seed, scenario, parameter set and run index, the
    /// same for every method ([`crate::matrix`]).
    pub seed: u64,
    /// The parameters of the run's parameter set.
    pub params: OptimizerParams,
    /// Total cost of the best plan (penalty included).
    #[serde(with = "cost_f64")]
    pub cost_total: f64,
    /// cost_total / number of UAVs, as the paper's tables report it.
    #[serde(with = "cost_f64")]
    pub cost_per_uav: f64,
    /// Each UAV's weighted terms summed (no penalty).
    #[serde(with = "swarmplan_core::json_f64::vec")]
    pub uav_costs: Vec<f64>,
    /// Weighted terms summed over UAVs, plus `penalty`.
    #[serde(with = "swarmplan_core::json_f64::map")]
    pub terms: BTreeMap<String, f64>,
    /// The feasibility profile the run was assessed under (`strict` in records written
    /// before profiles existed).
    #[serde(default)]
    pub profile: FeasibilityProfile,
    /// Whether the best plan has no hard violation under `profile`.
    pub feasible: bool,
    /// Number of hard violations of each kind in the best plan.
    pub violations: BTreeMap<String, usize>,
    /// Number of soft violations (cost only, under the `paper` profile) of each kind.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub soft_violations: BTreeMap<String, usize>,
    /// Evaluations spent, initialisation included.
    pub evaluations: u64,
    /// Iterations after initialisation (the last may have been cut short by the budget).
    pub iterations: usize,
    /// Wall time of the optimisation (assessment excluded), seconds; varies between
    /// executions.
    pub seconds: f64,
    /// Best cost per UAV after initialisation and after each iteration (past
    /// `TRACE_CAP` iterations, every s-th: `swarmplan_core::optim::thinned`).
    #[serde(with = "swarmplan_core::json_f64::vec")]
    pub convergence: Vec<f64>,
    /// Evaluations spent at each point of `convergence` (empty in records written before
    /// it existed), so methods with different evaluations per iteration compare over
    /// evaluations.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub convergence_evaluations: Vec<u64>,
    /// The iteration of each point of `convergence` when the run passed `TRACE_CAP`
    /// iterations and its trace was thinned (`swarmplan_core::optim::thinned`); empty when
    /// point k is iteration k.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub convergence_iterations: Vec<usize>,
    /// Evaluations spent when the best plan first became feasible (none if it never did,
    /// and in records written before it existed): where an anytime run
    /// (`plan --until-feasible`) would have stopped.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub first_feasible_evaluations: Option<u64>,
}

impl RunRecord {
    /// The run's identity in the matrix.
    #[must_use]
    pub fn key(&self) -> RunKey {
        RunKey {
            scenario: self.scenario.clone(),
            param_set: self.param_set.clone(),
            method: self.method,
            run: self.run,
        }
    }

    /// The record of `result`, run as `key` of an experiment with `master_seed`.
    #[must_use]
    pub fn new(
        key: &RunKey,
        master_seed: u64,
        params: OptimizerParams,
        result: &RunResult,
    ) -> Self {
        let a = &result.assessment;
        let uavs = a.per_uav.len();
        let t = a.term_totals();
        let mut terms: BTreeMap<String, f64> =
            t.iter().map(|(k, v)| (k.name().to_string(), v)).collect();
        terms.insert("penalty".into(), a.penalty);
        let (mut violations, mut soft_violations) = (BTreeMap::new(), BTreeMap::new());
        for v in a.violations.iter().flatten() {
            let map = if v.hard {
                &mut violations
            } else {
                &mut soft_violations
            };
            *map.entry(v.kind.name().to_string()).or_insert(0) += 1;
        }
        Self {
            scenario: key.scenario.clone(),
            param_set: key.param_set.clone(),
            method: key.method,
            optimizer: key.method.optimizer,
            encoding: key.method.encoding,
            init: key.method.init,
            run: key.run,
            master_seed,
            seed: result.seed,
            params,
            cost_total: a.total,
            cost_per_uav: cost_per_uav(a.total, uavs),
            uav_costs: a.per_uav.iter().map(|u| u.cost).collect(),
            terms,
            profile: a.profile,
            feasible: a.feasible(),
            violations,
            soft_violations,
            evaluations: result.outcome.evaluations,
            iterations: result.outcome.iterations,
            seconds: result.seconds,
            convergence: result
                .outcome
                .trace
                .iter()
                .map(|r| cost_per_uav(r.best_cost, uavs))
                .collect(),
            convergence_evaluations: result.outcome.trace.iter().map(|r| r.evaluations).collect(),
            convergence_iterations: thinned_iterations(&result.outcome.trace),
            first_feasible_evaluations: result
                .outcome
                .trace
                .iter()
                .find(|r| r.best_violation == 0.0)
                .map(|r| r.evaluations),
        }
    }
}

/// The iteration of each record of a thinned trace; empty when record k is iteration k.
fn thinned_iterations(trace: &[swarmplan_core::optim::IterationRecord]) -> Vec<usize> {
    if trace.iter().enumerate().all(|(k, r)| r.iteration == k) {
        Vec::new()
    } else {
        trace.iter().map(|r| r.iteration).collect()
    }
}

/// A cost: written as [`swarmplan_core::json_f64`] writes it; read also as records before
/// issue 44 wrote it (`null` for +inf).
mod cost_f64 {
    use serde::{Deserialize, Deserializer, Serializer};

    /// A value as [`swarmplan_core::json_f64`] reads it.
    #[derive(Deserialize)]
    struct Stored(#[serde(with = "swarmplan_core::json_f64")] f64);

    pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
        swarmplan_core::json_f64::serialize(v, s)
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        Ok(Option::<Stored>::deserialize(d)?.map_or(f64::INFINITY, |s| s.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarmplan_core::optim::IterationRecord;

    fn at(iterations: &[usize]) -> Vec<IterationRecord> {
        iterations
            .iter()
            .map(|&iteration| IterationRecord {
                iteration,
                evaluations: 10 * iteration as u64,
                best_cost: 1.0,
                best_violation: 0.0,
            })
            .collect()
    }

    #[test]
    fn costs_read_both_encodings_and_write_the_one_used_everywhere() {
        #[derive(serde::Serialize, serde::Deserialize)]
        struct Cost(#[serde(with = "cost_f64")] f64);
        assert_eq!(
            serde_json::to_string(&Cost(f64::INFINITY)).expect("writes"),
            "\"inf\""
        );
        assert_eq!(serde_json::to_string(&Cost(12.5)).expect("writes"), "12.5");
        for (old, want) in [
            ("null", f64::INFINITY),
            ("\"inf\"", f64::INFINITY),
            ("3", 3.0),
        ] {
            let Cost(v) = serde_json::from_str(old).expect("reads");
            assert_eq!(v, want, "{old}");
        }
    }

    #[test]
    fn a_record_names_its_iterations_only_when_the_trace_was_thinned() {
        assert!(thinned_iterations(&at(&[0, 1, 2, 3])).is_empty());
        assert!(thinned_iterations(&[]).is_empty());
        assert_eq!(thinned_iterations(&at(&[0, 4, 8, 9])), [0, 4, 8, 9]);
        assert_eq!(thinned_iterations(&at(&[0, 1, 3])), [0, 1, 3]);
    }
}
