//! Mission exports of a planned `tiny` plan with a geodetic origin: the QGroundControl
//! `.plan` against the documented format (keys and types), the WPL and GeoJSON read by
//! independent Python libraries (pymavlink's waypoint loader, the `geojson` package; see
//! export_check.py), KML and CSV contents, clear errors without an origin, and the round
//! trip: export CSV / GeoJSON, re-import, evaluate: the same cost to 1e-6.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;
use swarmplan_core::cost::assess_as_searched;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, IterationRecord, OptimizerParams};
use swarmplan_core::plan::Plan;
use swarmplan_core::run::{run, RunRequest};
use swarmplan_core::world::World;
use swarmplan_io::export::{export_plan, ExportFormat, Mission};
use swarmplan_io::geo::{resolve_frame, Geodetic, LocalFrame};
use swarmplan_io::import::{parse_csv, parse_geojson, read_exported_plan};
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

const ORIGIN: Geodetic = Geodetic::new(-10.45, 105.62, 30.0);

fn tiny() -> World {
    build_world(&load_spec("tiny").unwrap(), None).unwrap()
}

/// A short DLS-SMPSO run on `tiny` (a real, bent plan; seed fixed).
fn planned(world: &World) -> Plan {
    let mut params = OptimizerParams::default();
    params.set_population(16);
    let req = RunRequest {
        method: Method::preset("dls-smpso").expect("a preset"),
        params,
        budget: Budget::iterations(15),
        seed: 7,
    };
    let mut observer = |_: &IterationRecord| {};
    run(world, &req, &mut observer).plan
}

fn frame() -> LocalFrame {
    LocalFrame::tangent(ORIGIN).unwrap()
}

fn export_all(world: &World, plan: &Plan, dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    for f in ExportFormat::ALL {
        files.extend(export_plan(world, plan, &frame(), f, dir).unwrap());
    }
    files
}

fn is_num(v: &Value) -> bool {
    v.is_number()
}

/// Required keys of QGroundControl's plan format ("Plan File Format", QGC developer guide)
/// with their JSON types, checked on one `.plan` document.
fn check_qgc_plan_format(doc: &Value, what: &str) {
    let has = |obj: &Value, key: &str, ok: fn(&Value) -> bool, ty: &str| {
        let v = &obj[key];
        assert!(ok(v), "{what}: `{key}` must be {ty}, got {v}");
    };
    assert_eq!(doc["fileType"], "Plan", "{what}");
    assert_eq!(doc["version"], 1, "{what}");
    has(doc, "groundStation", Value::is_string, "a string");
    for key in ["mission", "geoFence", "rallyPoints"] {
        has(doc, key, Value::is_object, "an object");
    }
    let m = &doc["mission"];
    assert_eq!(m["version"], 2, "{what}: mission.version");
    for key in [
        "firmwareType",
        "vehicleType",
        "cruiseSpeed",
        "hoverSpeed",
        "globalPlanAltitudeMode",
    ] {
        has(m, key, is_num, "a number");
    }
    let home = m["plannedHomePosition"].as_array().unwrap();
    assert_eq!(
        home.len(),
        3,
        "{what}: plannedHomePosition is [lat, lon, alt]"
    );
    assert!(home.iter().all(is_num));
    let items = m["items"].as_array().unwrap();
    assert!(
        !items.is_empty(),
        "{what}: a mission needs at least one item"
    );
    for (k, it) in items.iter().enumerate() {
        let w = format!("{what}: items[{k}]");
        assert_eq!(it["type"], "SimpleItem", "{w}");
        assert!(it["autoContinue"].is_boolean(), "{w}");
        for key in ["command", "doJumpId", "frame"] {
            assert!(it[key].is_u64(), "{w}: {key} must be an unsigned integer");
        }
        let params = it["params"].as_array().unwrap();
        assert_eq!(params.len(), 7, "{w}: params has 7 values");
        assert!(params.iter().all(|p| p.is_number() || p.is_null()), "{w}");
        if it["frame"] == 0 {
            assert!(is_num(&it["Altitude"]) && it["AltitudeMode"] == 2, "{w}");
            assert!(it.get("AMSLAltAboveTerrain").is_some(), "{w}");
        }
    }
    let fence = &doc["geoFence"];
    assert_eq!(fence["version"], 2, "{what}: geoFence.version");
    assert!(fence["polygons"].is_array());
    for c in fence["circles"].as_array().unwrap() {
        let center = c["circle"]["center"].as_array().unwrap();
        assert!(
            center.len() == 2 && center.iter().all(is_num),
            "{what}: {c}"
        );
        assert!(
            is_num(&c["circle"]["radius"]) && c["inclusion"].is_boolean(),
            "{c}"
        );
        assert_eq!(c["version"], 1);
    }
    let rally = &doc["rallyPoints"];
    assert_eq!(rally["version"], 2, "{what}: rallyPoints.version");
    assert!(rally["points"].is_array());
}

