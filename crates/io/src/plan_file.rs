//! Plan files (JSON): what `evaluate` reads and `plan` writes.
//!
//! Input needs only `{"uavs": [{"waypoints": [[x, y, z_agl], ...]}, ...]}` with the start
//! and goal included. Output adds, per UAV, the time, speed and absolute and above-ground
//! altitude of every waypoint; readers ignore those extras, so a written plan reads back.
//!
//! A written plan also records the scenario's name and the terrain's fingerprint. A plan
//! carries heights above ground, so on other terrain it is another plan: reading one whose
//! recorded scenario or terrain differs from the world's is refused unless the caller says
//! [`Provenance::AllowOther`] (`evaluate --allow-other-terrain`). Hand-written plans without
//! these fields are accepted as they are.

use std::path::Path;
use swarmplan_core::world::DEPARTURE;

use glam::DVec3;
use serde::{Deserialize, Serialize};
use swarmplan_core::cost::comm::MAX_SWEPT_S;
use swarmplan_core::plan::{Path as UavPath, Plan};
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::spec::MAX_DELAY_LIMIT;
use swarmplan_core::world::World;
use thiserror::Error;

/// Why a plan file could not be read into a plan for a world; every variant names the file.
#[derive(Debug, Error)]
pub enum PlanFileError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The file is not JSON, or not the layout of a plan file.
    #[error("{path}: not a plan file: {message}")]
    Parse {
        /// The file.
        path: String,
        /// What is wrong, with where.
        message: String,
    },
    /// The plan was made for another scenario or terrain, or its pace or a delay is not one
    /// the scenario allows (only under [`Provenance::MustMatch`]).
    #[error("{path}: {what}: made for {recorded}, not for {current}; `evaluate --allow-other-terrain` assesses it anyway")]
    Provenance {
        /// The file.
        path: String,
        /// What differs: `scenario`, `terrain`, `pace` or `delay`.
        what: &'static str,
        /// What the file records.
        recorded: String,
        /// What the world has.
        current: String,
    },
    /// A field's value cannot be evaluated in the world (wrong UAV count, a waypoint
    /// outside the map or off the start or goal, a bad pace or delay).
    #[error("{path}: {field}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// The field, e.g. `uavs[0].waypoints[3]`.
        field: String,
        /// What was expected, and what was found.
        message: String,
    },
}

/// Waypoints of exactly three numbers: serde's arrays read the first three of a longer list
/// and leave the rest, which serde_json then reports as "trailing characters".
fn points<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<[f64; 3]>, D::Error> {
    let lists = Vec::<Vec<f64>>::deserialize(d)?;
    lists
        .into_iter()
        .enumerate()
        .map(|(k, p)| {
            let len = p.len();
            p.try_into().map_err(|_| {
                serde::de::Error::custom(format!(
                    "waypoint {k}: expected 3 numbers [x, y, z above ground], got {len}"
                ))
            })
        })
        .collect()
}

/// One UAV in a plan file. Unknown keys are refused, as in scenario files: a misspelt
/// `delay` used to be dropped and the UAV planned as leaving at once, without a word.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct UavEntry {
    /// [x, y, z above ground] of each waypoint, start and goal included.
    #[serde(deserialize_with = "points")]
    pub waypoints: Vec<[f64; 3]>,
    /// Departure delay, a share of the UAV's arrival time that it hovers at its start
    /// ([`Plan::delays`]; absent: 0, it leaves at once).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub delay: f64,
    /// Time at each waypoint, seconds after the mission starts (written, ignored on input);
    /// the first is the UAV's departure.
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

#[allow(clippy::trivially_copy_pass_by_ref, clippy::float_cmp)]
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// A plan file (unknown keys refused: a misspelt `pace` used to be read as pace 1).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlanFile {
    /// Name of the scenario it was made for (absent in hand-written plans).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scenario: Option<String>,
    /// [`swarmplan_core::world::terrain::Terrain::fingerprint`] of the terrain it was made on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub terrain_fingerprint: Option<String>,
    /// The fleet's pace ([`Plan::pace`]; absent: 1, nearest cruise).
    #[serde(
        default = "swarmplan_core::plan::unit_pace",
        skip_serializing_if = "swarmplan_core::plan::is_unit_pace"
    )]
    pub pace: f64,
    /// One entry per UAV, in the scenario's order.
    pub uavs: Vec<UavEntry>,
}

/// Whether a plan's recorded scenario and terrain must match the world it is read into.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Provenance {
    /// Refuse a plan recorded for another scenario or terrain.
    MustMatch,
    /// Read it anyway (the caller asked to evaluate a plan elsewhere).
    AllowOther,
}

