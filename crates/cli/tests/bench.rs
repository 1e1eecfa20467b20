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
                r["scenario"], r["param_set"], r["method"], r["run"]
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
        md.contains("| Method | Worst | Optimal | Mean | FR(%) |"),
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
fn one_optimizer_on_two_encodings_is_two_labelled_methods() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("enc");
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args([
            "bench",
            "--scenarios",
            "tiny",
            "--methods",
            "spso,pso-uniform,pso/spherical/line",
        ])
        .args([
            "--runs",
            "3",
            "--iterations",
            "5",
            "--population",
            "8",
            "--out",
        ])
        .arg(&out)
        .assert()
        .success();
    let recs = lines(&out.join("runs.jsonl"));
    let parts = |label: &str| {
        let r = recs.iter().find(|r| r["method"] == label).unwrap();
        (
            r["optimizer"].as_str().unwrap().to_string(),
            r["encoding"].as_str().unwrap().to_string(),
            r["init"].as_str().unwrap().to_string(),
        )
    };
    assert_eq!(
        parts("spso"),
        ("pso".into(), "spherical".into(), "uniform".into())
    );
    assert_eq!(
        parts("pso-uniform"),
        ("pso".into(), "cartesian".into(), "uniform".into())
    );
    assert_eq!(
        parts("pso/spherical/line"),
        ("pso".into(), "spherical".into(), "line".into())
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let groups = summary["scenarios"][0]["groups"].as_array().unwrap();
    let labelled: Vec<(String, String)> = groups
        .iter()
        .map(|g| {
            (
                g["method"].as_str().unwrap().to_string(),
                g["encoding"].as_str().unwrap().to_string(),
            )
        })
        .collect();
    assert_eq!(labelled.len(), 3);
    assert!(labelled.contains(&("spso".into(), "spherical".into())));
    assert!(labelled.contains(&("pso-uniform".into(), "cartesian".into())));
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("| spso | pso | spherical | uniform |"), "{md}");
    assert!(
        md.contains("| pso-uniform | pso | cartesian | uniform |"),
        "{md}"
    );
}

