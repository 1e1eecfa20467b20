//! Bench records grouped the way the bench figures compare them: one group per method
//! (and per parameter set, when a scenario was run with more than one), presets in the
//! order of [`PRESETS`] (the paper's table order), other methods after them by label.

use swarmplan_core::method::{Method, PRESETS};
use swarmplan_experiment::record::RunRecord;

/// Where `m` goes in the figures: presets first, in table order.
fn order(m: &Method) -> (usize, String) {
    let at = PRESETS.iter().position(|p| p.method == *m);
    (at.unwrap_or(PRESETS.len()), m.label())
}

/// The runs of one method (and parameter set) on one scenario.
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
    let mut methods: Vec<Method> = mine.iter().map(|r| r.method).collect();
    methods.sort_by_key(order);
    methods.dedup();
    let mut out = Vec::new();
    for alg in methods {
        for set in &sets {
            let runs: Vec<&RunRecord> = mine
                .iter()
                .copied()
                .filter(|r| r.method == alg && r.param_set == *set)
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
