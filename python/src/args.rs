//! Arguments checked the way the CLI checks its flags: each error names the argument, says
//! what was expected and what was given.

use std::path::PathBuf;

use pyo3::PyResult;
use swarmplan_core::feasibility::FeasibilityProfile;
use swarmplan_core::method::Method;
use swarmplan_core::optim::params::{POPULATION_EXPECTED, POPULATION_RANGE};
use swarmplan_core::optim::{Budget, OptimizerParams};

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

/// The budget of `iterations` and / or `evaluations`, or `default` when neither is given.
pub fn budget(
    iterations: Option<i128>,
    evaluations: Option<i128>,
    default: Budget,
) -> PyResult<Budget> {
    let iterations = iterations
        .map(|v| positive::<usize>("iterations", v))
        .transpose()?;
    let evaluations = evaluations
        .map(|v| positive::<u64>("evaluations", v))
        .transpose()?;
    Ok(match (iterations, evaluations) {
        (None, None) => default,
        (i, e) => Budget::new(i, e),
    })
}

/// Optimizer parameters from a TOML file (the CLI's `--params`), then `population`.
pub fn params(path: Option<PathBuf>, population: Option<i128>) -> PyResult<OptimizerParams> {
    let mut params = match &path {
        None => OptimizerParams::default(),
        Some(p) => {
            let text = std::fs::read_to_string(p)
                .map_err(|e| bad(format!("{}: cannot read: {e}", p.display())))?;
            toml::from_str(&text)
                .map_err(|e| bad(format!("{}: {}", p.display(), e.to_string().trim_end())))?
        }
    };
    if let Some(n) = population {
        let n = usize::try_from(n)
            .ok()
            .filter(|n| POPULATION_RANGE.contains(n))
            .ok_or_else(|| {
                bad(format!(
                    "population: expected {POPULATION_EXPECTED}, got {n}"
                ))
            })?;
        params.set_population(n);
    }
    params.validate().map_err(|e| {
        bad(format!(
            "{}: {e}",
            path.map_or("parameters".into(), |p| p.display().to_string())
        ))
    })?;
    Ok(params)
}
