//! Mission exports: a plan in WGS 84 for autopilots, ground stations and GIS.
//!
//! Formats ([`ExportFormat`]): per UAV a QGroundControl `.plan` and a `QGC WPL 110`
//! `.waypoints` file; for the fleet one GeoJSON FeatureCollection, one KML document and one
//! CSV table. Every file states its altitude reference (`docs/export.md`): altitudes are
//! metres above mean sea level (AMSL) = terrain height + height above ground (AGL), the
//! terrain heights being taken as AMSL (plus the frame's altitude offset, 0 for DEMs).
//!
//! [`Mission`] converts the plan once (times and speeds from the scenario's timing policy,
//! positions through a [`LocalFrame`]); each writer only formats it. Numbers are written
//! in Rust's shortest round-trip form, so a re-import ([`crate::import`]) recovers the
//! exact values that were written.

mod csv;
mod geojson;
mod kml;
mod qgc;

use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;
use swarmplan_core::world::DEPARTURE;

use glam::DVec3;
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;
use thiserror::Error;

use crate::geo::{GeoError, Geodetic, LocalFrame};

/// The sentence every export uses for its altitudes.
pub const ALTITUDE_REFERENCE: &str = "altitudes are metres above mean sea level (AMSL) = \
     terrain height + height above ground (AGL); terrain heights are taken as AMSL";

/// Vertices of the polygon drawn for a threat circle (a closing vertex is added).
pub const CIRCLE_VERTICES: usize = 72;

/// An export format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ExportFormat {
    /// QGroundControl plan (JSON), one per UAV: `uavN.plan`.
    QgcPlan,
    /// `QGC WPL 110` waypoint text, one per UAV: `uavN.waypoints`.
    Wpl,
    /// One GeoJSON FeatureCollection: `mission.geojson`.
    GeoJson,
    /// One KML document: `mission.kml`.
    Kml,
    /// One CSV table with a `uav` column: `mission.csv`.
    Csv,
}

impl ExportFormat {
    /// Every format, in the order `all` writes them.
    pub const ALL: [Self; 5] = [
        Self::QgcPlan,
        Self::Wpl,
        Self::GeoJson,
        Self::Kml,
        Self::Csv,
    ];

    /// The name used on the command line (`qgc-plan`, `wpl`, `geojson`, `kml`, `csv`).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::QgcPlan => "qgc-plan",
            Self::Wpl => "wpl",
            Self::GeoJson => "geojson",
            Self::Kml => "kml",
            Self::Csv => "csv",
        }
    }

    /// A comma-separated list of format names, or `all`.
    pub fn parse_list(text: &str) -> Result<Vec<Self>, ExportError> {
        let mut out = Vec::new();
        for part in text.split(',').map(str::trim) {
            if part.eq_ignore_ascii_case("all") {
                out.extend(Self::ALL);
            } else {
                out.push(part.parse()?);
            }
        }
        let mut seen = Vec::new();
        out.retain(|f| {
            let new = !seen.contains(f);
            seen.push(*f);
            new
        });
        Ok(out)
    }
}

impl fmt::Display for ExportFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for ExportFormat {
    type Err = ExportError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let s = s.trim().to_ascii_lowercase();
        Self::ALL
            .into_iter()
            .find(|f| f.name() == s)
            .or(match s.as_str() {
                "plan" | "qgc" => Some(Self::QgcPlan),
                "waypoints" | "qgc-wpl" => Some(Self::Wpl),
                "json" => Some(Self::GeoJson),
                _ => None,
            })
            .ok_or(ExportError::Format(s))
    }
}