#[test]
fn the_friedman_blocks_are_run_indices_with_one_seed_for_every_method() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("fr");
    bench(&out, &["--seed", "5"]).success();
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let sc = &summary["scenarios"][0];
    let blocks: Vec<u64> = sc["friedman_blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| b.as_u64().unwrap())
        .collect();
    assert_eq!(blocks, (0..6).collect::<Vec<u64>>());
    assert!(sc["friedman_note"]
        .as_str()
        .unwrap()
        .contains("common random numbers"));
    assert!(sc["friedman"]["p_value"].is_number() || sc["friedman"]["p_value"].is_string());
    // What the summary says holds in the records: each block's runs share one seed.
    let recs = lines(&out.join("runs.jsonl"));
    for b in &blocks {
        let seeds: Vec<u64> = recs
            .iter()
            .filter(|r| r["run"] == *b)
            .map(|r| r["seed"].as_u64().unwrap())
            .collect();
        assert_eq!(seeds.len(), 3);
        assert!(seeds.iter().all(|s| *s == seeds[0]), "block {b}: {seeds:?}");
    }
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("blocks: 6 run indices"), "{md}");
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
    // The merged folder names the build of its runs, as the shards do.
    assert_eq!(
        std::fs::read_to_string(whole.join("builds.json")).unwrap(),
        std::fs::read_to_string(merged.join("builds.json")).unwrap()
    );
    // Shards of two builds merge, with a warning that names each build and its folders.
    std::fs::write(shards[2].join("builds.json"), "[\"0123456789ab\"]").unwrap();
    let mixed = dir.path().join("mixed");
    Command::new(&bin)
        .arg("aggregate")
        .args(&shards)
        .arg("--out")
        .arg(&mixed)
        .assert()
        .success()
        .stderr(
            predicate::str::contains("build 0123456789ab (")
                .and(predicate::str::contains("s3"))
                .and(predicate::str::contains("mix its versions")),
        );
    let builds: Vec<String> =
        serde_json::from_str(&std::fs::read_to_string(mixed.join("builds.json")).unwrap()).unwrap();
    assert_eq!(builds.len(), 2, "{builds:?}");
    assert_eq!(builds[1], "0123456789ab");
    // A shard of a build that recorded none (older) is named too.
    std::fs::remove_file(shards[2].join("builds.json")).unwrap();
    Command::new(&bin)
        .arg("aggregate")
        .args(&shards)
        .arg("--out")
        .arg(dir.path().join("older"))
        .assert()
        .success()
        .stderr(
            predicate::str::contains("builds not recorded (")
                .and(predicate::str::contains("s3: no builds.json")),
        );
    // A malformed builds.json is refused before the out folder is made.
    std::fs::write(shards[2].join("builds.json"), "not json").unwrap();
    Command::new(&bin)
        .arg("aggregate")
        .args(&shards)
        .arg("--out")
        .arg(dir.path().join("never"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("builds.json"));
    assert!(!dir.path().join("never").exists());
    std::fs::remove_file(shards[2].join("builds.json")).unwrap();
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
    // The difference is named, whichever it is.
    bench(&out, &["--seed", "1", "--profile", "paper", "--resume"])
        .code(2)
        .stderr(predicate::str::contains(
            "feasibility profile strict there, paper now",
        ));
    // A --resume into a new folder says that it starts, and what.
    let fresh = dir.path().join("fresh");
    bench(&fresh, &["--seed", "1", "--resume"])
        .success()
        .stderr(
            predicate::str::contains("nothing to resume in")
                .and(predicate::str::contains("the flags describe")),
        );
    // Without flags, a mistyped folder is refused instead of starting the defaults.
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["bench", "--resume", "--out"])
        .arg(dir.path().join("mistyped"))
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains("nothing to resume there")
                .and(predicate::str::contains("leave out --resume")),
        );
    assert!(!dir.path().join("mistyped").join("runs.jsonl").exists());
}

#[test]
fn budgets_are_equal_by_default_and_per_method_with_budget_paper() {
    let dir = tempfile::tempdir().unwrap();
    let run = |name: &str, extra: &[&str]| {
        let out = dir.path().join(name);
        let assert = Command::cargo_bin("swarmplan")
            .unwrap()
            .args([
                "bench",
                "--scenarios",
                "tiny",
                "--runs",
                "2",
                "--population",
                "10",
            ])
            .args(extra)
            .arg("--out")
            .arg(&out)
            .assert()
            .success();
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
        (lines(&out.join("runs.jsonl")), stderr)
    };
    // Equal: every method spends exactly the budget, whatever its evaluations per
    // iteration (ABC's bees, DLS's substitution probes, swarmplan's sub-swarms).
    let (recs, stderr) = run(
        "equal",
        &[
            "--methods",
            "pso,abc,dls-smpso,swarmplan",
            "--evaluations",
            "700",
        ],
    );
    assert!(
        stderr.contains("equal budgets: 700 evaluations per run"),
        "{stderr}"
    );
    assert_eq!(recs.len(), 8);
    for r in &recs {
        assert_eq!(r["evaluations"], 700, "{}", r["method"]);
    }
    // Paper: each method its own setting; PSO does 200 iterations of 10 particles.
    let (recs, stderr) = run("paper", &["--methods", "pso", "--budget", "paper"]);
    assert!(stderr.contains("paper budgets"), "{stderr}");
    assert!(recs
        .iter()
        .all(|r| r["evaluations"] == 2010 && r["iterations"] == 200));
    let spec: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dir.path().join("paper/experiment.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(spec["budget_policy"], "paper");
    // The two do not combine.
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args([
            "bench",
            "--scenarios",
            "tiny",
            "--budget",
            "paper",
            "--iterations",
            "5",
        ])
        .arg("--out")
        .arg(dir.path().join("both"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("--budget paper"));
}

#[test]
fn the_profile_is_named_in_records_and_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("paper");
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args([
            "bench",
            "--scenarios",
            "tiny",
            "--methods",
            "spso",
            "--runs",
            "2",
        ])
        .args([
            "--evaluations",
            "200",
            "--population",
            "10",
            "--profile",
            "paper",
        ])
        .arg("--out")
        .arg(&out)
        .assert()
        .success()
        .stderr(predicate::str::contains("profile paper"));
    assert!(lines(&out.join("runs.jsonl"))
        .iter()
        .all(|r| r["profile"] == "paper"));
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("feasibility profile paper"), "{md}");
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["bench", "--scenarios", "tiny", "--profile", "lenient"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("expected `strict` or `paper`"));
    // A scenario that does not load, or a bad shard, is refused before the folder is made.
    let dir = tempfile::tempdir().unwrap();
    for extra in [
        &["--scenarios", "no-such-scenario"][..],
        &["--shard", "3/2"][..],
    ] {
        let out = dir.path().join("never");
        Command::cargo_bin("swarmplan")
            .unwrap()
            .args(["bench", "--methods", "pso"])
            .args(extra)
            .arg("--out")
            .arg(&out)
            .assert()
            .code(2);
        assert!(!out.exists(), "{extra:?} left {}", out.display());
    }
}

