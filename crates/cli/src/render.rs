//! Human-readable tables of an assessment (per-UAV figures, cost breakdown, violations,
//! where outages happen out of any direct ground link, and separation conflicts at the
//! edges of the take-off and landing zones).

use std::fmt::Write;

use swarmplan_core::cost::coverage::GroundCoverage;
use swarmplan_core::cost::Assessment;
use swarmplan_core::feasibility::{Violation, ViolationKind};
use swarmplan_core::world::spec::CommRequirement;
use swarmplan_core::world::World;

/// Per-UAV table, term breakdown, feasibility and violations.
#[must_use]
pub fn assessment(world: &World, a: &Assessment) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "scenario {}: {} UAVs",
        world.spec().name,
        a.per_uav.len()
    );
    let _ = writeln!(
        s,
        "{:>4} {:>9} {:>8} {:>9} {:>9} {:>8} {:>10} {:>8} {:>10}",
        "uav",
        "length m",
        "speed",
        "arrive s",
        "energy J",
        "battery",
        "clear m",
        "outage s",
        "cost"
    );
    for (i, u) in a.per_uav.iter().enumerate() {
        let _ = writeln!(
            s,
            "{:>4} {:>9.1} {:>8.2} {:>9.1} {:>9.0} {:>7.0}% {:>10.1} {:>8.0} {:>10.1}",
            i,
            u.length_m,
            u.speed_mps,
            u.arrival_s,
            u.energy_j,
            100.0 * u.battery_ratio,
            u.min_clearance_m,
            u.outage_s,
            u.cost
        );
    }
    let _ = writeln!(s, "\ncost breakdown (weighted, all UAVs):");
    let t = a.term_totals();
    for (term, v) in t.iter() {
        let _ = writeln!(s, "  {:<14} {v:>12.2}", term.name());
    }
    let _ = writeln!(s, "  {:<14} {:>12.2}", "penalty", a.penalty);
    let _ = writeln!(s, "  {:<14} {:>12.2}", "total", a.total);
    let _ = writeln!(s, "  {:<14} {:>12.2}", "per UAV", a.per_uav_cost());
    let v = a.violations.as_deref().unwrap_or_default();
    let hard = v.iter().filter(|x| x.hard).count();
    let soft = v.len() - hard;
    let soft_note = if soft > 0 {
        format!("; {soft} soft, in the cost only (profile {})", a.profile)
    } else {
        String::new()
    };
    if hard == 0 {
        let _ = writeln!(s, "\nfeasible: yes{soft_note}");
    } else {
        let _ = writeln!(s, "\nfeasible: no ({hard} violations{soft_note})");
    }
    for x in v {
        let when = x.time.map(|t| format!(" t={t:.1}s")).unwrap_or_default();
        let _ = writeln!(
            s,
            "  {:<10} uav {}{}: {}{}",
            x.kind.name(),
            x.uav,
            when,
            x.detail,
            if x.hard { "" } else { " (soft)" }
        );
    }
    if let Some(note) = dead_zone_note(world, v) {
        let _ = writeln!(s, "{note}");
    }
    if let Some(note) = zone_edge_note(world, v) {
        let _ = writeln!(s, "{note}");
    }
    s
}

