//! Methods ranked across the instances of a suite: per instance one score per method, the
//! methods ranked within each instance, Friedman's test over the instances as blocks, and
//! the pairwise post-hoc test with Holm's correction (Demšar 2006; García & Herrera 2008).
//!
//! **The score of a method on an instance** is its feasibility ratio first and its median
//! cost per UAV over all runs second: a method that flies more often ranks better, and among
//! methods with the same FR the cheaper median wins. FR first because a planner's first job
//! is a plan that flies (and the paper's tables lead with FR); the median because it is
//! robust to the few runs whose penalised cost explodes. Ties (same FR, same median) share
//! their mean rank. Ranking within an instance removes its difficulty, so easy and hard
//! instances weigh the same, which is why Friedman's test is the test across instances
//! rather than one pooled over all runs.
//!
//! Only instances where every method of the parameter set was run are blocks; the others
//! are listed as left out. Per-scenario tests (runs as blocks) stay in [`crate::scenario_summary`].

use serde::{Deserialize, Serialize};
use swarmplan_core::method::Method;

use crate::scenario_summary::ScenarioSummary;
use crate::stats::{friedman, mean_rank_posthoc, FriedmanTest, PairwiseRankTest};

/// One instance of a suite: each method's FR, median cost per UAV and rank, in the order of
/// [`SuiteRanking::methods`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InstanceScores {
    /// The instance's scenario.
    pub scenario: String,
    /// Each method's feasibility ratio, percent.
    #[serde(with = "crate::stats::json_f64::vec")]
    pub fr_percent: Vec<f64>,
    /// Each method's median cost per UAV over all its runs (+inf when undefined).
    #[serde(with = "crate::stats::json_f64::vec")]
    pub median_cost: Vec<f64>,
    /// 1 = best on this instance; ties share their mean rank.
    #[serde(with = "crate::stats::json_f64::vec")]
    pub ranks: Vec<f64>,
}

/// The methods of one parameter set ranked over the instances that ran them all.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SuiteRanking {
    /// Name of the parameter set.
    pub param_set: String,
    /// The methods ranked, in the order of every per-method list here.
    pub methods: Vec<Method>,
    /// The instances used as blocks: those where every method was run.
    pub instances: Vec<InstanceScores>,
    /// Scenarios of this parameter set that lack a run of some method.
    pub left_out: Vec<String>,
    /// Mean FR over the instances, per method.
    #[serde(with = "crate::stats::json_f64::vec")]
    pub mean_fr_percent: Vec<f64>,
    /// Instances on which the method ranks first (alone or tied).
    pub wins: Vec<usize>,
    /// Over the instances as blocks; its mean ranks are the methods' average ranks.
    pub friedman: Option<FriedmanTest>,
    /// Every pair of methods, Holm-adjusted (empty without a Friedman test).
    pub pairs: Vec<PairwiseRankTest>,
}

/// One ranking per parameter set that has at least two instances and two methods.
#[must_use]
pub fn rank_across_instances(scenarios: &[ScenarioSummary]) -> Vec<SuiteRanking> {
    let mut sets: Vec<&str> = scenarios.iter().map(|s| s.param_set.as_str()).collect();
    sets.sort_unstable();
    sets.dedup();
    sets.into_iter()
        .filter_map(|set| {
            let mine: Vec<&ScenarioSummary> =
                scenarios.iter().filter(|s| s.param_set == set).collect();
            rank_one_set(set, &mine)
        })
        .collect()
}

fn rank_one_set(set: &str, scenarios: &[&ScenarioSummary]) -> Option<SuiteRanking> {
    let mut methods: Vec<Method> = Vec::new();
    for g in scenarios.iter().flat_map(|s| &s.groups) {
        if !methods.contains(&g.method) {
            methods.push(g.method);
        }
    }
    let mut instances = Vec::new();
    let mut left_out = Vec::new();
    for sc in scenarios {
        let of: Vec<_> = methods
            .iter()
            .map(|m| sc.groups.iter().find(|g| g.method == *m))
            .collect();
        if of.iter().any(Option::is_none) {
            left_out.push(sc.scenario.clone());
            continue;
        }
        let fr: Vec<f64> = of.iter().flatten().map(|g| g.fr_percent).collect();
        let median: Vec<f64> = of
            .iter()
            .flatten()
            .map(|g| g.cost.as_ref().map_or(f64::INFINITY, |c| c.median))
            .map(|c| if c.is_nan() { f64::INFINITY } else { c })
            .collect();
        let ranks = lexicographic_ranks(&fr, &median);
        instances.push(InstanceScores {
            scenario: sc.scenario.clone(),
            fr_percent: fr,
            median_cost: median,
            ranks,
        });
    }
    if instances.len() < 2 || methods.len() < 2 {
        return None;
    }
    let k = methods.len();
    let blocks: Vec<Vec<f64>> = instances.iter().map(|i| i.ranks.clone()).collect();
    let friedman = friedman(&blocks);
    let pairs = friedman
        .as_ref()
        .map(|f| mean_rank_posthoc(&f.mean_ranks, instances.len()))
        .unwrap_or_default();
    let n = instances.len() as f64;
    let mean_fr_percent = (0..k)
        .map(|j| instances.iter().map(|i| i.fr_percent[j]).sum::<f64>() / n)
        .collect();
    let wins = (0..k)
        .map(|j| {
            instances
                .iter()
                .filter(|i| i.ranks[j] <= i.ranks.iter().copied().fold(f64::INFINITY, f64::min))
                .count()
        })
        .collect();
    Some(SuiteRanking {
        param_set: set.to_owned(),
        methods,
        instances,
        left_out,
        mean_fr_percent,
        wins,
        friedman,
        pairs,
    })
}

/// Ranks by higher `fr` first, then lower `cost`; equal pairs share their mean rank.
fn lexicographic_ranks(fr: &[f64], cost: &[f64]) -> Vec<f64> {
    let key = |i: usize| (-fr[i], cost[i]);
    let mut order: Vec<usize> = (0..fr.len()).collect();
    order.sort_by(|&a, &b| {
        let (ka, kb) = (key(a), key(b));
        ka.0.total_cmp(&kb.0).then(ka.1.total_cmp(&kb.1))
    });
    let mut ranks = vec![0.0; fr.len()];
    let mut start = 0;
    while start < order.len() {
        let mut end = start + 1;
        while end < order.len() && key(order[end]) == key(order[start]) {
            end += 1;
        }
        let rank = (start + end + 1) as f64 / 2.0;
        for &i in &order[start..end] {
            ranks[i] = rank;
        }
        start = end;
    }
    ranks
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn feasibility_ranks_before_cost_and_ties_share() {
        // Method 2 is cheapest but flies less often; methods 0 and 3 tie on both.
        let r = lexicographic_ranks(&[90.0, 100.0, 80.0, 90.0], &[5.0, 9.0, 1.0, 5.0]);
        assert_eq!(r, [2.5, 1.0, 4.0, 2.5]);
        let r = lexicographic_ranks(&[0.0, 0.0], &[f64::INFINITY, 3.0]);
        assert_eq!(r, [2.0, 1.0]);
    }
}
