//! Average ranks with ties, shared by the rank-sum and Friedman tests.
//!
//! Both tests rank values (pooled, or within one block), give tied values the mean of the
//! ranks they span (scipy's `rankdata(method='average')`) and correct their variance by
//! the tie term Σ(t³ − t) over tie groups of size t, so one function computes both.

/// Ranks of a sample, in the sample's order, and its tie term.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Ranked {
    /// 1-based ranks, lowest value first; ties share the mean of their ranks.
    pub ranks: Vec<f64>,
    /// Σ(t³ − t) over groups of t tied values (0 without ties).
    pub tie_term: f64,
}

/// Ranks `values` (NaN-free; callers check). `+inf` ranks after every finite value and
/// ties with other `+inf`s; `-0.0` ties with `0.0`, as in scipy.
#[must_use]
pub(crate) fn average_ranks(values: &[f64]) -> Ranked {
    debug_assert!(
        values.iter().all(|v| !v.is_nan()),
        "NaN values cannot be ranked"
    );
    let mut order: Vec<usize> = (0..values.len()).collect();
    order.sort_by(|&i, &j| values[i].total_cmp(&values[j]));
    let mut ranks = vec![0.0; values.len()];
    let mut tie_term = 0.0;
    let mut start = 0;
    while start < order.len() {
        // total_cmp orders -0.0 before 0.0 but they sit next to each other, so grouping
        // by `==` after the sort ties them, as a numeric comparison should.
        let mut end = start + 1;
        while end < order.len() && values[order[end]] == values[order[start]] {
            end += 1;
        }
        // Sorted positions start..end hold ranks start+1..=end; their mean is:
        let rank = (start + end + 1) as f64 / 2.0;
        for &i in &order[start..end] {
            ranks[i] = rank;
        }
        let t = (end - start) as f64;
        tie_term += t * t * t - t;
        start = end;
    }
    Ranked { ranks, tie_term }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distinct_values_get_their_positions() {
        let r = average_ranks(&[3.0, 1.0, 2.0]);
        assert_eq!(r.ranks, vec![3.0, 1.0, 2.0]);
        assert_eq!(r.tie_term, 0.0);
    }

    #[test]
    fn ties_share_the_mean_rank() {
        // Sorted: 1, 2, 2, 2, 5 -> ranks 1, 3, 3, 3, 5; one group of 3: 27 - 3 = 24.
        let r = average_ranks(&[2.0, 5.0, 2.0, 1.0, 2.0]);
        assert_eq!(r.ranks, vec![3.0, 5.0, 3.0, 1.0, 3.0]);
        assert_eq!(r.tie_term, 24.0);
    }

    #[test]
    fn infinities_rank_last_and_tie_and_signed_zeros_tie() {
        let r = average_ranks(&[f64::INFINITY, 0.0, f64::INFINITY, -0.0, 1e300]);
        assert_eq!(r.ranks, vec![4.5, 1.5, 4.5, 1.5, 3.0]);
        assert_eq!(r.tie_term, 12.0);
    }

    #[test]
    fn empty_input_is_empty() {
        let r = average_ranks(&[]);
        assert!(r.ranks.is_empty());
        assert_eq!(r.tie_term, 0.0);
    }
}
