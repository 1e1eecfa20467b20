//! The interface between a planning problem and an optimizer.
//!
//! An optimizer sees only box bounds and a pure, infallible evaluation. Keeping this narrow
//! lets any optimizer run on any encoding of any scenario, and on plain test functions.

use rand::Rng as _;
use serde::{Deserialize, Serialize};

use crate::rng::Rng;

/// Bounds of one decision variable. `periodic` marks an angle that wraps: optimizers may
/// wrap it instead of clamping.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Bound {
    /// Lowest allowed value.
    pub lo: f64,
    /// Highest allowed value.
    pub hi: f64,
    /// Whether the variable wraps from `hi` back to `lo`.
    pub periodic: bool,
}

impl Bound {
    /// A bound `[lo, hi]` that clamps (not periodic).
    #[must_use]
    pub const fn new(lo: f64, hi: f64) -> Self {
        Self {
            lo,
            hi,
            periodic: false,
        }
    }

    /// A periodic bound `[lo, hi]`, for an angle that wraps.
    #[must_use]
    pub const fn periodic(lo: f64, hi: f64) -> Self {
        Self {
            lo,
            hi,
            periodic: true,
        }
    }

    /// `hi - lo`.
    #[must_use]
    pub fn width(&self) -> f64 {
        self.hi - self.lo
    }

    /// Brings `x` into the bound: wraps periodic bounds, clamps the others.
    #[must_use]
    pub fn project(&self, x: f64) -> f64 {
        if self.periodic {
            let w = self.width();
            if w > 0.0 && x.is_finite() {
                return self.lo + (x - self.lo).rem_euclid(w);
            }
        }
        x.clamp(self.lo, self.hi)
    }

    /// Whether `x` lies in `[lo, hi]`.
    #[must_use]
    pub fn contains(&self, x: f64) -> bool {
        x >= self.lo && x <= self.hi
    }

    /// A uniform sample in `[lo, hi]`.
    pub fn sample(&self, rng: &mut Rng) -> f64 {
        let u: f64 = rng.random();
        (self.lo + u * (self.hi - self.lo)).clamp(self.lo, self.hi)
    }
}

/// Fills `out` with a uniform sample of the box `bounds`.
pub fn fill_uniform(bounds: &[Bound], rng: &mut Rng, out: &mut [f64]) {
    for (x, b) in out.iter_mut().zip(bounds) {
        *x = b.sample(rng);
    }
}

/// Result of one evaluation. Lower cost is better; `violation` is 0 exactly when the
/// candidate satisfies every hard constraint (it is a measure of how far it is from that).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// The objective; lower is better.
    pub cost: f64,
    /// How far the candidate is from satisfying every hard constraint (0 when it does).
    pub violation: f64,
}

impl Evaluation {
    /// An evaluation with NaN mapped to +inf, so a NaN never wins a comparison.
    #[must_use]
    pub fn new(cost: f64, violation: f64) -> Self {
        Self {
            cost: if cost.is_nan() { f64::INFINITY } else { cost },
            violation: if violation.is_nan() {
                f64::INFINITY
            } else {
                violation
            },
        }
    }

    /// Infinite cost and violation: loses every comparison.
    #[must_use]
    pub const fn worst() -> Self {
        Self {
            cost: f64::INFINITY,
            violation: f64::INFINITY,
        }
    }

    /// Whether the candidate satisfies every hard constraint (zero violation).
    #[must_use]
    pub fn feasible(&self) -> bool {
        self.violation == 0.0
    }

    /// Strictly better by cost (total order; NaN was mapped to +inf at construction).
    #[must_use]
    pub fn better_than(&self, other: &Self) -> bool {
        self.cost.total_cmp(&other.cost).is_lt()
    }

