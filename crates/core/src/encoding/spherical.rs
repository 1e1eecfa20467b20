//! Spherical motion encoding (SPSO, Phung & Ha 2021, doi:10.1016/j.asoc.2021.107376;
//! DLS-SMPSO Eqs. 16-17, doi:10.3390/drones8110654): each free
//! waypoint is a move (r, psi, phi) from the previous one: r the length, psi the climb angle
//! (heights above ground), phi the heading. Bounds: r in [0, 2 |start - goal| / n], psi in
//! [-pi/4, pi/4], phi in [phi0 - pi/4, phi0 + pi/4] around the start-goal bearing
//! phi0 = atan2(dy, dx). Along a seeded way ([`Spherical::along_guides`]) the sectors follow
//! the way, and r and psi widen where the way's moves need more.
//! Each coordinate is clamped into the map box and altitude band right after it is computed,
//! so clamping carries forward (as SPSO does).
//!
//! SPSO's code measures phi0 from +x but decodes x with sin(phi) and y with cos(phi); that
//! convention is kept behind [`AngleConvention::Spso`] for the cross-check against its
//! reference costs. The default decodes x with cos(phi), y with sin(phi).

use std::f64::consts::FRAC_PI_4;

use glam::DVec2;

use super::{PathEncoding, PathFrame};
use crate::plan::Plan;
use crate::problem::Bound;

/// How much longer than a guide's move its motion may be, where that exceeds the base
/// bound of twice the guide's length over n.
const LONG_MOVE_ROOM: f64 = 1.5;

/// How far a seeded move's climb bound reaches beyond the angle the seed needs, where that
/// angle exceeds SPSO's 45 deg: room for the band start's bow and layers. Less than
/// [`LONG_MOVE_ROOM`] gives a length, because near 90 deg a small change of angle moves the
/// waypoint far in the plane. Set before any run, not tuned.
const STEEP_MOVE_ROOM: f64 = 1.1;

/// The steepest climb angle a move's bound may reach, rad (85 deg).
const STEEPEST_MOVE: f64 = 85.0 * std::f64::consts::PI / 180.0;

/// Which trigonometric convention maps phi to the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AngleConvention {
    /// x += r cos(psi) cos(phi), y += r cos(psi) sin(phi).
    Consistent,
    /// SPSO's: x += r cos(psi) sin(phi), y += r cos(psi) cos(phi).
    Spso,
}

/// The spherical motion encoding of a frame: each free waypoint a move (r, psi, phi) from the
/// previous one.
#[derive(Debug, Clone)]
pub struct Spherical {
    frame: PathFrame,
    convention: AngleConvention,
    bounds: Vec<Bound>,
}

impl Spherical {
    /// Heading sectors centred on each UAV's start-goal bearing, under `convention`.
    #[must_use]
    pub fn new(frame: PathFrame, convention: AngleConvention) -> Self {
        Self::along_guides(frame, convention, &[], &[])
    }

    /// As [`Spherical::new`], but UAV i's heading sector at free waypoint k is centred on the
    /// bearing of `guides[i]` there (the `corridor` initialisation's path, resampled as it
    /// is, [`super::corridor::resample`]) instead of the start-goal bearing, and its motion
    /// lengths reach twice the guide's length over n; UAVs with an empty guide keep the
    /// start-goal sector. So a corridor that leaves the start-goal bearing by more than
    /// 45 degrees (round a threat) can be expressed and searched around.
    ///
    /// `climbs[i][k]`, where given, is the climb angle (rad, either sign) that UAV i's seeded
    /// move k needs in the encoding's frame, where heights are above ground: on rugged
    /// terrain a way whose absolute altitude keeps 45 deg may change its height above
    /// ground faster than that between two waypoints (outside instances: 80 m over 27 m
    /// of a cliff), and a move clamped to 45 deg then lands tens of metres off in the plane
    /// and a hundred in altitude. Such a move's bound widens to 1.1 times the angle, at
    /// most 85 deg (`STEEP_MOVE_ROOM`, `STEEPEST_MOVE`); the others keep SPSO's 45 deg.
    #[must_use]
    pub fn along_guides(
        frame: PathFrame,
        convention: AngleConvention,
        guides: &[Vec<DVec2>],
        climbs: &[Vec<f64>],
    ) -> Self {
        let n = frame.n;
        let mut bounds = Vec::with_capacity(frame.dimension());
        for (i, s) in frame.starts.iter().enumerate() {
            let d = frame.goal - *s;
            let guide = guides.get(i).filter(|g| g.len() >= 2);
            let (r_max, phis): (Vec<f64>, Vec<f64>) = match guide {
                None => (
                    vec![2.0 * d.length() / n as f64; n],
                    vec![d.y.atan2(d.x); n],
                ),
                Some(g) => {
                    let length: f64 = g.windows(2).map(|w| w[0].distance(w[1])).sum();
                    let mut points = vec![s.truncate()];
                    points.extend(super::corridor::resample(g, n));
                    let bearing = |a: DVec2, b: DVec2| match convention {
                        AngleConvention::Consistent => (b.y - a.y).atan2(b.x - a.x),
                        AngleConvention::Spso => (b.x - a.x).atan2(b.y - a.y),
                    };
                    let phis = points.windows(2).map(|w| bearing(w[0], w[1])).collect();
                    let base = (2.0 * length / n as f64).max(2.0 * d.length() / n as f64);
                    // A guide's move longer than the base (a straight over a valley between
                    // waypoints held in the band, `band`) keeps room to be expressed.
                    let r_max = points
                        .windows(2)
                        .map(|w| base.max(LONG_MOVE_ROOM * w[0].distance(w[1])))
                        .collect();
                    (r_max, phis)
                }
            };
            bounds.extend(r_max.iter().map(|&r| Bound::new(0.0, r)));
            let seeded = climbs.get(i).filter(|c| c.len() == n);
            bounds.extend((0..n).map(|k| {
                let need = seeded.map_or(0.0, |c| STEEP_MOVE_ROOM * c[k].abs());
                // SPSO's 45 deg unless the seed needs more (a NaN angle asks for nothing).
                let psi = if need > FRAC_PI_4 {
                    need.min(STEEPEST_MOVE)
                } else {
                    FRAC_PI_4
                };
                Bound::new(-psi, psi)
            }));
            bounds.extend(
                phis.iter()
                    .map(|&phi0| Bound::new(phi0 - FRAC_PI_4, phi0 + FRAC_PI_4)),
            );
        }
        Self {
            frame,
            convention,
            bounds,
        }
    }
}

