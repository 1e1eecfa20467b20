//! Re-import of exported plans: a mission CSV or GeoJSON written by [`crate::export`]
//! becomes a [`Plan`] again (WGS 84 -> local frame), so that export, re-import and
//! evaluation give the cost of the original plan (to rounding: the frames' round trips are
//! exact to about 1e-9 m).
//!
//! Heights above ground come from the `alt_agl_m` column (CSV) or property (GeoJSON) when
//! present, which the exports always write; otherwise from the altitude AMSL minus the
//! terrain under the imported position. The first and last waypoints of each path are
//! snapped onto the scenario's start and goal when within 1 cm, so that the round trip's
//! last-bit differences do not fail the plan checks of `evaluate`.
//!
//! The fleet's pace comes from the `pace` column (CSV, the same on every row) or property
//! (GeoJSON, the same on every path); files without it are at pace 1, as exports were
//! before the pace existed. A pace the scenario's `timing.pace` does not allow is refused:
//! the times in the file would not be the times the plan is evaluated at. Likewise each
//! UAV's departure delay comes from the `delay` column (the same on each of its rows) or
//! property (absent: 0), and one the scenario's `timing.max_delay` does not allow is refused.

use std::collections::BTreeMap;
use std::path::Path;
use swarmplan_core::world::DEPARTURE;

use glam::DVec3;
use serde_json::Value;
use swarmplan_core::plan::{Path as UavPath, Plan};
use swarmplan_core::world::World;
use thiserror::Error;

use crate::geo::{GeoError, Geodetic, LocalFrame};

/// Distance within which imported end points are snapped onto the start and goal, metres.
pub const SNAP_M: f64 = 0.01;

/// Why an exported mission could not be imported as a plan; every variant names the file.
#[derive(Debug, Error)]
pub enum ImportError {
    /// The file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: String,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A line of a CSV export is malformed.
    #[error("{path}: line {line}: {message}")]
    Line {
        /// The file.
        path: String,
        /// The line (1-based).
        line: usize,
        /// What is wrong.
        message: String,
    },
    /// The file is not a mission export, or its plan does not fit the scenario (UAV count,
    /// pace, delays, waypoints).
    #[error("{path}: {message}")]
    Invalid {
        /// The file.
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A waypoint could not be converted into the local frame.
    #[error("{path}: {source}")]
    Geo {
        /// The file, with the UAV and waypoint.
        path: String,
        /// The conversion error.
        source: GeoError,
    },
}

/// One imported waypoint before conversion: latitude, longitude, altitude AMSL, and the
/// height above ground if the file gave it.
#[derive(Debug, Clone, Copy)]
struct Fix {
    geo: Geodetic,
    agl: Option<f64>,
}

/// Reads a mission export by extension: `.csv`, or `.geojson` / `.json`.
pub fn read_exported_plan(
    path: &Path,
    world: &World,
    frame: &LocalFrame,
) -> Result<Plan, ImportError> {
    let name = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| ImportError::Read {
        path: name.clone(),
        source,
    })?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "csv" => parse_csv(&text, &name, world, frame),
        "geojson" | "json" => parse_geojson(&text, &name, world, frame),
        _ => Err(ImportError::Invalid {
            path: name,
            message: format!("expected a .csv or .geojson mission export, got `.{ext}`"),
        }),
    }
}

