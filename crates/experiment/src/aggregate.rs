//! Merging the folders of a sharded experiment: same experiment in each, no run twice,
//! none missing.

use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};

use thiserror::Error;

use crate::matrix::ExperimentSpec;
use crate::record::RunRecord;
use crate::store::{
    check_belong, describe, difference, read_fingerprints, read_records, read_spec, StoreError,
    RUNS_FILE,
};

/// Why the folders of a sharded experiment cannot be merged.
#[derive(Debug, Error)]
pub enum AggregateError {
    /// No folder was given.
    #[error("aggregate: no folder given")]
    NoFolders,
    /// A folder's files could not be read, or its records are not runs of its experiment.
    #[error(transparent)]
    Store(#[from] StoreError),
    /// A folder's `experiment.json` differs from the first folder's.
    #[error("{other}: a different experiment from {first}: {what}")]
    Different {
        /// The first folder given, whose experiment the others must match.
        first: PathBuf,
        /// The folder whose experiment differs.
        other: PathBuf,
        /// The first field that differs, with both values.
        what: String,
    },
    /// A folder recorded another fingerprint for a scenario than an earlier folder did: its
    /// runs were made on another version of the scenario or its terrain.
    #[error("{other}: scenario `{scenario}` is not the one its runs in {first} were made on (compare their scenarios.json)")]
    ScenarioDiffers {
        /// The folder that recorded the scenario first.
        first: PathBuf,
        /// The folder whose fingerprint differs.
        other: PathBuf,
        /// The scenario's name.
        scenario: String,
    },
    /// A run is recorded twice (in two folders, or twice in one).
    #[error("{path}: run {key} is also in {earlier}")]
    Duplicate {
        /// The `runs.jsonl` holding the second record of the run.
        path: PathBuf,
        /// The run, as `scenario/param_set/method#run`.
        key: String,
        /// The `runs.jsonl` holding its first record.
        earlier: PathBuf,
    },
    /// Some runs of the matrix are in none of the folders.
    #[error("{missing} of {total} runs are missing (first: {first}); run the remaining shards, or `bench --resume` in their folders")]
    Missing {
        /// Number of runs missing.
        missing: usize,
        /// Number of runs in the matrix.
        total: usize,
        /// The first missing run in the matrix order, as `scenario/param_set/method#run`.
        first: String,
    },
}

/// The experiment and all its records from `dirs`, checked complete and without duplicates.
pub fn aggregate(dirs: &[PathBuf]) -> Result<(ExperimentSpec, Vec<RunRecord>), AggregateError> {
    let first = dirs.first().ok_or(AggregateError::NoFolders)?;
    let spec = read_spec(first)?;
    let mut records: Vec<(RunRecord, &Path)> = Vec::new();
    let mut fingerprints: BTreeMap<String, (String, &PathBuf)> = BTreeMap::new();
    for d in dirs {
        let theirs = read_spec(d)?;
        if theirs != spec {
            return Err(AggregateError::Different {
                first: first.clone(),
                other: d.clone(),
                what: difference(&spec, &theirs, [&format!("in {}", first.display()), "here"]),
            });
        }
        for (scenario, fp) in read_fingerprints(d)? {
            if let Some((then, there)) = fingerprints.get(&scenario) {
                if *then != fp {
                    return Err(AggregateError::ScenarioDiffers {
                        first: (*there).clone(),
                        other: d.clone(),
                        scenario,
                    });
                }
            } else {
                fingerprints.insert(scenario, (fp, d));
            }
        }
        let shard = read_records(d, false)?;
        check_belong(&d.join(RUNS_FILE), &spec, &shard)?;
        for r in shard {
            records.push((r, d.as_path()));
        }
    }
    let mut seen = std::collections::HashMap::new();
    for (r, d) in &records {
        if let Some(earlier) = seen.insert(r.key(), *d) {
            return Err(AggregateError::Duplicate {
                path: d.join(RUNS_FILE),
                key: describe(&r.key()),
                earlier: earlier.join(RUNS_FILE),
            });
        }
    }
    let have: HashSet<_> = seen.into_keys().collect();
    let all = spec.runs();
    let missing: Vec<_> = all.iter().filter(|k| !have.contains(k)).collect();
    if let Some(m) = missing.first() {
        return Err(AggregateError::Missing {
            missing: missing.len(),
            total: all.len(),
            first: describe(m),
        });
    }
    let mut out: Vec<RunRecord> = records.into_iter().map(|(r, _)| r).collect();
    out.sort_by_key(RunRecord::key);
    Ok((spec, out))
}
