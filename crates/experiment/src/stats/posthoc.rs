//! Which pairs differ, once Friedman's test says the k methods do not all perform alike.
//!
//! The post-hoc test on mean ranks of Demšar (2006, "Statistical comparisons of classifiers
//! over multiple data sets", J. Mach. Learn. Res. 7:1-30, Sect. 3.2.2): with N blocks and
//! mean ranks R_i, R_j of methods i and j,
//!
//! ```text
//! z = (R_i - R_j) / sqrt(k (k + 1) / (6 N)),      p = 2 (1 - Φ(|z|))
//! ```
//!
//! and the k (k - 1) / 2 p-values are adjusted together with Holm's step-down procedure, as
//! García & Herrera (2008, J. Mach. Learn. Res. 9:2677-2694) recommend for all pairwise
//! comparisons. The statistic uses only the mean ranks, so a pair's verdict depends on the
//! other methods in the comparison (Benavoli, Corani & Mangili 2016, J. Mach. Learn. Res.
//! 17(5):1-10); the tables that print it also give the per-instance values, so a reader can
//! run a paired test of their choice.

use serde::{Deserialize, Serialize};
use statrs::distribution::{ContinuousCDF, Normal};

use super::holm;
use super::json_f64;

/// One pair (a, b) of methods, by their column in the mean ranks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PairwiseRankTest {
    /// Column of the first method.
    pub a: usize,
    /// Column of the second method (`a < b`).
    pub b: usize,
    /// (R_a - R_b) / SE: negative when a ranks better (lower) than b.
    #[serde(with = "json_f64")]
    pub z: f64,
    /// Two-sided, from the standard normal.
    #[serde(with = "json_f64")]
    pub p_value: f64,
    /// Holm-adjusted over all pairs.
    #[serde(with = "json_f64")]
    pub p_holm: f64,
}

/// All pairs a < b of the `mean_ranks` of k methods over `blocks` blocks, Holm-adjusted.
/// Empty for fewer than 2 methods or no block.
#[must_use]
pub fn mean_rank_posthoc(mean_ranks: &[f64], blocks: usize) -> Vec<PairwiseRankTest> {
    let k = mean_ranks.len();
    if k < 2 || blocks == 0 {
        return Vec::new();
    }
    let se = ((k * (k + 1)) as f64 / (6.0 * blocks as f64)).sqrt();
    let normal = Normal::standard();
    let mut pairs: Vec<PairwiseRankTest> = Vec::with_capacity(k * (k - 1) / 2);
    for a in 0..k {
        for b in a + 1..k {
            let z = (mean_ranks[a] - mean_ranks[b]) / se;
            // sf(|z|) computed as cdf(-|z|) keeps its precision in the far tail.
            let p_value = (2.0 * normal.cdf(-z.abs())).min(1.0);
            pairs.push(PairwiseRankTest {
                a,
                b,
                z,
                p_value,
                p_holm: f64::NAN,
            });
        }
    }
    let adjusted = holm(&pairs.iter().map(|p| p.p_value).collect::<Vec<_>>());
    for (pair, p) in pairs.iter_mut().zip(adjusted) {
        pair.p_holm = p;
    }
    pairs
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn demsar_worked_example() {
        // Demšar (2006), Sect. 3.2.2: k = 4 classifiers over N = 14 data sets, SE = 0.488 and
        // the critical difference of Nemenyi's test 2.569 * 0.488 = 1.25 at alpha 0.05.
        let pairs = mean_rank_posthoc(&[3.143, 2.000, 2.893, 1.964], 14);
        assert_eq!(pairs.len(), 6);
        let se = (4.0 * 5.0 / (6.0 * 14.0_f64)).sqrt();
        assert!((se - 0.488).abs() < 1e-3);
        let ab = &pairs[0];
        assert_eq!((ab.a, ab.b), (0, 1));
        assert!((ab.z - (3.143 - 2.000) / se).abs() < 1e-12);
        // z = 2.342: two-sided p = 0.0192 (normal table).
        assert!((ab.p_value - 0.0192).abs() < 5e-4, "{}", ab.p_value);
        for p in &pairs {
            assert!(p.p_holm >= p.p_value && p.p_holm <= 1.0);
        }
    }

    #[test]
    fn equal_ranks_give_p_one_and_degenerate_inputs_nothing() {
        let pairs = mean_rank_posthoc(&[2.0, 2.0, 2.0], 10);
        assert!(pairs.iter().all(|p| p.z == 0.0 && p.p_value == 1.0));
        assert!(mean_rank_posthoc(&[1.0], 10).is_empty());
        assert!(mean_rank_posthoc(&[1.0, 2.0], 0).is_empty());
    }
}