#[test]
fn qgc_plan_files_follow_the_documented_format_and_the_plan() {
    let world = tiny();
    let plan = planned(&world);
    let dir = tempfile::tempdir().unwrap();
    let files = export_all(&world, &plan, dir.path());
    let names: Vec<String> = files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "uav0.plan",
            "uav1.plan",
            "uav0.waypoints",
            "uav1.waypoints",
            "mission.geojson",
            "mission.kml",
            "mission.csv",
            "trajectory.csv"
        ]
    );
    // `plan --force` clears old exports by these names, and nothing else.
    assert!(names
        .iter()
        .all(|n| swarmplan_io::export::is_mission_file(n)));
    assert!(!swarmplan_io::export::is_mission_file("uav.plan"));
    assert!(!swarmplan_io::export::is_mission_file("notes.csv"));
    let mission = Mission::new(&world, &plan, &frame()).unwrap();
    for path in &mission.paths {
        let name = format!("uav{}.plan", path.uav);
        let text = std::fs::read_to_string(dir.path().join(&name)).unwrap();
        let doc: Value = serde_json::from_str(&text).unwrap();
        check_qgc_plan_format(&doc, &name);
        let items = doc["mission"]["items"].as_array().unwrap();
        let m = path.points.len();
        assert_eq!(items.len(), m + 3, "takeoff, speed, {m} waypoints, land");
        let cmds: Vec<u64> = items
            .iter()
            .map(|i| i["command"].as_u64().unwrap())
            .collect();
        assert_eq!(cmds[0], 22);
        assert_eq!(cmds[1], 178);
        assert!(cmds[2..m + 2].iter().all(|&c| c == 16));
        assert_eq!(cmds[m + 2], 21);
        let jump: Vec<u64> = items
            .iter()
            .map(|i| i["doJumpId"].as_u64().unwrap())
            .collect();
        assert_eq!(jump, (1..=items.len() as u64).collect::<Vec<_>>());
        assert_eq!(items[1]["params"][1], path.speed_mps);
        assert_eq!(doc["mission"]["cruiseSpeed"], path.speed_mps);
        for (k, pt) in path.points.iter().enumerate() {
            let p = &items[k + 2]["params"];
            assert_eq!(items[k + 2]["frame"], 0, "MAV_FRAME_GLOBAL");
            assert_eq!(p[4], pt.geo.lat_deg);
            assert_eq!(p[5], pt.geo.lon_deg);
            assert_eq!(p[6], pt.geo.alt_m);
            // Acceptance radius: the tangent length of the turn (none at the ends).
            assert_eq!(p[1], pt.acceptance_m);
            let abs = |k: usize| {
                let w = path.points[k].local;
                glam::DVec3::new(w.x, w.y, world.terrain().height(w.x, w.y) + w.z)
            };
            // A repeated waypoint turns between the places before and after it.
            let here = abs(k);
            let before = (0..k).rev().map(abs).find(|p| *p != here);
            let after = (k + 1..m).map(abs).find(|p| *p != here);
            let want = match (before, after) {
                (Some(a), Some(c)) if k > 0 && k + 1 < m => {
                    let theta = swarmplan_core::flight::turn_angle(a, here, c);
                    swarmplan_core::flight::tangent_length(path.turn_radius_m, theta)
                }
                _ => 0.0,
            };
            assert!((pt.acceptance_m - want).abs() < 1e-6 * want.max(1.0), "{k}");
            // Altitude AMSL = terrain + AGL + the origin's altitude offset.
            let want = world.terrain().height(pt.local.x, pt.local.y) + pt.local.z + ORIGIN.alt_m;
            assert!((pt.geo.alt_m - want).abs() < 1e-9);
        }
        assert!(doc["swarmplan"]["altitudeReference"]
            .as_str()
            .unwrap()
            .contains("above mean sea level"));
        assert_eq!(
            doc["geoFence"]["circles"].as_array().unwrap().len(),
            world.spec().threats.len()
        );
    }
}

