//! Plan files (JSON): what `evaluate` reads and `plan` writes.
//!
//! Input needs only `{"uavs": [{"waypoints": [[x, y, z_agl], ...]}, ...]}` with the start
//! and goal included. Output adds, per UAV, the time, speed and absolute and above-ground
//! altitude of every waypoint; readers ignore those extras, so a written plan reads back.

use std::path::Path;

use glam::DVec3;
use serde::{Deserialize, Serialize};
use swarmplan_core::cost::Assessment;
use swarmplan_core::plan::{Path as UavPath, Plan};
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;
use thiserror::Error;

#[derive(Debug, Error)]
pub enum PlanFileError {
    #[error("{path}: cannot read: {source}")]
    Read {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}: not a plan file: {message}")]
    Parse { path: String, message: String },
    #[error("{path}: {field}: {message}")]
    Invalid {
        path: String,
        field: String,
        message: String,
    },
}

/// One UAV in a plan file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct UavEntry {
    /// [x, y, z above ground] of each waypoint, start and goal included.
    pub waypoints: Vec<[f64; 3]>,
    /// Time at each waypoint, seconds after departure (written, ignored on input).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub time_s: Vec<f64>,
    /// Speed on the segment leaving each waypoint, m/s (the last repeats the previous).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub speed_mps: Vec<f64>,
    /// Absolute altitude (terrain + height above ground) of each waypoint, metres.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub altitude_abs_m: Vec<f64>,
    /// Height above ground of each waypoint, metres (the z of `waypoints`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub altitude_agl_m: Vec<f64>,
}

/// A plan file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PlanFile {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scenario: Option<String>,
    pub uavs: Vec<UavEntry>,
}

/// Reads a plan file and checks it against `world`: one path per UAV, at least start and
/// goal, finite numbers, first and last waypoints at the scenario's start and goal.
pub fn read_plan(path: &Path, world: &World) -> Result<Plan, PlanFileError> {
    let p = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| PlanFileError::Read {
        path: p.clone(),
        source,
    })?;
    parse_plan(&text, &p, world)
}

/// Parses plan JSON (see [`read_plan`]); `origin` names it in errors.
pub fn parse_plan(text: &str, origin: &str, world: &World) -> Result<Plan, PlanFileError> {
    let file: PlanFile = serde_json::from_str(text).map_err(|e| PlanFileError::Parse {
        path: origin.to_string(),
        message: e.to_string(),
    })?;
    let invalid = |field: String, message: String| PlanFileError::Invalid {
        path: origin.to_string(),
        field,
        message,
    };
    let n = world.uav_count();
    if file.uavs.len() != n {
        return Err(invalid(
            "uavs".into(),
            format!(
                "scenario `{}` has {n} UAVs, the plan has {}",
                world.spec.name,
                file.uavs.len()
            ),
        ));
    }
    let mut plan = Plan::default();
    for (i, u) in file.uavs.iter().enumerate() {
        if u.waypoints.len() < 2 {
            return Err(invalid(
                format!("uavs[{i}].waypoints"),
                format!(
                    "expected at least 2 waypoints (start and goal), got {}",
                    u.waypoints.len()
                ),
            ));
        }
        for (k, w) in u.waypoints.iter().enumerate() {
            if w.iter().any(|v| !v.is_finite()) {
                return Err(invalid(
                    format!("uavs[{i}].waypoints[{k}]"),
                    format!("expected finite numbers, got {w:?}"),
                ));
            }
        }
        let ends = [
            (0, world.start(i), "start"),
            (u.waypoints.len() - 1, world.goal, "goal"),
        ];
        for (k, want, what) in ends {
            let got = DVec3::from_array(u.waypoints[k]);
            if got.distance(want) > 1e-6 {
                return Err(invalid(
                    format!("uavs[{i}].waypoints[{k}]"),
                    format!(
                        "expected the scenario's {what} [{}, {}, {}], got {:?}",
                        want.x, want.y, want.z, u.waypoints[k]
                    ),
                ));
            }
        }
        plan.uavs.push(UavPath {
            waypoints: u.waypoints.iter().map(|w| DVec3::from_array(*w)).collect(),
        });
    }
    Ok(plan)
}

/// The plan file of `plan` with times, speeds and altitudes filled in.
#[must_use]
pub fn plan_file(world: &World, plan: &Plan) -> PlanFile {
    let timed = TimedPlan::new(world, plan);
    let uavs = plan
        .uavs
        .iter()
        .zip(&timed.paths)
        .map(|(p, tp)| {
            let m = p.waypoints.len();
            UavEntry {
                waypoints: p.waypoints.iter().map(|w| w.to_array()).collect(),
                time_s: (0..m).map(|k| tp.time_at(k)).collect(),
                speed_mps: vec![tp.speed; m],
                altitude_abs_m: tp.abs.iter().map(|a| a.z).collect(),
                altitude_agl_m: p.waypoints.iter().map(|w| w.z).collect(),
            }
        })
        .collect();
    PlanFile {
        scenario: Some(world.spec.name.clone()),
        uavs,
    }
}

/// The `--json` report of `evaluate`: feasibility, cost and violations.
#[must_use]
pub fn assessment_json(a: &Assessment) -> serde_json::Value {
    let terms = a.term_totals();
    let mut term_map = serde_json::Map::new();
    for (name, v) in swarmplan_core::cost::Terms::NAMES
        .iter()
        .zip(terms.values())
    {
        term_map.insert((*name).to_string(), json_number(v));
    }
    term_map.insert("penalty".into(), json_number(a.penalty));
    serde_json::json!({
        "feasible": a.feasible(),
        "violation": json_number(a.violation),
        "cost": {
            "total": json_number(a.total),
            "per_uav": json_number(a.per_uav_cost()),
            "terms": term_map,
        },
        "uavs": a.per_uav.iter().map(|u| serde_json::json!({
            "cost": json_number(u.cost),
            "length_m": json_number(u.length_m),
            "speed_mps": json_number(u.speed_mps),
            "arrival_s": json_number(u.arrival_s),
            "energy_j": json_number(u.energy_j),
            "battery_ratio": json_number(u.battery_ratio),
            "min_clearance_m": json_number(u.min_clearance_m),
            "outage_s": json_number(u.outage_s),
        })).collect::<Vec<_>>(),
        "violations": a.violations.clone().unwrap_or_default(),
    })
}

/// JSON has no infinity: non-finite numbers become the strings "inf", "-inf", "nan".
#[must_use]
pub fn json_number(v: f64) -> serde_json::Value {
    if v.is_finite() {
        serde_json::json!(v)
    } else if v.is_nan() {
        serde_json::json!("nan")
    } else if v > 0.0 {
        serde_json::json!("inf")
    } else {
        serde_json::json!("-inf")
    }
}
