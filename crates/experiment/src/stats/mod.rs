//! Statistics over run results: descriptive summaries and the tests a comparison of
//! optimizers reports.
//!
//! Everything here is a pure function of slices of `f64` (no I/O, no records), so the
//! statistics step can run over any grouping of runs, and each function can be checked
//! against a reference implementation: `tests/scipy_crosscheck.rs` compares every one of
//! them with scipy on fixed data sets.
//!
//! | Function | What it answers | Reference it matches |
//! |---|---|---|
//! | [`summarize`] | mean, median, sample std, min, max of one sample | numpy |
//! | [`rank_sum`] | do two methods' costs differ? (two-sided) | `scipy.stats.mannwhitneyu`, `method='exact'` without ties and n1 n2 <= 2500, else `'asymptotic'` |
//! | [`holm`] | p-values adjusted for many pairwise comparisons | `statsmodels` `multipletests(method='holm')` |
//! | [`fisher_exact`] | do two algorithms' success rates differ? (2x2, two-sided) | `scipy.stats.fisher_exact` |
//! | [`friedman`] | do k algorithms differ over the same scenarios or seeds? | `scipy.stats.friedmanchisquare` |
//! | [`mean_rank_posthoc`] | which pairs differ, after Friedman (Holm over all pairs) | Demšar (2006), worked example |
//!
//! Conventions shared by all:
//! - Costs are "lower is better" and may be `+inf` (an infeasible or failed run); `+inf`
//!   ranks after every finite value and ties with other `+inf`s, so rank tests stay
//!   meaningful when some runs failed.
//! - NaN is not a cost (the planner maps non-finite costs to `+inf`), so a NaN input is
//!   refused (`None`) rather than given an arbitrary rank.
//! - Ties get average ranks and the tests use the usual tie corrections.
//! - Result structs serialize their `f64` fields through [`json_f64`], which writes
//!   non-finite values as the strings `"inf"`, `"-inf"` and `"nan"`, since JSON has no
//!   infinity and serde_json would otherwise write `null` and fail to read it back.

mod descriptive;
mod fisher;
mod friedman;
mod holm;
mod posthoc;
pub use swarmplan_core::json_f64;
mod ranks;
mod ranksum;

pub use descriptive::{summarize, Summary};
pub use fisher::fisher_exact;
pub use friedman::{friedman, FriedmanTest};
pub use holm::holm;
pub use posthoc::{mean_rank_posthoc, PairwiseRankTest};
pub use ranksum::{exact_upper_tail, rank_sum, RankSumMethod, RankSumTest, EXACT_MAX_PAIRS};
