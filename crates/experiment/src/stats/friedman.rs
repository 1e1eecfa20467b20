//! Friedman test: do k algorithms differ when each is run on the same n blocks?
//!
//! A block is one scenario (or one seed shared by all algorithms); within a block the k
//! costs are ranked (lowest cost = rank 1, ties averaged), which removes the block's own
//! difficulty. With `R_j` the rank sum of treatment j and `t` the sizes of tie groups
//! within blocks (Friedman 1937, J. Am. Stat. Assoc. 32(200):675-701,
//! doi:10.1080/01621459.1937.10503522; tie correction as in scipy and Conover, "Practical
//! Nonparametric Statistics"):
//!
//! ```text
//! Q = (12 / (n k (k + 1)) Σ R_j² - 3 n (k + 1)) / (1 - Σ(t³ - t) / (n k (k² - 1)))
//! p = P(χ²(k - 1) >= Q)
//! ```
//!
//! which is `scipy.stats.friedmanchisquare(*columns)`. The mean ranks are what a
//! critical-difference diagram plots, so they are returned with the test.
//!
//! Where this departs from scipy, and why:
//! - k = 2 is accepted (scipy asks for k >= 3); the formula holds, though with two
//!   treatments a paired test (e.g. the sign test) is the usual choice.
//! - When every block is all ties the statistic is 0/0; scipy returns NaN, this returns
//!   `statistic = 0`, `p_value = 1` (no evidence of a difference), like [`super::rank_sum`]
//!   on all-equal data, so a results table or a Holm adjustment needs no special case.
//! - Rounding can leave `Σ R_j²` a hair below its minimum; the statistic is clamped at 0
//!   where scipy can report a tiny negative number.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ChiSquared, ContinuousCDF};

use super::json_f64;
use super::ranks::average_ranks;

/// Result of [`friedman`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FriedmanTest {
    /// Friedman's chi-squared statistic Q, tie-corrected; >= 0.
    #[serde(with = "json_f64")]
    pub statistic: f64,
    /// Degrees of freedom of the chi-squared approximation, k - 1.
    pub df: usize,
    /// P(χ²(df) >= statistic).
    #[serde(with = "json_f64")]
    pub p_value: f64,
    /// Mean rank of each treatment over the blocks, in column order (1 = always best);
    /// they sum to k (k + 1) / 2.
    #[serde(with = "json_f64::vec")]
    pub mean_ranks: Vec<f64>,
}

