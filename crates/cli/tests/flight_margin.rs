//! `plan --flight-margin`: searched on the scenario with every hard geometric limit tighter,
//! judged and written against the scenario as given.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::swarmplan;
use predicates::prelude::*;

fn json(out: &[u8]) -> serde_json::Value {
    serde_json::from_slice(out).unwrap()
}

#[test]
fn a_margin_keeps_the_plan_that_far_inside_every_limit_and_judges_it_as_given() {
    let dir = tempfile::tempdir().unwrap();
    let margin = 8.0;
    let out = swarmplan()
        .args(["plan", "--scenario", "tiny", "--seed", "2", "--no-figures"])
        .args(["--flight-margin", "8", "--out"])
        .arg(dir.path())
        .assert()
        .success();
    let stdout = String::from_utf8(out.get_output().stdout.clone()).unwrap();
    assert!(
        stdout.contains(
            "searched with a flight margin of 8 m (sizes, separation and clearance 8 m larger, the map box 8 m inside); with the margin: FEASIBLE"
        ),
        "{stdout}"
    );
    let run = json(&std::fs::read(dir.path().join("run.json")).unwrap());
    assert_eq!(run["flight_margin"], margin);
    // The folder holds the scenario as given: `evaluate` on it gives run.json's assessment.
    let scenario = std::fs::read_to_string(dir.path().join("scenario.toml")).unwrap();
    assert!(
        scenario.contains("x = [\n    0.0,\n    300.0,\n]"),
        "{scenario}"
    );
    let evaluated = swarmplan()
        .args(["evaluate", "--json", "--scenario"])
        .arg(dir.path().join("scenario.toml"))
        .arg("--plan")
        .arg(dir.path().join("plan.json"))
        .assert()
        .success();
    let evaluated = json(&evaluated.get_output().stdout);
    assert_eq!(
        evaluated["cost"]["total"],
        run["assessment"]["cost"]["total"]
    );
    assert_eq!(evaluated["feasible"], true);
    // Every free waypoint is the margin inside the map box (x [0, 300], y [0, 200]) and
    // beyond the threats' hard zones (r + size 1 m) by the margin.
    let plan = json(&std::fs::read(dir.path().join("plan.json")).unwrap());
    let threats = [(120.0, 80.0, 25.0), (200.0, 140.0, 20.0)];
    for uav in plan["uavs"].as_array().unwrap() {
        let points = uav["waypoints"].as_array().unwrap();
        for p in &points[1..points.len() - 1] {
            let (x, y) = (p[0].as_f64().unwrap(), p[1].as_f64().unwrap());
            assert!((margin..=300.0 - margin).contains(&x), "x {x}");
            assert!((margin..=200.0 - margin).contains(&y), "y {y}");
            for (tx, ty, r) in threats {
                let d = (x - tx).hypot(y - ty);
                assert!(d >= r + 1.0 + margin - 1e-9, "{d} m from ({tx}, {ty})");
            }
        }
    }
}

#[test]
fn a_margin_that_is_no_distance_or_leaves_no_map_is_refused_once() {
    for (margin, said) in [
        ("-1", "flight margin -1: expected a finite distance of at least 0 m (--flight-margin)"),
        ("nan", "flight margin NaN: expected a finite distance"),
        (
            "120",
            "flight margin 120 m: the map box's y range [0, 200] shrunk by 120 m on each side is empty",
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        swarmplan()
            .args(["plan", "--scenario", "tiny", "--flight-margin", margin, "--out"])
            .arg(&out)
            .assert()
            .failure()
            .stderr(predicate::str::contains(said))
            .stderr(predicate::str::contains("flight margin").count(1));
        assert!(!out.exists(), "no folder for a refused margin");
    }
    // A margin that leaves a start outside the box is the world's error, named.
    swarmplan()
        .args(["plan", "--scenario", "tiny", "--flight-margin", "40"])
        .args(["--out", "/nonexistent/never"])
        .assert()
        .failure()
        .stderr(predicate::str::contains(
            "flight margin 40 m: the scenario with every limit 40 m tighter is not valid: uavs[0].start",
        ));
}