/// For a plan with hard separation violations at the edge of the take-off or landing zone:
/// how many, and what parting there takes. UAVs that leave one point at once are exempt
/// inside the zone (radius r) and must be `separation` d apart where they leave it, so their
/// directions must differ by 2 asin(d / 2r) (19 deg for 10 m at 30 m) unless their speeds
/// or departure times differ; the search meets this as its hardest trap on the outside
/// instances (docs/results.md, "Repairs, a doubled budget, ...").
fn zone_edge_note(world: &World, violations: &[Violation]) -> Option<String> {
    let timing = &world.spec().timing;
    let (r, d) = (timing.zone_radius, timing.separation);
    if r <= 0.0 {
        return None;
    }
    // Within one separation distance beyond the zone's edge (horizontally).
    let near = |p: &[f64; 3], c: swarmplan_core::DVec3| {
        let h = (p[0] - c.x).hypot(p[1] - c.y);
        h <= r + d
    };
    let conflicts: Vec<&Violation> = violations
        .iter()
        .filter(|x| x.hard && x.kind == ViolationKind::Separation)
        .collect();
    let (mut take_off, mut landing) = (0, 0);
    for x in &conflicts {
        let Some(p) = x.position else { continue };
        if x.uav < world.uav_count() && near(&p, world.start(x.uav)) {
            take_off += 1;
        } else if near(&p, world.goal_at(swarmplan_core::world::DEPARTURE)) {
            landing += 1;
        }
    }
    if take_off + landing == 0 {
        return None;
    }
    let parting = 2.0 * (0.5 * d / r).min(1.0).asin().to_degrees();
    // Delays stagger departures only: under common arrival every UAV still lands at T.
    let delays = match (take_off > 0, timing.delay_is_free()) {
        (false, _) => "",
        (true, true) => {
            "; departure delays are free here, so the search can also stagger the take-offs"
        }
        (true, false) => {
            "; free departure delays (`timing.max_delay`) would let them take off one after another"
        }
    };
    let slots = match (take_off > 0, landing > 0) {
        _ if world.slots().any() => String::new(),
        (true, true) => "; launch and recovery slots (`timing.launch_interval`, `timing.recovery_interval`; docs/model.md) would take them off and land them one after another".into(),
        (true, false) => "; launch slots (`timing.launch_interval`; docs/model.md) would take them off one after another".into(),
        _ => "; recovery slots (`timing.recovery_interval`; docs/model.md) would land them one after another".into(),
    };
    let n = conflicts.len();
    let place = match (take_off, landing) {
        (t, 0) => format!("{t} of the {n} where UAVs leave the take-off zone"),
        (0, l) => format!("{l} of the {n} where UAVs enter the landing zone"),
        (t, l) => format!("{t} of the {n} where UAVs leave the take-off zone and {l} where they enter the landing zone"),
    };
    Some(format!(
        "  separation conflicts: {place} ({r} m around a start or UGV0; separation counts outside it): UAVs that cross its edge together must part by at least {parting:.0} deg there (2 asin({d} / {})), or cross it at different speeds or times{delays}{slots}; `plan --attempts K` tries further seeds",
        2.0 * r
    ))
}

