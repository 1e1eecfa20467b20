//! One GeoJSON FeatureCollection (RFC 7946) for the fleet: a LineString per UAV with
//! positions [longitude, latitude, altitude AMSL] and its schedule in the properties
//! (`time_s`, `alt_agl_m`, `speed_mps`; `delay` and `depart_s`, its departure delay as a
//! share of its arrival and in seconds, before which it hovers at its start), a Point for each start and for the goal, and a
//! Polygon per threat (its circle, counter-clockwise as RFC 7946 asks of exterior rings).
//!
//! RFC 7946 calls the third coordinate a height above the ellipsoid; these files carry the
//! altitude above mean sea level instead (no geoid model is applied), and every feature
//! says so in its `altitude_reference` property. `kind` tells features apart: `path` (the
//! waypoints, re-importable), `flown` (the path as flown and assessed: arcs of the turning
//! radius through the corners, time-stamped), `start`, `goal`, `threat`.

use serde_json::{json, Value};

use super::{Mission, ALTITUDE_REFERENCE};
use crate::geo::Geodetic;

fn position(g: &Geodetic) -> Value {
    json!([g.lon_deg, g.lat_deg, g.alt_m])
}

/// The GeoJSON text of a mission.
pub(crate) fn geojson(m: &Mission) -> String {
    let reference = format!("third coordinate: {ALTITUDE_REFERENCE}");
    let mut features = Vec::new();
    for p in &m.paths {
        features.push(json!({
            "type": "Feature",
            "geometry": {
                "type": "LineString",
                "coordinates": p.points.iter().map(|pt| position(&pt.geo)).collect::<Vec<_>>(),
            },
            "properties": {
                "kind": "path",
                "scenario": m.scenario,
                "uav": p.uav,
                "speed_mps": p.speed_mps,
                "pace": m.pace,
                "delay": p.delay,
                "depart_s": p.depart_s,
                "length_m": p.length_m,
                "arrival_s": p.points[p.points.len() - 1].time_s,
                "acceptance_m": p.points.iter().map(|pt| pt.acceptance_m).collect::<Vec<_>>(),
                "time_s": p.points.iter().map(|pt| pt.time_s).collect::<Vec<_>>(),
                "alt_agl_m": p.points.iter().map(|pt| pt.alt_agl_m).collect::<Vec<_>>(),
                "ground_amsl_m": p.points.iter().map(|pt| pt.ground_amsl_m).collect::<Vec<_>>(),
                "altitude_reference": reference,
            },
        }));
    }
    for p in &m.paths {
        features.push(json!({
            "type": "Feature",
            "geometry": {
                "type": "LineString",
                "coordinates": p.flown.iter().map(|pt| position(&pt.geo)).collect::<Vec<_>>(),
            },
            "properties": {
                "kind": "flown",
                "scenario": m.scenario,
                "uav": p.uav,
                "turn_radius_m": p.turn_radius_m,
                "time_s": p.flown.iter().map(|pt| pt.time_s).collect::<Vec<_>>(),
                "alt_agl_m": p.flown.iter().map(|pt| pt.alt_agl_m).collect::<Vec<_>>(),
                "altitude_reference": reference,
            },
        }));
    }
    for p in &m.paths {
        let s = &p.points[0];
        features.push(json!({
            "type": "Feature",
            "geometry": {"type": "Point", "coordinates": position(&s.geo)},
            "properties": {
                "kind": "start",
                "uav": p.uav,
                "alt_agl_m": s.alt_agl_m,
                "altitude_reference": reference,
            },
        }));
    }
    features.push(json!({
        "type": "Feature",
        "geometry": {"type": "Point", "coordinates": position(&m.goal)},
        "properties": {
            "kind": "goal",
            "name": "UGV0",
            "altitude_reference": format!("third coordinate: ground altitude AMSL at UGV0; {ALTITUDE_REFERENCE}"),
        },
    }));
    for t in &m.threats {
        features.push(json!({
            "type": "Feature",
            "geometry": {
                "type": "Polygon",
                "coordinates": [t.ring.iter().map(|g| json!([g.lon_deg, g.lat_deg])).collect::<Vec<_>>()],
            },
            "properties": {
                "kind": "threat",
                "index": t.index,
                "x_m": t.x,
                "y_m": t.y,
                "radius_m": t.r,
                "center": [t.center.lon_deg, t.center.lat_deg],
                "height": "unbounded (vertical cylinder)",
                "draw_height_agl_m": t.draw_height_m,
            },
        }));
    }
    let doc = json!({
        "type": "FeatureCollection",
        "name": format!("swarmplan {}", m.scenario),
        "description": m.header(),
        "features": features,
    });
    serde_json::to_string_pretty(&doc).expect("a JSON value always serialises") + "\n"
}