#[test]
fn a_bench_over_instances_ranks_the_methods_across_them() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("suite");
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args([
            "bench",
            "--scenarios",
            "tiny,gen-s1-u2-t2",
            "--algos",
            "spso,qpso,gwo",
            "--runs",
            "3",
            "--iterations",
            "5",
            "--population",
            "8",
            "--seed",
            "2",
        ])
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(md.contains("## Across 2 instances"), "{md}");
    assert!(
        md.contains("Friedman test over 2 instances and 3 methods"),
        "{md}"
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let ranks = &json["rankings"][0]["friedman"]["mean_ranks"];
    let sum: f64 = ranks
        .as_array()
        .unwrap()
        .iter()
        .map(|r| r.as_f64().unwrap())
        .sum();
    assert!((sum - 6.0).abs() < 1e-12, "mean ranks {ranks}");
    assert!(out.join("performance_profile.png").exists());
    assert!(out.join("performance_profile.svg").exists());
}

#[test]
fn resume_alone_reads_the_experiment_from_the_folder() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b");
    bench(&out, &["--seed", "6"]).success();
    let whole = std::fs::read_to_string(out.join("summary.json")).unwrap();
    // Keep the first 5 records, as an interrupted run would.
    let runs = out.join("runs.jsonl");
    let kept: String = std::fs::read_to_string(&runs)
        .unwrap()
        .lines()
        .take(5)
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(&runs, kept).unwrap();
    std::fs::remove_file(out.join("summary.json")).unwrap();
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["bench", "--resume", "--out"])
        .arg(&out)
        .assert()
        .success()
        .stderr(predicate::str::contains(
            "resuming the experiment recorded in",
        ));
    assert_eq!(
        std::fs::read_to_string(out.join("summary.json")).unwrap(),
        whole
    );
    assert_eq!(lines(&runs).len(), 18);
}

#[test]
fn records_say_when_the_best_plan_first_became_feasible() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("anytime");
    Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["bench", "--scenarios", "tiny", "--methods", "swarmplan"])
        .args(["--runs", "3", "--evaluations", "3000", "--seed", "1"])
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let records = lines(&out.join("runs.jsonl"));
    let feasible: Vec<&serde_json::Value> =
        records.iter().filter(|r| r["feasible"] == true).collect();
    assert!(!feasible.is_empty(), "no feasible run on tiny");
    for r in feasible {
        let first = r["first_feasible_evaluations"].as_u64().unwrap();
        assert!(first <= r["evaluations"].as_u64().unwrap(), "{r}");
        // It is a point of the convergence record, where the best plan was feasible.
        let at = r["convergence_evaluations"]
            .as_array()
            .unwrap()
            .iter()
            .position(|e| e.as_u64() == Some(first));
        assert!(at.is_some(), "{r}");
    }
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    assert!(
        md.contains("median evaluations to the first feasible plan"),
        "{md}"
    );
    let csv = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "median_first_feasible_evaluations")
        .unwrap();
    let row: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    let median: f64 = row[col].parse().unwrap();
    assert!(median > 0.0 && median <= 3000.0, "{median}");
}