#[test]
fn wpl_and_geojson_read_with_pymavlink_and_geojson() {
    let world = tiny();
    let plan = planned(&world);
    let dir = tempfile::tempdir().unwrap();
    export_all(&world, &plan, dir.path());
    let mission = Mission::new(&world, &plan, &frame()).unwrap();
    // The Rust view of the WPL files, and the expectations for Python.
    let mut wpl = Vec::new();
    for p in &mission.paths {
        let name = format!("uav{}.waypoints", p.uav);
        let text = std::fs::read_to_string(dir.path().join(&name)).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some("QGC WPL 110"));
        let rows: Vec<Vec<&str>> = lines.map(|l| l.split('\t').collect()).collect();
        assert_eq!(
            rows.len(),
            p.points.len() + 4,
            "home, takeoff, speed, path, land"
        );
        for (k, r) in rows.iter().enumerate() {
            assert_eq!(r.len(), 12, "{name} line {k}: {r:?}");
            assert_eq!(r[0], k.to_string());
            assert_eq!(r[1], if k == 0 { "1" } else { "0" });
        }
        let (first, last) = (&p.points[0], &p.points[p.points.len() - 1]);
        let mut items = vec![
            serde_json::json!([
                16,
                0,
                first.geo.lat_deg,
                first.geo.lon_deg,
                first.ground_amsl_m
            ]),
            serde_json::json!([22, 0, first.geo.lat_deg, first.geo.lon_deg, first.geo.alt_m]),
            serde_json::json!([178, 2, 0.0, 0.0, 0.0]),
        ];
        for pt in &p.points {
            items.push(serde_json::json!([
                16,
                0,
                pt.geo.lat_deg,
                pt.geo.lon_deg,
                pt.geo.alt_m,
                pt.acceptance_m
            ]));
        }
        items.push(serde_json::json!([
            21,
            0,
            last.geo.lat_deg,
            last.geo.lon_deg,
            last.ground_amsl_m
        ]));
        wpl.push(serde_json::json!({"file": name, "items": items}));
    }
    let n_features = 3 * mission.paths.len() + 1 + mission.threats.len();
    let expected = serde_json::json!({
        "wpl": wpl,
        "geojson": {"file": "mission.geojson", "features": n_features},
    });
    std::fs::write(
        dir.path().join("expected.json"),
        serde_json::to_string_pretty(&expected).unwrap(),
    )
    .unwrap();
    // GeoJSON structure on the Rust side.
    let gj: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("mission.geojson")).unwrap())
            .unwrap();
    assert_eq!(gj["type"], "FeatureCollection");
    let feats = gj["features"].as_array().unwrap();
    assert_eq!(feats.len(), n_features);
    let path0 = &feats[0];
    assert_eq!(path0["geometry"]["type"], "LineString");
    assert_eq!(path0["properties"]["kind"], "path");
    assert!(path0["properties"]["altitude_reference"]
        .as_str()
        .unwrap()
        .contains("above mean sea level"));
    let c0 = &path0["geometry"]["coordinates"][0];
    assert_eq!(
        c0[0], mission.paths[0].points[0].geo.lon_deg,
        "[lon, lat, alt]"
    );
    let threat = feats.last().unwrap();
    assert_eq!(threat["geometry"]["type"], "Polygon");
    let ring = threat["geometry"]["coordinates"][0].as_array().unwrap();
    assert_eq!(ring.first(), ring.last(), "closed ring");
    // Counter-clockwise exterior ring (RFC 7946): positive shoelace area in lon/lat.
    let area: f64 = ring
        .windows(2)
        .map(|w| {
            let (a, b) = (&w[0], &w[1]);
            a[0].as_f64().unwrap() * b[1].as_f64().unwrap()
                - b[0].as_f64().unwrap() * a[1].as_f64().unwrap()
        })
        .sum();
    assert!(area > 0.0);

    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/export_check.py");
    let required = std::env::var("SWARMPLAN_REQUIRE_PYMAVLINK").is_ok_and(|v| v == "1");
    let out = match Command::new("python3")
        .arg(&script)
        .arg(dir.path())
        .output()
    {
        Ok(out) => out,
        Err(e) => {
            assert!(
                !required,
                "SWARMPLAN_REQUIRE_PYMAVLINK=1 but python3 cannot run: {e}"
            );
            println!("skipped: python3 cannot run ({e}); the pymavlink / geojson check needs it");
            return;
        }
    };
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    match out.status.code() {
        Some(0) => println!("{}", text.trim()),
        Some(3) if !required => println!("{}", text.trim()),
        Some(3) => panic!("SWARMPLAN_REQUIRE_PYMAVLINK=1 but the check was skipped: {text}"),
        _ => panic!("export_check.py failed:\n{text}"),
    }
}

