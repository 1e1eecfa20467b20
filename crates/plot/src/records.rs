//! Bench records grouped the way the bench figures compare them: one group per algorithm
//! (and per parameter set, when a scenario was run with more than one), in the order of
//! [`Algorithm::ALL`].

use swarmplan_core::optim::Algorithm;
use swarmplan_experiment::record::RunRecord;

/// The runs of one algorithm (and parameter set) on one scenario.
pub(crate) struct Group<'a> {
    pub label: String,
    pub runs: Vec<&'a RunRecord>,
}

/// Groups `records` of `scenario`.
pub(crate) fn groups<'a>(records: &'a [RunRecord], scenario: &str) -> Vec<Group<'a>> {
    let mine: Vec<&RunRecord> = records.iter().filter(|r| r.scenario == scenario).collect();
    let mut sets: Vec<&str> = mine.iter().map(|r| r.param_set.as_str()).collect();
    sets.sort_unstable();
    sets.dedup();
    let mut out = Vec::new();
    for alg in Algorithm::ALL {
        for set in &sets {
            let runs: Vec<&RunRecord> = mine
                .iter()
                .copied()
                .filter(|r| r.algorithm == alg && r.param_set == *set)
                .collect();
            if runs.is_empty() {
                continue;
            }
            let label = if sets.len() > 1 {
                format!("{alg}/{set}")
            } else {
                alg.to_string()
            };
            out.push(Group { label, runs });
        }
    }
    out
}

/// A recorded cost as a plotting value: the records store +inf as `f64::MAX` in diagnostic
/// fields, which is turned back into +inf here.
pub(crate) fn cost(v: f64) -> f64 {
    if v.is_nan() || v >= f64::MAX {
        f64::INFINITY
    } else {
        v
    }
}
