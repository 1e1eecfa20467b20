//! Methods ranked across the instances of a suite (summary.rs + ranking.rs).

use std::collections::BTreeMap;

use swarmplan_core::feasibility::FeasibilityProfile;
use swarmplan_core::method::Method;
use swarmplan_core::optim::OptimizerParams;
use swarmplan_experiment::record::RunRecord;
use swarmplan_experiment::summary::{markdown, summarize_records};

fn record(scenario: &str, method: &str, run: usize, cost: f64, feasible: bool) -> RunRecord {
    let m = Method::preset(method).expect("a preset");
    RunRecord {
        scenario: scenario.into(),
        param_set: "default".into(),
        method: m,
        optimizer: m.optimizer,
        encoding: m.encoding,
        init: m.init,
        run,
        master_seed: 1,
        seed: 10 + run as u64,
        params: OptimizerParams::default(),
        cost_total: cost * 2.0,
        cost_per_uav: cost,
        uav_costs: vec![cost, cost],
        terms: BTreeMap::new(),
        profile: FeasibilityProfile::Strict,
        feasible,
        violations: BTreeMap::new(),
        soft_violations: BTreeMap::new(),
        evaluations: 100,
        iterations: 2,
        seconds: 0.01,
        convergence: vec![cost],
        convergence_evaluations: vec![100],
        convergence_iterations: Vec::new(),
        first_feasible_evaluations: feasible.then_some(100),
    }
}

/// Four instances, three methods, two runs each. On every instance `qpso` flies most often;
/// `gwo` is the cheapest but never feasible; `spso` is in between on FR and dearest.
fn suite() -> Vec<RunRecord> {
    let mut out = Vec::new();
    for (i, sc) in ["a", "b", "c", "d"].into_iter().enumerate() {
        let base = 1000.0 * (i + 1) as f64;
        for run in 0..2 {
            out.push(record(sc, "qpso", run, base + 50.0, true));
            out.push(record(sc, "gwo", run, base, false));
            out.push(record(sc, "spso", run, base + 90.0, run == 0));
        }
    }
    // An instance only one method ran: left out of the ranking.
    out.push(record("e", "qpso", 0, 1.0, true));
    out
}

#[test]
fn methods_are_ranked_by_feasibility_then_median_cost_over_instances() {
    let s = summarize_records(1, &suite());
    assert_eq!(s.rankings.len(), 1);
    let r = &s.rankings[0];
    let names: Vec<String> = r.methods.iter().map(ToString::to_string).collect();
    let at = |m: &str| names.iter().position(|n| n == m).unwrap();
    assert_eq!(r.instances.len(), 4);
    assert_eq!(r.left_out, ["e"]);
    let f = r.friedman.as_ref().expect("a Friedman test");
    // The same order on every instance: ranks 1, 2, 3 exactly.
    assert_eq!(f.mean_ranks[at("qpso")], 1.0);
    assert_eq!(f.mean_ranks[at("spso")], 2.0);
    assert_eq!(f.mean_ranks[at("gwo")], 3.0);
    // Q = 12 / (n k (k+1)) sum R_j^2 - 3 n (k+1) with n = 4, k = 3, R = 4, 8, 12: 8.
    assert!((f.statistic - 8.0).abs() < 1e-12, "{}", f.statistic);
    assert_eq!(r.wins[at("qpso")], 4);
    assert_eq!(r.wins[at("gwo")], 0);
    assert_eq!(r.mean_fr_percent[at("spso")], 50.0);
    // All three pairs, Holm-adjusted; qpso against gwo is the largest difference.
    assert_eq!(r.pairs.len(), 3);
    let big = r
        .pairs
        .iter()
        .find(|p| [p.a, p.b].contains(&at("qpso")) && [p.a, p.b].contains(&at("gwo")))
        .unwrap();
    let se = (3.0 * 4.0 / (6.0 * 4.0_f64)).sqrt();
    assert!((big.z.abs() - 2.0 / se).abs() < 1e-12);
    assert!(r.pairs.iter().all(|p| big.p_holm <= p.p_holm));

    let md = markdown(&s);
    assert!(md.contains("## Across 4 instances"), "{md}");
    assert!(
        md.contains("Left out (some method has no run there): e."),
        "{md}"
    );
    assert!(md.contains("| qpso | 1.00 | 4 | 100.0 |"), "{md}");
    // The JSON summary keeps the ranking (with infinite medians as strings).
    let json = serde_json::to_string(&s).unwrap();
    let back: swarmplan_experiment::summary::ExperimentSummary =
        serde_json::from_str(&json).unwrap();
    assert_eq!(back.rankings, s.rankings);
}

#[test]
fn one_instance_has_no_ranking_across_instances() {
    let one: Vec<RunRecord> = suite().into_iter().filter(|r| r.scenario == "a").collect();
    assert!(summarize_records(1, &one).rankings.is_empty());
}

#[test]
fn near_misses_are_infeasible_runs_with_at_most_two_violations() {
    let mut recs = Vec::new();
    for (run, count) in [1_usize, 2, 3].into_iter().enumerate() {
        let mut r = record("a", "qpso", run, 10.0, false);
        r.violations.insert("threat".into(), count);
        recs.push(r);
    }
    recs.push(record("a", "qpso", 3, 5.0, true));
    let s = summarize_records(1, &recs);
    let g = &s.scenarios[0].groups[0];
    assert_eq!((g.feasible, g.near_misses), (1, 2));
    assert!(markdown(&s).contains("| 4 | 1 | 2 |"), "{}", markdown(&s));
}
