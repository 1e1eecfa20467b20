//! Angle encoding (theta-PSO, Zhong, Li, Qian 2008, doi:10.1631/jzus.A071278; used for UAV routes by Fu, Ding, Zhou
//! 2012 as APSO): each coordinate = (max + min)/2 + (max - min)/2 sin(theta), with theta in
//! [-pi/2, pi/2] (the paper's range, where sin is one-to-one). With `periodic` the phases
//! live on the whole circle [-pi, pi) and wrap, since sin is 2 pi-periodic.

use std::f64::consts::{FRAC_PI_2, PI};

use super::{PathEncoding, PathFrame};
use crate::plan::Plan;
use crate::problem::Bound;

/// The angle encoding of a frame: one phase per coordinate of each free waypoint.
#[derive(Debug, Clone)]
pub struct Angle {
    frame: PathFrame,
    bounds: Vec<Bound>,
}

impl Angle {
    /// Phases in [-pi/2, pi/2], or with `periodic` on the whole circle [-pi, pi), wrapping.
    #[must_use]
    pub fn new(frame: PathFrame, periodic: bool) -> Self {
        let b = if periodic {
            Bound::periodic(-PI, PI)
        } else {
            Bound::new(-FRAC_PI_2, FRAC_PI_2)
        };
        let bounds = vec![b; frame.dimension()];
        Self { frame, bounds }
    }
}

/// The phase whose coordinate is `v` (the inverse of [`map`] on [-pi/2, pi/2]).
fn unmap(v: f64, r: [f64; 2]) -> f64 {
    let half = 0.5 * (r[1] - r[0]);
    if half <= 0.0 {
        return 0.0;
    }
    ((v - 0.5 * (r[0] + r[1])) / half).clamp(-1.0, 1.0).asin()
}

fn map(theta: f64, r: [f64; 2]) -> f64 {
    let v = 0.5 * (r[0] + r[1]) + 0.5 * (r[1] - r[0]) * theta.sin();
    v.clamp(r[0], r[1])
}

impl PathEncoding for Angle {
    fn bounds(&self) -> &[Bound] {
        &self.bounds
    }

    fn decode_into(&self, x: &[f64], plan: &mut Plan) {
        let f = &self.frame;
        let n = f.n;
        f.prepare(plan);
        for (i, path) in plan.uavs.iter_mut().enumerate() {
            let b = &x[3 * n * i..3 * n * (i + 1)];
            for k in 0..n {
                let w = &mut path.waypoints[k + 1];
                w.x = map(b[k], f.x);
                w.y = map(b[n + k], f.y);
                w.z = map(b[2 * n + k], f.z);
            }
        }
    }

    fn encode_into(&self, plan: &Plan, out: &mut [f64]) {
        let f = &self.frame;
        let n = f.n;
        for (i, path) in plan.uavs.iter().enumerate() {
            let b = &mut out[3 * n * i..3 * n * (i + 1)];
            for k in 0..n {
                let w = path.waypoints[k + 1];
                b[k] = unmap(w.x, f.x);
                b[n + k] = unmap(w.y, f.y);
                b[2 * n + k] = unmap(w.z, f.z);
            }
        }
        for (v, bound) in out.iter_mut().zip(&self.bounds) {
            *v = bound.project(*v);
        }
    }
}
