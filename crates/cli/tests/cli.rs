//! The command-line interface, end to end on the `tiny` scenario: the stable interfaces
//! that scripts rely on (`scenario`, `evaluate --json`, `plan --json`, the files written)
//! and clear errors for bad input.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::swarmplan;

use predicates::prelude::*;

fn json(out: &[u8]) -> serde_json::Value {
    serde_json::from_slice(out).unwrap()
}

#[test]
fn scenario_list_names_every_builtin() {
    let out = swarmplan().args(["scenario", "list"]).assert().success();
    let text = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    for name in [
        "paper-case1",
        "paper-case2",
        "spso-case1",
        "spso-case2",
        "tiny",
    ] {
        assert!(text.contains(name), "{text}");
    }
}

#[test]
fn scenario_show_round_trips_through_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let shown = swarmplan()
        .args(["scenario", "show", "paper-case1"])
        .assert()
        .success();
    let toml_text = shown.get_output().stdout.clone();
    let path = dir.path().join("my.toml");
    std::fs::write(&path, &toml_text).unwrap();
    let again = swarmplan()
        .args(["scenario", "show", path.to_str().unwrap()])
        .assert()
        .success();
    assert_eq!(again.get_output().stdout, toml_text);
}

#[test]
fn plan_writes_files_that_evaluate_reads_back_with_the_same_cost() {
    let dir = tempfile::tempdir().unwrap();
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--iterations",
            "30",
            "--population",
            "20",
            "--seed",
            "7",
            "--json",
            "--out",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let planned = json(&out.get_output().stdout);
    for key in [
        "version",
        "scenario",
        "terrain_fingerprint",
        "seed",
        "method",
        "optimizer",
        "encoding",
        "init",
        "budget",
        "assessment",
        "evaluations",
        "seconds",
        "files",
    ] {
        assert!(planned.get(key).is_some(), "missing {key}");
    }
    assert_eq!(planned["seed"], 7);
    assert_eq!(planned["method"], "swarmplan");
    assert_eq!(planned["optimizer"], "coop");
    // run.json is the same typed artifact.
    let run_json = json(&std::fs::read(dir.path().join("run.json")).unwrap());
    assert_eq!(run_json, planned);
    let plan_path = dir.path().join("plan.json");
    assert!(dir.path().join("convergence.csv").exists());
    let conv = std::fs::read_to_string(dir.path().join("convergence.csv")).unwrap();
    assert_eq!(conv.lines().count(), 1 + 31, "header + iterations 0..=30");

    let out = swarmplan()
        .args(["evaluate", "--scenario", "tiny", "--json", "--plan"])
        .arg(&plan_path)
        .assert()
        .success();
    let evaluated = json(&out.get_output().stdout);
    let (a, b) = (
        planned["assessment"]["cost"]["total"].as_f64().unwrap(),
        evaluated["cost"]["total"].as_f64().unwrap(),
    );
    assert!((a - b).abs() <= 1e-9 * a.abs().max(1.0), "{a} vs {b}");
    assert_eq!(planned["assessment"]["feasible"], evaluated["feasible"]);
    assert!(evaluated["violations"].is_array());
    assert!(evaluated["cost"]["terms"]["length"].as_f64().unwrap() > 0.0);
}

#[test]
fn evaluate_refuses_a_plan_made_for_other_terrain_or_another_scenario() {
    let dir = tempfile::tempdir().unwrap();
    common::plan_folder(dir.path(), &["--no-figures"]);
    let plan_path = dir.path().join("plan.json");
    let mut plan = json(&std::fs::read(&plan_path).unwrap());
    assert_eq!(plan["scenario"], "tiny");
    assert_eq!(plan["terrain_fingerprint"].as_str().unwrap().len(), 16);
    plan["terrain_fingerprint"] = "0123456789abcdef".into();
    let other = dir.path().join("other.json");
    std::fs::write(&other, serde_json::to_string(&plan).unwrap()).unwrap();
    swarmplan()
        .args(["evaluate", "--scenario", "tiny", "--plan"])
        .arg(&other)
        .assert()
        .code(2)
        .stderr(
            predicates::str::contains("terrain 0123456789abcdef")
                .and(predicates::str::contains("--allow-other-terrain")),
        );
    swarmplan()
        .args([
            "evaluate",
            "--scenario",
            "tiny",
            "--allow-other-terrain",
            "--plan",
        ])
        .arg(&other)
        .assert()
        .success();
    swarmplan()
        .args(["evaluate", "--scenario", "paper-case1", "--plan"])
        .arg(&plan_path)
        .assert()
        .code(2)
        .stderr(predicates::str::contains("scenario `tiny`"));
}

