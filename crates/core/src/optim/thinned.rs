//! A run's trace kept in bounded memory: every iteration up to a cap, then every s-th.
//!
//! Why: a run under a wall-clock limit or a large evaluation budget makes hundreds of
//! thousands of iterations (a 5-UAV plan about 4,700 a second), and its trace (one record
//! per iteration, and in `plan` one row of per-UAV costs) grew by 32 to 140 bytes an
//! iteration, about half a gigabyte for an hour's run, written out again as a
//! `convergence.csv` of gigabytes. Runs within the cap ([`TRACE_CAP`] iterations; the
//! default budgets make a few thousand) keep every record, as before. Past it the stride s
//! doubles (1, 2, 4, ...) and only iterations that are multiples of s stay, so the trace
//! holds about `TRACE_CAP / 2` to `TRACE_CAP + 1` records, evenly spread, whatever the
//! run's length. Kept besides, whatever the stride: the last record (the run's end) and the first
//! record whose best is feasible (so the evaluations to first feasibility stay exact).
//!
//! The rule depends only on the iteration numbers and the records' feasibility, so two
//! traces of one run (the loop's records, `plan`'s per-UAV rows) keep the same iterations
//! and stay aligned row by row.

use super::IterationRecord;

/// The last iteration a trace keeps whole: it holds iterations 0 to `TRACE_CAP` (that many
/// records plus one) before its stride doubles.
pub const TRACE_CAP: usize = 1 << 16;

/// Values of a run, one per iteration offered, thinned as the module describes.
#[derive(Debug, Clone)]
pub struct Thinned<T> {
    /// (iteration, kept whatever the stride, value), in offered order.
    kept: Vec<(usize, bool, T)>,
    /// The latest value, when its iteration is not on the stride (kept until a later one).
    latest: Option<(usize, T)>,
    stride: usize,
    cap: usize,
    seen_feasible: bool,
}

impl<T> Default for Thinned<T> {
    fn default() -> Self {
        Self::with_cap(TRACE_CAP)
    }
}

impl<T> Thinned<T> {
    /// A trace that keeps iterations 0 to `cap` (at least 2) whole, and then at most
    /// `cap + 1` records on its stride (and the latest).
    #[must_use]
    pub fn with_cap(cap: usize) -> Self {
        Self {
            kept: Vec::new(),
            latest: None,
            stride: 1,
            cap: cap.max(2),
            seen_feasible: false,
        }
    }

    /// Room for `records` (at most the cap) without reallocating.
    pub fn reserve(&mut self, records: usize) {
        self.kept.reserve(records.min(self.cap + 1));
    }

    /// Offers `value`, the state after `rec.iteration` (iterations offered in increasing
    /// order).
    pub fn push(&mut self, rec: &IterationRecord, value: T) {
        let first_feasible = !self.seen_feasible && rec.best_violation == 0.0;
        self.seen_feasible |= first_feasible;
        let kept = |stride: usize| first_feasible || rec.iteration.is_multiple_of(stride);
        if !kept(self.stride) {
            self.latest = Some((rec.iteration, value));
            return;
        }
        if self.kept.len() > self.cap {
            // Full (iterations 0 to the cap at stride 1): double the stride first, so that
            // a record off the new stride becomes the latest instead of being dropped.
            self.stride *= 2;
            let stride = self.stride;
            self.kept
                .retain(|(k, pinned, _)| *pinned || k.is_multiple_of(stride));
            if !kept(stride) {
                self.latest = Some((rec.iteration, value));
                return;
            }
        }
        self.latest = None;
        self.kept.push((rec.iteration, first_feasible, value));
    }

    /// Keeps only every `stride`-th iteration from now on (1 while the trace is within its
    /// cap).
    #[must_use]
    pub fn stride(&self) -> usize {
        self.stride
    }

    /// The kept values in iteration order, the latest offered one last.
    #[must_use]
    pub fn into_vec(self) -> Vec<T> {
        let mut out: Vec<T> = self.kept.into_iter().map(|(_, _, v)| v).collect();
        out.extend(self.latest.map(|(_, v)| v));
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(iteration: usize, feasible_from: usize) -> IterationRecord {
        IterationRecord {
            iteration,
            evaluations: 10 * iteration as u64,
            best_cost: 1.0,
            best_violation: if iteration >= feasible_from { 0.0 } else { 1.0 },
        }
    }

    fn kept(n: usize, cap: usize, feasible_from: usize) -> Vec<usize> {
        let mut t = Thinned::with_cap(cap);
        for k in 0..n {
            t.push(&rec(k, feasible_from), k);
        }
        t.into_vec()
    }

    #[test]
    fn a_trace_within_its_cap_keeps_every_iteration() {
        assert_eq!(kept(50, 64, 7), (0..50).collect::<Vec<_>>());
        // Iterations 0 to the cap: every one.
        assert_eq!(kept(65, 64, usize::MAX), (0..65).collect::<Vec<_>>());
        assert_ne!(kept(66, 64, usize::MAX), (0..66).collect::<Vec<_>>());
    }

    #[test]
    fn a_long_trace_keeps_an_even_stride_its_end_and_its_first_feasible_iteration() {
        let (cap, n) = (64, 100_003);
        let k = kept(n, cap, 777);
        assert!(k.len() <= cap + 2, "{} records", k.len());
        assert!(k.len() >= cap / 2, "{} records", k.len());
        assert_eq!(k.first(), Some(&0));
        assert_eq!(k.last(), Some(&(n - 1)));
        assert!(k.contains(&777), "the first feasible iteration is kept");
        assert!(k.windows(2).all(|w| w[0] < w[1]), "in order");
        // Between the pinned and the last, one stride apart.
        let stride = *k.iter().filter(|&&i| i != 777 && i != 0).min().unwrap();
        assert!(stride.is_power_of_two() && stride > 1);
        let on_stride: Vec<usize> = k[..k.len() - 1]
            .iter()
            .copied()
            .filter(|&i| i != 777)
            .collect();
        assert!(on_stride.windows(2).all(|w| w[1] - w[0] == stride));
    }

    #[test]
    fn every_length_ends_at_its_last_iteration_and_keeps_its_first_feasible() {
        // The record that fills the trace can fall off the doubled stride (the pinned
        // record shifts the count): it must stay as the latest, not vanish.
        for feasible_from in [0, 3, 777, usize::MAX] {
            let mut t = Thinned::with_cap(16);
            for k in 0..3_000 {
                t.push(&rec(k, feasible_from), k);
                let v = t.clone().into_vec();
                assert_eq!(
                    v.last(),
                    Some(&k),
                    "after {k} (feasible from {feasible_from})"
                );
                assert!(v.len() <= 16 + 2, "{} records", v.len());
                if feasible_from <= k {
                    assert!(v.contains(&feasible_from));
                }
            }
        }
        assert_eq!(kept(1_009, 64, 777).last(), Some(&1_008));
    }
}
