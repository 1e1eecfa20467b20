//! Time-varying communication: who is in contact at each time step, J_communication, and
//! the outage constraint.
//!
//! The paper's Eq. 6 (sum of 1/(d - d_max) over pairs beyond range) rewards drifting further
//! apart once a link is lost, so DESIGN.md replaces it: at every step (1 s) each UAV must be
//! connected to a ground node, directly or through other UAVs (`relay`), or have at least
//! one link (`neighbour`). A UAV out of contact at a step costs `outage_base_cost` plus its
//! gap: how far (metres) it is beyond the range of the nearest node that is in contact. The
//! cost is zero when connected and grows smoothly with the gap, so it points the search back
//! into range. A UAV out of contact longer than `max_outage_s` in a row violates the hard
//! constraint.

use glam::DVec3;

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPlan;
use crate::world::spec::CommRequirement;
use crate::world::World;

/// Reusable buffers of the connectivity sweep.
#[derive(Debug, Clone, Default)]
pub struct CommScratch {
    hints: Vec<usize>,
    pos: Vec<DVec3>,
    db: Vec<f64>,
    ground_db: Vec<f64>,
    reached: Vec<bool>,
    queue: Vec<usize>,
    run: Vec<usize>,
    run_start: Vec<(f64, DVec3)>,
}

/// Per-UAV results of the sweep.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct CommOutcome {
    /// J_communication share of the UAV (metres-equivalent).
    pub cost: f64,
    /// Seconds out of contact.
    pub outage_s: f64,
}

/// Sweeps the mission in communication time steps; writes one outcome per UAV into `out`.
pub fn communication(
    world: &World,
    plan: &TimedPlan,
    s: &mut CommScratch,
    sink: &mut ViolationSink,
    out: &mut [CommOutcome],
) {
    let n = plan.paths.len();
    out.iter_mut().for_each(|o| *o = CommOutcome::default());
    let spec = &world.spec.communication;
    if spec.requirement == CommRequirement::None || n == 0 {
        return;
    }
    let ch = &world.channel;
    let dt = ch.step();
    let steps = (plan.horizon / dt).ceil() as usize;
    s.hints.clear();
    s.hints.resize(n, 0);
    s.pos.resize(n, DVec3::ZERO);
    s.db.resize(n, 0.0);
    s.reached.resize(n, false);
    s.run.clear();
    s.run.resize(n, 0);
    s.run_start.resize(n, (0.0, DVec3::ZERO));
    let ground = &world.ground_nodes;
    s.ground_db.resize(ground.len(), 0.0);
    let has_interference = !ch.interference().is_empty();
    let max_run = (spec.max_outage_s / dt + 1e-9).floor() as usize;
    for k in 0..=steps {
        let t = k as f64 * dt;
        plan.sample(t, &mut s.hints, &mut s.pos);
        if has_interference {
            for (d, p) in s.db.iter_mut().zip(&s.pos) {
                *d = ch.interference_db(t, p.x, p.y);
            }
            for (d, g) in s.ground_db.iter_mut().zip(ground) {
                *d = ch.interference_db(t, g.position.x, g.position.y);
            }
        }
        let link = |a: DVec3, da: f64, b: DVec3, db: f64| {
            a.distance(b) <= ch.link_range(k, da, db) && ch.line_of_sight(&world.terrain, a, b)
        };
        s.reached.iter_mut().for_each(|r| *r = false);
        match spec.requirement {
            CommRequirement::Relay => {
                s.queue.clear();
                for (g, gdb) in ground.iter().zip(&s.ground_db) {
                    for u in 0..n {
                        if !s.reached[u] && link(g.position, *gdb, s.pos[u], s.db[u]) {
                            s.reached[u] = true;
                            s.queue.push(u);
                        }
                    }
                }
                let mut head = 0;
                while head < s.queue.len() && s.queue.len() < n {
                    let a = s.queue[head];
                    head += 1;
                    for u in 0..n {
                        if !s.reached[u] && link(s.pos[a], s.db[a], s.pos[u], s.db[u]) {
                            s.reached[u] = true;
                            s.queue.push(u);
                        }
                    }
                }
            }
            CommRequirement::Neighbour => {
                for u in 0..n {
                    let to_ground = ground
                        .iter()
                        .zip(&s.ground_db)
                        .any(|(g, gdb)| link(g.position, *gdb, s.pos[u], s.db[u]));
                    s.reached[u] = to_ground
                        || (0..n).any(|v| v != u && link(s.pos[u], s.db[u], s.pos[v], s.db[v]));
                }
            }
            CommRequirement::None => unreachable!("returned above"),
        }
        for u in 0..n {
            if s.reached[u] {
                close_run(world, u, dt, max_run, s, sink);
                continue;
            }
            // Gap to the nearest node in contact (ground nodes are always in contact).
            let mut gap = f64::INFINITY;
            for (g, gdb) in ground.iter().zip(&s.ground_db) {
                let r = ch.link_range(k, s.db[u], *gdb);
                gap = gap.min((s.pos[u].distance(g.position) - r).max(0.0));
            }
            for v in 0..n {
                if s.reached[v] {
                    let r = ch.link_range(k, s.db[u], s.db[v]);
                    gap = gap.min((s.pos[u].distance(s.pos[v]) - r).max(0.0));
                }
            }
            out[u].cost += spec.outage_base_cost + gap;
            out[u].outage_s += dt;
            if s.run[u] == 0 {
                s.run_start[u] = (t, s.pos[u]);
            }
            s.run[u] += 1;
        }
    }
    for u in 0..n {
        close_run(world, u, dt, max_run, s, sink);
    }
}

/// Ends UAV u's current outage run, reporting it if it was too long.
fn close_run(
    world: &World,
    u: usize,
    dt: f64,
    max_run: usize,
    s: &mut CommScratch,
    sink: &mut ViolationSink,
) {
    let run = s.run[u];
    s.run[u] = 0;
    if run > max_run {
        let (t0, p0) = s.run_start[u];
        let secs = run as f64 * dt;
        let tol = world.spec.communication.max_outage_s;
        sink.add(
            ViolationKind::Comm,
            u,
            secs - tol,
            At {
                position: Some(p0),
                time: Some(t0),
                ..At::default()
            },
            || format!("out of contact for {secs:.0} s from t = {t0:.0} s; tolerated {tol} s"),
        );
    }
}