#[test]
fn kml_and_csv_state_their_altitude_reference() {
    let world = tiny();
    let plan = planned(&world);
    let dir = tempfile::tempdir().unwrap();
    export_all(&world, &plan, dir.path());
    let kml = std::fs::read_to_string(dir.path().join("mission.kml")).unwrap();
    assert!(kml.starts_with("<?xml"));
    assert_eq!(
        kml.matches("<LineString><altitudeMode>absolute</altitudeMode>")
            .count(),
        2
    );
    assert_eq!(kml.matches("<Polygon>").count(), world.spec().threats.len());
    assert!(kml.contains("above mean sea level"));
    assert_eq!(
        kml.matches("<Placemark>").count(),
        kml.matches("</Placemark>").count()
    );
    let csv = std::fs::read_to_string(dir.path().join("mission.csv")).unwrap();
    let mut lines = csv.lines();
    let comment = lines.next().unwrap();
    assert!(comment.starts_with("# ") && comment.contains("above mean sea level"));
    assert_eq!(
        lines.next(),
        Some(
            "uav,waypoint,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,speed_mps,acceptance_m,pace,delay"
        )
    );
    let rows = lines.count();
    assert_eq!(
        rows,
        plan.uavs.iter().map(|p| p.waypoints.len()).sum::<usize>()
    );
}

#[test]
fn export_then_reimport_gives_the_same_cost() {
    let world = tiny();
    let plan = planned(&world);
    let before = assess_as_searched(&world, &plan);
    let dir = tempfile::tempdir().unwrap();
    for format in [ExportFormat::Csv, ExportFormat::GeoJson] {
        let files = export_plan(&world, &plan, &frame(), format, dir.path()).unwrap();
        let again = read_exported_plan(&files[0], &world, &frame()).unwrap();
        let worst = plan
            .uavs
            .iter()
            .zip(&again.uavs)
            .flat_map(|(a, b)| a.waypoints.iter().zip(&b.waypoints))
            .map(|(a, b)| a.distance(*b))
            .fold(0.0, f64::max);
        let after = assess_as_searched(&world, &again);
        println!(
            "{format}: worst waypoint error {worst:.2e} m, cost {} -> {} (diff {:.2e})",
            before.total,
            after.total,
            (after.total - before.total).abs()
        );
        assert!(worst < 1e-6, "{format}: {worst}");
        assert!((after.total - before.total).abs() < 1e-6, "{format}");
        assert!(
            (after.violation - before.violation).abs() < 1e-6,
            "{format}"
        );
        // Ends are snapped exactly onto the scenario's start and goal.
        for (i, p) in again.uavs.iter().enumerate() {
            assert_eq!(p.waypoints[0], world.start(i));
            assert_eq!(
                *p.waypoints.last().unwrap(),
                world.goal_at(swarmplan_core::world::DEPARTURE)
            );
        }
    }
}

