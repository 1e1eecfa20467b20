//! The summary of an experiment (`summary.json`, `.md`, `.csv`): per scenario and method
//! the feasible share, cost statistics and tests ([`crate::scenario_summary`]), and, over a
//! suite of instances, the methods ranked across them ([`crate::ranking`]).
//!
//! Computed from records sorted by run identity, so it is the same whatever the thread count
//! or shard layout that produced them. Timings are the one thing that differs between two
//! executions of the same experiment; they appear in `summary.md` and `summary.csv` but not
//! in `summary.json`, which is therefore identical for identical seeds.

use std::fmt::Write as _;

use serde::{Deserialize, Serialize};
use swarmplan_core::feasibility::FeasibilityProfile;

use crate::ranking::{rank_across_instances, SuiteRanking};
use crate::record::RunRecord;
pub use crate::scenario_summary::{
    reference_method, summarize_scenario, GroupSummary, ScenarioSummary, Versus,
    NEAR_MISS_VIOLATIONS,
};

/// The summary of an experiment's records (written as `summary.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ExperimentSummary {
    /// The experiment's master seed.
    pub master_seed: u64,
    /// Number of run records summarised.
    pub records: usize,
    /// The feasibility profiles of the records (one, unless folders were mixed).
    #[serde(default)]
    pub profiles: Vec<FeasibilityProfile>,
    /// One per (scenario, parameter set), sorted by scenario, then parameter set.
    pub scenarios: Vec<ScenarioSummary>,
    /// Across the instances of a suite, per parameter set (none for a single scenario).
    #[serde(default)]
    pub rankings: Vec<SuiteRanking>,
}

/// Summarises records (any order).
#[must_use]
pub fn summarize_records(master_seed: u64, records: &[RunRecord]) -> ExperimentSummary {
    let mut sorted: Vec<&RunRecord> = records.iter().collect();
    sorted.sort_by_key(|r| r.key());
    let mut profiles: Vec<FeasibilityProfile> = records.iter().map(|r| r.profile).collect();
    profiles.sort_by_key(|p| p.name());
    profiles.dedup();
    let mut cells: Vec<(String, String)> = sorted
        .iter()
        .map(|r| (r.scenario.clone(), r.param_set.clone()))
        .collect();
    cells.dedup();
    let mut scenarios = Vec::new();
    for (scenario, set) in cells {
        let mine: Vec<&RunRecord> = sorted
            .iter()
            .filter(|r| r.scenario == scenario && r.param_set == set)
            .copied()
            .collect();
        scenarios.push(summarize_scenario(scenario, set, &mine));
    }
    let rankings = rank_across_instances(&scenarios);
    ExperimentSummary {
        master_seed,
        records: records.len(),
        profiles,
        scenarios,
        rankings,
    }
}

fn num(v: Option<f64>) -> String {
    match v {
        Some(x) if x.is_finite() => format!("{x:.1}"),
        Some(x) if x.is_nan() => "nan".into(),
        Some(_) => "inf".into(),
        None => "-".into(),
    }
}

fn p(v: f64) -> String {
    if v < 1e-4 {
        format!("{v:.1e}")
    } else {
        format!("{v:.4}")
    }
}