#[test]
fn a_resume_on_an_edited_scenario_or_foreign_records_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let scenario = dir.path().join("mine.toml");
    let shown = Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["scenario", "show", "tiny"])
        .output()
        .unwrap();
    let original = String::from_utf8(shown.stdout).unwrap();
    std::fs::write(&scenario, &original).unwrap();
    let out = dir.path().join("x");
    let run = |out: &Path| {
        Command::cargo_bin("swarmplan")
            .unwrap()
            .args(["bench", "--methods", "pso", "--runs", "2", "--threads", "1"])
            .args(["--iterations", "5", "--population", "6", "--scenarios"])
            .arg(&scenario)
            .arg("--out")
            .arg(out)
            .arg("--resume")
            .assert()
    };
    run(&out).success();
    assert!(out.join("scenarios.json").exists());
    // Cut the last record, as a kill would, then edit the scenario: the resumed runs would
    // be of another experiment under the same name.
    let runs = out.join("runs.jsonl");
    let text = std::fs::read_to_string(&runs).unwrap();
    let first = text.lines().next().unwrap().to_string();
    std::fs::write(&runs, format!("{first}\n")).unwrap();
    std::fs::write(
        &scenario,
        original.replace("cruise_speed = 15.0", "cruise_speed = 16.0"),
    )
    .unwrap();
    run(&out).code(2).stderr(predicate::str::contains(
        "has changed since its runs there were recorded",
    ));
    // Restored, it resumes.
    std::fs::write(&scenario, &original).unwrap();
    run(&out).success();
    assert_eq!(lines(&runs).len(), 2);
    // A record that is no run of this experiment (an edited or concatenated runs.jsonl) is
    // refused by resume and by aggregate.
    let mut foreign: serde_json::Value = serde_json::from_str(&first).unwrap();
    foreign["run"] = serde_json::json!(999);
    let mut text = std::fs::read_to_string(&runs).unwrap();
    text.push_str(&format!("{foreign}\n"));
    std::fs::write(&runs, text).unwrap();
    run(&out).code(2).stderr(predicate::str::contains(
        "is not a run of this folder's experiment",
    ));
    Command::cargo_bin("swarmplan")
        .unwrap()
        .arg("aggregate")
        .arg(&out)
        .arg("--out")
        .arg(dir.path().join("merged"))
        .assert()
        .code(2)
        .stderr(predicate::str::contains("#999 is not a run"));
}

