//! The run artifact: what `plan` writes as `run.json` and `plot`, `report`, `export` and
//! `evaluate --json` read or print, as one versioned serde type (no string-keyed JSON).
//!
//! Like a bench run record, it names the method in full (label,
//! optimizer, encoding, initialisation), the seed and budget, and carries the typed
//! assessment of the plan. Non-finite numbers are written as the strings `"inf"`, `"-inf"`
//! and `"nan"` everywhere ([`swarmplan_core::json_f64`]).

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};
use swarmplan_core::attempts::AttemptRecord;
use swarmplan_core::cost::Assessment;
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::feasibility::Violation;
use swarmplan_core::json_f64;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerKind, OptimizerParams, Termination};
use swarmplan_core::run::RunResult;
use swarmplan_core::world::World;
use thiserror::Error;

/// Version of the `run.json` layout; readers refuse other versions.
pub const RUN_ARTIFACT_VERSION: u32 = 1;

/// Why a `run.json` could not be read; every variant names the file.
#[derive(Debug, Error)]
pub enum ArtifactError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not JSON, or not the layout of a run artifact.
    #[error("{path}: not a run artifact: {message}")]
    Parse {
        /// The file.
        path: String,
        /// What the JSON parser said.
        message: String,
    },
    /// The file has a whole-number version other than [`RUN_ARTIFACT_VERSION`].
    #[error("{path}: version {found}, this build reads version {RUN_ARTIFACT_VERSION}")]
    Version {
        /// The file.
        path: String,
        /// The version it has (`u32::MAX` if larger).
        found: u32,
    },
    /// The file has no `version` field.
    #[error("{path}: no `version` field: not a run.json of swarmplan `plan` (or one from before run.json had versions; plan again to write one)")]
    NoVersion {
        /// The file.
        path: String,
    },
    /// The file's `version` is not a whole number.
    #[error("{path}: `version` is {found}, expected a whole number (this build reads version {RUN_ARTIFACT_VERSION})")]
    BadVersion {
        /// The file.
        path: String,
        /// The `version` value as JSON text.
        found: String,
    },
}

/// One UAV in the report.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UavSummary {
    /// Weighted sum of this UAV's cost terms (no penalty).
    #[serde(with = "json_f64")]
    pub cost: f64,
    /// Path length, m.
    #[serde(with = "json_f64")]
    pub length_m: f64,
    /// Constant flight speed, m/s.
    #[serde(with = "json_f64")]
    pub speed_mps: f64,
    /// Arrival time at the goal, s.
    #[serde(with = "json_f64")]
    pub arrival_s: f64,
    /// Energy used over the flight, J.
    #[serde(with = "json_f64")]
    pub energy_j: f64,
    /// Energy used over battery capacity.
    #[serde(with = "json_f64")]
    pub battery_ratio: f64,
    /// Minimum clearance above terrain, m.
    #[serde(with = "json_f64")]
    pub min_clearance_m: f64,
    /// Time out of communication contact, s.
    #[serde(with = "json_f64")]
    pub outage_s: f64,
}

/// Cost of the plan: total, per UAV and per term (weighted, summed over UAVs, plus
/// `penalty`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CostSummary {
    /// Penalised total cost (weighted terms plus penalty; +inf if not finite).
    #[serde(with = "json_f64")]
    pub total: f64,
    /// Total cost divided by the number of UAVs, as the paper's tables report it.
    #[serde(with = "json_f64")]
    pub per_uav: f64,
    /// Weighted term totals; a non-finite one (SPSO's infinite collision cost) is written as
    /// `"inf"` like the total, not as the largest finite number.
    #[serde(with = "json_f64::map")]
    pub terms: BTreeMap<String, f64>,
}

/// The assessment of a plan as `evaluate --json` prints it and `run.json` stores it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AssessmentRecord {
    /// True when no hard constraint is violated (`violation` is 0).
    pub feasible: bool,
    /// The feasibility profile: which violations decide `feasible`.
    #[serde(default)]
    pub profile: swarmplan_core::feasibility::FeasibilityProfile,
    /// Measure of hard violation: 0 iff feasible.
    #[serde(with = "json_f64")]
    pub violation: f64,
    /// Cost of the plan.
    pub cost: CostSummary,
    /// One summary per UAV, in the scenario's order.
    pub uavs: Vec<UavSummary>,
    /// Every violation found, hard and soft (empty if the assessment did not list them).
    pub violations: Vec<Violation>,
}

impl AssessmentRecord {
    /// The report of an assessment (its violation list, if it has one).
    #[must_use]
    pub fn of(a: &Assessment) -> Self {
        let mut terms: BTreeMap<String, f64> = a
            .term_totals()
            .iter()
            .map(|(t, v)| (t.name().to_string(), v))
            .collect();
        terms.insert("penalty".into(), a.penalty);
        Self {
            feasible: a.feasible(),
            profile: a.profile,
            violation: a.violation,
            cost: CostSummary {
                total: a.total,
                per_uav: a.per_uav_cost(),
                terms,
            },
            uavs: a
                .per_uav
                .iter()
                .map(|u| UavSummary {
                    cost: u.cost,
                    length_m: u.length_m,
                    speed_mps: u.speed_mps,
                    arrival_s: u.arrival_s,
                    energy_j: u.energy_j,
                    battery_ratio: u.battery_ratio,
                    min_clearance_m: u.min_clearance_m,
                    outage_s: u.outage_s,
                })
                .collect(),
            violations: a.violations.clone().unwrap_or_default(),
        }
    }
}

