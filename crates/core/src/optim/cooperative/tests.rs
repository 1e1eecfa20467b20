//! Tests of the cooperative optimizer on small block-structured problems of their own.

use super::*;
use crate::optim::{solve, Budget};
use crate::problem::{BlockProblem, Bound, Problem};
use crate::rng::rng_from_seed;

/// Sphere in blocks of 3, with a "constraint" x_0 >= 1 (violation 1 - x_0).
struct Constrained(Vec<Bound>);

impl Problem for Constrained {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let violation = (1.0 - x[0]).max(0.0);
        Evaluation::new(
            x.iter().map(|v| v * v).sum::<f64>() + 1e3 * violation,
            violation,
        )
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for Constrained {
    fn block_size(&self) -> usize {
        3
    }
}

/// [`Constrained`] that gives up every bounded evaluation it can (and counts them).
struct GivingUp(Constrained, std::sync::atomic::AtomicUsize);

impl Problem for GivingUp {
    fn bounds(&self) -> &[Bound] {
        self.0.bounds()
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        self.0.evaluate(x)
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for GivingUp {
    fn block_size(&self) -> usize {
        self.0.block_size()
    }

    fn evaluate_blocks_bounded(
        &self,
        x: &[f64],
        by_block: &mut Vec<f64>,
        cutoff: f64,
    ) -> Option<Evaluation> {
        let e = self.evaluate_blocks(x, by_block);
        if e.violation > cutoff {
            self.1.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
            return None;
        }
        Some(e)
    }
}

#[test]
fn giving_up_bounded_evaluations_changes_nothing_in_a_run() {
    let bounds = vec![Bound::new(-5.0, 5.0); 9];
    let run = |p: &dyn Problem| {
        let mut opt = Cooperative::new(CoopParams::DEFAULT);
        solve(
            p,
            &mut opt,
            Budget::evaluations(3000),
            &mut rng_from_seed(4),
            &mut |_| {},
        )
    };
    let plain = run(&Constrained(bounds.clone()));
    let giving_up = GivingUp(Constrained(bounds), std::sync::atomic::AtomicUsize::new(0));
    let bounded = run(&giving_up);
    assert_eq!(plain.best_x, bounded.best_x);
    assert_eq!(plain.trace, bounded.trace);
    assert_eq!(plain.evaluations, bounded.evaluations);
    let given_up = giving_up.1.into_inner();
    assert!(given_up > 100, "only {given_up} evaluations given up");
}

/// Violation 1 on a plateau that no local move leaves.
struct Plateau(Vec<Bound>);

impl Problem for Plateau {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, _: &[f64]) -> Evaluation {
        Evaluation::new(1e3, 1.0)
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for Plateau {
    fn block_size(&self) -> usize {
        2
    }
}

#[test]
fn a_stuck_infeasible_context_is_restarted_and_the_best_kept() {
    let p = Plateau(vec![Bound::new(0.0, 1.0); 4]);
    let mut opt = Cooperative::new(CoopParams::DEFAULT);
    let out = solve(
        &p,
        &mut opt,
        Budget::evaluations(5000),
        &mut rng_from_seed(1),
        &mut |_| {},
    );
    // A round is 2 blocks x 11 steps x 10 evaluations = 220; restart after 3 stale ones.
    assert!(opt.restarts() >= 2, "{}", opt.restarts());
    assert_eq!(out.best.violation, 1.0);
    let mut never = Cooperative::new(CoopParams {
        restart_after: 0,
        ..CoopParams::DEFAULT
    });
    let _ = solve(
        &p,
        &mut never,
        Budget::evaluations(5000),
        &mut rng_from_seed(1),
        &mut |_| {},
    );
    assert_eq!(never.restarts(), 0);
}

/// Never feasible: violation 1 + x_0 over [0, 1]^4 in blocks of 2, so the context's
/// violation creeps down towards 1 and no round halves it.
struct Creeping(Vec<Bound>);

impl Problem for Creeping {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        Evaluation::new(1e3, 1.0 + x[0])
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for Creeping {
    fn block_size(&self) -> usize {
        2
    }
}

#[test]
fn restart_drop_sets_what_counts_as_progress() {
    let p = Creeping(vec![Bound::new(0.0, 1.0); 4]);
    let restarts = |restart_drop: f64| {
        let mut opt = Cooperative::new(CoopParams {
            restart_drop,
            refine_from: 1.0,
            ..CoopParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut opt,
            Budget::evaluations(5000),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        opt.restarts()
    };
    // Asking for a 90 % drop per round makes every round stale; any drop at all counts
    // as progress while the violation still creeps.
    let (strict, lenient) = (restarts(0.9), restarts(0.0));
    assert!(strict >= 5, "{strict}");
    assert!(lenient < strict, "{lenient} vs {strict}");
    let bad = CoopParams {
        restart_drop: 1.0,
        ..CoopParams::DEFAULT
    };
    assert_eq!(
        bad.validate().expect_err("a 100 % drop").field,
        "restart_drop"
    );
}

/// Four blocks of 3; block 3 holds a violation no move removes (x_9 >= 10 in [-5, 5])
/// and says so through `evaluate_blocks`. Counts the evaluations that changed block 3
/// alone, i.e. that were spent visiting it.
struct LastBlockViolated {
    bounds: Vec<Bound>,
    prev: std::sync::Mutex<Vec<f64>>,
    visiting_last: std::sync::atomic::AtomicUsize,
}

impl Problem for LastBlockViolated {
    fn bounds(&self) -> &[Bound] {
        &self.bounds
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let mut prev = self.prev.lock().expect("not poisoned");
        let changed: Vec<usize> = (0..4)
            .filter(|b| x[3 * b..3 * b + 3] != prev[3 * b..3 * b + 3])
            .collect();
        if changed == [3] {
            self.visiting_last
                .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
        prev.copy_from_slice(x);
        Evaluation::new(x.iter().map(|v| v * v).sum(), 10.0 - x[9])
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for LastBlockViolated {
    fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
        let e = self.evaluate(x);
        by_block.clear();
        by_block.extend([0.0, 0.0, 0.0, e.violation]);
        e
    }

    fn block_size(&self) -> usize {
        3
    }
}

#[test]
fn focus_sends_the_visits_of_an_infeasible_context_to_the_violating_block() {
    let share = |focus: f64| {
        let p = LastBlockViolated {
            bounds: vec![Bound::new(-5.0, 5.0); 12],
            prev: std::sync::Mutex::new(vec![f64::NAN; 12]),
            visiting_last: 0.into(),
        };
        let mut opt = Cooperative::new(CoopParams {
            focus,
            restart_after: 0,
            ..CoopParams::DEFAULT
        });
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(4000),
            &mut rng_from_seed(2),
            &mut |_| {},
        );
        assert!(!out.best.feasible());
        p.visiting_last.into_inner() as f64 / 4000.0
    };
    let (off, half, full) = (share(0.0), share(0.5), share(1.0));
    assert!((0.2..0.3).contains(&off), "cyclic visits: {off}");
    assert!(full > 0.9, "focused visits: {full}");
    assert!(half > off + 0.2 && half < full, "{off} {half} {full}");
}

/// Two blocks of 6 in [0, 1]; block 1 is violated (1, a plateau) unless each of its
/// values is within 0.05 of block 0's: a gap that only block 0's path knows, found by a
/// uniform draw once in about 10^6.
struct NarrowGap(Vec<Bound>);

impl Problem for NarrowGap {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        let inside = (0..6).all(|k| (x[6 + k] - x[k]).abs() <= 0.05);
        // Only block 0 has a cost (towards 0.9), so block 1's own search has nothing to
        // follow on its plateau.
        let cost = x[..6].iter().map(|v| (v - 0.9).powi(2)).sum();
        Evaluation::new(cost, if inside { 0.0 } else { 1.0 })
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for NarrowGap {
    fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
        let e = self.evaluate(x);
        by_block.clear();
        by_block.extend([0.0, e.violation]);
        e
    }

    fn block_size(&self) -> usize {
        6
    }
}

#[test]
fn a_violating_block_finds_the_way_another_block_knows_by_transplant() {
    let run = |transplant: Transplant, seed: u64| {
        let mut opt = Cooperative::new(CoopParams {
            transplant,
            ..CoopParams::DEFAULT
        });
        solve(
            &NarrowGap(vec![Bound::new(0.0, 1.0); 12]),
            &mut opt,
            Budget::evaluations(3000),
            &mut rng_from_seed(seed),
            &mut |_| {},
        )
        .best
        .feasible()
    };
    for seed in 1..=5 {
        assert!(
            run(Transplant::ShiftedWhenStuck, seed),
            "seed {seed}: transplant did not cross the gap"
        );
        assert!(
            !run(Transplant::Off, seed),
            "seed {seed}: crossed without transplant"
        );
    }
}

/// [`LastBlockViolated`]'s plateau, counting the nudges asked for per block, and
/// recording the shifted copies asked for as (block, donor), the hot spots asked for
/// (per block) and the site of every nudge. Its hot spots put every weight on site 2
/// of 3.
struct CountsMoves {
    inner: LastBlockViolated,
    asked: std::sync::Mutex<Vec<usize>>,
    copies: std::sync::Mutex<Vec<(usize, usize)>>,
    spots: std::sync::Mutex<Vec<usize>>,
    sites: std::sync::Mutex<Vec<Option<usize>>>,
    /// Calls of `evaluate` and `evaluate_blocks`.
    evaluated: std::sync::atomic::AtomicU64,
}

impl CountsMoves {
    fn new() -> Self {
        Self {
            inner: LastBlockViolated {
                bounds: vec![Bound::new(-5.0, 5.0); 12],
                prev: std::sync::Mutex::new(vec![f64::NAN; 12]),
                visiting_last: 0.into(),
            },
            asked: std::sync::Mutex::new(vec![0; 4]),
            copies: std::sync::Mutex::new(Vec::new()),
            spots: std::sync::Mutex::new(vec![0; 4]),
            sites: std::sync::Mutex::new(Vec::new()),
            evaluated: 0.into(),
        }
    }
}

impl Problem for CountsMoves {
    fn bounds(&self) -> &[Bound] {
        self.inner.bounds()
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        self.evaluated
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.inner.evaluate(x)
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for CountsMoves {
    fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
        self.evaluated
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.inner.evaluate_blocks(x, by_block)
    }

    fn block_size(&self) -> usize {
        3
    }

    fn nudge(
        &self,
        x: &[f64],
        block: usize,
        site: Option<usize>,
        _: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        self.asked.lock().expect("not poisoned")[block] += 1;
        self.sites.lock().expect("not poisoned").push(site);
        out.copy_from_slice(&x[3 * block..3 * block + 3]);
        true
    }

    fn shifted_copy(
        &self,
        x: &[f64],
        block: usize,
        donor: usize,
        _: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        self.copies
            .lock()
            .expect("not poisoned")
            .push((block, donor));
        out.copy_from_slice(&x[3 * donor..3 * donor + 3]);
        true
    }

    fn hot_spots(&self, _: &[f64], block: usize, out: &mut Vec<f64>) -> bool {
        self.spots.lock().expect("not poisoned")[block] += 1;
        out.clear();
        out.extend([0.0, 0.0, 1.5]);
        true
    }
}

#[test]
fn nudges_go_to_the_violating_block_only_and_only_when_asked_for() {
    let asked = |nudges: usize| {
        let p = CountsMoves::new();
        let mut opt = Cooperative::new(CoopParams {
            nudges,
            focus: 0.0,
            ..CoopParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut opt,
            Budget::evaluations(3000),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        p.asked.into_inner().expect("not poisoned")
    };
    assert_eq!(asked(0), vec![0; 4]);
    let two = asked(2);
    assert_eq!(two[..3], [0, 0, 0], "{two:?}");
    assert!(
        two[3] >= 4 && two[3] % 2 == 0,
        "two per visit of block 3: {two:?}"
    );
}

#[test]
fn aimed_nudges_ask_for_the_hot_spots_once_per_violating_visit_and_move_a_hot_site() {
    let run = |aimed_nudges: f64| {
        let p = CountsMoves::new();
        let mut opt = Cooperative::new(CoopParams {
            aimed_nudges,
            focus: 0.0,
            ..CoopParams::DEFAULT
        });
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(3000),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        // The hot spots are evaluations: the budget holds them too.
        assert_eq!(out.evaluations, 3000);
        let asked = p.asked.into_inner().expect("not poisoned");
        let spots = p.spots.into_inner().expect("not poisoned");
        let looks: usize = spots.iter().sum();
        assert_eq!(
            p.evaluated.into_inner() + looks as u64,
            out.evaluations,
            "every evaluation made, and every look, counted once"
        );
        (asked, spots, p.sites.into_inner().expect("not poisoned"))
    };
    let (asked, spots, sites) = run(0.0);
    assert_eq!(spots, vec![0; 4]);
    assert!(sites.iter().all(Option::is_none) && asked[3] > 0);
    let (asked, spots, sites) = run(1.0);
    assert_eq!(spots[..3], [0, 0, 0], "{spots:?}");
    let per_visit = CoopParams::DEFAULT.nudges;
    // One look per visit (the last visit may be cut short by the budget).
    assert!(
        spots[3] > 0 && asked[3].abs_diff(per_visit * spots[3]) <= per_visit,
        "{asked:?} {spots:?}"
    );
    assert!(sites.iter().all(|s| *s == Some(2)), "{sites:?}");
    let (_, _, sites) = run(0.5);
    let hot = sites.iter().filter(|s| s.is_some()).count();
    assert!(
        sites.iter().all(|s| s.is_none() || *s == Some(2)) && hot > 0 && hot < sites.len(),
        "{sites:?}"
    );
}

#[test]
fn a_problem_without_hot_spots_spends_no_evaluation_on_them() {
    let run = |aimed_nudges: f64| {
        let mut opt = Cooperative::new(CoopParams {
            aimed_nudges,
            ..CoopParams::DEFAULT
        });
        // A block in violation, so nudges (and their aim) are asked for, but neither
        // nudges nor hot spots of its own.
        let p = CountsMoves::new().inner;
        let mut trace = Vec::new();
        let out = solve(
            &p,
            &mut opt,
            Budget::evaluations(2000),
            &mut rng_from_seed(4),
            &mut |s| trace.push((s.evaluations, s.best_cost.to_bits())),
        );
        (out.best_x, trace)
    };
    assert_eq!(run(1.0), run(0.0));
}

#[test]
fn shifted_copies_come_after_a_round_without_progress_for_the_violating_block() {
    let asked = |transplant: Transplant, evaluations: u64| {
        let p = CountsMoves::new();
        let mut opt = Cooperative::new(CoopParams {
            transplant,
            ..CoopParams::DEFAULT
        });
        let _ = solve(
            &p,
            &mut opt,
            Budget::evaluations(evaluations),
            &mut rng_from_seed(3),
            &mut |_| {},
        );
        p.copies.into_inner().expect("not poisoned")
    };
    assert!(asked(Transplant::Perturbed, 6000).is_empty());
    // A round visits the four blocks, 100 evaluations a visit: none has ended yet.
    assert!(asked(Transplant::ShiftedWhenStuck, 300).is_empty());
    let on = asked(Transplant::ShiftedWhenStuck, 6000);
    assert!(!on.is_empty());
    assert!(
        on.iter().all(|&(b, d)| b == 3 && d < 3),
        "only the violating block, from the others: {on:?}"
    );
}

#[test]
fn an_unvalidated_population_of_zero_does_not_panic() {
    let p = Constrained(vec![Bound::new(-5.0, 5.0); 6]);
    let mut opt = Cooperative::new(CoopParams {
        population: 0,
        ..CoopParams::DEFAULT
    });
    let out = solve(
        &p,
        &mut opt,
        Budget::evaluations(200),
        &mut rng_from_seed(1),
        &mut |_| {},
    );
    assert_eq!(out.evaluations, 200);
    assert!(out.best.cost.is_finite());
}

#[test]
fn finds_the_constrained_optimum_block_by_block() {
    let p = Constrained(vec![Bound::new(-5.0, 5.0); 9]);
    let mut opt = Cooperative::new(CoopParams::DEFAULT);
    let out = solve(
        &p,
        &mut opt,
        Budget::evaluations(6000),
        &mut rng_from_seed(3),
        &mut |_| {},
    );
    assert!(out.best.feasible(), "{:?}", out.best);
    // Optimum: x_0 = 1, the rest 0, cost 1.
    assert!((out.best.cost - 1.0).abs() < 1e-2, "{}", out.best.cost);
    assert_eq!(out.evaluations, 6000);
}

/// The constraint of [`Constrained`] left out of the cost, so only the comparison can
/// see it.
struct Unpenalised(Vec<Bound>);

impl Problem for Unpenalised {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        Evaluation::new(x.iter().map(|v| v * v).sum(), (1.0 - x[0]).max(0.0))
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}

impl BlockProblem for Unpenalised {
    fn block_size(&self) -> usize {
        3
    }
}

#[test]
fn without_feasibility_first_the_search_follows_the_cost_alone() {
    let p = Unpenalised(vec![Bound::new(-5.0, 5.0); 6]);
    let run = |compare: Comparison| {
        let mut opt = Cooperative::new(CoopParams {
            compare,
            ..CoopParams::DEFAULT
        });
        solve(
            &p,
            &mut opt,
            Budget::evaluations(3000),
            &mut rng_from_seed(5),
            &mut |_| {},
        )
        .best
    };
    assert!(run(Comparison::FeasibilityFirst).feasible());
    let blind = run(Comparison::PenalisedCost);
    assert!(!blind.feasible() && blind.cost < 0.1, "{blind:?}");
}

#[test]
fn each_ablation_switch_changes_the_search_and_still_runs() {
    let p = Constrained(vec![Bound::new(-5.0, 5.0); 9]);
    let run = |params: CoopParams| {
        let mut opt = Cooperative::new(params);
        solve(
            &p,
            &mut opt,
            Budget::evaluations(3000),
            &mut rng_from_seed(5),
            &mut |_| {},
        )
    };
    let base = run(CoopParams::DEFAULT);
    for off in [
        CoopParams {
            spread: Spread::Fixed,
            ..CoopParams::DEFAULT
        },
        CoopParams {
            blocks: Blocks::WholePlan,
            ..CoopParams::DEFAULT
        },
    ] {
        let out = run(off);
        assert_eq!(out.evaluations, 3000, "{off:?}");
        assert!(out.best.cost.is_finite(), "{off:?}");
        assert_ne!(out.best_x, base.best_x, "{off:?} searched the same way");
    }
}

#[test]
fn switches_read_their_names_and_the_old_booleans() {
    let read = |text: &str| toml::from_str::<CoopParams>(text);
    let named = read(
        "compare = \"penalised-cost\"\nspread = \"fixed\"\nblocks = \"whole-plan\"\n\
         updates = \"sequential\"\ntransplant = \"perturbed\"",
    )
    .expect("names");
    assert_eq!(
        (
            named.compare,
            named.spread,
            named.blocks,
            named.updates,
            named.transplant
        ),
        (
            Comparison::PenalisedCost,
            Spread::Fixed,
            Blocks::WholePlan,
            Updates::Sequential,
            Transplant::Perturbed
        )
    );
    let old = read(
        "feasibility_first = false\nadaptive_spread = false\ndecompose = false\n\
         synchronous = false\ntransplant = false",
    )
    .expect("old booleans");
    assert_eq!(
        (
            old.compare,
            old.spread,
            old.blocks,
            old.updates,
            old.transplant
        ),
        (
            Comparison::PenalisedCost,
            Spread::Fixed,
            Blocks::WholePlan,
            Updates::Sequential,
            Transplant::Off
        )
    );
    assert_eq!(read("").expect("empty"), CoopParams::DEFAULT);
    let bad = read("spread = \"wide\"")
        .expect_err("an unknown name")
        .to_string();
    assert!(
        bad.contains("\"adaptive\", \"fixed\"") && bad.contains("wide"),
        "{bad}"
    );
    let both = read("spread = \"fixed\"\nadaptive_spread = true").expect_err("both spellings");
    assert!(both.to_string().contains("duplicate"), "{both}");
    // Records write the names.
    let json = serde_json::to_value(CoopParams::DEFAULT).expect("serialises");
    assert_eq!(json["transplant"], "shifted-when-stuck");
    assert_eq!(json["compare"], "feasibility-first");
}
