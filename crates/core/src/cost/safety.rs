//! The paper's Eq. 4, J_safety: one indicator per segment flown below v_min or above v_max,
//! plus one if the payload exceeds W_max. The same conditions are hard constraints.

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPath;
use crate::world::World;

/// Counts Eq. 4's indicators for UAV `uav` flying `tp` over the plan's `segments`
/// waypoint segments, and reports speed and payload violations.
pub fn safety_term(
    world: &World,
    uav: usize,
    tp: &TimedPath,
    segments: usize,
    sink: &mut ViolationSink,
) -> f64 {
    let u = &world.spec().uavs[uav];
    let [vmin, vmax] = u.speed;
    let segments = segments as f64;
    let mut j = 0.0;
    let v = tp.speed;
    if tp.length > 0.0 && (v < vmin - 1e-9 || v > vmax + 1e-9) {
        j += segments;
        let excess = (vmin - v).max(v - vmax);
        sink.add(ViolationKind::Speed, uav, excess, At::default(), || {
            format!("flies at {v:.2} m/s; range [{vmin}, {vmax}] m/s")
        });
    }
    if u.payload_kg > u.max_payload_kg {
        j += 1.0;
        sink.add(
            ViolationKind::Payload,
            uav,
            u.payload_kg - u.max_payload_kg,
            At::default(),
            || format!("carries {} kg; limit {} kg", u.payload_kg, u.max_payload_kg),
        );
    }
    j
}