/// Parses a mission CSV (columns by name: `uav`, `lat_deg`, `lon_deg`, `alt_amsl_m`;
/// optional `waypoint`, `alt_agl_m`; `#` lines are comments).
pub fn parse_csv(
    text: &str,
    name: &str,
    world: &World,
    frame: &LocalFrame,
) -> Result<Plan, ImportError> {
    let line_err = |line: usize, message: String| ImportError::Line {
        path: name.to_string(),
        line,
        message,
    };
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (hline, header) = lines.next().ok_or_else(|| ImportError::Invalid {
        path: name.to_string(),
        message: "no header row".into(),
    })?;
    let cols: Vec<&str> = header.split(',').map(str::trim).collect();
    let col = |c: &str| cols.iter().position(|h| *h == c);
    let need = |c: &str| {
        col(c).ok_or_else(|| {
            line_err(
                hline,
                format!("missing column `{c}` (expected uav, lat_deg, lon_deg, alt_amsl_m)"),
            )
        })
    };
    let (cu, clat, clon, camsl) = (
        need("uav")?,
        need("lat_deg")?,
        need("lon_deg")?,
        need("alt_amsl_m")?,
    );
    let (cwp, cagl, cpace) = (col("waypoint"), col("alt_agl_m"), col("pace"));
    let cdelay = col("delay");
    let mut pace: Option<(f64, String)> = None;
    let mut delays: BTreeMap<usize, Option<(f64, String)>> = BTreeMap::new();
    let mut rows: BTreeMap<usize, Vec<(usize, Fix)>> = BTreeMap::new();
    for (line, l) in lines {
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        if f.len() != cols.len() {
            return Err(line_err(
                line,
                format!("expected {} fields, got {}", cols.len(), f.len()),
            ));
        }
        let number = |c: usize| {
            f[c].parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    line_err(
                        line,
                        format!("{}: expected a number, got `{}`", cols[c], f[c]),
                    )
                })
        };
        let index = |c: usize| {
            f[c].parse::<usize>().map_err(|_| {
                line_err(
                    line,
                    format!(
                        "{}: expected a non-negative integer, got `{}`",
                        cols[c], f[c]
                    ),
                )
            })
        };
        if let Some(c) = cpace {
            let p = number(c)?;
            one_value(&mut pace, p, format!("line {line}"), "the fleet's one pace")
                .map_err(|m| line_err(line, format!("pace: {m}")))?;
        }
        let uav = index(cu)?;
        if let Some(c) = cdelay {
            let d = number(c)?;
            let what = format!("uav {uav}'s one departure delay");
            one_value(
                delays.entry(uav).or_default(),
                d,
                format!("line {line}"),
                &what,
            )
            .map_err(|m| line_err(line, format!("delay: {m}")))?;
        }
        let entry = rows.entry(uav).or_default();
        let k = match cwp {
            Some(c) => index(c)?,
            None => entry.len(),
        };
        let fix = Fix {
            geo: Geodetic::new(number(clat)?, number(clon)?, number(camsl)?),
            agl: cagl.map(number).transpose()?,
        };
        entry.push((k, fix));
    }
    let paths = ordered_paths(rows, name)?;
    let delays = delays
        .into_iter()
        .filter_map(|(u, d)| Some((u, d?.0)))
        .collect();
    to_plan(paths, pace.map(|(p, _)| p), &delays, name, world, frame)
}

/// Each UAV's fixes in waypoint order; UAVs must run 0, 1, 2, ... and so must each UAV's
/// waypoints.
fn ordered_paths(
    rows: BTreeMap<usize, Vec<(usize, Fix)>>,
    name: &str,
) -> Result<Vec<Vec<Fix>>, ImportError> {
    let mut paths = Vec::with_capacity(rows.len());
    for (expect, (uav, mut pts)) in rows.into_iter().enumerate() {
        if uav != expect {
            return Err(ImportError::Invalid {
                path: name.to_string(),
                message: format!("uav {expect} has no rows (UAVs must be numbered from 0)"),
            });
        }
        pts.sort_by_key(|(k, _)| *k);
        if let Some(pos) = pts.iter().enumerate().position(|(pos, (k, _))| pos != *k) {
            return Err(ImportError::Invalid {
                path: name.to_string(),
                message: format!(
                    "uav {uav}: waypoint {pos} is missing or repeated (waypoints must run 0, 1, 2, ...)"
                ),
            });
        }
        paths.push(pts.into_iter().map(|(_, f)| f).collect::<Vec<_>>());
    }
    Ok(paths)
}