/// Reads a plan file and checks it against `world`: one path per UAV, at least start and
/// goal, finite numbers, first and last waypoints at the scenario's start and goal.
pub fn read_plan(
    path: &Path,
    world: &World,
    provenance: Provenance,
) -> Result<Plan, PlanFileError> {
    let p = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| PlanFileError::Read {
        path: p.clone(),
        source,
    })?;
    parse_plan(&text, &p, world, provenance)
}

/// Parses plan JSON (see [`read_plan`]); `origin` names it in errors.
pub fn parse_plan(
    text: &str,
    origin: &str,
    world: &World,
    provenance: Provenance,
) -> Result<Plan, PlanFileError> {
    let file = parse_syntax(text, origin)?;
    if provenance == Provenance::MustMatch {
        check_provenance(&file, origin, world)?;
    }
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
                world.spec().name,
                file.uavs.len()
            ),
        ));
    }
    if !(file.pace.is_finite() && file.pace > 0.0) {
        return Err(invalid(
            "pace".into(),
            format!(
                "expected a positive factor on the preferred speed (1 = nearest cruise), got {}",
                file.pace
            ),
        ));
    }
    let [lo, hi] = world.spec().timing.pace;
    if provenance == Provenance::MustMatch && !world.spec().timing.allows_pace(file.pace) {
        return Err(PlanFileError::Provenance {
            path: origin.to_string(),
            what: "pace",
            recorded: format!("a pace of {}", file.pace),
            current: format!(
                "scenario `{}`'s timing.pace [{lo}, {hi}]",
                world.spec().name
            ),
        });
    }
    let mut plan = Plan {
        pace: file.pace,
        ..Plan::default()
    };
    for (i, u) in file.uavs.iter().enumerate() {
        let (waypoints, delay) = read_uav(i, u, origin, world, provenance)?;
        plan.uavs.push(UavPath { waypoints });
        plan.delays.push(delay);
    }
    if swarmplan_core::plan::no_delays(&plan.delays) {
        plan.delays.clear();
    }
    Ok(plan)
}

/// The JSON of a plan file, read as [`PlanFile`] (an object; nothing after it).
fn parse_syntax(text: &str, origin: &str) -> Result<PlanFile, PlanFileError> {
    let parse_error = |message: String| PlanFileError::Parse {
        path: origin.to_string(),
        message,
    };
    // serde reads a top-level array as the struct's fields in order, and would say
    // "invalid length 0, expected struct PlanFile with 4 elements".
    if text.trim_start().starts_with('[') {
        return Err(parse_error(
            "expected a JSON object (`{\"uavs\": [...], ...}`, as `plan` writes), found an array"
                .into(),
        ));
    }
    let de = &mut serde_json::Deserializer::from_str(text);
    let file: PlanFile = serde_path_to_error::deserialize(&mut *de).map_err(|e| {
        let at = e.path().to_string();
        let inner = e.into_inner();
        parse_error(if at == "." || at.is_empty() {
            inner.to_string()
        } else {
            format!("{at}: {inner}")
        })
    })?;
    de.end()
        .map_err(|e| parse_error(format!("text after the plan object: {e}")))?;
    Ok(file)
}

/// A plan recorded for another scenario or terrain is refused.
fn check_provenance(file: &PlanFile, origin: &str, world: &World) -> Result<(), PlanFileError> {
    let mismatch = |what, recorded: &str, current: String| PlanFileError::Provenance {
        path: origin.to_string(),
        what,
        recorded: recorded.to_string(),
        current,
    };
    if let Some(s) = file.scenario.as_deref().filter(|s| *s != world.spec().name) {
        return Err(mismatch(
            "scenario",
            &format!("scenario `{s}`"),
            format!("scenario `{}`", world.spec().name),
        ));
    }
    let current = world.terrain().fingerprint();
    if let Some(t) = file
        .terrain_fingerprint
        .as_deref()
        .filter(|t| *t != current)
    {
        return Err(mismatch(
            "terrain",
            &format!("terrain {t}"),
            format!("terrain {current} ({})", world.spec().terrain.source),
        ));
    }
    Ok(())
}