#[test]
fn same_seed_gives_the_same_plan_on_any_number_of_threads() {
    // The run (plan, report, evaluations; seconds and file names aside) and stderr of a
    // short run of `tiny`.
    let run_with = |threads: &str, json: bool, rayon: &str| {
        let dir = tempfile::tempdir().unwrap();
        let out = swarmplan()
            .env("RAYON_NUM_THREADS", rayon)
            .args(["plan", "--scenario", "tiny", "--iterations", "15"])
            .args(["--population", "12", "--seed", "3", "--no-figures"])
            .args(json.then_some("--json"))
            .args(["--threads", threads, "--out"])
            .arg(dir.path())
            .timeout(std::time::Duration::from_secs(60))
            .assert()
            .success();
        let read = |name: &str| -> serde_json::Value {
            serde_json::from_str(&std::fs::read_to_string(dir.path().join(name)).unwrap()).unwrap()
        };
        let mut run = read("run.json");
        run.as_object_mut().unwrap().remove("seconds");
        run.as_object_mut().unwrap().remove("files");
        let stderr = String::from_utf8_lossy(&out.get_output().stderr).into_owned();
        ((read("plan.json"), run), stderr)
    };
    let run = |threads: &str| run_with(threads, true, "").0;
    let one = run("1");
    assert_eq!(one, run("1"));
    assert_eq!(one, run("3"));
    assert_eq!(one, run("0"));
    // More threads than cores run as many as there are cores (each idle worker woke for
    // every swarm batch: 256 threads took 8.3 s on 2 cores), said once; the same plan.
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    if cores < 4096 {
        let held = if cores == 1 {
            "this process may use 1 core, so 1 thread runs".to_string()
        } else {
            format!("this process may use {cores} cores, so {cores} threads run")
        };
        for json in [true, false] {
            let (plan, err) = run_with("4096", json, "");
            assert_eq!(one, plan);
            assert_eq!(
                err.matches(&format!("--threads 4096: {held}")).count(),
                1,
                "{err}"
            );
        }
        // rayon's own variable, read when --threads is 0, is held the same way.
        let (plan, err) = run_with("0", false, "4096");
        assert_eq!(one, plan);
        let note = format!("RAYON_NUM_THREADS=4096: {held}");
        assert_eq!(err.matches(&note).count(), 1, "{err}");
        let (_, err) = run_with("1", false, "4096");
        assert!(!err.contains("RAYON_NUM_THREADS"), "{err}");
    }
    swarmplan()
        .args(["plan", "--threads", "5000"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "expected 0 (one per core) to 4096",
        ));
    // A negative count is refused by --threads' own message, not taken for a flag.
    swarmplan()
        .args(["plan", "--threads", "-1"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("got `-1`"));
}

#[test]
fn evaluate_reports_violations_of_a_straight_plan() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("straight.json");
    // Both UAVs fly the same straight line: through a threat, and together.
    let plan = r#"{"uavs": [
        {"waypoints": [[30, 30, 60], [120, 80, 60], [270, 170, 60]]},
        {"waypoints": [[30, 30, 60], [120, 80, 60], [270, 170, 60]]}]}"#;
    std::fs::write(&path, plan).unwrap();
    let out = swarmplan()
        .args(["evaluate", "--scenario", "tiny", "--json", "--plan"])
        .arg(&path)
        .assert()
        .success();
    let v = json(&out.get_output().stdout);
    assert_eq!(v["feasible"], false);
    let kinds: Vec<&str> = v["violations"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x["kind"].as_str().unwrap())
        .collect();
    assert!(
        kinds.contains(&"threat") && kinds.contains(&"separation"),
        "{kinds:?}"
    );
    // Tables for humans name the violations too.
    swarmplan()
        .args(["evaluate", "--scenario", "tiny", "--plan"])
        .arg(&path)
        .assert()
        .success()
        .stdout(predicate::str::contains("feasible: no").and(predicate::str::contains("threat")));
}

