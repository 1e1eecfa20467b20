//! Wilcoxon rank-sum (Mann-Whitney U) test, two-sided: exact for small samples without
//! ties, normal approximation otherwise.
//!
//! **Which p-value.** Without ties and with n1 n2 <= [`EXACT_MAX_PAIRS`] (e.g. 50 runs
//! against 50), the p-value is exact: the null distribution of U is counted over all
//! C(n, n1) equally likely rank assignments (Mann & Whitney 1947, Ann. Math.
//! Stat. 18(1):50-60, doi:10.1214/aoms/1177730491), and
//! `p = min(1, 2 P(U >= max(U, n1 n2 - U)))`, which is scipy's `method="exact"`. With ties
//! (which the exact count does not cover) or larger samples, the normal approximation
//! below, which is accurate there. [`RankSumTest::method`] says which was used. The first
//! build always used the normal approximation, which is off by a factor of 2-3 for n = 3.
//!
//! The comparison of two algorithms' costs over independent runs: no assumption of
//! normality, and failed runs (`+inf`) simply rank last. With `n1`, `n2` the sample
//! sizes, `n = n1 + n2`, `R1` the sum of `x`'s average ranks in the pooled sample and
//! `t` the sizes of tie groups:
//!
//! ```text
//! U  = R1 - n1 (n1 + 1) / 2                      (scipy's statistic for x)
//! mu = n1 n2 / 2
//! s² = n1 n2 / 12 · ((n + 1) - Σ(t³ - t) / (n (n - 1)))
//! z  = sign(U - mu) · max(|U - mu| - 1/2, 0) / s
//! p  = min(1, 2 Φ(-|z|)) = min(1, P(χ²(1) >= z²))
//! ```
//!
//! This is `scipy.stats.mannwhitneyu(x, y, alternative='two-sided',
//! method='asymptotic', use_continuity=True)` (its `_get_mwu_z`), whose p-value comes out
//! the same; scipy's own z is not returned by it and is computed from `max(U1, U2)`, so
//! it is always `|z|` here, less the sign. Reference: Mann & Whitney 1947; the tie
//! correction as in the "Normal approximation and tie correction" section of Wikipedia's
//! Mann-Whitney U test article, which scipy follows.
//!
//! The p-value is computed in its chi-squared form (z² of a standard normal is χ²(1)):
//! statrs's normal CDF goes through an `erfc` that is off by up to 1e-10 relative for
//! arguments near 0.5-0.75, while its χ² survival function (regularized incomplete gamma)
//! agrees with scipy to about 1e-14 over the whole range.
//!

use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::json_f64;
use super::ranks::{average_ranks, Ranked};

/// Largest n1 n2 for which the exact distribution is counted (the count costs about
/// n n1 n1 n2 / 2 operations: 1.25e7 at 50 against 50).
pub const EXACT_MAX_PAIRS: usize = 2500;

/// How the p-value of a [`RankSumTest`] was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum RankSumMethod {
    /// The exact null distribution (no ties, n1 n2 <= [`EXACT_MAX_PAIRS`]).
    Exact,
    /// Normal approximation with tie and continuity corrections.
    Normal,
}

impl RankSumMethod {
    /// `exact` or `normal`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::Normal => "normal",
        }
    }
}

/// Result of [`rank_sum`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RankSumTest {
    /// Mann-Whitney U of `x`: the number of pairs `(xi, yj)` with `xi > yj`, ties counted
    /// one half. Ranges over `0..=n1 n2`; `n1 n2 / 2` means no shift.
    #[serde(with = "json_f64")]
    pub u: f64,
    /// Standardized U with tie and continuity corrections; positive when `x` tends to be
    /// larger than `y` (for costs: `x` is worse). 0 when all values are equal.
    #[serde(with = "json_f64")]
    pub z: f64,
    /// Two-sided p-value, in `[0, 1]`.
    #[serde(with = "json_f64")]
    pub p_value: f64,
    /// Whether the p-value is exact or from the normal approximation.
    pub method: RankSumMethod,
}