#[test]
fn a_paced_plan_is_reimported_at_its_pace_and_a_foreign_pace_is_refused() {
    // Before the exports recorded the pace, a re-import was timed at pace 1: same waypoints,
    // other times, other cost.
    let mut loaded = load_spec("tiny").unwrap();
    loaded.spec.timing.pace = [0.5, 1.5];
    let world = build_world(&loaded, None).unwrap();
    let mut plan = planned(&world);
    plan.pace = 1.3;
    let before = assess_as_searched(&world, &plan);
    let at_unit_pace = assess_as_searched(
        &world,
        &Plan {
            pace: 1.0,
            ..plan.clone()
        },
    );
    assert!(
        (at_unit_pace.total - before.total).abs() > 1e-3,
        "the pace must matter here"
    );
    let dir = tempfile::tempdir().unwrap();
    for format in [ExportFormat::Csv, ExportFormat::GeoJson] {
        let files = export_plan(&world, &plan, &frame(), format, dir.path()).unwrap();
        let again = read_exported_plan(&files[0], &world, &frame()).unwrap();
        assert_eq!(again.pace.to_bits(), plan.pace.to_bits(), "{format}");
        let after = assess_as_searched(&world, &again);
        assert!((after.total - before.total).abs() < 1e-6, "{format}");
        // The unpaced scenario (pace fixed at 1) refuses the file, naming the pace.
        let e = read_exported_plan(&files[0], &tiny(), &frame())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("pace 1.3") && e.contains("timing.pace [1, 1]"),
            "{format}: {e}"
        );
    }
    // One fleet, one pace: rows that disagree are refused at the row.
    let csv_file = dir.path().join("mission.csv");
    let text = std::fs::read_to_string(&csv_file).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let last = lines.len() - 1;
    // The pace is the second column from the end (the UAV's delay is last).
    let (head, delay) = lines[last].rsplit_once(',').unwrap();
    lines[last] = format!("{},1.25,{delay}", head.rsplit_once(',').unwrap().0);
    let e = parse_csv(&lines.join("\n"), "m.csv", &world, &frame())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(&format!("line {}", last + 1)) && e.contains("one pace") && e.contains("1.25"),
        "{e}"
    );
}

#[test]
fn reimport_errors_name_the_file_and_the_problem() {
    let world = tiny();
    let f = frame();
    let e = parse_csv("uav,lat_deg\n0,1\n", "m.csv", &world, &f)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("m.csv: line 1") && e.contains("lon_deg"),
        "{e}"
    );
    let e = parse_csv(
        "uav,lat_deg,lon_deg,alt_amsl_m\n0,x,1,2\n",
        "m.csv",
        &world,
        &f,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("line 2") && e.contains("lat_deg") && e.contains("`x`"),
        "{e}"
    );
    let e = parse_csv(
        "uav,lat_deg,lon_deg,alt_amsl_m\n0,-10.45,105.62,100\n0,-10.45,105.62,100\n",
        "m.csv",
        &world,
        &f,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("2 UAVs") && e.contains("the file has 1"), "{e}");
    let e = parse_geojson("{\"type\": \"Feature\"}", "m.geojson", &world, &f)
        .unwrap_err()
        .to_string();
    assert!(e.contains("FeatureCollection"), "{e}");
    for bad in ["inf", "x", "-1"] {
        let e = parse_csv(
            &format!(
                "uav,lat_deg,lon_deg,alt_amsl_m,pace\n0,-10.45,105.62,100,{bad}\n1,-10.45,105.62,100,{bad}\n"
            ),
            "m.csv",
            &world,
            &f,
        )
        .unwrap_err()
        .to_string();
        let named = if bad == "-1" {
            e.contains("pace -1") && e.contains("timing.pace [1, 1]")
        } else {
            e.contains("line 2") && e.contains("pace: expected a number")
        };
        assert!(named, "{bad}: {e}");
    }
}

#[test]
fn without_an_origin_exports_are_refused_with_a_way_out() {
    let loaded = load_spec("tiny").unwrap();
    let e = resolve_frame(&loaded, None, None, None)
        .unwrap_err()
        .to_string();
    assert!(e.contains("scenario `tiny` has no geodetic origin"), "{e}");
    assert!(e.contains("[geo] origin = [lat, lon, alt]"), "{e}");
    assert!(e.contains("--origin LAT,LON"), "{e}");
    assert!(e.contains("procedural"), "{e}");
}

