//! Incremental evaluation equals full evaluation (issue 12).
//!
//! The proximity sweep keeps the pair results of the previous evaluation on the same
//! buffers and reuses those of pairs whose motions did not change, and the flown path keeps
//! the arcs of UAVs whose waypoints did not change (`TimedPlan::fill_flown`). An evaluation after a
//! change to some UAVs must give, bit for bit, what a sweep of every pair on fresh buffers
//! gives: the same cost, violation measure, per-UAV reports and violation list, whatever the
//! sequence of changes before it. Checked over random plans and random changes on worlds
//! with common arrival (where a change moves every UAV's timing) and cruise timing, a shared
//! start (separation episodes at every evaluation) and spread starts.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::sync::OnceLock;
use swarmplan_core::problem::BlockProblem;

use proptest::prelude::*;
use swarmplan_core::cost::{assess_into, Scratch, UavAssessment};
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::feasibility::{Violation, ViolationSink};
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::Problem;
use swarmplan_core::rng::rng_from_seed;
use swarmplan_core::world::spec::{ObjectivePreset, TimingPolicy};
use swarmplan_core::world::World;
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

/// paper-case2 (common arrival), gen-s2-u8-t12-shared with cruise timing, gen-s1-u10-t12,
/// and paper-case2 and the cruise one again with the fleet's pace free (a change to one
/// UAV's block can then change everyone's speed), and with departure delays free (a UAV
/// that waits hovers at its start: a leading segment of its motion).
fn worlds() -> &'static [World] {
    static W: OnceLock<Vec<World>> = OnceLock::new();
    W.get_or_init(|| {
        let load = |name: &str, cruise: bool, free_pace: bool, max_delay: f64| {
            let mut loaded = load_spec(name).unwrap();
            if cruise {
                loaded.spec.timing.policy = TimingPolicy::Cruise;
            }
            if free_pace {
                loaded.spec.timing.pace = [0.5, 1.5];
            }
            loaded.spec.timing.max_delay = max_delay;
            build_world(&loaded, None).unwrap()
        };
        vec![
            load("paper-case2", false, false, 0.0),
            load("gen-s2-u8-t12-shared", true, false, 0.0),
            load("gen-s1-u10-t12", false, false, 0.0),
            load("paper-case2", false, true, 0.0),
            load("gen-s2-u8-t12-shared", true, true, 0.0),
            load("paper-case2", false, true, 0.4),
            load("gen-s2-u8-t12-shared", true, false, 0.4),
        ]
    })
}

type Outcome = (u64, u64, Vec<UavAssessment>, Vec<Violation>);

/// Assesses `x` on `scratch` with the violation list collected.
fn outcome(problem: &PlanningProblem<'_>, x: &[f64], scratch: &mut Scratch) -> Outcome {
    let world = problem.world();
    let plan = problem.decode(x);
    let mut sink = ViolationSink::collecting(world.spec().planning.profile);
    let (total, violation) = assess_into(world, &plan, scratch, &mut sink, false);
    (
        total.to_bits(),
        violation.to_bits(),
        scratch.reports().to_vec(),
        sink.list.unwrap_or_default(),
    )
}

/// What an optimizer's summing assessment gives: total, measure, soft measure, reports and
/// each UAV's share of the measure, as bits. Unlike [`outcome`] this takes the memo of
/// each UAV's own terms (a collecting sink never does).
type Summed = (u64, u64, u64, Vec<UavAssessment>, Vec<u64>);

