//! Runs an experiment's pending runs in parallel (rayon) and records each as it finishes.
//!
//! Results do not depend on the thread count or the order runs finish in: each run's seed
//! comes from its identity, runs share nothing mutable, and the summary sorts records by
//! identity before computing anything.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;
use swarmplan_core::optim::cancel::Cancel;
use swarmplan_core::optim::Termination;
use swarmplan_core::run::{run, RunRequest};
use swarmplan_core::world::World;
use swarmplan_io::scenario::{build_world, ScenarioError};

use swarmplan_io::catalog::load_spec;
use thiserror::Error;

use crate::matrix::{ExperimentSpec, MatrixError, RunKey, Shard};
use crate::record::RunRecord;
use crate::store::{check_fingerprints, FolderLock, RecordWriter, StoreError};
use crate::workers;

/// Why an experiment did not run to its end.
#[derive(Debug, Error)]
pub enum RunnerError {
    /// The experiment's matrix is refused.
    #[error(transparent)]
    Matrix(#[from] MatrixError),
    /// A scenario (or the experiment's terrain) could not be loaded or built.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// The folder could not be opened, checked or written.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// The pool of worker threads could not be built.
    #[error("cannot start {threads} worker threads: {message}")]
    Pool {
        /// Number of threads asked for.
        threads: usize,
        /// The thread pool's error.
        message: String,
    },
    /// The options' cancel flag was raised: the runs recorded stay, the rest were not run
    /// (or stopped, and not recorded).
    #[error("interrupted: {recorded} runs of this call were recorded; resume continues")]
    Cancelled {
        /// Runs this call recorded before it stopped.
        recorded: usize,
    },
}

/// How to run.
#[derive(Debug, Clone, Copy, Default)]
pub struct RunnerOptions {
    /// Worker threads (0: one per core, or `RAYON_NUM_THREADS`), held to the cores
    /// ([`crate::workers`]).
    pub threads: usize,
    /// Only this slice of the matrix.
    pub shard: Option<Shard>,
    /// Continue the records already in the folder.
    pub resume: bool,
    /// A flag that stops the experiment between runs and the runs in flight between
    /// iterations (none from the command line, which its signal stops).
    pub cancel: Cancel,
}

/// What a call did.
#[derive(Debug, Clone)]
pub struct RunnerOutcome {
    /// Every record of the folder (earlier ones included), sorted by run identity.
    pub records: Vec<RunRecord>,
    /// Runs executed by this call.
    pub executed: usize,
    /// Runs of this shard found already recorded.
    pub skipped: usize,
    /// The folder's lock, held while this outcome lives (the caller writes the summary
    /// and figures under it).
    pub lock: FolderLock,
}

/// Runs this shard's pending runs into `dir`, calling `start(pending)` once and
/// `done(record)` after each run is recorded (from worker threads).
pub fn run_experiment(
    spec: &ExperimentSpec,
    dir: &Path,
    opts: RunnerOptions,
    start: &mut dyn FnMut(usize),
    done: &(dyn Fn(&RunRecord) + Sync),
) -> Result<RunnerOutcome, RunnerError> {
    spec.validate()?;
    let worlds: Vec<(String, World)> = spec
        .scenarios
        .iter()
        .map(|name| {
            let mut loaded = load_spec(name)?;
            loaded.spec.planning.profile = spec.profile;
            let terrain = spec.terrain.as_ref().map(PathBuf::from);
            Ok((name.clone(), build_world(&loaded, terrain.as_deref())?))
        })
        .collect::<Result<_, ScenarioError>>()?;
    let (writer, existing) = RecordWriter::open(dir, spec, opts.resume)?;
    let fingerprints = worlds
        .iter()
        .map(|(name, world)| (name.clone(), world_fingerprint(world)))
        .collect();
    check_fingerprints(dir, &fingerprints)?;
    let done_keys: HashSet<RunKey> = existing.iter().map(RunRecord::key).collect();
    let mine: Vec<RunKey> = spec
        .runs()
        .into_iter()
        .enumerate()
        .filter(|(pos, _)| opts.shard.is_none_or(|s| s.contains(*pos)))
        .map(|(_, k)| k)
        .collect();
    let mut pending: Vec<RunKey> = mine
        .iter()
        .filter(|k| !done_keys.contains(k))
        .cloned()
        .collect();
    // Run-major: run k of every scenario, set and method before run k + 1 (in each
    // worker's share). The matrix lists a method's runs together, so its cheap methods
    // came first and a time estimate from the runs done fell short (the paper experiment
    // said 418 s left at 484 s, then took 1,178 s); an interrupted bench holds about as many
    // runs of each method. Which runs a shard owns and every run's seed are unchanged.
    pending.sort_by(|a, b| a.run.cmp(&b.run).then_with(|| a.cmp(b)));
    let skipped = mine.len() - pending.len();
    start(pending.len());

    // More workers than runs would only idle (each costs a stack and holds a run in
    // flight), more than cores only wait on each other.
    let threads = workers::Asked::from_count_or_env(opts.threads)
        .threads(workers::cores())
        .min(pending.len().max(1));
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| RunnerError::Pool {
            threads,
            message: e.to_string(),
        })?;
    let recorded = AtomicUsize::new(0);
    let new: Vec<RunRecord> = pool
        .install(|| {
            pending
                .par_iter()
                .map(|key| {
                    if opts.cancel.requested() {
                        return Err(Stop::Cancelled);
                    }
                    let world = &worlds
                        .iter()
                        .find(|(n, _)| *n == key.scenario)
                        .expect("every scenario of the matrix was loaded")
                        .1;
                    let set = spec
                        .param_set(&key.param_set)
                        .expect("keys come from the spec's sets");
                    let mut budget = spec.budget_for(key.method);
                    budget.cancel = opts.cancel;
                    let req = RunRequest {
                        method: key.method,
                        params: set.params,
                        budget,
                        seed: spec.seed(key),
                    };
                    let result = run(world, &req, &mut |_| {});
                    if result.outcome.termination == Termination::Cancelled {
                        return Err(Stop::Cancelled);
                    }
                    let record = RunRecord::new(key, spec.master_seed, set.params, &result);
                    writer.append(&record).map_err(Stop::Store)?;
                    recorded.fetch_add(1, Ordering::Relaxed);
                    done(&record);
                    Ok(record)
                })
                .collect::<Result<Vec<_>, Stop>>()
        })
        .map_err(|stop| match stop {
            Stop::Store(e) => RunnerError::Store(e),
            Stop::Cancelled => RunnerError::Cancelled {
                recorded: recorded.load(Ordering::Relaxed),
            },
        })?;
    let executed = new.len();
    let mut records = existing;
    records.extend(new);
    records.sort_by_key(RunRecord::key);
    Ok(RunnerOutcome {
        records,
        executed,
        skipped,
        lock: writer.lock(),
    })
}

