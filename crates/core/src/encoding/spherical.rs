//! Spherical motion encoding (SPSO, Phung & Ha 2021; DLS-SMPSO Eqs. 16-17): each free
//! waypoint is a move (r, psi, phi) from the previous one: r the length, psi the climb angle,
//! phi the heading. Bounds: r in [0, 2 |start - goal| / n], psi in [-pi/4, pi/4],
//! phi in [phi0 - pi/4, phi0 + pi/4] around the start-goal bearing phi0 = atan2(dy, dx).
//! Each coordinate is clamped into the map box and altitude band right after it is computed,
//! so clamping carries forward (as SPSO does).
//!
//! SPSO's code measures phi0 from +x but decodes x with sin(phi) and y with cos(phi); that
//! convention is kept behind [`AngleConvention::Spso`] for the cross-check against its
//! reference costs. The default decodes x with cos(phi), y with sin(phi).

use std::f64::consts::FRAC_PI_4;

use super::{Frame, PathEncoding};
use crate::plan::Plan;
use crate::problem::Bound;

/// Which trigonometric convention maps phi to the plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AngleConvention {
    /// x += r cos(psi) cos(phi), y += r cos(psi) sin(phi).
    Consistent,
    /// SPSO's: x += r cos(psi) sin(phi), y += r cos(psi) cos(phi).
    Spso,
}

#[derive(Debug, Clone)]
pub struct Spherical {
    frame: Frame,
    convention: AngleConvention,
    bounds: Vec<Bound>,
}

impl Spherical {
    #[must_use]
    pub fn new(frame: Frame, convention: AngleConvention) -> Self {
        let n = frame.n;
        let mut bounds = Vec::with_capacity(frame.dimension());
        for s in &frame.starts {
            let d = frame.goal - *s;
            let r_max = 2.0 * d.length() / n as f64;
            let phi0 = d.y.atan2(d.x);
            bounds.extend(std::iter::repeat_n(Bound::new(0.0, r_max), n));
            bounds.extend(std::iter::repeat_n(Bound::new(-FRAC_PI_4, FRAC_PI_4), n));
            bounds.extend(std::iter::repeat_n(
                Bound::new(phi0 - FRAC_PI_4, phi0 + FRAC_PI_4),
                n,
            ));
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
                let horizontal = r[k] * psi[k].cos();
                let (ux, uy) = match self.convention {
                    AngleConvention::Consistent => (phi[k].cos(), phi[k].sin()),
                    AngleConvention::Spso => (phi[k].sin(), phi[k].cos()),
                };
                p.x = (p.x + horizontal * ux).clamp(f.x[0], f.x[1]);
                p.y = (p.y + horizontal * uy).clamp(f.y[0], f.y[1]);
                p.z = (p.z + r[k] * psi[k].sin()).clamp(f.z[0], f.z[1]);
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