fn summed(problem: &PlanningProblem<'_>, x: &[f64], scratch: &mut Scratch) -> Summed {
    let world = problem.world();
    let plan = problem.decode(x);
    let n = plan.uavs.len();
    let mut sink = ViolationSink::new(world.spec().planning.profile).sharing(n, Vec::new());
    let (total, violation) = assess_into(world, &plan, scratch, &mut sink, false);
    let shares = sink.by_uav.unwrap_or_default();
    (
        total.to_bits(),
        violation.to_bits(),
        sink.soft.to_bits(),
        scratch.reports().to_vec(),
        shares.iter().map(|s| s.to_bits()).collect(),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    #[test]
    fn an_evaluation_after_changes_equals_one_on_fresh_buffers(
        world_index in 0usize..7,
        seed in any::<u64>(),
        changes in prop::collection::vec((0usize..64, 1usize..3, prop::bool::ANY), 1..8),
    ) {
        let world = &worlds()[world_index];
        let problem = PlanningProblem::new(world, EncodingKind::Spherical, InitKind::Line);
        let (dim, block) = (problem.dimension(), problem.block_size());
        let blocks = dim / block;
        let mut rng = rng_from_seed(seed);
        let mut x = vec![0.0; dim];
        problem.sample_initial(&mut rng, &mut x);
        let mut warm = Scratch::default();
        let mut warm_summing = Scratch::default();
        prop_assert_eq!(outcome(&problem, &x, &mut warm), outcome(&problem, &x, &mut Scratch::default()));
        prop_assert_eq!(summed(&problem, &x, &mut warm_summing), summed(&problem, &x, &mut Scratch::default()));
        for (first, count, redraw) in changes {
            // Change `count` consecutive UAVs from `first`: redrawn from the initialisation,
            // or nudged by a small step (what a search near its context evaluates).
            let mut fresh = vec![0.0; dim];
            problem.sample_initial(&mut rng, &mut fresh);
            for b in (first..first + count).map(|b| b % blocks) {
                for k in b * block..(b + 1) * block {
                    let bound = problem.bounds()[k];
                    x[k] = if redraw {
                        fresh[k]
                    } else {
                        bound.project(x[k] + 0.01 * bound.width() * (fresh[k] - x[k]).signum())
                    };
                }
            }
            let incremental = outcome(&problem, &x, &mut warm);
            let full = outcome(&problem, &x, &mut Scratch::default());
            prop_assert_eq!(incremental, full);
            let incremental = summed(&problem, &x, &mut warm_summing);
            let full = summed(&problem, &x, &mut Scratch::default());
            prop_assert_eq!(incremental, full);
        }
    }
}

/// A problem on world `index`, a vector drawn from its initialisation with `seed`, and
/// buffers warmed by one evaluation of it (with its outcome).
fn evaluated_once(
    index: usize,
    seed: u64,
) -> (PlanningProblem<'static>, Vec<f64>, Scratch, Outcome) {
    let problem = PlanningProblem::new(&worlds()[index], EncodingKind::Spherical, InitKind::Line);
    let mut rng = rng_from_seed(seed);
    let mut x = vec![0.0; problem.dimension()];
    problem.sample_initial(&mut rng, &mut x);
    let mut warm = Scratch::default();
    let first = outcome(&problem, &x, &mut warm);
    (problem, x, warm, first)
}

/// The property above would hold trivially if nothing was ever reused: on a plan changed in
/// one UAV of ten, the warm buffers must sweep fewer pairs than fresh ones.
#[test]
fn a_change_to_one_uav_reuses_the_other_pairs() {
    let (problem, mut x, mut warm, _) = evaluated_once(2, 7);
    assert_eq!(
        warm.pairs_swept(),
        45,
        "a first evaluation sweeps all 10 x 9 / 2 pairs"
    );
    let k = problem.block_size() + 1;
    x[k] = problem.bounds()[k].project(x[k] + 0.05 * problem.bounds()[k].width());
    let _ = outcome(&problem, &x, &mut warm);
    assert_eq!(
        warm.pairs_swept(),
        9,
        "UAV 1 changed: only its 9 pairs are swept again"
    );
}

/// Under common arrival a change of pace only rescales time, which the pair results follow
/// exactly: no pair is swept again, and the result is that of fresh buffers.
#[test]
fn a_change_of_pace_alone_sweeps_no_pair_again() {
    let (problem, mut x, mut warm, before) = evaluated_once(3, 8);
    assert_eq!(warm.pairs_swept(), 10);
    let k = problem.block_size() - 1; // UAV 0's pace value
    x[k] = problem.bounds()[k].project(x[k] + 0.2);
    let after = outcome(&problem, &x, &mut warm);
    assert_eq!(warm.pairs_swept(), 0);
    assert_ne!(before.0, after.0, "the pace changed the cost");
    assert_eq!(after, outcome(&problem, &x, &mut Scratch::default()));
}

/// With departure delays free, every UAV block ends with its delay, and a plan drawn from
/// the initialisation waits: some UAV departs after t = 0 and hovers at its start.
#[test]
fn free_delays_add_a_value_per_block_that_the_plan_waits_for() {
    let paced = PlanningProblem::new(&worlds()[3], EncodingKind::Spherical, InitKind::Line);
    let delayed = PlanningProblem::new(&worlds()[5], EncodingKind::Spherical, InitKind::Line);
    assert_eq!(delayed.block_size(), paced.block_size() + 1);
    let bounds = delayed.bounds();
    let block = delayed.block_size();
    for b in 0..delayed.dimension() / block {
        let last = bounds[(b + 1) * block - 1];
        assert_eq!((last.lo, last.hi), (0.0, 0.4));
    }
    let mut x = vec![0.0; delayed.dimension()];
    delayed.sample_initial(&mut rng_from_seed(3), &mut x);
    let plan = delayed.decode(&x);
    assert_eq!(plan.delays.len(), 5);
    assert!(plan.delays.iter().all(|d| (0.0..=0.4).contains(d)));
    assert!(plan.delays.iter().any(|d| *d > 0.0));
    let timed = swarmplan_core::timing::TimedPlan::new(delayed.world(), &plan);
    let (u, tp) = timed
        .paths
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.depart.total_cmp(&b.1.depart))
        .unwrap();
    assert!(tp.depart > 0.0);
    let start = tp.abs[0];
    assert_eq!(tp.position_at_time(0.5 * tp.depart), start, "uav {u}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// A bounded evaluation (the cooperative method's moved particles,
    /// `Problem::evaluate_blocks_bounded`) either gives up, and then the full violation is
    /// above the cutoff, or returns the full evaluation bit for bit, block shares included;
    /// on warm buffers in a sequence of evaluations as a search makes them, under both
    /// objective presets.
    #[test]
    fn a_bounded_evaluation_is_the_full_one_or_gives_up_only_above_the_cutoff(
        world_index in 0usize..9,
        seed in any::<u64>(),
        cutoffs in prop::collection::vec(prop_oneof![Just(0.0), 0.0f64..3.0, 0.0f64..300.0], 1..8),
    ) {
        let world = &worlds_and_spso_presets()[world_index];
        let problem = PlanningProblem::new(world, EncodingKind::Spherical, InitKind::Line);
        let mut rng = rng_from_seed(seed);
        let mut x = vec![0.0; problem.dimension()];
        let (mut full_shares, mut bounded_shares) = (Vec::new(), Vec::new());
        for cutoff in cutoffs {
            problem.sample_initial(&mut rng, &mut x);
            let full = problem.evaluate_blocks(&x, &mut full_shares);
            match problem.evaluate_blocks_bounded(&x, &mut bounded_shares, cutoff) {
                None => prop_assert!(full.violation > cutoff, "{} <= {cutoff}", full.violation),
                Some(b) => {
                    prop_assert_eq!(b.cost.to_bits(), full.cost.to_bits());
                    prop_assert_eq!(b.violation.to_bits(), full.violation.to_bits());
                    prop_assert_eq!(&bounded_shares, &full_shares);
                }
            }
            // And a full evaluation after it on the same (thread's) buffers is unchanged.
            let again = problem.evaluate_blocks(&x, &mut full_shares);
            prop_assert_eq!(again.cost.to_bits(), full.cost.to_bits());
        }
    }
}

/// The property above must see both outcomes: a plan from the initialisation of
/// paper-case2 is infeasible, so a cutoff of 0 gives it up and +inf does not.
#[test]
fn bounded_evaluations_give_up_below_the_violation_and_not_above() {
    let problem = PlanningProblem::new(&worlds()[0], EncodingKind::Spherical, InitKind::Line);
    let mut x = vec![0.0; problem.dimension()];
    problem.sample_initial(&mut rng_from_seed(1), &mut x);
    let mut shares = Vec::new();
    let full = problem.evaluate_blocks(&x, &mut shares);
    assert!(full.violation > 0.0);
    assert!(problem
        .evaluate_blocks_bounded(&x, &mut shares, 0.0)
        .is_none());
    let kept = problem
        .evaluate_blocks_bounded(&x, &mut shares, full.violation)
        .unwrap();
    assert_eq!(kept.violation.to_bits(), full.violation.to_bits());
}

/// The worlds of [`worlds`], then two under the `spso-mycost` objective preset (SPSO's MyCost: no
/// fleet terms, collisions at +inf; one UAV): spso-case1 and spso-case2 on the procedural
/// terrain.
fn worlds_and_spso_presets() -> &'static [World] {
    static W: OnceLock<Vec<World>> = OnceLock::new();
    W.get_or_init(|| {
        let spso = |name: &str| {
            let mut loaded = load_spec(name).unwrap();
            loaded.spec.objective.preset = ObjectivePreset::SpsoMycost;
            build_world(&loaded, None).unwrap()
        };
        let mut all = worlds().to_vec();
        all.push(spso("spso-case1"));
        all.push(spso("spso-case2"));
        all
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(40))]

    /// A cost-bounded evaluation (the PSO family's, QPSO's, ABC's and GWO's candidates,
    /// `Problem::evaluate_cost_bounded`), which may give up after the waypoint terms, the
    /// flown terms or the communication sweep, either gives up, and then the full cost is
    /// above the cutoff, or returns the full evaluation bit for bit; cutoffs within 30 % of
    /// the plan's cost, on warm buffers, under both objective presets.
    #[test]
    fn a_cost_bounded_evaluation_is_the_full_one_or_gives_up_only_above_the_cutoff(
        world_index in 0usize..9,
        seed in any::<u64>(),
        shares in prop::collection::vec(-0.3f64..0.3, 1..8),
    ) {
        let world = &worlds_and_spso_presets()[world_index];
        let problem = PlanningProblem::new(world, EncodingKind::Spherical, InitKind::Line);
        let mut rng = rng_from_seed(seed);
        let mut x = vec![0.0; problem.dimension()];
        for share in shares {
            problem.sample_initial(&mut rng, &mut x);
            let full = problem.evaluate(&x);
            let cutoff = full.cost * (1.0 + share);
            match problem.evaluate_cost_bounded(&x, cutoff) {
                None => prop_assert!(full.cost > cutoff, "{} <= {cutoff}", full.cost),
                Some(b) => {
                    prop_assert_eq!(b.cost.to_bits(), full.cost.to_bits());
                    prop_assert_eq!(b.violation.to_bits(), full.violation.to_bits());
                }
            }
            let again = problem.evaluate(&x);
            prop_assert_eq!(again.cost.to_bits(), full.cost.to_bits());
        }
    }
}