#[test]
fn bad_input_gets_a_clear_error_and_status_2() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("one.json");
    std::fs::write(
        &path,
        r#"{"uavs": [{"waypoints": [[30, 30, 60], [270, 170, 60]]}]}"#,
    )
    .unwrap();
    swarmplan()
        .args(["evaluate", "--scenario", "tiny", "--plan"])
        .arg(&path)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("one.json").and(predicate::str::contains("2 UAVs")));
    swarmplan()
        .args(["evaluate", "--scenario", "no-such", "--plan"])
        .arg(&path)
        .assert()
        .code(2)
        .stderr(predicate::str::contains("no-such").and(predicate::str::contains("paper-case1")));
    let bad = dir.path().join("bad.toml");
    let text = String::from_utf8(
        swarmplan()
            .args(["scenario", "show", "tiny"])
            .output()
            .unwrap()
            .stdout,
    )
    .unwrap()
    .replacen("range = ", "range = -", 1);
    std::fs::write(&bad, text).unwrap();
    swarmplan()
        .args(["scenario", "show", bad.to_str().unwrap()])
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains("bad.toml")
                .and(predicate::str::contains("communication.range")),
        );
    swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--terrain",
            "/nonexistent/dem.tif",
            "--out",
        ])
        .arg(dir.path())
        .assert()
        .code(2)
        .stderr(predicate::str::contains("/nonexistent/dem.tif"));
}

#[test]
fn an_infeasible_plan_says_so_last_and_require_feasible_exits_3() {
    let dir = tempfile::tempdir().unwrap();
    // Two iterations of six particles on tiny leave violations.
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--iterations",
            "2",
            "--population",
            "6",
        ])
        .args(["--seed", "1", "--no-figures", "--require-feasible", "--out"])
        .arg(dir.path())
        .assert()
        .code(3);
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    // The verdict, then what the route layer says: nothing rules every plan out on tiny.
    let lines: Vec<&str> = stdout.lines().collect();
    let (verdict, outcome) = (lines[lines.len() - 2], lines[lines.len() - 1]);
    assert!(verdict.starts_with("INFEASIBLE: "), "{stdout}");
    assert!(verdict.contains(" violations ("), "{verdict}");
    assert!(outcome.starts_with("none found: "), "{outcome}");
    assert!(
        outcome.contains("widest way between the threats keeps"),
        "{outcome}"
    );
    assert!(outcome.contains("; in height ("), "{outcome}");
    // Outputs were written before the exit.
    assert!(dir.path().join("plan.json").exists());
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("--require-feasible"), "{stderr}");
}

#[test]
fn under_a_time_limit_the_outcome_leaves_the_search_in_height_out_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let out = swarmplan()
        .args(["plan", "--scenario", "tiny", "--iterations", "2"])
        .args(["--population", "6", "--time-limit", "60", "--seed", "1"])
        .args(["--no-figures", "--out"])
        .arg(dir.path())
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    let outcome = stdout.lines().last().unwrap();
    assert!(outcome.starts_with("none found: "), "{stdout}");
    assert!(!outcome.contains("; in height ("), "{outcome}");
    assert!(
        outcome.contains("the route layer in height was left out under the time limit"),
        "{outcome}"
    );
}

#[test]
fn scenario_check_says_when_threats_wall_the_start_off_from_the_goal() {
    swarmplan()
        .args(["scenario", "check", "tiny"])
        .assert()
        .success()
        .stdout(predicate::str::contains(
            "the widest way between the threats keeps",
        ))
        .stdout(predicate::str::contains("no cause found"));
    // Eight threats of hard radius 13 m on a ring of 25 m around UGV0 (270, 170): the
    // 19 m between neighbouring axes leave no gap.
    let tiny = swarmplan()
        .args(["scenario", "show", "tiny"])
        .assert()
        .success();
    let text = String::from_utf8(tiny.get_output().stdout.clone()).unwrap();
    let ring: String = (0..8)
        .map(|k| {
            let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
            format!(
                "[[threats]]\nx = {}\ny = {}\nz = 60.0\nr = 12.0\n\n",
                270.0 + 25.0 * a.cos(),
                170.0 + 25.0 * a.sin()
            )
        })
        .collect();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("ringed.toml");
    std::fs::write(&path, text.replacen("[goal]", &format!("{ring}[goal]"), 1)).unwrap();
    swarmplan()
        .args(["scenario", "check"])
        .arg(&path)
        .assert()
        .code(3)
        .stdout(predicate::str::contains(
            "no way around the threats' hard zones reaches UGV0",
        ))
        .stdout(predicate::str::contains(
            "no plan exists: uavs[0].start: (30, 30) is walled off from the goal",
        ));
}

