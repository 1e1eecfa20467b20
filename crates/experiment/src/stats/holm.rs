//! Holm-Bonferroni adjustment of p-values for multiple comparisons.
//!
//! Comparing one algorithm against m others (or all pairs) runs m tests; Holm's step-down
//! procedure controls the family-wise error rate without Bonferroni's loss of power and
//! without assumptions on how the tests depend on each other (Holm 1979, Scand. J. Stat. 6(2):65-70,
//! JSTOR 4615733). With the
//! p-values sorted ascending, `p(1) <= ... <= p(m)`:
//!
//! ```text
//! adjusted(i) = min(1, max over j <= i of (m - j + 1) p(j))
//! ```
//!
//! which is statsmodels' `multipletests(p, method='holm')[1]` and R's
//! `p.adjust(p, "holm")`. Rejecting where `adjusted <= alpha` is Holm's test at level
//! alpha.

/// Holm-adjusted p-values, in the order of `p`.
///
/// Entries should be p-values in `[0, 1]`. A NaN entry (a test that could not be run)
/// stays NaN and does not count towards m, as in R's `p.adjust`. The result is monotone
/// in the sorted order, never below the raw p-value, and at most 1.
#[must_use]
pub fn holm(p: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..p.len()).filter(|&i| !p[i].is_nan()).collect();
    order.sort_by(|&i, &j| p[i].total_cmp(&p[j]));
    let m = order.len();
    let mut adjusted = vec![f64::NAN; p.len()];
    let mut running_max = 0.0_f64;
    for (j, &i) in order.iter().enumerate() {
        running_max = running_max.max(((m - j) as f64 * p[i]).min(1.0));
        adjusted[i] = running_max;
    }
    adjusted
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_and_single() {
        assert!(holm(&[]).is_empty());
        assert_eq!(holm(&[0.03]), vec![0.03]);
    }

    #[test]
    fn step_down_multipliers_in_original_order() {
        // Sorted 0.01, 0.02, 0.04 with multipliers 3, 2, 1: 0.03, 0.04, 0.04 (monotone).
        let a = holm(&[0.04, 0.01, 0.02]);
        let expected = [0.04, 0.03, 0.04];
        for (got, want) in a.iter().zip(expected) {
            assert!((got - want).abs() < 1e-15, "{a:?}");
        }
    }

    #[test]
    fn monotone_and_capped_at_one() {
        // Sorted 0.005, 0.3, 0.5, 0.6: 0.02, 0.9, min(1, 1.0) = 1, max(1, 0.6) = 1.
        let a = holm(&[0.5, 0.005, 0.6, 0.3]);
        assert_eq!(a[1], 0.02);
        assert!((a[3] - 0.9).abs() < 1e-15);
        assert_eq!((a[0], a[2]), (1.0, 1.0));
    }

    #[test]
    fn ties_get_the_same_adjustment() {
        assert_eq!(holm(&[0.01, 0.01]), vec![0.02, 0.02]);
    }

    #[test]
    fn nan_is_kept_and_not_counted() {
        let a = holm(&[0.01, f64::NAN, 0.02]);
        assert_eq!(a[0], 0.02);
        assert!(a[1].is_nan());
        assert_eq!(a[2], 0.02);
    }
}
