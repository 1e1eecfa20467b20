//! A run's settings as a user gives them (flags of `plan` and `bench`, arguments of the
//! Python package), checked and resolved in one place.
//!
//! Why here and not in the commands: `plan`, `bench` and Python read the same settings and
//! must refuse the same bad values with the same words, and a command should not import
//! another. Each front end fills [`RunSettings`] from what it was given (counts as `i128`,
//! so a negative Python integer is refused here like a zero flag) and turns a
//! [`SettingsError`] into its own spelling of the field (`--time-limit` or `time_limit`).

use std::path::{Path, PathBuf};

use swarmplan_core::optim::params::{POPULATION_EXPECTED, POPULATION_RANGE};
use swarmplan_core::optim::{Budget, OptimizerParams};
use thiserror::Error;

/// The longest `time_limit` accepted, in seconds (about 115 days).
pub const MAX_TIME_LIMIT_S: f64 = 1e7;

/// A setting with a bad value. `field` is the setting's name in snake case (`time_limit`);
/// the CLI says it as a flag (`--time-limit`), Python as an argument.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
pub enum SettingsError {
    /// A value out of its range, said with what was expected.
    #[error("{field}: expected {expected}, got {got}")]
    Value {
        /// The setting's name in snake case.
        field: &'static str,
        /// What it must be.
        expected: String,
        /// What was given.
        got: String,
    },
    /// A whole number too large for its use.
    #[error("{field}: {got} is too large")]
    TooLarge {
        /// The setting's name in snake case.
        field: &'static str,
        /// What was given.
        got: i128,
    },
    /// A parameter file that cannot be read, parsed or validated; the message names it.
    #[error("{0}")]
    Params(String),
}

impl SettingsError {
    /// The setting the error is about (`None` for a parameter file, whose message names it).
    #[must_use]
    pub fn field(&self) -> Option<&'static str> {
        match self {
            Self::Value { field, .. } | Self::TooLarge { field, .. } => Some(field),
            Self::Params(_) => None,
        }
    }

    /// The message with the field spelled as a command-line flag (`--time-limit: ...`).
    #[must_use]
    pub fn as_flag(&self) -> String {
        let message = self.to_string();
        match self.field() {
            Some(field) => format!("--{}{}", field.replace('_', "-"), &message[field.len()..]),
            None => message,
        }
    }
}

/// The budget and optimizer settings of a run, unchecked.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RunSettings {
    /// Iterations per run (at least 1).
    pub iterations: Option<i128>,
    /// Evaluations per run (at least 1).
    pub evaluations: Option<i128>,
    /// Population size of every optimizer ([`POPULATION_RANGE`]).
    pub population: Option<i128>,
    /// A TOML file of optimizer parameters (sections by optimizer).
    pub params: Option<PathBuf>,
    /// Wall-clock bound on the run, in seconds, in (0, [`MAX_TIME_LIMIT_S`]].
    pub time_limit_s: Option<f64>,
    /// Stop at the first feasible plan.
    pub until_feasible: bool,
}

/// [`RunSettings`] checked: the budget and the optimizer parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    /// The budget, `default` where neither iterations nor evaluations were given.
    pub budget: Budget,
    /// Every optimizer's parameters, from the file and the population.
    pub params: OptimizerParams,
}

impl RunSettings {
    /// Checks every setting and resolves the budget (`default` when neither iterations nor
    /// evaluations are given) and the parameters; the first bad setting is the error.
    pub fn resolve(&self, default: Budget) -> Result<Resolved, SettingsError> {
        let params = self.params()?;
        let mut budget = self.budget(default)?;
        if let Some(t) = self.time_limit_s {
            budget.time_limit_ms = Some(time_limit_ms(t)?);
        }
        budget.until_feasible = self.until_feasible;
        Ok(Resolved { budget, params })
    }

    /// The budget from iterations and / or evaluations; `default` when neither is given
    /// (no time limit, not until feasible: see [`RunSettings::resolve`]).
    pub fn budget(&self, default: Budget) -> Result<Budget, SettingsError> {
        let iterations = self
            .iterations
            .map(|v| positive::<usize>("iterations", v))
            .transpose()?;
        let evaluations = self
            .evaluations
            .map(|v| positive::<u64>("evaluations", v))
            .transpose()?;
        Ok(match (iterations, evaluations) {
            (None, None) => default,
            (i, e) => Budget::new(i, e),
        })
    }

