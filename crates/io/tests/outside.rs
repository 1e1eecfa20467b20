//! The outside benchmark instances load by name as scenarios (needs `../shared`; required
//! in CI): the threats, map, start and goal of the instance file, on its terrain.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use swarmplan_io::reference_data::reference_files;
use swarmplan_io::scenario::{build_world, load_spec};

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
        world.terrain.max_height() > 500.0,
        "max height {}",
        world.terrain.max_height()
    );
    // The TOML it prints reads back to the same scenario; other fleet sizes by name.
    let again = swarmplan_io::scenario::parse_spec(&loaded.text, "again").unwrap();
    assert_eq!(&again, spec);
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
