//! The defaults make cooperation matter (calibration in docs/model.md): in both paper cases
//! the straight start-to-goal plan is infeasible because of threats, and, since it ignores
//! communication, it also loses contact (the interference windows sit on the direct route).

#![allow(clippy::unwrap_used)] // tests fail loudly by design

mod common;

use common::{build_world, load_spec};

use swarmplan_core::feasibility::{check, ViolationKind};
use swarmplan_core::plan::Plan;

#[test]
fn the_straight_plan_hits_threats_and_loses_contact_in_both_cases() {
    for case in ["paper-case1", "paper-case2"] {
        let world = build_world(&load_spec(case).unwrap(), None).unwrap();
        let starts: Vec<_> = (0..world.uav_count()).map(|i| world.start(i)).collect();
        let plan = Plan::straight(
            &starts,
            world.goal_at(swarmplan_core::world::DEPARTURE),
            world.spec().planning.waypoints,
        );
        let v = check(&world, &plan);
        for kind in [ViolationKind::Threat, ViolationKind::Comm] {
            assert!(
                v.iter().any(|x| x.kind == kind),
                "{case}: no {kind:?} violation in {v:?}"
            );
        }
        // Every UAV of the fleet is out of contact too long, not just one.
        let out: std::collections::BTreeSet<usize> = v
            .iter()
            .filter(|x| x.kind == ViolationKind::Comm)
            .map(|x| x.uav)
            .collect();
        assert_eq!(out.len(), world.uav_count(), "{case}");
    }
}

#[test]
fn tracing_per_uav_costs_does_not_change_the_run() {
    use swarmplan_core::method::Method;
    use swarmplan_core::optim::{Budget, OptimizerParams};
    use swarmplan_core::run::{run, run_with_uav_trace, RunRequest};
    let world = build_world(&load_spec("tiny").unwrap(), None).unwrap();
    // dls-smpso changes many UAVs at once; swarmplan's coevolution one at a time, so its
    // trace reuses the pair sweeps of the rows before.
    for preset in ["dls-smpso", "swarmplan"] {
        let req = RunRequest {
            method: Method::preset(preset).expect("a preset"),
            params: OptimizerParams::default(),
            budget: Budget::iterations(15),
            seed: 11,
        };
        let plain = run(&world, &req, &mut |_| {});
        let (traced, trace) = run_with_uav_trace(&world, &req, &mut |_| {});
        assert_eq!(plain.outcome.best_x, traced.outcome.best_x, "{preset}");
        assert_eq!(plain.outcome.evaluations, traced.outcome.evaluations);
        assert_eq!(trace.len(), traced.outcome.trace.len());
        let last = trace.last().unwrap();
        for (c, u) in last.iter().zip(&traced.assessment.per_uav) {
            assert_eq!(c.to_bits(), u.cost.to_bits(), "{preset}: {c} vs {}", u.cost);
        }
        // An iteration that keeps the best shares its row with the iteration before (one
        // row in memory per change of the best), and a shared row means an unchanged best.
        let mut shared = 0;
        for (k, pair) in trace.windows(2).enumerate() {
            let r = &traced.outcome.trace;
            if std::sync::Arc::ptr_eq(&pair[0], &pair[1]) {
                shared += 1;
                assert_eq!(r[k].best_cost.to_bits(), r[k + 1].best_cost.to_bits());
            }
        }
        assert!(shared > 0, "{preset}: no iteration kept its best");
    }
}
