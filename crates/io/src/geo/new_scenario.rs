//! `swarmplan scenario new`: an editable scenario on a georeferenced DEM from a start and a
//! goal given in latitude and longitude.
//!
//! It starts from the built-in `paper-case1` (so every model setting has the paper's
//! value), then: terrain = the DEM in the `georeferenced` frame with bilinear sampling; map
//! box = the DEM's extent (or the start-goal box plus a margin, clipped to it); start and
//! goal converted to the local frame at a given height above ground (150 m); N identical
//! UAVs at the start; no threats, interference windows or extra ground nodes (they were
//! placed for the paper's map); the communication range and battery scaled by the
//! start-goal distance over the paper's (922 m; the battery never below the paper's); and
//! the geodetic origin of local (0, 0) as `[geo] origin`; launch and recovery slots 5 s
//! apart (the fleet shares its start and UGV0; docs/model.md, "Launch and recovery slots").

use std::path::Path;

use glam::DVec2;
use swarmplan_core::world::spec::{ScenarioSpec, TerrainFrame};
use swarmplan_core::world::terrain::Sampling;

use super::ellipsoid::Geodetic;
use super::frame::LocalFrame;
use super::GeoError;
use crate::dem::{read_terrain, DemFrame, DemOptions, LoadedDem};
use crate::scenario::{parse_spec, to_toml};

use crate::scenario::load_builtin;

/// What `scenario new` was asked for.
#[derive(Debug, Clone)]
pub struct NewScenarioRequest<'a> {
    /// The DEM file to read.
    pub terrain: &'a Path,
    /// What to write as `terrain.source` (relative to where the TOML will live).
    pub terrain_source: String,
    /// Start and goal latitude and longitude (altitudes ignored).
    pub start: Geodetic,
    /// Goal latitude and longitude (altitude ignored).
    pub goal: Geodetic,
    /// Number of UAVs, >= 1.
    pub uavs: usize,
    /// Height above ground of the start and goal, metres (150).
    pub agl: f64,
    /// Scenario name.
    pub name: String,
    /// Map box = start-goal box plus this margin (m), clipped to the DEM; None: the DEM.
    pub margin: Option<f64>,
}

/// The result: the spec, its origin and where start and goal landed.
#[derive(Debug, Clone)]
pub struct NewScenario {
    /// The scenario built.
    pub spec: ScenarioSpec,
    /// Geodetic position of local (0, 0) (the DEM's south-west node), altitude 0.
    pub origin: Geodetic,
    /// The DEM's frame, which maps the scenario's plan coordinates to WGS 84.
    pub frame: LocalFrame,
    /// Local (x, y) of the start and the goal, metres.
    pub start_local: DVec2,
    /// Local (x, y) of the goal, metres.
    pub goal_local: DVec2,
}

/// Start-goal distance of the paper's Case 1, metres (from (200, 100) to (800, 800)).
fn paper_distance(spec: &ScenarioSpec) -> f64 {
    let s = spec.uavs[0].start;
    let g = spec.goal.position;
    (g[0] - s[0]).hypot(g[1] - s[1])
}

/// A bad value of `what` (a flag): what was expected and what was given.
fn flag(what: &str, expected: String, got: String) -> GeoError {
    GeoError::Syntax {
        what: what.into(),
        expected,
        got,
    }
}

/// Builds the scenario (see the module docs). Errors name the flag at fault.
pub fn new_scenario(req: &NewScenarioRequest<'_>) -> Result<NewScenario, GeoError> {
    check_request(req)?;
    let (dem, frame) = read_dem(req)?;
    let (start, goal) = locate_ends(req, &dem, &frame)?;
    let spec = fit_template(req, start, goal, dem.terrain.extent())?;
    // The result must read back as a valid scenario.
    let spec = parse_spec(&to_toml(&spec), "scenario new")?;
    let origin = frame.origin()?;
    Ok(NewScenario {
        spec,
        origin: Geodetic::new(origin.lat_deg, origin.lon_deg, 0.0),
        frame,
        start_local: start,
        goal_local: goal,
    })
}

