//! Bad input, as the reproducers of issue 13 kept in `tests/reproducers/`: every one ends
//! with exit code 2 (or, for scenarios no plan can satisfy, a warning at load time), within
//! seconds, with one message naming the file or flag, the field, what was expected and what
//! was found. None may panic (exit 101), abort (134) or hang.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use std::path::PathBuf;
use std::time::{Duration, Instant};

use common::swarmplan;

fn reproducer(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/reproducers")
        .join(name)
}

/// Runs `args`, checks the exit code and that stderr contains every one of `says`, each
/// exactly once for the first; returns stderr.
fn fails_with(args: &[&str], code: i32, says: &[&str]) -> String {
    let started = Instant::now();
    let out = swarmplan()
        .args(args)
        .timeout(Duration::from_secs(60))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(code), "{args:?}: {err}");
    for s in says {
        assert!(err.contains(s), "{args:?}: expected `{s}` in: {err}");
    }
    assert_eq!(
        err.matches(says[0]).count(),
        1,
        "{args:?}: said more than once: {err}"
    );
    assert!(
        started.elapsed() < Duration::from_secs(30),
        "{args:?} took {:?}",
        started.elapsed()
    );
    err
}

#[test]
fn scenarios_beyond_what_the_model_can_hold_are_refused_with_the_field() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let out = out.to_str().unwrap();
    for (file, says) in [
        (
            "map-huge.toml",
            &["map.x", "at most 1000000 m", "-1e300"][..],
        ),
        ("map-1e12.toml", &["map.x", "1000000000000"]),
        (
            "map-1e6.toml",
            &["map.clearance_step", "at least 100", "got 5"],
        ),
        (
            "map-beyond-terrain.toml",
            &["reaches beyond the terrain", "x [0, 300]"],
        ),
        (
            "clearance-step-tiny.toml",
            &["map.clearance_step", "at least 0.036", "0.000000001"],
        ),
        (
            "los-step-tiny.toml",
            &["communication.line_of_sight_step", "at least"],
        ),
        (
            "time-step-tiny.toml",
            &["communication.time_step", "at least 0.01 s", "0.000000001"],
        ),
        (
            "climb-95.toml",
            &["uavs[0].max_climb_deg", "(0, 90]", "got 95"],
        ),
        (
            "ground-node-utm.toml",
            &[
                "communication.ground_nodes[0] (`relay`).position",
                "(566712, 8838247) is outside the map box",
                "not geographic coordinates",
            ],
        ),
        (
            "cell-larger-than-map.toml",
            &["terrain.procedural.cell", "at most half", "got 500"],
        ),
        (
            "start-z-1e200.toml",
            &["uavs[0].start.z", "[-1e5, 1e5] m", "got -1e200"],
        ),
        (
            "relays-fine-step.toml",
            &[
                "communication.ground_nodes",
                "at most 5 relays",
                "148 MB",
                "got 6",
            ],
        ),
        (
            "heights-overflow.toml",
            &[
                "terrain.procedural.min_height",
                "[-1e5, 1e5] m",
                "got -1e308",
            ],
        ),
    ] {
        let path = reproducer(file);
        let err = fails_with(
            &["plan", "--scenario", path.to_str().unwrap(), "--out", out],
            2,
            says,
        );
        assert!(err.contains(file), "names the file: {err}");
    }
}

