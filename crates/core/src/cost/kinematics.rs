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

/// Wraps an angle difference into (-pi, pi].
#[must_use]
pub fn wrap_angle(a: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = (a + PI).rem_euclid(TAU) - PI;
    if r == -PI {
        PI
    } else {
        r
    }
}

/// Computes the sums for UAV `uav` and reports turn and climb violations.
pub fn kinematics(
    world: &World,
    uav: usize,
    tp: &TimedPath,
    sink: &mut ViolationSink,
) -> Kinematics {
    let spec = &world.spec.uavs[uav];
    let max_turn = spec.max_turn_deg.to_radians();
    let max_climb = spec.max_climb_deg.to_radians();
    let tan_climb = if max_climb >= std::f64::consts::FRAC_PI_2 {
        f64::INFINITY
    } else {
        max_climb.tan()
    };
    let p = &tp.abs;
    let mut k = Kinematics::default();
    let mut last_heading: Option<f64> = None;
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
        let heading = d.y.atan2(d.x);
        if let Some(prev) = last_heading {
            let turn = wrap_angle(heading - prev);
            k.turn_abs += turn.abs();
            k.turn_sq += turn * turn;
            if turn.abs() > max_turn + 1e-9 {
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
        last_heading = Some(heading);
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn wrap_keeps_angles_in_half_open_circle() {
        assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
        assert!((wrap_angle(-3.0 * PI / 2.0) - PI / 2.0).abs() < 1e-12);
        assert!((wrap_angle(PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
    }
}