/// Under the `spso-mycost` objective preset a cost-bounded evaluation gives up too: SPSO's terms on the
/// waypoints are its whole cost, so a plan costing twice the cutoff is not assessed further,
/// and a plan that collides (+inf) is given up at its first collision under any finite
/// cutoff (`f64::MAX`, what a particle whose pbest collides passes), while one that does not
/// is then assessed in full, bit for bit.
#[test]
fn a_cost_bounded_evaluation_gives_up_under_the_spso_preset() {
    let mut finite = 0;
    let mut infinite = 0;
    for (world, init) in [
        (&worlds_and_spso_presets()[7], InitKind::Corridor),
        (&worlds_and_spso_presets()[7], InitKind::Uniform),
        (&worlds_and_spso_presets()[8], InitKind::Uniform),
    ] {
        let problem = PlanningProblem::new(world, EncodingKind::Spherical, init);
        let mut rng = rng_from_seed(1);
        let mut x = vec![0.0; problem.dimension()];
        for _ in 0..20 {
            problem.sample_initial(&mut rng, &mut x);
            let full = problem.evaluate(&x);
            let bounded = problem.evaluate_cost_bounded(&x, f64::MAX);
            if full.cost.is_finite() {
                finite += 1;
                assert!(problem.evaluate_cost_bounded(&x, 0.5 * full.cost).is_none());
                for cutoff in [full.cost, f64::MAX] {
                    let kept = problem.evaluate_cost_bounded(&x, cutoff).unwrap();
                    assert_eq!(kept.cost.to_bits(), full.cost.to_bits());
                    assert_eq!(kept.violation.to_bits(), full.violation.to_bits());
                }
            } else {
                infinite += 1;
                assert!(bounded.is_none());
            }
        }
    }
    assert!(
        finite > 0 && infinite > 0,
        "{finite} finite, {infinite} infinite"
    );
}