#[test]
fn scenario_generate_writes_a_scenario_that_plans() {
    let dir = tempfile::tempdir().unwrap();
    let toml_path = dir.path().join("gen.toml");
    swarmplan()
        .args([
            "scenario",
            "generate",
            "--seed",
            "4",
            "--uavs",
            "8",
            "--threats",
            "12",
        ])
        .arg("--out")
        .arg(&toml_path)
        .assert()
        .success();
    let text = std::fs::read_to_string(&toml_path).unwrap();
    assert!(text.starts_with("# swarmplan scenario generate --seed 4 --uavs 8 --threats 12"));
    assert_eq!(text.matches("[[uavs]]").count(), 8);
    assert_eq!(text.matches("[[threats]]").count(), 12);
    // Launch and recovery slots by default (a mission an operator could fly).
    assert!(
        text.contains("launch_interval = 5.0") && text.contains("recovery_interval = 5.0"),
        "{text}"
    );
    assert!(text.contains("name = \"gen-s4-u8-t12-slots\""), "{text}");
    // The same flags give the same file.
    let again = swarmplan()
        .args([
            "scenario",
            "generate",
            "--seed",
            "4",
            "--uavs",
            "8",
            "--threats",
            "12",
        ])
        .assert()
        .success();
    assert_eq!(String::from_utf8_lossy(&again.get_output().stdout), text);
    swarmplan()
        .args([
            "plan",
            "--iterations",
            "2",
            "--population",
            "6",
            "--no-figures",
            "--scenario",
        ])
        .arg(&toml_path)
        .arg("--out")
        .arg(dir.path().join("p"))
        .assert()
        .success()
        .stdout(predicates::str::contains(
            "take-off and landing (launch slots 5 s, recovery slots 5 s apart): uav 0 0.0-",
        ));
    // --no-slots: everyone at once, the paper's layout, and the suites' name.
    swarmplan()
        .args([
            "scenario",
            "generate",
            "--seed",
            "4",
            "--uavs",
            "8",
            "--threats",
            "12",
            "--no-slots",
        ])
        .assert()
        .success()
        .stdout(
            predicates::str::contains("name = \"gen-s4-u8-t12\"")
                .and(predicates::str::contains("launch_interval").not()),
        );
    swarmplan()
        .args([
            "scenario",
            "generate",
            "--seed",
            "1",
            "--uavs",
            "5",
            "--threats",
            "400",
        ])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("--threats 400: placed only"));
}

#[test]
fn scenario_generate_on_a_dem_names_it_from_where_the_scenario_is_written() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("dem")).unwrap();
    std::fs::create_dir_all(dir.path().join("scenarios")).unwrap();
    let mut grid = String::from(
        "ncols 61\nnrows 41\nxllcorner 300000\nyllcorner 5000000\ncellsize 15\nNODATA_value -9999\n",
    );
    for row in 0..41 {
        let line: Vec<String> = (0..61).map(|c| format!("{}", 100 + row + c)).collect();
        grid.push_str(&line.join(" "));
        grid.push('\n');
    }
    std::fs::write(dir.path().join("dem/hill.asc"), grid).unwrap();
    swarmplan()
        .current_dir(dir.path())
        .args(["scenario", "generate", "--seed", "3", "--uavs", "6"])
        .args(["--threats", "4", "--terrain", "dem/hill.asc"])
        .args(["--out", "scenarios/g.toml"])
        .assert()
        .success();
    let text = std::fs::read_to_string(dir.path().join("scenarios/g.toml")).unwrap();
    // Paths in a scenario are relative to the scenario file.
    let sep = std::path::MAIN_SEPARATOR;
    assert!(
        text.contains(&format!("source = \"..{sep}dem{sep}hill.asc\"")),
        "{text}"
    );
    // The map is the DEM's extent (x 900 m, y 600 m).
    assert!(text.contains("x = [\n    0.0,\n    900.0,\n]"), "{text}");
    assert!(text.contains("y = [\n    0.0,\n    600.0,\n]"), "{text}");
    // Planned from elsewhere: the DEM is found through the scenario's folder.
    swarmplan()
        .current_dir(dir.path().join("dem"))
        .args(["plan", "--evaluations", "200", "--no-figures", "--scenario"])
        .arg(dir.path().join("scenarios/g.toml"))
        .arg("--out")
        .arg(dir.path().join("p"))
        .assert()
        .success();
    // Printed, the scenario may be saved anywhere: the DEM's path is absolute.
    let printed = swarmplan()
        .current_dir(dir.path())
        .args(["scenario", "generate", "--seed", "3", "--uavs", "6"])
        .args(["--threats", "4", "--terrain", "dem/hill.asc"])
        .assert()
        .success();
    let printed = String::from_utf8_lossy(&printed.get_output().stdout).to_string();
    let absolute = std::fs::canonicalize(dir.path().join("dem/hill.asc")).unwrap();
    let toml_string = toml::Value::String(absolute.display().to_string()).to_string();
    assert!(
        printed.contains(&format!("source = {toml_string}")),
        "{printed}"
    );
}

