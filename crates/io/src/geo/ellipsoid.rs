//! WGS 84 geodesy: geodetic <-> ECEF <-> ENU, in closed form (forward) and by Bowring's
//! iteration run to convergence (inverse), so there is no flat-earth step anywhere.
//!
//! - Geodetic: latitude and longitude in degrees, height in metres above the ellipsoid.
//! - ECEF: earth-centred, earth-fixed Cartesian metres (x to 0 N 0 E, z to the north pole).
//! - ENU: east, north, up metres in the plane tangent to the ellipsoid at an origin.
//!
//! Accuracy: the forward map is exact to rounding (~1e-9 m at the Earth's radius); the
//! inverse iterates Bowring's (1976, Surv. Rev. 23(181):323-327, doi:10.1179/sre.1976.23.181.323) formula until the latitude changes by less than
//! 1e-15 rad (two to three passes for points within 10 km of the surface), and the height
//! comes from `h = p cos(lat) + z sin(lat) - a^2 / N`, which is well conditioned at every
//! latitude. `tests/geo.rs` checks both against independently derived points to 1 mm.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// A reference ellipsoid: semi-major axis `a` (m) and flattening `f`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ellipsoid {
    /// Semi-major (equatorial) axis, metres.
    pub a: f64,
    /// Flattening (a - b) / a.
    pub f: f64,
}

impl Ellipsoid {
    /// WGS 84: a = 6 378 137 m, 1/f = 298.257 223 563.
    pub const WGS84: Self = Self {
        a: 6_378_137.0,
        f: 1.0 / 298.257_223_563,
    };
    /// GRS 80 (GDA94, GDA2020, ETRS89, NAD83): 1/f = 298.257 222 101; it differs from
    /// WGS 84 by 0.1 mm in the semi-minor axis.
    pub const GRS80: Self = Self {
        a: 6_378_137.0,
        f: 1.0 / 298.257_222_101,
    };

    /// Semi-minor axis b = a (1 - f).
    #[must_use]
    pub fn b(&self) -> f64 {
        self.a * (1.0 - self.f)
    }

    /// First eccentricity squared, e^2 = f (2 - f).
    #[must_use]
    pub fn e2(&self) -> f64 {
        self.f * (2.0 - self.f)
    }

    /// Prime-vertical radius of curvature N at geodetic latitude `lat` (radians).
    #[must_use]
    pub fn prime_vertical_radius(&self, lat: f64) -> f64 {
        let s = lat.sin();
        self.a / (1.0 - self.e2() * s * s).sqrt()
    }
}

/// A geodetic position on WGS 84: latitude and longitude in degrees, and a height in metres.
///
/// For the ECEF functions the height is above the ellipsoid; the mission exports call the
/// same number "altitude AMSL" (see `docs/export.md`: no geoid model is applied).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Geodetic {
    /// Latitude, degrees north, in [-90, 90].
    pub lat_deg: f64,
    /// Longitude, degrees east, in [-180, 180].
    pub lon_deg: f64,
    /// Height, metres.
    pub alt_m: f64,
}

impl Geodetic {
    /// The position at `lat_deg`, `lon_deg` (degrees) and `alt_m` (metres).
    #[must_use]
    pub const fn new(lat_deg: f64, lon_deg: f64, alt_m: f64) -> Self {
        Self {
            lat_deg,
            lon_deg,
            alt_m,
        }
    }

    /// Unit vector of the ellipsoid normal ("up") at this latitude and longitude, in ECEF.
    #[must_use]
    pub fn up(&self) -> DVec3 {
        let (sp, cp) = self.lat_deg.to_radians().sin_cos();
        let (sl, cl) = self.lon_deg.to_radians().sin_cos();
        DVec3::new(cp * cl, cp * sl, sp)
    }
}

/// ECEF coordinates of a WGS 84 geodetic position (closed form).
#[must_use]
pub fn geodetic_to_ecef(g: Geodetic) -> DVec3 {
    let e = Ellipsoid::WGS84;
    let lat = g.lat_deg.to_radians();
    let (sp, cp) = lat.sin_cos();
    let (sl, cl) = g.lon_deg.to_radians().sin_cos();
    let n = e.prime_vertical_radius(lat);
    DVec3::new(
        (n + g.alt_m) * cp * cl,
        (n + g.alt_m) * cp * sl,
        (n * (1.0 - e.e2()) + g.alt_m) * sp,
    )
}

