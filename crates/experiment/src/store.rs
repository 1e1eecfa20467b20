//! The files of an experiment folder: `experiment.json` (the matrix), `scenarios.json` (a
//! fingerprint of each scenario its runs were made on) and `runs.jsonl` (one record per
//! finished run), written so that a kill at any moment loses at most the runs in
//! flight and never leaves a corrupt line.
//!
//! Each record is serialised first and appended with a single `write` of the whole line to
//! a file opened in append mode, then synced; the kernel completes a write it has started
//! even when the process is killed, so a line is either all there or absent. Reading back
//! still tolerates a torn last line (a full disk, a crash of the machine): it is dropped and
//! the file truncated before appending again.

use std::collections::{BTreeMap, HashSet};
use std::fs::{File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

use thiserror::Error;

use crate::matrix::{BudgetPolicy, ExperimentSpec, RunKey};
use crate::record::RunRecord;

/// The file of an experiment folder that describes its matrix ([`ExperimentSpec`]).
pub const SPEC_FILE: &str = "experiment.json";
/// The file of an experiment folder that holds its records, one line per finished run.
pub const RUNS_FILE: &str = "runs.jsonl";

/// Why an experiment folder cannot be read, written or used.
#[derive(Debug, Error)]
pub enum StoreError {
    /// A file or folder could not be read, written, created or locked.
    #[error("{path}: {source}")]
    Io {
        /// The file or folder.
        path: PathBuf,
        /// The system's error.
        source: std::io::Error,
    },
    /// A line of `runs.jsonl` does not parse as a run record.
    #[error("{path}: line {line}: not a run record: {message}")]
    BadRecord {
        /// The `runs.jsonl` file.
        path: PathBuf,
        /// Line number, 1-based.
        line: usize,
        /// The parser's error.
        message: String,
    },
    /// `experiment.json` (or `builds.json`, `scenarios.json`) does not parse.
    #[error("{path}: not an experiment description: {message}")]
    BadSpec {
        /// The file.
        path: PathBuf,
        /// The parser's error.
        message: String,
    },
    /// The folder's `experiment.json` describes another experiment than the one asked for.
    #[error("{dir}: holds results of a different experiment ({what}); use another --out, or the same flags to --resume")]
    Mismatch {
        /// The experiment folder.
        dir: PathBuf,
        /// The first field that differs, with both values.
        what: String,
    },
    /// Another bench holds the folder's lock ([`LOCK_FILE`]).
    #[error("{dir}: another `swarmplan bench` is writing its records there now (it holds {dir}/{LOCK_FILE}); wait for it to finish, or use another --out")]
    Busy {
        /// The experiment folder.
        dir: PathBuf,
    },
    /// The folder already holds run records and no resume was asked for.
    #[error("{dir}: already holds {count} run records; pass --resume to continue them, or choose another --out")]
    NotEmpty {
        /// The experiment folder.
        dir: PathBuf,
        /// Number of records it holds.
        count: usize,
    },
    /// The folder holds a plan (`plan.json`).
    #[error("{dir}: holds a plan (plan.json); a bench needs its own folder")]
    HoldsPlan {
        /// The folder.
        dir: PathBuf,
    },
    /// Two records of `runs.jsonl` share a run identity.
    #[error("{path}: run {key} appears twice")]
    Duplicate {
        /// The `runs.jsonl` file.
        path: PathBuf,
        /// The run, as `scenario/param_set/method#run`.
        key: String,
    },
    /// A record is not a run of the folder's experiment: another master seed, or a run
    /// outside its matrix.
    #[error("{path}: run {key} is not a run of this folder's experiment ({why})")]
    Foreign {
        /// The `runs.jsonl` file.
        path: PathBuf,
        /// The run, as `scenario/param_set/method#run`.
        key: String,
        /// How it differs from the experiment's runs.
        why: String,
    },
    /// A scenario's fingerprint is not the one the folder recorded for its runs.
    #[error("{dir}: scenario `{scenario}` has changed since its runs there were recorded (fingerprint {then} there, {now} now); restore it, or use another --out")]
    ScenarioChanged {
        /// The experiment folder.
        dir: PathBuf,
        /// The scenario's name.
        scenario: String,
        /// The fingerprint recorded in the folder.
        then: String,
        /// The scenario's fingerprint now.
        now: String,
    },
}

/// Refuses a folder that holds a plan (`plan.json`): plan and bench folders are never mixed.
pub fn check_not_a_plan_folder(dir: &Path) -> Result<(), StoreError> {
    if dir.join("plan.json").exists() {
        return Err(StoreError::HoldsPlan {
            dir: dir.to_path_buf(),
        });
    }
    Ok(())
}

/// The file of an experiment folder that lists the builds that wrote runs into it, in
/// order ([`build_id`]): a folder resumed by another build may mix two versions' results.
pub const BUILDS_FILE: &str = "builds.json";

/// This build: its git commit, or `v` and the crate version outside a git checkout.
#[must_use]
pub fn build_id() -> &'static str {
    env!("SWARMPLAN_BUILD")
}

