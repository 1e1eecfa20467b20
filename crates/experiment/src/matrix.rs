//! The experiment matrix: scenarios x parameter sets x methods x runs, in one fixed order,
//! and each run's seed.
//!
//! A run's seed is derived from the master seed, the scenario, the parameter set and the
//! run index alone, so it does not depend on thread count, execution order, sharding or
//! resuming, and it is the *same for every method*: run k of every method on a scenario
//! draws from the same random stream (common random numbers). Two methods with the same
//! encoding and initialisation therefore start from the same population, and the run index
//! is a real block for paired statistics (the summary's Friedman test).

use serde::{Deserialize, Serialize};
use swarmplan_core::feasibility::FeasibilityProfile;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams, PAPER_EVALUATIONS};
use swarmplan_core::rng::derive_seed;
use thiserror::Error;

/// One set of algorithm parameters, named so records and tables can tell sets apart.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ParamSet {
    /// Name of the set, unique within an experiment (`paper` for the default set).
    pub name: String,
    /// The optimizers' parameters (default: the paper's setting).
    #[serde(default)]
    pub params: OptimizerParams,
}

impl Default for ParamSet {
    fn default() -> Self {
        Self {
            name: "paper".into(),
            params: OptimizerParams::default(),
        }
    }
}

/// What an experiment runs. Written to `experiment.json` next to the records, so a resumed
/// run or an aggregation can check it is continuing the same experiment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ExperimentSpec {
    /// Master seed: every run's seed derives from it.
    pub master_seed: u64,
    /// Repetitions per (scenario, parameter set, algorithm).
    pub runs: usize,
    /// Built-in scenario names or scenario files.
    pub scenarios: Vec<String>,
    /// Methods by label: presets (`spso`) or `optimizer/encoding/init`.
    pub methods: Vec<Method>,
    /// Parameter sets, each run with every scenario and method (default: one set `paper`
    /// of the paper's parameters).
    #[serde(default = "default_param_sets")]
    pub param_sets: Vec<ParamSet>,
    /// The budget of every run under [`BudgetPolicy::Equal`] (default: 38,700 evaluations,
    /// DLS-SMPSO's paper mean).
    #[serde(default = "equal_budget")]
    pub budget: Budget,
    /// Equal budgets (the default) or each method's paper setting.
    #[serde(default)]
    pub budget_policy: BudgetPolicy,
    /// Feasibility profile of every run (`strict` unless set; docs/model.md).
    #[serde(default)]
    pub profile: FeasibilityProfile,
    /// Terrain file replacing every scenario's terrain source.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terrain: Option<String>,
}

/// How an experiment budgets its runs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BudgetPolicy {
    /// Every method gets the experiment's `budget` (fair comparisons; the default).
    #[default]
    Equal,
    /// Each method gets its own default: the paper's 200 iterations for the paper's
    /// methods (so DLS-SMPSO spends about 38,700 evaluations and PSO 10,050), 38,700
    /// evaluations for swarmplan's own (Tables 4-5 as the paper ran them).
    Paper,
}

impl BudgetPolicy {
    /// `equal` or `paper`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Equal => "equal",
            Self::Paper => "paper",
        }
    }
}

/// Most runs one experiment may hold: every run's key is listed before the runs start, so a
/// matrix past this would fill memory before doing any work (at a millisecond per run it is
/// still about three hours).
pub const MAX_MATRIX_RUNS: usize = 10_000_000;

/// The default equal budget: [`PAPER_EVALUATIONS`] evaluations.
#[must_use]
pub const fn equal_budget() -> Budget {
    Budget::evaluations(PAPER_EVALUATIONS)
}

fn default_param_sets() -> Vec<ParamSet> {
    vec![ParamSet::default()]
}

impl ExperimentSpec {
    /// The paper's experiment: both cases, the six methods of the paper plus SPSO (the
    /// ablation of DLS), 200 runs each, paper parameters, at equal budgets of
    /// [`PAPER_EVALUATIONS`] evaluations (set `budget_policy` to `paper` for the paper's
    /// per-iteration budgets).
    #[must_use]
    pub fn paper(master_seed: u64) -> Self {
        Self {
            master_seed,
            runs: 200,
            scenarios: vec!["paper-case1".into(), "paper-case2".into()],
            methods: Method::paper_methods(),
            param_sets: default_param_sets(),
            budget: equal_budget(),
            budget_policy: BudgetPolicy::Equal,
            profile: FeasibilityProfile::Strict,
            terrain: None,
        }
    }