/// WGS 84 geodetic position of an ECEF point (Bowring's iteration, run to convergence).
///
/// On the polar axis the longitude is 0 and the latitude +-90. Points near the Earth's
/// centre (where the geodetic latitude is not unique) are outside its intended use.
#[must_use]
pub fn ecef_to_geodetic(p: DVec3) -> Geodetic {
    let e = Ellipsoid::WGS84;
    let (a, b, e2) = (e.a, e.b(), e.e2());
    let ep2 = e2 / (1.0 - e2); // second eccentricity squared
    let r = p.x.hypot(p.y);
    if r == 0.0 {
        let lat = if p.z >= 0.0 { 90.0 } else { -90.0 };
        return Geodetic::new(lat, 0.0, p.z.abs() - b);
    }
    let lon = p.y.atan2(p.x);
    // Parametric (reduced) latitude beta; Bowring's formula gives the geodetic latitude
    // from it; iterating with tan(beta) = (1 - f) tan(lat) converges quadratically.
    let mut beta = (a * p.z).atan2(b * r);
    let mut lat = f64::NAN;
    for _ in 0..16 {
        let (sb, cb) = beta.sin_cos();
        let next = (p.z + ep2 * b * sb * sb * sb).atan2(r - e2 * a * cb * cb * cb);
        let converged = (next - lat).abs() <= 1e-15;
        lat = next;
        if converged {
            break;
        }
        let (sl, cl) = lat.sin_cos();
        beta = ((1.0 - e.f) * sl).atan2(cl);
    }
    let (sl, cl) = lat.sin_cos();
    let n = e.prime_vertical_radius(lat);
    let h = r * cl + p.z * sl - a * a / n;
    Geodetic::new(lat.to_degrees(), lon.to_degrees(), h)
}

/// East-north-up axes at a geodetic origin: converts between ECEF and ENU metres.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EnuFrame {
    origin: Geodetic,
    origin_ecef: DVec3,
    east: DVec3,
    north: DVec3,
    up: DVec3,
}

impl EnuFrame {
    /// The ENU frame tangent to the WGS 84 ellipsoid at `origin`.
    #[must_use]
    pub fn new(origin: Geodetic) -> Self {
        let (sp, cp) = origin.lat_deg.to_radians().sin_cos();
        let (sl, cl) = origin.lon_deg.to_radians().sin_cos();
        Self {
            origin,
            origin_ecef: geodetic_to_ecef(origin),
            east: DVec3::new(-sl, cl, 0.0),
            north: DVec3::new(-sp * cl, -sp * sl, cp),
            up: DVec3::new(cp * cl, cp * sl, sp),
        }
    }

    /// The geodetic origin of the frame.
    #[must_use]
    pub fn origin(&self) -> Geodetic {
        self.origin
    }

    /// ECEF of the origin.
    #[must_use]
    pub fn origin_ecef(&self) -> DVec3 {
        self.origin_ecef
    }

    /// Unit east, north and up vectors in ECEF.
    #[must_use]
    pub fn axes(&self) -> [DVec3; 3] {
        [self.east, self.north, self.up]
    }

    /// ENU coordinates (east, north, up) of an ECEF point.
    #[must_use]
    pub fn ecef_to_enu(&self, p: DVec3) -> DVec3 {
        let d = p - self.origin_ecef;
        DVec3::new(self.east.dot(d), self.north.dot(d), self.up.dot(d))
    }

    /// ECEF of ENU coordinates (east, north, up).
    #[must_use]
    pub fn enu_to_ecef(&self, enu: DVec3) -> DVec3 {
        self.origin_ecef + enu.x * self.east + enu.y * self.north + enu.z * self.up
    }

    /// ENU coordinates of a geodetic position.
    #[must_use]
    pub fn geodetic_to_enu(&self, g: Geodetic) -> DVec3 {
        self.ecef_to_enu(geodetic_to_ecef(g))
    }

    /// Geodetic position of ENU coordinates.
    #[must_use]
    pub fn enu_to_geodetic(&self, enu: DVec3) -> Geodetic {
        ecef_to_geodetic(self.enu_to_ecef(enu))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_points_have_the_textbook_coordinates() {
        let p = geodetic_to_ecef(Geodetic::new(0.0, 0.0, 0.0));
        assert!(
            (p - DVec3::new(6_378_137.0, 0.0, 0.0)).length() < 1e-9,
            "{p}"
        );
        let pole = geodetic_to_ecef(Geodetic::new(90.0, 0.0, 0.0));
        assert!((pole.z - Ellipsoid::WGS84.b()).abs() < 1e-9, "{pole}");
        let g = ecef_to_geodetic(DVec3::new(0.0, 0.0, -6_356_852.314_245));
        assert_eq!(g.lat_deg, -90.0);
        assert!((g.alt_m - 100.0).abs() < 1e-6, "{g:?}");
    }

    #[test]
    fn enu_axes_are_orthonormal() {
        let f = EnuFrame::new(Geodetic::new(-10.45, 105.62, 120.0));
        let [e, n, u] = f.axes();
        for (a, b) in [(e, n), (n, u), (u, e)] {
            assert!(a.dot(b).abs() < 1e-15);
        }
        assert!((e.cross(n) - u).length() < 1e-15);
    }
}