#[test]
fn a_threat_far_larger_than_the_map_is_drawn_in_bounded_memory() {
    // Radius 1e308 m: its outline was cut into dashes without end (24 GB before the kernel
    // stopped it); its run has no finite cost, so no convergence line, which is said.
    let dir = tempfile::tempdir().unwrap();
    let started = Instant::now();
    let out = swarmplan()
        .args(["plan", "--scenario"])
        .arg(reproducer("threat-1e308.toml"))
        .args(["--evaluations", "200", "--out"])
        .arg(dir.path().join("o"))
        .timeout(Duration::from_secs(60))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(
        started.elapsed() < Duration::from_secs(30),
        "{:?}",
        started.elapsed()
    );
    for figure in ["top_view.png", "view_3d.png", "comm_timeline.png"] {
        assert!(
            dir.path().join("o").join(figure).is_file(),
            "{figure}: {err}"
        );
    }
    assert!(!dir.path().join("o/convergence.png").exists());
    assert_eq!(
        err.matches("no finite cost; that figure is left out")
            .count(),
        1,
        "{err}"
    );
    // Its size is written as an exponent, not as 309 digits.
    assert!(err.contains("radius 1e308 + UAV size 1)"), "{err}");
}

#[test]
fn scenarios_no_plan_can_satisfy_are_said_at_load_time() {
    for (file, says) in [
        ("start-in-threat.toml", "uavs[0].start: (120.0, 80.0)"),
        ("goal-in-threat.toml", "goal.position: (270.0, 170.0)"),
        (
            "start-below-ground.toml",
            "uavs[0].start: its height above ground is -60 m",
        ),
        (
            "payload-above-max.toml",
            "uavs[0].payload_kg: 5 kg is above",
        ),
        (
            "start-walled-in.toml",
            "uavs[0].start: (60, 100) is walled off from the goal by the hard zones (radius + UAV size 1) of threats [0, 1, 2, 3, 4, 5]",
        ),
        (
            "start-walled-in.toml",
            "uavs[1].start: (30, 30) is walled off",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let path = reproducer(file);
        let out = swarmplan()
            .args(["plan", "--scenario", path.to_str().unwrap()])
            .args(["--evaluations", "40", "--no-figures", "--out"])
            .arg(dir.path())
            .timeout(Duration::from_secs(60))
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&out.stderr);
        let line = format!("warning: {}: {says}", path.display());
        assert_eq!(err.matches(&line).count(), 1, "{file}: {err}");
        assert!(err.contains("no plan can be feasible"), "{file}: {err}");
        // Planning still runs and says the plan is infeasible.
        assert!(out.status.success(), "{file}: {err}");
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(stdout.contains("INFEASIBLE"), "{file}: {stdout}");
    }
}

#[test]
fn plans_that_cannot_be_evaluated_name_the_uav_and_waypoint() {
    for (file, says) in [
        (
            "plan-far-x.json",
            &["uavs[0].waypoints[2]", "map box", "1000000000.0"][..],
        ),
        (
            "plan-high-z.json",
            &[
                "uavs[0].waypoints:",
                "beyond the 36000 s the model assesses",
            ],
        ),
        (
            "plan-string.json",
            &["uavs[1].waypoints[2][0]", "expected f64"],
        ),
        ("plan-trailing.json", &["text after the plan object"]),
        (
            "plan-misspelt-delay.json",
            &[
                "uavs[0].Delay: unknown field `Delay`",
                "expected one of `waypoints`, `delay`",
            ],
        ),
        (
            "plan-array.json",
            &["expected a JSON object", "found an array"],
        ),
        (
            "plan-other-scenario.json",
            &["made for scenario `paper-case1`", "--allow-other-terrain"],
        ),
    ] {
        let path = reproducer(file);
        let err = fails_with(
            &[
                "evaluate",
                "--scenario",
                "tiny",
                "--plan",
                path.to_str().unwrap(),
            ],
            2,
            says,
        );
        assert!(err.contains(file), "names the file: {err}");
    }
}