/// The builds recorded in `dir` (empty if none: a new folder, or one of an older build).
pub fn read_builds(dir: &Path) -> Result<Vec<String>, StoreError> {
    read_json_or_default(&dir.join(BUILDS_FILE))
}

/// The JSON value of `path`, or the type's default (empty) when there is no such file.
fn read_json_or_default<T: serde::de::DeserializeOwned + Default>(
    path: &Path,
) -> Result<T, StoreError> {
    match std::fs::read_to_string(path) {
        Ok(text) => serde_json::from_str(&text).map_err(|e| StoreError::BadSpec {
            path: path.to_path_buf(),
            message: e.to_string(),
        }),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(T::default()),
        Err(source) => Err(StoreError::Io {
            path: path.to_path_buf(),
            source,
        }),
    }
}

/// A warning for a folder whose runs were made by other builds than this one, if so.
pub fn other_builds_warning(dir: &Path) -> Result<Option<String>, StoreError> {
    let builds = read_builds(dir)?;
    let has_runs = dir.join(RUNS_FILE).is_file();
    Ok((has_runs && !builds.is_empty() && !builds.iter().any(|b| b == build_id())).then(|| {
        format!(
            "{}: its runs were made by build {}, this is build {}; if a method changed between them, the folder now mixes two versions' results; a new --out keeps them apart",
            dir.display(),
            builds.join(", "),
            build_id()
        )
    }))
}

/// The builds that made the runs of shard folders, as their `builds.json` files say.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ShardBuilds {
    /// Each build, in order of first appearance, with the folders that name it.
    pub builds: Vec<(String, Vec<PathBuf>)>,
    /// Folders without a `builds.json` (written before builds were recorded).
    pub unrecorded: Vec<PathBuf>,
}

impl ShardBuilds {
    /// Reads the `builds.json` of each of `dirs`.
    pub fn of(dirs: &[PathBuf]) -> Result<Self, StoreError> {
        let mut out = Self::default();
        for d in dirs {
            if !d.join(BUILDS_FILE).is_file() {
                out.unrecorded.push(d.clone());
                continue;
            }
            for b in read_builds(d)? {
                match out.builds.iter_mut().find(|(known, _)| *known == b) {
                    Some((_, folders)) => folders.push(d.clone()),
                    None => out.builds.push((b, vec![d.clone()])),
                }
            }
        }
        Ok(out)
    }

    /// A warning when the runs were made by more than one build, or by a recorded build and
    /// folders that record none: merged, they may mix versions of a method.
    #[must_use]
    pub fn warning(&self) -> Option<String> {
        let mixed =
            self.builds.len() > 1 || (!self.builds.is_empty() && !self.unrecorded.is_empty());
        mixed.then(|| {
            let names = |dirs: &[PathBuf]| -> String {
                let v: Vec<String> = dirs.iter().map(|d| d.display().to_string()).collect();
                v.join(", ")
            };
            let mut each: Vec<String> = self
                .builds
                .iter()
                .map(|(b, dirs)| format!("build {b} ({})", names(dirs)))
                .collect();
            if !self.unrecorded.is_empty() {
                each.push(format!(
                    "builds not recorded ({}: no builds.json)",
                    names(&self.unrecorded)
                ));
            }
            format!(
                "the folders' runs were made by {}; if a method changed between them, the merged results mix its versions (re-run the shards with one build to keep them apart)",
                each.join(" and ")
            )
        })
    }

    /// Writes the recorded builds as `dir`'s list, for the merged folder.
    pub fn write(&self, dir: &Path) -> Result<(), StoreError> {
        let list: Vec<String> = self.builds.iter().map(|(b, _)| b.clone()).collect();
        write_build_list(dir, &list)
    }
}