impl PathEncoding for Spherical {
    fn bounds(&self) -> &[Bound] {
        &self.bounds
    }

    fn decode_into(&self, x: &[f64], plan: &mut Plan) {
        let f = &self.frame;
        let n = f.n;
        f.prepare(plan);
        for (i, path) in plan.uavs.iter_mut().enumerate() {
            let block = &x[3 * n * i..3 * n * (i + 1)];
            let (r, rest) = block.split_at(n);
            let (psi, phi) = rest.split_at(n);
            let mut p = path.waypoints[0];
            for k in 0..n {
                // One `sincos` per angle (glibc's equals its `sin` and `cos` bit for bit).
                let (psi_sin, psi_cos) = psi[k].sin_cos();
                let (phi_sin, phi_cos) = phi[k].sin_cos();
                let horizontal = r[k] * psi_cos;
                let (ux, uy) = match self.convention {
                    AngleConvention::Consistent => (phi_cos, phi_sin),
                    AngleConvention::Spso => (phi_sin, phi_cos),
                };
                p.x = (p.x + horizontal * ux).clamp(f.x[0], f.x[1]);
                p.y = (p.y + horizontal * uy).clamp(f.y[0], f.y[1]);
                p.z = (p.z + r[k] * psi_sin).clamp(f.z[0], f.z[1]);
                path.waypoints[k + 1] = p;
            }
        }
    }

    /// Segment by segment from the *decoded* previous waypoint, so clamping of one motion
    /// does not shift all later ones.
    fn encode_into(&self, plan: &Plan, out: &mut [f64]) {
        let f = &self.frame;
        let n = f.n;
        for (i, path) in plan.uavs.iter().enumerate() {
            let base = 3 * n * i;
            let mut p = path.waypoints[0];
            for k in 0..n {
                let d = path.waypoints[k + 1] - p;
                let horizontal = d.truncate().length();
                let phi_raw = match self.convention {
                    AngleConvention::Consistent => d.y.atan2(d.x),
                    AngleConvention::Spso => d.x.atan2(d.y),
                };
                let rb = self.bounds[base + k];
                let psib = self.bounds[base + n + k];
                let phib = self.bounds[base + 2 * n + k];
                // Bring the heading to the branch nearest the bound's centre before clamping.
                let centre = 0.5 * (phib.lo + phib.hi);
                let phi_near = centre
                    + (phi_raw - centre + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                let r = rb.project(d.length());
                let psi = psib.project(d.z.atan2(horizontal));
                let phi = phib.project(phi_near);
                out[base + k] = r;
                out[base + n + k] = psi;
                out[base + 2 * n + k] = phi;
                let h = r * psi.cos();
                let (ux, uy) = match self.convention {
                    AngleConvention::Consistent => (phi.cos(), phi.sin()),
                    AngleConvention::Spso => (phi.sin(), phi.cos()),
                };
                p.x = (p.x + h * ux).clamp(f.x[0], f.x[1]);
                p.y = (p.y + h * uy).clamp(f.y[0], f.y[1]);
                p.z = (p.z + r * psi.sin()).clamp(f.z[0], f.z[1]);
            }
        }
    }
}