/// A bounded assessment fills a UAV's turn tangents before any arc and may give up there
/// (`TimedPlan::fill_tangents`); the arcs built afterwards, for that plan or another, are
/// those of a fresh flown plan bit for bit.
#[test]
fn tangents_filled_ahead_of_the_arcs_leave_the_flown_paths_as_fresh_ones() {
    use swarmplan_core::timing::TimedPlan;
    let world = &worlds()[0];
    assert!(world.flies_arcs());
    let problem = PlanningProblem::new(world, EncodingKind::Spherical, InitKind::Line);
    let mut rng = rng_from_seed(3);
    let mut x = vec![0.0; problem.dimension()];
    let mut draw = || {
        problem.sample_initial(&mut rng, &mut x);
        problem.decode(&x)
    };
    let (a, b) = (draw(), draw());
    let (wa, wb) = (TimedPlan::new(world, &a), TimedPlan::new(world, &b));
    let (fresh_a, fresh_b) = (TimedPlan::flown(world, &a), TimedPlan::flown(world, &b));
    let same = |warm: &TimedPlan, fresh: &TimedPlan, arcs: bool| {
        for (w, f) in warm.paths.iter().zip(&fresh.paths) {
            let bits = |v: &[f64]| v.iter().map(|t| t.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&w.tangents), bits(&f.tangents));
            if arcs {
                assert_eq!(w.abs, f.abs);
                assert_eq!(w.flown, f.flown);
                assert_eq!(w.arrival.to_bits(), f.arrival.to_bits());
            }
        }
    };
    let mut warm = TimedPlan::default();
    warm.fill_flown(world, &wa);
    same(&warm, &fresh_a, true);
    // b's tangents only, as in an assessment of b given up on the turning radius.
    warm.fill_tangents(world, &wb);
    same(&warm, &fresh_b, false);
    warm.fill_flown(world, &wa);
    same(&warm, &fresh_a, true);
    warm.fill_tangents(world, &wb);
    warm.fill_flown(world, &wb);
    same(&warm, &fresh_b, true);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(30))]

    /// Evaluations on a slot's own buffers (ABC's candidates, on their food source's:
    /// `Problem::evaluate_cost_bounded_in`) are those on the common buffers: each candidate
    /// a one-coordinate change of its slot's point, as ABC makes them, slots drawn at random
    /// (one beyond the slots with buffers of their own).
    #[test]
    fn an_evaluation_on_a_slots_buffers_is_the_one_on_the_common_buffers(
        world_index in 0usize..7,
        seed in any::<u64>(),
        moves in prop::collection::vec((0usize..3, any::<u64>(), -0.2f64..0.2), 1..12),
    ) {
        use rand::Rng as _;
        let world = &worlds()[world_index];
        let problem = PlanningProblem::new(world, EncodingKind::Spherical, InitKind::Line);
        let mut rng = rng_from_seed(seed);
        let dim = problem.dimension();
        let slots = [0, 1, swarmplan_core::planning::BUFFER_SLOTS + 1];
        let mut points = vec![vec![0.0; dim]; slots.len()];
        for p in &mut points {
            problem.sample_initial(&mut rng, p);
        }
        for (which, draw, share) in moves {
            let mut local = rng_from_seed(draw);
            let x = &mut points[which];
            let j = local.random_range(0..dim);
            let b = problem.bounds()[j];
            x[j] = (x[j] + share * (b.hi - b.lo)).clamp(b.lo, b.hi);
            let full = problem.evaluate(x);
            let cutoff = if share > 0.0 { f64::INFINITY } else { full.cost * (1.0 + share) };
            match problem.evaluate_cost_bounded_in(x, cutoff, slots[which]) {
                None => prop_assert!(full.cost > cutoff),
                Some(e) => {
                    prop_assert_eq!(e.cost.to_bits(), full.cost.to_bits());
                    prop_assert_eq!(e.violation.to_bits(), full.violation.to_bits());
                }
            }
        }
    }
}