/// Why a mission could not be converted or written.
#[derive(Debug, Error)]
pub enum ExportError {
    /// The output folder or a file in it could not be written.
    #[error("{}: cannot write: {source}", path.display())]
    Write {
        /// The folder or file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A point could not be converted to WGS 84.
    #[error(transparent)]
    Geo(#[from] GeoError),
    /// A format name is not one of the export formats.
    #[error("expected qgc-plan, wpl, geojson, kml, csv or all, got `{0}`")]
    Format(String),
    /// The plan does not fit the scenario: wrong number of paths, fewer than 2 waypoints,
    /// or a waypoint that is not finite.
    #[error("plan: {0}")]
    Plan(String),
}

/// One waypoint of a mission.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MissionPoint {
    /// Plan coordinates [x, y, z above ground].
    pub local: DVec3,
    /// WGS 84 latitude, longitude; `alt_m` is the altitude AMSL.
    pub geo: Geodetic,
    /// Height above ground, metres (the plan's z).
    pub alt_agl_m: f64,
    /// Terrain altitude AMSL below the point, metres.
    pub ground_amsl_m: f64,
    /// When the flown path passes the waypoint, seconds from the fleet's departure (t = 0;
    /// a UAV with a departure delay leaves later): the middle of the arc that flies its
    /// corner; every waypoint of a run of equal ones gets the run's time
    /// ([`swarmplan_core::timing::TimedPath::waypoint_times`]).
    pub time_s: f64,
    /// Distance before the waypoint at which the turn starts, R tan(theta / 2), metres:
    /// the acceptance radius that makes an autopilot turn where the assessed arc does
    /// (0 at the start and the goal, and for plans assessed as straight segments).
    pub acceptance_m: f64,
}

/// One point of the flown path (densified arcs, [`swarmplan_core::flight`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlownPoint {
    /// Plan coordinates [x, y, absolute altitude] in the local frame.
    pub local_abs: DVec3,
    /// WGS 84 latitude, longitude; `alt_m` is the altitude AMSL.
    pub geo: Geodetic,
    /// Height above ground, metres.
    pub alt_agl_m: f64,
    /// When the UAV passes the point, seconds (on the clock of [`MissionPoint::time_s`]).
    pub time_s: f64,
    /// Whether the segment that ends here is a chord of an arc.
    pub on_arc: bool,
}

/// One UAV's path.
#[derive(Debug, Clone, PartialEq)]
pub struct MissionPath {
    /// Index of the UAV in the scenario (N of `uavN.plan`).
    pub uav: usize,
    /// The plan's waypoints, start to goal.
    pub points: Vec<MissionPoint>,
    /// Constant planned speed, m/s.
    pub speed_mps: f64,
    /// Departure delay, a share of the arrival time ([`Plan::delays`]), which the
    /// re-importable formats record.
    pub delay: f64,
    /// When it leaves its start, seconds (it hovers there until then; 0: at once).
    pub depart_s: f64,
    /// 3-D length with absolute altitudes, metres.
    pub length_m: f64,
    /// Drone size (hard zone margin of threats), metres.
    pub size_m: f64,
    /// Turning radius the flown path uses, metres (0: straight segments).
    pub turn_radius_m: f64,
    /// The path as flown and assessed: the waypoint polyline with an arc through every
    /// corner, time-stamped (the waypoints themselves under the paper profile).
    pub flown: Vec<FlownPoint>,
}

/// A threat cylinder in WGS 84.
#[derive(Debug, Clone, PartialEq)]
pub struct MissionThreat {
    /// Index of the threat in the scenario.
    pub index: usize,
    /// Axis in plan coordinates, metres.
    pub x: f64,
    /// Axis y in plan coordinates, metres.
    pub y: f64,
    /// Radius, metres.
    pub r: f64,
    /// Drawn height above ground, metres (threats are unbounded in height).
    pub draw_height_m: f64,
    /// Axis position; `alt_m` is the ground altitude AMSL there.
    pub center: Geodetic,
    /// The circle of radius `r` as a closed ring, counter-clockwise (first = last).
    pub ring: Vec<Geodetic>,
}

/// A plan converted to WGS 84, ready for the writers.
#[derive(Debug, Clone, PartialEq)]
pub struct Mission {
    /// Name of the scenario.
    pub scenario: String,
    /// [`LocalFrame::describe`] of the frame used.
    pub frame: String,
    /// One path per UAV, in the scenario's order.
    pub paths: Vec<MissionPath>,
    /// The scenario's threats, in its order.
    pub threats: Vec<MissionThreat>,
    /// UGV0's position on the ground (altitude = ground AMSL).
    pub goal: Geodetic,
    /// `None` for a feasible plan; else the verdict (`INFEASIBLE: N violations (...)`),
    /// which every format with a description records (QGC, GeoJSON, KML, CSV).
    pub infeasible: Option<String>,
    /// The plan's pace ([`Plan::pace`]), which the re-importable formats (CSV, GeoJSON)
    /// record so that a re-imported plan is timed as the original.
    pub pace: f64,
}

