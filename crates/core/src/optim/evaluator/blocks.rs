//! The evaluator's block-wise side, for optimizers that decompose the search (`coop`):
//! evaluations with each block's share of the violation, and the problem's local moves,
//! through [`Problem::blocks`]. A problem without a block-wise view is one block with
//! nothing known of its violations, and has no local moves.

use rayon::prelude::*;

use super::{normalised, Evaluator};
use crate::problem::{BlockProblem, Evaluation};
use crate::rng::Rng;

impl Evaluator<'_> {
    /// The problem's local move of one block ([`BlockProblem::nudge`]; not an evaluation).
    pub fn nudge(
        &self,
        x: &[f64],
        block: usize,
        site: Option<usize>,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        self.problem
            .blocks()
            .is_some_and(|p| p.nudge(x, block, site, rng, out))
    }

    /// Where block `block`'s violations of `x` lie, as weights over its nudge sites
    /// ([`BlockProblem::hot_spots`]); counted as one evaluation when the problem assessed `x` for
    /// it, `None` (nothing asked) when the budget is spent.
    pub fn hot_spots(&mut self, x: &[f64], block: usize, out: &mut Vec<f64>) -> Option<()> {
        if self.spent() {
            return None;
        }
        let assessed = match self.problem.blocks() {
            Some(p) => p.hot_spots(x, block, out),
            None => {
                out.clear();
                false
            }
        };
        if assessed {
            self.count += 1;
        }
        Some(())
    }

    /// The problem's shifted copy of one block's path into another ([`BlockProblem::shifted_copy`];
    /// not an evaluation).
    pub fn shifted_copy(
        &self,
        x: &[f64],
        block: usize,
        donor: usize,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        self.problem
            .blocks()
            .is_some_and(|p| p.shifted_copy(x, block, donor, rng, out))
    }

    /// The problem's block size ([`BlockProblem::block_size`]), at least 1 and at most the
    /// dimension.
    #[must_use]
    pub fn block_size(&self) -> usize {
        self.problem
            .blocks()
            .map_or(self.dimension(), BlockProblem::block_size)
            .clamp(1, self.dimension().max(1))
    }

    /// [`Evaluator::evaluate_rows`] with each row's block shares of the violation
    /// ([`BlockProblem::evaluate_blocks`]) in `shares[i]`.
    pub fn evaluate_rows_blocks(
        &mut self,
        rows: &[f64],
        n: usize,
        out: &mut Vec<Evaluation>,
        shares: &mut Vec<Vec<f64>>,
    ) {
        self.rows_blocks(rows, n, |_| f64::INFINITY, out, shares);
    }

    /// [`Evaluator::evaluate_rows_blocks`] for rows that only need to beat, by Deb's rules,
    /// a candidate whose violation is `cutoffs[i]` ([`BlockProblem::evaluate_blocks_bounded`]): a
    /// row the problem gives up on comes back as [`Evaluation::worst`], which no comparison
    /// prefers, and its shares are unspecified. Each row counts as one evaluation either way,
    /// so budgets stay what they were; only the time falls.
    pub fn evaluate_rows_blocks_bounded(
        &mut self,
        rows: &[f64],
        n: usize,
        cutoffs: &[f64],
        out: &mut Vec<Evaluation>,
        shares: &mut Vec<Vec<f64>>,
    ) {
        assert!(cutoffs.len() >= n, "a cutoff per row");
        self.rows_blocks(rows, n, |i| cutoffs[i], out, shares);
    }

    /// Rows with block shares, row i bounded by `cutoff(i)` (+inf: evaluated in full, which
    /// a problem's bounded evaluation must then be).
    fn rows_blocks(
        &mut self,
        rows: &[f64],
        n: usize,
        cutoff: impl Fn(usize) -> f64 + Sync,
        out: &mut Vec<Evaluation>,
        shares: &mut Vec<Vec<f64>>,
    ) {
        let problem = self.problem;
        let dim = self.dimension();
        let allowed = self.admit_rows(rows, n);
        shares.resize_with(allowed.max(shares.len()), Vec::new);
        out.clear();
        let one = |x: &[f64], s: &mut Vec<f64>, c: f64| match problem.blocks() {
            // BlockProblem's defaults: shares unknown, evaluated in full, never given up.
            None => {
                s.clear();
                normalised(problem.evaluate(x))
            }
            Some(p) if c == f64::INFINITY => normalised(p.evaluate_blocks(x, s)),
            Some(p) => p
                .evaluate_blocks_bounded(x, s, c)
                .map_or_else(Evaluation::worst, normalised),
        };
        if dim == 0 {
            for (i, s) in shares.iter_mut().take(allowed).enumerate() {
                out.push(one(&[], s, cutoff(i)));
            }
            return;
        }
        rows[..allowed * dim]
            .par_chunks(dim)
            .zip(shares[..allowed].par_iter_mut())
            .enumerate()
            .map(|(i, (x, s))| one(x, s, cutoff(i)))
            .collect_into_vec(out);
    }

    /// [`Evaluator::evaluate`] with each block's share of the violation in `by_block`
    /// ([`BlockProblem::evaluate_blocks`]); counted the same.
    pub fn evaluate_blocks(&mut self, x: &[f64], by_block: &mut Vec<f64>) -> Option<Evaluation> {
        self.admit(x)?;
        Some(normalised(match self.problem.blocks() {
            Some(p) => p.evaluate_blocks(x, by_block),
            None => {
                by_block.clear();
                self.problem.evaluate(x)
            }
        }))
    }
}
