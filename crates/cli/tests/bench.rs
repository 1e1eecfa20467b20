//! `swarmplan bench` and `aggregate` end to end on the `tiny` scenario: determinism across
//! thread counts, surviving SIGKILL with `--resume`, shards that aggregate to the same
//! summary, and refusals that protect results.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::path::Path;
use std::process::Stdio;
use std::time::{Duration, Instant};

use assert_cmd::Command;
use predicates::prelude::*;

const SMALL: [&str; 10] = [
    "--scenarios",
    "tiny",
    "--algos",
    "dls-smpso,spso,pso",
    "--runs",
    "6",
    "--iterations",
    "10",
    "--population",
    "10",
];

fn bench(out: &Path, extra: &[&str]) -> assert_cmd::assert::Assert {
    Command::cargo_bin("swarmplan")
        .unwrap()
        .arg("bench")
        .args(SMALL)
        .args(extra)
        .arg("--out")
        .arg(out)
        .assert()
}

fn lines(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn keys(records: &[serde_json::Value]) -> Vec<String> {
    let mut k: Vec<String> = records
        .iter()
        .map(|r| {
            format!(
                "{}/{}/{}#{}",
                r["scenario"], r["param_set"], r["algorithm"], r["run"]
            )
        })
        .collect();
    k.sort();
    k
}

#[test]
fn summary_is_identical_on_one_and_two_threads() {
    let dir = tempfile::tempdir().unwrap();
    let (a, b) = (dir.path().join("t1"), dir.path().join("t2"));
    bench(&a, &["--threads", "1", "--seed", "9"]).success();
    bench(&b, &["--threads", "2", "--seed", "9"]).success();
    let sa = std::fs::read_to_string(a.join("summary.json")).unwrap();
    assert_eq!(sa, std::fs::read_to_string(b.join("summary.json")).unwrap());
    let summary: serde_json::Value = serde_json::from_str(&sa).unwrap();
    assert_eq!(summary["master_seed"], 9);
    assert_eq!(summary["records"], 18);
    let md = std::fs::read_to_string(a.join("summary.md")).unwrap();
    assert!(
        md.contains("| Algorithm | Worst | Optimal | Mean | FR(%) |"),
        "{md}"
    );
    assert!(md.contains("Friedman") && md.contains("Fisher"), "{md}");
    assert!(
        std::fs::read_to_string(a.join("summary.csv"))
            .unwrap()
            .lines()
            .count()
            == 4
    );
    // Records carry seeds, costs and traces.
    let recs = lines(&a.join("runs.jsonl"));
    assert_eq!(recs.len(), 18);
    assert!(recs.iter().all(|r| r["seed"].is_u64()
        && r["master_seed"] == 9
        && r["convergence"].as_array().unwrap().len() == 11));
}

#[test]
fn a_killed_bench_resumes_without_losing_or_repeating_a_run() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b");
    let args: Vec<String> = [
        "bench",
        "--scenarios",
        "tiny",
        "--algos",
        "dls-smpso,spso",
        "--runs",
        "40",
        "--iterations",
        "60",
        "--population",
        "20",
        "--threads",
        "2",
        "--out",
    ]
    .iter()
    .map(|s| (*s).to_string())
    .chain([out.display().to_string()])
    .collect();
    let bin = assert_cmd::cargo::cargo_bin("swarmplan");
    let mut child = std::process::Command::new(&bin)
        .args(&args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let runs = out.join("runs.jsonl");
    let deadline = Instant::now() + Duration::from_secs(60);
    loop {
        let n = std::fs::read_to_string(&runs)
            .map(|t| t.lines().count())
            .unwrap_or(0);
        if n >= 5 || Instant::now() > deadline {
            break;
        }
        std::thread::sleep(Duration::from_millis(5));
    }
    child.kill().unwrap(); // SIGKILL on Unix
    child.wait().unwrap();
    let before = std::fs::read_to_string(&runs)
        .map(|t| t.lines().count())
        .unwrap_or(0);
    assert!(
        before >= 5,
        "the bench wrote {before} records before the kill"
    );
    // Without --resume the folder is protected.
    Command::new(&bin)
        .args(&args)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--resume"));
    Command::new(&bin)
        .args(&args)
        .arg("--resume")
        .assert()
        .success();
    let recs = lines(&runs);
    let k = keys(&recs);
    let mut unique = k.clone();
    unique.dedup();
    assert_eq!(k.len(), 80, "{before} before the kill");
    assert_eq!(unique.len(), 80);
    assert!(out.join("summary.json").exists());
}

#[test]
fn shards_aggregate_to_the_unsharded_summary() {
    let dir = tempfile::tempdir().unwrap();
    let whole = dir.path().join("whole");
    bench(&whole, &["--seed", "4"]).success();
    let shards: Vec<_> = (1..=3).map(|k| dir.path().join(format!("s{k}"))).collect();
    for (k, s) in shards.iter().enumerate() {
        bench(s, &["--seed", "4", "--shard", &format!("{}/3", k + 1)]).success();
    }
    let merged = dir.path().join("merged");
    let bin = assert_cmd::cargo::cargo_bin("swarmplan");
    Command::new(&bin)
        .arg("aggregate")
        .args(&shards)
        .arg("--out")
        .arg(&merged)
        .assert()
        .success();
    assert_eq!(
        std::fs::read_to_string(whole.join("summary.json")).unwrap(),
        std::fs::read_to_string(merged.join("summary.json")).unwrap()
    );
    // A missing shard is named; a shard given twice is a duplicate.
    Command::new(&bin)
        .arg("aggregate")
        .args(&shards[..2])
        .arg("--out")
        .arg(dir.path().join("m2"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("missing"));
    Command::new(&bin)
        .arg("aggregate")
        .args([&shards[0], &shards[0]])
        .arg("--out")
        .arg(dir.path().join("m3"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("appears twice").or(predicate::str::contains("also in")));
}

#[test]
fn a_different_experiment_cannot_resume_in_the_same_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("x");
    bench(&out, &["--seed", "1"]).success();
    bench(&out, &["--seed", "2", "--resume"]).code(2).stderr(
        predicate::str::contains("different experiment")
            .and(predicate::str::contains("master seed")),
    );
}