#[test]
fn flags_out_of_range_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let out = out.to_str().unwrap();
    fails_with(
        &["plan", "--population", "100000000", "--out", out],
        2,
        &["--population", "[4, 100000]", "100000000"],
    );
    // The same range in a parameter file.
    let params = dir.path().join("p.toml");
    std::fs::write(&params, "[pso]\npopulation = 2\n").unwrap();
    fails_with(
        &[
            "plan",
            "--method",
            "pso",
            "--params",
            params.to_str().unwrap(),
            "--out",
            out,
        ],
        2,
        &["pso.population", "[4, 100000]", "got 2"],
    );
    fails_with(
        &["plan", "--seed", "-1", "--out", out],
        2,
        &["--seed", "whole number", "-1"],
    );
    // A negative count is a value of the flag, not an unknown flag `-1`.
    fails_with(
        &["plan", "--evaluations", "-1", "--out", out],
        2,
        &["invalid value '-1' for '--evaluations"],
    );
    fails_with(
        &["bench", "--runs", "-3", "--out", out],
        2,
        &["invalid value '-3' for '--runs"],
    );
    fails_with(
        &[
            "plan", "--export", "qgc-plan", "--origin", "90,0", "--out", out,
        ],
        2,
        &["within 89.999 degrees of the equator", "got 90"],
    );
    fails_with(
        &[
            "plan",
            "--export",
            "qgc-plan",
            "--origin",
            "10,0,-1e6",
            "--out",
            out,
        ],
        2,
        &["altitude", "[-1000, 20000]", "-1000000"],
    );
}

#[test]
fn output_folders_are_checked_first_and_never_overwritten_silently() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let started = Instant::now();
    fails_with(
        &["plan", "--out", file.to_str().unwrap()],
        2,
        &["--out", "is a file, expected a folder"],
    );
    // Refused before planning: far quicker than a run.
    assert!(started.elapsed() < Duration::from_secs(5));

    let out = dir.path().join("out");
    let plan = |extra: &[&str]| {
        swarmplan()
            .args([
                "plan",
                "--scenario",
                "tiny",
                "--evaluations",
                "40",
                "--no-figures",
            ])
            .args(extra)
            .arg("--out")
            .arg(&out)
            .output()
            .unwrap()
    };
    assert!(plan(&[]).status.success());
    let first = std::fs::read_to_string(out.join("plan.json")).unwrap();
    let second = plan(&["--seed", "9"]);
    assert!(second.status.success());
    let err = String::from_utf8_lossy(&second.stderr);
    assert!(
        err.contains("holds a plan already") && err.contains("out-2"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("plan.json")).unwrap(),
        first
    );
    assert!(dir.path().join("out-2/plan.json").exists());
    // --force replaces it, and leaves none of the old plan's exports or figures to be taken
    // for the new one's; a file of the user's own stays.
    assert!(plan(&["--export", "qgc,kml", "--origin", "1,1", "--force"])
        .status
        .success());
    assert!(out.join("uav0.plan").exists() && out.join("mission.kml").exists());
    std::fs::write(out.join("top_view.png"), "an old figure").unwrap();
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let replaced = plan(&["--seed", "9", "--force"]);
    assert!(replaced.status.success());
    let err = String::from_utf8_lossy(&replaced.stderr);
    assert!(err.contains("--force: removed the"), "{err}");
    assert_ne!(
        std::fs::read_to_string(out.join("plan.json")).unwrap(),
        first
    );
    for gone in ["uav0.plan", "uav1.plan", "mission.kml", "top_view.png"] {
        assert!(!out.join(gone).exists(), "{gone} left from the old plan");
    }
    assert!(out.join("notes.txt").exists() && out.join("run.json").exists());
    // No temporary file is left behind.
    let leftovers: Vec<_> = std::fs::read_dir(&out)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().contains("partial"))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");

    // Plan and bench folders are not mixed.
    fails_with(
        &[
            "bench",
            "--scenarios",
            "tiny",
            "--methods",
            "spso",
            "--runs",
            "1",
            "--iterations",
            "2",
            "--out",
            out.to_str().unwrap(),
        ],
        2,
        &["holds a plan (plan.json)"],
    );
}

