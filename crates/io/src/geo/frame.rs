//! [`LocalFrame`]: the map between plan coordinates (x east, y north, metres; z a height in
//! metres above the local datum) and WGS 84 (latitude, longitude, altitude above mean sea
//! level). Three kinds: a tangent plane at a geodetic origin, the grid of a projected DEM
//! (UTM / MGA), and the grid of a geographic DEM.

use glam::DVec3;

use super::ellipsoid::{geodetic_to_ecef, EnuFrame, Geodetic};
use super::projected::{GeographicCrs, UtmZone};
use super::{check_geodetic, GeoError};
use crate::dem::{Crs, DemFrame, LoadedDem};

/// The plane tangent to the WGS 84 ellipsoid at an origin, with exact conversions.
///
/// A position (lat, lon) maps to the east and north coordinates of the point where the
/// ellipsoid normal through it meets the plane (so the map does not depend on the
/// position's altitude, and a terrain height field over the plane is a height field over
/// the Earth). The inverse follows the normal back: the plane point's geodetic latitude
/// and longitude. Both directions are exact up to rounding (about 1e-9 m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentPlane {
    enu: EnuFrame,
}

impl TangentPlane {
    /// The plane tangent at `origin` (its altitude is the plane's height above the
    /// ellipsoid).
    #[must_use]
    pub fn new(origin: Geodetic) -> Self {
        Self {
            enu: EnuFrame::new(origin),
        }
    }

    /// The geodetic origin the plane is tangent at.
    #[must_use]
    pub fn origin(&self) -> Geodetic {
        self.enu.origin()
    }

    /// The ENU axes at the origin.
    #[must_use]
    pub fn enu(&self) -> &EnuFrame {
        &self.enu
    }

    /// Latitude and longitude (degrees) of plane coordinates (east, north), metres.
    #[must_use]
    pub fn to_lat_lon(&self, east: f64, north: f64) -> (f64, f64) {
        let g = self.enu.enu_to_geodetic(DVec3::new(east, north, 0.0));
        (g.lat_deg, g.lon_deg)
    }

    /// Plane coordinates (east, north), metres, of a latitude and longitude (degrees).
    pub fn from_lat_lon(&self, lat: f64, lon: f64) -> Result<(f64, f64), GeoError> {
        let foot = geodetic_to_ecef(Geodetic::new(lat, lon, 0.0));
        let normal = Geodetic::new(lat, lon, 0.0).up();
        let [east, north, up] = self.enu.axes();
        let cos = up.dot(normal);
        if cos < 0.5 {
            let o = self.origin();
            return Err(GeoError::TooFar {
                lat,
                lon,
                lat0: o.lat_deg,
                lon0: o.lon_deg,
            });
        }
        // foot + t normal lies in the plane: up . (foot + t normal - origin) = 0.
        let d0 = foot - self.enu.origin_ecef();
        let t = -up.dot(d0) / cos;
        let d = d0 + t * normal;
        Ok((east.dot(d), north.dot(d)))
    }
}

/// What a [`LocalFrame`] maps through.
#[derive(Debug, Clone, PartialEq)]
pub enum FrameKind {
    /// A tangent plane at a geodetic origin (local (0, 0) is the origin).
    Tangent(TangentPlane),
    /// A projected DEM's grid: easting = e0 + x, northing = n0 + y (metres), where
    /// (e0, n0) is the DEM's south-west node.
    Projected {
        /// The DEM's UTM / MGA zone.
        zone: UtmZone,
        /// (e0, n0): easting and northing of the DEM's south-west node, metres.
        south_west: (f64, f64),
    },
    /// A geographic DEM's grid: longitude = lon0 + x / mx, latitude = lat0 + y / my, with
    /// (lon0, lat0) its south-west node and (mx, my) the metres per degree the DEM reader
    /// used (WGS 84 at the raster's centre latitude).
    Geographic {
        /// The DEM's geographic CRS.
        crs: GeographicCrs,
        /// (lon0, lat0): longitude and latitude of the DEM's south-west node, degrees.
        south_west: (f64, f64),
        /// (mx, my): metres per degree of longitude and of latitude.
        metres_per_degree: (f64, f64),
    },
}

/// `lon` (degrees) brought into [-180, 180): a geographic raster that crosses the
/// antimeridian runs on past 180 in its own grid, but a longitude written for an autopilot
/// or GIS does not.
fn wrap_longitude(lon: f64) -> f64 {
    if (-180.0..180.0).contains(&lon) {
        lon
    } else {
        (lon + 180.0).rem_euclid(360.0) - 180.0
    }
}

