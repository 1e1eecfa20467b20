//! The CRSs a DEM may name, by EPSG code: UTM / MGA zones (projected) and the geographic
//! CRSs of the same datums. The transverse Mercator math is `proj4rs` (a pure-Rust port of
//! PROJ.4's `utm`, i.e. the Poder / Engsager extended transverse Mercator, accurate to
//! millimetres across a zone); this module only maps EPSG codes to zone, hemisphere and
//! ellipsoid, and degrees to the radians proj4rs works in.
//!
//! Supported: WGS 84 / UTM (EPSG 32601-32660 north, 32701-32760 south), GDA94 / MGA
//! (28348-28358), GDA2020 / MGA (7846-7859), ETRS89 / UTM (25828-25838), NAD83 / UTM
//! (26901-26923); geographic 4326 (WGS 84), 4283 (GDA94), 7844 (GDA2020), 4258 (ETRS89),
//! 4269 (NAD83). Non-WGS 84 datums are taken as WGS 84 (see the module docs of `geo`).

use proj4rs::proj::Proj;

use super::ellipsoid::Ellipsoid;
use super::GeoError;

/// The datum of a supported CRS.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Datum {
    /// World Geodetic System 1984.
    Wgs84,
    /// Geocentric Datum of Australia 1994 (GRS 80).
    Gda94,
    /// Geocentric Datum of Australia 2020 (GRS 80).
    Gda2020,
    /// European Terrestrial Reference System 1989 (GRS 80).
    Etrs89,
    /// North American Datum 1983 (GRS 80).
    Nad83,
}

impl Datum {
    /// E.g. "WGS 84", "GDA94".
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Wgs84 => "WGS 84",
            Self::Gda94 => "GDA94",
            Self::Gda2020 => "GDA2020",
            Self::Etrs89 => "ETRS89",
            Self::Nad83 => "NAD83",
        }
    }

    /// The datum's ellipsoid: WGS 84, or GRS 80 for the others.
    #[must_use]
    pub fn ellipsoid(self) -> Ellipsoid {
        match self {
            Self::Wgs84 => Ellipsoid::WGS84,
            _ => Ellipsoid::GRS80,
        }
    }

    fn proj_ellps(self) -> &'static str {
        match self {
            Self::Wgs84 => "WGS84",
            _ => "GRS80",
        }
    }
}

/// A UTM (or MGA, which is UTM on GDA) zone.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct UtmZone {
    /// The EPSG code it was made from.
    pub epsg: u16,
    /// Zone number, 1 to 60.
    pub zone: u8,
    /// Southern hemisphere (false northing 10 000 km).
    pub south: bool,
    /// Datum of the zone.
    pub datum: Datum,
}

impl UtmZone {
    /// The zone of a supported projected EPSG code, or None.
    #[must_use]
    pub fn from_epsg(code: u16) -> Option<Self> {
        let z = |base: u16| u8::try_from(code - base).ok();
        let (zone, south, datum) = match code {
            32601..=32660 => (z(32600)?, false, Datum::Wgs84),
            32701..=32760 => (z(32700)?, true, Datum::Wgs84),
            28348..=28358 => (z(28300)?, true, Datum::Gda94),
            7846..=7859 => (z(7800)?, true, Datum::Gda2020),
            25828..=25838 => (z(25800)?, false, Datum::Etrs89),
            26901..=26923 => (z(26900)?, false, Datum::Nad83),
            _ => return None,
        };
        Some(Self {
            epsg: code,
            zone,
            south,
            datum,
        })
    }

    /// E.g. "GDA94 / MGA zone 48 (EPSG 28348)".
    #[must_use]
    pub fn name(&self) -> String {
        let system = match self.datum {
            Datum::Gda94 | Datum::Gda2020 => format!("MGA zone {}", self.zone),
            _ => format!(
                "UTM zone {}{}",
                self.zone,
                if self.south { "S" } else { "N" }
            ),
        };
        format!("{} / {system} (EPSG {})", self.datum.name(), self.epsg)
    }

    fn projs(&self) -> Result<(Proj, Proj), GeoError> {
        let ellps = self.datum.proj_ellps();
        let utm = format!(
            "+proj=utm +zone={}{} +ellps={ellps} +units=m",
            self.zone,
            if self.south { " +south" } else { "" }
        );
        let geo = format!("+proj=latlong +ellps={ellps}");
        let make = |s: &str| {
            Proj::from_proj_string(s).map_err(|e| GeoError::Projection {
                crs: self.name(),
                message: format!("cannot set up `{s}`: {e}"),
            })
        };
        Ok((make(&utm)?, make(&geo)?))
    }