#[test]
fn scenario_generate_frees_the_pace_and_the_delays_when_asked() {
    let dir = tempfile::tempdir().unwrap();
    let toml_path = dir.path().join("gen.toml");
    swarmplan()
        .args(["scenario", "generate", "--seed", "2", "--uavs", "4"])
        .args(["--threats", "3", "--free-pace", "--free-delays"])
        .arg("--out")
        .arg(&toml_path)
        .assert()
        .success();
    let text = std::fs::read_to_string(&toml_path).unwrap();
    assert!(
        text.starts_with(
            "# swarmplan scenario generate --seed 2 --uavs 4 --threats 3 --free-pace --free-delays"
        ),
        "{text}"
    );
    assert!(text.contains("max_delay = 0.3"), "{text}");
    let out = dir.path().join("p");
    swarmplan()
        .args(["plan", "--evaluations", "200", "--no-figures", "--scenario"])
        .arg(&toml_path)
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let delays: Vec<f64> = plan["uavs"]
        .as_array()
        .unwrap()
        .iter()
        // An absent delay is 0: the UAV leaves at once (`PlanFile`, crates/io/src/plan_file.rs).
        .map(|u| u.get("delay").map_or(0.0, |d| d.as_f64().unwrap()))
        .collect();
    assert_eq!(delays.len(), 4);
    assert!(delays.iter().all(|d| (0.0..=0.3).contains(d)), "{delays:?}");
    // By name, too: the same request.
    swarmplan()
        .args(["scenario", "show", "gen-s2-u4-t3-pace-delay"])
        .assert()
        .success()
        .stdout(predicates::str::contains("max_delay = 0.3"));
}

#[test]
fn anytime_stops_at_the_first_feasible_plan_or_at_the_time_limit() {
    let dir = tempfile::tempdir().unwrap();
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--until-feasible",
            "--json",
            "--no-figures",
        ])
        .arg("--out")
        .arg(dir.path().join("a"))
        .assert()
        .success();
    let a = json(&out.get_output().stdout);
    assert_eq!(a["termination"], "feasible");
    assert_eq!(a["assessment"]["feasible"], true);
    assert!(a["evaluations"].as_u64().unwrap() < 38_700);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("first feasible plan after"), "{stderr}");
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "paper-case1",
            "--time-limit",
            "0.2",
            "--json",
        ])
        .arg("--no-figures")
        .arg("--out")
        .arg(dir.path().join("b"))
        .assert()
        .success();
    let b = json(&out.get_output().stdout);
    assert_eq!(b["termination"], "time-limit");
    assert!(String::from_utf8_lossy(&out.get_output().stderr).contains("not reproducible"));
    // Refused before an output folder is chosen: nothing is left behind.
    let cwd = tempfile::tempdir().unwrap();
    swarmplan()
        .current_dir(cwd.path())
        .args(["plan", "--scenario", "tiny", "--time-limit", "-1"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("--time-limit: expected seconds"));
    assert_eq!(std::fs::read_dir(cwd.path()).unwrap().count(), 0);
    // A huge number is echoed short, not as three hundred digits.
    swarmplan()
        .args(["plan", "--scenario", "tiny", "--time-limit", "1e300"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("got 1e300\n"));
    swarmplan()
        .args(["plan", "--scenario", "tiny", "--time-limit", "-1e-300"])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("got -1e-300\n"));
}

