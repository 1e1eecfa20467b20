//! Golden outputs: what `plan`, `evaluate` and `bench` produce, held against files written
//! by an earlier build, so that a change of structure is shown to change no result.
//!
//! `plan` and `evaluate` on paper-case1, paper-case2, tiny and outside-1 (default method
//! and seed) are compared in full, seconds and output paths aside; `bench --runs 2` over
//! every preset on both paper cases and the outside suite (168 runs, about 3 minutes on 2
//! cores, so `#[ignore]`d: run it on purpose) is compared by a digest of each record.
//!
//! A change that is meant to move results rewrites the files with `SWARMPLAN_BLESS=1` (the
//! same command) and says in its commit and issue note which results moved and by how much
//! (docs/contributing.md).

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use std::hash::Hasher;
use std::path::{Path, PathBuf};

use common::swarmplan;
use serde_json::Value;

/// The scenarios whose `plan` and `evaluate` outputs are golden.
const PLANNED: [&str; 4] = ["paper-case1", "paper-case2", "tiny", "outside-1"];

/// Every method preset, as `bench --methods` takes them.
const METHODS: &str = "pso,apso,qpso,gwo,abc,spso,dls-smpso,dls-smpso-exemplar,pso-uniform,\
                       apso-uniform,swarmplan,swarmplan-uniform,lshade,cmaes";

fn golden_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden")
}

fn blessing() -> bool {
    std::env::var_os("SWARMPLAN_BLESS").is_some()
}

/// Whether the outside instances are here; a skip is said, and refused where the shared
/// data is required (CI).
fn outside_data_present() -> bool {
    swarmplan_io::reference_data::reference_files(&["outside/outside-1.json"])
        .unwrap_or_else(|e| panic!("{e}"))
        .is_some()
}

/// `value` without the keys that differ between identical runs: wall-clock seconds and the
/// paths of the files written.
fn without_run_specifics(mut value: Value) -> Value {
    fn strip(v: &mut Value) {
        match v {
            Value::Object(map) => {
                map.remove("seconds");
                map.remove("files");
                map.values_mut().for_each(strip);
            }
            Value::Array(items) => items.iter_mut().for_each(strip),
            _ => {}
        }
    }
    strip(&mut value);
    value
}

fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e} (write it with SWARMPLAN_BLESS=1)", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn fnv_hex(bytes: &[u8]) -> String {
    let mut h = fnv::FnvHasher::default();
    h.write(bytes);
    format!("{:016x}", h.finish())
}

/// Compares `got` with the golden file `name`, or writes it when blessing.
fn check_golden(name: &str, got: &Value) {
    let path = golden_dir().join(name);
    if blessing() {
        std::fs::create_dir_all(golden_dir()).unwrap();
        std::fs::write(&path, serde_json::to_string_pretty(got).unwrap() + "\n").unwrap();
        return;
    }
    let want = read_json(&path);
    if &want != got {
        let (w, g) = (want.as_object(), got.as_object());
        let moved: Vec<&String> = match (w, g) {
            (Some(w), Some(g)) => w
                .keys()
                .chain(g.keys())
                .filter(|k| w.get(*k) != g.get(*k))
                .collect(),
            _ => Vec::new(),
        };
        panic!(
            "{name}: output differs from the golden file in {moved:?}; a change meant to move \
             results rewrites it with SWARMPLAN_BLESS=1 and says by how much"
        );
    }
}

#[test]
fn plan_and_evaluate_outputs_match_the_golden_files() {
    let dir = tempfile::tempdir().unwrap();
    for scenario in PLANNED {
        if scenario.starts_with("outside") && !outside_data_present() {
            continue;
        }
        let out = dir.path().join(scenario);
        swarmplan()
            .args([
                "plan",
                "--scenario",
                scenario,
                "--no-figures",
                "--json",
                "--out",
            ])
            .arg(&out)
            .assert()
            .success();
        let evaluated = swarmplan()
            .args(["evaluate", "--scenario", scenario, "--json", "--plan"])
            .arg(out.join("plan.json"))
            .assert()
            .success();
        let convergence = std::fs::read(out.join("convergence.csv")).unwrap();
        let got = serde_json::json!({
            "plan": read_json(&out.join("plan.json")),
            "run": without_run_specifics(read_json(&out.join("run.json"))),
            "evaluate": serde_json::from_slice::<Value>(&evaluated.get_output().stdout).unwrap(),
            "convergence_csv_fnv1a": fnv_hex(&convergence),
        });
        check_golden(&format!("plan-{scenario}.json"), &got);
    }
}

#[test]
#[ignore = "168 runs, about 3 minutes on 2 cores: run on purpose around a change of structure"]
fn bench_records_match_the_golden_records() {
    assert!(
        outside_data_present(),
        "the bench golden covers the outside suite: needs ../shared/data/outside"
    );
    let dir = tempfile::tempdir().unwrap();
    let scenarios = "paper-case1,paper-case2,outside-0,outside-1,outside-2,outside-3";
    swarmplan()
        .args([
            "bench",
            "--scenarios",
            scenarios,
            "--methods",
            METHODS,
            "--runs",
            "2",
        ])
        .arg("--out")
        .arg(dir.path())
        .assert()
        .success();
    let text = std::fs::read_to_string(dir.path().join("runs.jsonl")).unwrap();
    let mut rows: Vec<Value> = text
        .lines()
        .map(|line| {
            let record = without_run_specifics(serde_json::from_str(line).unwrap());
            serde_json::json!({
                "scenario": record["scenario"],
                "method": record["method"],
                "run": record["run"],
                "seed": record["seed"],
                "cost_total": record["cost_total"],
                "feasible": record["feasible"],
                "evaluations": record["evaluations"],
                "record_fnv1a": fnv_hex(record.to_string().as_bytes()),
            })
        })
        .collect();
    // Records are written as runs finish; their order depends on the threads.
    rows.sort_by_key(|r| {
        (
            r["scenario"].to_string(),
            r["method"].to_string(),
            r["run"].to_string(),
        )
    });
    check_golden("bench-records.json", &Value::Array(rows));
}
