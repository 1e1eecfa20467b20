//! `plot`, `export` and `scenario new` end to end: figures next to a plan, exports that need
//! a geodetic origin and say how to give one, and a scenario written from a real DEM.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{plan_folder, swarmplan};

use predicates::prelude::*;

#[test]
fn plan_writes_figures_and_plot_redraws_them() {
    let dir = tempfile::tempdir().unwrap();
    plan_folder(dir.path(), &[]);
    for f in ["top_view", "view_3d", "convergence", "comm_timeline"] {
        let png = dir.path().join(format!("{f}.png"));
        assert!(
            png.exists() && dir.path().join(format!("{f}.svg")).exists(),
            "{f}"
        );
        std::fs::remove_file(png).unwrap();
    }
    swarmplan().arg("plot").arg(dir.path()).assert().success();
    assert!(dir.path().join("top_view.png").exists());
}

#[test]
fn export_needs_an_origin_and_writes_every_format_with_one() {
    let dir = tempfile::tempdir().unwrap();
    plan_folder(dir.path(), &[]);
    swarmplan()
        .args(["export"])
        .arg(dir.path())
        .args(["--format", "all"])
        .assert()
        .code(2)
        .stderr(predicate::str::contains("origin"));
    let out = dir.path().join("mission");
    swarmplan()
        .args(["export"])
        .arg(dir.path())
        .args(["--format", "all", "--origin", "45.5,7.25,300", "--out"])
        .arg(&out)
        .assert()
        .success();
    for f in [
        "uav0.plan",
        "uav1.plan",
        "uav0.waypoints",
        "mission.geojson",
        "mission.kml",
        "mission.csv",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    let plan: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("uav0.plan")).unwrap()).unwrap();
    assert_eq!(plan["fileType"], "Plan");
    let home = plan["mission"]["plannedHomePosition"].as_array().unwrap();
    assert!((home[0].as_f64().unwrap() - 45.5).abs() < 0.01, "{home:?}");
    // The same from `plan --export`.
    let dir2 = tempfile::tempdir().unwrap();
    plan_folder(
        dir2.path(),
        &["--export", "kml,csv", "--origin", "45.5,7.25,300"],
    );
    assert!(dir2.path().join("mission.kml").exists() && dir2.path().join("mission.csv").exists());
}

#[test]
fn scenario_new_from_a_real_dem() {
    let Some(tif) =
        swarmplan_io::reference_data::reference_file("spso/ChrismasTerrain.tif").unwrap()
    else {
        return;
    };
    let dir = tempfile::tempdir().unwrap();
    let toml_path = dir.path().join("island.toml");
    swarmplan()
        .args(["scenario", "new", "--terrain"])
        .arg(&tif)
        .args([
            "--start=-10.475,105.62",
            "--goal=-10.495,105.645",
            "--uavs",
            "3",
            "--out",
        ])
        .arg(&toml_path)
        .assert()
        .success();
    let shown = swarmplan()
        .args(["scenario", "show"])
        .arg(&toml_path)
        .assert()
        .success();
    let text = String::from_utf8(shown.get_output().stdout.clone()).unwrap();
    assert!(
        text.contains("georeferenced") && text.matches("[[uavs]]").count() == 3,
        "{text}"
    );
    // A start outside the DEM is refused with the DEM's extent.
    swarmplan()
        .args(["scenario", "new", "--terrain"])
        .arg(&tif)
        .args([
            "--start=-10.3,105.62",
            "--goal=-10.495,105.645",
            "--uavs",
            "3",
        ])
        .assert()
        .code(2)
        .stderr(
            predicate::str::contains("--start").and(predicate::str::contains("inside the DEM")),
        );
}
