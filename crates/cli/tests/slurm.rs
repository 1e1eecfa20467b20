//! A bench as a real Slurm array job: `docs/slurm/bench-array.sbatch` submitted with
//! `sbatch --array`, one shard per task, then `aggregate`; the merged summary must equal the
//! unsharded run's byte for byte.
//!
//! Needs a running Slurm cluster (`.ci/slurm-up` starts a one-node one and `.ci/run` calls
//! it). Without `sbatch` the test says so and passes, unless `SWARMPLAN_REQUIRE_SLURM=1`
//! (set by `.ci/run`), where a missing or unresponsive cluster fails it.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::path::Path;
use std::process::Command;

const BENCH: [&str; 12] = [
    "--scenarios",
    "tiny",
    "--algos",
    "dls-smpso,spso,qpso",
    "--runs",
    "4",
    "--iterations",
    "8",
    "--population",
    "8",
    "--seed",
    "11",
];
const TASKS: usize = 3;

fn cluster_is_up() -> Result<(), String> {
    let required = std::env::var("SWARMPLAN_REQUIRE_SLURM").is_ok_and(|v| v == "1");
    let probe = Command::new("sinfo")
        .args(["--noheader", "--format=%T"])
        .output();
    let why = match probe {
        Ok(o) if o.status.success() && !o.stdout.is_empty() => return Ok(()),
        Ok(o) => format!(
            "sinfo failed ({}): {}",
            o.status,
            String::from_utf8_lossy(&o.stderr).trim()
        ),
        Err(e) => format!("sinfo cannot run: {e}"),
    };
    if required {
        panic!("SWARMPLAN_REQUIRE_SLURM=1 but no Slurm cluster answers: {why} (start one with .ci/slurm-up)");
    }
    Err(why)
}

fn job_script() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/slurm/bench-array.sbatch")
}

#[test]
fn a_slurm_array_job_of_shards_aggregates_to_the_unsharded_summary() {
    if let Err(why) = cluster_is_up() {
        eprintln!("skipped: no Slurm cluster ({why})");
        return;
    }
    let bin = assert_cmd::cargo::cargo_bin("swarmplan");
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole");
    let run = Command::new(&bin)
        .arg("bench")
        .args(BENCH)
        .arg("--out")
        .arg(&whole)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );

    let jobs = dir.path().join("jobs");
    let logs = dir.path().join("slurm-%A_%a.out");
    // --wait returns when every task of the array has ended, with a non-zero status if one
    // failed; `timeout` keeps a stuck cluster from hanging the suite.
    let submit = Command::new("timeout")
        .arg("600")
        .arg("sbatch")
        .arg("--wait")
        .arg(format!("--array=1-{TASKS}"))
        .arg("--cpus-per-task=1")
        .arg(format!("--output={}", logs.display()))
        .arg(job_script())
        .arg(&jobs)
        .args(BENCH)
        .env("SWARMPLAN", &bin)
        .output()
        .unwrap();
    let task_logs = || -> String {
        let mut all = String::new();
        for e in std::fs::read_dir(dir.path()).unwrap().flatten() {
            if e.file_name().to_string_lossy().starts_with("slurm-") {
                all += &std::fs::read_to_string(e.path()).unwrap_or_default();
            }
        }
        all
    };
    assert!(
        submit.status.success(),
        "sbatch: {}\n{}\ntask logs:\n{}",
        submit.status,
        String::from_utf8_lossy(&submit.stderr),
        task_logs()
    );
    let shards: Vec<_> = (1..=TASKS)
        .map(|k| jobs.join(format!("shard-{k}")))
        .collect();
    for s in &shards {
        assert!(
            s.join("runs.jsonl").exists(),
            "{}: {}",
            s.display(),
            task_logs()
        );
    }
    let merged = dir.path().join("merged");
    let run = Command::new(&bin)
        .arg("aggregate")
        .args(&shards)
        .arg("--out")
        .arg(&merged)
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert_eq!(
        std::fs::read_to_string(whole.join("summary.json")).unwrap(),
        std::fs::read_to_string(merged.join("summary.json")).unwrap(),
        "the summary of the array job's shards differs from the unsharded one"
    );
    // Each task ran its own shard: 12 runs split 4 / 4 / 4.
    for s in &shards {
        let n = std::fs::read_to_string(s.join("runs.jsonl"))
            .unwrap()
            .lines()
            .count();
        assert_eq!(n, 4, "{}", s.display());
    }
}

#[test]
fn the_documented_job_script_is_the_one_tested() {
    let script = std::fs::read_to_string(job_script()).unwrap();
    let doc = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/experiments.md"),
    )
    .unwrap();
    assert!(
        doc.contains(&script),
        "docs/experiments.md must show docs/slurm/bench-array.sbatch as it is"
    );
}
