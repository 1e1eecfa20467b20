//! QGroundControl exports, one mission per UAV: the `.plan` JSON format (QGC's
//! "Plan File Format": fileType, version 1, groundStation, mission version 2 with
//! firmwareType, vehicleType, cruiseSpeed, hoverSpeed, plannedHomePosition and SimpleItems,
//! geoFence, rallyPoints) and the older `QGC WPL 110` text format (tab-separated; item 0 is
//! the home position).
//!
//! Items: NAV_TAKEOFF (22) at the start up to the start's altitude, NAV_LOITER_TIME (19) at
//! the start for the UAV's departure delay when it has one (param 1 the seconds it hovers
//! there before it leaves, the time the plan was assessed with), DO_CHANGE_SPEED (178,
//! ground speed) once, because a swarmplan path has one constant planned speed,
//! NAV_WAYPOINT (16) for every path point (start and goal included), NAV_LAND (21) at the
//! goal. A waypoint's param 2, the acceptance radius, is the tangent length R tan(theta/2)
//! of its turn (issue 15): the autopilot moves on to the next leg where the assessed arc
//! begins (docs/export.md says what autopilots do with it). Positions use MAV_FRAME_GLOBAL (0): altitude above mean sea level, the planner's
//! terrain + AGL, so the mission does not depend on the home altitude the autopilot
//! measures; the .plan items also say `AltitudeMode` 2 (QGC's "absolute"). Yaw (param 4)
//! is NaN (null in JSON, `nan` in WPL): the autopilot's own heading mode. Threats become
//! exclusion circles of the geofence (radius + drone size, the hard zone).

use serde_json::{json, Value};

use super::{num, Mission, MissionPath, ALTITUDE_REFERENCE};

const MAV_CMD_NAV_WAYPOINT: u16 = 16;
const MAV_CMD_NAV_LOITER_TIME: u16 = 19;
const MAV_CMD_NAV_LAND: u16 = 21;
const MAV_CMD_NAV_TAKEOFF: u16 = 22;
const MAV_CMD_DO_CHANGE_SPEED: u16 = 178;
/// Latitude, longitude, altitude AMSL.
const MAV_FRAME_GLOBAL: u8 = 0;
/// No position (commands).
const MAV_FRAME_MISSION: u8 = 2;
/// MAV_AUTOPILOT_GENERIC: nothing firmware-specific is used.
const FIRMWARE_GENERIC: u8 = 0;
/// MAV_TYPE_QUADROTOR (the energy model is a rotary wing).
const VEHICLE_QUADROTOR: u8 = 2;
/// QGroundControl's AltitudeMode "absolute" (AMSL, MAV_FRAME_GLOBAL).
const QGC_ALTITUDE_ABSOLUTE: u8 = 2;
/// DO_CHANGE_SPEED param 1: ground speed.
const SPEED_TYPE_GROUND: f64 = 1.0;

/// One mission item; NaN params are "not set".
pub(crate) struct Item {
    pub command: u16,
    pub frame: u8,
    pub params: [f64; 7],
}

impl Item {
    fn has_position(&self) -> bool {
        self.frame == MAV_FRAME_GLOBAL
    }
}

/// The items of one UAV's mission (without the WPL home item).
pub(crate) fn items(p: &MissionPath) -> Vec<Item> {
    let first = &p.points[0];
    let last = &p.points[p.points.len() - 1];
    let nav = |command: u16, lat: f64, lon: f64, alt: f64| Item {
        command,
        frame: MAV_FRAME_GLOBAL,
        params: [0.0, 0.0, 0.0, f64::NAN, lat, lon, alt],
    };
    let mut out = Vec::with_capacity(p.points.len() + 3);
    let at_start = |command: u16| {
        nav(
            command,
            first.geo.lat_deg,
            first.geo.lon_deg,
            first.geo.alt_m,
        )
    };
    out.push(at_start(MAV_CMD_NAV_TAKEOFF));
    if p.depart_s > 0.0 {
        let mut hold = at_start(MAV_CMD_NAV_LOITER_TIME);
        hold.params[0] = p.depart_s;
        out.push(hold);
    }
    out.push(Item {
        command: MAV_CMD_DO_CHANGE_SPEED,
        frame: MAV_FRAME_MISSION,
        params: [SPEED_TYPE_GROUND, p.speed_mps, -1.0, 0.0, 0.0, 0.0, 0.0],
    });
    for pt in &p.points {
        let mut item = nav(
            MAV_CMD_NAV_WAYPOINT,
            pt.geo.lat_deg,
            pt.geo.lon_deg,
            pt.geo.alt_m,
        );
        item.params[1] = pt.acceptance_m;
        out.push(item);
    }
    out.push(nav(
        MAV_CMD_NAV_LAND,
        last.geo.lat_deg,
        last.geo.lon_deg,
        last.ground_amsl_m,
    ));
    out
}

