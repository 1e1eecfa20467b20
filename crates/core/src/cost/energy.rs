//! Energy: the paper's Eq. 5 as an objective term, and the physical energy against the
//! battery as a hard constraint.
//!
//! Eq. 5 (per UAV): J_energy = L + alpha sum |dz| + beta sum |d heading| (metres, metres,
//! radians). Physical: E = P(v) L / v + m g (metres climbed) + turn energy x (radians
//! turned) + P(0) x (departure delay, hovering at the start), with P the rotary-wing power
//! of [`crate::world::energy::RotaryWing`]. Feasible iff E <= (1 - reserve) x battery.
//!
//! Both are of the path the UAV flies (docs/model.md, "Energy"): L, the metres flown up
//! and down and the metres climbed are summed over the flown polyline, whose arcs cut the
//! corners (a climb-then-dive corner is flown lower than its waypoint). The heading changes
//! are the waypoints' ([`Kinematics::turn_abs`]): each arc is tangent to both segments of
//! its corner and turns one way, so the flown path turns through exactly the headings its
//! waypoints do.

use super::kinematics::Kinematics;
use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPath;
use crate::world::energy::G;
use crate::world::World;

/// Joules in a watt-hour.
pub const J_PER_WH: f64 = 3600.0;

/// How a flown path moves up and down.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Vertical {
    /// Sum of |dz| of the absolute altitude over the path's segments, metres (Eq. 5).
    pub travel: f64,
    /// Sum of the climbs only (dz > 0), metres (the physical energy).
    pub climbed: f64,
}

impl Vertical {
    /// The vertical sums of the polyline of `tp` (a flown path: straight pieces and arc
    /// chords; a waypoint path where the world flies no arcs).
    #[must_use]
    pub fn of(tp: &TimedPath) -> Self {
        let mut v = Self::default();
        for pair in tp.abs.windows(2) {
            let dz = pair[1].z - pair[0].z;
            v.travel += dz.abs();
            v.climbed += dz.max(0.0);
        }
        v
    }
}

/// The paper's Eq. 5 for one flown path `tp`, moving `vertical` up and down and turning
/// through the headings of `k`.
#[must_use]
pub fn energy_term(world: &World, tp: &TimedPath, vertical: Vertical, k: &Kinematics) -> f64 {
    let e = &world.spec().energy;
    tp.length + e.alpha * vertical.travel + e.beta * k.turn_abs
}

/// Physical energy of one flown path `tp`, joules (moving `vertical` up and down and
/// turning through the headings of `k`).
#[must_use]
pub fn physical_energy(
    world: &World,
    uav: usize,
    tp: &TimedPath,
    vertical: Vertical,
    k: &Kinematics,
) -> f64 {
    if tp.length == 0.0 {
        return 0.0;
    }
    let m = &world.spec().energy.model;
    let payload = world.spec().uavs[uav].payload_kg;
    let cruise = if tp.speed > 0.0 {
        m.power(tp.speed, payload) * tp.length / tp.speed
    } else {
        f64::INFINITY
    };
    let moving =
        cruise + m.mass(payload) * G * vertical.climbed + m.turn_energy_per_rad * k.turn_abs;
    let hover = tp.depart - tp.launch;
    if hover > 0.0 {
        // Hovering at the start from its launch slot until departure (on the launcher
        // before, drawing nothing).
        moving + m.power(0.0, payload) * hover
    } else {
        moving
    }
}

/// Usable energy of UAV `uav`, joules.
#[must_use]
pub fn usable_energy(world: &World, uav: usize) -> f64 {
    let u = &world.spec().uavs[uav];
    (1.0 - u.reserve) * u.battery_wh * J_PER_WH
}

/// Checks the battery; returns E / battery (the ratio reported per UAV).
pub fn check_battery(world: &World, uav: usize, energy: f64, sink: &mut ViolationSink) -> f64 {
    let usable = usable_energy(world, uav);
    if energy > usable {
        sink.add(
            ViolationKind::Energy,
            uav,
            100.0 * (energy / usable - 1.0),
            At::default(),
            || format!("needs {energy:.0} J; usable battery {usable:.0} J"),
        );
    }
    energy / (world.spec().uavs[uav].battery_wh * J_PER_WH)
}
