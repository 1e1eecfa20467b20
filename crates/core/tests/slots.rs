//! Launch and recovery slots (docs/model.md, "Launch and recovery slots"): who shares a
//! take-off place, when each UAV leaves and lands, what it pays for waiting, and a fleet of
//! ten on one start that no plan can separate without slots and that slots make feasible.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use glam::DVec3;
use swarmplan_core::cost::assess;
use swarmplan_core::feasibility::ViolationKind;
use swarmplan_core::method::Method;
use swarmplan_core::optim::{Budget, OptimizerParams};
use swarmplan_core::plan::{Path, Plan};
use swarmplan_core::run::{run, RunRequest};
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::slots::Slots;
use swarmplan_core::world::spec::*;
use swarmplan_core::world::{Terrain, Threat, World};

/// A 1000 x 1000 m flat world, no threats, comm off, goal (900, 900); one UAV per start.
fn spec(starts: &[[f64; 3]], launch: f64, recovery: f64) -> ScenarioSpec {
    ScenarioSpec {
        name: "slots".into(),
        description: String::new(),
        terrain: TerrainSpec::default(),
        geo: None,
        map: MapSpec {
            x: [0.0, 1000.0],
            y: [0.0, 1000.0],
            ..MapSpec::default()
        },
        threats: vec![],
        goal: GoalSpec {
            position: [900.0, 900.0, 100.0],
            antenna: 2.0,
        },
        uavs: starts
            .iter()
            .map(|s| UavSpec {
                start: *s,
                battery_wh: 100.0,
                ..UavSpec::default()
            })
            .collect(),
        communication: CommSpec {
            requirement: CommRequirement::None,
            ..CommSpec::default()
        },
        energy: EnergySpec::default(),
        objective: ObjectiveSpec::default(),
        timing: TimingSpec {
            launch_interval: launch,
            recovery_interval: recovery,
            ..TimingSpec::default()
        },
        planning: PlanningSpec {
            waypoints: 3,
            ..PlanningSpec::default()
        },
    }
}

fn world(spec: ScenarioSpec) -> World {
    World::new(spec, Terrain::flat(1000.0, 1000.0, 0.0)).unwrap()
}

/// Ten UAVs on one start (100, 100).
fn shared_start(launch: f64, recovery: f64) -> World {
    world(spec(&[[100.0, 100.0, 100.0]; 10], launch, recovery))
}

/// Every UAV on the straight line from (100, 100) to the goal, 100 m up.
fn straight(n: usize, waypoints: usize) -> Plan {
    let line = |s: f64| DVec3::new(100.0 + 800.0 * s, 100.0 + 800.0 * s, 100.0);
    let path = Path {
        waypoints: (0..waypoints + 2)
            .map(|k| line(k as f64 / (waypoints + 1) as f64))
            .collect(),
    };
    Plan {
        uavs: vec![path; n],
        pace: 1.0,
        delays: Vec::new(),
    }
}

#[test]
fn starts_within_the_zone_share_a_launch_place_in_scenario_order() {
    let s = spec(
        &[
            [100.0, 100.0, 100.0],
            [500.0, 500.0, 100.0],
            [120.0, 100.0, 100.0], // 20 m from UAV 0: its group
            [500.0, 529.0, 100.0], // 29 m from UAV 1: its group
            [100.0, 160.0, 100.0], // 60 m from UAV 0: a place of its own
            [100.0, 100.0, 100.0],
        ],
        4.0,
        2.5,
    );
    let slots = Slots::of(&s);
    let launch: Vec<f64> = (0..6).map(|u| slots.launch(u)).collect();
    assert_eq!(launch, [0.0, 0.0, 4.0, 4.0, 0.0, 8.0]);
    let recovery: Vec<f64> = (0..6).map(|u| slots.recovery(u)).collect();
    assert_eq!(recovery, [0.0, 2.5, 5.0, 7.5, 10.0, 12.5]);
    assert!(slots.any());
    assert!(!Slots::of(&spec(&[[100.0, 100.0, 100.0]; 3], 0.0, 0.0)).any());
}

#[test]
fn each_uav_flies_the_unslotted_schedule_moved_into_its_slots() {
    let plan = straight(10, 3);
    let free = TimedPlan::new(&shared_start(0.0, 0.0), &plan);
    // Launches 5 s apart, recoveries 3 s apart: the common lag is
    // max(0, max_i 5 i - 3 i) = 18 s, so UAV i lands at T + 18 + 3 i and takes off 18 + 3 i.
    let w = shared_start(5.0, 3.0);
    let timed = TimedPlan::new(&w, &plan);
    let t = free.paths[0].arrival;
    for (u, (p, f)) in timed.paths.iter().zip(&free.paths).enumerate() {
        let shift = 18.0 + 3.0 * u as f64;
        assert!(p.launch >= 5.0 * u as f64, "UAV {u} before its slot");
        assert_eq!(p.launch, shift);
        assert_eq!(p.depart, shift, "no delay: it leaves as it takes off");
        assert!((p.arrival - (t + shift)).abs() < 1e-9);
        assert_eq!(p.speed, f.speed, "UAV {u}: speeds are those without slots");
        // Before it takes off it stands at its start.
        let before = p.position_at_time(0.5 * p.launch);
        assert!(before.distance(p.abs[0]) < 1e-9, "UAV {u}: {before}");
    }
    // Under cruise the launch slot alone moves it.
    let mut s = spec(&[[100.0, 100.0, 100.0]; 3], 4.0, 0.0);
    s.timing.policy = TimingPolicy::Cruise;
    let cruise = TimedPlan::new(&world(s), &straight(3, 3));
    let launches: Vec<f64> = cruise.paths.iter().map(|p| p.launch).collect();
    assert_eq!(launches, [0.0, 4.0, 8.0]);
}