/// The request's numbers: at least one UAV, a positive height, a non-negative margin.
fn check_request(req: &NewScenarioRequest<'_>) -> Result<(), GeoError> {
    if req.uavs == 0 {
        return Err(flag("--uavs", "at least 1 UAV".into(), "0".into()));
    }
    if !(req.agl.is_finite() && req.agl > 0.0) {
        return Err(flag(
            "--agl",
            "a positive height above ground in metres".into(),
            req.agl.to_string(),
        ));
    }
    if let Some(m) = req.margin {
        if !(m.is_finite() && m >= 0.0) {
            return Err(flag(
                "--margin",
                "a non-negative number of metres".into(),
                m.to_string(),
            ));
        }
    }
    Ok(())
}

/// The DEM and the local frame its CRS gives.
fn read_dem(req: &NewScenarioRequest<'_>) -> Result<(LoadedDem, LocalFrame), GeoError> {
    let opts = DemOptions {
        frame: DemFrame::Georeferenced,
        sampling: Sampling::Bilinear,
    };
    let dem = read_terrain(req.terrain, &opts).map_err(|e| {
        flag(
            "--terrain",
            "a readable GeoTIFF (or ESRI ASCII grid) DEM".into(),
            e.to_string(),
        )
    })?;
    let frame = LocalFrame::from_dem(&dem).map_err(|e| {
        flag(
            "--terrain",
            "a GeoTIFF in a supported CRS (WGS 84 / UTM, GDA94 or GDA2020 / MGA, or \
             geographic WGS 84)"
                .into(),
            e.to_string(),
        )
    })?;
    Ok((dem, frame))
}

/// The start and goal in the local frame, each inside the DEM and at least 1 m apart.
fn locate_ends(
    req: &NewScenarioRequest<'_>,
    dem: &LoadedDem,
    frame: &LocalFrame,
) -> Result<(DVec2, DVec2), GeoError> {
    let (x0, y0, x1, y1) = dem.terrain.extent();
    // The DEM's geodetic bounds, for messages.
    let corners: Vec<Geodetic> = [(x0, y0), (x1, y0), (x0, y1), (x1, y1)]
        .iter()
        .map(|&(x, y)| frame.to_geodetic(glam::DVec3::new(x, y, 0.0)))
        .collect::<Result<_, _>>()
        .map_err(|e| {
            // A tie point or cell size far off the projection's range: say which file.
            flag(
                "--terrain",
                "a DEM whose corners are places on Earth".into(),
                format!("{}: {e}", dem.path.display()),
            )
        })?;
    let span = |f: fn(&Geodetic) -> f64| {
        let v: Vec<f64> = corners.iter().map(f).collect();
        (
            v.iter().copied().fold(f64::INFINITY, f64::min),
            v.iter().copied().fold(f64::NEG_INFINITY, f64::max),
        )
    };
    let (lat_lo, lat_hi) = span(|g| g.lat_deg);
    let (lon_lo, lon_hi) = span(|g| g.lon_deg);
    let locate = |what: &str, g: Geodetic| -> Result<DVec2, GeoError> {
        let p = frame.from_geodetic(Geodetic::new(g.lat_deg, g.lon_deg, 0.0))?;
        if p.x < x0 || p.x > x1 || p.y < y0 || p.y > y1 {
            return Err(flag(
                what,
                format!(
                    "a point inside the DEM {} (latitude {lat_lo:.6} to {lat_hi:.6}, \
                     longitude {lon_lo:.6} to {lon_hi:.6}; local x {x0} to {x1} m, y {y0} to \
                     {y1} m)",
                    dem.path.display()
                ),
                format!(
                    "{},{} (local x {:.1} m, y {:.1} m)",
                    g.lat_deg, g.lon_deg, p.x, p.y
                ),
            ));
        }
        Ok(p.truncate())
    };
    let start = locate("--start", req.start)?;
    let goal = locate("--goal", req.goal)?;
    let distance = start.distance(goal);
    if distance < 1.0 {
        return Err(flag(
            "--goal",
            "a point at least 1 m from --start".into(),
            format!(
                "{},{} ({distance:.3} m away)",
                req.goal.lat_deg, req.goal.lon_deg
            ),
        ));
    }
    Ok((start, goal))
}