impl Mission {
    /// Converts `plan` (checked against `world`: one path per UAV, >= 2 finite waypoints).
    pub fn new(world: &World, plan: &Plan, frame: &LocalFrame) -> Result<Self, ExportError> {
        let n = world.uav_count();
        if plan.uavs.len() != n {
            return Err(ExportError::Plan(format!(
                "scenario `{}` has {n} UAVs, the plan has {}",
                world.spec().name,
                plan.uavs.len()
            )));
        }
        for (i, p) in plan.uavs.iter().enumerate() {
            if p.waypoints.len() < 2 {
                return Err(ExportError::Plan(format!(
                    "uavs[{i}]: expected at least 2 waypoints, got {}",
                    p.waypoints.len()
                )));
            }
            if let Some(k) = p.waypoints.iter().position(|w| !w.is_finite()) {
                return Err(ExportError::Plan(format!(
                    "uavs[{i}].waypoints[{k}]: not finite: {}",
                    p.waypoints[k]
                )));
            }
        }
        let offset = frame.altitude_offset();
        let ground = |x: f64, y: f64| world.terrain().height(x, y) + offset;
        let timed = TimedPlan::new(world, plan);
        let arcs = world.flies_arcs();
        let flown = TimedPlan::flown(world, plan);
        let mut paths = Vec::with_capacity(n);
        for (i, (p, (tp, fp))) in plan
            .uavs
            .iter()
            .zip(timed.paths.iter().zip(&flown.paths))
            .enumerate()
        {
            let times = fp.waypoint_times(&tp.abs);
            let points = p
                .waypoints
                .iter()
                .enumerate()
                .map(|(k, w)| {
                    Ok(MissionPoint {
                        local: *w,
                        geo: frame.to_geodetic(tp.abs[k])?,
                        alt_agl_m: w.z,
                        ground_amsl_m: ground(w.x, w.y),
                        time_s: times[k],
                        acceptance_m: fp.tangents.get(k).copied().unwrap_or(0.0),
                    })
                })
                .collect::<Result<Vec<_>, GeoError>>()?;
            let flown_points = fp
                .abs
                .iter()
                .enumerate()
                .map(|(k, a)| {
                    Ok(FlownPoint {
                        local_abs: *a,
                        geo: frame.to_geodetic(*a)?,
                        alt_agl_m: a.z - world.terrain().height(a.x, a.y),
                        time_s: fp.time_at(k),
                        on_arc: k > 0 && fp.flown.get(k - 1).is_some_and(|f| f.arc),
                    })
                })
                .collect::<Result<Vec<_>, GeoError>>()?;
            paths.push(MissionPath {
                uav: i,
                points,
                speed_mps: fp.speed,
                delay: fp.delay,
                depart_s: fp.depart,
                length_m: fp.length,
                size_m: world.spec().uavs[i].size,
                turn_radius_m: if arcs {
                    world.spec().uavs[i].turn_radius
                } else {
                    0.0
                },
                flown: flown_points,
            });
        }
        let mut threats = Vec::with_capacity(world.spec().threats.len());
        for (index, t) in world.spec().threats.iter().enumerate() {
            let h = world.terrain().height(t.x, t.y);
            let ring = (0..=CIRCLE_VERTICES)
                .map(|k| {
                    // The last vertex repeats the first exactly (a closed ring).
                    let a = std::f64::consts::TAU * (k % CIRCLE_VERTICES) as f64
                        / CIRCLE_VERTICES as f64;
                    frame.to_geodetic(DVec3::new(t.x + t.r * a.cos(), t.y + t.r * a.sin(), h))
                })
                .collect::<Result<Vec<_>, _>>()?;
            threats.push(MissionThreat {
                index,
                x: t.x,
                y: t.y,
                r: t.r,
                draw_height_m: t.z,
                center: frame.to_geodetic(DVec3::new(t.x, t.y, h))?,
                ring,
            });
        }
        let g = world.goal_at(DEPARTURE);
        Ok(Self {
            scenario: world.spec().name.clone(),
            frame: frame.describe(),
            paths,
            threats,
            goal: frame.to_geodetic(DVec3::new(g.x, g.y, world.terrain().height(g.x, g.y)))?,
            infeasible: {
                let a = swarmplan_core::cost::assess(world, plan);
                (!a.feasible()).then(|| a.verdict())
            },
            pace: plan.pace,
        })
    }