#[test]
fn waiting_on_the_launcher_costs_no_energy_and_hovering_does() {
    let energy = |w: &World, plan: &Plan, u: usize| assess(w, plan).per_uav[u].energy_j;
    let plan = straight(10, 3);
    // Equal windows (launch = recovery interval): every UAV flies as UAV 0 does.
    let slotted = shared_start(5.0, 5.0);
    let e0 = energy(&slotted, &plan, 0);
    let e9 = energy(&slotted, &plan, 9);
    assert!(
        (e9 - e0).abs() < 1e-6 * e0,
        "launcher wait charged: {e0} {e9}"
    );
    // A departure delay on top is hovered, and paid.
    let mut delayed = plan.clone();
    delayed.delays = vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.2];
    let slotted_delays = world({
        let mut s = spec(&[[100.0, 100.0, 100.0]; 10], 5.0, 5.0);
        s.timing.max_delay = 0.3;
        s
    });
    let hovered = energy(&slotted_delays, &delayed, 9);
    assert!(hovered > e9 + 1000.0, "hover not paid: {hovered} vs {e9}");
}

#[test]
fn recovery_slots_need_common_arrival_and_intervals_are_checked() {
    let mut s = spec(&[[100.0, 100.0, 100.0]; 2], 0.0, 5.0);
    s.timing.policy = TimingPolicy::Cruise;
    let e = World::new(s, Terrain::flat(1000.0, 1000.0, 0.0)).unwrap_err();
    assert!(e.to_string().contains("timing.recovery_interval"), "{e}");
    let s = spec(&[[100.0, 100.0, 100.0]; 2], -1.0, 0.0);
    let e = World::new(s, Terrain::flat(1000.0, 1000.0, 0.0)).unwrap_err();
    assert!(e.to_string().contains("timing.launch_interval"), "{e}");
    // Slots must end within half the channel's modelled hour: 400 UAVs 5 s apart do not.
    let s = spec(&[[100.0, 100.0, 100.0]; 400], 5.0, 5.0);
    let e = World::new(s, Terrain::flat(1000.0, 1000.0, 0.0)).unwrap_err();
    assert!(e.to_string().contains("1995 s late"), "{e}");
    assert!(
        world(spec(&[[100.0, 100.0, 100.0]; 361], 5.0, 5.0))
            .slots()
            .span()
            == 1800.0
    );
}

#[test]
fn ten_uavs_on_one_start_fly_one_line_apart_in_time_with_slots_only() {
    let plan = straight(10, 3);
    let together = assess(&shared_start(0.0, 0.0), &plan);
    assert!(
        together
            .violations
            .iter()
            .flatten()
            .any(|v| v.kind == ViolationKind::Separation),
        "the same line at the same time must lose separation"
    );
    // 5 s apart at about 15 m/s: 75 m between neighbours on the line.
    let slotted = assess(&shared_start(5.0, 5.0), &plan);
    assert!(slotted.feasible(), "{:?}", slotted.violations);
}

/// Ten UAVs on one start (100, 500), goal (900, 500), and a wall of threats across the map
/// at x = 300 with one gap 30 m wide beyond the hard zones, on the straight line: all ten
/// must pass it, and abreast they do not fit.
fn gap(launch: f64, recovery: f64) -> World {
    let mut s = spec(&[[100.0, 500.0, 100.0]; 10], launch, recovery);
    s.goal.position = [900.0, 500.0, 100.0];
    let (r, size) = (60.0, s.uavs[0].size);
    let edge = 15.0 + size + r;
    for k in 0..8 {
        let off = edge + 1.6 * r * f64::from(k);
        for y in [500.0 - off, 500.0 + off] {
            s.threats.push(Threat {
                x: 300.0,
                y,
                z: 150.0,
                r,
            });
        }
    }
    world(s)
}

#[test]
fn slots_make_ten_uavs_through_one_gap_feasible_for_the_planner() {
    let req = RunRequest {
        method: Method::preset("swarmplan").unwrap(),
        params: OptimizerParams::default(),
        budget: Budget::evaluations(4000),
        seed: 1,
    };
    let slotted = gap(5.0, 5.0);
    let a = run(&slotted, &req, &mut |_| {});
    assert!(a.assessment.feasible(), "{:?}", a.assessment.violations);
    // Deterministic per seed, on one thread or three.
    assert_eq!(a.plan, run(&slotted, &req, &mut |_| {}).plan);
    for threads in [1, 3] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        let b = pool.install(|| run(&slotted, &req, &mut |_| {}));
        assert_eq!(a.outcome.best_x, b.outcome.best_x, "{threads} threads");
        assert_eq!(a.outcome.trace, b.outcome.trace, "{threads} threads");
    }
    // Without slots the same search, at the same budget, is not (as measured: separation).
    let together = run(&gap(0.0, 0.0), &req, &mut |_| {});
    assert!(
        !together.assessment.feasible(),
        "ten through the gap together"
    );
}
