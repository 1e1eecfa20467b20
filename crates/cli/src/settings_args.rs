//! The budget and optimizer flags that `plan` and `bench` share, as clap sees them; what
//! they mean and how they are checked is the library's [`RunSettings`], which Python uses
//! too.

use std::path::PathBuf;

use clap::Args;
use swarmplan_experiment::settings::RunSettings;

/// Budget and algorithm settings, shared by `plan` and `bench`.
#[derive(Debug, Clone, Args)]
pub struct SettingsArgs {
    /// Iterations per run (plan's default: 200, the paper's, for the paper's methods, 38,700
    /// evaluations for swarmplan's own; bench: see --budget). With --evaluations, whichever
    /// ends first.
    #[arg(long, allow_negative_numbers = true)]
    pub iterations: Option<usize>,
    /// Population size (default 50, the paper's; 10 for swarmplan's sub-swarms).
    #[arg(long, allow_negative_numbers = true)]
    pub population: Option<usize>,
    /// Evaluation budget per run (fair comparisons); with --iterations, whichever ends first.
    #[arg(long, allow_negative_numbers = true)]
    pub evaluations: Option<u64>,
    /// Optimizer parameters as TOML (help text: [`params_help`]).
    #[arg(long, help = params_help())]
    pub params: Option<PathBuf>,
}

impl SettingsArgs {
    /// The flags as the library's settings, with `plan`'s time limit and stop rule.
    #[must_use]
    pub fn run_settings(&self, time_limit_s: Option<f64>, until_feasible: bool) -> RunSettings {
        RunSettings {
            iterations: self.iterations.map(|v| v as i128),
            evaluations: self.evaluations.map(i128::from),
            population: self.population.map(|v| v as i128),
            params: self.params.clone(),
            time_limit_s,
            until_feasible,
        }
    }
}

/// `--params`' help, listing the optimizers' sections from the registry.
fn params_help() -> String {
    format!(
        "Optimizer parameters as TOML (sections {})",
        swarmplan_core::optim::OptimizerKind::sections()
    )
}
