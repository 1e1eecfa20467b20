//! Analytic tests of the planning model on hand-made worlds (flat terrain unless a ridge is
//! the point): each asserts a number or a verdict that follows from geometry alone.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use glam::DVec3;
use swarmplan_core::cost::comm::{contact_at, Contact};
use swarmplan_core::cost::TermId;
use swarmplan_core::cost::{assess, assess_as_searched};
use swarmplan_core::feasibility::{check, ViolationKind};
use swarmplan_core::plan::{Path, Plan};
use swarmplan_core::problem::BlockProblem;
use swarmplan_core::world::spec::*;
use swarmplan_core::world::terrain::Sampling;
use swarmplan_core::world::{Terrain, Threat, World};

/// A 1000 x 1000 m flat world at height 0, no threats, one UAV per start, goal (900, 900).
fn spec(starts: &[[f64; 3]]) -> ScenarioSpec {
    ScenarioSpec {
        name: "test".into(),
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
            position: [900.0, 900.0, 150.0],
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
        timing: TimingSpec::default(),
        planning: PlanningSpec::default(),
    }
}

fn flat() -> Terrain {
    Terrain::flat(1000.0, 1000.0, 0.0)
}

fn path(points: &[[f64; 3]]) -> Path {
    Path {
        waypoints: points.iter().map(|p| DVec3::from_array(*p)).collect(),
    }
}

fn kinds(world: &World, plan: &Plan) -> Vec<ViolationKind> {
    check(world, plan).into_iter().map(|v| v.kind).collect()
}

#[test]
fn straight_path_length_is_the_distance() {
    let w = World::new(spec(&[[100.0, 100.0, 150.0]]), flat()).unwrap();
    let plan = Plan::straight(
        &[w.start(0)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        5,
    );
    let a = assess(&w, &plan);
    let want = (800.0f64 * 800.0 * 2.0).sqrt();
    assert!((a.per_uav[0].raw[TermId::Length] - want).abs() < 1e-9);
    assert!((a.per_uav[0].length_m - want).abs() < 1e-9);
    // A straight line turns nowhere and stays in the band: no smoothness, no turning.
    assert_eq!(a.per_uav[0].raw[TermId::Smoothness], 0.0);
    assert_eq!(a.per_uav[0].raw[TermId::Turning], 0.0);
    assert!(a.feasible(), "{:?}", a.violations);
}

#[test]
fn a_segment_clear_of_a_cylinder_costs_nothing_and_one_through_it_violates() {
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    // 200 m beside the diagonal: far beyond r + 11 m.
    s.threats = vec![Threat {
        x: 500.0 + 141.0,
        y: 500.0 - 141.0,
        z: 150.0,
        r: 50.0,
    }];
    let w = World::new(s.clone(), flat()).unwrap();
    let plan = Plan::straight(
        &[w.start(0)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        5,
    );
    let a = assess(&w, &plan);
    assert_eq!(a.per_uav[0].raw[TermId::Threat], 0.0);
    assert!(!kinds(&w, &plan).contains(&ViolationKind::Threat));

    // On the diagonal: a collision, reported with its place.
    s.threats[0].x = 500.0;
    s.threats[0].y = 500.0;
    let w = World::new(s, flat()).unwrap();
    let v = check(&w, &plan);
    let hit = v
        .iter()
        .find(|v| v.kind == ViolationKind::Threat)
        .expect("a threat violation");
    assert!((hit.amount - 51.0).abs() < 1e-9, "intrusion {}", hit.amount);
    assert!(hit.position.is_some() && hit.time.is_some());
    assert!(assess_as_searched(&w, &plan).total > 1000.0);
}

#[test]
fn a_ninety_degree_turn_violates_and_a_thirty_degree_one_does_not() {
    let w = World::new(spec(&[[100.0, 100.0, 150.0]]), flat()).unwrap();
    let sharp = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![path(&[
            [100.0, 100.0, 150.0],
            [900.0, 100.0, 150.0],
            [900.0, 900.0, 150.0],
        ])],
    };
    assert!(kinds(&w, &sharp).contains(&ViolationKind::Turn));
    let v = check(&w, &sharp);
    let turn = v.iter().find(|v| v.kind == ViolationKind::Turn).unwrap();
    assert!((turn.amount - 45.0).abs() < 1e-9);
    // A slight bend off the diagonal: headings 38.7 and 51.3 deg, a 12.7 deg turn.
    let mid = [550.0, 450.0, 150.0];
    let gentle = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![path(&[[100.0, 100.0, 150.0], mid, [900.0, 900.0, 150.0]])],
    };
    assert!(
        !kinds(&w, &gentle).contains(&ViolationKind::Turn),
        "{:?}",
        check(&w, &gentle)
    );
}

#[test]
fn a_steep_climb_violates() {
    let w = World::new(spec(&[[100.0, 100.0, 150.0]]), flat()).unwrap();
    let plan = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![path(&[
            [100.0, 100.0, 100.0],
            [130.0, 130.0, 200.0],
            [900.0, 900.0, 150.0],
        ])],
    };
    let mut s = spec(&[[100.0, 100.0, 100.0]]);
    s.map.z_agl = [50.0, 250.0];
    let w2 = World::new(s, flat()).unwrap();
    assert!(kinds(&w2, &plan).contains(&ViolationKind::Climb));
    let _ = w;
}

#[test]
fn crossing_at_the_same_time_violates_separation_and_at_different_times_does_not() {
    // Two UAVs on the two diagonals of a square, crossing at its centre.
    let mut s = spec(&[[100.0, 100.0, 150.0], [100.0, 900.0, 150.0]]);
    s.goal.position = [900.0, 500.0, 150.0];
    let w = World::new(s.clone(), flat()).unwrap();
    // Same length legs: both reach (500, 500) at the same time.
    let a = path(&[
        [100.0, 100.0, 150.0],
        [500.0, 500.0, 150.0],
        [700.0, 700.0, 150.0],
        [900.0, 500.0, 150.0],
    ]);
    let b = path(&[
        [100.0, 900.0, 150.0],
        [500.0, 500.0, 150.0],
        [700.0, 300.0, 150.0],
        [900.0, 500.0, 150.0],
    ]);
    let plan = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![a.clone(), b],
    };
    let v = check(&w, &plan);
    let sep: Vec<_> = v
        .iter()
        .filter(|v| v.kind == ViolationKind::Separation)
        .collect();
    assert_eq!(sep.len(), 1, "{v:?}");
    assert_eq!((sep[0].uav, sep[0].other), (0, Some(1)));
    // UAV 1 takes a longer route before the crossing, so it passes the centre later.
    let late = path(&[
        [100.0, 900.0, 150.0],
        [100.0, 600.0, 150.0],
        [300.0, 500.0, 150.0],
        [500.0, 500.0, 150.0],
        [700.0, 300.0, 150.0],
        [900.0, 500.0, 150.0],
    ]);
    let mut s2 = s;
    s2.timing.policy = TimingPolicy::Cruise;
    let w2 = World::new(s2, flat()).unwrap();
    let plan2 = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![a, late],
    };
    assert!(
        !kinds(&w2, &plan2).contains(&ViolationKind::Separation),
        "{:?}",
        check(&w2, &plan2)
    );
}

