//! `bench()`: an experiment matrix run by the same runner as the CLI's `bench` (parallel,
//! resumable, one record per run in `OUT/runs.jsonl`), returning the records.

use std::path::PathBuf;

use pyo3::prelude::*;
use swarmplan_experiment::matrix::{BudgetPolicy, ExperimentSpec, ParamSet};
use swarmplan_experiment::runner::{run_experiment, RunnerError, RunnerOptions};
use swarmplan_experiment::store::{other_builds_warning, StoreError};

use swarmplan_core::optim::cancel::Cancel;

use crate::args;
use crate::errors::{bad, message, to_py, with_advice};
use crate::interrupt;

/// Largest thread count accepted (as the CLI; held to the cores by the runner).
const MAX_THREADS: i128 = 4096;

/// Runs scenarios x methods x runs into `out` and returns every record of the folder as a
/// JSON line (the lines of `runs.jsonl`), sorted by run identity.
#[pyfunction]
#[pyo3(signature = (
    out, scenarios, methods, runs=1, seed=1, evaluations=None, iterations=None,
    budget="equal", population=None, params=None, terrain=None, profile=None, threads=0,
    resume=false
))]
#[allow(clippy::too_many_arguments)]
pub fn bench(
    py: Python<'_>,
    out: PathBuf,
    scenarios: Vec<String>,
    methods: Vec<String>,
    runs: i128,
    seed: i128,
    evaluations: Option<i128>,
    iterations: Option<i128>,
    budget: &str,
    population: Option<i128>,
    params: Option<PathBuf>,
    terrain: Option<PathBuf>,
    profile: Option<&str>,
    threads: i128,
    resume: bool,
) -> PyResult<Vec<String>> {
    let mut spec = ExperimentSpec::paper(args::seed("seed", seed)?);
    spec.runs = args::positive("runs", runs)?;
    spec.scenarios = scenarios;
    spec.methods = methods
        .iter()
        .map(|m| args::method(m))
        .collect::<PyResult<_>>()?;
    let fixed = iterations.is_some() || evaluations.is_some();
    spec.budget_policy = match budget {
        "equal" => BudgetPolicy::Equal,
        "paper" if fixed => {
            return Err(bad(
                "budget: `paper` gives each method its paper setting; it cannot be combined with iterations or evaluations",
            ))
        }
        "paper" => BudgetPolicy::Paper,
        other => {
            return Err(bad(format!(
                "budget: expected `equal` or `paper`, got `{other}`"
            )))
        }
    };
    if fixed {
        spec.budget = args::budget(iterations, evaluations, spec.budget)?;
    }
    if params.is_some() || population.is_some() {
        let name = if params.is_some() { "custom" } else { "paper" };
        spec.param_sets = vec![ParamSet {
            name: name.into(),
            params: args::params(params, population)?,
        }];
    }
    spec.terrain = terrain.map(|t| t.display().to_string());
    if let Some(p) = profile {
        spec.profile = args::profile(p)?;
    }
    if !(0..=MAX_THREADS).contains(&threads) {
        return Err(bad(format!(
            "threads: expected 0 (one per core) or at most {MAX_THREADS}, got {threads}"
        )));
    }
    spec.validate().map_err(to_py)?;
    let opts = RunnerOptions {
        threads: usize::try_from(threads).map_err(to_py)?,
        shard: None,
        resume,
        cancel: Cancel::NONE,
    };
    std::fs::create_dir_all(&out)
        .map_err(|e| bad(format!("{}: cannot create: {e}", out.display())))?;
    // As the CLI says it: runs of another build in the same folder (a RuntimeWarning).
    if let Some(text) = other_builds_warning(&out).map_err(to_py)? {
        let text = std::ffi::CString::new(with_advice(text, "another out keeps them apart"))
            .map_err(to_py)?;
        PyErr::warn(
            py,
            &py.get_type::<pyo3::exceptions::PyRuntimeWarning>(),
            &text,
            1,
        )?;
    }
    let outcome = interrupt::interruptible(py, |cancel| {
        let opts = RunnerOptions { cancel, ..opts };
        run_experiment(&spec, &out, opts, &mut |_| {}, &|_| {})
    })?
    .map_err(|e| bad(in_python_terms(&e)))?;
    outcome
        .records
        .iter()
        .map(|r| serde_json::to_string(r).map_err(to_py))
        .collect()
}

/// The runner's message with its advice (the part after the last `; `, which names the
/// CLI's flags) given in this function's arguments instead; the rest (folders, scenario
/// names) as it is.
fn in_python_terms(e: &RunnerError) -> String {
    let advice = match e {
        RunnerError::Store(s) => match s {
            StoreError::Mismatch { .. } => {
                Some("use another out, or the same arguments with resume=True")
            }
            StoreError::Busy { .. } => Some("wait for it to finish, or use another out"),
            StoreError::NotEmpty { .. } => {
                Some("pass resume=True to continue them, or choose another out")
            }
            StoreError::ScenarioChanged { .. } => Some("restore it, or use another out"),
            _ => None,
        },
        _ => None,
    };
    let text = message(e);
    match advice {
        Some(advice) => with_advice(text, advice),
        None => text,
    }
}