/// `summary.md`: a table per scenario laid out like the paper's Tables 4-5, then the full
/// statistics and the tests.
#[must_use]
pub fn markdown(s: &ExperimentSummary) -> String {
    let mut out = String::new();
    let profiles: Vec<&str> = s.profiles.iter().map(|p| p.name()).collect();
    let _ = writeln!(out, "# Experiment summary\n\nMaster seed {}, {} runs recorded, feasibility profile {} (FR counts {}). Costs are per UAV (total / n), as in the paper.\n", s.master_seed, s.records, profiles.join(" + "), if s.profiles == [FeasibilityProfile::Paper] { "threat, terrain, turn and energy violations only; the others are in the cost" } else { "every hard constraint" });
    for sc in &s.scenarios {
        let _ = writeln!(
            out,
            "## {} (parameter set `{}`)\n",
            sc.scenario, sc.param_set
        );
        let _ = writeln!(
            out,
            "| Method | Worst | Optimal | Mean | FR(%) |\n|---|---|---|---|---|"
        );
        for g in &sc.groups {
            let c = g.cost.as_ref();
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {:.1} |",
                g.method,
                num(c.map(|c| c.max)),
                num(c.map(|c| c.min)),
                num(c.map(|c| c.mean)),
                g.fr_percent
            );
        }
        let _ = writeln!(out, "\n| method | optimizer | encoding | init | runs | feasible | near misses (<= 2 violations) | median | std | feasible runs: worst / best / mean / median / std | mean evaluations | median evaluations to the first feasible plan | mean s/run |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|");
        for g in &sc.groups {
            let c = g.cost.as_ref();
            let f = g.cost_feasible.as_ref();
            let _ = writeln!(
                out,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} / {} / {} / {} | {:.0} | {} | {:.3} |",
                g.method,
                g.optimizer,
                g.encoding,
                g.init,
                g.runs,
                g.feasible,
                g.near_misses,
                num(c.map(|c| c.median)),
                num(c.map(|c| c.std)),
                num(f.map(|c| c.max)),
                num(f.map(|c| c.min)),
                num(f.map(|c| c.mean)),
                num(f.map(|c| c.median)),
                num(f.map(|c| c.std)),
                g.mean_evaluations,
                num(g.median_first_feasible_evaluations),
                g.mean_seconds
            );
        }
        if let Some(rf) = sc.reference {
            let _ = writeln!(out, "\nAgainst {rf}: Wilcoxon rank-sum on cost (two-sided, Holm-adjusted over the methods; p exact for samples without ties and n1 n2 <= 2500, else the normal approximation with tie correction, as the column says) and Fisher's exact test on FR.\n\n| method | U | p | p from | p (Holm) | Fisher p (FR) |\n|---|---|---|---|---|---|");
            for g in &sc.groups {
                if let Some(v) = &g.versus_reference {
                    let _ = writeln!(
                        out,
                        "| {} | {:.1} | {} | {} | {} | {} |",
                        g.method,
                        v.rank_sum_u,
                        p(v.rank_sum_p),
                        v.rank_sum_method.name(),
                        p(v.rank_sum_p_holm),
                        p(v.fisher_p)
                    );
                }
            }
        }
        if let Some(fr) = &sc.friedman {
            let ranks: Vec<String> = sc
                .groups
                .iter()
                .zip(&fr.mean_ranks)
                .map(|(g, r)| format!("{} {r:.2}", g.method))
                .collect();
            let _ = writeln!(
                out,
                "\nFriedman test over {} methods: chi2 = {:.3}, df = {}, p = {}. Average ranks (1 = best): {}. {}.\n",
                sc.groups.len(),
                fr.statistic,
                fr.df,
                p(fr.p_value),
                ranks.join(", "),
                sc.friedman_note
            );
        } else {
            let _ = writeln!(out, "\n{}.\n", sc.friedman_note);
        }
    }
    for r in &s.rankings {
        ranking_markdown(&mut out, r);
    }
    out
}