#[test]
fn speeds_out_of_range_count_in_safety_and_violate() {
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.timing.policy = TimingPolicy::Cruise;
    s.uavs[0].cruise_speed = 40.0;
    s.uavs[0].payload_kg = 2.0;
    let w = World::new(s, flat()).unwrap();
    let plan = Plan::straight(
        &[w.start(0)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        3,
    );
    let a = assess(&w, &plan);
    // 4 segments too fast + 1 payload indicator.
    assert_eq!(a.per_uav[0].raw[TermId::Safety], 5.0);
    let k = kinds(&w, &plan);
    assert!(k.contains(&ViolationKind::Speed) && k.contains(&ViolationKind::Payload));
}

#[test]
fn a_small_battery_violates_energy() {
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.uavs[0].battery_wh = 1.0;
    let w = World::new(s, flat()).unwrap();
    let plan = Plan::straight(
        &[w.start(0)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        3,
    );
    let v = check(&w, &plan);
    assert!(v.iter().any(|v| v.kind == ViolationKind::Energy), "{v:?}");
    // The physical energy is P(15 m/s) L / 15 with the payload, at least 9 J/m.
    let a = assess(&w, &plan);
    assert!(a.per_uav[0].energy_j > 9.0 * a.per_uav[0].length_m);
}

#[test]
fn terrain_in_the_way_violates_clearance() {
    // A 400 m high block in the middle of the map.
    let nx = 101;
    let h: Vec<f64> = (0..nx)
        .flat_map(|j| {
            (0..nx).map(move |i| {
                if (40..=60).contains(&i) && (40..=60).contains(&j) {
                    400.0
                } else {
                    0.0
                }
            })
        })
        .collect();
    let t = Terrain::new(nx, nx, (0.0, 0.0), (10.0, 10.0), h, Sampling::Bilinear).unwrap();
    let w = World::new(spec(&[[100.0, 100.0, 150.0]]), t).unwrap();
    let plan = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![path(&[
            [100.0, 100.0, 150.0],
            [200.0, 200.0, 150.0],
            [900.0, 900.0, 150.0],
        ])],
    };
    assert!(kinds(&w, &plan).contains(&ViolationKind::Terrain));
}

/// Communication worlds: ground station at the start, UGV0 at the goal, 300 m range.
fn comm_spec(starts: &[[f64; 3]], goal: [f64; 3]) -> ScenarioSpec {
    let mut s = spec(starts);
    s.goal.position = goal;
    s.communication = CommSpec {
        requirement: CommRequirement::Relay,
        range: 300.0,
        shadowing_sigma_db: 0.0,
        max_outage_s: 5.0,
        ..CommSpec::default()
    };
    s.timing.separation = 0.0;
    s
}

#[test]
fn a_relay_chain_connects_a_uav_out_of_direct_range() {
    let w = World::new(
        comm_spec(&[[100.0, 500.0, 150.0]; 3], [900.0, 500.0, 150.0]),
        flat(),
    )
    .unwrap();
    let at = |x: f64| DVec3::new(x, 500.0, 150.0);
    // UAV 0 at x = 500 is 400 m from both ground nodes (range 300 m): out alone.
    assert_eq!(contact_at(&w, 10.0, &[at(500.0)])[0], Contact::Out);
    // With UAV 1 at x = 300 (200 m from the station, 200 m from UAV 0): relayed.
    let c = contact_at(&w, 10.0, &[at(500.0), at(300.0)]);
    assert_eq!(c, vec![Contact::Relayed, Contact::Direct]);
    // A longer chain: station -> 2 -> 1 -> 0 with 250 m hops, UAV 0 600 m out.
    let c = contact_at(&w, 10.0, &[at(850.0 - 100.0 - 150.0), at(450.0), at(250.0)]);
    assert_eq!(c[2], Contact::Direct);
    assert_ne!(c[0], Contact::Out);
    // The relaxed mode only asks for a neighbour.
    let mut s = comm_spec(&[[100.0, 500.0, 150.0]; 2], [900.0, 500.0, 150.0]);
    s.communication.requirement = CommRequirement::Neighbour;
    let w = World::new(s, flat()).unwrap();
    let c = contact_at(&w, 10.0, &[at(500.0), at(520.0)]);
    assert_eq!(c, vec![Contact::Relayed, Contact::Relayed]);
}

/// 1000 x 1000 m of flat ground at height 0 with a 500 m ridge across it at x in [240, 260].
fn ridge() -> Terrain {
    let nx = 101;
    let h: Vec<f64> = (0..nx)
        .flat_map(|_| (0..nx).map(|i| if (24..=26).contains(&i) { 500.0 } else { 0.0 }))
        .collect();
    Terrain::new(nx, nx, (0.0, 0.0), (10.0, 10.0), h, Sampling::Bilinear).unwrap()
}

#[test]
fn a_uav_behind_a_ridge_has_no_line_of_sight() {
    // A 500 m ridge across the map at x in [240, 260], between the station (x = 100) and
    // a UAV at x = 350: 250 m away, in range, but hidden.
    let t = ridge();
    let mut s = comm_spec(&[[100.0, 500.0, 150.0]], [900.0, 500.0, 150.0]);
    let w = World::new(s.clone(), t.clone()).unwrap();
    let before = DVec3::new(200.0, 500.0, 150.0);
    let behind = DVec3::new(350.0, 500.0, 150.0);
    assert_eq!(contact_at(&w, 10.0, &[before])[0], Contact::Direct);
    assert_eq!(contact_at(&w, 10.0, &[behind])[0], Contact::Out);
    // Without the terrain check the same UAV is in contact: the ridge made the difference.
    s.communication.line_of_sight = false;
    let w = World::new(s, t).unwrap();
    assert_eq!(contact_at(&w, 10.0, &[behind])[0], Contact::Direct);
}

#[test]
fn flying_out_of_range_costs_and_violates_outage() {
    let w = World::new(
        comm_spec(&[[100.0, 500.0, 150.0]], [900.0, 500.0, 150.0]),
        flat(),
    )
    .unwrap();
    let plan = Plan::straight(
        &[w.start(0)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        3,
    );
    let a = assess(&w, &plan);
    // Out of both 300 m disks for the middle of the 800 m trip (about 200 m, 13 s at 15 m/s).
    assert!(a.per_uav[0].outage_s >= 10.0, "{}", a.per_uav[0].outage_s);
    assert!(a.per_uav[0].raw[TermId::Communication] > 0.0);
    assert!(kinds(&w, &plan).contains(&ViolationKind::Comm));
}

/// A path from (100, 100) east to `corner`, then turning left by each of `turns_deg` and
/// flying the matching leg of `legs`, with the goal at its end (flat ground, 150 m up).
fn bent(corner: [f64; 2], turns_deg: &[f64], legs: &[f64]) -> (ScenarioSpec, Plan) {
    let mut points = vec![[100.0, 100.0, 150.0], [corner[0], corner[1], 150.0]];
    let mut heading = 0.0_f64;
    for (turn, leg) in turns_deg.iter().zip(legs) {
        heading += turn.to_radians();
        let [x, y, _] = *points.last().unwrap();
        points.push([x + leg * heading.cos(), y + leg * heading.sin(), 150.0]);
    }
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.goal.position = *points.last().unwrap();
    (
        s,
        Plan {
            pace: 1.0,
            delays: Vec::new(),
            uavs: vec![path(&points)],
        },
    )
}

#[test]
fn two_forty_degree_turns_three_metres_apart_break_the_turning_radius() {
    // Each turn needs 50 tan(20 deg) = 18.2 m of straight flight on each side; 3 m separate
    // them. Both are within the 45 deg turn limit, so the paper's model passes the plan.
    let (s, plan) = bent([500.0, 100.0], &[40.0, 40.0], &[3.0, 700.0]);
    let w = World::new(s.clone(), flat()).unwrap();
    let v = check(&w, &plan);
    let radius: Vec<_> = v
        .iter()
        .filter(|v| v.kind == ViolationKind::TurnRadius)
        .collect();
    assert_eq!(radius.len(), 1, "{v:?}");
    assert_eq!(radius[0].index, Some(1));
    let need = 2.0 * 50.0 * 20f64.to_radians().tan();
    assert!((radius[0].amount - (need - 3.0)).abs() < 1e-6);
    assert!(!v.iter().any(|v| v.kind == ViolationKind::Turn), "{v:?}");
    // The paper profile keeps the paper's model: no turning radius.
    let mut paper = s.clone();
    paper.planning.profile = swarmplan_core::feasibility::FeasibilityProfile::Paper;
    let w = World::new(paper, flat()).unwrap();
    assert!(assess(&w, &plan).feasible(), "{:?}", check(&w, &plan));
    // Spaced 60 m apart the turns fit.
    let (s, plan) = bent([500.0, 100.0], &[40.0, 40.0], &[60.0, 700.0]);
    let w = World::new(s, flat()).unwrap();
    assert!(assess(&w, &plan).feasible(), "{:?}", check(&w, &plan));
}

#[test]
fn a_threat_that_only_the_cut_corner_enters_is_caught_on_the_flown_path() {
    // A 40 deg left turn at (500, 100). The arc of radius 50 m passes 50 (1 / cos 20 deg - 1)
    // = 3.2 m inside the corner; a threat of radius 5 m (hard zone 6 m with the drone's size)
    // 8 m in along the bisector is 8 sin 70 deg = 7.5 m from both waypoint segments.
    let (mut s, plan) = bent([500.0, 100.0], &[40.0], &[600.0]);
    let inward = 110f64.to_radians();
    s.threats = vec![Threat {
        x: 500.0 + 8.0 * inward.cos(),
        y: 100.0 + 8.0 * inward.sin(),
        z: 150.0,
        r: 5.0,
    }];
    let w = World::new(s.clone(), flat()).unwrap();
    let v = check(&w, &plan);
    let hit: Vec<_> = v
        .iter()
        .filter(|v| v.kind == ViolationKind::Threat)
        .collect();
    assert!(!hit.is_empty(), "{v:?}");
    assert!(
        hit.iter().all(|h| h.detail.contains("flown arc")),
        "{hit:?}"
    );
    // The arc comes within 8 - 3.2 = 4.8 m of the axis (chords a little closer).
    let deepest = hit.iter().map(|h| h.amount).fold(0.0, f64::max);
    let arc_gap = 8.0 - 50.0 * (1.0 / 20f64.to_radians().cos() - 1.0);
    assert!(
        deepest >= 6.0 - arc_gap - 1e-9 && deepest < 6.0 - arc_gap + 0.5,
        "{deepest}"
    );
    // Flown sharp (radius 0) the corner clears the threat.
    for u in &mut s.uavs {
        u.turn_radius = 0.0;
    }
    let w = World::new(s, flat()).unwrap();
    assert!(assess(&w, &plan).feasible(), "{:?}", check(&w, &plan));
}

#[test]
fn the_flown_path_is_shorter_than_the_waypoints_by_the_cut_corners() {
    // One 40 deg turn: the arc replaces 2 t of corner by R theta.
    let (s, plan) = bent([500.0, 100.0], &[40.0], &[600.0]);
    let w = World::new(s, flat()).unwrap();
    let a = assess(&w, &plan);
    let theta = 40f64.to_radians();
    let t = 50.0 * (0.5 * theta).tan();
    let want = 400.0 + 600.0 - 2.0 * t + 50.0 * theta;
    // Chords of sagitta <= 0.5 m fly the arc a little shorter than the arc itself.
    let chords_short = 50.0 * theta * swarmplan_core::flight::SAGITTA_M / 50.0;
    assert!(
        a.per_uav[0].length_m <= want && a.per_uav[0].length_m > want - chords_short,
        "{} vs {want}",
        a.per_uav[0].length_m
    );
    // The waypoint length (J1, SPSO's term) is unchanged.
    assert!((a.per_uav[0].raw[TermId::Length] - 1000.0).abs() < 1e-9);
}

#[test]
fn repeated_waypoints_outside_the_map_are_reported_at_the_waypoint() {
    // Found by the CI's 30-second `import` fuzz smoke: an imported plan whose waypoints repeat
    // flies a path with fewer vertices than it has waypoints, and the map-box check indexed the
    // flown path by waypoint number (out of bounds). The box is checked on the waypoints.
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.goal.position = [900.0, 100.0, 150.0];
    let plan = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![path(&[
            [100.0, 100.0, 150.0],
            [500.0, 100.0, 150.0],
            [500.0, 100.0, 150.0],
            [500.0, 100.0, 150.0],
            [500.0, 1200.0, 150.0],
            [900.0, 100.0, 150.0],
        ])],
    };
    let w = World::new(s, flat()).unwrap();
    let v = check(&w, &plan);
    let out: Vec<_> = v
        .iter()
        .filter(|v| v.kind == ViolationKind::Bounds)
        .collect();
    assert_eq!(out.len(), 1, "{v:?}");
    assert_eq!(out[0].index, Some(4));
    assert!((out[0].amount - 200.0).abs() < 1e-9, "{:?}", out[0]);
    let at = out[0].position.unwrap();
    assert!(
        (at[0] - 500.0).abs() < 1e-9 && (at[1] - 1200.0).abs() < 1e-9,
        "{at:?}"
    );
}

#[test]
fn a_flight_longer_than_the_swept_horizon_is_a_communication_violation_not_a_hang() {
    // A plan built in code (not read from a file, whose checks refuse it first) 1e50 m above
    // ground lasts about 1e49 s; the communication sweep once walked all of it in 1 s steps.
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.communication.requirement = CommRequirement::Relay;
    let w = World::new(s, flat()).unwrap();
    let plan = Plan {
        pace: 1.0,
        delays: Vec::new(),
        uavs: vec![path(&[
            [100.0, 100.0, 150.0],
            [500.0, 500.0, 1e50],
            [900.0, 900.0, 150.0],
        ])],
    };
    let v = check(&w, &plan);
    let comm: Vec<_> = v
        .iter()
        .filter(|v| v.kind == ViolationKind::Comm && v.detail.contains("assessed over the first"))
        .collect();
    assert_eq!(comm.len(), 1, "{v:?}");
    assert!(comm[0].amount > 1e40, "{:?}", comm[0]);
    // A mission of ordinary length has no such violation.
    let straight = Plan::straight(
        &[w.start(0)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        5,
    );
    assert!(!check(&w, &straight)
        .iter()
        .any(|v| v.detail.contains("assessed over the first")));
}

#[test]
fn the_pace_scales_the_preferred_speed_within_the_limits() {
    use swarmplan_core::timing::TimedPlan;
    let w = World::new(spec(&[[100.0, 100.0, 150.0]]), flat()).unwrap();
    let line = |pace| Plan {
        pace,
        delays: Vec::new(),
        uavs: vec![path(&[[100.0, 100.0, 150.0], [900.0, 900.0, 150.0]])],
    };
    let speed = |pace| TimedPlan::new(&w, &line(pace)).paths[0].speed;
    // Cruise 15 m/s, limits [5, 25].
    assert!((speed(1.0) - 15.0).abs() < 1e-9);
    assert!((speed(1.5) - 22.5).abs() < 1e-9);
    assert!((speed(0.5) - 7.5).abs() < 1e-9);
    assert!((speed(3.0) - 25.0).abs() < 1e-9, "clamped to v_max");
    let arrival = TimedPlan::new(&w, &line(1.25)).paths[0].arrival;
    assert!((arrival - 800.0 * 2f64.sqrt() / 18.75).abs() < 1e-9);
}

#[test]
fn a_free_pace_is_one_more_variable_per_uav_and_the_plan_flies_it() {
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::PlanningProblem;
    use swarmplan_core::problem::Problem;
    use swarmplan_core::rng::rng_from_seed;
    let starts = [[100.0, 100.0, 150.0], [150.0, 80.0, 150.0]];
    let fixed = World::new(spec(&starts), flat()).unwrap();
    let mut free_spec = spec(&starts);
    free_spec.timing.pace = [0.5, 1.5];
    let free = World::new(free_spec, flat()).unwrap();
    let n = fixed.spec().planning.waypoints;
    for kind in [EncodingKind::Spherical, EncodingKind::Cartesian] {
        let a = PlanningProblem::new(&fixed, kind, InitKind::Line);
        let b = PlanningProblem::new(&free, kind, InitKind::Line);
        assert_eq!(a.block_size(), 3 * n);
        assert_eq!(b.block_size(), 3 * n + 1);
        assert_eq!(b.bounds().len(), 2 * (3 * n + 1));
        let mut x = vec![0.0; b.bounds().len()];
        let mut rng = rng_from_seed(5);
        let mut paces = Vec::new();
        for _ in 0..20 {
            b.sample_initial(&mut rng, &mut x);
            let plan = b.decode(&x);
            assert!((0.5..=1.5).contains(&plan.pace));
            paces.push(plan.pace);
            // The evaluation is that of the decoded plan, pace included.
            let e = b.evaluate(&x);
            let fresh = assess_as_searched(&free, &plan);
            assert_eq!(e.cost.to_bits(), fresh.total.to_bits());
            // Paced T is the pace-1 T over the pace (the speeds stay inside [5, 25] here).
            let at_one = assess_as_searched(
                &free,
                &Plan {
                    pace: 1.0,
                    ..plan.clone()
                },
            );
            let (t, t1) = (fresh.per_uav[0].arrival_s, at_one.per_uav[0].arrival_s);
            assert!(
                (t * plan.pace - t1).abs() < 1e-9 * t1,
                "{t} {t1} {}",
                plan.pace
            );
        }
        assert!(paces.iter().any(|&p| p < 0.9) && paces.iter().any(|&p| p > 1.1));
        // The fixed-pace problem decodes pace 1, whatever was decoded before on the thread.
        let mut y = vec![0.0; a.bounds().len()];
        a.sample_initial(&mut rng, &mut y);
        assert_eq!(a.decode(&y).pace, 1.0);
    }
}

/// The arcs' threat check (which first picks the threats an arc's box may touch, among the
/// first 64) finds, in the same order, what checking every chord against every threat finds.
#[test]
fn arc_threat_check_finds_what_a_chord_by_chord_check_finds() {
    use swarmplan_core::feasibility::{FeasibilityProfile, ViolationSink};
    use swarmplan_core::flight::check_arc_threats;
    use swarmplan_core::timing::TimedPlan;
    use swarmplan_core::world::threat::{point_segment_distance, segment_box_misses};
    let mut s = spec(&[[50.0, 50.0, 150.0]]);
    // 90 small threats on a grid: more than the filter's 64, many near the corners.
    s.threats = (0..90)
        .map(|i| Threat {
            x: 60.0 + (i % 10) as f64 * 95.0,
            y: 60.0 + (i / 10) as f64 * 100.0,
            z: 100.0,
            r: 8.0 + (i % 7) as f64 * 3.0,
        })
        .collect();
    let world = World::new(s, flat()).unwrap();
    assert!(world.flies_arcs());
    let (mut found, mut chords) = (0, 0);
    for r in 0..40_usize {
        let f = |k: usize, m: f64| ((r * k * 7919 + k * 104_729) % 1000) as f64 / 1000.0 * m;
        let mut points = vec![[50.0, 50.0, 150.0]];
        points.extend((1..9).map(|k| [60.0 + f(2 * k, 880.0), 60.0 + f(2 * k + 1, 880.0), 150.0]));
        points.push([900.0, 900.0, 150.0]);
        let plan = Plan {
            uavs: vec![path(&points)],
            ..Plan::default()
        };
        let flown = TimedPlan::flown(&world, &plan);
        let tp = &flown.paths[0];
        let mut sink = ViolationSink::collecting(FeasibilityProfile::Strict);
        check_arc_threats(&world, 0, tp, &mut sink);
        let got: Vec<(Option<usize>, Option<[f64; 3]>, u64)> = sink
            .list
            .unwrap()
            .iter()
            .map(|v| (v.index, v.position, v.amount.to_bits()))
            .collect();
        let mut expected = Vec::new();
        for (c, seg) in tp.flown.iter().enumerate().filter(|(_, f)| f.arc) {
            chords += 1;
            let (a, b) = (tp.abs[c], tp.abs[c + 1]);
            for t in &world.spec().threats {
                let hard = t.r + world.spec().uavs[0].size;
                if segment_box_misses(t, a, b, hard) {
                    continue;
                }
                let d = point_segment_distance((t.x, t.y), (a.x, a.y), (b.x, b.y));
                if d < hard {
                    let at = a.lerp(b, 0.5).to_array();
                    expected.push((Some(seg.waypoint_segment), Some(at), (hard - d).to_bits()));
                }
            }
        }
        assert_eq!(got, expected, "path {r}");
        found += expected.len();
    }
    assert!(
        found > 20 && chords > 500,
        "{found} violations, {chords} chords"
    );
}

/// Common arrival with a departure delay: UAV 1 waits half the mission, so it flies its
/// 800 sqrt(2) m in T / 2; T minimises the speeds' distance to cruise with UAV 1's length
/// counted twice (T = 5 L / (3 c)), it hovers at its start until T / 2, and both arrive at T.
#[test]
fn a_delayed_uav_hovers_at_its_start_and_arrives_with_the_others() {
    use swarmplan_core::timing::TimedPlan;
    let starts = [[100.0, 100.0, 150.0], [100.0, 100.0, 150.0]];
    let w = World::new(spec(&starts), flat()).unwrap();
    let line = path(&[[100.0, 100.0, 150.0], [900.0, 900.0, 150.0]]);
    let plan = Plan {
        uavs: vec![line.clone(), line],
        delays: vec![0.0, 0.5],
        ..Plan::default()
    };
    let timed = TimedPlan::new(&w, &plan);
    let l = 800.0 * 2f64.sqrt();
    let t = 5.0 * l / (3.0 * 15.0);
    let (a, b) = (&timed.paths[0], &timed.paths[1]);
    assert!((a.arrival - t).abs() < 1e-9 && (b.arrival - t).abs() < 1e-9);
    assert!((b.depart - 0.5 * t).abs() < 1e-9 && a.depart == 0.0);
    assert!((a.speed - l / t).abs() < 1e-9 && (b.speed - 2.0 * l / t).abs() < 1e-9);
    let start = DVec3::new(100.0, 100.0, 150.0);
    assert_eq!(b.position_at_time(0.49 * t), start);
    assert!(a.position_at_time(0.49 * t).distance(start) > 0.4 * l);
    assert!(
        b.position_at_time(0.75 * t)
            .distance(a.position_at_time(0.5 * t))
            < 1e-6
    );
    assert!((b.time_at(1) - t).abs() < 1e-9 && (b.time_at(0) - 0.5 * t).abs() < 1e-9);
    // No delays: the same bits as before delays existed (a plan without the field).
    let plain = Plan {
        delays: Vec::new(),
        ..plan.clone()
    };
    let zeros = Plan {
        delays: vec![0.0, 0.0],
        ..plan
    };
    let (p, z) = (TimedPlan::new(&w, &plain), TimedPlan::new(&w, &zeros));
    assert_eq!(p.paths[1].speed.to_bits(), z.paths[1].speed.to_bits());
    assert_eq!(
        p.paths[1].time_at(1).to_bits(),
        z.paths[1].time_at(1).to_bits()
    );
}

/// Under the cruise policy a delay of delta of the arrival hovers delta / (1 - delta) of the
/// flight time, and the battery pays the hover power for it.
#[test]
fn hovering_before_departure_costs_hover_power() {
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.timing.policy = TimingPolicy::Cruise;
    let w = World::new(s, flat()).unwrap();
    let line = path(&[[100.0, 100.0, 150.0], [900.0, 900.0, 150.0]]);
    let at = |delay: f64| {
        let plan = Plan {
            uavs: vec![line.clone()],
            delays: vec![delay],
            ..Plan::default()
        };
        assess(&w, &plan).per_uav[0].clone()
    };
    let (now, later) = (at(0.0), at(0.25));
    let flight = 800.0 * 2f64.sqrt() / 15.0;
    let hover_s = 0.25 / 0.75 * flight;
    assert!((later.arrival_s - (flight + hover_s)).abs() < 1e-9);
    let hover_w = w
        .spec()
        .energy
        .model
        .power(0.0, w.spec().uavs[0].payload_kg);
    assert!(hover_w > 100.0, "{hover_w}");
    let extra = later.energy_j - now.energy_j;
    assert!((extra - hover_w * hover_s).abs() < 1e-6 * extra, "{extra}");
}

#[test]
fn a_delay_limit_outside_its_range_is_refused_by_name() {
    for bad in [-0.1, 0.95, f64::NAN] {
        let mut s = spec(&[[100.0, 100.0, 150.0]]);
        s.timing.max_delay = bad;
        let e = World::new(s, flat()).unwrap_err().to_string();
        assert!(e.contains("timing.max_delay"), "{e}");
    }
}

/// Delays a plan built in code may hold (beyond the range, 1, negative, NaN, infinite) are
/// timed as the nearest admissible share: every UAV departs, arrives at a finite time, and
/// the plan is assessed without a panic.
#[test]
fn out_of_range_delays_are_timed_as_the_nearest_admissible_share() {
    use swarmplan_core::timing::TimedPlan;
    let starts = [[100.0, 100.0, 150.0], [100.0, 100.0, 150.0]];
    let w = World::new(spec(&starts), flat()).unwrap();
    let line = path(&[
        [100.0, 100.0, 150.0],
        [500.0, 300.0, 150.0],
        [900.0, 900.0, 150.0],
    ]);
    for (d, expected) in [
        (1.0, 0.9),
        (5.0, 0.9),
        (f64::INFINITY, 0.9),
        (-0.5, 0.0),
        (f64::NAN, 0.0),
    ] {
        let plan = Plan {
            uavs: vec![line.clone(), line.clone()],
            delays: vec![0.1, d],
            ..Plan::default()
        };
        let timed = TimedPlan::new(&w, &plan);
        let p = &timed.paths[1];
        assert_eq!(p.delay, expected, "{d}");
        assert!(
            p.arrival.is_finite() && p.depart.is_finite() && p.depart < p.arrival,
            "{d}"
        );
        let a = assess(&w, &plan);
        assert!(a.total.is_finite(), "{d}: {}", a.total);
    }
}

#[test]
fn the_search_and_the_report_agree_on_terrain_clearance() {
    // Smooth hills; paths that hug them at about the 10 m clearance, so that many segments
    // graze it between their samples.
    let nx = 101;
    let ground = |x: f64, y: f64| 60.0 + 40.0 * (x / 97.0).sin() * (y / 61.0).cos();
    let h: Vec<f64> = (0..nx)
        .flat_map(|j| (0..nx).map(move |i| ground(10.0 * i as f64, 10.0 * j as f64)))
        .collect();
    let t = Terrain::new(nx, nx, (0.0, 0.0), (10.0, 10.0), h, Sampling::Bilinear).unwrap();
    let w = World::new(spec(&[[100.0, 100.0, 150.0]]), t).unwrap();
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut uniform = |lo: f64, hi: f64| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        lo + (hi - lo) * (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut grazing, mut clear) = (0, 0);
    for _ in 0..300 {
        let mut points = vec![[100.0, 100.0, 150.0]];
        for k in 1..4 {
            let s = k as f64 / 4.0;
            let (x, y) = (
                100.0 + 800.0 * s + uniform(-40.0, 40.0),
                100.0 + 800.0 * s + uniform(-40.0, 40.0),
            );
            // Waypoint heights are above ground; the segments between them are straight.
            points.push([x, y, 10.0 + uniform(0.0, 12.0)]);
        }
        points.push([900.0, 900.0, 150.0]);
        let plan = Plan {
            pace: 1.0,
            delays: Vec::new(),
            uavs: vec![path(&points)],
        };
        let report = assess(&w, &plan);
        let search = assess_as_searched(&w, &plan);
        assert_eq!(
            report.violation.to_bits(),
            search.violation.to_bits(),
            "{points:?}"
        );
        if report
            .violations
            .iter()
            .flatten()
            .any(|v| v.kind == ViolationKind::Terrain)
        {
            grazing += 1;
        } else {
            clear += 1;
        }
    }
    assert!(
        grazing > 30 && clear > 30,
        "{grazing} grazing, {clear} clear"
    );
}

#[test]
fn a_nudge_moves_one_free_waypoint_of_one_uav_and_keeps_the_rest() {
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::PlanningProblem;
    use swarmplan_core::problem::Problem;
    let mut s = spec(&[[100.0, 100.0, 150.0], [140.0, 100.0, 150.0]]);
    s.timing.max_delay = 0.2; // a block with a delay value too
    let w = World::new(s, flat()).unwrap();
    let p = PlanningProblem::new(&w, EncodingKind::Spherical, InitKind::Line);
    let mut rng = swarmplan_core::rng::rng_from_seed(5);
    let size = p.block_size();
    let mut x = vec![0.0; p.dimension()];
    let mut moved_by = Vec::new();
    for _ in 0..50 {
        p.sample_initial(&mut rng, &mut x);
        let mut block = vec![f64::NAN; size];
        assert!(p.nudge(&x, 1, None, &mut rng, &mut block));
        let mut y = x.clone();
        y[size..2 * size].copy_from_slice(&block);
        for (b, v) in block.iter().enumerate() {
            let bound = p.bounds()[size + b];
            assert!(
                bound.lo <= *v && *v <= bound.hi,
                "value {b} outside its bound"
            );
        }
        let (before, after) = (p.decode(&x), p.decode(&y));
        assert_eq!(before.uavs[0].waypoints, after.uavs[0].waypoints);
        assert!((before.delay(1) - after.delay(1)).abs() < 1e-12);
        let gaps: Vec<f64> = before.uavs[1]
            .waypoints
            .iter()
            .zip(&after.uavs[1].waypoints)
            .map(|(a, b)| a.distance(*b))
            .collect();
        let moved: Vec<usize> = (0..gaps.len()).filter(|&k| gaps[k] > 1e-6).collect();
        if let Some(&k) = moved.first() {
            // The start, the goal and everything before the moved waypoint stay.
            assert!(
                k >= 1 && moved.iter().all(|&m| m + 1 < gaps.len()),
                "{gaps:?}"
            );
            moved_by.push((gaps[k], moved.len()));
        }
    }
    // Most nudges move their waypoint by metres (a few are clamped at the altitude band),
    // and most move only it: the motion encoding changes the moves into and out of it, and
    // a later waypoint follows only when a move hits its bounds (length, heading sector).
    assert!(moved_by.len() >= 40, "{}", moved_by.len());
    let mean = moved_by.iter().map(|m| m.0).sum::<f64>() / moved_by.len() as f64;
    assert!((10.0..60.0).contains(&mean), "mean move {mean} m");
    let alone = moved_by.iter().filter(|m| m.1 == 1).count();
    assert!(
        alone * 10 >= moved_by.len() * 6,
        "{alone} of {}",
        moved_by.len()
    );
}

#[test]
fn hot_spots_weigh_the_free_waypoints_next_to_a_uavs_violations() {
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::PlanningProblem;
    let mut s = spec(&[[100.0, 100.0, 150.0], [100.0, 500.0, 150.0]]);
    let w = World::new(s.clone(), flat()).unwrap();
    let p = PlanningProblem::new(&w, EncodingKind::Cartesian, InitKind::Line);
    let n = p.block_size() / 3;
    let plan = Plan::straight(
        &[w.start(0), w.start(1)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        n,
    );
    // A small threat on UAV 1's free waypoint 3, far from UAV 0's line.
    let at = plan.uavs[1].waypoints[3];
    s.threats = vec![Threat {
        x: at.x,
        y: at.y,
        z: 150.0,
        r: 5.0,
    }];
    let w = World::new(s, flat()).unwrap();
    let p = PlanningProblem::new(&w, EncodingKind::Cartesian, InitKind::Line);
    let x = p.encode(&plan);
    let (mut own, mut other) = (Vec::new(), Vec::new());
    p.hot_spots(&x, 1, &mut own);
    p.hot_spots(&x, 0, &mut other);
    assert_eq!(own.len(), n);
    // The segments into and out of waypoint 3 cross the threat: waypoint 3 (site 2) is
    // the end of both, waypoints 2 and 4 of one each; the first half holds nothing else.
    assert!(own[2] > own[1] && own[1] > 0.0 && own[3] > 0.0, "{own:?}");
    assert!(own[0] == 0.0 && own[4] == 0.0, "{own:?}");
    assert!(other[..n / 2].iter().all(|&v| v == 0.0), "{other:?}");
    // Out of range: nothing known.
    p.hot_spots(&x, 2, &mut own);
    assert!(own.is_empty());
}

#[test]
fn with_delays_free_a_waiting_uavs_energy_weighs_its_delay_and_a_nudge_there_moves_only_it() {
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::PlanningProblem;
    let mut s = spec(&[[100.0, 100.0, 150.0], [100.0, 500.0, 150.0]]);
    s.timing.max_delay = 0.2;
    for u in &mut s.uavs {
        u.battery_wh = 1.0; // far too small: both UAVs violate energy
    }
    let n = s.planning.waypoints;
    let w = World::new(s, flat()).unwrap();
    let p = PlanningProblem::new(&w, EncodingKind::Cartesian, InitKind::Line);
    let mut plan = Plan::straight(
        &[w.start(0), w.start(1)],
        w.goal_at(swarmplan_core::world::DEPARTURE),
        n,
    );
    plan.delays = vec![0.0, 0.1];
    let x = p.encode(&plan);
    assert!(kinds(&w, &p.decode(&x)).contains(&ViolationKind::Energy));
    let (mut waits, mut leaves) = (Vec::new(), Vec::new());
    p.hot_spots(&x, 1, &mut waits);
    p.hot_spots(&x, 0, &mut leaves);
    assert_eq!(waits.len(), n + 1);
    // UAV 1 waits 0.1 of the mission: its energy weighs its delay; UAV 0 leaves at once.
    assert!(waits[n] > 0.0 && leaves[n] == 0.0, "{waits:?} {leaves:?}");
    let mut rng = swarmplan_core::rng::rng_from_seed(2);
    let size = p.block_size();
    let mut moved = 0;
    for _ in 0..20 {
        let mut block = vec![f64::NAN; size];
        assert!(p.nudge(&x, 1, Some(n), &mut rng, &mut block));
        let mut y = x.clone();
        y[size..2 * size].copy_from_slice(&block);
        let after = p.decode(&y);
        let kept = after.uavs.iter().zip(&plan.uavs).all(|(a, b)| {
            a.waypoints
                .iter()
                .zip(&b.waypoints)
                .all(|(p, q)| p.distance(*q) < 1e-6)
        });
        assert!(kept, "a delay nudge keeps every waypoint");
        assert!((0.0..=0.2).contains(&after.delay(1)));
        moved += usize::from((after.delay(1) - 0.1).abs() > 1e-9);
    }
    assert!(moved >= 15, "{moved} of 20 moved the delay");
}

#[test]
fn a_nudge_at_a_shared_zone_puts_the_end_waypoint_at_a_clear_bearing_near_it() {
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::PlanningProblem;
    use swarmplan_core::zone_slot::{bearing, min_angle, SLOT_DISTANCE, SLOT_MARGIN};
    let turned = |starts: &[[f64; 3]], at_start: bool| {
        let s = spec(starts);
        let (zone, sep, band) = (s.timing.zone_radius, s.timing.separation, s.map.z_agl);
        let w = World::new(s, flat()).unwrap();
        let p = PlanningProblem::new(&w, EncodingKind::Cartesian, InitKind::Line);
        let n = p.block_size() / 3;
        let plan = Plan::straight(
            &(0..starts.len()).map(|i| w.start(i)).collect::<Vec<_>>(),
            w.goal_at(swarmplan_core::world::DEPARTURE),
            n,
        );
        let x = p.encode(&plan);
        let (k, site, centre) = if at_start {
            (1, 0, w.start(1))
        } else {
            (n, n - 1, w.goal_at(swarmplan_core::world::DEPARTURE))
        };
        let before = plan.uavs[1].waypoints[k];
        let mut rng = swarmplan_core::rng::rng_from_seed(3);
        let size = p.block_size();
        let mut turned = 0;
        for _ in 0..30 {
            let mut block = vec![f64::NAN; size];
            assert!(p.nudge(&x, 1, Some(site), &mut rng, &mut block));
            let mut y = x.clone();
            y[size..2 * size].copy_from_slice(&block);
            let after = p.decode(&y);
            // Only that waypoint of that UAV moves.
            for (u, path) in after.uavs.iter().enumerate() {
                for (j, q) in path.waypoints.iter().enumerate() {
                    if (u, j) != (1, k) {
                        assert!(q.distance(plan.uavs[u].waypoints[j]) < 1e-9, "{u} {j}");
                    }
                }
            }
            let moved = after.uavs[1].waypoints[k];
            let turn = (bearing(centre, moved) - bearing(centre, before)).abs();
            let turn = turn.min(std::f64::consts::TAU - turn);
            let r = moved.truncate().distance(centre.truncate());
            let in_ring =
                (SLOT_DISTANCE[0] * zone - 1e-9..=SLOT_DISTANCE[1] * zone + 1e-9).contains(&r);
            assert!((band[0]..=band[1]).contains(&moved.z), "{}", moved.z);
            if turn >= SLOT_MARGIN * min_angle(sep, zone) - 1e-9 && in_ring {
                turned += 1;
            }
        }
        turned
    };
    // Three UAVs from one start, on one line: a nudge of the first (or last) free
    // waypoint turns it out of the others' bearing, into the ring near the zone.
    let shared = [[100.0, 100.0, 150.0]; 3];
    assert_eq!(turned(&shared, true), 30);
    assert_eq!(turned(&shared, false), 30);
    // Starts 200 m apart share no zone: a Gaussian nudge rarely turns that far and lands
    // in the ring.
    let apart = [
        [100.0, 100.0, 150.0],
        [100.0, 300.0, 150.0],
        [100.0, 500.0, 150.0],
    ];
    assert!(turned(&apart, true) < 10);
}

#[test]
fn a_shifted_copy_flies_the_donors_path_a_few_separations_aside() {
    use swarmplan_core::encoding::{EncodingKind, InitKind};
    use swarmplan_core::planning::{PlanningProblem, SHIFT_SEPARATIONS};
    use swarmplan_core::problem::Problem;
    let mut s = spec(&[[100.0, 100.0, 150.0], [140.0, 100.0, 150.0]]);
    s.timing.max_delay = 0.2; // a block with a delay value too
    let sep = s.timing.separation;
    let w = World::new(s, flat()).unwrap();
    let p = PlanningProblem::new(&w, EncodingKind::Spherical, InitKind::Line);
    let mut rng = swarmplan_core::rng::rng_from_seed(5);
    let size = p.block_size();
    let mut x = vec![0.0; p.dimension()];
    let mut rigid = 0;
    for _ in 0..50 {
        p.sample_initial(&mut rng, &mut x);
        let mut block = vec![f64::NAN; size];
        assert!(p.shifted_copy(&x, 1, 0, &mut rng, &mut block));
        for (b, v) in block.iter().enumerate() {
            let bound = p.bounds()[size + b];
            assert!(
                bound.lo <= *v && *v <= bound.hi,
                "value {b} outside its bound"
            );
        }
        let mut y = x.clone();
        y[size..2 * size].copy_from_slice(&block);
        let (before, after) = (p.decode(&x), p.decode(&y));
        assert_eq!(before.uavs[0].waypoints, after.uavs[0].waypoints);
        assert!((before.delay(1) - after.delay(1)).abs() < 1e-12);
        let (own, copy) = (&before.uavs[1].waypoints, &after.uavs[1].waypoints);
        let last = own.len() - 1;
        assert!(copy[0].distance(own[0]) < 1e-9 && copy[last].distance(own[last]) < 1e-9);
        // Every free waypoint is the donor's moved by one offset, unless a bound of the
        // encoding (a segment's length, the heading sector) or the map clipped it.
        let donor = &before.uavs[0].waypoints;
        let offset = copy[1] - donor[1];
        let same = (1..last).all(|k| (copy[k] - donor[k] - offset).length() < 1e-6);
        let aside = offset.truncate().length() / sep;
        if same {
            rigid += 1;
            assert!(
                (SHIFT_SEPARATIONS[0] - 1e-9..=SHIFT_SEPARATIONS[1] + 1e-9).contains(&aside),
                "{aside} separations aside"
            );
        }
    }
    assert!(rigid >= 25, "{rigid} of 50 copies kept the donor's shape");
}

#[test]
fn the_ground_coverage_map_is_dead_behind_a_ridge_and_beyond_the_range() {
    use swarmplan_core::cost::coverage::{direct_ground_link, GroundCoverage};
    // A 500 m ridge across the map at x in [240, 260]; the station at x = 100, UGV0 at
    // x = 900; range 300 m. Between them a UAV at 150 m above ground sees the station up to
    // the ridge, then nothing until it comes within 300 m of UGV0 (x >= 600).
    let t = ridge();
    let mut s = comm_spec(&[[100.0, 500.0, 150.0]], [900.0, 500.0, 150.0]);
    s.map.z_agl = [100.0, 150.0];
    let w = World::new(s, t).unwrap();
    let map = GroundCoverage::at_band_top(&w);
    assert_eq!(map.agl, 150.0);
    assert_eq!(map.range, 300.0);
    let at = |x: f64| map.linked(x, 500.0);
    assert!(at(150.0) && at(220.0), "in front of the ridge, in range");
    assert!(
        !at(300.0) && !at(450.0) && !at(590.0),
        "behind it, out of UGV0's range"
    );
    assert!(at(650.0) && at(880.0), "near UGV0");
    // The cells agree with the single-point test at their centres.
    for ([x0, y0, x1, y1], linked) in map.cells() {
        let (x, y) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
        let p = DVec3::new(x, y, w.terrain().height(x, y) + 150.0);
        assert_eq!(linked, direct_ground_link(&w, p), "cell at ({x}, {y})");
    }
    let dead = map.dead_share();
    assert!((0.2..0.8).contains(&dead), "dead share {dead}");
}

/// A UAV flying east at 15 m/s (cruise) on flat ground through `points` (x, z pairs at
/// y = 100), the last one UGV0.
fn east_at_cruise(points: &[[f64; 2]]) -> (World, Plan) {
    let points: Vec<[f64; 3]> = points.iter().map(|p| [p[0], 100.0, p[1]]).collect();
    let mut s = spec(&[points[0]]);
    s.timing.policy = TimingPolicy::Cruise;
    s.goal.position = *points.last().unwrap();
    let plan = Plan {
        uavs: vec![path(&points)],
        ..Plan::default()
    };
    (World::new(s, flat()).unwrap(), plan)
}

#[test]
fn a_peak_corner_is_climbed_as_flown_not_as_its_waypoint() {
    // Up 30 deg for 200 m east, down 30 deg for 200 m: a corner of theta = 60 deg in the
    // vertical plane. Its arc (R = 50 m) leaves the segments t = 50 tan 30 deg = 28.87 m
    // before and after the peak and passes 50 (1 / cos 30 deg - 1) = 7.735 m below it; it is
    // flown as ceil(60 / 16.2) = 4 chords of 15 deg, whose middle vertex is the arc's top.
    // So the UAV climbs 115.470 - 7.735 = 107.735 m, not the waypoints' 115.470 m, and
    // descends as much; it turns through no heading.
    let peak = 200.0 * 30f64.to_radians().tan();
    let (w, plan) = east_at_cruise(&[[100.0, 100.0], [300.0, 100.0 + peak], [500.0, 100.0]]);
    let theta = 60f64.to_radians();
    let (r, t) = (50.0, 50.0 * (0.5 * theta).tan());
    let arc = swarmplan_core::flight::Fillet::at(
        DVec3::new(100.0, 100.0, 100.0),
        DVec3::new(300.0, 100.0, 100.0 + peak),
        DVec3::new(500.0, 100.0, 100.0),
        r,
    )
    .unwrap();
    assert_eq!(arc.chords(), 4);
    let climbed = peak - r * (1.0 / (0.5 * theta).cos() - 1.0);
    assert!((climbed - 107.735).abs() < 1e-3, "{climbed}");
    let length =
        2.0 * (200.0 / 30f64.to_radians().cos() - t) + 4.0 * 2.0 * r * 7.5f64.to_radians().sin();
    let a = assess(&w, &plan);
    let u = &a.per_uav[0];
    assert!(
        (u.length_m - length).abs() < 1e-9,
        "{} vs {length}",
        u.length_m
    );
    let model = &w.spec().energy.model;
    let payload = w.spec().uavs[0].payload_kg;
    let weight_n = model.mass(payload) * swarmplan_core::world::energy::G;
    assert!((weight_n - 24.903_325).abs() < 1e-9, "{weight_n}");
    let want = model.power(15.0, payload) * length / 15.0 + weight_n * climbed;
    assert!(
        (u.energy_j - want).abs() < 1e-9 * want,
        "{} vs {want}",
        u.energy_j
    );
    // Eq. 5: L + alpha (up + down) + beta x 0, alpha = 1.
    let eq5 = length + 2.0 * climbed;
    assert!((u.raw[TermId::Energy] - eq5).abs() < 1e-9, "{:?}", u.raw);
    // On its waypoints it would need m g 7.735 m = 192.6 J more.
    let waypoint_joules = want + weight_n * (peak - climbed);
    assert!((waypoint_joules - u.energy_j - 192.63).abs() < 0.01);
}

#[test]
fn a_repeated_waypoint_is_passed_once_on_a_straight_line_and_mid_arc_at_a_corner() {
    use swarmplan_core::timing::TimedPlan;
    let times = |w: &World, plan: &Plan| {
        let timed = TimedPlan::new(w, plan);
        let flown = TimedPlan::flown(w, plan);
        flown.paths[0].waypoint_times(&timed.paths[0].abs)
    };
    // Straight east: (300, 100) twice, the goal (500, 100) twice.
    let (w, plan) = east_at_cruise(&[
        [100.0, 100.0],
        [300.0, 100.0],
        [300.0, 100.0],
        [500.0, 100.0],
        [500.0, 100.0],
    ]);
    let got = times(&w, &plan);
    let pass = 200.0 / 15.0;
    let want = [0.0, pass, pass, 2.0 * pass, 2.0 * pass];
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-9, "{got:?} vs {want:?}");
    }
    // A left turn of 90 deg at (300, 100), given twice: both copies when the UAV is half
    // way round the arc, 200 - 50 m after the start plus half the arc's 6 chords of 15 deg.
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.timing.policy = TimingPolicy::Cruise;
    s.goal.position = [300.0, 300.0, 150.0];
    let plan = Plan {
        uavs: vec![path(&[
            [100.0, 100.0, 150.0],
            [300.0, 100.0, 150.0],
            [300.0, 100.0, 150.0],
            [300.0, 300.0, 150.0],
        ])],
        ..Plan::default()
    };
    let w = World::new(s, flat()).unwrap();
    let got = times(&w, &plan);
    let chords = 6.0 * 2.0 * 50.0 * 7.5f64.to_radians().sin();
    let mid = (150.0 + 0.5 * chords) / 15.0;
    let arrival = (150.0 + chords + 150.0) / 15.0;
    let want = [0.0, mid, mid, arrival];
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() < 1e-9, "{got:?} vs {want:?}");
    }
}

