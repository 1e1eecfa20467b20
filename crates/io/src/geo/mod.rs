//! Georeferencing: where the local frame (x east, y north, metres; heights in metres above
//! mean sea level) lies on the Earth, and the conversions both ways.
//!
//! A plan's local coordinates reach WGS 84 through a [`LocalFrame`], which comes from one of
//! (in this order of precedence, see [`resolve_frame`]):
//! 1. an explicit origin (`--origin LAT,LON[,ALT]`), giving a tangent-plane frame;
//! 2. the scenario's DEM, when it is read in the `georeferenced` frame and names a supported
//!    CRS (WGS 84 / UTM, GDA94 and GDA2020 / MGA, ETRS89 and NAD83 / UTM, or one of their
//!    geographic CRSs): local (x, y) then maps through the DEM's own grid, so the terrain
//!    under a waypoint is exactly the terrain the planner saw;
//! 3. the scenario's `[geo] origin = [lat, lon, alt]`, giving a tangent-plane frame.
//!
//! The tangent-plane frame ([`TangentPlane`]) is exact, not flat-earth: local (x, y) are the
//! east and north coordinates, in the plane tangent to the WGS 84 ellipsoid at the origin,
//! of the point where the ellipsoid normal through the position meets that plane; heights
//! are kept as altitudes (terrain heights are metres above sea level), so a waypoint's
//! altitude is the same number in both frames. Geodetic <-> ECEF <-> ENU conversions are
//! closed form one way and Bowring's iteration to convergence the other
//! ([`ellipsoid`]); tests check them against independent values to 1 mm.
//!
//! `alt` of an origin is the altitude (m above mean sea level) of local height 0: 0 when the
//! terrain heights are already metres above sea level, as DEM files are.
//!
//! Datums: GDA94, GDA2020, ETRS89 and NAD83 coordinates are taken as WGS 84 (they differ
//! by 0.1 to 2 m, below a DEM cell); no geoid model is applied, so altitudes AMSL are used
//! as ellipsoidal heights in the ECEF step, which moves latitudes and longitudes by less
//! than 2 cm per kilometre from the origin (an undulation of 100 m at most).

pub mod ellipsoid;
pub mod frame;
mod new_scenario;
mod projected;
mod scenario;

use thiserror::Error;

pub use ellipsoid::{ecef_to_geodetic, geodetic_to_ecef, Ellipsoid, EnuFrame, Geodetic};
pub use frame::{check_tangent_origin, FrameKind, LocalFrame, TangentPlane};
pub use new_scenario::{new_scenario, scenario_toml_with_origin, NewScenario, NewScenarioRequest};
pub use projected::{Datum, GeographicCrs, UtmZone};
pub use scenario::{
    dem_frame_of_spec, load_spec_with_origin, resolve_frame, scenario_origin, FrameSource,
};