/// The across-instances section of `summary.md`.
fn ranking_markdown(out: &mut String, r: &SuiteRanking) {
    let _ = writeln!(
        out,
        "## Across {} instances (parameter set `{}`)\n\nPer instance, each method is scored by its FR first and its median cost per UAV over all runs second, and ranked (1 = best, ties share the mean rank); the instances are the blocks of Friedman's test.{}\n",
        r.instances.len(),
        r.param_set,
        if r.left_out.is_empty() {
            String::new()
        } else {
            format!(" Left out (some method has no run there): {}.", r.left_out.join(", "))
        }
    );
    let mut order: Vec<usize> = (0..r.methods.len()).collect();
    if let Some(f) = &r.friedman {
        order.sort_by(|&a, &b| f.mean_ranks[a].total_cmp(&f.mean_ranks[b]));
    }
    let _ = writeln!(
        out,
        "| method | average rank | instances won | mean FR(%) |\n|---|---|---|---|"
    );
    for &j in &order {
        let rank = r
            .friedman
            .as_ref()
            .map_or("-".into(), |f| format!("{:.2}", f.mean_ranks[j]));
        let _ = writeln!(
            out,
            "| {} | {rank} | {} | {:.1} |",
            r.methods[j], r.wins[j], r.mean_fr_percent[j]
        );
    }
    match &r.friedman {
        Some(f) => {
            let _ = writeln!(
                out,
                "\nFriedman test over {} instances and {} methods: chi2 = {:.3}, df = {}, p = {}.\n",
                r.instances.len(),
                r.methods.len(),
                f.statistic,
                f.df,
                p(f.p_value)
            );
        }
        None => {
            let _ = writeln!(
                out,
                "\nNo Friedman test (needs two instances and no NaN).\n"
            );
        }
    }
    if !r.pairs.is_empty() {
        let _ = writeln!(out, "Pairwise post-hoc test on the average ranks (Demšar 2006), two-sided, Holm-adjusted over all {} pairs; in each pair the first method has the better (lower) average rank, z = rank difference / SE.\n\n| pair | z | p | p (Holm) |\n|---|---|---|---|", r.pairs.len());
        let mut pairs: Vec<_> = r.pairs.iter().collect();
        pairs.sort_by(|a, b| a.p_holm.total_cmp(&b.p_holm));
        for t in pairs {
            let (better, worse) = if t.z <= 0.0 { (t.a, t.b) } else { (t.b, t.a) };
            let _ = writeln!(
                out,
                "| {} vs {} | {:.2} | {} | {} |",
                r.methods[better],
                r.methods[worse],
                t.z.abs(),
                p(t.p_value),
                p(t.p_holm)
            );
        }
    }
    let head: Vec<String> = order.iter().map(|&j| r.methods[j].to_string()).collect();
    let _ = writeln!(
        out,
        "\nPer instance, FR(%) / median cost per UAV:\n\n| instance | {} |\n|---|{}",
        head.join(" | "),
        "---|".repeat(order.len())
    );
    for i in &r.instances {
        let cells: Vec<String> = order
            .iter()
            .map(|&j| format!("{:.0} / {}", i.fr_percent[j], num(Some(i.median_cost[j]))))
            .collect();
        let _ = writeln!(out, "| {} | {} |", i.scenario, cells.join(" | "));
    }
    out.push('\n');
}

/// `summary.csv`: one row per scenario, parameter set and method.
#[must_use]
pub fn csv(s: &ExperimentSummary) -> String {
    let mut out = String::from("scenario,param_set,method,optimizer,encoding,init,runs,feasible,near_misses,fr_percent,worst,best,mean,median,std,feasible_worst,feasible_best,feasible_mean,feasible_median,feasible_std,mean_evaluations,median_first_feasible_evaluations,mean_seconds,rank_sum_p,rank_sum_p_holm,fisher_p\n");
    let opt = |v: Option<f64>| {
        v.map_or(String::new(), |x| {
            if x.is_finite() {
                x.to_string()
            } else {
                "inf".into()
            }
        })
    };
    for sc in &s.scenarios {
        for g in &sc.groups {
            let c = g.cost.as_ref();
            let f = g.cost_feasible.as_ref();
            let v = g.versus_reference.as_ref();
            let _ = writeln!(
                out,
                "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
                sc.scenario,
                sc.param_set,
                g.method,
                g.optimizer,
                g.encoding,
                g.init,
                g.runs,
                g.feasible,
                g.near_misses,
                g.fr_percent,
                opt(c.map(|c| c.max)),
                opt(c.map(|c| c.min)),
                opt(c.map(|c| c.mean)),
                opt(c.map(|c| c.median)),
                opt(c.map(|c| c.std)),
                opt(f.map(|c| c.max)),
                opt(f.map(|c| c.min)),
                opt(f.map(|c| c.mean)),
                opt(f.map(|c| c.median)),
                opt(f.map(|c| c.std)),
                g.mean_evaluations,
                opt(g.median_first_feasible_evaluations),
                g.mean_seconds,
                opt(v.map(|v| v.rank_sum_p)),
                opt(v.map(|v| v.rank_sum_p_holm)),
                opt(v.map(|v| v.fisher_p)),
            );
        }
    }
    out
}
