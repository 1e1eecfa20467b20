//! Two CSV tables for the fleet, each with a comment line naming the scenario, frame and
//! altitude reference, then a header. Readers that do not skip `#` lines can drop it.
//! - `mission.csv`, one row per waypoint (re-importable, [`crate::import`]):
//!   `uav,waypoint,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,speed_mps,acceptance_m,pace,delay`
//!   (`pace` the fleet's, the same on every row, and `delay` the UAV's departure delay as a
//!   share of its arrival time, the same on each of its rows, so that a re-import is timed
//!   as planned; the first waypoint's `time_s` is when the UAV leaves it);
//! - `trajectory.csv`, the flown path time-stamped, one row per vertex of the densified
//!   arcs: `uav,index,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,on_arc`.

use super::{num, Mission};

/// The header row.
pub(crate) const COLUMNS: &str =
    "uav,waypoint,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,speed_mps,acceptance_m,pace,delay";

/// The header row of the trajectory.
pub(crate) const TRAJECTORY_COLUMNS: &str =
    "uav,index,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,on_arc";

/// The CSV text of a mission.
pub(crate) fn csv(m: &Mission) -> String {
    let mut s = format!("# {}\n{COLUMNS}\n", m.header());
    for p in &m.paths {
        for (k, pt) in p.points.iter().enumerate() {
            s.push_str(&format!(
                "{},{k},{},{},{},{},{},{},{},{},{}\n",
                p.uav,
                num(pt.time_s),
                num(pt.geo.lat_deg),
                num(pt.geo.lon_deg),
                num(pt.geo.alt_m),
                num(pt.alt_agl_m),
                num(p.speed_mps),
                num(pt.acceptance_m),
                num(m.pace),
                num(p.delay)
            ));
        }
    }
    s
}

/// The CSV text of the flown, time-stamped trajectory.
pub(crate) fn trajectory_csv(m: &Mission) -> String {
    let mut s = format!(
        "# {}; flown path (arcs as chords within {} m)\n{TRAJECTORY_COLUMNS}\n",
        m.header(),
        swarmplan_core::flight::SAGITTA_M
    );
    for p in &m.paths {
        for (k, pt) in p.flown.iter().enumerate() {
            s.push_str(&format!(
                "{},{k},{},{},{},{},{},{}\n",
                p.uav,
                num(pt.time_s),
                num(pt.geo.lat_deg),
                num(pt.geo.lon_deg),
                num(pt.geo.alt_m),
                num(pt.alt_agl_m),
                u8::from(pt.on_arc)
            ));
        }
    }
    s
}
