//! Greedy dimensional learning (Xu et al. 2019, "Particle swarm optimization based on
//! dimensional learning strategy", Swarm Evol. Comput. 45:33-51): the building block both
//! DLS-SMPSO optimizers share.
//!
//! Starting from pbest, each dimension where it differs from a guide (gbest) is replaced by
//! the guide's value and kept only if the cost drops, cumulatively. The paper variant
//! ([`super::dls_paper`]) applies it to stagnant particles' pbest; the exemplar variant
//! ([`super::dls_exemplar`]) builds a learning exemplar with it each time pbest improves.

use crate::problem::Evaluation;

/// What a greedy dimension-by-dimension substitution produced.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ExemplarStats {
    /// Evaluation of the resulting vector (that of pbest when nothing was accepted).
    pub eval: Evaluation,
    /// Evaluations spent.
    pub evaluations: u64,
    /// Dimensions taken from the guide.
    pub accepted: usize,
}

/// An exemplar and how it was obtained.
#[derive(Debug, Clone, PartialEq)]
pub struct Exemplar {
    /// The exemplar: pbest with the accepted dimensions taken from the guide.
    pub x: Vec<f64>,
    /// Its evaluation, the evaluations spent and the dimensions accepted.
    pub stats: ExemplarStats,
}

/// Greedy dimensional learning (Xu et al. 2019): starting from `pbest` (evaluation
/// `pbest_eval`), for each dimension j where the current vector differs from `guide`, try
/// the vector with j set to `guide[j]` and keep it if its cost is strictly lower. At most
/// D evaluations; never worse than `pbest`. `evaluate(x, cost)` is asked only whether `x`
/// costs less than `cost`, so it may give up on a candidate known to cost more (returning
/// [`Evaluation::worst`], as [`crate::problem::Problem::evaluate_cost_bounded`] does);
/// `cost` is [`Evaluation::cutoff_to_beat`] of what was accepted so far (`f64::MAX` while
/// that costs +inf).
/// `evaluate` returning `None` (budget spent) stops the pass, keeping what was accepted.
/// Writes the result into `out`.
pub fn build_exemplar_into(
    evaluate: &mut impl FnMut(&[f64], f64) -> Option<Evaluation>,
    pbest: &[f64],
    pbest_eval: Evaluation,
    guide: &[f64],
    out: &mut [f64],
) -> ExemplarStats {
    out.copy_from_slice(pbest);
    let mut stats = ExemplarStats {
        eval: pbest_eval,
        evaluations: 0,
        accepted: 0,
    };
    for (j, &gj) in guide.iter().enumerate() {
        let old = out[j];
        if old == gj {
            continue;
        }
        out[j] = gj;
        let Some(e) = evaluate(out, stats.eval.cutoff_to_beat()) else {
            out[j] = old;
            break;
        };
        stats.evaluations += 1;
        if e.better_than(&stats.eval) {
            stats.eval = e;
            stats.accepted += 1;
        } else {
            out[j] = old;
        }
    }
    stats
}