/// Thread-local buffers serve every problem evaluated on their thread, so what they keep of
/// one world (each UAV's own terms) must not be served to another with the same geometry:
/// here paper-case1 with wider threats, the same plan evaluated on buffers warmed by the
/// original.
#[test]
fn buffers_that_served_one_world_serve_another_afresh() {
    let a = &worlds()[0];
    let mut spec = a.spec().clone();
    for t in &mut spec.threats {
        t.r *= 1.5;
    }
    let b = World::new(spec, a.terrain().clone()).unwrap();
    let (pa, pb) = (
        PlanningProblem::new(a, EncodingKind::Spherical, InitKind::Line),
        PlanningProblem::new(&b, EncodingKind::Spherical, InitKind::Line),
    );
    let mut rng = rng_from_seed(3);
    let mut x = vec![0.0; pa.dimension()];
    pa.sample_initial(&mut rng, &mut x);
    let mut warm = Scratch::default();
    let on_a = summed(&pa, &x, &mut warm);
    let fresh_b = summed(&pb, &x, &mut Scratch::default());
    assert_ne!(
        on_a.1, fresh_b.1,
        "the worlds must differ in what the plan violates"
    );
    assert_eq!(summed(&pb, &x, &mut warm), fresh_b);
    // A clone is a world of its own too (it is what one edits).
    assert_ne!(a.clone().id(), a.id());
}