/// Friedman test over `blocks`, each one row of k treatment values (column j is treatment
/// j in every block).
///
/// `None` if there are fewer than 2 blocks or fewer than 2 treatments, if the blocks have
/// different lengths, or if a value is NaN. `+inf` ranks last within its block and ties
/// with other `+inf`s.
#[must_use]
pub fn friedman(blocks: &[Vec<f64>]) -> Option<FriedmanTest> {
    let k = blocks.first()?.len();
    if blocks.len() < 2
        || k < 2
        || blocks
            .iter()
            .any(|b| b.len() != k || b.iter().any(|v| v.is_nan()))
    {
        return None;
    }
    let mut rank_sums = vec![0.0; k];
    let mut tie_term = 0.0;
    for block in blocks {
        let ranked = average_ranks(block);
        for (sum, rank) in rank_sums.iter_mut().zip(&ranked.ranks) {
            *sum += rank;
        }
        tie_term += ranked.tie_term;
    }
    let (n, kf) = (blocks.len() as f64, k as f64);
    let mean_ranks = rank_sums.iter().map(|r| r / n).collect();
    let df = k - 1;
    // Σ(t³ - t) and n k (k² - 1) are integers held exactly, so all-ties gives exactly 0.
    let correction = 1.0 - tie_term / (kf * (kf * kf - 1.0) * n);
    if correction <= 0.0 {
        return Some(FriedmanTest {
            statistic: 0.0,
            df,
            p_value: 1.0,
            mean_ranks,
        });
    }
    let ssbn: f64 = rank_sums.iter().map(|r| r * r).sum();
    let statistic =
        ((12.0 / (kf * n * (kf + 1.0)) * ssbn - 3.0 * n * (kf + 1.0)) / correction).max(0.0);
    let chi2 = ChiSquared::new(df as f64).expect("k >= 2 gives positive degrees of freedom");
    Some(FriedmanTest {
        statistic,
        df,
        p_value: chi2.sf(statistic),
        mean_ranks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invalid_designs_give_none() {
        assert_eq!(friedman(&[]), None);
        assert_eq!(friedman(&[vec![1.0, 2.0, 3.0]]), None);
        assert_eq!(friedman(&[vec![1.0], vec![2.0]]), None);
        assert_eq!(friedman(&[vec![1.0, 2.0], vec![2.0]]), None);
        assert_eq!(friedman(&[vec![1.0, 2.0], vec![f64::NAN, 1.0]]), None);
    }

    #[test]
    fn consistent_ordering() {
        // 4 blocks, each ranking (1, 2, 3): R = 4, 8, 12, Σ R² = 224,
        // Q = 12/48 · 224 - 48 = 8, p = exp(-8/2) for df 2.
        let blocks = vec![vec![1.0, 2.0, 3.0]; 4];
        let t = friedman(&blocks).unwrap();
        assert_eq!(t.df, 2);
        assert_eq!(t.statistic, 8.0);
        assert!((t.p_value - (-4.0_f64).exp()).abs() < 1e-15);
        assert_eq!(t.mean_ranks, vec![1.0, 2.0, 3.0]);
    }

    #[test]
    fn latin_square_shows_no_difference() {
        let blocks = vec![
            vec![1.0, 2.0, 3.0],
            vec![2.0, 3.0, 1.0],
            vec![3.0, 1.0, 2.0],
        ];
        let t = friedman(&blocks).unwrap();
        assert_eq!((t.statistic, t.p_value), (0.0, 1.0));
        assert_eq!(t.mean_ranks, vec![2.0, 2.0, 2.0]);
    }

    #[test]
    fn ties_are_corrected() {
        // Blocks (1, 1, 2) and (1, 2, 3): ranks (1.5, 1.5, 3), (1, 2, 3); R = 2.5, 3.5, 6,
        // Σ R² = 54.5; uncorrected 12/24 · 54.5 - 24 = 3.25; ties Σ(t³ - t) = 6,
        // correction 1 - 6/(3 · 8 · 2) = 0.875; Q = 3.25 / 0.875 = 26/7.
        let blocks = vec![vec![1.0, 1.0, 2.0], vec![1.0, 2.0, 3.0]];
        let t = friedman(&blocks).unwrap();
        assert!((t.statistic - 26.0 / 7.0).abs() < 1e-14);
        assert!((t.p_value - (-13.0_f64 / 7.0).exp()).abs() < 1e-14);
        assert_eq!(t.mean_ranks, vec![1.25, 1.75, 3.0]);
    }

    #[test]
    fn all_ties_give_zero_and_p_one_with_mean_ranks() {
        let blocks = vec![vec![f64::INFINITY; 3]; 4];
        let t = friedman(&blocks).unwrap();
        assert_eq!((t.statistic, t.p_value), (0.0, 1.0));
        assert_eq!(t.mean_ranks, vec![2.0, 2.0, 2.0]);
    }

    #[test]
    fn two_treatments_and_infinity() {
        // k = 2, 3 blocks, the second treatment always worse (one run failed): R = 3, 6,
        // Q = 12/18 · 45 - 27 = 3, df 1.
        let blocks = vec![vec![1.0, 2.0], vec![5.0, f64::INFINITY], vec![0.0, 0.5]];
        let t = friedman(&blocks).unwrap();
        assert_eq!(t.df, 1);
        assert!((t.statistic - 3.0).abs() < 1e-14);
        assert!(
            (t.p_value - 0.083_264_516_663_550_42).abs() < 1e-12,
            "{}",
            t.p_value
        );
    }
}
