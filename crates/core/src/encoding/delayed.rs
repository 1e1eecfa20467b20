//! Departure delays as decision variables: any encoding with one more value per UAV block.
//!
//! Why: under common arrival every UAV is at the same share of its path at every moment,
//! so none can stay behind to relay for the others; on the outside benchmark's instance 2
//! the fleet flies out of the ground station's sight behind a ridge for 25 s (docs/results.md,
//! "Departure delays"). When a scenario's `timing.max_delay` is above 0, the planning
//! problem wraps its encoding in [`Delayed`]: UAV i's block is the inner block followed by
//! its delay in [0, max_delay], a share of its arrival time that it hovers at its start
//! ([`crate::timing`]). Wrapped last, so a block with a free pace ends pace, delay. With
//! `max_delay = 0` the problem is not wrapped: the paper's layout and every result on it
//! are unchanged.

use super::{per_block, PathEncoding};
use crate::plan::Plan;
use crate::problem::Bound;

/// An inner encoding with a departure delay after each UAV's block.
pub struct Delayed {
    inner: Box<dyn PathEncoding>,
    /// The inner encoding's values per UAV.
    block: usize,
    uavs: usize,
    delay: Bound,
    bounds: Vec<Bound>,
}

impl Delayed {
    /// Wraps `inner` (blocks of `block` values for `uavs` UAVs) with a delay in
    /// [0, `max_delay`] per UAV.
    #[must_use]
    pub fn new(inner: Box<dyn PathEncoding>, uavs: usize, max_delay: f64) -> Self {
        let block = inner.bounds().len() / uavs.max(1);
        let delay = Bound::new(0.0, max_delay);
        let bounds = per_block::bounds_with_extra(inner.bounds(), block, delay);
        Self {
            inner,
            block,
            uavs,
            delay,
            bounds,
        }
    }
}

impl PathEncoding for Delayed {
    fn bounds(&self) -> &[Bound] {
        &self.bounds
    }

    fn decode_into(&self, x: &[f64], plan: &mut Plan) {
        per_block::decode_inner(self.inner.as_ref(), self.block, x, plan);
        plan.delays.clear();
        plan.delays
            .extend(x.chunks(self.block + 1).map(|b| b[self.block]));
    }

    fn encode_into(&self, plan: &Plan, out: &mut [f64]) {
        let delay = |u: usize| self.delay.project(plan.delay(u));
        let inner = self.inner.as_ref();
        per_block::encode_with_extra(inner, self.block, self.uavs, plan, out, delay);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encoding::cartesian::Cartesian;
    use crate::encoding::tests::frame_with;

    #[test]
    fn each_block_ends_with_its_uavs_delay_and_round_trips() {
        let inner = Cartesian::new(frame_with(3));
        let mid: Vec<f64> = inner.bounds().iter().map(|b| 0.5 * (b.lo + b.hi)).collect();
        let plain = inner.decode(&mid);
        let delayed = Delayed::new(Box::new(Cartesian::new(frame_with(3))), 2, 0.4);
        assert_eq!(delayed.bounds().len(), 2 * (9 + 1));
        assert_eq!(delayed.bounds()[9], Bound::new(0.0, 0.4));
        assert_eq!(delayed.bounds()[19], Bound::new(0.0, 0.4));
        let mut x: Vec<f64> = delayed
            .bounds()
            .iter()
            .map(|b| 0.5 * (b.lo + b.hi))
            .collect();
        x[9] = 0.0;
        x[19] = 0.3;
        let plan = delayed.decode(&x);
        assert_eq!(plan.delays, vec![0.0, 0.3]);
        assert_eq!(plan.uavs, plain.uavs);
        let mut y = vec![0.0; x.len()];
        delayed.encode_into(&plan, &mut y);
        assert_eq!(y, x);
        // A delay outside the range is clamped into it; a missing one is 0.
        let late = Plan {
            delays: vec![0.9],
            ..plan
        };
        delayed.encode_into(&late, &mut y);
        assert_eq!((y[9], y[19]), (0.4, 0.0));
    }
}
