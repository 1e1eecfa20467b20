//! The outside benchmark instances load by name as scenarios (needs `../shared`; required
//! in CI): the threats, map, start and goal of the instance file, on its terrain.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use swarmplan_io::reference_data::reference_files;
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

#[test]
fn outside_instances_load_as_scenarios() {
    let files: Vec<String> = (0..swarmplan_io::outside::INSTANCES)
        .flat_map(|k| {
            [
                format!("outside/outside-{k}.json"),
                format!("outside/outside-{k}.asc.gz"),
            ]
        })
        .collect();
    let names: Vec<&str> = files.iter().map(String::as_str).collect();
    let Some(paths) = reference_files(&names).unwrap() else {
        return;
    };
    let instance: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&paths[0]).unwrap()).unwrap();
    let loaded = load_spec("outside-0").unwrap();
    let spec = &loaded.spec;
    assert_eq!(spec.name, "outside-0");
    assert_eq!(spec.uavs.len(), 5);
    let threats = instance["threats_x_y_height_r"].as_array().unwrap();
    assert_eq!(spec.threats.len(), threats.len());
    assert_eq!(spec.threats[3].x, threats[3][0].as_f64().unwrap());
    assert_eq!(spec.threats[3].r, threats[3][3].as_f64().unwrap());
    assert_eq!(spec.map.x, [1.0, 900.0]);
    let start: Vec<f64> = instance["start"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert!(spec.uavs.iter().all(|u| u.start.to_vec() == start));
    // The rugged terrain of the instance, not the procedural one.
    let world = build_world(&loaded, None).unwrap();
    assert!(
        world.terrain().max_height() > 500.0,
        "max height {}",
        world.terrain().max_height()
    );
    // The TOML it prints reads back to the same scenario; other fleet sizes by name.
    let again = swarmplan_io::scenario::parse_spec(&loaded.text, "again").unwrap();
    assert_eq!(&again, spec);
    // What it prints names no folder (of this machine or of the one that built it): the
    // terrain is the instance's file, beside the instance.
    assert_eq!(spec.terrain.source, "outside-0.asc.gz");
    assert!(!loaded.text.contains('/'), "{}", loaded.text);
    assert_eq!(loaded.base_dir.join(&spec.terrain.source), paths[1]);
    assert_eq!(load_spec("outside-3-u12").unwrap().spec.uavs.len(), 12);
    assert!(load_spec("outside-3").unwrap().spec.threats.len() >= 15);
}

#[test]
fn a_missing_outside_instance_names_where_it_looked() {
    let e = load_spec("outside-99").unwrap_err().to_string();
    assert!(
        e.contains("outside-99.json") && e.contains("SWARMPLAN_SHARED"),
        "{e}"
    );
}

#[test]
fn outside_instances_leave_the_pace_free_and_plan_files_keep_it() {
    use swarmplan_core::plan::Plan;
    use swarmplan_io::plan_file::{parse_plan, plan_file, Provenance};
    let Some(_) = reference_files(&["outside/outside-1.json", "outside/outside-1.asc.gz"]).unwrap()
    else {
        return;
    };
    let loaded = load_spec("outside-1").unwrap();
    let t = &loaded.spec.timing;
    assert!(t.pace_is_free());
    let u = &loaded.spec.uavs[0];
    assert_eq!(
        t.pace,
        [u.speed[0] / u.cruise_speed, u.speed[1] / u.cruise_speed]
    );
    let world = build_world(&loaded, None).unwrap();
    let starts: Vec<_> = (0..world.uav_count()).map(|i| world.start(i)).collect();
    let plan = Plan {
        pace: 1.4,
        ..Plan::straight(&starts, world.goal_at(swarmplan_core::world::DEPARTURE), 3)
    };
    let text = serde_json::to_string(&plan_file(&world, &plan)).unwrap();
    assert!(text.contains("\"pace\":1.4"), "{text}");
    let back = parse_plan(&text, "p.json", &world, Provenance::MustMatch).unwrap();
    assert_eq!(back, plan);
    // Speeds in the file are those of the pace: 1.4 x the pace-1 ones (no limit reached).
    let at_one = serde_json::to_value(plan_file(
        &world,
        &Plan {
            pace: 1.0,
            ..plan.clone()
        },
    ))
    .unwrap();
    let paced = serde_json::to_value(plan_file(&world, &plan)).unwrap();
    let v = |j: &serde_json::Value| j["uavs"][0]["speed_mps"][0].as_f64().unwrap();
    assert!((v(&paced) - 1.4 * v(&at_one)).abs() < 1e-9);
    assert!(!serde_json::to_string(&plan_file(
        &world,
        &Plan {
            pace: 1.0,
            ..plan.clone()
        }
    ))
    .unwrap()
    .contains("pace"));
    // A pace the scenario does not allow is refused unless asked otherwise.
    let fast = text.replace("\"pace\":1.4", "\"pace\":1.9");
    let e = parse_plan(&fast, "p.json", &world, Provenance::MustMatch)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("pace") && e.contains("1.9") && e.contains("timing.pace"),
        "{e}"
    );
    assert_eq!(
        parse_plan(&fast, "p.json", &world, Provenance::AllowOther)
            .unwrap()
            .pace,
        1.9
    );
    let bad = text.replace("\"pace\":1.4", "\"pace\":-2.0");
    let e = parse_plan(&bad, "p.json", &world, Provenance::MustMatch)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("p.json") && e.contains("pace") && e.contains("-2"),
        "{e}"
    );
}
