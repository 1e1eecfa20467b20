//! Fisher's exact test on a 2x2 table, two-sided.
//!
//! Compares two algorithms' success rates (feasible plans out of runs) where the counts
//! are too small for a chi-squared approximation. With the margins fixed, the top-left
//! cell `x` is hypergeometric:
//!
//! ```text
//! P(x) ∝ 1 / (x! (r1 - x)! (c1 - x)! (r2 - c1 + x)!)     r1 = a + b, r2 = c + d, c1 = a + c
//! p    = Σ P(x) over tables with P(x) <= P(a) (1 + 1e-7)
//! ```
//!
//! The relative tolerance 1e-7 (R's `fisher.test`, and older scipy) counts tables
//! whose probability equals the observed one up to rounding; current scipy uses 1e-14 with
//! its more exact pmf. The two agree unless two distinct tables' probabilities differ by
//! less than 1e-7 relative without being equal, which the cross-check's tables do not hit.
//!
//! Probabilities are computed as logarithms (`ln_gamma`) and normalized by their sum over
//! the whole support, rather than by the binomial coefficient, so counts in the thousands
//! neither overflow nor lose the normalizing constant to rounding, and a table at the mode
//! gets exactly `p = 1`. The cost is one pass over `min(r1, c1) - max(0, c1 - r2) + 1`
//! tables.

use statrs::function::gamma::ln_gamma;

/// Relative tolerance under which a table counts as no more likely than the observed one.
const RELATIVE_TOLERANCE: f64 = 1e-7;

/// Two-sided p-value of Fisher's exact test on the table `[[a, b], [c, d]]`.
///
/// Equals `scipy.stats.fisher_exact([[a, b], [c, d]]).pvalue`; a table with an empty row
/// or column gives 1. Runs in time linear in the smaller of the first row and first column
/// sums, so it is meant for counts of runs (up to millions), not for arbitrary `u64`s.
///
/// # Panics
/// If `a + b + c + d` overflows `u64`.
#[must_use]
pub fn fisher_exact(a: u64, b: u64, c: u64, d: u64) -> f64 {
    let sum = |x: u64, y: u64| {
        x.checked_add(y)
            .expect("fisher_exact: table total overflows u64")
    };
    let (row1, row2, col1) = (sum(a, b), sum(c, d), sum(a, c));
    // Checking the total once means `row2 + x` below (at most the total) cannot overflow.
    sum(row1, row2);
    // Tables with these margins: x = top-left cell in lo..=hi; the others follow.
    let (lo, hi) = (col1.saturating_sub(row2), row1.min(col1));
    let ln_weight = |x: u64| -> f64 {
        let cells = [x, row1 - x, col1 - x, row2 + x - col1];
        -cells.iter().map(|&k| ln_gamma(k as f64 + 1.0)).sum::<f64>()
    };
    let observed = ln_weight(a);
    let cutoff = observed + RELATIVE_TOLERANCE.ln_1p();
    let peak = (lo..=hi).map(ln_weight).fold(f64::NEG_INFINITY, f64::max);
    let (mut tail, mut all) = (0.0, 0.0);
    for x in lo..=hi {
        let w = ln_weight(x);
        let weight = (w - peak).exp();
        all += weight;
        if w <= cutoff {
            tail += weight;
        }
    }
    (tail / all).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs()
    }

    #[test]
    fn symmetric_small_table() {
        // Margins 4, 4 / 4, 4: P(x) = C(4,x) C(4,4-x) / 70 = 1, 16, 36, 16, 1 over 70.
        // Observed x = 3 (16/70): tables 0, 1, 3, 4 count: 34/70.
        assert!(close(fisher_exact(3, 1, 1, 3), 34.0 / 70.0, 1e-13));
        assert!(close(fisher_exact(1, 3, 3, 1), 34.0 / 70.0, 1e-13));
    }

    #[test]
    fn asymmetric_small_table() {
        // Margins r1 = 10, r2 = 6, c1 = 9: x in 3..=9, weights C(10,x) C(6,9-x):
        // 120·1, 210·6, 252·15, 210·20, 120·15, 45·6, 10·1 = 120, 1260, 3780, 4200, 1800,
        // 270, 10 (sum 11440 = C(16,9)). Observed x = 8 (270): 120 + 270 + 10 = 400.
        assert!(close(fisher_exact(8, 2, 1, 5), 400.0 / 11440.0, 1e-13));
    }

    #[test]
    fn mode_and_empty_margins_give_one() {
        assert_eq!(fisher_exact(2, 2, 2, 2), 1.0);
        assert_eq!(fisher_exact(0, 0, 3, 4), 1.0);
        assert_eq!(fisher_exact(0, 3, 0, 4), 1.0);
        assert_eq!(fisher_exact(0, 0, 0, 0), 1.0);
    }

    #[test]
    fn extreme_table() {
        // Only the observed and the mirror table (both weight 1 of C(20,10)) are as
        // extreme: p = 2 / 184756.
        assert!(close(fisher_exact(10, 0, 0, 10), 2.0 / 184_756.0, 1e-12));
    }

    #[test]
    fn large_counts_stay_finite() {
        let p = fisher_exact(1500, 1520, 1480, 1510);
        assert!(close(p, 0.897_386_589_132_165, 1e-9), "{p}");
        let p = fisher_exact(3000, 10, 10, 3000);
        assert!((0.0..1e-300).contains(&p), "{p}");
    }
}