    /// Checks the matrix is well formed.
    pub fn validate(&self) -> Result<(), MatrixError> {
        if self.runs == 0 {
            return Err(MatrixError::Empty("runs must be at least 1".into()));
        }
        let size = [
            self.scenarios.len(),
            self.param_sets.len(),
            self.methods.len(),
        ]
        .into_iter()
        .try_fold(self.runs, usize::checked_mul);
        if size.is_none_or(|n| n > MAX_MATRIX_RUNS) {
            return Err(MatrixError::TooLarge(format!(
                "runs: {} scenarios x {} methods x {} parameter sets x {} runs is more than {MAX_MATRIX_RUNS} runs",
                self.scenarios.len(),
                self.methods.len(),
                self.param_sets.len(),
                self.runs
            )));
        }
        if self.scenarios.is_empty() || self.methods.is_empty() || self.param_sets.is_empty() {
            return Err(MatrixError::Empty(
                "scenarios, methods and param_sets must each list at least one entry".into(),
            ));
        }
        // A repeated entry would run every run twice with the same seed and count it twice.
        if let Some(d) = first_duplicate(self.scenarios.iter()) {
            return Err(MatrixError::Duplicate(format!(
                "scenarios: `{d}` appears twice"
            )));
        }
        if let Some(d) = first_duplicate(self.methods.iter()) {
            return Err(MatrixError::Duplicate(format!(
                "methods: `{d}` appears twice"
            )));
        }
        if let Some(d) = first_duplicate(self.param_sets.iter().map(|p| &p.name)) {
            return Err(MatrixError::Duplicate(format!(
                "param_sets: name `{d}` appears twice"
            )));
        }
        // A run of no evaluation would still be recorded with the cost of its first draw.
        let zero = [
            ("iterations", self.budget.iterations.map(|i| i as u64)),
            ("evaluations", self.budget.evaluations),
            ("time_limit_ms", self.budget.time_limit_ms),
        ]
        .into_iter()
        .find(|(_, v)| *v == Some(0));
        if let Some((field, _)) = zero {
            return Err(MatrixError::Budget(format!(
                "budget.{field}: expected at least 1, got 0"
            )));
        }
        for p in &self.param_sets {
            p.params
                .validate()
                .map_err(|e| MatrixError::Params(format!("param_sets `{}`: {e}", p.name)))?;
        }
        Ok(())
    }

    /// The budget of a run of `method`.
    #[must_use]
    pub fn budget_for(&self, method: Method) -> Budget {
        match self.budget_policy {
            BudgetPolicy::Equal => self.budget,
            BudgetPolicy::Paper => method.optimizer.default_budget(),
        }
    }

    /// Number of runs in the matrix.
    #[must_use]
    pub fn size(&self) -> usize {
        self.scenarios.len() * self.param_sets.len() * self.methods.len() * self.runs
    }

    /// Every run, in the matrix's fixed order.
    #[must_use]
    pub fn runs(&self) -> Vec<RunKey> {
        let mut v = Vec::with_capacity(self.size());
        for scenario in &self.scenarios {
            for set in &self.param_sets {
                for method in &self.methods {
                    for run in 0..self.runs {
                        v.push(RunKey {
                            scenario: scenario.clone(),
                            param_set: set.name.clone(),
                            method: *method,
                            run,
                        });
                    }
                }
            }
        }
        v
    }

    /// The seed of a run: common to every method (see the module docs).
    #[must_use]
    pub fn seed(&self, key: &RunKey) -> u64 {
        derive_seed(
            self.master_seed,
            &[&key.scenario, &key.param_set],
            key.run as u64,
        )
    }

    /// The parameter set named `name`, if the experiment has one.
    #[must_use]
    pub fn param_set(&self, name: &str) -> Option<&ParamSet> {
        self.param_sets.iter().find(|p| p.name == name)
    }
}

/// The identity of one run.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct RunKey {
    /// The scenario, as the experiment names it (built-in name or file).
    pub scenario: String,
    /// Name of the parameter set.
    pub param_set: String,
    /// The method of the run (optimizer, encoding, initialisation).
    pub method: Method,
    /// Run index, 0-based, within its (scenario, parameter set, method).
    pub run: usize,
}

/// The first item that appears twice.
fn first_duplicate<T: Ord + std::fmt::Display>(items: impl Iterator<Item = T>) -> Option<String> {
    let mut seen = std::collections::BTreeSet::new();
    for i in items {
        let label = i.to_string();
        if !seen.insert(i) {
            return Some(label);
        }
    }
    None
}

/// A slice of the matrix: runs whose position in the matrix order is `index - 1` modulo
/// `count`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// 1-based.
    pub index: usize,
    /// Number of shards the matrix is split into.
    pub count: usize,
}