fn param_json(v: f64) -> Value {
    if v.is_finite() {
        json!(v)
    } else {
        Value::Null
    }
}

/// The `.plan` file of one UAV.
pub(crate) fn plan_json(m: &Mission, p: &MissionPath) -> String {
    let items: Vec<Value> = items(p)
        .iter()
        .enumerate()
        .map(|(k, it)| {
            let mut o = json!({
                "type": "SimpleItem",
                "autoContinue": true,
                "command": it.command,
                "doJumpId": k + 1,
                "frame": it.frame,
                "params": it.params.iter().map(|v| param_json(*v)).collect::<Vec<_>>(),
            });
            if it.has_position() {
                o["Altitude"] = json!(it.params[6]);
                o["AltitudeMode"] = json!(QGC_ALTITUDE_ABSOLUTE);
                o["AMSLAltAboveTerrain"] = Value::Null;
            }
            o
        })
        .collect();
    let first = &p.points[0];
    let circles: Vec<Value> = m
        .threats
        .iter()
        .map(|t| {
            json!({
                "circle": {
                    "center": [t.center.lat_deg, t.center.lon_deg],
                    "radius": t.r + p.size_m,
                },
                "inclusion": false,
                "version": 1,
            })
        })
        .collect();
    let last = &p.points[p.points.len() - 1];
    let doc = json!({
        "fileType": "Plan",
        "version": 1,
        "groundStation": "QGroundControl",
        "mission": {
            "version": 2,
            "firmwareType": FIRMWARE_GENERIC,
            "vehicleType": VEHICLE_QUADROTOR,
            "cruiseSpeed": p.speed_mps,
            "hoverSpeed": p.speed_mps,
            "globalPlanAltitudeMode": QGC_ALTITUDE_ABSOLUTE,
            "plannedHomePosition": [first.geo.lat_deg, first.geo.lon_deg, first.ground_amsl_m],
            "items": items,
        },
        "geoFence": {"circles": circles, "polygons": [], "version": 2},
        "rallyPoints": {"points": [], "version": 2},
        "swarmplan": {
            "description": m.header(),
            "altitudeReference": format!(
                "MAV_FRAME_GLOBAL (0): {ALTITUDE_REFERENCE}"
            ),
            "scenario": m.scenario,
            "uav": p.uav,
            "speedMps": p.speed_mps,
            "lengthM": p.length_m,
            "arrivalS": last.time_s,
        },
    });
    serde_json::to_string_pretty(&doc).expect("a JSON value always serialises") + "\n"
}

fn wpl_num(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else {
        num(v)
    }
}

/// The `QGC WPL 110` file of one UAV: header, home (item 0), then the mission items.
/// No comment lines: QGroundControl's reader takes every line after the header as an item.
pub(crate) fn wpl(p: &MissionPath) -> String {
    let first = &p.points[0];
    let mut rows = vec![(
        1u8,
        Item {
            command: MAV_CMD_NAV_WAYPOINT,
            frame: MAV_FRAME_GLOBAL,
            params: [
                0.0,
                0.0,
                0.0,
                0.0,
                first.geo.lat_deg,
                first.geo.lon_deg,
                first.ground_amsl_m,
            ],
        },
    )];
    rows.extend(items(p).into_iter().map(|it| (0u8, it)));
    let mut s = String::from("QGC WPL 110\n");
    for (k, (current, it)) in rows.iter().enumerate() {
        let params: Vec<String> = it.params.iter().map(|v| wpl_num(*v)).collect();
        s.push_str(&format!(
            "{k}\t{current}\t{}\t{}\t{}\t1\n",
            it.frame,
            it.command,
            params.join("\t")
        ));
    }
    s
}