/// Plan coordinates <-> WGS 84. Altitude AMSL = local height + `altitude_offset`.
#[derive(Debug, Clone, PartialEq)]
pub struct LocalFrame {
    kind: FrameKind,
    altitude_offset: f64,
}

/// `origin` if a tangent frame can be made at it (a valid place, off the poles); `what`
/// names it in the error (`origin`, or `geo.origin` for a scenario's).
pub fn check_tangent_origin(origin: Geodetic, what: &str) -> Result<Geodetic, GeoError> {
    let origin = check_geodetic(origin, what)?;
    if origin.lat_deg.abs() > 89.999 {
        return Err(GeoError::Pole {
            what: what.into(),
            value: origin.lat_deg,
        });
    }
    Ok(origin)
}

impl LocalFrame {
    /// A tangent-plane frame at `origin`; `origin.alt_m` is the altitude AMSL of local
    /// height 0 (0 when terrain heights are metres above sea level).
    pub fn tangent(origin: Geodetic) -> Result<Self, GeoError> {
        let origin = check_tangent_origin(origin, "origin")?;
        Ok(Self {
            kind: FrameKind::Tangent(TangentPlane::new(origin)),
            altitude_offset: origin.alt_m,
        })
    }

    /// The frame of a DEM read in the `georeferenced` frame with a supported CRS; local
    /// heights are the DEM's, taken as metres above sea level (offset 0).
    pub fn from_dem(dem: &LoadedDem) -> Result<Self, GeoError> {
        let path = dem.path.display().to_string();
        let fail = |message: String| GeoError::Dem {
            path: path.clone(),
            message,
        };
        if dem.options.frame != DemFrame::Georeferenced {
            return Err(fail(
                "read in the `spso-pixels` frame (1 unit per pixel), which is not \
                 georeferenced; use `frame = \"georeferenced\"` or a `[geo] origin`"
                    .into(),
            ));
        }
        let g = dem.georef.as_ref().ok_or_else(|| {
            fail("the file has no georeferencing (no GeoTIFF tie point or transform)".into())
        })?;
        let kind = match g.crs {
            Crs::Projected(code) => {
                let zone = UtmZone::from_epsg(code).ok_or_else(|| {
                    fail(format!(
                        "projected CRS EPSG {code} is not supported (supported: UTM and MGA \
                         zones on WGS 84, GDA94, GDA2020, ETRS89, NAD83)"
                    ))
                })?;
                if (g.metres_per_unit - 1.0).abs() > 1e-12 {
                    return Err(fail(format!(
                        "{}: linear unit is {} m, expected metres",
                        zone.name(),
                        g.metres_per_unit
                    )));
                }
                FrameKind::Projected {
                    zone,
                    south_west: g.south_west_node,
                }
            }
            Crs::Geographic(code) => {
                let crs = GeographicCrs::from_epsg(code).ok_or_else(|| {
                    fail(format!(
                        "geographic CRS EPSG {code} is not supported (supported: 4326, \
                         4283, 7844, 4258, 4269)"
                    ))
                })?;
                // A tie point or cell size that puts the raster past a pole is no place on
                // Earth (latitude 95 was read as one, and exported as 94.999).
                let (_, _, _, north) = dem.terrain.extent();
                let lat_north = g.south_west_node.1 + north * g.cell.1 / dem.cell_metres.1;
                for lat in [g.south_west_node.1, lat_north] {
                    if !(lat.is_finite() && (-90.0..=90.0).contains(&lat)) {
                        return Err(fail(format!(
                            "{}: the raster reaches latitude {lat}, beyond the poles",
                            crs.name()
                        )));
                    }
                }
                FrameKind::Geographic {
                    crs,
                    south_west: g.south_west_node,
                    metres_per_degree: (dem.cell_metres.0 / g.cell.0, dem.cell_metres.1 / g.cell.1),
                }
            }
            Crs::Unknown { .. } => {
                return Err(fail(
                    "the file names no EPSG code (an ESRI ASCII grid, or a user-defined CRS)"
                        .into(),
                ))
            }
        };
        Ok(Self {
            kind,
            altitude_offset: 0.0,
        })
    }

    /// What the frame maps through.
    #[must_use]
    pub fn kind(&self) -> &FrameKind {
        &self.kind
    }

    /// Altitude AMSL of local height 0.
    #[must_use]
    pub fn altitude_offset(&self) -> f64 {
        self.altitude_offset
    }