    /// Optimizer parameters from the file (defaults without one), then the population.
    pub fn params(&self) -> Result<OptimizerParams, SettingsError> {
        let path = self.params.as_deref();
        let mut params = match path {
            None => OptimizerParams::default(),
            Some(p) => read_params(p)?,
        };
        if let Some(n) = self.population {
            let n = usize::try_from(n)
                .ok()
                .filter(|n| POPULATION_RANGE.contains(n))
                .ok_or_else(|| SettingsError::Value {
                    field: "population",
                    expected: POPULATION_EXPECTED.to_owned(),
                    got: n.to_string(),
                })?;
            params.set_population(n);
        }
        params.validate().map_err(|e| {
            SettingsError::Params(format!(
                "{}: {e}",
                path.map_or("parameters".into(), |p| p.display().to_string())
            ))
        })?;
        Ok(params)
    }
}

/// A parameter file, parsed (not yet validated).
fn read_params(path: &Path) -> Result<OptimizerParams, SettingsError> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| SettingsError::Params(format!("{}: cannot read: {e}", path.display())))?;
    toml::from_str(&text).map_err(|e| {
        SettingsError::Params(format!("{}: {}", path.display(), e.to_string().trim_end()))
    })
}

/// A count of at least 1 that fits `T`.
fn positive<T: TryFrom<i128>>(field: &'static str, v: i128) -> Result<T, SettingsError> {
    if v < 1 {
        return Err(SettingsError::Value {
            field,
            expected: "at least 1".into(),
            got: v.to_string(),
        });
    }
    T::try_from(v).map_err(|_| SettingsError::TooLarge { field, got: v })
}

/// Milliseconds of a time limit of `t` seconds, rounded up.
fn time_limit_ms(t: f64) -> Result<u64, SettingsError> {
    if !(t.is_finite() && t > 0.0 && t <= MAX_TIME_LIMIT_S) {
        let got = if t.abs() >= MAX_TIME_LIMIT_S || (t != 0.0 && t.abs() < 1e-4) {
            format!("{t:e}")
        } else {
            t.to_string()
        };
        return Err(SettingsError::Value {
            field: "time_limit",
            expected: "seconds in (0, 1e7]".into(),
            got,
        });
    }
    // Truncation intended: milliseconds of a checked, bounded number of seconds.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    Ok((t * 1000.0).ceil() as u64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_settings_name_their_field_in_both_spellings() {
        let zero = RunSettings {
            iterations: Some(0),
            ..RunSettings::default()
        };
        let e = zero.resolve(Budget::DEFAULT).expect_err("zero iterations");
        assert_eq!(e.to_string(), "iterations: expected at least 1, got 0");
        assert_eq!(e.as_flag(), "--iterations: expected at least 1, got 0");
        let slow = RunSettings {
            time_limit_s: Some(-1.0),
            ..RunSettings::default()
        };
        let e = slow.resolve(Budget::DEFAULT).expect_err("negative time");
        assert_eq!(
            e.to_string(),
            "time_limit: expected seconds in (0, 1e7], got -1"
        );
        assert_eq!(
            e.as_flag(),
            "--time-limit: expected seconds in (0, 1e7], got -1"
        );
        let crowd = RunSettings {
            population: Some(3),
            ..RunSettings::default()
        };
        assert_eq!(
            crowd.resolve(Budget::DEFAULT).expect_err("3").as_flag(),
            format!("--population: expected {POPULATION_EXPECTED}, got 3")
        );
    }

    #[test]
    fn good_settings_resolve_to_the_budget_and_parameters() {
        let s = RunSettings {
            evaluations: Some(500),
            population: Some(20),
            time_limit_s: Some(1.5),
            until_feasible: true,
            ..RunSettings::default()
        };
        let r = s.resolve(Budget::DEFAULT).expect("valid");
        assert_eq!(r.budget.evaluations, Some(500));
        assert_eq!(r.budget.time_limit_ms, Some(1500));
        assert!(r.budget.until_feasible);
        assert_eq!(r.params.pso.population, 20);
        let none = RunSettings::default()
            .resolve(Budget::DEFAULT)
            .expect("defaults");
        assert_eq!(none.budget.iterations, Budget::DEFAULT.iterations);
        assert_eq!(none.budget.evaluations, None);
        assert_eq!(none.params, OptimizerParams::default());
    }
}
