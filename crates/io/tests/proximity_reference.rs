//! Proximity (Eq. 8 and separation) against a slow reference written another way
//! (issue 47, item 4).
//!
//! The fast sweep (`cost/proximity.rs`, `cost/interval_batch.rs`) merges each pair's motions
//! into intervals in its own time unit, computes every interval's closed-form integral with
//! its own arctangent in a vectorised loop, and keeps pair results between evaluations that
//! change one UAV. The reference here shares none of that: it reads positions from
//! `TimedPath::position_at_time` in seconds, finds where each UAV leaves its start zone and
//! last enters UGV0's by bisection on a fine time grid, integrates 1 / (d^2 + eps) by
//! adaptive Simpson quadrature between the vertex times of both paths, and finds each pair's
//! closest approach by ternary search on those pieces. Every UAV's proximity term must agree
//! within 1e-9 relative, and the pairs that lose separation must be the same, at the same
//! closest distance within a micrometre; over random plans, and over sequences of changes
//! to one UAV on one scratch (the memo of pair results), on worlds with common arrival and
//! cruise timing, departure delays (hovering), a shared start and ten UAVs.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use glam::DVec3;
use rand::Rng as _;
use swarmplan_core::cost::proximity::{proximity, ProximityScratch};
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::feasibility::{ViolationKind, ViolationSink};
use swarmplan_core::plan::Plan;
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::{BlockProblem, Problem};
use swarmplan_core::quadrature::adaptive_simpson;
use swarmplan_core::rng::rng_from_seed;
use swarmplan_core::timing::{TimedPath, TimedPlan};
use swarmplan_core::world::spec::TimingPolicy;
use swarmplan_core::world::World;
use swarmplan_io::catalog::load_spec;
use swarmplan_io::scenario::build_world;

/// The times at which a path passes its vertices (its motion's kinks), in seconds.
fn kinks(p: &TimedPath) -> Vec<f64> {
    let mut t = vec![p.depart];
    if p.speed > 0.0 {
        t.extend(p.cum.iter().map(|c| p.depart + c / p.speed));
    }
    t
}

/// First time `p` is horizontally farther than `r` from `c` (infinite if never), or, with
/// `last_entry`, the last time it comes within `r` of `c` (0 if always within): a scan of
/// a 0.02 s grid, then bisection.
fn zone_time(p: &TimedPath, c: DVec3, r: f64, last_entry: bool) -> f64 {
    let outside = |t: f64| p.position_at_time(t).truncate().distance(c.truncate()) > r;
    let end = p.arrival + 1.0;
    let steps = (end / 0.02).ceil() as usize;
    let grid = |k: usize| k as f64 * 0.02;
    let crossing = |(mut lo, mut hi): (f64, f64), want_outside_at_hi: bool| {
        for _ in 0..80 {
            let m = 0.5 * (lo + hi);
            if outside(m) == want_outside_at_hi {
                hi = m;
            } else {
                lo = m;
            }
        }
        hi
    };
    if last_entry {
        if !outside(0.0) && (0..=steps).all(|k| !outside(grid(k))) {
            return 0.0;
        }
        // Walking back from the end: the last grid step that goes from outside to inside.
        for k in (0..steps).rev() {
            if outside(grid(k)) && !outside(grid(k + 1)) {
                return crossing((grid(k + 1), grid(k)), true);
            }
        }
        0.0
    } else {
        for k in 0..steps {
            if !outside(grid(k)) && outside(grid(k + 1)) {
                return crossing((grid(k), grid(k + 1)), true);
            }
            if k == 0 && outside(0.0) {
                return 0.0;
            }
        }
        f64::INFINITY
    }
}

/// Per UAV, its proximity term (or, of the reference, its share of the pair integrals
/// alone); per pair that loses separation, its closest distance.
type Reference = (Vec<f64>, Vec<((usize, usize), f64)>);

/// Per UAV, the waypoint-to-threat part of its term.
fn threat_shares(world: &World, plan: &Plan) -> Vec<f64> {
    let spec = world.spec();
    let eps = spec.objective.obstacle_epsilon;
    plan.uavs
        .iter()
        .enumerate()
        .map(|(u, path)| {
            let size = spec.uavs[u].size;
            path.waypoints
                .iter()
                .flat_map(|w| {
                    spec.threats.iter().map(move |t| {
                        let d = (w.truncate().distance(glam::DVec2::new(t.x, t.y)) - t.r - size)
                            .max(0.0);
                        1.0 / (d * d + eps)
                    })
                })
                .sum()
        })
        .collect()
}

fn reference(world: &World, timed: &TimedPlan) -> Reference {
    let spec = world.spec();
    let eps = spec.objective.obstacle_epsilon;
    let (zone, sep) = (spec.timing.zone_radius, spec.timing.separation);
    let goal = world.goal_at(0.0);
    let n = timed.paths.len();
    let mut out = vec![0.0; n];
    let windows: Vec<(f64, f64)> = timed
        .paths
        .iter()
        .map(|p| {
            (
                zone_time(p, p.abs[0], zone, false),
                zone_time(p, goal, zone, true),
            )
        })
        .collect();
    let mut lost = Vec::new();
    for i in 0..n {
        for j in i + 1..n {
            let (from, to) = (
                windows[i].0.max(windows[j].0),
                windows[i].1.min(windows[j].1),
            );
            if to <= from {
                continue;
            }
            let (a, b) = (&timed.paths[i], &timed.paths[j]);
            let distance = |t: f64| a.position_at_time(t).distance(b.position_at_time(t));
            let f = |t: f64| 1.0 / (distance(t).powi(2) + eps);
            let mut cuts: Vec<f64> = kinks(a)
                .into_iter()
                .chain(kinks(b))
                .filter(|t| *t > from && *t < to)
                .collect();
            cuts.push(from);
            cuts.push(to);
            cuts.sort_by(f64::total_cmp);
            let mut integral = 0.0;
            let mut closest = f64::INFINITY;
            for w in cuts.windows(2) {
                integral += adaptive_simpson(&f, (w[0], w[1]), 1e-12, 60);
                // The distance is convex on a piece where both fly straight.
                let (mut lo, mut hi) = (w[0], w[1]);
                for _ in 0..200 {
                    let (m1, m2) = (lo + (hi - lo) / 3.0, hi - (hi - lo) / 3.0);
                    if distance(m1) <= distance(m2) {
                        hi = m2;
                    } else {
                        lo = m1;
                    }
                }
                closest = closest
                    .min(distance(w[0]))
                    .min(distance(w[1]))
                    .min(distance(0.5 * (lo + hi)));
            }
            out[i] += 0.5 * integral;
            out[j] += 0.5 * integral;
            if closest < sep {
                lost.push(((i, j), closest));
            }
        }
    }
    (out, lost)
}