/// [`build_exemplar_into`] returning a new vector.
#[must_use]
pub fn build_exemplar(
    mut evaluate: impl FnMut(&[f64], f64) -> Option<Evaluation>,
    pbest: &[f64],
    pbest_eval: Evaluation,
    guide: &[f64],
) -> Exemplar {
    let mut x = vec![0.0; pbest.len()];
    let stats = build_exemplar_into(&mut evaluate, pbest, pbest_eval, guide, &mut x);
    Exemplar { x, stats }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sphere(x: &[f64]) -> f64 {
        x.iter().map(|v| v * v).sum()
    }

    #[test]
    fn reproduces_the_worked_example_of_xu_et_al() {
        let pbest = [1.0, 0.0, 3.0, 2.0, 4.0];
        let gbest = [2.0, 2.0, 2.0, 4.0, 0.0];
        assert_eq!(sphere(&pbest), 30.0);
        assert_eq!(sphere(&gbest), 28.0);
        let ex = build_exemplar(
            |x, _| Some(Evaluation::new(sphere(x), 0.0)),
            &pbest,
            Evaluation::new(30.0, 0.0),
            &gbest,
        );
        assert_eq!(ex.x, vec![1.0, 0.0, 2.0, 2.0, 0.0]);
        assert_eq!(ex.stats.eval.cost, 9.0);
        assert_eq!(ex.stats.evaluations, 5);
        assert_eq!(ex.stats.accepted, 2);
    }

    #[test]
    fn equal_dimensions_cost_nothing_and_budget_stops_the_pass() {
        let pbest = [1.0, 5.0, 3.0];
        let guide = [1.0, 0.0, 0.0];
        let mut calls = 0;
        let ex = build_exemplar(
            |x, _| {
                calls += 1;
                (calls <= 1).then(|| Evaluation::new(sphere(x), 0.0))
            },
            &pbest,
            Evaluation::new(35.0, 0.0),
            &guide,
        );
        // Dimension 0 is skipped, dimension 1 accepted, dimension 2 refused by the budget.
        assert_eq!(ex.x, vec![1.0, 0.0, 3.0]);
        assert_eq!(ex.stats.evaluations, 1);
        assert_eq!(ex.stats.eval.cost, 10.0);
    }

    /// Each probe is asked only to beat the cost accepted so far, so an evaluation that gives
    /// up above it changes nothing.
    #[test]
    fn probes_are_bounded_by_the_cost_accepted_so_far() {
        let pbest = [1.0, 0.0, 3.0, 2.0, 4.0];
        let gbest = [2.0, 2.0, 2.0, 4.0, 0.0];
        let plain = build_exemplar(
            |x, _| Some(Evaluation::new(sphere(x), 0.0)),
            &pbest,
            Evaluation::new(30.0, 0.0),
            &gbest,
        );
        let mut cutoffs = Vec::new();
        let bounded = build_exemplar(
            |x, cutoff| {
                cutoffs.push(cutoff);
                let cost = sphere(x);
                Some(if cost > cutoff {
                    Evaluation::worst()
                } else {
                    Evaluation::new(cost, 0.0)
                })
            },
            &pbest,
            Evaluation::new(30.0, 0.0),
            &gbest,
        );
        assert_eq!(bounded, plain);
        // Probes 1, 2 and 4 are refused (costs 33, 34 and 37), 3 and 5 accepted (25, then 9).
        assert_eq!(cutoffs, [30.0, 30.0, 30.0, 25.0, 25.0]);
    }

    /// From a pbest at +inf (SPSO's cost of a collision), probes are bounded by `f64::MAX`:
    /// one that costs +inf too is given up, and the exemplar is the same.
    #[test]
    fn probes_from_a_pbest_at_infinity_give_up_only_at_infinity() {
        // +inf while the first coordinate is above 1.5, else the sphere.
        let cost = |x: &[f64]| {
            if x[0] > 1.5 {
                f64::INFINITY
            } else {
                sphere(x)
            }
        };
        let pbest = [2.0, 0.0, 3.0];
        let guide = [2.5, 1.0, 1.0];
        let worse_guide = [1.0, 1.0, 1.0];
        for guide in [guide, worse_guide] {
            let plain = build_exemplar(
                |x, _| Some(Evaluation::new(cost(x), 0.0)),
                &pbest,
                Evaluation::new(f64::INFINITY, 0.0),
                &guide,
            );
            let mut cutoffs = Vec::new();
            let bounded = build_exemplar(
                |x, cutoff| {
                    cutoffs.push(cutoff);
                    let c = cost(x);
                    Some(if c > cutoff {
                        Evaluation::worst()
                    } else {
                        Evaluation::new(c, 0.0)
                    })
                },
                &pbest,
                Evaluation::new(f64::INFINITY, 0.0),
                &guide,
            );
            assert_eq!(bounded, plain);
            assert_eq!(cutoffs[0], f64::MAX);
        }
    }
}