fn write_build_list(dir: &Path, list: &[String]) -> Result<(), StoreError> {
    let path = dir.join(BUILDS_FILE);
    let text = serde_json::to_string_pretty(list).expect("a list serialises");
    std::fs::write(&path, text + "\n").map_err(io(&path))
}

/// Adds this build to `dir`'s list.
fn record_build(dir: &Path) -> Result<(), StoreError> {
    let mut builds = read_builds(dir)?;
    if !builds.iter().any(|b| b == build_id()) {
        builds.push(build_id().to_owned());
        write_build_list(dir, &builds)?;
    }
    Ok(())
}

/// The file of an experiment folder that records what each scenario was when its runs
/// were made: name -> fingerprint (scenario and terrain).
pub const SCENARIOS_FILE: &str = "scenarios.json";

/// Reads `dir/scenarios.json` (empty if absent: folders of older builds).
pub fn read_fingerprints(dir: &Path) -> Result<BTreeMap<String, String>, StoreError> {
    read_json_or_default(&dir.join(SCENARIOS_FILE))
}

/// Checks `now` (scenario -> fingerprint) against what `dir` recorded, and records any
/// scenario it did not know: a resumed experiment must run on the scenarios its records
/// were made on, or it would mix two experiments under one name.
pub fn check_fingerprints(dir: &Path, now: &BTreeMap<String, String>) -> Result<(), StoreError> {
    let mut known = read_fingerprints(dir)?;
    for (scenario, fp) in now {
        match known.get(scenario) {
            Some(then) if then != fp => {
                return Err(StoreError::ScenarioChanged {
                    dir: dir.to_path_buf(),
                    scenario: scenario.clone(),
                    then: then.clone(),
                    now: fp.clone(),
                })
            }
            Some(_) => {}
            None => {
                known.insert(scenario.clone(), fp.clone());
            }
        }
    }
    let path = dir.join(SCENARIOS_FILE);
    let text = serde_json::to_string_pretty(&known).expect("a map serialises");
    std::fs::write(&path, text + "\n").map_err(io(&path))
}

/// Checks that every record of `path` is a run of `spec` (its scenario, parameter set,
/// method and run number in the matrix, under its master seed): a concatenated or edited
/// `runs.jsonl` must not be summarised as this experiment.
pub fn check_belong(
    path: &Path,
    spec: &ExperimentSpec,
    records: &[RunRecord],
) -> Result<(), StoreError> {
    let runs: HashSet<RunKey> = spec.runs().into_iter().collect();
    for r in records {
        let why = if r.master_seed != spec.master_seed {
            format!(
                "master seed {}, the experiment's is {}",
                r.master_seed, spec.master_seed
            )
        } else if !runs.contains(&r.key()) {
            "not in its matrix of scenarios, parameter sets, methods and runs".to_string()
        } else {
            continue;
        };
        return Err(StoreError::Foreign {
            path: path.to_path_buf(),
            key: describe(&r.key()),
            why,
        });
    }
    Ok(())
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> StoreError + '_ {
    move |source| StoreError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Reads `dir/experiment.json`.
pub fn read_spec(dir: &Path) -> Result<ExperimentSpec, StoreError> {
    let path = dir.join(SPEC_FILE);
    let text = std::fs::read_to_string(&path).map_err(io(&path))?;
    serde_json::from_str(&text).map_err(|e| StoreError::BadSpec {
        path,
        message: e.to_string(),
    })
}

/// Reads the records of `dir/runs.jsonl` (none if absent). With `repair`, a torn last line
/// is cut off the file; without, it is only skipped.
pub fn read_records(dir: &Path, repair: bool) -> Result<Vec<RunRecord>, StoreError> {
    let path = dir.join(RUNS_FILE);
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(io(&path)(e)),
    };
    let complete = bytes.iter().rposition(|b| *b == b'\n').map_or(0, |p| p + 1);
    if complete < bytes.len() && repair {
        let f = OpenOptions::new()
            .write(true)
            .open(&path)
            .map_err(io(&path))?;
        f.set_len(complete as u64).map_err(io(&path))?;
    }
    let text = String::from_utf8_lossy(&bytes[..complete]);
    let mut records = Vec::new();
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let r: RunRecord = serde_json::from_str(line).map_err(|e| StoreError::BadRecord {
            path: path.clone(),
            line: i + 1,
            message: e.to_string(),
        })?;
        records.push(r);
    }
    Ok(records)
}