#[test]
fn terrain_flags_are_named_as_flags_and_filled_cells_are_said() {
    let dir = tempfile::tempdir().unwrap();
    let garbage = dir.path().join("g.asc");
    std::fs::write(&garbage, "garbage\n").unwrap();
    let err = fails_with(
        &[
            "plan",
            "--scenario",
            "tiny",
            "--terrain",
            garbage.to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ],
        2,
        &["--terrain ", "g.asc: line 1", "garbage"],
    );
    assert!(!err.contains("builtin:tiny"), "{err}");

    // A grid covering tiny's map (SPSO pixel frame: x, y from 1) with two nodata cells.
    let (nx, ny) = (302, 202);
    let mut text = format!(
        "ncols {nx}\nnrows {ny}\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -9999\n"
    );
    for j in 0..ny {
        let row: Vec<String> = (0..nx)
            .map(|i| {
                if (i, j) == (5, 5) || (i, j) == (100, 50) {
                    "-9999".to_string()
                } else {
                    format!("{}", 20 + (i + j) % 7)
                }
            })
            .collect();
        text += &row.join(" ");
        text.push('\n');
    }
    let dem = dir.path().join("holes.asc");
    std::fs::write(&dem, text).unwrap();
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--evaluations",
            "30",
            "--no-figures",
        ])
        .arg("--terrain")
        .arg(&dem)
        .arg("--out")
        .arg(dir.path().join("o2"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert_eq!(
        err.matches("holes.asc: 2 of 61004 cells were nodata")
            .count(),
        1,
        "{err}"
    );
}

#[test]
fn parameters_take_the_papers_symbols() {
    let dir = tempfile::tempdir().unwrap();
    let params = dir.path().join("p.toml");
    std::fs::write(
        &params,
        "[pso]\nw = 0.7298\nc1 = 1.49618\nc2 = 1.49618\nwdamp = 1.0\n",
    )
    .unwrap();
    let out = swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--method",
            "pso",
            "--iterations",
            "3",
        ])
        .args(["--no-figures", "--params"])
        .arg(&params)
        .arg("--out")
        .arg(dir.path().join("o"))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("o/run.json")).unwrap())
            .unwrap();
    let pso = &run["params"]["pso"];
    assert_eq!(pso["inertia"], 0.7298, "{run}");
    assert_eq!(pso["cognitive"], 1.49618);
    assert_eq!(pso["inertia_damping"], 1.0);
}

#[test]
fn more_threads_than_runs_is_no_hang_and_absurd_counts_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let bench = |threads: &str, out: &str| {
        tiny_bench("spso", "2")
            .args(["--threads", threads])
            .arg("--out")
            .arg(dir.path().join(out))
            .timeout(Duration::from_secs(60))
            .output()
            .unwrap()
    };
    let out = bench("1000", "a");
    assert!(out.status.success());
    // Held to the cores, said once (crates/experiment/src/workers.rs).
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let err = String::from_utf8_lossy(&out.stderr);
    if cores < 1000 {
        assert_eq!(
            err.matches("note: --threads 1000: this process may use")
                .count(),
            1,
            "{err}"
        );
        assert!(err.contains(&format!(", {cores} threads, into")), "{err}");
    }
    let out = bench("100000", "b");
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--threads") && err.contains("100000"), "{err}");
    // A negative count gets the same parser's message as `plan --threads -1`.
    let out = bench("-1", "c");
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("0 (one per core)") && err.contains("`-1`"),
        "{err}"
    );
    assert!(!dir.path().join("b").exists() && !dir.path().join("c").exists());
}

/// A bench of `method` on `tiny`, `runs` runs of 2 iterations of 4 particles: seconds of
/// work; the caller adds the rest (`--out`, ...).
fn tiny_bench(method: &str, runs: &str) -> assert_cmd::Command {
    let mut c = swarmplan();
    c.args(["bench", "--scenarios", "tiny", "--methods", method])
        .args(["--runs", runs, "--iterations", "2", "--population", "4"]);
    c
}