/// trajectory.csv is the flown path that was assessed: read back into the local frame, its
/// vertices, times and length are those of the assessment, its arcs cut every corner, and
/// it is flown at the assessed speed.
#[test]
fn the_exported_trajectory_is_the_assessed_flown_path() {
    use swarmplan_core::timing::TimedPlan;
    let world = tiny();
    assert!(
        world.flies_arcs(),
        "tiny is strict: plans are assessed as flown"
    );
    let plan = planned(&world);
    let report = assess_as_searched(&world, &plan);
    let waypoints = TimedPlan::new(&world, &plan);
    let mut flown = TimedPlan::default();
    flown.fill_flown(&world, &waypoints);
    let dir = tempfile::tempdir().unwrap();
    export_plan(&world, &plan, &frame(), ExportFormat::Csv, dir.path()).unwrap();
    let text = std::fs::read_to_string(dir.path().join("trajectory.csv")).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    assert_eq!(
        lines.next(),
        Some("uav,index,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,on_arc")
    );
    let mut by_uav: Vec<Vec<(f64, glam::DVec3, bool)>> = vec![Vec::new(); world.uav_count()];
    for l in lines {
        let f: Vec<&str> = l.split(',').collect();
        let num = |k: usize| f[k].parse::<f64>().unwrap();
        let local = frame()
            .from_geodetic(Geodetic::new(num(3), num(4), num(5)))
            .unwrap();
        by_uav[f[0].parse::<usize>().unwrap()].push((num(2), local, f[7] == "1"));
    }
    for (u, rows) in by_uav.iter().enumerate() {
        let fp = &flown.paths[u];
        assert_eq!(rows.len(), fp.abs.len(), "uav {u}");
        assert!(
            rows.len() > plan.uavs[u].waypoints.len(),
            "uav {u}: arcs add vertices"
        );
        let mut length = 0.0;
        for (k, (t, p, _)) in rows.iter().enumerate() {
            assert!(p.distance(fp.abs[k]) < 1e-6, "uav {u} vertex {k}");
            assert!((t - fp.time_at(k)).abs() < 1e-9, "uav {u} vertex {k}");
            if k > 0 {
                length += p.distance(rows[k - 1].1);
            }
        }
        let r = &report.per_uav[u];
        assert!((length - r.length_m).abs() < 1e-5, "uav {u}");
        assert!(
            (rows[rows.len() - 1].0 - r.arrival_s).abs() < 1e-9,
            "uav {u}"
        );
        assert!(
            rows.iter().any(|r| r.2),
            "uav {u}: some vertices are on arcs"
        );
        // The flown path never passes through an interior waypoint it turns at.
        let wps = &waypoints.paths[u].abs;
        for k in 1..wps.len() - 1 {
            if fp.tangents[k] > 1.0 {
                let nearest = rows
                    .iter()
                    .map(|r| r.1.distance(wps[k]))
                    .fold(f64::INFINITY, f64::min);
                assert!(nearest > 1e-3, "uav {u}: corner {k} is cut");
            }
        }
    }
}

/// Rewrites field `column` of the CSV row of UAV 0's waypoint 1 in an exported mission.
fn edit_mission_csv(csv: &str, column: &str, edit: impl Fn(f64) -> f64) -> String {
    let mut lines: Vec<String> = csv.lines().map(str::to_string).collect();
    let header = lines.iter().position(|l| l.starts_with("uav,")).unwrap();
    let col = lines[header].split(',').position(|c| c == column).unwrap();
    let row = lines
        .iter()
        .position(|l| l.starts_with("0,1,"))
        .expect("a row for uav 0 waypoint 1");
    let mut fields: Vec<String> = lines[row].split(',').map(str::to_string).collect();
    fields[col] = edit(fields[col].parse().unwrap()).to_string();
    lines[row] = fields.join(",");
    lines.join("\n")
}

#[test]
fn imported_missions_outside_the_model_are_refused_naming_the_waypoint() {
    // Found by the CI's 30-second `import` fuzz smoke: an imported waypoint 1e50 m above
    // ground made a flight of 1e48 s, which the communication sweep walked step by step (a
    // hang). Imports now pass the plan file's checks: map box and the channel's horizon.
    let world = tiny();
    let plan = Plan::straight(
        &(0..world.uav_count())
            .map(|i| world.start(i))
            .collect::<Vec<_>>(),
        world.goal_at(swarmplan_core::world::DEPARTURE),
        4,
    );
    let dir = tempfile::tempdir().unwrap();
    export_plan(&world, &plan, &frame(), ExportFormat::Csv, dir.path()).unwrap();
    let csv = std::fs::read_to_string(dir.path().join("mission.csv")).unwrap();
    let f = frame();
    assert!(parse_csv(&csv, "m.csv", &world, &f).is_ok());
    let high = edit_mission_csv(&csv, "alt_agl_m", |_| 1e50);
    let e = parse_csv(&high, "m.csv", &world, &f)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("m.csv: uav 0: the path is") && e.contains("beyond the 36000 s"),
        "{e}"
    );
    let east = edit_mission_csv(&csv, "lon_deg", |lon| lon + 1.0);
    let e = parse_csv(&east, "m.csv", &world, &f)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("m.csv: uav 0 waypoint 1: expected a point in the map box"),
        "{e}"
    );
}

