//! Calibration of the paper cases' defaults (docs/model.md quotes its output):
//! 1. the straight start-to-goal plan and what it violates;
//! 2. "each UAV planned alone": DLS-SMPSO on a one-UAV copy of the case with communication
//!    and separation switched off (5 seeds, one path per UAV), then the fleet of those
//!    paths assessed in the full model: contact lost?
//! 3. the cooperative plan: DLS-SMPSO on the full model over 10 seeds: feasible share,
//!    outage, and how often a UAV was in contact only through a relay.
//!
//! Run: `cargo run --release -p swarmplan-io --example calibrate [CASE...]`

use swarmplan_core::cost::assess;
use swarmplan_core::cost::comm::{contact_at, Contact};
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_core::plan::Plan;
use swarmplan_core::run::{run, RunRequest};
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::spec::CommRequirement;
use swarmplan_core::world::World;
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

fn request(seed: u64) -> RunRequest {
    RunRequest {
        method: Method::preset("dls-smpso").expect("a preset"),
        params: OptimizerParams::default(),
        budget: Budget::iterations(200),
        seed,
    }
}

/// Seconds in which some UAV is in contact only through another UAV.
fn relayed_seconds(world: &World, plan: &Plan) -> usize {
    let timed = TimedPlan::new(world, plan);
    let steps = timed.horizon.ceil() as usize;
    (0..=steps)
        .filter(|k| {
            let t = *k as f64;
            let pos: Vec<_> = timed.paths.iter().map(|p| p.position_at_time(t)).collect();
            contact_at(world, t, &pos).contains(&Contact::Relayed)
        })
        .count()
}

fn kinds(a: &swarmplan_core::cost::Assessment) -> String {
    let mut k: Vec<&str> = a
        .violations
        .iter()
        .flatten()
        .map(|v| v.kind.name())
        .collect();
    k.sort_unstable();
    k.dedup();
    k.join(",")
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let cases: Vec<String> = std::env::args().skip(1).collect();
    let cases = if cases.is_empty() {
        vec!["paper-case1".to_string(), "paper-case2".to_string()]
    } else {
        cases
    };
    for case in cases {
        let loaded = load_spec(&case)?;
        let world = build_world(&loaded, None)?;
        let n = world.uav_count();
        println!(
            "== {case}: R0 {} m, {} interference window(s)",
            world.spec().communication.range,
            world.spec().communication.interference.len()
        );

        let straight = Plan::straight(
            &(0..n).map(|i| world.start(i)).collect::<Vec<_>>(),
            world.goal_at(swarmplan_core::world::DEPARTURE),
            10,
        );
        let a = assess(&world, &straight);
        println!(
            "straight plan: feasible {}, violations [{}]",
            a.feasible(),
            kinds(&a)
        );

        // Each UAV alone: one UAV, no communication, no separation.
        let mut solo = loaded.clone();
        solo.spec.uavs.truncate(1);
        solo.spec.communication.requirement = CommRequirement::None;
        let solo_world = build_world(&solo, None)?;
        let mut fleet = Plan::default();
        for seed in 1..=n as u64 {
            let r = run(&solo_world, &request(seed), &mut |_| {});
            println!(
                "  solo seed {seed}: length {:.0} m, energy {:.0} J ({:.0}% of battery), feasible alone {}",
                r.assessment.per_uav[0].length_m,
                r.assessment.per_uav[0].energy_j,
                100.0 * r.assessment.per_uav[0].battery_ratio,
                r.assessment.feasible()
            );
            let timed = TimedPlan::new(&solo_world, &r.plan);
            let t_end = timed.horizon;
            let at: Vec<String> = [0.3, 0.5, 0.7]
                .iter()
                .map(|f| {
                    let p = timed.paths[0].position_at_time(f * t_end);
                    format!("t={:.0}s ({:.0}, {:.0})", f * t_end, p.x, p.y)
                })
                .collect();
            println!("    arrives at {t_end:.0} s; passes {}", at.join(", "));
            fleet.uavs.push(r.plan.uavs[0].clone());
        }
        let a = assess(&world, &fleet);
        let outage: Vec<String> = a
            .per_uav
            .iter()
            .map(|u| format!("{:.0}", u.outage_s))
            .collect();
        println!(
            "solo paths flown together: feasible {}, outage s per UAV [{}], violations [{}]",
            a.feasible(),
            outage.join(", "),
            kinds(&a)
        );

        // Cooperative planning.
        let mut feasible = 0;
        for seed in 1..=10 {
            let r = run(&world, &request(seed), &mut |_| {});
            let a = &r.assessment;
            feasible += usize::from(a.feasible());
            let outage: f64 = a.per_uav.iter().map(|u| u.outage_s).sum();
            println!(
                "  coop seed {seed}: feasible {}, cost/UAV {:.1}, outage {:.0} UAV-s, relayed {} s, max battery {:.0}%, violations [{}], {:.2} s",
                a.feasible(),
                a.per_uav_cost(),
                outage,
                relayed_seconds(&world, &r.plan),
                100.0 * a.per_uav.iter().map(|u| u.battery_ratio).fold(0.0, f64::max),
                kinds(a),
                r.seconds
            );
        }
        println!("cooperative DLS-SMPSO: {feasible}/10 feasible\n");
    }
    Ok(())
}
