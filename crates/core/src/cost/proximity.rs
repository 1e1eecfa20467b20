//! UAV-UAV proximity at equal times: the paper's Eq. 8 made sound, and the separation
//! constraint.
//!
//! Eq. 8 as printed sums 1/(|p_ij - p_kl|^2 + eps) over all waypoint pairs of two UAVs,
//! whatever their times, so two UAVs that pass the same place a minute apart are "close".
//! We sum over UAV pairs at the same time instead (sampled every `timing.separation_step`
//! seconds, weighted by the step so the term is per second), plus the waypoint-to-threat
//! part measured to the cylinder surface. Separation: two UAVs closer than `timing.separation`
//! at the same time collide, except while either is inside the take-off or landing zone
//! (radius `timing.zone_radius` around a start or UGV0), which a shared start makes
//! necessary.

use glam::DVec3;

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::plan::Plan;
use crate::timing::TimedPlan;
use crate::world::World;

/// Reusable buffers of the proximity sweep.
#[derive(Debug, Clone, Default)]
pub struct ProximityScratch {
    hints: Vec<usize>,
    pos: Vec<DVec3>,
    in_zone: Vec<bool>,
    zones: Vec<(f64, f64)>,
    /// Per pair (i < j): (distance minimum, time, place) of the current close episode.
    episode: Vec<Option<(f64, f64, DVec3)>>,
}

/// Adds each UAV's share of Eq. 8 to `out` and reports separation violations.
pub fn proximity(
    world: &World,
    plan: &Plan,
    timed: &TimedPlan,
    s: &mut ProximityScratch,
    sink: &mut ViolationSink,
    out: &mut [f64],
) {
    let n = timed.paths.len();
    out.iter_mut().for_each(|o| *o = 0.0);
    let eps = world.spec.objective.obstacle_epsilon;
    // Waypoint-to-threat part.
    for (u, path) in plan.uavs.iter().enumerate() {
        let size = world.spec.uavs[u].size;
        for w in &path.waypoints {
            for t in &world.spec.threats {
                let (dx, dy) = (w.x - t.x, w.y - t.y);
                let d = ((dx * dx + dy * dy).sqrt() - t.r - size).max(0.0);
                out[u] += 1.0 / (d * d + eps);
            }
        }
    }
    if n < 2 {
        return;
    }
    let timing = &world.spec.timing;
    let dt = timing.separation_step;
    let steps = (timed.horizon / dt).ceil() as usize;
    s.hints.clear();
    s.hints.resize(n, 0);
    s.pos.resize(n, DVec3::ZERO);
    s.in_zone.resize(n, false);
    s.episode.clear();
    s.episode.resize(n * (n - 1) / 2, None);
    let zone2 = timing.zone_radius * timing.zone_radius;
    s.zones.clear();
    s.zones.push((world.goal.x, world.goal.y));
    for u in &world.spec.uavs {
        if !s.zones.contains(&(u.start[0], u.start[1])) {
            s.zones.push((u.start[0], u.start[1]));
        }
    }
    let sep = timing.separation;
    let sep2 = sep * sep;
    for k in 0..=steps {
        let t = k as f64 * dt;
        timed.sample(t, &mut s.hints, &mut s.pos);
        for (z, p) in s.in_zone.iter_mut().zip(&s.pos) {
            *z = s
                .zones
                .iter()
                .any(|c| (p.x - c.0) * (p.x - c.0) + (p.y - c.1) * (p.y - c.1) <= zone2);
        }
        let mut pair = 0;
        for i in 0..n {
            for j in i + 1..n {
                let idx = pair;
                pair += 1;
                let exempt = s.in_zone[i] || s.in_zone[j];
                let d2 = s.pos[i].distance_squared(s.pos[j]);
                if !exempt {
                    let share = 0.5 * dt / (d2 + eps);
                    out[i] += share;
                    out[j] += share;
                }
                if !exempt && d2 < sep2 {
                    let d = d2.sqrt();
                    let mid = s.pos[i].lerp(s.pos[j], 0.5);
                    let e = s.episode[idx].get_or_insert((d, t, mid));
                    if d < e.0 {
                        *e = (d, t, mid);
                    }
                } else if let Some(e) = s.episode[idx].take() {
                    report(sink, i, j, sep, e);
                }
            }
        }
    }
    let mut pair = 0;
    for i in 0..n {
        for j in i + 1..n {
            if let Some(e) = s.episode[pair].take() {
                report(sink, i, j, sep, e);
            }
            pair += 1;
        }
    }
}

fn report(sink: &mut ViolationSink, i: usize, j: usize, sep: f64, (d, t, p): (f64, f64, DVec3)) {
    sink.add(
        ViolationKind::Separation,
        i,
        sep - d,
        At {
            other: Some(j),
            position: Some(p),
            time: Some(t),
            ..At::default()
        },
        || format!("UAVs {i} and {j} come within {d:.1} m at t = {t:.1} s; separation {sep} m"),
    );
}