    /// The cost cutoff ([`Problem::evaluate_cost_bounded`]) for a candidate that matters only
    /// if it is [`Evaluation::better_than`] this one: this cost, or `f64::MAX` when it is
    /// +inf, so that a candidate found to cost +inf, which cannot beat it, is given up too
    /// (one costing less is never given up). SPSO's MyCost puts +inf on every collision, and
    /// a particle's pbest stays there until it finds a path that does not collide.
    #[must_use]
    pub fn cutoff_to_beat(&self) -> f64 {
        self.cost.min(f64::MAX)
    }

    /// Strictly better under Deb's feasibility rules (Deb 2000, Comput. Methods Appl. Mech.
    /// Eng. 186:311-338, doi:10.1016/S0045-7825(99)00389-8): the smaller violation wins, and between equal violations (two
    /// feasible candidates in particular) the lower cost.
    #[must_use]
    pub fn better_feasibility_first(&self, other: &Self) -> bool {
        match self.violation.total_cmp(&other.violation) {
            std::cmp::Ordering::Less => true,
            std::cmp::Ordering::Greater => false,
            std::cmp::Ordering::Equal => self.better_than(other),
        }
    }
}

/// A minimisation problem over a box.
pub trait Problem: Sync {
    /// One bound per decision variable.
    fn bounds(&self) -> &[Bound];

    /// Pure and infallible: same `x`, same result; never touches a random generator.
    fn evaluate(&self, x: &[f64]) -> Evaluation;

    /// Draws a starting point into `out` (one row of an initial population, or an ABC
    /// scout). The default is uniform in the box; a problem that knows its structure (a
    /// planning problem with a start-goal line) may draw elsewhere, but always inside the
    /// bounds. Part of a method's definition, so optimizers never sample the box directly.
    fn sample_initial(&self, rng: &mut Rng, out: &mut [f64]) {
        fill_uniform(self.bounds(), rng, out);
    }

    /// The number of decision variables.
    fn dimension(&self) -> usize {
        self.bounds().len()
    }

    /// [`Problem::evaluate`] for a caller that only needs to know whether `x` costs less
    /// than `cutoff`: `None` means its cost is known to exceed `cutoff`, so it does not. Must
    /// otherwise return exactly what `evaluate` returns. The default evaluates in full.
    fn evaluate_cost_bounded(&self, x: &[f64], cutoff: f64) -> Option<Evaluation> {
        let _ = cutoff;
        Some(self.evaluate(x))
    }

    /// [`Problem::evaluate_cost_bounded`] on buffers kept for `slot`, the caller's index of
    /// the point `x` was made from (an ABC food source): a problem whose evaluation reuses
    /// the work of the previous one on the same buffers does less when `x` is a small change
    /// of the slot's previous point than of whatever was evaluated last. Must return exactly
    /// what [`Problem::evaluate_cost_bounded`] returns. The default ignores the slot.
    fn evaluate_cost_bounded_in(&self, x: &[f64], cutoff: f64, slot: usize) -> Option<Evaluation> {
        let _ = slot;
        self.evaluate_cost_bounded(x, cutoff)
    }

    /// The block-wise view of this problem, for optimizers that decompose the search
    /// (`coop`): `Some(self)` from a problem that implements [`BlockProblem`]; `None` (the
    /// default) for one whose vector is a single block with nothing known of where its
    /// violations lie.
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        None
    }
}

/// A problem whose variables come in blocks (one UAV's path each in a planning problem),
/// with what a decomposing optimizer (`coop`) asks of it beyond [`Problem`]: the block size,
/// each block's share of the violation, and local moves of one block. Every method has a
/// default that knows nothing, so a problem implements only what it can say. Reached
/// through [`Problem::blocks`], so the optimizers' common interface stays narrow.
pub trait BlockProblem: Problem {
    /// A local move of block `block` of `x`, written into `out` (that block's values, inside
    /// the bounds): for a planning problem, one free waypoint of the UAV moved by a few
    /// separation distances (or, at a zone the UAV shares, placed near it at a clear
    /// bearing), the rest of its path kept where it is. `site` picks what moves
    /// (an index into [`BlockProblem::hot_spots`]' weights, which may include sites other than
    /// waypoints, such as a departure delay); `None` draws a waypoint uniformly. Returns
    /// false, writing nothing, when the problem has no such move (the default). Not an
    /// evaluation; it draws only from `rng`.
    fn nudge(
        &self,
        x: &[f64],
        block: usize,
        site: Option<usize>,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        let _ = (x, block, site, rng, out);
        false
    }

