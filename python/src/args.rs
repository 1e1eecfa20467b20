//! Arguments checked the way the CLI checks its flags: each error names the argument, says
//! what was expected and what was given.

use std::path::PathBuf;

use pyo3::PyResult;
use swarmplan_core::feasibility::FeasibilityProfile;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_experiment::settings::{Resolved, RunSettings};

use crate::errors::bad;

/// A seed in [0, 2^64 - 1].
pub fn seed(name: &str, v: i128) -> PyResult<u64> {
    u64::try_from(v).map_err(|_| {
        bad(format!(
            "{name}: expected a whole number in [0, 2^64 - 1], got {v}"
        ))
    })
}

/// A count of at least 1 that fits `T`.
pub fn positive<T: TryFrom<i128>>(name: &str, v: i128) -> PyResult<T> {
    if v < 1 {
        return Err(bad(format!("{name}: expected at least 1, got {v}")));
    }
    T::try_from(v).map_err(|_| bad(format!("{name}: {v} is too large")))
}

/// A method label (`swarmplan`, `gwo`, `pso/spherical/line`, ...).
pub fn method(v: &str) -> PyResult<Method> {
    v.parse()
        .map_err(|e: swarmplan_core::method::UnknownMethod| bad(format!("method: {e}")))
}

/// `strict` or `paper`.
pub fn profile(v: &str) -> PyResult<FeasibilityProfile> {
    FeasibilityProfile::from_name(v)
        .ok_or_else(|| bad(format!("profile: expected `strict` or `paper`, got `{v}`")))
}

/// The budget of `iterations` and / or `evaluations`, or `default` when neither is given
/// (checked as the CLI checks them: [`RunSettings::budget`]).
pub fn budget(
    iterations: Option<i128>,
    evaluations: Option<i128>,
    default: Budget,
) -> PyResult<Budget> {
    RunSettings {
        iterations,
        evaluations,
        ..RunSettings::default()
    }
    .budget(default)
    .map_err(|e| bad(e.to_string()))
}

/// Optimizer parameters from a TOML file (the CLI's `--params`), then `population`
/// ([`RunSettings::params`]).
pub fn params(path: Option<PathBuf>, population: Option<i128>) -> PyResult<OptimizerParams> {
    RunSettings {
        params: path,
        population,
        ..RunSettings::default()
    }
    .params()
    .map_err(|e| bad(e.to_string()))
}

/// The budget and parameters of one run, with its time limit and stop rule
/// ([`RunSettings::resolve`], as `plan` resolves its flags).
pub fn run_settings(settings: &RunSettings, default: Budget) -> PyResult<Resolved> {
    settings.resolve(default).map_err(|e| bad(e.to_string()))
}