/// The paper's Case 1 fitted to the request: its fleet at the start, UGV0 at the goal, the
/// map box the DEM (or the margin around both), batteries and range scaled with the
/// distance, no threats, interference or extra nodes.
fn fit_template(
    req: &NewScenarioRequest<'_>,
    start: DVec2,
    goal: DVec2,
    (x0, y0, x1, y1): (f64, f64, f64, f64),
) -> Result<ScenarioSpec, GeoError> {
    let distance = start.distance(goal);
    let mut spec = load_builtin("paper-case1")?.spec;
    let ratio = distance / paper_distance(&spec);
    spec.name = req.name.clone();
    spec.description = format!(
        "{} UAVs over {} from ({}, {}) to ({}, {}), {:.0} m apart (scenario new)",
        req.uavs,
        req.terrain.file_name().map_or_else(
            || req.terrain.display().to_string(),
            |n| n.to_string_lossy().into()
        ),
        req.start.lat_deg,
        req.start.lon_deg,
        req.goal.lat_deg,
        req.goal.lon_deg,
        distance
    );
    spec.terrain.source = req.terrain_source.clone();
    spec.terrain.frame = TerrainFrame::Georeferenced;
    spec.terrain.sampling = Sampling::Bilinear;
    let (mut bx, mut by) = ([x0, x1], [y0, y1]);
    if let Some(m) = req.margin {
        bx = [
            (start.x.min(goal.x) - m).max(x0),
            (start.x.max(goal.x) + m).min(x1),
        ];
        by = [
            (start.y.min(goal.y) - m).max(y0),
            (start.y.max(goal.y) + m).min(y1),
        ];
        if bx[1] - bx[0] < 1.0 || by[1] - by[0] < 1.0 {
            return Err(flag(
                "--margin",
                "a margin that leaves a map box at least 1 m wide each way".into(),
                m.to_string(),
            ));
        }
    }
    spec.map.x = bx;
    spec.map.y = by;
    let z = spec.map.z_agl;
    if !(z[0]..=z[1]).contains(&req.agl) {
        spec.map.z_agl = [req.agl * 2.0 / 3.0, req.agl * 4.0 / 3.0];
    }
    spec.threats.clear();
    spec.goal.position = [goal.x, goal.y, req.agl];
    let mut uav = spec.uavs[0];
    uav.start = [start.x, start.y, req.agl];
    uav.battery_wh *= ratio.max(1.0);
    spec.uavs = vec![uav; req.uavs];
    spec.communication.range *= ratio;
    spec.communication.interference.clear();
    spec.communication.ground_nodes.clear();
    // Every UAV starts at one place and lands at UGV0: launch and recover them in turn.
    let interval = crate::generate::slot_interval(spec.uavs.len());
    spec.timing.launch_interval = interval;
    spec.timing.recovery_interval = interval;
    Ok(spec)
}

/// The scenario as TOML with `[geo] origin` appended (unless the spec already writes a
/// `geo` table) and `header` lines as comments on top.
#[must_use]
pub fn scenario_toml_with_origin(spec: &ScenarioSpec, origin: Geodetic, header: &str) -> String {
    let mut text = String::new();
    for line in header.lines() {
        text.push_str("# ");
        text.push_str(line);
        text.push('\n');
    }
    let body = to_toml(spec);
    let has_geo = toml::from_str::<toml::Table>(&body).is_ok_and(|t| t.contains_key("geo"));
    text.push_str(&body);
    if !has_geo {
        if !text.ends_with('\n') {
            text.push('\n');
        }
        text.push_str(&format!(
            "\n[geo]\n# WGS 84 latitude and longitude (degrees) of local (0, 0), and the \
             altitude (m above mean sea level) of local height 0.\norigin = [{:?}, {:?}, {:?}]\n",
            origin.lat_deg, origin.lon_deg, origin.alt_m
        ));
    }
    text
}
