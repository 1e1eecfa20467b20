//! Descriptive statistics of one sample: what a results table prints per algorithm.
//!
//! Costs of failed runs are `+inf`, and a table should still show the median and the
//! best run of an algorithm that sometimes fails, so `+inf` is accepted: the mean and the
//! standard deviation become `+inf` (the honest answer), while the median, minimum and
//! maximum stay meaningful. [`Summary`] serializes non-finite fields as strings (see
//! [`super::json_f64`]).

use serde::{Deserialize, Serialize};

use super::json_f64;

/// Size, location and spread of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Number of values.
    pub n: usize,
    /// Arithmetic mean; `+inf` if any value is `+inf` (NaN if both `+inf` and `-inf` occur).
    #[serde(with = "json_f64")]
    pub mean: f64,
    /// Middle value, or the mean of the two middle values for even `n` (as numpy).
    #[serde(with = "json_f64")]
    pub median: f64,
    /// Sample standard deviation (divisor `n - 1`, numpy's `ddof=1`); 0 for `n < 2`;
    /// `+inf` when `n >= 2` and some value is infinite (numpy gives NaN there).
    #[serde(with = "json_f64")]
    pub std: f64,
    /// Smallest value (the best run, for costs).
    #[serde(with = "json_f64")]
    pub min: f64,
    /// Largest value.
    #[serde(with = "json_f64")]
    pub max: f64,
}

/// Summarizes `values`: `None` if it is empty or holds a NaN (NaN is not a cost; the
/// planner maps non-finite costs to `+inf`). Infinite values are allowed (see [`Summary`]).
#[must_use]
pub fn summarize(values: &[f64]) -> Option<Summary> {
    if values.is_empty() || values.iter().any(|v| v.is_nan()) {
        return None;
    }
    let n = values.len();
    let mut sorted = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let median = if n % 2 == 1 {
        sorted[n / 2]
    } else {
        // Halving each term first cannot overflow to inf for two large finite values.
        sorted[n / 2 - 1] / 2.0 + sorted[n / 2] / 2.0
    };
    let mean = values.iter().sum::<f64>() / n as f64;
    let std = if n < 2 {
        0.0
    } else if !mean.is_finite() || values.iter().any(|v| v.is_infinite()) {
        // Deviations from an infinite mean are inf - inf = NaN; the spread is unbounded.
        f64::INFINITY
    } else {
        // Two passes: deviations from the mean, which keeps precision when the values
        // share a large offset (costs of similar plans).
        let ss: f64 = values.iter().map(|v| (v - mean) * (v - mean)).sum();
        (ss / (n - 1) as f64).sqrt()
    };
    Some(Summary {
        n,
        mean,
        median,
        std,
        min: sorted[0],
        max: sorted[n - 1],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_and_nan_give_none() {
        assert_eq!(summarize(&[]), None);
        assert_eq!(summarize(&[1.0, f64::NAN]), None);
    }

    #[test]
    fn single_value_has_no_spread() {
        let s = summarize(&[4.0]).unwrap();
        assert_eq!(
            s,
            Summary {
                n: 1,
                mean: 4.0,
                median: 4.0,
                std: 0.0,
                min: 4.0,
                max: 4.0
            }
        );
    }

    #[test]
    fn odd_and_even_sizes() {
        // 2, 4, 4, 4, 5, 5, 7, 9: mean 5, squared deviations sum to 32, sample var 32/7.
        let s = summarize(&[9.0, 4.0, 2.0, 4.0, 5.0, 4.0, 7.0, 5.0]).unwrap();
        assert_eq!(s.n, 8);
        assert_eq!(s.mean, 5.0);
        assert_eq!(s.median, 4.5);
        assert!((s.std - (32.0_f64 / 7.0).sqrt()).abs() < 1e-15);
        assert_eq!((s.min, s.max), (2.0, 9.0));
        let s = summarize(&[3.0, 1.0, 2.0]).unwrap();
        assert_eq!((s.mean, s.median, s.std), (2.0, 2.0, 1.0));
    }

    #[test]
    fn infinity_keeps_median_min_max() {
        let s = summarize(&[1.0, f64::INFINITY, 2.0]).unwrap();
        assert_eq!(s.mean, f64::INFINITY);
        assert_eq!(s.std, f64::INFINITY);
        assert_eq!((s.median, s.min, s.max), (2.0, 1.0, f64::INFINITY));
        let s = summarize(&[f64::INFINITY]).unwrap();
        assert_eq!(
            (s.mean, s.std, s.median),
            (f64::INFINITY, 0.0, f64::INFINITY)
        );
    }

    #[test]
    fn large_values_do_not_overflow_the_median() {
        let s = summarize(&[f64::MAX, f64::MAX]).unwrap();
        assert_eq!(s.median, f64::MAX);
    }

    #[test]
    fn serializes_infinity_as_a_string_and_reads_it_back() {
        let s = summarize(&[1.0, f64::INFINITY]).unwrap();
        let json = serde_json::to_string(&s).unwrap();
        assert!(json.contains(r#""mean":"inf""#), "{json}");
        let back: Summary = serde_json::from_str(&json).unwrap();
        assert_eq!(back, s);
    }
}
