//! The folder `plan` writes: `plan.json`, `run.json`, `convergence.csv` and
//! `scenario.toml`, written and read by one type, so `plan`, `plot`, `report`, `export`
//! and `evaluate` agree on names, formats and the messages a missing file gets.

use std::path::{Path, PathBuf};

use swarmplan_core::optim::IterationRecord;
use swarmplan_core::plan::Plan;
use swarmplan_core::world::spec::ScenarioSpec;
use swarmplan_core::world::World;
use thiserror::Error;

use crate::artifact::{ArtifactError, RunArtifact};
use crate::atomic::write_atomic;
use crate::convergence::{
    read_convergence, write_convergence, ConvergenceColumns, ConvergenceError,
};
use crate::plan_file::{plan_file, read_plan, PlanFileError, Provenance};
use crate::scenario::{to_toml, LoadedSpec, ScenarioError};

use crate::catalog::load_spec;

/// A plan folder's file that cannot be written or read.
#[derive(Debug, Error)]
pub enum PlanFolderError {
    /// A file could not be written.
    #[error("{}: cannot write: {source}", .path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// What the system said.
        source: std::io::Error,
    },
    /// A value could not be serialised (not expected of the types written here).
    #[error("{}: cannot serialise: {source}", .path.display())]
    Serialise {
        /// The file.
        path: PathBuf,
        /// What serde said.
        source: serde_json::Error,
    },
    /// The folder has no `scenario.toml` to read its plan against.
    #[error("{}: missing; `swarmplan plan --out {}` writes it next to plan.json", .path.display(), .dir.display())]
    NoScenario {
        /// The scenario file looked for.
        path: PathBuf,
        /// The folder.
        dir: PathBuf,
    },
    /// The scenario file is unreadable or invalid.
    #[error(transparent)]
    Scenario(#[from] Box<ScenarioError>),
    /// `plan.json` is unreadable, invalid or of another scenario.
    #[error(transparent)]
    Plan(#[from] PlanFileError),
    /// `run.json` is unreadable or invalid.
    #[error(transparent)]
    Run(#[from] ArtifactError),
    /// `convergence.csv` cannot be written or read.
    #[error(transparent)]
    Convergence(#[from] ConvergenceError),
}

/// A folder written by `plan`, or to be.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlanFolder {
    dir: PathBuf,
}

impl PlanFolder {
    /// The plan's waypoints ([`crate::plan_file`]).
    pub const PLAN: &'static str = "plan.json";
    /// The run's record ([`RunArtifact`]).
    pub const RUN: &'static str = "run.json";
    /// The best cost after every kept iteration ([`crate::convergence`]).
    pub const CONVERGENCE: &'static str = "convergence.csv";
    /// The scenario the plan was made for, every field written out.
    pub const SCENARIO: &'static str = "scenario.toml";

    /// The folder at `dir` (nothing is checked or created).
    #[must_use]
    pub fn new(dir: impl Into<PathBuf>) -> Self {
        Self { dir: dir.into() }
    }

    /// The folder.
    #[must_use]
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Path of `plan.json`.
    #[must_use]
    pub fn plan_path(&self) -> PathBuf {
        self.dir.join(Self::PLAN)
    }

    /// Path of `run.json`.
    #[must_use]
    pub fn run_path(&self) -> PathBuf {
        self.dir.join(Self::RUN)
    }

    /// Path of `convergence.csv`.
    #[must_use]
    pub fn convergence_path(&self) -> PathBuf {
        self.dir.join(Self::CONVERGENCE)
    }

    /// Path of `scenario.toml`.
    #[must_use]
    pub fn scenario_path(&self) -> PathBuf {
        self.dir.join(Self::SCENARIO)
    }

    /// Whether the folder holds a plan (`plan.json`).
    #[must_use]
    pub fn holds_plan(&self) -> bool {
        self.plan_path().exists()
    }

    /// Writes `plan` of `world` as `plan.json`, atomically; returns its path.
    pub fn write_plan(&self, world: &World, plan: &Plan) -> Result<PathBuf, PlanFolderError> {
        let path = self.plan_path();
        self.write_json(&path, &plan_file(world, plan))?;
        Ok(path)
    }

    /// Writes the run's kept iterations and each UAV's cost after them as
    /// `convergence.csv`; returns its path.
    pub fn write_convergence(
        &self,
        uavs: usize,
        trace: &[IterationRecord],
        uav_costs: &[impl AsRef<[f64]>],
    ) -> Result<PathBuf, PlanFolderError> {
        let path = self.convergence_path();
        write_convergence(&path, uavs, trace, uav_costs)?;
        Ok(path)
    }

    /// Writes the run's record as `run.json`; returns its path.
    pub fn write_run(&self, run: &RunArtifact) -> Result<PathBuf, PlanFolderError> {
        let path = self.run_path();
        self.write_json(&path, run)?;
        Ok(path)
    }

    /// Writes `spec` as `scenario.toml`, its terrain file (if any) made absolute so the
    /// folder's scenario resolves from anywhere; returns its path.
    pub fn write_scenario(&self, spec: &ScenarioSpec) -> Result<PathBuf, PlanFolderError> {
        let path = self.scenario_path();
        let mut written = spec.clone();
        if written.terrain.source != "procedural" {
            if let Ok(abs) = std::fs::canonicalize(&written.terrain.source) {
                written.terrain.source = abs.display().to_string();
            }
        }
        write_atomic(&path, to_toml(&written).as_bytes()).map_err(|source| {
            PlanFolderError::Write {
                path: path.clone(),
                source,
            }
        })?;
        Ok(path)
    }

    /// The folder's `scenario.toml`, parsed and validated.
    pub fn load_scenario(&self) -> Result<LoadedSpec, PlanFolderError> {
        let path = self.scenario_path();
        if !path.exists() {
            return Err(PlanFolderError::NoScenario {
                path,
                dir: self.dir.clone(),
            });
        }
        Ok(load_spec(&path.display().to_string()).map_err(Box::new)?)
    }

    /// The folder's `plan.json`, read against `world` (refused if made for another
    /// scenario or terrain).
    pub fn read_plan(&self, world: &World) -> Result<Plan, PlanFolderError> {
        Ok(read_plan(&self.plan_path(), world, Provenance::MustMatch)?)
    }

    /// The folder's `run.json`, or `None` when there is none (a plan written by hand).
    pub fn read_run(&self) -> Result<Option<RunArtifact>, PlanFolderError> {
        let path = self.run_path();
        if !path.exists() {
            return Ok(None);
        }
        Ok(Some(RunArtifact::read(&path)?))
    }

    /// The folder's `convergence.csv`, as columns.
    pub fn read_convergence(&self) -> Result<ConvergenceColumns, PlanFolderError> {
        Ok(read_convergence(&self.convergence_path())?)
    }

    /// `value` as pretty JSON with a final newline, written atomically to `path`.
    fn write_json(
        &self,
        path: &Path,
        value: &impl serde::Serialize,
    ) -> Result<(), PlanFolderError> {
        let text =
            serde_json::to_string_pretty(value).map_err(|source| PlanFolderError::Serialise {
                path: path.to_path_buf(),
                source,
            })?;
        write_atomic(path, (text + "\n").as_bytes()).map_err(|source| PlanFolderError::Write {
            path: path.to_path_buf(),
            source,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_folder_without_its_scenario_says_which_command_writes_it() {
        let dir = tempfile::tempdir().expect("temp dir");
        let folder = PlanFolder::new(dir.path());
        assert!(!folder.holds_plan());
        assert!(folder
            .read_run()
            .expect("no run.json is no error")
            .is_none());
        let e = folder.load_scenario().expect_err("no scenario.toml");
        assert_eq!(
            e.to_string(),
            format!(
                "{}: missing; `swarmplan plan --out {}` writes it next to plan.json",
                dir.path().join("scenario.toml").display(),
                dir.path().display()
            )
        );
    }
}