    /// One line naming the scenario, the frame and the altitude reference, for headers
    /// (no line breaks, whatever the scenario's name holds).
    #[must_use]
    pub fn header(&self) -> String {
        let name: String = self
            .scenario
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect();
        let verdict = self
            .infeasible
            .as_ref()
            .map_or(String::new(), |v| format!("; WARNING, the plan is {v}"));
        format!(
            "swarmplan mission, scenario `{name}`; WGS 84 latitude and longitude in degrees; \
             {ALTITUDE_REFERENCE}; frame: {}{verdict}",
            self.frame
        )
    }
}

/// Converts `plan` and writes `format` into `out_dir` (created if missing); returns the
/// files written.
pub fn export_plan(
    world: &World,
    plan: &Plan,
    frame: &LocalFrame,
    format: ExportFormat,
    out_dir: &Path,
) -> Result<Vec<PathBuf>, ExportError> {
    let mission = Mission::new(world, plan, frame)?;
    write_mission(&mission, format, out_dir)
}

/// Whether `name` is one of the file names [`write_mission`] writes, so that a folder's
/// old exports can be told from a user's own files when a plan is replaced.
#[must_use]
pub fn is_mission_file(name: &str) -> bool {
    let numbered = |ext: &str| {
        name.strip_prefix("uav")
            .and_then(|rest| rest.strip_suffix(ext))
            .is_some_and(|digits| !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()))
    };
    matches!(
        name,
        "mission.geojson" | "mission.kml" | "mission.csv" | "trajectory.csv"
    ) || numbered(".plan")
        || numbered(".waypoints")
}

/// Writes one format of an already converted mission into `out_dir`.
pub fn write_mission(
    mission: &Mission,
    format: ExportFormat,
    out_dir: &Path,
) -> Result<Vec<PathBuf>, ExportError> {
    std::fs::create_dir_all(out_dir).map_err(|source| ExportError::Write {
        path: out_dir.to_path_buf(),
        source,
    })?;
    let files: Vec<(String, String)> = match format {
        ExportFormat::QgcPlan => mission
            .paths
            .iter()
            .map(|p| (format!("uav{}.plan", p.uav), qgc::plan_json(mission, p)))
            .collect(),
        ExportFormat::Wpl => mission
            .paths
            .iter()
            .map(|p| (format!("uav{}.waypoints", p.uav), qgc::wpl(p)))
            .collect(),
        ExportFormat::GeoJson => vec![("mission.geojson".into(), geojson::geojson(mission))],
        ExportFormat::Kml => vec![("mission.kml".into(), kml::kml(mission))],
        ExportFormat::Csv => vec![
            ("mission.csv".into(), csv::csv(mission)),
            ("trajectory.csv".into(), csv::trajectory_csv(mission)),
        ],
    };
    let mut written = Vec::with_capacity(files.len());
    for (name, text) in files {
        let path = out_dir.join(name);
        crate::atomic::write_atomic(&path, text.as_bytes()).map_err(|source| {
            ExportError::Write {
                path: path.clone(),
                source,
            }
        })?;
        written.push(path);
    }
    Ok(written)
}

/// Shortest round-trip decimal text of a number (never exponent notation).
pub(crate) fn num(v: f64) -> String {
    if v == 0.0 {
        "0".into() // also for -0.0
    } else {
        format!("{v}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn format_lists_parse() {
        assert_eq!(
            ExportFormat::parse_list("all").unwrap(),
            ExportFormat::ALL.to_vec()
        );
        assert_eq!(
            ExportFormat::parse_list("csv, KML,csv").unwrap(),
            vec![ExportFormat::Csv, ExportFormat::Kml]
        );
        let e = ExportFormat::parse_list("csv,shp").unwrap_err().to_string();
        assert!(e.contains("expected qgc-plan") && e.contains("shp"), "{e}");
        for f in ExportFormat::ALL {
            assert_eq!(f.name().parse::<ExportFormat>().unwrap(), f);
        }
    }

    #[test]
    fn numbers_round_trip_without_exponents() {
        for v in [1e-7, -10.123_456_789_012_345, 105.6, 1e21, 0.1 + 0.2] {
            let s = num(v);
            assert!(!s.contains('e'), "{s}");
            assert_eq!(s.parse::<f64>().unwrap(), v);
        }
        assert_eq!(num(-0.0), "0");
    }
}
