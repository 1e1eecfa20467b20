//! What every optimizer's parameter section shares: the population range, the error a bad
//! value gets, and [`OptimizerConfig`], through which the registry (`params.rs`) sizes and
//! builds each optimizer. Apart from the registry so that an optimizer's file depends on
//! this and the registry on the optimizers, not both ways.

use std::fmt;

use thiserror::Error;

use super::Optimizer;

/// Population sizes every optimizer accepts, from a TOML section or `--population` alike: at
/// least 4 (ABC's two food sources; DE's mutation needs three others), at most 100,000 (the
/// swarm's arrays then stay below a few hundred MB on a 5-UAV plan).
pub const POPULATION_RANGE: std::ops::RangeInclusive<usize> = 4..=100_000;
/// How [`POPULATION_RANGE`] is said in messages.
pub const POPULATION_EXPECTED: &str = "a whole number in [4, 100000]";

/// A parameter with a bad value; `field` is its path (`dls_paper.pso.velocity_clamp`).
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{field}: expected {expected}, got {got}")]
pub struct ParamsError {
    /// Path of the parameter, sections joined by dots.
    pub field: String,
    /// What values it accepts, in words (`a number in (0, 1]`).
    pub expected: String,
    /// The value it was given, as displayed.
    pub got: String,
}

impl ParamsError {
    /// The same error with `section.` prepended to the field path.
    #[must_use]
    pub fn within(mut self, section: &str) -> Self {
        self.field = format!("{section}.{}", self.field);
        self
    }
}

/// `Ok` when `ok`, else an error naming `field`.
pub fn check(
    ok: bool,
    field: &str,
    expected: &str,
    got: impl fmt::Display,
) -> Result<(), ParamsError> {
    if ok {
        Ok(())
    } else {
        Err(ParamsError {
            field: field.to_owned(),
            expected: expected.to_owned(),
            got: got.to_string(),
        })
    }
}

/// What an optimizer's parameter section tells the registry (`optimizer_registry!` below):
/// the population it runs, how `--population` sets it, and how to build the optimizer.
/// The section also has an inherent `DEFAULT` (the paper's setting, feeding `Default` and
/// serde) and `validate`.
pub trait OptimizerConfig {
    /// The population size the optimizer will use (for ABC: bees, twice the food sources).
    fn population(&self) -> usize;
    /// Sets the population size (e.g. the population-500 runs), raised to the optimizer's
    /// least workable size.
    fn set_population(&mut self, n: usize);
    /// Makes the optimizer. The section should have passed its `validate`; out-of-range
    /// sizes are raised to the smallest workable value rather than panicking.
    fn build(&self) -> Box<dyn Optimizer>;
    /// The budget of a run given none: the paper's 200 iterations unless the optimizer's
    /// iterations mean something else.
    fn default_budget(&self) -> super::Budget {
        super::Budget::DEFAULT
    }
}
