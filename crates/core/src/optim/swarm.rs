//! Small helpers every population-based optimizer here shares: bringing a moved coordinate back into its bound, and a best-so-far record.
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
