//! Property tests: encodings always decode into the box, angles wrap, and every cost term is
//! finite and non-negative (and NaN never reaches a comparison) for arbitrary inputs on the
//! paper's Case 1 world.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{build_world, load_spec};

use std::sync::OnceLock;
use swarmplan_core::problem::BlockProblem;

use proptest::prelude::*;
use swarmplan_core::cost::assess;
use swarmplan_core::encoding::{
    angle::Angle, build, EncodingKind, InitKind, PathEncoding, PathFrame,
};
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::Problem;
use swarmplan_core::world::World;

fn world() -> &'static World {
    static W: OnceLock<World> = OnceLock::new();
    W.get_or_init(|| build_world(&load_spec("paper-case1").unwrap(), None).unwrap())
}

const DIM: usize = 150;

/// Values spread over and beyond a bound: the decoder must clamp what optimizers send.
fn raw_vector() -> impl Strategy<Value = Vec<f64>> {
    prop::collection::vec(-2.0f64..2.0, DIM)
}

fn into_bounds(u: &[f64], enc: &dyn PathEncoding) -> Vec<f64> {
    u.iter()
        .zip(enc.bounds())
        .map(|(v, b)| b.lo + (v + 2.0) / 4.0 * 1.4 * b.width() - 0.2 * b.width())
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn decoded_waypoints_stay_in_the_box(u in raw_vector(), kind in prop::sample::select(EncodingKind::ALL.to_vec())) {
        let w = world();
        let enc = build(kind, w);
        let x = into_bounds(&u, enc.as_ref());
        let plan = enc.decode(&x);
        let m = &w.spec().map;
        prop_assert_eq!(plan.uavs.len(), 5);
        for (i, p) in plan.uavs.iter().enumerate() {
            prop_assert_eq!(p.waypoints[0], w.start(i));
            prop_assert_eq!(*p.waypoints.last().unwrap(), w.goal_at(swarmplan_core::world::DEPARTURE));
            for q in &p.waypoints[1..p.waypoints.len() - 1] {
                prop_assert!(q.x >= m.x[0] && q.x <= m.x[1], "x {}", q.x);
                prop_assert!(q.y >= m.y[0] && q.y <= m.y[1], "y {}", q.y);
                prop_assert!(q.z >= m.z_agl[0] && q.z <= m.z_agl[1], "z {}", q.z);
            }
        }
    }

    #[test]
    fn spherical_headings_wrap(u in raw_vector(), turns in -3i32..3) {
        let w = world();
        let enc = build(EncodingKind::Spherical, w);
        let x = into_bounds(&u, enc.as_ref());
        let mut shifted = x.clone();
        // phi is the third run of each UAV's block.
        for i in 0..5 {
            for k in 20..30 {
                shifted[30 * i + k] += f64::from(turns) * std::f64::consts::TAU;
            }
        }
        let (a, b) = (enc.decode(&x), enc.decode(&shifted));
        for (p, q) in a.uavs.iter().zip(&b.uavs) {
            for (r, s) in p.waypoints.iter().zip(&q.waypoints) {
                prop_assert!(r.distance(*s) < 1e-6);
            }
        }
    }

    #[test]
    fn periodic_angle_encoding_wraps(u in raw_vector(), turns in -3i32..3) {
        let enc = Angle::new(PathFrame::of(world()), true);
        let x: Vec<f64> = u.iter().map(|v| v * 1.5).collect();
        let shifted: Vec<f64> = x.iter().map(|v| v + f64::from(turns) * std::f64::consts::TAU).collect();
        let projected: Vec<f64> = shifted.iter().zip(enc.bounds()).map(|(v, b)| b.project(*v)).collect();
        let (a, b) = (enc.decode(&x), enc.decode(&projected));
        for (p, q) in a.uavs.iter().zip(&b.uavs) {
            for (r, s) in p.waypoints.iter().zip(&q.waypoints) {
                prop_assert!(r.distance(*s) < 1e-6);
            }
        }
    }

    #[test]
    fn cost_terms_are_finite_and_non_negative(u in raw_vector(), kind in prop::sample::select(EncodingKind::ALL.to_vec())) {
        let w = world();
        let enc = build(kind, w);
        let x = into_bounds(&u, enc.as_ref());
        let a = assess(w, &enc.decode(&x));
        for r in &a.per_uav {
            for v in r.raw.iter().chain(r.weighted.iter()).map(|(_, v)| v) {
                prop_assert!(v.is_finite() && v >= 0.0, "term {}", v);
            }
            prop_assert!(r.energy_j.is_finite() && r.energy_j > 0.0);
        }
        prop_assert!(a.total.is_finite() && a.total >= 0.0);
        prop_assert!(a.violation >= 0.0 && a.violation.is_finite());
        prop_assert_eq!(a.feasible(), a.violations.as_ref().unwrap().is_empty());
    }

    #[test]
    fn nan_inputs_never_produce_a_nan_cost(u in raw_vector(), holes in prop::collection::vec(0usize..DIM, 1..5)) {
        let w = world();
        let p = PlanningProblem::new(w, EncodingKind::Spherical, InitKind::Uniform);
        let mut x = into_bounds(&u, &*swarmplan_core::encoding::build(EncodingKind::Spherical, w));
        for h in holes {
            x[h] = f64::NAN;
        }
        let e = p.evaluate(&x);
        prop_assert!(!e.cost.is_nan() && !e.violation.is_nan());
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// `evaluate_blocks` is `evaluate` plus each UAV's share of the violation, and a UAV has
    /// a share exactly when a hard violation of the full assessment names it (as its UAV or,
    /// for separation, as the other one).
    #[test]
    fn violation_shares_name_the_uavs_of_the_hard_violations(u in raw_vector(), kind in prop::sample::select(EncodingKind::ALL.to_vec())) {
        let w = world();
        let problem = PlanningProblem::new(w, kind, InitKind::Uniform);
        let enc = build(kind, w);
        let x = into_bounds(&u, enc.as_ref());
        let x: Vec<f64> = x.iter().zip(problem.bounds()).map(|(v, b)| b.project(*v)).collect();
        let mut shares = Vec::new();
        let e = problem.evaluate_blocks(&x, &mut shares);
        prop_assert_eq!(e, problem.evaluate(&x));
        prop_assert_eq!(shares.len(), 5);
        let a = problem.assess(&x);
        let list = a.violations.unwrap_or_default();
        for (i, share) in shares.iter().enumerate() {
            let named = list.iter().any(|v| v.hard && (v.uav == i || v.other == Some(i)));
            prop_assert_eq!(*share > 0.0, named, "UAV {}: share {}", i, share);
            prop_assert!(*share <= e.violation + 1e-9);
        }
        prop_assert_eq!(e.violation == 0.0, shares.iter().all(|s| *s == 0.0));
    }
}