    /// Latitude and longitude (degrees) of grid coordinates (easting, northing) in metres.
    pub fn to_lat_lon(&self, easting: f64, northing: f64) -> Result<(f64, f64), GeoError> {
        let (utm, geo) = self.projs()?;
        let mut p = (easting, northing, 0.0);
        proj4rs::transform::transform(&utm, &geo, &mut p).map_err(|e| GeoError::Projection {
            crs: self.name(),
            message: format!("easting {easting}, northing {northing}: {e}"),
        })?;
        let (lat, lon) = (p.1.to_degrees(), p.0.to_degrees());
        if !(lat.is_finite() && lon.is_finite()) {
            return Err(GeoError::Projection {
                crs: self.name(),
                message: format!("easting {easting}, northing {northing} is outside the zone"),
            });
        }
        Ok((lat, lon))
    }

    /// Grid coordinates (easting, northing) in metres of a latitude and longitude (degrees).
    pub fn from_lat_lon(&self, lat: f64, lon: f64) -> Result<(f64, f64), GeoError> {
        let (utm, geo) = self.projs()?;
        let mut p = (lon.to_radians(), lat.to_radians(), 0.0);
        proj4rs::transform::transform(&geo, &utm, &mut p).map_err(|e| GeoError::Projection {
            crs: self.name(),
            message: format!("latitude {lat}, longitude {lon}: {e}"),
        })?;
        if !(p.0.is_finite() && p.1.is_finite()) {
            return Err(GeoError::Projection {
                crs: self.name(),
                message: format!("latitude {lat}, longitude {lon} is outside the zone"),
            });
        }
        Ok((p.0, p.1))
    }
}

/// A supported geographic CRS (longitude, latitude in degrees).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GeographicCrs {
    /// The EPSG code it was made from.
    pub epsg: u16,
    /// Its datum.
    pub datum: Datum,
}

impl GeographicCrs {
    /// The CRS of a supported geographic EPSG code, or None.
    #[must_use]
    pub fn from_epsg(code: u16) -> Option<Self> {
        let datum = match code {
            4326 => Datum::Wgs84,
            4283 => Datum::Gda94,
            7844 => Datum::Gda2020,
            4258 => Datum::Etrs89,
            4269 => Datum::Nad83,
            _ => return None,
        };
        Some(Self { epsg: code, datum })
    }

    /// E.g. "WGS 84 geographic (EPSG 4326)".
    #[must_use]
    pub fn name(&self) -> String {
        format!("{} geographic (EPSG {})", self.datum.name(), self.epsg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn epsg_codes_map_to_zones() {
        let z = UtmZone::from_epsg(28348).unwrap();
        assert_eq!((z.zone, z.south, z.datum), (48, true, Datum::Gda94));
        assert_eq!(z.name(), "GDA94 / MGA zone 48 (EPSG 28348)");
        assert_eq!(UtmZone::from_epsg(32633).unwrap().zone, 33);
        assert!(!UtmZone::from_epsg(32633).unwrap().south);
        assert!(UtmZone::from_epsg(32760).unwrap().south);
        assert_eq!(UtmZone::from_epsg(7855).unwrap().datum, Datum::Gda2020);
        assert!(UtmZone::from_epsg(3857).is_none());
        assert!(UtmZone::from_epsg(32661).is_none());
        assert!(GeographicCrs::from_epsg(4326).is_some());
        assert!(GeographicCrs::from_epsg(4230).is_none());
    }

    #[test]
    fn central_meridian_on_the_equator_is_the_false_easting() {
        let z = UtmZone::from_epsg(32631).unwrap(); // central meridian 3 E
        let (e, n) = z.from_lat_lon(0.0, 3.0).unwrap();
        assert!((e - 500_000.0).abs() < 1e-6 && n.abs() < 1e-6, "{e} {n}");
        let (lat, lon) = z.to_lat_lon(500_000.0, 0.0).unwrap();
        assert!(
            lat.abs() < 1e-12 && (lon - 3.0).abs() < 1e-12,
            "{lat} {lon}"
        );
    }
}