/// Why a georeferencing step failed. Messages name the input (flag, file or field) and what
/// was expected.
#[derive(Debug, Error)]
pub enum GeoError {
    /// A latitude is not finite or outside [-90, 90] degrees.
    #[error("{what}: latitude must be a number in [-90, 90] degrees, got {value}")]
    Latitude {
        /// The input (flag, file or field).
        what: String,
        /// The latitude given, degrees.
        value: f64,
    },
    /// A longitude is not finite or outside [-180, 180] degrees.
    #[error("{what}: longitude must be a number in [-180, 180] degrees, got {value}")]
    Longitude {
        /// The input (flag, file or field).
        what: String,
        /// The longitude given, degrees.
        value: f64,
    },
    /// An altitude is not finite or outside [`MIN_ALTITUDE_M`, `MAX_ALTITUDE_M`].
    #[error("{what}: altitude must be a number of metres in [{}, {}] (Earth's surface and the airspace above it), got {value}", MIN_ALTITUDE_M, MAX_ALTITUDE_M)]
    Altitude {
        /// The input (flag, file or field).
        what: String,
        /// The altitude given, metres.
        value: f64,
    },
    /// A tangent-plane origin lies within 0.001 degrees of a pole.
    #[error("{what}: a tangent-plane origin needs a latitude within 89.999 degrees of the equator (east and north are undefined at a pole, and ill-conditioned next to it), got {value}")]
    Pole {
        /// The input (flag, file or field).
        what: String,
        /// The latitude given, degrees.
        value: f64,
    },
    /// A value (e.g. a `LAT,LON` flag) is not written as expected.
    #[error("{what}: expected {expected}, got `{got}`")]
    Syntax {
        /// The input (flag, file or field).
        what: String,
        /// What was expected.
        expected: String,
        /// The text given.
        got: String,
    },
    /// A UTM / MGA projection could not be set up, or a point is outside its zone.
    #[error("{crs}: {message}")]
    Projection {
        /// Name of the projected CRS.
        crs: String,
        /// What failed, with the point.
        message: String,
    },
    /// A point is more than 60 degrees of arc from a tangent plane's origin.
    #[error(
        "point at latitude {lat}, longitude {lon} is too far from the tangent plane at \
         ({lat0}, {lon0}) to map into the local frame (more than 60 degrees of arc)"
    )]
    TooFar {
        /// Latitude of the point, degrees.
        lat: f64,
        /// Longitude of the point, degrees.
        lon: f64,
        /// Latitude of the plane's origin, degrees.
        lat0: f64,
        /// Longitude of the plane's origin, degrees.
        lon0: f64,
    },
    /// A DEM's georeferencing cannot give a frame (wrong DEM frame, no georeferencing, or an
    /// unsupported CRS or unit).
    #[error("{path}: {message}")]
    Dem {
        /// The DEM file.
        path: String,
        /// Why it gives no frame.
        message: String,
    },
    /// A scenario's `[geo]` table is invalid (not raised in this crate: the scenario spec
    /// validates that table itself).
    #[error("{origin}: geo: {message}")]
    Spec {
        /// The scenario's name or file.
        origin: String,
        /// What is wrong.
        message: String,
    },
    /// A scenario has neither a usable DEM frame nor a `[geo] origin`, and no origin was given.
    #[error(
        "scenario `{scenario}` has no geodetic origin{why}; give one with `[geo] origin = \
         [lat, lon, alt]` in the scenario file, a terrain GeoTIFF with a supported CRS \
         (WGS 84 / UTM, GDA94 or GDA2020 / MGA) in the `georeferenced` frame, or \
         `--origin LAT,LON[,ALT]`"
    )]
    NoOrigin {
        /// The scenario's name.
        scenario: String,
        /// Why its DEM gave no frame, as ` (reason)`.
        why: String,
    },
    /// The scenario could not be loaded.
    #[error(transparent)]
    Scenario(#[from] crate::scenario::ScenarioError),
    /// A DEM file could not be read.
    #[error(transparent)]
    Read(#[from] crate::dem::DemError),
}

/// Lowest altitude accepted, metres above sea level (the Dead Sea shore is at -430 m).
pub const MIN_ALTITUDE_M: f64 = -1_000.0;
/// Highest altitude accepted, metres above sea level (small UAVs fly far below).
pub const MAX_ALTITUDE_M: f64 = 20_000.0;

/// Checks that latitude, longitude and altitude are in range; `what` names the input.
pub fn check_geodetic(g: Geodetic, what: &str) -> Result<Geodetic, GeoError> {
    if !(g.lat_deg.is_finite() && (-90.0..=90.0).contains(&g.lat_deg)) {
        return Err(GeoError::Latitude {
            what: what.into(),
            value: g.lat_deg,
        });
    }
    if !(g.lon_deg.is_finite() && (-180.0..=180.0).contains(&g.lon_deg)) {
        return Err(GeoError::Longitude {
            what: what.into(),
            value: g.lon_deg,
        });
    }
    if !(g.alt_m.is_finite() && (MIN_ALTITUDE_M..=MAX_ALTITUDE_M).contains(&g.alt_m)) {
        return Err(GeoError::Altitude {
            what: what.into(),
            value: g.alt_m,
        });
    }
    Ok(g)
}

/// Parses `LAT,LON` or `LAT,LON,ALT` (degrees, degrees, metres; ALT defaults to 0), e.g. a
/// command-line value; `what` (e.g. `--start`) names it in errors.
pub fn parse_lat_lon_alt(text: &str, what: &str) -> Result<Geodetic, GeoError> {
    let syntax = || GeoError::Syntax {
        what: what.into(),
        expected: "LAT,LON or LAT,LON,ALT in degrees and metres (e.g. -10.45,105.62)".into(),
        got: text.into(),
    };
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    if !(2..=3).contains(&parts.len()) {
        return Err(syntax());
    }
    let mut v = [0.0; 3];
    for (slot, p) in v.iter_mut().zip(&parts) {
        *slot = p.parse::<f64>().map_err(|_| syntax())?;
    }
    check_geodetic(Geodetic::new(v[0], v[1], v[2]), what)
}

/// Parses `LAT,LON` (no altitude allowed), e.g. `--start` of `scenario new`.
pub fn parse_lat_lon(text: &str, what: &str) -> Result<Geodetic, GeoError> {
    if text.split(',').count() != 2 {
        return Err(GeoError::Syntax {
            what: what.into(),
            expected: "LAT,LON in degrees (e.g. -10.45,105.62)".into(),
            got: text.into(),
        });
    }
    parse_lat_lon_alt(text, what)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lat_lon_flags_parse_and_name_the_flag_on_errors() {
        let g = parse_lat_lon_alt("-10.5, 105.6,12", "--origin").unwrap();
        assert_eq!(g, Geodetic::new(-10.5, 105.6, 12.0));
        assert_eq!(parse_lat_lon("1,2", "--start").unwrap().alt_m, 0.0);
        let e = parse_lat_lon("95,10", "--start").unwrap_err().to_string();
        assert!(
            e.starts_with("--start: latitude") && e.contains("95"),
            "{e}"
        );
        let e = parse_lat_lon("10,-181", "--goal").unwrap_err().to_string();
        assert!(e.contains("--goal: longitude") && e.contains("-181"), "{e}");
        let e = parse_lat_lon("10,20,30", "--goal").unwrap_err().to_string();
        assert!(e.contains("LAT,LON") && e.contains("10,20,30"), "{e}");
        let e = parse_lat_lon_alt("ten,20", "--origin")
            .unwrap_err()
            .to_string();
        assert!(e.contains("--origin") && e.contains("ten,20"), "{e}");
        assert!(parse_lat_lon_alt("1,2,nan", "--origin").is_err());
    }
}