/// Why a worker stopped the experiment.
enum Stop {
    Store(StoreError),
    Cancelled,
}

/// A fingerprint of what a run is made on: the scenario as planned (its TOML, after the
/// experiment's profile) and its terrain's heights ([`swarmplan_core::world::terrain::Terrain::fingerprint`]),
/// FNV-1a, 16 hex digits.
#[must_use]
pub fn world_fingerprint(world: &World) -> String {
    use std::hash::Hasher as _;
    let mut h = fnv::FnvHasher::default();
    h.write(swarmplan_io::scenario::to_toml(world.spec()).as_bytes());
    h.write(world.terrain().fingerprint().as_bytes());
    format!("{:016x}", h.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::AtomicBool;
    use swarmplan_core::method::Method;

    #[test]
    fn a_raised_cancel_flag_records_nothing_more_and_says_so() {
        static RAISED: AtomicBool = AtomicBool::new(true);
        let dir = tempfile::tempdir().expect("a temporary folder");
        let mut spec = ExperimentSpec::paper(1);
        spec.scenarios = vec!["tiny".into()];
        spec.methods = vec![Method::preset("pso").expect("a preset")];
        spec.runs = 3;
        let opts = RunnerOptions {
            threads: 1,
            cancel: Cancel::on(&RAISED),
            ..RunnerOptions::default()
        };
        let outcome = run_experiment(&spec, dir.path(), opts, &mut |_| {}, &|_| {});
        assert!(
            matches!(outcome, Err(RunnerError::Cancelled { recorded: 0 })),
            "{outcome:?}"
        );
        let records = std::fs::read_to_string(dir.path().join("runs.jsonl")).unwrap_or_default();
        assert!(records.is_empty(), "{records}");
    }

    #[test]
    fn runs_go_run_major_so_every_method_has_its_first_runs_early() {
        let dir = tempfile::tempdir().expect("a temporary folder");
        let mut spec = ExperimentSpec::paper(1);
        spec.scenarios = vec!["tiny".into()];
        spec.methods = ["pso", "gwo", "abc"]
            .iter()
            .map(|m| Method::preset(m).expect("a preset"))
            .collect();
        spec.runs = 3;
        spec.budget = swarmplan_core::optim::Budget::evaluations(40);
        let order = std::sync::Mutex::new(Vec::new());
        let opts = RunnerOptions {
            threads: 1,
            ..RunnerOptions::default()
        };
        run_experiment(&spec, dir.path(), opts, &mut |_| {}, &|r| {
            order.lock().expect("not poisoned").push(r.run);
        })
        .expect("the runs");
        assert_eq!(
            order.into_inner().expect("not poisoned"),
            [0, 0, 0, 1, 1, 1, 2, 2, 2]
        );
    }
}