impl Shard {
    /// Parses `K/N` with 1 <= K <= N.
    pub fn parse(s: &str) -> Result<Self, MatrixError> {
        let bad = || MatrixError::Shard(format!("expected K/N with 1 <= K <= N, got `{s}`"));
        let (k, n) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = k.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether the run at `position` (0-based, in the matrix order) is in this shard.
    #[must_use]
    pub fn contains(&self, position: usize) -> bool {
        position % self.count == self.index - 1
    }
}

/// Why an experiment's matrix or a shard is refused.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum MatrixError {
    /// Zero runs, or no scenario, method or parameter set.
    #[error("experiment: {0}")]
    Empty(String),
    /// A scenario, method or parameter set name is listed twice.
    #[error("experiment: {0}")]
    Duplicate(String),
    /// A parameter set's parameters fail their checks.
    #[error("experiment: {0}")]
    Params(String),
    /// The matrix holds more than [`MAX_MATRIX_RUNS`] runs.
    #[error("experiment: {0}")]
    TooLarge(String),
    /// A budget limit (iterations, evaluations or time) is 0.
    #[error("experiment: {0}")]
    Budget(String),
    /// A `--shard` that is not `K/N` with 1 <= K <= N.
    #[error("--shard: {0}")]
    Shard(String),
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_budget_of_nothing_is_refused() {
        for field in ["iterations", "evaluations", "time_limit_ms"] {
            let mut spec = ExperimentSpec::paper(1);
            match field {
                "iterations" => spec.budget.iterations = Some(0),
                "evaluations" => spec.budget.evaluations = Some(0),
                _ => spec.budget.time_limit_ms = Some(0),
            }
            let e = spec.validate().expect_err("refused");
            assert_eq!(
                e.to_string(),
                format!("experiment: budget.{field}: expected at least 1, got 0")
            );
        }
        ExperimentSpec::paper(1)
            .validate()
            .expect("the paper's budget is valid");
    }

    #[test]
    fn a_matrix_too_large_to_list_is_refused() {
        let mut spec = ExperimentSpec::paper(1);
        spec.runs = usize::MAX;
        let e = spec.validate().expect_err("refused");
        assert!(e.to_string().contains("is more than 10000000 runs"), "{e}");
        spec.runs = MAX_MATRIX_RUNS / spec.scenarios.len() / spec.methods.len();
        assert!(spec.validate().is_ok());
    }

    #[test]
    fn budgets_default_to_equal_evaluations() {
        let spec = ExperimentSpec::paper(1);
        let pso = Method::preset("pso").unwrap();
        let coop = Method::preset("swarmplan").unwrap();
        assert_eq!(spec.budget_for(pso), Budget::evaluations(PAPER_EVALUATIONS));
        assert_eq!(
            spec.budget_for(coop),
            Budget::evaluations(PAPER_EVALUATIONS)
        );
        // A file without a budget gets the same; `budget_policy = "paper"` each method its own.
        let text = "master_seed = 1\nruns = 2\nscenarios = [\"tiny\"]\nmethods = [\"pso\"]\n";
        let read: ExperimentSpec = toml::from_str(text).unwrap();
        assert_eq!(read.budget_for(pso), Budget::evaluations(PAPER_EVALUATIONS));
        let paper: ExperimentSpec =
            toml::from_str(&format!("{text}budget_policy = \"paper\"\n")).unwrap();
        assert_eq!(paper.budget_for(pso), Budget::DEFAULT);
        assert_eq!(
            paper.budget_for(coop),
            Budget::evaluations(PAPER_EVALUATIONS)
        );
    }

    #[test]
    fn matrix_order_and_size() {
        let spec = ExperimentSpec::paper(1);
        let runs = spec.runs();
        assert_eq!(runs.len(), 2 * 7 * 200);
        assert_eq!(runs.len(), spec.size());
        assert_eq!(runs[0].scenario, "paper-case1");
        assert_eq!(runs[0].run, 0);
        assert_eq!(runs[199].run, 199);
        assert_eq!(runs[200].method.label(), "apso");
    }

    #[test]
    fn seeds_depend_on_identity_only_and_are_common_to_methods() {
        let spec = ExperimentSpec::paper(7);
        let runs = spec.runs();
        let a = spec.seed(&runs[5]);
        assert_eq!(a, spec.seed(&runs[5].clone()));
        assert_ne!(a, spec.seed(&runs[6]));
        let other = ExperimentSpec::paper(8);
        assert_ne!(a, other.seed(&runs[5]));
        // Run 5 of the second method (APSO) has run 5 of the first's seed.
        assert_ne!(runs[5].method, runs[205].method);
        assert_eq!(runs[205].run, 5);
        assert_eq!(spec.seed(&runs[205]), a);
        // Another scenario has other seeds.
        let case2 = runs
            .iter()
            .find(|k| k.scenario == "paper-case2" && k.run == 5);
        assert_ne!(case2.map(|k| spec.seed(k)), Some(a));
    }

    #[test]
    fn repeated_entries_are_refused() {
        let mut spec = ExperimentSpec::paper(1);
        spec.methods.push(spec.methods[0]);
        let e = spec.validate().expect_err("duplicate method");
        assert_eq!(e.to_string(), "experiment: methods: `pso` appears twice");
        let mut spec = ExperimentSpec::paper(1);
        spec.scenarios.push("paper-case1".into());
        assert!(spec.validate().is_err());
    }

    #[test]
    fn shards_partition_the_matrix() {
        let n = 3;
        let shards: Vec<Shard> = (1..=n)
            .map(|k| Shard::parse(&format!("{k}/{n}")).unwrap())
            .collect();
        for pos in 0..100 {
            assert_eq!(shards.iter().filter(|s| s.contains(pos)).count(), 1);
        }
        assert!(Shard::parse("0/3").is_err());
        assert!(Shard::parse("4/3").is_err());
        assert!(Shard::parse("x").is_err());
    }
}