/// Fails if two records share a run identity.
pub fn check_unique(path: &Path, records: &[RunRecord]) -> Result<(), StoreError> {
    let mut seen = HashSet::new();
    for r in records {
        if !seen.insert(r.key()) {
            return Err(StoreError::Duplicate {
                path: path.to_path_buf(),
                key: describe(&r.key()),
            });
        }
    }
    Ok(())
}

/// `scenario/param_set/method#run`.
#[must_use]
pub fn describe(k: &RunKey) -> String {
    format!("{}/{}/{}#{}", k.scenario, k.param_set, k.method, k.run)
}

/// Appends records to `runs.jsonl` from any thread.
pub struct RecordWriter {
    path: PathBuf,
    file: Mutex<File>,
    /// The folder's lock, held while this writer or a copy of it lives.
    lock: FolderLock,
}

/// A held lock of a bench folder ([`LOCK_FILE`]), released when the last copy is dropped:
/// the runner hands one to its caller, so the lock also covers the summary and figures
/// written after the runs.
#[derive(Debug, Clone, Default)]
pub struct FolderLock {
    /// The locked file (none where the file system cannot lock); held, never read.
    _file: Option<std::sync::Arc<File>>,
}

/// The file a bench holds locked in its folder while it writes there.
pub const LOCK_FILE: &str = ".bench.lock";

/// Takes `dir`'s lock: two benches appending to one `runs.jsonl` would each run what the
/// other runs, and the duplicates make the folder unusable. Where the file system cannot
/// lock, an empty lock (the bench goes on unguarded there rather than refuse to run).
fn lock(dir: &Path) -> Result<FolderLock, StoreError> {
    let path = dir.join(LOCK_FILE);
    let file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&path)
        .map_err(io(&path))?;
    match file.try_lock() {
        Ok(()) => Ok(FolderLock {
            _file: Some(std::sync::Arc::new(file)),
        }),
        Err(std::fs::TryLockError::WouldBlock) => Err(StoreError::Busy {
            dir: dir.to_path_buf(),
        }),
        Err(std::fs::TryLockError::Error(_)) => Ok(FolderLock::default()),
    }
}

impl RecordWriter {
    /// A copy of the folder's lock, which keeps it held after this writer is dropped.
    #[must_use]
    pub fn lock(&self) -> FolderLock {
        self.lock.clone()
    }

    /// Prepares `dir` for `spec`: writes `experiment.json` or checks it matches, and with
    /// `resume` returns the runs already recorded. Without `resume` the folder must not hold
    /// records yet.
    pub fn open(
        dir: &Path,
        spec: &ExperimentSpec,
        resume: bool,
    ) -> Result<(Self, Vec<RunRecord>), StoreError> {
        check_not_a_plan_folder(dir)?;
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let lock = lock(dir)?;
        let spec_path = dir.join(SPEC_FILE);
        if spec_path.exists() {
            let old = read_spec(dir)?;
            if old != *spec {
                return Err(StoreError::Mismatch {
                    dir: dir.to_path_buf(),
                    what: diff(&old, spec),
                });
            }
        } else {
            let text = serde_json::to_string_pretty(spec).expect("a spec serialises");
            std::fs::write(&spec_path, text + "\n").map_err(io(&spec_path))?;
        }
        let existing = read_records(dir, true)?;
        if !resume && !existing.is_empty() {
            return Err(StoreError::NotEmpty {
                dir: dir.to_path_buf(),
                count: existing.len(),
            });
        }
        let path = dir.join(RUNS_FILE);
        check_unique(&path, &existing)?;
        check_belong(&path, spec, &existing)?;
        record_build(dir)?;
        let file = OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .map_err(io(&path))?;
        Ok((
            Self {
                path,
                file: Mutex::new(file),
                lock,
            },
            existing,
        ))
    }

    /// Appends one record as one line, in one write, and syncs it to disk.
    pub fn append(&self, record: &RunRecord) -> Result<(), StoreError> {
        let mut line = serde_json::to_vec(record).expect("a record serialises");
        line.push(b'\n');
        let mut f = self
            .file
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        f.write_all(&line).map_err(io(&self.path))?;
        f.sync_data().map_err(io(&self.path))
    }
}