/// The fast sweep's terms, and per pair its closest separation loss.
fn fast(
    world: &World,
    plan: &Plan,
    timed: &TimedPlan,
    scratch: &mut ProximityScratch,
) -> Reference {
    let mut out = vec![0.0; timed.paths.len()];
    let mut sink = ViolationSink::collecting(world.spec().planning.profile);
    proximity(world, plan, timed, scratch, &mut sink, &mut out);
    let sep = world.spec().timing.separation;
    let mut lost: Vec<((usize, usize), f64)> = Vec::new();
    for v in sink.list.unwrap() {
        if v.kind != ViolationKind::Separation {
            continue;
        }
        let pair = (v.uav, v.other.unwrap());
        let d = sep - v.amount;
        match lost.iter_mut().find(|(p, _)| *p == pair) {
            Some((_, closest)) => *closest = closest.min(d),
            None => lost.push((pair, d)),
        }
    }
    (out, lost)
}

fn timed(world: &World, plan: &Plan) -> TimedPlan {
    if world.flies_arcs() {
        TimedPlan::flown(world, plan)
    } else {
        TimedPlan::new(world, plan)
    }
}

/// The fast terms less the threat shares against the reference's pair shares: within
/// 1e-9 relative, plus the rounding of the subtraction.
fn agree(name: &str, got: &Reference, want: &Reference, shares: &[f64]) {
    for (u, ((g, w), s)) in got.0.iter().zip(&want.0).zip(shares).enumerate() {
        let pairs = g - s;
        assert!(
            (pairs - w).abs() <= 1e-9 * w.abs() + 1e-14 * g.abs(),
            "{name}: UAV {u}: pair share {pairs} against {w}"
        );
    }
    let pairs = |r: &Reference| r.1.iter().map(|(p, _)| *p).collect::<Vec<_>>();
    let (mut gp, mut wp) = (pairs(got), pairs(want));
    gp.sort_unstable();
    wp.sort_unstable();
    assert_eq!(gp, wp, "{name}: pairs that lose separation");
    for (pair, d) in &got.1 {
        let w = want.1.iter().find(|(p, _)| p == pair).unwrap().1;
        assert!(
            (d - w).abs() < 1e-6,
            "{name}: {pair:?} closest {d} against {w}"
        );
    }
}

#[test]
fn proximity_agrees_with_the_slow_reference() {
    let load = |name: &str, cruise: bool, max_delay: f64| {
        let mut loaded = load_spec(name).unwrap();
        if cruise {
            loaded.spec.timing.policy = TimingPolicy::Cruise;
        }
        loaded.spec.timing.max_delay = max_delay;
        build_world(&loaded, None).unwrap()
    };
    let worlds = [
        ("paper-case2", load("paper-case2", false, 0.0)),
        ("paper-case1 with delays", load("paper-case1", false, 0.4)),
        (
            "gen-s2-u8-t12-shared cruise",
            load("gen-s2-u8-t12-shared", true, 0.0),
        ),
        ("gen-s1-u10-t12", load("gen-s1-u10-t12", false, 0.0)),
    ];
    let (mut separation_losses, mut pair_share, mut total) = (0, 0.0, 0.0);
    for (name, world) in &worlds {
        let problem = PlanningProblem::new(world, EncodingKind::Spherical, InitKind::Uniform);
        let mut rng = rng_from_seed(47);
        let mut scratch = ProximityScratch::default();
        let mut x = vec![0.0; problem.dimension()];
        problem.sample_initial(&mut rng, &mut x);
        for step in 0..12 {
            // Half the steps draw a new plan, half move one UAV's block (the memo's case).
            if step % 2 == 0 {
                problem.sample_initial(&mut rng, &mut x);
            } else {
                let block = problem.block_size();
                let b = rng.random_range(0..problem.dimension() / block);
                for j in b * block..(b + 1) * block {
                    let bound = problem.bounds()[j];
                    x[j] = bound.project(x[j] + 0.02 * bound.width() * rng.random_range(-1.0..1.0));
                }
            }
            let plan = problem.decode(&x);
            let timed = timed(world, &plan);
            let want = reference(world, &timed);
            let got = fast(world, &plan, &timed, &mut scratch);
            separation_losses += want.1.len();
            pair_share += want.0.iter().sum::<f64>();
            total += got.0.iter().sum::<f64>();
            agree(
                &format!("{name}, step {step}"),
                &got,
                &want,
                &threat_shares(world, &plan),
            );
        }
    }
    assert!(
        separation_losses > 0,
        "no plan lost separation: the verdicts went untested"
    );
    assert!(
        pair_share > 0.01 * total,
        "pair integrals {pair_share} of {total}"
    );
}