/// P(U >= u) under the null for samples of sizes `m` and `n` without ties, `u` an integer.
/// Counts rank sums of m-subsets of 1..=m+n by dynamic programming (counts in f64, then
/// divided by C(m + n, m): relative error about 1e-15).
#[must_use]
pub fn exact_upper_tail(m: usize, n: usize, u: usize) -> f64 {
    let max_u = m * n;
    if u > max_u {
        return 0.0;
    }
    // ways[k][s]: subsets of size k of the items seen so far with U-contribution s, where
    // an item at position i (0-based) chosen as the k-th smallest adds i - (k - 1).
    let mut ways = vec![vec![0.0_f64; max_u + 1]; m + 1];
    ways[0][0] = 1.0;
    for i in 0..m + n {
        for k in (1..=m.min(i + 1)).rev() {
            let add = i + 1 - k;
            if add > n {
                continue;
            }
            let (lower, upper) = ways.split_at_mut(k);
            let (from, to) = (&lower[k - 1], &mut upper[0]);
            for s in (0..=max_u - add).rev() {
                if from[s] != 0.0 {
                    to[s + add] += from[s];
                }
            }
        }
    }
    let total: f64 = ways[m].iter().sum();
    ways[m][u..].iter().sum::<f64>() / total
}

/// Two-sided rank-sum test of `x` against `y`.
///
/// `None` if either sample is empty or holds a NaN. `+inf` values rank after every finite
/// value and tie with each other. When every value is equal the variance is zero and the
/// test reports `z = 0`, `p = 1` (scipy reaches `p = 1` by clipping).
#[must_use]
pub fn rank_sum(x: &[f64], y: &[f64]) -> Option<RankSumTest> {
    if x.is_empty() || y.is_empty() || x.iter().chain(y).any(|v| v.is_nan()) {
        return None;
    }
    let (n1, n2) = (x.len() as f64, y.len() as f64);
    let n = n1 + n2;
    let pooled: Vec<f64> = x.iter().chain(y).copied().collect();
    let Ranked { ranks, tie_term } = average_ranks(&pooled);
    // Ranks are multiples of 1/2, so R1, U and U - mu are exact.
    let r1: f64 = ranks[..x.len()].iter().sum();
    let u = r1 - n1 * (n1 + 1.0) / 2.0;
    let mu = n1 * n2 / 2.0;
    // n >= 2 here, so n (n - 1) > 0; with every value tied, tie_term = n³ - n and the
    // bracket is exactly 0 (integer arithmetic in f64).
    let variance = n1 * n2 / 12.0 * ((n + 1.0) - tie_term / (n * (n - 1.0)));
    if variance <= 0.0 {
        return Some(RankSumTest {
            u,
            z: 0.0,
            p_value: 1.0,
            method: RankSumMethod::Normal,
        });
    }
    let shift = u - mu;
    // The continuity correction moves |U - mu| half a step towards 0; at U = mu scipy's
    // numerator becomes -1/2 and its p-value (> 1) is clipped to 1, which z = 0 gives.
    let z = shift.signum() * (shift.abs() - 0.5).max(0.0) / variance.sqrt();
    if tie_term == 0.0 && x.len() * y.len() <= EXACT_MAX_PAIRS {
        // Without ties U is an integer; the larger of U and n1 n2 - U gives the upper tail.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let big = u.max(n1 * n2 - u).round() as usize;
        let p_value = (2.0 * exact_upper_tail(x.len(), y.len(), big)).min(1.0);
        return Some(RankSumTest {
            u,
            z,
            p_value,
            method: RankSumMethod::Exact,
        });
    }
    let chi2 = ChiSquared::new(1.0).expect("one degree of freedom is valid");
    let p_value = chi2.sf(z * z).min(1.0);
    Some(RankSumTest {
        u,
        z,
        p_value,
        method: RankSumMethod::Normal,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * b.abs().max(1e-300)
    }

    #[test]
    fn empty_or_nan_gives_none() {
        assert_eq!(rank_sum(&[], &[1.0]), None);
        assert_eq!(rank_sum(&[1.0], &[]), None);
        assert_eq!(rank_sum(&[1.0, f64::NAN], &[2.0]), None);
    }

    #[test]
    fn separated_small_samples_get_the_exact_p() {
        // x ranks 1, 2, 3: U = 0. Of the C(5, 3) = 10 assignments one gives U = 0 and one
        // U = 6, so p = 2/10 exactly (the normal approximation says 0.149).
        let t = rank_sum(&[1.0, 2.0, 3.0], &[4.0, 5.0]).unwrap();
        assert_eq!(t.u, 0.0);
        assert_eq!(t.method, RankSumMethod::Exact);
        assert!(close(t.z, -2.5 / 3.0_f64.sqrt(), 1e-15));
        assert!(close(t.p_value, 0.2, 1e-14), "{}", t.p_value);
        // Swapping the samples mirrors U and z and keeps p.
        let s = rank_sum(&[4.0, 5.0], &[1.0, 2.0, 3.0]).unwrap();
        assert_eq!((s.u, s.z, s.p_value), (6.0, -t.z, t.p_value));
    }

    #[test]
    fn the_exact_tail_sums_to_one_and_is_symmetric() {
        for (m, n) in [(1, 1), (3, 2), (5, 8), (12, 9)] {
            assert!(close(exact_upper_tail(m, n, 0), 1.0, 1e-14));
            assert_eq!(exact_upper_tail(m, n, m * n + 1), 0.0);
            for u in 0..=m * n {
                // P(U >= u) = P(U <= mn - u) = 1 - P(U >= mn - u + 1).
                let mirrored = 1.0 - exact_upper_tail(m, n, m * n - u + 1);
                assert!((exact_upper_tail(m, n, u) - mirrored).abs() < 1e-13);
            }
        }
        // Two samples of 2: U takes 0, 1, 2, 2, 3, 4 over the six assignments.
        assert!(close(exact_upper_tail(2, 2, 3), 2.0 / 6.0, 1e-15));
    }

    #[test]
    fn large_samples_use_the_normal_approximation() {
        let x: Vec<f64> = (0..60).map(f64::from).collect();
        let y: Vec<f64> = (0..60).map(|v| f64::from(v) + 30.5).collect();
        assert_eq!(rank_sum(&x, &y).unwrap().method, RankSumMethod::Normal);
    }

    #[test]
    fn ties_use_average_ranks_and_the_tie_correction() {
        // Pooled 1, 2, 2, 2, 3, 4, 4: ranks 1, 3, 3, 3, 5, 6.5, 6.5; R1 = 12, U = 2,
        // mu = 6, tie term 24 + 6 = 30, s² = 8 - 30/42 = 51/7, z = -3.5/√(51/7);
        // scipy: p = 0.19474217283959172.
        let t = rank_sum(&[1.0, 2.0, 2.0, 3.0], &[2.0, 4.0, 4.0]).unwrap();
        assert_eq!(t.u, 2.0);
        assert_eq!(t.method, RankSumMethod::Normal);
        assert!(close(t.z, -3.5 / (51.0_f64 / 7.0).sqrt(), 1e-15));
        assert!(
            close(t.p_value, 0.194_742_172_839_591_72, 1e-12),
            "{}",
            t.p_value
        );
    }

    #[test]
    fn all_equal_gives_p_one() {
        let t = rank_sum(&[1.0, 1.0], &[1.0, 1.0, 1.0]).unwrap();
        assert_eq!((t.u, t.z, t.p_value), (3.0, 0.0, 1.0));
        let t = rank_sum(&[f64::INFINITY], &[f64::INFINITY]).unwrap();
        assert_eq!((t.u, t.p_value), (0.5, 1.0));
    }

    #[test]
    fn no_shift_gives_p_one() {
        // U = mu = 2: no shift at all, exactly or approximately.
        let t = rank_sum(&[1.0, 4.0], &[2.0, 3.0]).unwrap();
        assert_eq!((t.u, t.z, t.p_value), (2.0, 0.0, 1.0));
    }

    #[test]
    fn infinity_ranks_last() {
        // x = {inf, 0}: inf beats both y values, 0 beats none: U = 2.
        let t = rank_sum(&[f64::INFINITY, 0.0], &[1.0, 2.0]).unwrap();
        assert_eq!(t.u, 2.0);
        let t = rank_sum(&[f64::INFINITY, 5.0], &[1.0, 2.0]).unwrap();
        assert_eq!(t.u, 4.0);
        assert!(t.z > 0.0);
    }
}