/// `plan --terrain` on a kept TIFF reproducer fails as bad input (status 2) saying `why`,
/// naming the file, without a panic.
fn corrupt_tiff_is_refused(file: &str, why: &str) {
    let path = reproducer(file);
    let dir = tempfile::tempdir().unwrap();
    let err = fails_with(
        &[
            "plan",
            "--scenario",
            "tiny",
            "--terrain",
            path.to_str().unwrap(),
            "--out",
            dir.path().join("o").to_str().unwrap(),
        ],
        2,
        &[why, file],
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn a_tiff_whose_sample_format_is_text_is_a_corrupt_file() {
    // Found by the CI's 30-second `geotiff` fuzz smoke: SampleFormat stored as ASCII, which the
    // `tiff` crate reads as an empty list and then indexes.
    corrupt_tiff_is_refused(
        "tiff-ascii-sampleformat.tif",
        "tag SampleFormat is of TIFF type 2, expected an unsigned integer type",
    );
}

#[test]
fn a_tiff_the_decoder_would_panic_on_is_a_corrupt_file() {
    // Found by the `geotiff` fuzz target: a SampleFormat tag with no value made the `tiff`
    // crate index an empty list.
    corrupt_tiff_is_refused(
        "tiff-empty-sampleformat.tif",
        "tag SampleFormat has no value",
    );
}

#[test]
fn bench_says_which_scenarios_no_plan_can_satisfy_before_running() {
    let dir = tempfile::tempdir().unwrap();
    let path = reproducer("start-in-threat.toml");
    let scenarios = format!("{},tiny", path.display());
    let out = swarmplan()
        .args([
            "bench",
            "--scenarios",
            &scenarios,
            "--methods",
            "spso",
            "--runs",
            "1",
        ])
        .args(["--iterations", "2", "--population", "4", "--out"])
        .arg(dir.path().join("b"))
        .timeout(Duration::from_secs(60))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let line = format!("warning: {}: uavs[0].start:", path.display());
    assert_eq!(err.matches(&line).count(), 1, "{err}");
    assert_eq!(err.matches("no plan can be feasible").count(), 1, "{err}");
}

#[test]
fn a_bad_plan_export_is_said_before_the_planning() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("o");
    let o = out.to_str().unwrap();
    // Case 2 at its default budget plans for about a second; the errors come before it,
    // so no folder is made and nothing is planned.
    let err = fails_with(
        &[
            "plan",
            "--scenario",
            "paper-case2",
            "--out",
            o,
            "--export",
            "bogus",
        ],
        2,
        &["--export: expected qgc-plan, wpl, geojson, kml, csv or all, got `bogus`"],
    );
    assert!(!err.contains("planning"), "{err}");
    assert!(!out.exists());
    let err = fails_with(
        &["plan", "--scenario", "tiny", "--out", o, "--export", "all"],
        2,
        &["--export", "tiny"],
    );
    assert!(!err.contains("planning"), "{err}");
    assert!(!out.exists());
    // And `export` names its own flag.
    fails_with(
        &["export", o, "--format", "nope"],
        2,
        &["--format: expected qgc-plan"],
    );
}

#[test]
fn a_plan_of_a_flight_over_an_hour_is_read_back() {
    // The channel's shadowing is tabulated for 3600 s and held after; the sweep assesses
    // 36000 s. Plan files used to be refused beyond 3600 s at v_max, so `plan` wrote a
    // plan it called feasible that `evaluate` and `export` then refused.
    let dir = tempfile::tempdir().unwrap();
    let scenario = reproducer("slow-uavs.toml");
    let out = dir.path().join("o");
    let planned = swarmplan()
        .args(["plan", "--evaluations", "200", "--no-figures", "--scenario"])
        .arg(&scenario)
        .arg("--out")
        .arg(&out)
        .timeout(Duration::from_secs(120))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&planned.stdout).into_owned();
    assert!(planned.status.success(), "{said}");
    let run: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    let arrival = run["uavs"][0]["time_s"]
        .as_array()
        .unwrap()
        .last()
        .unwrap()
        .as_f64()
        .unwrap();
    assert!(arrival > 3600.0, "{arrival}");
    let evaluated = swarmplan()
        .args(["evaluate", "--scenario"])
        .arg(&scenario)
        .arg("--plan")
        .arg(out.join("plan.json"))
        .timeout(Duration::from_secs(60))
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&evaluated.stdout).into_owned();
    assert!(
        evaluated.status.success(),
        "{text}{}",
        String::from_utf8_lossy(&evaluated.stderr)
    );
    // The same verdict as `plan`'s.
    let verdict = |s: &str| {
        s.lines()
            .find(|l| l.starts_with("feasible:"))
            .map(str::to_owned)
    };
    assert!(verdict(&said).is_some(), "{said}");
    assert_eq!(verdict(&text), verdict(&said));
}