/// The files a `plan` folder holds.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ArtifactFiles {
    /// Path of the plan (`plan.json`).
    pub plan: String,
    /// Path of the convergence trace (`convergence.csv`).
    pub convergence: String,
    /// Paths of the exported flight files (`plan --export`); empty (and not written) when none.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub exports: Vec<String>,
}

/// `run.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunArtifact {
    /// Layout version, [`RUN_ARTIFACT_VERSION`].
    pub version: u32,
    /// Name of the scenario planned.
    pub scenario: String,
    /// [`swarmplan_core::world::terrain::Terrain::fingerprint`] of the terrain planned on.
    pub terrain_fingerprint: String,
    /// The method's label, then its three parts spelled out.
    pub method: Method,
    /// The method's optimizer.
    pub optimizer: OptimizerKind,
    /// The method's encoding of a plan.
    pub encoding: EncodingKind,
    /// The method's initialisation.
    pub init: InitKind,
    /// Seed of the run (of the attempt whose plan was kept).
    pub seed: u64,
    /// The budget the run was given.
    pub budget: Budget,
    /// The optimizer parameters the run used.
    pub params: OptimizerParams,
    /// Evaluations spent, initialisation included.
    pub evaluations: u64,
    /// Steps taken after initialisation.
    pub iterations: usize,
    /// Why the search stopped (`time-limit`: not reproducible from the seed alone).
    pub termination: Termination,
    /// Of a staged run (the `line-corridor` and `line-band` starts): the evaluations after which it left
    /// its line start for the corridor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restarted_after: Option<u64>,
    /// Wall time of the optimisation, seconds.
    #[serde(with = "json_f64")]
    pub seconds: f64,
    /// The assessment of the plan (key `report` in folders written before issue 44, still
    /// read).
    #[serde(alias = "report")]
    pub assessment: AssessmentRecord,
    /// The other files written next to `run.json`.
    pub files: ArtifactFiles,
    /// Every attempt of `plan --attempts K` (K > 1), in order; the plan is the one of
    /// `seed`. Empty (and not written) for a single run.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attempts: Vec<AttemptRecord>,
    /// Of `plan --flight-margin M`: the margin in metres the plan was searched with
    /// ([`swarmplan_core::world::flight_margin`]); `assessment` is against the scenario as
    /// given. Absent (0) otherwise.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub flight_margin: f64,
}

/// Whether a margin is 0 (not written).
#[allow(clippy::trivially_copy_pass_by_ref)]
fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

impl RunArtifact {
    /// The artifact of one run: the method, seed and counts of `result`, its assessment, and
    /// the budget, parameters and files it was run with (no attempts).
    #[must_use]
    pub fn new(
        world: &World,
        result: &RunResult,
        budget: Budget,
        params: OptimizerParams,
        files: ArtifactFiles,
    ) -> Self {
        Self {
            version: RUN_ARTIFACT_VERSION,
            scenario: world.spec().name.clone(),
            terrain_fingerprint: world.terrain().fingerprint(),
            method: result.method,
            optimizer: result.method.optimizer,
            encoding: result.method.encoding,
            init: result.method.init,
            seed: result.seed,
            budget,
            params,
            evaluations: result.outcome.evaluations,
            iterations: result.outcome.iterations,
            termination: result.outcome.termination,
            restarted_after: result.outcome.restarted_after,
            seconds: result.seconds,
            assessment: AssessmentRecord::of(&result.assessment),
            files,
            attempts: Vec::new(),
            flight_margin: 0.0,
        }
    }

    /// A one-line description for figure titles and reports.
    #[must_use]
    pub fn describe(&self) -> String {
        let attempt = self
            .attempts
            .iter()
            .find(|a| a.seed == self.seed)
            .map_or(String::new(), |a| {
                format!(" (attempt {} of {})", a.attempt, self.attempts.len())
            });
        format!(
            "{} ({} on the {} encoding, {} init), seed {}{attempt}, {} evaluations",
            self.method, self.optimizer, self.encoding, self.init, self.seed, self.evaluations
        )
    }

    /// Reads `run.json`, refusing another version.
    pub fn read(path: &Path) -> Result<Self, ArtifactError> {
        let p = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|source| ArtifactError::Read {
            path: p.clone(),
            source,
        })?;
        let version: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| ArtifactError::Parse {
                path: p.clone(),
                message: e.to_string(),
            })?;
        let Some(found) = version["version"].as_u64() else {
            return Err(match version.get("version") {
                None => ArtifactError::NoVersion { path: p },
                Some(v) => ArtifactError::BadVersion {
                    path: p,
                    found: v.to_string(),
                },
            });
        };
        if found != u64::from(RUN_ARTIFACT_VERSION) {
            return Err(ArtifactError::Version {
                path: p,
                found: u32::try_from(found).unwrap_or(u32::MAX),
            });
        }
        serde_json::from_str(&text).map_err(|e| ArtifactError::Parse {
            path: p,
            message: e.to_string(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_text(text: &str) -> String {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let path = dir.path().join("run.json");
        std::fs::write(&path, text).expect("written");
        RunArtifact::read(&path)
            .expect_err("not a run.json of this build")
            .to_string()
    }

    #[test]
    fn a_run_json_without_a_version_is_named_as_such_and_another_version_by_its_number() {
        for text in ["{}", "[]"] {
            let e = read_text(text);
            assert!(e.contains("no `version` field"), "{text}: {e}");
        }
        for text in [
            "{\"version\": \"1\"}",
            "{\"version\": 1.5}",
            "{\"version\": -1}",
        ] {
            let e = read_text(text);
            assert!(e.contains("expected a whole number"), "{text}: {e}");
        }
        let e = read_text("{\"version\": 7}");
        assert!(e.contains("version 7, this build reads version"), "{e}");
    }
}
