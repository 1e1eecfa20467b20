//! Heading and climb along one path: the sums that the paper's Eq. 5 (energy) and Eq. 7
//! (turning) need, and the hard turn and climb limits (45 deg each by default).
//!
//! Headings are those of the xy-projected segments; zero-length projections carry no heading
//! and are skipped, so a waypoint repeated in place does not count as a turn. The turn at a
//! waypoint is the wrapped difference of the headings before and after it. A segment's climb
//! angle is atan2(dz, horizontal length) with absolute altitudes (terrain included).

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPath;
use crate::world::World;

/// Heading and altitude sums of one path.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Kinematics {
    /// Sum of |heading change| over waypoints, radians (Eq. 5's turn sum).
    pub turn_abs: f64,
    /// Sum of squared heading changes, rad^2 (Eq. 7).
    pub turn_sq: f64,
    /// Sum of |dz| of the absolute altitude over segments, metres (Eq. 5).
    pub vertical_abs: f64,
    /// Sum of the climbs only (dz > 0), metres (energy model).
    pub climb_up: f64,
}

/// Computes the sums for UAV `uav` and reports turn and climb violations. Without `sums`
/// (the `spso` preset weighs them 0) the turn sums are left at 0 and only the limits are
/// checked, which saves an `atan2` per waypoint.
pub fn kinematics(
    world: &World,
    uav: usize,
    tp: &TimedPath,
    sums: bool,
    sink: &mut ViolationSink,
) -> Kinematics {
    let spec = &world.spec().uavs[uav];
    let max_turn = spec.max_turn_deg.to_radians();
    let max_climb = spec.max_climb_deg.to_radians();
    let tan_climb = if max_climb >= std::f64::consts::FRAC_PI_2 {
        f64::INFINITY
    } else {
        max_climb.tan()
    };
    let p = &tp.abs;
    let mut k = Kinematics::default();
    let mut last_heading: Option<(f64, f64, f64)> = None;
    let cos_turn = max_turn.cos();
    for s in 0..p.len().saturating_sub(1) {
        let d = p[s + 1] - p[s];
        k.vertical_abs += d.z.abs();
        k.climb_up += d.z.max(0.0);
        let horizontal = (d.x * d.x + d.y * d.y).sqrt();
        // |climb| > limit, without an atan2 unless it is violated.
        if d.z.abs() > tan_climb * horizontal && d.z.abs().atan2(horizontal) > max_climb + 1e-9 {
            let climb = d.z.atan2(horizontal);
            sink.add(
                ViolationKind::Climb,
                uav,
                (climb.abs() - max_climb).to_degrees(),
                At {
                    index: Some(s),
                    position: Some(p[s]),
                    time: Some(tp.time_at(s)),
                    ..At::default()
                },
                || {
                    format!(
                        "segment {s} {} at {:.1} deg; limit {:.1} deg",
                        if climb > 0.0 { "climbs" } else { "dives" },
                        climb.abs().to_degrees(),
                        spec.max_climb_deg
                    )
                },
            );
        }
        if horizontal == 0.0 {
            continue;
        }
        if let Some((px, py, ph)) = last_heading {
            // The unsigned angle between consecutive headings; atan2 only when a sum needs
            // it or the limit is broken (cos turn < cos limit, tested without it).
            let cross = (px * d.y - py * d.x).abs();
            let dot = px * d.x + py * d.y;
            let broken = dot < cos_turn * ph * horizontal;
            let turn = if sums || broken {
                cross.atan2(dot)
            } else {
                0.0
            };
            k.turn_abs += turn;
            k.turn_sq += turn * turn;
            if broken && turn > max_turn + 1e-9 {
                sink.add(
                    ViolationKind::Turn,
                    uav,
                    (turn.abs() - max_turn).to_degrees(),
                    At {
                        index: Some(s),
                        position: Some(p[s]),
                        time: Some(tp.time_at(s)),
                        ..At::default()
                    },
                    || {
                        format!(
                            "turns {:.1} deg at waypoint {s}; limit {:.1} deg",
                            turn.abs().to_degrees(),
                            spec.max_turn_deg
                        )
                    },
                );
            }
        }
        last_heading = Some((d.x, d.y, horizontal));
    }
    k
}