#[test]
fn an_experiment_file_with_a_budget_of_nothing_is_refused_naming_it() {
    let dir = tempfile::tempdir().unwrap();
    for (field, value) in [("evaluations", 0), ("time_limit_ms", 0), ("iterations", 0)] {
        let file = dir.path().join(format!("{field}.toml"));
        std::fs::write(
            &file,
            format!(
                "master_seed = 1\nruns = 1\nscenarios = [\"tiny\"]\nmethods = [\"pso\"]\n[budget]\n{field} = {value}\n"
            ),
        )
        .unwrap();
        let out = dir.path().join(format!("o-{field}"));
        let (f, o) = (file.to_str().unwrap(), out.to_str().unwrap());
        fails_with(
            &["bench", "--experiment", f, "--out", o],
            2,
            &[&format!(
                "{field}.toml: experiment: budget.{field}: expected at least 1, got 0"
            )],
        );
        assert!(!out.exists(), "nothing is run or written");
    }
    // A terrain the file names and that is not there is named as the file's field.
    let file = dir.path().join("terrain.toml");
    std::fs::write(
        &file,
        "master_seed = 1\nruns = 1\nscenarios = [\"tiny\"]\nmethods = [\"pso\"]\nterrain = \"nope.asc\"\n",
    )
    .unwrap();
    let out = dir.path().join("o-terrain");
    let err = fails_with(
        &[
            "bench",
            "--experiment",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        2,
        &["terrain.toml: terrain: no file", "nope.asc"],
    );
    assert!(!err.contains("--terrain"), "{err}");
    assert!(!out.exists(), "nothing is run or written");
}

#[test]
fn aggregate_and_export_check_their_out_folder_first() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("r.sh");
    std::fs::write(&file, "#!/bin/sh\n").unwrap();
    let shard = dir.path().join("b");
    let b = shard.to_str().unwrap();
    tiny_bench("pso", "1").args(["--out", b]).assert().success();
    let summary = std::fs::read_to_string(shard.join("summary.md")).unwrap();
    let f = file.to_str().unwrap();
    fails_with(&["aggregate", b, "--out", f], 2, &["r.sh: is a file"]);
    fails_with(
        &["aggregate", b, "--out", b],
        2,
        &["is one of the folders aggregated"],
    );
    // Folders of two experiments: what differs is named.
    let other = dir.path().join("b2");
    tiny_bench("pso", "2")
        .args(["--out", other.to_str().unwrap()])
        .assert()
        .success();
    fails_with(
        &[
            "aggregate",
            b,
            other.to_str().unwrap(),
            "--out",
            dir.path().join("all").to_str().unwrap(),
        ],
        2,
        &["a different experiment from", "1 runs in", "2 here"],
    );
    assert_eq!(
        std::fs::read_to_string(shard.join("summary.md")).unwrap(),
        summary
    );
    let planned = dir.path().join("p");
    let p = planned.to_str().unwrap();
    swarmplan()
        .args(["plan", "--scenario", "paper-case1", "--evaluations", "100"])
        .args(["--no-figures", "--out", p])
        .assert()
        .success();
    fails_with(
        &["aggregate", b, "--out", p],
        2,
        &["holds a plan (plan.json)"],
    );
    fails_with(
        &["export", p, "--origin", "45,7", "--out", f],
        2,
        &["r.sh: is a file"],
    );
}