/// For a plan with hard communication violations: how much of the map has no direct ground
/// link even at the top of the altitude band, and how many of the outages begin there
/// (where another path at the same place cannot help, only a relay).
fn dead_zone_note(world: &World, violations: &[Violation]) -> Option<String> {
    if world.spec().communication.requirement != CommRequirement::Relay {
        return None; // contact is then not about the ground
    }
    let outages: Vec<&Violation> = violations
        .iter()
        .filter(|x| x.hard && x.kind == ViolationKind::Comm)
        .collect();
    if outages.is_empty() {
        return None;
    }
    let map = GroundCoverage::at_band_top(world);
    let placed: Vec<[f64; 3]> = outages.iter().filter_map(|x| x.position).collect();
    let there = placed.iter().filter(|p| !map.linked(p[0], p[1])).count();
    let consequence = if there == 0 {
        format!(
            "none of the {} outages begins there; they come from the channel's dips in time (shadowing, interference), which a relay or other timing can bridge",
            placed.len()
        )
    } else {
        format!(
            "{there} of the {} outages begin there, where only a relay through another UAV keeps contact",
            placed.len()
        )
    };
    Some(format!(
        "  no direct ground link from {:.0} % of the map even at {} m AGL (nominal range {} m, line of sight; the top view of `plan` or `plot` hatches it): {consequence}",
        100.0 * map.dead_share(),
        map.agl,
        map.range,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarmplan_core::cost::assess;
    use swarmplan_core::plan::{Path, Plan};
    use swarmplan_io::scenario::build_world;

    use swarmplan_io::catalog::load_spec;

    /// `tiny` with a fixed radio range and both UAVs flying the straight line to UGV0 at
    /// 60 m above the start's ground.
    fn straight(range: f64) -> (World, Assessment) {
        straight_with(range, &[])
    }

    /// [`straight`] with interference windows.
    fn straight_with(
        range: f64,
        windows: &[swarmplan_core::world::spec::InterferenceSpec],
    ) -> (World, Assessment) {
        let mut loaded = load_spec("tiny").expect("built-in");
        let c = &mut loaded.spec.communication;
        c.requirement = CommRequirement::Relay;
        c.range = range;
        c.shadowing_sigma_db = 0.0;
        c.interference = windows.to_vec();
        let world = build_world(&loaded, None).expect("world");
        let path = |i: usize| Path {
            waypoints: vec![
                world.start(i),
                world.goal_at(swarmplan_core::world::DEPARTURE),
            ],
        };
        let plan = Plan {
            pace: 1.0,
            delays: Vec::new(),
            uavs: vec![path(0), path(1)],
        };
        let a = assess(&world, &plan);
        (world, a)
    }

    #[test]
    fn outages_where_no_ground_link_exists_are_said_to_need_a_relay() {
        // 100 m of range: out of reach of both ground nodes for about 8 s mid-way (5 s
        // tolerated), and at the top of the band (80 m) in reach only within about 60 m
        // horizontally of either.
        let (world, a) = straight(100.0);
        let text = assessment(&world, &a);
        assert!(text.contains("out of contact"), "{text}");
        assert!(
            text.contains("even at 80 m AGL (nominal range 100 m")
                && text.contains("2 of the 2 outages begin there"),
            "{text}"
        );
        // In range all the way: no outage, no note.
        let (world, a) = straight(2000.0);
        let text = assessment(&world, &a);
        assert!(!text.contains("no direct ground link"), "{text}");
        // In range everywhere, but a 60 dB window over the whole map from 2 to 12 s: the
        // outages come from the channel in time, not from the place.
        let window = swarmplan_core::world::spec::InterferenceSpec {
            time: [2.0, 12.0],
            center: [150.0, 100.0],
            radius: 400.0,
            loss_db: 60.0,
        };
        let (world, a) = straight_with(2000.0, &[window]);
        let text = assessment(&world, &a);
        assert!(
            text.contains("none of the 2 outages begins there"),
            "{text}"
        );
    }

    /// A hard separation conflict of UAV 0 with UAV 1 at `(x, y)`.
    fn conflict_at(x: f64, y: f64) -> Violation {
        Violation {
            kind: ViolationKind::Separation,
            uav: 0,
            other: Some(1),
            index: None,
            position: Some([x, y, 100.0]),
            time: Some(2.0),
            amount: 1.0,
            detail: String::new(),
            hard: true,
        }
    }

    #[test]
    fn separation_conflicts_are_placed_at_the_zone_edges_or_en_route() {
        // tiny: both UAVs start at (30, 30); UGV0 at (270, 170); zone 30 m, separation 10 m.
        let world = build_world(&load_spec("tiny").expect("built-in"), None).expect("world");
        let off = 30.0 / std::f64::consts::SQRT_2 + 2.0; // 32.8 m from the start
        let take_off = conflict_at(30.0 + off / 1.2, 30.0 + off / 1.7);
        let en_route = conflict_at(150.0, 100.0);
        let landing = conflict_at(270.0 - 35.0, 170.0);
        let note = zone_edge_note(&world, &[take_off.clone(), en_route.clone()]).expect("a note");
        assert!(
            note.contains("1 of the 2 where UAVs leave the take-off zone (30 m")
                && note.contains("at least 19 deg")
                && note.contains("take off one after another"),
            "{note}"
        );
        let note = zone_edge_note(&world, &[landing.clone(), take_off]).expect("a note");
        assert!(
            note.contains("1 of the 2 where UAVs leave the take-off zone and 1 where they enter the landing zone"),
            "{note}"
        );
        // Landing only: delays cannot help (every UAV lands at the common arrival time).
        let note = zone_edge_note(&world, std::slice::from_ref(&landing)).expect("a note");
        assert!(
            note.contains("1 of the 1 where UAVs enter the landing zone"),
            "{note}"
        );
        assert!(!note.contains("delays"), "{note}");
        assert!(
            note.contains("recovery slots (`timing.recovery_interval`"),
            "{note}"
        );
        // En route only, or a soft conflict: no note.
        assert_eq!(zone_edge_note(&world, &[en_route]), None);
        let soft = Violation {
            hard: false,
            ..landing
        };
        assert_eq!(zone_edge_note(&world, &[soft]), None);
    }

    #[test]
    fn a_fleet_leaving_one_point_side_by_side_gets_the_zone_edge_note() {
        // Both UAVs of tiny from the shared start, UAV 1 by a waypoint 5 deg off UAV 0's
        // straight line: closer than 10 m where they leave the 30 m zone.
        let world = build_world(&load_spec("tiny").expect("built-in"), None).expect("world");
        let (start, goal) = (
            world.start(0),
            world.goal_at(swarmplan_core::world::DEPARTURE),
        );
        let bearing = (goal.y - start.y).atan2(goal.x - start.x) + 5f64.to_radians();
        let via = swarmplan_core::DVec3::new(
            start.x + 100.0 * bearing.cos(),
            start.y + 100.0 * bearing.sin(),
            start.z,
        );
        let plan = Plan {
            pace: 1.0,
            delays: Vec::new(),
            uavs: vec![
                Path {
                    waypoints: vec![start, goal],
                },
                Path {
                    waypoints: vec![start, via, goal],
                },
            ],
        };
        let text = assessment(&world, &assess(&world, &plan));
        assert!(text.contains("separation"), "{text}");
        assert!(
            text.contains("separation conflicts: 1 of the 2 where UAVs leave the take-off zone")
                && text.contains("at least 19 deg"),
            "{text}"
        );
    }
}
