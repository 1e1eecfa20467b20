//! Cartesian encoding: each free waypoint's (x, y, z above ground) directly, bounded by the
//! map box and the altitude band. The plain PSO / QPSO / GWO / ABC baselines use it.

use super::{PathEncoding, PathFrame};
use crate::plan::Plan;
use crate::problem::Bound;

/// The Cartesian encoding of a frame: free waypoints' coordinates as they are.
#[derive(Debug, Clone)]
pub struct Cartesian {
    frame: PathFrame,
    bounds: Vec<Bound>,
}

impl Cartesian {
    /// Each coordinate bounded by the frame's map box and altitude band.
    #[must_use]
    pub fn new(frame: PathFrame) -> Self {
        let n = frame.n;
        let mut bounds = Vec::with_capacity(frame.dimension());
        for _ in &frame.starts {
            for r in [frame.x, frame.y, frame.z] {
                bounds.extend(std::iter::repeat_n(Bound::new(r[0], r[1]), n));
            }
        }
        Self { frame, bounds }
    }
}

impl PathEncoding for Cartesian {
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
                w.x = b[k].clamp(f.x[0], f.x[1]);
                w.y = b[n + k].clamp(f.y[0], f.y[1]);
                w.z = b[2 * n + k].clamp(f.z[0], f.z[1]);
            }
        }
    }

    fn encode_into(&self, plan: &Plan, out: &mut [f64]) {
        let n = self.frame.n;
        for (i, path) in plan.uavs.iter().enumerate() {
            let b = &mut out[3 * n * i..3 * n * (i + 1)];
            for k in 0..n {
                let w = path.waypoints[k + 1];
                b[k] = w.x;
                b[n + k] = w.y;
                b[2 * n + k] = w.z;
            }
        }
        for (v, bound) in out.iter_mut().zip(&self.bounds) {
            *v = bound.project(*v);
        }
    }
}