#[test]
fn a_waypoint_of_four_numbers_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("p");
    swarmplan()
        .args([
            "plan",
            "--scenario",
            "tiny",
            "--evaluations",
            "50",
            "--no-figures",
        ])
        .arg("--out")
        .arg(&out)
        .assert()
        .success();
    let mut plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("plan.json")).unwrap()).unwrap();
    plan["uavs"][0]["waypoints"][1]
        .as_array_mut()
        .unwrap()
        .push(serde_json::json!(1.0));
    let edited = dir.path().join("four.json");
    std::fs::write(&edited, plan.to_string()).unwrap();
    fails_with(
        &[
            "evaluate",
            "--scenario",
            "tiny",
            "--plan",
            edited.to_str().unwrap(),
        ],
        2,
        &[
            "four.json",
            "uavs[0].waypoints",
            "waypoint 1: expected 3 numbers [x, y, z above ground], got 4",
        ],
    );
}

#[test]
fn folders_of_records_without_a_summary_say_which_command_completes_them() {
    let dir = tempfile::tempdir().unwrap();
    let folder = |name: &str| dir.path().join(name).to_str().unwrap().to_string();
    let bench = |extra: &[&str], out: &str| {
        tiny_bench("pso", "2")
            .args(extra)
            .args(["--out", out])
            .assert()
            .success();
    };
    // A bench whose summary was never written (interrupted, or run from Python).
    let cut = folder("cut");
    bench(&[], &cut);
    std::fs::remove_file(dir.path().join("cut/summary.md")).unwrap();
    fails_with(
        &["report", &cut],
        2,
        &[
            "holds run records but no summary.md",
            "bench --resume --out",
        ],
    );
    // An aggregate folder: a summary and figures, no records.
    let (one, two, all) = (folder("s1"), folder("s2"), folder("all"));
    bench(&["--shard", "1/2"], &one);
    bench(&["--shard", "2/2"], &two);
    swarmplan()
        .args(["aggregate", &one, &two, "--out", &all])
        .assert()
        .success();
    fails_with(
        &["plot", &all],
        2,
        &[
            "an `aggregate` folder keeps no records",
            "swarmplan aggregate SHARD",
        ],
    );
}

#[test]
fn a_convergence_file_with_iterations_out_of_order_is_refused_with_the_line() {
    // A long run's convergence.csv skips iterations, so `plot` draws at the iteration
    // column; a hand-edited file whose iterations go back is refused, not drawn as a zigzag.
    let dir = tempfile::tempdir().unwrap();
    common::plan_folder(dir.path(), &["--no-figures"]);
    let csv = dir.path().join("convergence.csv");
    std::fs::write(
        &csv,
        "iteration,evaluations,best_cost\n0,10,5\n4,20,3\n2,30,1\n",
    )
    .unwrap();
    let folder = dir.path().display().to_string();
    fails_with(
        &["plot", &folder],
        2,
        &["convergence.csv: line 4: iteration 2 does not follow iteration 4"],
    );
    std::fs::write(&csv, "iteration,evaluations,best_cost\n0,10,5\n1.5,20,3\n").unwrap();
    fails_with(
        &["plot", &folder],
        2,
        &["line 3: expected a whole number in column iteration"],
    );
    // Rows that skip iterations draw.
    std::fs::write(
        &csv,
        "iteration,evaluations,best_cost\n0,10,5\n4,20,3\n8,30,1\n",
    )
    .unwrap();
    swarmplan().arg("plot").arg(dir.path()).assert().success();
}
