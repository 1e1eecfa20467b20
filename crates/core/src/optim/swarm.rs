//! Small helpers every population-based optimizer here shares: bringing a moved coordinate
//! back into its bound, the PSO velocity kernel, and a best-so-far record.
//!
//! Populations are stored as flat row-major `Vec<f64>` (one row of `dim` values per
//! individual), allocated once per run, so the inner loops never allocate.

use crate::problem::{Bound, Evaluation};

/// Brings `x` into its bound: wraps periodic bounds, clamps the others. A NaN (which only
/// a degenerate update could produce) goes to the middle, so nothing outside the box is
/// ever evaluated.
pub(crate) fn into_bound(b: &Bound, x: f64) -> f64 {
    if x.is_nan() {
        0.5 * (b.lo + b.hi)
    } else {
        b.project(x)
    }
}

/// The coefficients of one PSO velocity update ([`move_coordinate`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct VelocityRule {
    /// Inertia weight w.
    pub inertia: f64,
    /// Cognitive coefficient c1.
    pub cognitive: f64,
    /// Social coefficient c2.
    pub social: f64,
    /// DLS-SMPSO's deterministic pull lambda (gbest - x) (Eq. 21), `None` in plain PSO.
    /// An `Option`, not 0: adding 0 (gbest - x) would change the sign of a zero velocity.
    pub pull: Option<f64>,
    /// Negate a velocity whose move left a non-periodic bound (SPSO's mirroring).
    pub mirror: bool,
}

/// Moves one coordinate of one particle, the kernel every swarm here shares (`pso`, the
/// DLS modes and `coop`'s sub-swarms), with fresh r1, r2 ~ U(0, 1) drawn in that order:
///
/// ```text
/// v <- clamp(w v + c1 r1 (p - x) + c2 r2 (g - x) [+ lambda (g - x)], -vmax, vmax)
/// x <- into_bound(x + v); v <- -v if the move left a non-periodic bound and rule.mirror
/// ```
#[allow(clippy::too_many_arguments)]
#[inline]
pub(crate) fn move_coordinate(
    x: &mut f64,
    v: &mut f64,
    guide: f64,
    gbest: f64,
    vmax: f64,
    bound: &Bound,
    rule: &VelocityRule,
    rng: &mut crate::rng::Rng,
) {
    use rand::Rng as _;
    let r1: f64 = rng.random();
    let r2: f64 = rng.random();
    let to_g = gbest - *x;
    let mut vj = rule.inertia * *v + rule.cognitive * r1 * (guide - *x) + rule.social * r2 * to_g;
    if let Some(lambda) = rule.pull {
        vj += lambda * to_g;
    }
    let vj = vj.clamp(-vmax, vmax);
    let moved = *x + vj;
    *v = if rule.mirror && !bound.periodic && !bound.contains(moved) {
        -vj
    } else {
        vj
    };
    *x = into_bound(bound, moved);
}

/// Row `i` of a flat population with rows of `dim` values.
pub(crate) fn row(v: &[f64], i: usize, dim: usize) -> &[f64] {
    &v[i * dim..(i + 1) * dim]
}

pub(crate) fn row_mut(v: &mut [f64], i: usize, dim: usize) -> &mut [f64] {
    &mut v[i * dim..(i + 1) * dim]
}

/// The best position seen so far. The first offer is always taken, even with an infinite
/// cost, so the position is defined as soon as anything was evaluated; later offers must be
/// strictly better ([`Evaluation::better_than`], under which NaN never wins).
#[derive(Debug, Clone)]
pub(crate) struct BestSoFar {
    pub x: Vec<f64>,
    pub eval: Evaluation,
    set: bool,
}

impl BestSoFar {
    pub fn new(dim: usize) -> Self {
        Self {
            x: vec![0.0; dim],
            eval: Evaluation::worst(),
            set: false,
        }
    }

    /// Takes `x` if it is the first offer or strictly better; says whether it did.
    pub fn offer(&mut self, x: &[f64], e: Evaluation) -> bool {
        if !self.set || e.better_than(&self.eval) {
            self.x.copy_from_slice(x);
            self.eval = e;
            self.set = true;
            true
        } else {
            false
        }
    }

    /// Forgets the record (keeps the allocation).
    pub fn clear(&mut self) {
        self.eval = Evaluation::worst();
        self.set = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_from_seed;

    #[test]
    fn samples_stay_in_the_box_and_nan_goes_to_the_middle() {
        let mut rng = rng_from_seed(1);
        let b = Bound::new(-2.0, 3.0);
        for _ in 0..1000 {
            assert!(b.contains(b.sample(&mut rng)));
        }
        assert_eq!(Bound::new(1.0, 1.0).sample(&mut rng), 1.0);
        assert_eq!(into_bound(&b, f64::NAN), 0.5);
        assert_eq!(into_bound(&b, 9.0), 3.0);
    }

    #[test]
    fn best_so_far_takes_first_then_strictly_better() {
        let mut best = BestSoFar::new(1);
        assert!(best.offer(&[1.0], Evaluation::worst()));
        assert!(best.offer(&[2.0], Evaluation::new(3.0, 0.0)));
        assert!(!best.offer(&[3.0], Evaluation::new(3.0, 0.0)));
        assert!(!best.offer(&[4.0], Evaluation::new(f64::NAN, 0.0)));
        assert_eq!(best.x, vec![2.0]);
    }
}
