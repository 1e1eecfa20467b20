//! `plan()`: one planning run, the same run as the CLI's `plan` (same request, same
//! `run_attempts`), so a seed gives the CLI's plan.

use std::path::PathBuf;

use pyo3::prelude::*;
use serde_json::json;
use swarmplan_core::attempts::{run_attempts, MAX_ATTEMPTS};
use swarmplan_core::run::RunRequest;
use swarmplan_core::world::flight_margin::grown_world;
use swarmplan_experiment::settings::{Resolved, RunSettings};
use swarmplan_io::artifact::{ArtifactFiles, RunArtifact};
use swarmplan_io::convergence::ConvergenceRow;
use swarmplan_io::plan_file::plan_file;

use crate::errors::{bad, to_py};
use crate::{args, interrupt, scenario};

/// Plans `scenario` and returns JSON with `run` (the CLI's `run.json`), `plan` (its
/// `plan.json`), `convergence` (its `convergence.csv` rows), `uav_costs` (per row of
/// `convergence` and UAV), `verdict` (the verdict line `plan` prints), `outcome` (the line
/// `plan` prints after an infeasible verdict: `no plan exists: ...` or `none found: ...`;
/// null for a feasible plan), `notes`, and `margin_verdict` (with `flight_margin` > 0, the
/// verdict on the scenario tightened by it, which the search ran on; else null).
#[pyfunction]
#[pyo3(signature = (
    scenario="paper-case1", method="swarmplan", seed=None, evaluations=None, iterations=None,
    population=None, params=None, terrain=None, profile=None, time_limit=None,
    until_feasible=false, attempts=1, flight_margin=0.0
))]
#[allow(clippy::too_many_arguments)]
pub fn plan(
    py: Python<'_>,
    scenario: &str,
    method: &str,
    seed: Option<i128>,
    evaluations: Option<i128>,
    iterations: Option<i128>,
    population: Option<i128>,
    params: Option<PathBuf>,
    terrain: Option<PathBuf>,
    profile: Option<&str>,
    time_limit: Option<f64>,
    until_feasible: bool,
    attempts: i128,
    flight_margin: f64,
) -> PyResult<String> {
    let attempts: usize = args::positive("attempts", attempts)?;
    if attempts > MAX_ATTEMPTS {
        return Err(bad(format!(
            "attempts: expected 1 to {MAX_ATTEMPTS}, got {attempts}"
        )));
    }
    let method = args::method(method)?;
    let settings = RunSettings {
        iterations,
        evaluations,
        population,
        params,
        time_limit_s: time_limit,
        until_feasible,
    };
    // time_limit counts from here: loading, the route layer's checks and the search.
    let began = std::time::Instant::now();
    let Resolved { mut budget, params } =
        args::run_settings(&settings, method.optimizer.default_budget())?;
    budget.started = Some(began);
    let loaded = scenario::load(scenario, terrain, profile)?;
    let world = &loaded.world;
    let grown =
        grown_world(world, flight_margin).map_err(|e| bad(format!("flight_margin: {e}")))?;
    let searched_on = grown.as_ref().unwrap_or(world);
    let req = RunRequest {
        method,
        params,
        budget,
        seed: seed
            .map(|s| args::seed("seed", s))
            .transpose()?
            .unwrap_or(world.spec().planning.seed),
    };
    let made = interrupt::interruptible(py, |cancel| {
        let mut req = req.clone();
        req.budget.cancel = cancel;
        run_attempts(searched_on, &req, attempts, &mut |_, _| {}, &mut |_| {})
    })?;
    let (mut result, uav_trace) = (made.result, made.uav_trace);
    // With a margin: judged against the scenario as given, the margin's verdict beside it.
    let margin_verdict = grown.as_ref().map(|_| result.judge_on(world).verdict());
    let mut artifact = RunArtifact::new(
        world,
        &result,
        req.budget,
        req.params,
        ArtifactFiles::default(),
    );
    if attempts > 1 {
        artifact.attempts = made.records;
    }
    artifact.flight_margin = flight_margin;
    let convergence: Vec<ConvergenceRow> = result
        .outcome
        .trace
        .iter()
        .map(|r| ConvergenceRow::of(r, world.uav_count()))
        .collect();
    let out = json!({
        "run": artifact,
        "plan": plan_file(world, &result.plan),
        "convergence": convergence,
        "uav_costs": uav_trace.iter().map(|row| &row[..]).collect::<Vec<&[f64]>>(),
        "verdict": result.assessment.verdict(),
        "outcome": swarmplan_core::outcome::infeasible_outcome(world, &result.assessment),
        "notes": loaded.notes,
        "margin_verdict": margin_verdict,
    });
    serde_json::to_string(&out).map_err(to_py)
}