#[test]
fn the_shadowing_series_is_reproduced_from_its_documented_definition() {
    // docs/model.md, "Communication": ChaCha8 (rand_chacha) seeded by `seed_from_u64` with
    // `communication.seed`; standard normal draws by rand_distr's `StandardNormal`;
    // X_0 = sigma z_0, X_{k+1} = rho X_k + sqrt(1 - rho^2) sigma z_{k+1}, rho = exp(-dt / tau),
    // for k = 0..=ceil(3600 / dt); R_k = R0 10^(-X_k / 20).
    use rand::SeedableRng;
    use rand_distr::{Distribution, StandardNormal};
    use swarmplan_core::world::channel::Channel;
    for seed in [1, 7] {
        let spec = CommSpec {
            seed,
            ..CommSpec::default()
        };
        let channel = Channel::new(&spec);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let mut z = || -> f64 { StandardNormal.sample(&mut rng) };
        let sigma = spec.shadowing_sigma_db;
        let rho = (-spec.time_step / spec.shadowing_tau_s).exp();
        let mut x = sigma * z();
        for k in 0..=3600 {
            assert_eq!(
                channel.shadowing_db(k).to_bits(),
                x.to_bits(),
                "seed {seed}, k {k}"
            );
            let range = spec.range * 10f64.powf(-x / 20.0);
            assert!((channel.base_range(k) - range).abs() <= 1e-9 * range);
            x = rho * x + (1.0 - rho * rho).sqrt() * sigma * z();
        }
        // Later times reuse the last value.
        assert_eq!(channel.shadowing_db(9999), channel.shadowing_db(3600));
    }
    // The first values for seed 1 as an implementation outside Rust computes them (ChaCha8
    // and the ziggurat written out in Python from their definitions; docs/model.md).
    let channel = Channel::new(&CommSpec::default());
    let first = [
        -0.939_388_234_223_683_9,
        -3.252_657_155_106_094_3,
        -2.375_968_470_949_139_5,
        -4.068_780_961_414_792_5,
        -4.250_111_236_278_161,
    ];
    for (k, want) in first.into_iter().enumerate() {
        assert_eq!(channel.shadowing_db(k), want, "step {k}");
    }
}