/// Parses a mission GeoJSON: the `path` features (LineStrings of [lon, lat, alt AMSL] with
/// a `uav` property and, optionally, an `alt_agl_m` array).
pub fn parse_geojson(
    text: &str,
    name: &str,
    world: &World,
    frame: &LocalFrame,
) -> Result<Plan, ImportError> {
    let invalid = |message: String| ImportError::Invalid {
        path: name.to_string(),
        message,
    };
    let doc: Value = serde_json::from_str(text).map_err(|e| invalid(format!("not JSON: {e}")))?;
    if doc["type"] != "FeatureCollection" {
        return Err(invalid(format!(
            "expected a GeoJSON FeatureCollection, got type {}",
            doc["type"]
        )));
    }
    let features = doc["features"]
        .as_array()
        .ok_or_else(|| invalid("`features` is not an array".into()))?;
    let mut by_uav: BTreeMap<usize, Vec<Fix>> = BTreeMap::new();
    let mut pace: Option<(f64, String)> = None;
    let mut delays: BTreeMap<usize, f64> = BTreeMap::new();
    for (k, f) in features.iter().enumerate() {
        let props = &f["properties"];
        let is_path = props["kind"] == "path"
            || (props["kind"].is_null() && f["geometry"]["type"] == "LineString");
        if !is_path {
            continue;
        }
        let here = format!("features[{k}]");
        if f["geometry"]["type"] != "LineString" {
            return Err(invalid(format!("{here}: a path must be a LineString")));
        }
        let uav = props["uav"]
            .as_u64()
            .and_then(|u| usize::try_from(u).ok())
            .ok_or_else(|| invalid(format!("{here}.properties.uav: expected a UAV index")))?;
        if !props["pace"].is_null() {
            let p = props["pace"].as_f64().ok_or_else(|| {
                invalid(format!(
                    "{here}.properties.pace: expected a number, got {}",
                    props["pace"]
                ))
            })?;
            one_value(&mut pace, p, here.clone(), "the fleet's one pace")
                .map_err(|m| invalid(format!("{here}.properties.pace: {m}")))?;
        }
        if !props["delay"].is_null() {
            let d = props["delay"].as_f64().ok_or_else(|| {
                invalid(format!(
                    "{here}.properties.delay: expected a number, got {}",
                    props["delay"]
                ))
            })?;
            delays.insert(uav, d);
        }
        let coords = f["geometry"]["coordinates"]
            .as_array()
            .ok_or_else(|| invalid(format!("{here}: coordinates are not an array")))?;
        let agl = props["alt_agl_m"].as_array();
        if agl.is_some_and(|a| a.len() != coords.len()) {
            return Err(invalid(format!(
                "{here}.properties.alt_agl_m: expected {} values, one per position",
                coords.len()
            )));
        }
        let mut fixes = Vec::with_capacity(coords.len());
        for (j, c) in coords.iter().enumerate() {
            let v: Option<Vec<f64>> = c
                .as_array()
                .map(|a| a.iter().filter_map(Value::as_f64).collect());
            let Some(v) = v.filter(|v| v.len() == 3 && c.as_array().is_some_and(|a| a.len() == 3))
            else {
                return Err(invalid(format!(
                    "{here}.coordinates[{j}]: expected [longitude, latitude, altitude], got {c}"
                )));
            };
            let a = match agl {
                Some(a) => Some(a[j].as_f64().ok_or_else(|| {
                    invalid(format!(
                        "{here}.properties.alt_agl_m[{j}]: expected a number"
                    ))
                })?),
                None => None,
            };
            fixes.push(Fix {
                geo: Geodetic::new(v[1], v[0], v[2]),
                agl: a,
            });
        }
        if by_uav.insert(uav, fixes).is_some() {
            return Err(invalid(format!("{here}: a second path for uav {uav}")));
        }
    }
    let mut paths = Vec::with_capacity(by_uav.len());
    for (expect, (uav, fixes)) in by_uav.into_iter().enumerate() {
        if uav != expect {
            return Err(invalid(format!(
                "no path for uav {expect} (UAVs must be numbered from 0)"
            )));
        }
        paths.push(fixes);
    }
    to_plan(paths, pace.map(|(p, _)| p), &delays, name, world, frame)
}