#[test]
fn an_experiment_files_scenario_files_are_relative_to_it() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("exp");
    std::fs::create_dir(&folder).unwrap();
    let tiny = Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["scenario", "show", "tiny"])
        .output()
        .unwrap();
    std::fs::write(folder.join("mine.toml"), tiny.stdout).unwrap();
    std::fs::write(
        folder.join("e.toml"),
        "master_seed = 2\nruns = 1\nscenarios = [\"tiny\", \"mine.toml\"]\nmethods = [\"pso\"]\n\n[budget]\nevaluations = 200\n",
    )
    .unwrap();
    // Run from the folder above: `mine.toml` is found beside the experiment file.
    Command::cargo_bin("swarmplan")
        .unwrap()
        .current_dir(dir.path())
        .args(["bench", "--experiment", "exp/e.toml", "--out", "out"])
        .assert()
        .success();
    let records = lines(&dir.path().join("out/runs.jsonl"));
    let scenarios: Vec<&str> = records
        .iter()
        .map(|r| r["scenario"].as_str().unwrap())
        .collect();
    assert_eq!(records.len(), 2, "{scenarios:?}");
    assert!(scenarios.contains(&"exp/mine.toml"), "{scenarios:?}");
    // However the experiment file is named, its scenario file is the same run identity.
    let absolute = dir.path().join("exp/e.toml");
    for spelling in [
        "./exp/e.toml",
        "exp/../exp/e.toml",
        absolute.to_str().unwrap(),
    ] {
        Command::cargo_bin("swarmplan")
            .unwrap()
            .current_dir(dir.path())
            .args([
                "bench",
                "--experiment",
                spelling,
                "--out",
                "out",
                "--resume",
            ])
            .assert()
            .success();
    }
    // Resumed from another folder, the recorded path is not found, and the message says why.
    Command::cargo_bin("swarmplan")
        .unwrap()
        .current_dir(&folder)
        .args(["bench", "--resume", "--out", "../out"])
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains("names the file exp/mine.toml")
                .and(predicate::str::contains("resume it from there")),
        );
}

#[test]
fn a_folder_resumed_by_another_build_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("b");
    bench(&out, &["--seed", "1"]).success();
    let builds: Vec<String> =
        serde_json::from_str(&std::fs::read_to_string(out.join("builds.json")).unwrap()).unwrap();
    assert_eq!(builds.len(), 1, "{builds:?}");
    // The same build resumes without a word.
    bench(&out, &["--seed", "1", "--resume"])
        .success()
        .stderr(predicate::str::contains("made by build").not());
    // Runs recorded by another build: said before any run, and this build is added.
    std::fs::write(out.join("builds.json"), "[\"0123456789ab\"]").unwrap();
    bench(&out, &["--seed", "1", "--resume"])
        .success()
        .stderr(predicate::str::contains(
            "its runs were made by build 0123456789ab, this is build",
        ));
    let builds: Vec<String> =
        serde_json::from_str(&std::fs::read_to_string(out.join("builds.json")).unwrap()).unwrap();
    assert_eq!(builds[0], "0123456789ab");
    assert_eq!(builds.len(), 2, "{builds:?}");
}

#[test]
fn scenarios_whose_file_names_meet_in_one_figure_name_keep_their_own_figures() {
    // `x/t.toml` and `x_t.toml` both make the stem `x_t_toml`: the second scenario's box
    // plots used to replace the first's.
    let dir = tempfile::tempdir().unwrap();
    let tiny = Command::cargo_bin("swarmplan")
        .unwrap()
        .args(["scenario", "show", "tiny"])
        .output()
        .unwrap()
        .stdout;
    std::fs::create_dir(dir.path().join("x")).unwrap();
    std::fs::write(dir.path().join("x/t.toml"), &tiny).unwrap();
    std::fs::write(dir.path().join("x_t.toml"), &tiny).unwrap();
    // One PSO run of 3 iterations per scenario of `scenarios`, into `out`.
    let pso = |scenarios: &str, out: &str| {
        Command::cargo_bin("swarmplan")
            .unwrap()
            .current_dir(dir.path())
            .args(["bench", "--scenarios", scenarios, "--methods", "pso"])
            .args(["--runs", "1", "--iterations", "3", "--population", "6"])
            .args(["--out", out])
            .assert()
    };
    pso("x/t.toml,x_t.toml", "b").success();
    for stem in [
        "bench_x_t_toml",
        "bench_x_t_toml_2",
        "convergence_x_t_toml",
        "convergence_x_t_toml_2",
    ] {
        assert!(
            dir.path().join("b").join(format!("{stem}.svg")).is_file(),
            "{stem}"
        );
    }
    // Two spellings of one file are one scenario listed twice.
    pso("x/t.toml,./x//t.toml", "c")
        .code(2)
        .stderr(predicate::str::contains(
            "scenarios: `./x//t.toml` is the same file as `x/t.toml`",
        ));
    assert!(!dir.path().join("c").exists());
}
