//! Long line series thinned to what their pixels show (M4).
//!
//! Why: a run under `--time-limit` or a large `--evaluations` takes hundreds of thousands
//! of iterations (a 5-UAV plan makes about 4,700 a second), and a line of one vertex per
//! iteration made a convergence SVG of 9 MB after 40 s, drawn as slowly as it is large.
//! Run traces are now bounded (`swarmplan_core::optim::thinned`), but a bounded trace
//! still holds up to 65,537 rows, dozens per pixel column of the figure. M4 (Jugel, Jerzak, Hackenbroich and Markl, "M4: A
//! Visualization-Oriented Time Series Data Aggregation", PVLDB 7(10):797-808, 2014,
//! doi:10.14778/2732951.2732953) keeps, of the consecutive vertices that fall in one
//! pixel column, the first, the last, the lowest and the highest, in their order: the
//! line through them enters and leaves the column where the full line does and spans the
//! same rows inside it. For a one-pixel line that is the same picture; our lines are two
//! and three pixels wide, whose joins inside a crowded column are filled a little
//! differently (docs/performance.md: 819 of 1,080,000 pixels of a 187,000-iteration
//! figure, all in its first columns). A series is thinned only when it has more than
//! [`KEEP_ALL_PER_COLUMN`] vertices per column of the plot, so runs of ordinary length
//! (the default budget's 3,905 iterations) draw every vertex, as before.

/// Series with at most this many vertices per pixel column of the plot are drawn whole.
pub(crate) const KEEP_ALL_PER_COLUMN: usize = 4;

/// Whether a series of `len` vertices over a plot `columns` pixels wide is thinned.
pub(crate) fn thins(len: usize, columns: u32) -> bool {
    len > KEEP_ALL_PER_COLUMN * columns.max(1) as usize
}

/// Streams vertices in order and keeps M4's four per pixel column.
pub(crate) struct M4<F> {
    column_of: F,
    bucket: Option<Bucket>,
    out: Vec<(f64, f64)>,
}

/// The vertices of one column so far: (sequence number, vertex) of the first, the lowest,
/// the highest and the last.
#[derive(Clone, Copy)]
struct Bucket {
    column: i32,
    first: (usize, (f64, f64)),
    low: (usize, (f64, f64)),
    high: (usize, (f64, f64)),
    last: (usize, (f64, f64)),
}

impl<F: Fn(f64, f64) -> i32> M4<F> {
    /// `column_of(x, y)` is the pixel column the chart draws vertex (x, y) in.
    pub(crate) fn new(column_of: F) -> Self {
        Self {
            column_of,
            bucket: None,
            out: Vec::new(),
        }
    }

    /// Adds the `seq`-th vertex of the series (sequence numbers increase).
    pub(crate) fn push(&mut self, seq: usize, p: (f64, f64)) {
        let column = (self.column_of)(p.0, p.1);
        match &mut self.bucket {
            Some(b) if b.column == column => {
                if p.1 < b.low.1 .1 {
                    b.low = (seq, p);
                }
                if p.1 > b.high.1 .1 {
                    b.high = (seq, p);
                }
                b.last = (seq, p);
            }
            _ => {
                self.flush();
                self.bucket = Some(Bucket {
                    column,
                    first: (seq, p),
                    low: (seq, p),
                    high: (seq, p),
                    last: (seq, p),
                });
            }
        }
    }

    /// The kept vertices, in order.
    pub(crate) fn finish(mut self) -> Vec<(f64, f64)> {
        self.flush();
        self.out
    }

    fn flush(&mut self) {
        let Some(b) = self.bucket.take() else {
            return;
        };
        let mut kept = [b.first, b.low, b.high, b.last];
        kept.sort_by_key(|(seq, _)| *seq);
        let mut previous = None;
        for (seq, p) in kept {
            if previous != Some(seq) {
                self.out.push(p);
                previous = Some(seq);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A deterministic wiggly series (no RNG dependency needed for this).
    fn series(n: usize) -> Vec<(f64, f64)> {
        (0..n)
            .map(|k| {
                let x = k as f64;
                (
                    x,
                    (x * 0.37).sin() * 50.0 + (x * 0.013).cos() * 200.0 - x * 0.01,
                )
            })
            .collect()
    }

    #[test]
    fn each_column_keeps_its_ends_and_extremes_in_order() {
        let points = series(10_000);
        let column = |x: f64, _y: f64| (x / 37.0).floor() as i32;
        let mut m4 = M4::new(column);
        for (k, p) in points.iter().enumerate() {
            m4.push(k, *p);
        }
        let kept = m4.finish();
        assert!(kept.len() < points.len() / 5, "{} kept", kept.len());
        // Order is kept (x increases with the sequence here).
        assert!(kept.windows(2).all(|w| w[0].0 < w[1].0));
        let columns = |ps: &[(f64, f64)]| {
            let mut by: std::collections::BTreeMap<i32, Vec<(f64, f64)>> = Default::default();
            for p in ps {
                by.entry(column(p.0, p.1)).or_default().push(*p);
            }
            by
        };
        let (all, thin) = (columns(&points), columns(&kept));
        assert_eq!(all.len(), thin.len());
        for ((c, a), (d, t)) in all.iter().zip(&thin) {
            assert_eq!(c, d);
            assert!(t.len() <= 4);
            assert_eq!(a.first(), t.first());
            assert_eq!(a.last(), t.last());
            let low = |v: &[(f64, f64)]| v.iter().map(|p| p.1).fold(f64::INFINITY, f64::min);
            let high = |v: &[(f64, f64)]| v.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max);
            assert_eq!(low(a), low(t));
            assert_eq!(high(a), high(t));
        }
    }

    #[test]
    fn a_column_of_one_vertex_keeps_it_once() {
        let mut m4 = M4::new(|x: f64, _| x as i32);
        for (k, x) in [0.0, 1.0, 2.0].into_iter().enumerate() {
            m4.push(k, (x, x * 2.0));
        }
        assert_eq!(m4.finish(), vec![(0.0, 0.0), (1.0, 2.0), (2.0, 4.0)]);
    }

    #[test]
    fn ordinary_lengths_are_not_thinned() {
        assert!(!thins(3_905, 1_000));
        assert!(!thins(4_000, 1_000));
        assert!(thins(4_001, 1_000));
        assert!(thins(5, 0));
    }
}
