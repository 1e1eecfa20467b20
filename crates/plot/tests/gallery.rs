//! Renders every figure for the `paper-case1` scenario, for a person to look at (ignored by
//! default):
//!
//! ```sh
//! SWARMPLAN_GALLERY=/tmp/figs cargo test -p swarmplan-plot --test gallery -- --ignored
//! ```
//!
//! The plan is a decoded spherical vector spread over the bounds (no optimizer runs here)
//! unless `SWARMPLAN_GALLERY_PLAN` names a plan file written by `swarmplan plan`; the bench
//! figures use the records of the bench folder `SWARMPLAN_GALLERY_BENCH` when given, else a
//! few synthetic records.

use std::collections::BTreeMap;
use std::path::PathBuf;

use swarmplan_core::encoding::{build, EncodingKind};
use swarmplan_core::method::Method;
use swarmplan_core::optim::OptimizerParams;
use swarmplan_experiment::record::RunRecord;
use swarmplan_experiment::store::read_records;
use swarmplan_io::plan_file::{read_plan, Provenance};
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;
use swarmplan_plot::{
    bench_boxplots, comm_timeline, convergence_bench, convergence_run, top_view, view_3d, PerUav,
};

fn synthetic_records() -> Vec<RunRecord> {
    let mut out = Vec::new();
    for (a, alg) in Method::paper_methods().into_iter().enumerate() {
        for run in 0..12 {
            let spread = ((run * 7 + a * 3) % 11) as f64;
            let end = 5200.0 + 150.0 * a as f64 + 60.0 * spread;
            let penalised = (run + a) % 4 == 0;
            let cost = if penalised {
                end + 3.0e4 * (1.0 + spread)
            } else {
                end
            };
            let convergence = (0..=200)
                .map(|k| cost + 2.0e5 * (-(k as f64) / (10.0 + 3.0 * a as f64)).exp())
                .collect();
            out.push(RunRecord {
                scenario: "paper-case1".into(),
                param_set: "default".into(),
                method: alg,
                optimizer: alg.optimizer,
                encoding: alg.encoding,
                init: alg.init,
                run,
                master_seed: 1,
                seed: run as u64,
                params: OptimizerParams::default(),
                cost_total: cost * 5.0,
                cost_per_uav: cost,
                uav_costs: vec![cost; 5],
                terms: BTreeMap::new(),
                feasible: !penalised,
                profile: swarmplan_core::feasibility::FeasibilityProfile::Strict,
                violations: BTreeMap::new(),
                soft_violations: BTreeMap::new(),
                evaluations: 10_050,
                iterations: 200,
                seconds: 1.0,
                convergence,
                convergence_evaluations: Vec::new(),
                convergence_iterations: Vec::new(),
                first_feasible_evaluations: None,
            });
        }
    }
    out
}

#[test]
#[ignore = "writes figures for a person to look at; set SWARMPLAN_GALLERY"]
fn paper_case1_gallery() {
    let dir = PathBuf::from(std::env::var("SWARMPLAN_GALLERY").unwrap_or("/tmp/figs".into()));
    let loaded = load_spec("paper-case1").unwrap();
    let world = build_world(&loaded, None).unwrap();
    let (plan, what) = match std::env::var("SWARMPLAN_GALLERY_PLAN") {
        Ok(p) => (
            read_plan(p.as_ref(), &world, Provenance::MustMatch).unwrap(),
            "plan file",
        ),
        Err(_) => {
            let enc = build(EncodingKind::Spherical, &world);
            let x: Vec<f64> = enc
                .bounds()
                .iter()
                .enumerate()
                .map(|(k, b)| {
                    let f = ((k as f64 + 1.0) * 0.618_033_988_75).fract();
                    b.lo + (b.hi - b.lo) * (0.25 + 0.5 * f)
                })
                .collect();
            (enc.decode(&x), "decoded spherical vector")
        }
    };
    let title = format!("paper-case1: {what}, seed 1");
    top_view(&world, &plan, &title, dir.join("top_view")).unwrap();
    view_3d(&world, &plan, &title, dir.join("view_3d")).unwrap();
    comm_timeline(&world, &plan, &title, dir.join("comm_timeline")).unwrap();

    let trace: Vec<f64> = (0..=200)
        .map(|k| 26_000.0 + 1.0e6 * (-(k as f64) / 12.0).exp())
        .collect();
    let per_uav: Vec<Vec<f64>> = (0..5)
        .map(|i| trace.iter().map(|v| v * (0.16 + 0.02 * i as f64)).collect())
        .collect();
    convergence_run(
        None,
        &trace,
        PerUav::Columns(&per_uav),
        &title,
        dir.join("convergence_run"),
    )
    .unwrap();

    let records = match std::env::var("SWARMPLAN_GALLERY_BENCH") {
        Ok(b) => read_records(b.as_ref(), false).unwrap(),
        Err(_) => synthetic_records(),
    };
    convergence_bench(&records, "paper-case1", dir.join("convergence_bench")).unwrap();
    bench_boxplots(&records, "paper-case1", dir.join("bench_boxplots")).unwrap();
}