/// Names the first field where two specs differ, as this folder's record (`there`) against
/// the experiment asked for (`now`).
fn diff(old: &ExperimentSpec, new: &ExperimentSpec) -> String {
    difference(old, new, ["there", "now"])
}

/// Names the first field where specs `a` and `b` differ, each value followed by its label.
pub fn difference(old: &ExperimentSpec, new: &ExperimentSpec, [a, b]: [&str; 2]) -> String {
    if old.master_seed != new.master_seed {
        format!(
            "master seed {} {a}, {} {b}",
            old.master_seed, new.master_seed
        )
    } else if old.runs != new.runs {
        format!("{} runs {a}, {} {b}", old.runs, new.runs)
    } else if old.scenarios != new.scenarios {
        format!("scenarios {:?} {a}, {:?} {b}", old.scenarios, new.scenarios)
    } else if old.methods != new.methods {
        let labels = |s: &ExperimentSpec| {
            s.methods
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(",")
        };
        format!("methods {} {a}, {} {b}", labels(old), labels(new))
    } else if old.budget != new.budget || old.budget_policy != new.budget_policy {
        format!(
            "budget {} {a}, {} {b}",
            budget_words(old),
            budget_words(new)
        )
    } else if old.profile != new.profile {
        format!(
            "feasibility profile {} {a}, {} {b}",
            old.profile, new.profile
        )
    } else if old.terrain != new.terrain {
        let terrain = |s: &ExperimentSpec| {
            s.terrain
                .clone()
                .unwrap_or_else(|| "each scenario's own".into())
        };
        format!("terrain {} {a}, {} {b}", terrain(old), terrain(new))
    } else {
        "other parameter sets (--params, --population)".into()
    }
}

/// A spec's budget for a message: `equal: 38700 evaluations`, `paper: 200 iterations`.
fn budget_words(s: &ExperimentSpec) -> String {
    let b = &s.budget;
    let mut parts = Vec::new();
    if let Some(i) = b.iterations {
        parts.push(format!("{i} iterations"));
    }
    if let Some(e) = b.evaluations {
        parts.push(format!("{e} evaluations"));
    }
    if let Some(t) = b.time_limit_ms {
        parts.push(format!("{t} ms"));
    }
    if b.until_feasible {
        parts.push("until feasible".into());
    }
    let policy = match s.budget_policy {
        BudgetPolicy::Equal => "equal",
        BudgetPolicy::Paper => "paper",
    };
    if parts.is_empty() {
        policy.to_string()
    } else {
        format!("{policy}: {}", parts.join(", "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarmplan_core::feasibility::FeasibilityProfile;
    use swarmplan_core::method::Method;

    #[test]
    fn a_mismatch_names_what_differs() {
        let old = ExperimentSpec::paper(1);
        let mut new = old.clone();
        new.methods = vec![Method::preset("pso").expect("a preset")];
        assert!(
            diff(&old, &new).ends_with("there, pso now"),
            "{}",
            diff(&old, &new)
        );
        let mut new = old.clone();
        new.profile = FeasibilityProfile::Paper;
        assert_eq!(
            diff(&old, &new),
            "feasibility profile strict there, paper now"
        );
        let mut new = old.clone();
        new.terrain = Some("dem.tif".into());
        assert_eq!(
            diff(&old, &new),
            "terrain each scenario's own there, dem.tif now"
        );
        let mut new = old.clone();
        new.budget.evaluations = Some(5000);
        new.budget.iterations = None;
        let said = diff(&old, &new);
        assert!(
            said.starts_with("budget equal: ")
                && said.ends_with("there, equal: 5000 evaluations now"),
            "{said}"
        );
    }

    #[test]
    fn a_folder_takes_one_writer_at_a_time() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let spec = ExperimentSpec::paper(1);
        let (first, _) = RecordWriter::open(dir.path(), &spec, true).expect("the first writer");
        let second = RecordWriter::open(dir.path(), &spec, true);
        assert!(
            matches!(second, Err(StoreError::Busy { .. })),
            "{:?}",
            second.err()
        );
        // A copy of the lock outlives the writer (the runner's caller holds it while it
        // writes the summary).
        let kept = first.lock();
        drop(first);
        assert!(matches!(
            RecordWriter::open(dir.path(), &spec, true),
            Err(StoreError::Busy { .. })
        ));
        drop(kept);
        assert!(RecordWriter::open(dir.path(), &spec, true).is_ok());
    }
}
