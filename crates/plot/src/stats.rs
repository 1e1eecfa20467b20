//! The few statistics figures need: quantiles (linear interpolation between order
//! statistics, numpy's and R's default "type 7") and Tukey box-plot numbers. Infinite values
//! take part as the largest values (an infeasible run ranks last), so a quantile may be
//! +inf; callers clip to the axis.

/// The q-quantile (0 <= q <= 1) of sorted values, type 7; NaN for an empty slice.
#[must_use]
pub(crate) fn quantile_sorted(sorted: &[f64], q: f64) -> f64 {
    match sorted.len() {
        0 => f64::NAN,
        1 => sorted[0],
        n => {
            let h = (n - 1) as f64 * q.clamp(0.0, 1.0);
            let k = h.floor() as usize;
            let f = h - k as f64;
            if k + 1 >= n {
                sorted[n - 1]
            } else if f == 0.0 {
                sorted[k]
            } else if sorted[k + 1].is_infinite() {
                // Interpolating towards +inf: anything above the lower value is +inf.
                sorted[k + 1]
            } else {
                sorted[k] + (sorted[k + 1] - sorted[k]) * f
            }
        }
    }
}

/// `values` without NaN, sorted ascending (+inf last).
#[must_use]
pub(crate) fn sorted(values: impl IntoIterator<Item = f64>) -> Vec<f64> {
    let mut v: Vec<f64> = values.into_iter().filter(|x| !x.is_nan()).collect();
    v.sort_by(f64::total_cmp);
    v
}

/// Tukey box-plot numbers of finite values.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BoxStats {
    pub q1: f64,
    pub median: f64,
    pub q3: f64,
    /// Most extreme values within 1.5 IQR of the box.
    pub whisker_lo: f64,
    pub whisker_hi: f64,
    pub outliers: Vec<f64>,
}

impl BoxStats {
    /// Box-plot numbers of the finite values in `values`; `None` when there are none.
    #[must_use]
    pub(crate) fn of(values: &[f64]) -> Option<Self> {
        let v = sorted(values.iter().copied().filter(|x| x.is_finite()));
        if v.is_empty() {
            return None;
        }
        let q1 = quantile_sorted(&v, 0.25);
        let median = quantile_sorted(&v, 0.5);
        let q3 = quantile_sorted(&v, 0.75);
        let iqr = q3 - q1;
        let (lo_fence, hi_fence) = (q1 - 1.5 * iqr, q3 + 1.5 * iqr);
        let inside = || {
            v.iter()
                .copied()
                .filter(|x| *x >= lo_fence && *x <= hi_fence)
        };
        let whisker_lo = inside().fold(f64::INFINITY, f64::min).min(q1);
        let whisker_hi = inside().fold(f64::NEG_INFINITY, f64::max).max(q3);
        let outliers = v
            .iter()
            .copied()
            .filter(|x| *x < lo_fence || *x > hi_fence)
            .collect();
        Some(Self {
            q1,
            median,
            q3,
            whisker_lo,
            whisker_hi,
            outliers,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_match_numpy_defaults() {
        // numpy.quantile([1, 2, 3, 4], [0.25, 0.5, 0.75]) = [1.75, 2.5, 3.25]
        let v = [1.0, 2.0, 3.0, 4.0];
        assert!((quantile_sorted(&v, 0.25) - 1.75).abs() < 1e-12);
        assert!((quantile_sorted(&v, 0.5) - 2.5).abs() < 1e-12);
        assert!((quantile_sorted(&v, 0.75) - 3.25).abs() < 1e-12);
        assert!(quantile_sorted(&[], 0.5).is_nan());
        assert_eq!(quantile_sorted(&[7.0], 0.9), 7.0);
    }

    #[test]
    fn infinite_values_rank_last() {
        let v = sorted([3.0, f64::INFINITY, 1.0, 2.0]);
        assert_eq!(v[3], f64::INFINITY);
        assert_eq!(quantile_sorted(&v, 0.5), 2.5);
        assert_eq!(quantile_sorted(&v, 0.9), f64::INFINITY);
    }

    #[test]
    fn box_stats_flag_outliers() {
        let b = BoxStats::of(&[1.0, 2.0, 3.0, 4.0, 5.0, 100.0, f64::INFINITY]).unwrap();
        assert_eq!(b.median, 3.5);
        assert_eq!(b.outliers, vec![100.0]);
        assert_eq!(b.whisker_lo, 1.0);
        assert_eq!(b.whisker_hi, 5.0);
        assert!(BoxStats::of(&[f64::INFINITY]).is_none());
    }
}