#[test]
fn a_battery_short_of_the_way_and_the_climb_is_a_cause_no_plan_can_be_feasible() {
    use swarmplan_core::world::unreachable::{unreachable_feasibility, unreachable_in_world};
    // From (100, 100) to UGV0 at (900, 900): at least 1131 m. The default rotary wing needs
    // about 9.4 J per metre at its most economical speed, so about 10.6 kJ flown level:
    // within a 6 Wh battery's usable 17.3 kJ, beyond a 3 Wh one's 8.6 kJ.
    let mut s = spec(&[[100.0, 100.0, 150.0]]);
    s.uavs[0].battery_wh = 6.0;
    assert!(unreachable_feasibility(&s).is_empty());
    s.uavs[0].battery_wh = 3.0;
    let causes = unreachable_feasibility(&s);
    assert_eq!(causes.len(), 1, "{causes:?}");
    assert_eq!(causes[0].field, "uavs[0].battery_wh");
    assert!(
        causes[0].reason.contains("at least 1131 m"),
        "{}",
        causes[0].reason
    );
    // On ground that rises towards UGV0, 400 m from the start's to UGV0's, the 6 Wh battery
    // must also lift the UAV 400 m (24.9 N x 400 m = 10.0 kJ): 20.6 kJ, beyond its 17.3 kJ.
    s.uavs[0].battery_wh = 6.0;
    let n = 11;
    let h: Vec<f64> = (0..n)
        .flat_map(|j| (0..n).map(move |i| 500.0 * f64::from(i.min(j) as u32) / 10.0))
        .collect();
    let slope = Terrain::new(n, n, (0.0, 0.0), (100.0, 100.0), h, Sampling::Bilinear).unwrap();
    let w = World::new(s.clone(), slope).unwrap();
    let causes = unreachable_in_world(&w);
    assert_eq!(causes.len(), 1, "{causes:?}");
    assert!(
        causes[0].reason.contains("to rise the 400 m"),
        "{}",
        causes[0].reason
    );
    // On flat ground the same battery suffices.
    assert!(unreachable_in_world(&World::new(s, flat()).unwrap()).is_empty());
}