    /// Weights over the sites of block `block`'s [nudges](BlockProblem::nudge), by how much of
    /// `x`'s hard violation lies at each (a planning problem: per free waypoint of the UAV,
    /// the violations it or its pairs hold next to it), written into `out`; empty when
    /// nothing is known. Returns whether it assessed `x`, which the
    /// [`super::optim::Evaluator`] then counts as an evaluation; the default knows nothing,
    /// assesses nothing and returns false.
    fn hot_spots(&self, x: &[f64], block: usize, out: &mut Vec<f64>) -> bool {
        let _ = (x, block);
        out.clear();
        false
    }

    /// Block `donor`'s path of `x` made block `block`'s, shifted by a random offset of a
    /// few separation distances (every free waypoint by the same offset), written into `out`;
    /// false, writing nothing, when the problem has no such move (the default). Not an
    /// evaluation; it draws only from `rng`.
    fn shifted_copy(
        &self,
        x: &[f64],
        block: usize,
        donor: usize,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        let _ = (x, block, donor, rng, out);
        false
    }

    /// [`Problem::evaluate`], also writing into `by_block` each block's share of the
    /// violation (a planning problem: each UAV's, a pair's violation counting for both), so
    /// a decomposing optimizer can search where the violations are. The shares need not sum
    /// to the violation. The default leaves `by_block` empty: nothing known.
    fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
        by_block.clear();
        self.evaluate(x)
    }

    /// [`BlockProblem::evaluate_blocks`] for a caller that only needs to know whether `x` beats,
    /// by Deb's rules, a candidate whose violation is `cutoff`: `None` (and `by_block`
    /// unspecified) means the violation is known to exceed `cutoff`, so it does not. Must
    /// otherwise return exactly what `evaluate_blocks` returns. The default evaluates in full.
    fn evaluate_blocks_bounded(
        &self,
        x: &[f64],
        by_block: &mut Vec<f64>,
        cutoff: f64,
    ) -> Option<Evaluation> {
        let _ = cutoff;
        Some(self.evaluate_blocks(x, by_block))
    }

    /// Size of the blocks the variables come in (one UAV's path in a planning problem),
    /// for optimizers that decompose the search; the whole vector by default.
    fn block_size(&self) -> usize {
        self.dimension()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cutoff_to_beat_gives_up_only_on_what_cannot_beat() {
        let finite = Evaluation::new(12.5, 0.0);
        assert_eq!(finite.cutoff_to_beat(), 12.5);
        let colliding = Evaluation::new(f64::INFINITY, 3.0);
        let cutoff = colliding.cutoff_to_beat();
        assert!(cutoff.is_finite());
        // Every candidate above the cutoff is one that is not better.
        let worse = Evaluation::new(f64::INFINITY, 0.0);
        assert!(worse.cost > cutoff && !worse.better_than(&colliding));
        let better = Evaluation::new(f64::MAX, 9.0);
        assert!(better.cost <= cutoff && better.better_than(&colliding));
    }

    #[test]
    fn periodic_bound_wraps_and_plain_bound_clamps() {
        let p = Bound::periodic(-1.0, 1.0);
        assert!((p.project(1.5) - (-0.5)).abs() < 1e-12);
        assert!((p.project(-1.5) - 0.5).abs() < 1e-12);
        let b = Bound::new(-1.0, 1.0);
        assert_eq!(b.project(1.5), 1.0);
        assert_eq!(b.project(-7.0), -1.0);
    }

    #[test]
    fn nan_never_wins() {
        let nan = Evaluation::new(f64::NAN, 0.0);
        let one = Evaluation::new(1.0, 0.0);
        assert!(one.better_than(&nan));
        assert!(!nan.better_than(&one));
    }
}
