//! One CSV table for the fleet: a comment line with the scenario, frame and altitude
//! reference, a header, then one row per waypoint:
//! `uav,waypoint,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,speed_mps`.
//! Readers that do not skip `#` lines can drop the first line.

use super::{num, Mission};

/// The header row.
pub(crate) const COLUMNS: &str =
    "uav,waypoint,time_s,lat_deg,lon_deg,alt_amsl_m,alt_agl_m,speed_mps";

/// The CSV text of a mission.
pub(crate) fn csv(m: &Mission) -> String {
    let mut s = format!("# {}\n{COLUMNS}\n", m.header());
    for p in &m.paths {
        for (k, pt) in p.points.iter().enumerate() {
            s.push_str(&format!(
                "{},{k},{},{},{},{},{},{}\n",
                p.uav,
                num(pt.time_s),
                num(pt.geo.lat_deg),
                num(pt.geo.lon_deg),
                num(pt.geo.alt_m),
                num(pt.alt_agl_m),
                num(p.speed_mps)
            ));
        }
    }
    s
}