    /// Geodetic position of local (x, y, z): latitude, longitude, altitude AMSL
    /// (z + offset).
    pub fn to_geodetic(&self, p: DVec3) -> Result<Geodetic, GeoError> {
        let (lat, lon) = match &self.kind {
            FrameKind::Tangent(t) => t.to_lat_lon(p.x, p.y),
            FrameKind::Projected { zone, south_west } => {
                zone.to_lat_lon(south_west.0 + p.x, south_west.1 + p.y)?
            }
            FrameKind::Geographic {
                south_west,
                metres_per_degree,
                ..
            } => (
                south_west.1 + p.y / metres_per_degree.1,
                wrap_longitude(south_west.0 + p.x / metres_per_degree.0),
            ),
        };
        Ok(Geodetic::new(lat, lon, p.z + self.altitude_offset))
    }

    /// Local (x, y, z) of a geodetic position (altitude AMSL).
    pub fn from_geodetic(&self, g: Geodetic) -> Result<DVec3, GeoError> {
        let g = check_geodetic(g, "position")?;
        let (x, y) = match &self.kind {
            FrameKind::Tangent(t) => t.from_lat_lon(g.lat_deg, g.lon_deg)?,
            FrameKind::Projected { zone, south_west } => {
                let (e, n) = zone.from_lat_lon(g.lat_deg, g.lon_deg)?;
                (e - south_west.0, n - south_west.1)
            }
            FrameKind::Geographic {
                south_west,
                metres_per_degree,
                ..
            } => (
                // East of the south-west node by at most half a turn: a raster across the
                // antimeridian holds longitudes on both sides of it.
                wrap_longitude(g.lon_deg - south_west.0) * metres_per_degree.0,
                (g.lat_deg - south_west.1) * metres_per_degree.1,
            ),
        };
        Ok(DVec3::new(x, y, g.alt_m - self.altitude_offset))
    }

    /// Geodetic position of local (0, 0, 0).
    pub fn origin(&self) -> Result<Geodetic, GeoError> {
        self.to_geodetic(DVec3::ZERO)
    }

    /// One line for file headers, e.g. "tangent plane at 51.5 N, 0.1 W; altitude AMSL =
    /// local height + 0 m".
    #[must_use]
    pub fn describe(&self) -> String {
        let what = match &self.kind {
            FrameKind::Tangent(t) => {
                let o = t.origin();
                format!(
                    "local x east / y north on the WGS 84 tangent plane at latitude {}, \
                     longitude {}",
                    o.lat_deg, o.lon_deg
                )
            }
            FrameKind::Projected { zone, south_west } => format!(
                "local x, y = {} grid easting - {}, northing - {} (the DEM's south-west node)",
                zone.name(),
                south_west.0,
                south_west.1
            ),
            FrameKind::Geographic {
                crs, south_west, ..
            } => format!(
                "local x, y = the {} DEM grid from its south-west node (longitude {}, \
                 latitude {})",
                crs.name(),
                south_west.0,
                south_west.1
            ),
        };
        format!(
            "{what}; altitude AMSL = local height + {} m",
            self.altitude_offset
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tangent_plane_round_trips_and_keeps_altitudes() {
        let f = LocalFrame::tangent(Geodetic::new(47.3977, 8.5456, 400.0)).unwrap();
        for p in [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1234.5, -987.25, 150.0),
            DVec3::new(-20_000.0, 35_000.0, 2_000.0),
        ] {
            let g = f.to_geodetic(p).unwrap();
            assert_eq!(g.alt_m, p.z + 400.0);
            let q = f.from_geodetic(g).unwrap();
            assert!((q - p).length() < 1e-6, "{p} -> {q}");
        }
        let o = f.origin().unwrap();
        assert!((o.lat_deg - 47.3977).abs() < 1e-12 && (o.lon_deg - 8.5456).abs() < 1e-12);
    }

    #[test]
    fn far_points_and_poles_are_refused() {
        let f = LocalFrame::tangent(Geodetic::new(0.0, 0.0, 0.0)).unwrap();
        let e = f
            .from_geodetic(Geodetic::new(0.0, 120.0, 0.0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("too far"), "{e}");
        assert!(LocalFrame::tangent(Geodetic::new(90.0, 0.0, 0.0)).is_err());
        assert!(LocalFrame::tangent(Geodetic::new(10.0, 200.0, 0.0)).is_err());
    }
}
