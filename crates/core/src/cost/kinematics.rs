//! Heading and climb along one path: the heading sums that the paper's Eq. 5 (energy) and
//! Eq. 7 (turning) need, and the hard turn and climb limits (45 deg each by default). The
//! vertical sums of Eq. 5 are the flown path's ([`super::energy::Vertical`]).
//!
//! Headings are those of the xy-projected segments; zero-length projections carry no heading
//! and are skipped, so a waypoint repeated in place does not count as a turn. The turn at a
//! waypoint is the wrapped difference of the headings before and after it. A segment's climb
//! angle is atan2(dz, horizontal length) with absolute altitudes (terrain included).

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPath;
use crate::world::World;

/// Heading sums of one path.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Kinematics {
    /// Sum of |heading change| over waypoints, radians (Eq. 5's turn sum).
    pub turn_abs: f64,
    /// Sum of squared heading changes, rad^2 (Eq. 7).
    pub turn_sq: f64,
}

/// Computes the sums for UAV `uav` and reports turn and climb violations. The sums are
/// computed under every objective preset: the `spso-mycost` objective preset weighs Eq. 7 at 0, but the
/// battery check needs the radians turned (until issue 45 it skipped them there, and the
/// turning energy counted only the turns that broke the limit).
pub fn kinematics(
    world: &World,
    uav: usize,
    tp: &TimedPath,
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
            // The unsigned angle between consecutive headings; the limit is tested without
            // it first (cos turn < cos limit).
            let cross = (px * d.y - py * d.x).abs();
            let dot = px * d.x + py * d.y;
            let broken = dot < cos_turn * ph * horizontal;
            let turn = cross.atan2(dot);
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