#[test]
fn a_delayed_plan_hovers_in_every_export_and_is_reimported_with_its_delays() {
    let mut loaded = load_spec("tiny").unwrap();
    loaded.spec.timing.max_delay = 0.4;
    let world = build_world(&loaded, None).unwrap();
    let mut plan = planned(&world);
    plan.delays = vec![0.0, 0.25];
    let before = assess_as_searched(&world, &plan);
    let undelayed = assess_as_searched(
        &world,
        &Plan {
            delays: Vec::new(),
            ..plan.clone()
        },
    );
    assert!(
        (undelayed.total - before.total).abs() > 1e-3,
        "the delay must matter here"
    );
    let mission = Mission::new(&world, &plan, &frame()).unwrap();
    let late = &mission.paths[1];
    assert!(late.depart_s > 0.0 && mission.paths[0].depart_s == 0.0);
    assert!((late.depart_s - 0.25 * late.points.last().unwrap().time_s).abs() < 1e-9);
    assert!((late.points[0].time_s - late.depart_s).abs() < 1e-9);
    let dir = tempfile::tempdir().unwrap();
    // QGroundControl: the delayed UAV hovers at its start (NAV_LOITER_TIME, its seconds).
    export_plan(&world, &plan, &frame(), ExportFormat::QgcPlan, dir.path()).unwrap();
    for (uav, hold) in [(0, None), (1, Some(late.depart_s))] {
        let text = std::fs::read_to_string(dir.path().join(format!("uav{uav}.plan"))).unwrap();
        let doc: Value = serde_json::from_str(&text).unwrap();
        check_qgc_plan_format(&doc, "delayed");
        let items = doc["mission"]["items"].as_array().unwrap();
        let cmds: Vec<u64> = items
            .iter()
            .map(|i| i["command"].as_u64().unwrap())
            .collect();
        match hold {
            None => assert!(!cmds.contains(&19), "{cmds:?}"),
            Some(s) => {
                assert_eq!(&cmds[..3], &[22, 19, 178], "{cmds:?}");
                assert!((items[1]["params"][0].as_f64().unwrap() - s).abs() < 1e-9);
                assert_eq!(items[1]["params"][4], items[0]["params"][4]);
            }
        }
    }
    for format in [ExportFormat::Csv, ExportFormat::GeoJson] {
        let files = export_plan(&world, &plan, &frame(), format, dir.path()).unwrap();
        let again = read_exported_plan(&files[0], &world, &frame()).unwrap();
        let bits = |p: &Plan| p.delays.iter().map(|d| d.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&again), bits(&plan), "{format}");
        let after = assess_as_searched(&world, &again);
        assert!((after.total - before.total).abs() < 1e-6, "{format}");
        // A scenario without delays refuses the file, naming the UAV and the limit.
        let e = read_exported_plan(&files[0], &tiny(), &frame())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("uav 1") && e.contains("0.25") && e.contains("timing.max_delay 0"),
            "{format}: {e}"
        );
    }
    // One UAV, one departure: a row that disagrees is refused at the row.
    let text = std::fs::read_to_string(dir.path().join("mission.csv")).unwrap();
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    let last = lines.len() - 1;
    lines[last] = format!("{},0.125", lines[last].rsplit_once(',').unwrap().0);
    let e = swarmplan_io::import::parse_csv(&lines.join("\n"), "m.csv", &world, &frame())
        .unwrap_err()
        .to_string();
    assert!(
        e.contains(&format!("line {}", last + 1))
            && e.contains("uav 1's one departure delay")
            && e.contains("0.125"),
        "{e}"
    );
    // The plan file records each UAV's delay and reads it back.
    let file = swarmplan_io::plan_file::plan_file(&world, &plan);
    let text = serde_json::to_string(&file).unwrap();
    assert!(text.contains("\"delay\":0.25"), "{text}");
    let read = swarmplan_io::plan_file::parse_plan(
        &text,
        "plan.json",
        &world,
        swarmplan_io::plan_file::Provenance::MustMatch,
    )
    .unwrap();
    assert_eq!(read, plan);
    let e = swarmplan_io::plan_file::parse_plan(
        &text.replace("\"delay\":0.25", "\"delay\":0.95"),
        "plan.json",
        &world,
        swarmplan_io::plan_file::Provenance::AllowOther,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("uavs[1].delay") && e.contains("0.95"), "{e}");
}