/// UAV `i`'s waypoints and departure delay, checked against the world: at least two, each
/// admissible, the first at its start and the last at the goal, a delay the scenario
/// allows.
fn read_uav(
    i: usize,
    u: &UavEntry,
    origin: &str,
    world: &World,
    provenance: Provenance,
) -> Result<(Vec<DVec3>, f64), PlanFileError> {
    let invalid = |field: String, message: String| PlanFileError::Invalid {
        path: origin.to_string(),
        field,
        message,
    };
    if u.waypoints.len() < 2 {
        return Err(invalid(
            format!("uavs[{i}].waypoints"),
            format!(
                "expected at least 2 waypoints (start and goal), got {}",
                u.waypoints.len()
            ),
        ));
    }
    let waypoints: Vec<DVec3> = u.waypoints.iter().map(|w| DVec3::from_array(*w)).collect();
    check_waypoints(world, i, &waypoints).map_err(|e| {
        invalid(
            match e.waypoint {
                Some(k) => format!("uavs[{i}].waypoints[{k}]"),
                None => format!("uavs[{i}].waypoints"),
            },
            e.message,
        )
    })?;
    let ends = [
        (0, world.start(i), "start"),
        (u.waypoints.len() - 1, world.goal_at(DEPARTURE), "goal"),
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
    let timing = &world.spec().timing;
    if !(0.0..=MAX_DELAY_LIMIT).contains(&u.delay) {
        return Err(invalid(
            format!("uavs[{i}].delay"),
            format!(
                "expected a share of the arrival time in [0, {MAX_DELAY_LIMIT}] (0: it leaves at once), got {}",
                u.delay
            ),
        ));
    }
    if provenance == Provenance::MustMatch && !timing.allows_delay(u.delay) {
        return Err(PlanFileError::Provenance {
            path: origin.to_string(),
            what: "delay",
            recorded: format!("uavs[{i}].delay {}", u.delay),
            current: format!(
                "scenario `{}`'s timing.max_delay {}",
                world.spec().name,
                timing.max_delay
            ),
        });
    }
    Ok((waypoints, u.delay))
}

/// Why a UAV's waypoints cannot be evaluated: which waypoint (none when it is the path as a
/// whole) and what was expected.
#[derive(Debug, Clone, PartialEq)]
pub struct InadmissiblePath {
    /// Index of the waypoint at fault; None when it is the path as a whole (too long).
    pub waypoint: Option<usize>,
    /// What was expected, and what was found.
    pub message: String,
}

/// Checks that UAV `uav`'s waypoints (x, y, height above ground) are a path the model can
/// evaluate: finite, inside the map box (the model is defined there), and short enough to be
/// flown at top speed within the [`MAX_SWEPT_S`] the communication sweep assesses (a longer
/// one is no plan and would take hours to evaluate; `plan` itself reports a flight beyond it
/// as a communication violation, so a plan it calls feasible is always read back). Every
/// reader of plans from outside (plan files, imported missions) goes through it.
pub fn check_waypoints(
    world: &World,
    uav: usize,
    waypoints: &[DVec3],
) -> Result<(), InadmissiblePath> {
    let at = |k: usize, message: String| InadmissiblePath {
        waypoint: Some(k),
        message,
    };
    if let Some(k) = waypoints.iter().position(|w| !w.is_finite()) {
        return Err(at(
            k,
            format!("expected finite numbers, got {:?}", waypoints[k].to_array()),
        ));
    }
    let (bx, by) = (world.spec().map.x, world.spec().map.y);
    let slack = 1e-6 * (bx[1] - bx[0]).max(by[1] - by[0]);
    for (k, w) in waypoints.iter().enumerate() {
        let inside = w.x >= bx[0] - slack
            && w.x <= bx[1] + slack
            && w.y >= by[0] - slack
            && w.y <= by[1] + slack;
        if !inside {
            return Err(at(
                k,
                format!(
                    "expected a point in the map box x {bx:?}, y {by:?} (the model is defined there), got {:?}",
                    w.to_array()
                ),
            ));
        }
    }
    let length: f64 = waypoints.windows(2).map(|s| s[0].distance(s[1])).sum();
    let v_max = world.spec().uavs[uav].speed[1];
    if length / v_max > MAX_SWEPT_S {
        return Err(InadmissiblePath {
            waypoint: None,
            message: format!(
                "the path is {length:.3e} m long: even at v_max {v_max} m/s the flight lasts {:.3e} s, beyond the {MAX_SWEPT_S} s the model assesses",
                length / v_max
            ),
        });
    }
    Ok(())
}

/// The plan file of `plan` with times, speeds and altitudes filled in.
#[must_use]
pub fn plan_file(world: &World, plan: &Plan) -> PlanFile {
    let timed = TimedPlan::new(world, plan);
    // Times and speeds are those of the flown path (the middle of each corner's arc).
    let flown = TimedPlan::flown(world, plan);
    let uavs = plan
        .uavs
        .iter()
        .zip(timed.paths.iter().zip(&flown.paths))
        .map(|(p, (tp, fp))| {
            let m = p.waypoints.len();
            UavEntry {
                delay: tp.delay,
                waypoints: p.waypoints.iter().map(|w| w.to_array()).collect(),
                time_s: fp.waypoint_times(&tp.abs),
                speed_mps: vec![fp.speed; m],
                altitude_abs_m: tp.abs.iter().map(|a| a.z).collect(),
                altitude_agl_m: p.waypoints.iter().map(|w| w.z).collect(),
            }
        })
        .collect();
    PlanFile {
        scenario: Some(world.spec().name.clone()),
        terrain_fingerprint: Some(world.terrain().fingerprint()),
        pace: plan.pace,
        uavs,
    }
}
