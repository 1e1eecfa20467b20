//! The fleet's pace as a decision variable: any encoding with one more value per UAV block.
//!
//! Why: under a time-varying channel when the fleet is where matters as much as the route
//! (docs/model.md, "Pace"), and the timing policy alone fixes the speeds nearest cruise. When
//! a scenario's `timing.pace` range is open (lo < hi), the planning problem wraps its
//! encoding in [`Paced`]: UAV i's block is its path's 3 n values followed by one pace value
//! in the range, and the plan flies at the mean of the n pace values. A value per block (not
//! one for the fleet) keeps every block the same size, so optimizers that work block by
//! block (cooperative coevolution, the focused moves) handle it with no special case; the
//! mean lets each UAV's search move the fleet's pace by its share. With a closed range the
//! problem is not wrapped, so the paper's layout and every result on it are unchanged.

use super::{per_block, PathEncoding};
use crate::plan::Plan;
use crate::problem::Bound;

/// An inner encoding with a pace value after each UAV's block.
pub struct Paced {
    inner: Box<dyn PathEncoding>,
    /// The inner encoding's values per UAV.
    block: usize,
    uavs: usize,
    pace: Bound,
    bounds: Vec<Bound>,
}

impl Paced {
    /// Wraps `inner` (blocks of `block` values for `uavs` UAVs) with a pace in `range`.
    #[must_use]
    pub fn new(inner: Box<dyn PathEncoding>, uavs: usize, range: [f64; 2]) -> Self {
        let block = inner.bounds().len() / uavs.max(1);
        let pace = Bound::new(range[0], range[1]);
        let bounds = per_block::bounds_with_extra(inner.bounds(), block, pace);
        Self {
            inner,
            block,
            uavs,
            pace,
            bounds,
        }
    }

    /// The fleet's pace of decision vector `x`: the mean of its pace values, exactly the
    /// value when they are all equal (as [`PathEncoding::encode_into`] writes them; a sum
    /// over n and back is not always the same bits).
    #[must_use]
    pub fn pace_of(&self, x: &[f64]) -> f64 {
        let values = || x.chunks(self.block + 1).map(|b| b[self.block]);
        let first = values().next().unwrap_or(1.0);
        if values().all(|v| v.to_bits() == first.to_bits()) {
            return first;
        }
        values().sum::<f64>() / self.uavs.max(1) as f64
    }
}

impl PathEncoding for Paced {
    fn bounds(&self) -> &[Bound] {
        &self.bounds
    }

    fn decode_into(&self, x: &[f64], plan: &mut Plan) {
        per_block::decode_inner(self.inner.as_ref(), self.block, x, plan);
        plan.pace = self.pace_of(x);
    }

    fn encode_into(&self, plan: &Plan, out: &mut [f64]) {
        let pace = self.pace.project(plan.pace);
        let inner = self.inner.as_ref();
        per_block::encode_with_extra(inner, self.block, self.uavs, plan, out, |_| pace);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::encoding::cartesian::Cartesian;
    use crate::encoding::tests::frame_with;

    fn frame() -> crate::encoding::PathFrame {
        frame_with(3)
    }

    #[test]
    fn pace_values_follow_each_block_and_the_plan_flies_their_mean() {
        let inner = Cartesian::new(frame());
        let plain = inner.decode(
            &inner
                .bounds()
                .iter()
                .map(|b| 0.5 * (b.lo + b.hi))
                .collect::<Vec<_>>(),
        );
        let paced = Paced::new(Box::new(Cartesian::new(frame())), 2, [0.8, 1.6]);
        assert_eq!(paced.bounds().len(), 2 * (9 + 1));
        assert_eq!(paced.bounds()[9], Bound::new(0.8, 1.6));
        assert_eq!(paced.bounds()[19], Bound::new(0.8, 1.6));
        let mut x: Vec<f64> = paced.bounds().iter().map(|b| 0.5 * (b.lo + b.hi)).collect();
        x[9] = 1.0;
        x[19] = 1.5;
        let plan = paced.decode(&x);
        assert_eq!(plan.pace, 1.25);
        assert_eq!(plan.uavs, plain.uavs);
        // Round trip: every block gets the plan's pace.
        let mut y = vec![0.0; x.len()];
        paced.encode_into(&plan, &mut y);
        assert_eq!((y[9], y[19]), (1.25, 1.25));
        assert_eq!(paced.decode(&y), plan);
        // Equal values give back exactly that pace: with three UAVs, (0.1 + 0.1 + 0.1) / 3
        // is 0.10000000000000002, not 0.1.
        assert_ne!((0.1f64 + 0.1 + 0.1) / 3.0, 0.1);
        let mut three = frame();
        three.starts.push(glam::DVec3::new(140.0, 40.0, 150.0));
        let wide = Paced::new(Box::new(Cartesian::new(three.clone())), 3, [0.05, 1.6]);
        let tenth = Plan {
            pace: 0.1,
            ..Cartesian::new(three).decode(&vec![500.0; 27])
        };
        let mut z = vec![0.0; wide.bounds().len()];
        wide.encode_into(&tenth, &mut z);
        assert_eq!(wide.decode(&z).pace.to_bits(), 0.1f64.to_bits());
        // A pace outside the range is clamped into it.
        let fast = Plan { pace: 3.0, ..plan };
        paced.encode_into(&fast, &mut y);
        assert_eq!((y[9], y[19]), (1.6, 1.6));
    }
}