#[test]
fn exporting_an_infeasible_plan_warns_and_the_files_say_so() {
    let dir = tempfile::tempdir().unwrap();
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--iterations",
            "2",
            "--population",
            "6",
        ])
        .args(["--seed", "1", "--no-figures", "--export", "geojson,kml,csv"])
        .arg("--origin=-10.5,105.6")
        .arg("--out")
        .arg(dir.path())
        .assert()
        .success();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(
        stderr.contains("warning: exporting a plan that is INFEASIBLE: "),
        "{stderr}"
    );
    let mut seen = 0;
    for entry in std::fs::read_dir(dir.path()).unwrap() {
        let p = entry.unwrap().path();
        let ext = p.extension().and_then(|e| e.to_str()).unwrap_or_default();
        let name = p.file_name().and_then(|n| n.to_str()).unwrap_or_default();
        if ["geojson", "kml", "csv"].contains(&ext) && name != "convergence.csv" {
            let text = std::fs::read_to_string(&p).unwrap();
            assert!(
                text.contains("WARNING, the plan is INFEASIBLE: "),
                "{}",
                p.display()
            );
            seen += 1;
        }
    }
    assert!(seen >= 3, "{seen} export files found");
}

#[test]
fn an_error_says_its_cause_once() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.toml");
    std::fs::write(
        &bad,
        "name = \"x\"\n[goal]\nposition = [800, 800, 150]\n[[uavs]]\nbattery_wh = -2\n",
    )
    .unwrap();
    let out = swarmplan()
        .args(["plan", "--scenario"])
        .arg(&bad)
        .assert()
        .code(2);
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert_eq!(
        stderr
            .matches("battery_wh: a positive number, got -2")
            .count(),
        1,
        "{stderr}"
    );
    assert!(stderr.contains("bad.toml"), "{stderr}");
}

#[test]
fn attempts_are_printed_stored_and_the_kept_one_repeats_by_its_seed() {
    let dir = tempfile::tempdir().unwrap();
    let args = |out: &str| {
        let mut c = swarmplan();
        c.args([
            "plan",
            "--scenario",
            "paper-case2",
            "--evaluations",
            "300",
            "--no-figures",
        ])
        .arg("--out")
        .arg(dir.path().join(out));
        c
    };
    let out = args("a").args(["--attempts", "3"]).assert().success();
    let stdout = String::from_utf8_lossy(&out.get_output().stdout).to_string();
    let stderr = String::from_utf8_lossy(&out.get_output().stderr).to_string();
    assert!(stderr.contains("up to 3 attempts"), "{stderr}");
    assert!(stderr.contains("attempt 1 of 3, seed 1:"), "{stderr}");
    assert!(stdout.contains("kept attempt "), "{stdout}");
    let run: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("a/run.json")).unwrap()).unwrap();
    let records = run["attempts"].as_array().unwrap();
    assert!((1..=3).contains(&records.len()), "{records:?}");
    assert_eq!(records[0]["seed"], 1);
    let kept: Vec<&serde_json::Value> = records
        .iter()
        .filter(|r| r["seed"] == run["seed"])
        .collect();
    assert_eq!(kept.len(), 1, "{run}");
    let seed = run["seed"].as_u64().unwrap().to_string();
    // The report's subtitle says which attempt the plan is.
    swarmplan()
        .arg("report")
        .arg(dir.path().join("a"))
        .assert()
        .success();
    let html = std::fs::read_to_string(dir.path().join("a/report.html")).unwrap();
    let chosen = kept[0]["attempt"].as_u64().unwrap();
    assert!(
        html.contains(&format!(
            "seed {seed} (attempt {chosen} of {})",
            records.len()
        )),
        "{}",
        &html[..html.len().min(2000)]
    );
    // Alone, by its seed: the same plan file.
    args("b").args(["--seed", &seed]).assert().success();
    let plan = |d: &str| std::fs::read_to_string(dir.path().join(d).join("plan.json")).unwrap();
    assert_eq!(plan("a"), plan("b"));
    let alone: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.path().join("b/run.json")).unwrap()).unwrap();
    assert!(
        alone.get("attempts").is_none(),
        "a single run stores no attempts"
    );
    args("c").args(["--attempts", "0"]).assert().code(2).stderr(
        predicate::str::contains("--attempts")
            .and(predicate::str::contains("expected 1 to 1000, got 0")),
    );
}