/// Keeps the first value read (with where it was read) and refuses a later one that is
/// not the same bits: a fleet flies at one pace, a UAV departs once (`what` names it).
fn one_value(
    first: &mut Option<(f64, String)>,
    v: f64,
    at: String,
    what: &str,
) -> Result<(), String> {
    match first {
        None => *first = Some((v, at)),
        Some((q, there)) if q.to_bits() != v.to_bits() => {
            return Err(format!("expected {what}, {q} ({there}), got {v}"));
        }
        Some(_) => {}
    }
    Ok(())
}

/// Converts imported fixes to a plan and checks it against the world.
fn to_plan(
    paths: Vec<Vec<Fix>>,
    pace: Option<f64>,
    delays: &BTreeMap<usize, f64>,
    name: &str,
    world: &World,
    frame: &LocalFrame,
) -> Result<Plan, ImportError> {
    let invalid = |message: String| ImportError::Invalid {
        path: name.to_string(),
        message,
    };
    let n = world.uav_count();
    if paths.len() != n {
        return Err(invalid(format!(
            "scenario `{}` has {n} UAVs, the file has {}",
            world.spec().name,
            paths.len()
        )));
    }
    let pace = pace.unwrap_or(1.0);
    let [lo, hi] = world.spec().timing.pace;
    if !(pace.is_finite() && pace > 0.0 && world.spec().timing.allows_pace(pace)) {
        return Err(invalid(format!(
            "pace {pace}: scenario `{}` allows timing.pace [{lo}, {hi}]",
            world.spec().name
        )));
    }
    let mut plan = Plan {
        pace,
        ..Plan::default()
    };
    for (i, fixes) in paths.into_iter().enumerate() {
        if fixes.len() < 2 {
            return Err(invalid(format!(
                "uav {i}: expected at least 2 waypoints (start and goal), got {}",
                fixes.len()
            )));
        }
        let mut waypoints = Vec::with_capacity(fixes.len());
        for (k, f) in fixes.iter().enumerate() {
            let p = frame
                .from_geodetic(f.geo)
                .map_err(|source| ImportError::Geo {
                    path: format!("{name}: uav {i} waypoint {k}"),
                    source,
                })?;
            let agl = f
                .agl
                .unwrap_or_else(|| p.z - world.terrain().height(p.x, p.y));
            waypoints.push(DVec3::new(p.x, p.y, agl));
        }
        let last = waypoints.len() - 1;
        for (k, want) in [(0, world.start(i)), (last, world.goal_at(DEPARTURE))] {
            if waypoints[k].distance(want) <= SNAP_M {
                waypoints[k] = want;
            }
        }
        crate::plan_file::check_waypoints(world, i, &waypoints).map_err(|e| {
            invalid(match e.waypoint {
                Some(k) => format!("uav {i} waypoint {k}: {}", e.message),
                None => format!("uav {i}: {}", e.message),
            })
        })?;
        plan.uavs.push(UavPath { waypoints });
        let delay = delays.get(&i).copied().unwrap_or(0.0);
        if !(delay.is_finite() && world.spec().timing.allows_delay(delay)) {
            return Err(invalid(format!(
                "uav {i}: departure delay {delay}: scenario `{}` allows timing.max_delay {} (a share of the arrival time in [0, max_delay])",
                world.spec().name, world.spec().timing.max_delay
            )));
        }
        plan.delays.push(delay);
    }
    if swarmplan_core::plan::no_delays(&plan.delays) {
        plan.delays.clear();
    }
    Ok(plan)
}
