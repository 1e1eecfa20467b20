//! Time-varying communication: who is in contact at each time step, J_communication, and
//! the outage constraint.
//!
//! The paper's Eq. 6 (sum of 1/(d - d_max) over pairs beyond range) rewards drifting further
//! apart once a link is lost, so docs/model.md ("Communication") replaces it: at every step (1 s) each UAV must be
//! connected to a ground node, directly or through other UAVs (`relay`), or have at least
//! one link (`neighbour`). A UAV out of contact at a step costs `outage_base_cost` plus its
//! gap: how far (metres) it is beyond the range of the nearest node that is in contact. The
//! cost is zero when connected and grows smoothly with the gap, so it points the search back
//! into range. A UAV out of contact longer than `max_outage_s` in a row violates the hard
//! constraint.

use glam::DVec3;

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPlan;
use crate::world::channel::CHANNEL_HORIZON_S;
use crate::world::spec::CommRequirement;
use crate::world::World;

/// The sweep covers at most this much of a mission (ten times the channel's tabulated
/// horizon): a plan built in code whose flight lasts longer (an altitude of 1e50 m once made
/// it 1e48 s) gets a communication violation for the rest instead of a sweep that never ends.
/// Plan files and imports are refused earlier ([`CHANNEL_HORIZON_S`], docs/reliability.md).
pub const MAX_SWEPT_S: f64 = 10.0 * CHANNEL_HORIZON_S;

/// Reusable buffers of the connectivity sweep.
#[derive(Debug, Clone, Default)]
pub struct CommScratch {
    hints: Vec<usize>,
    pos: Vec<DVec3>,
    /// Interference range factors (1 = no interference) of UAVs and ground nodes.
    db: Vec<f64>,
    ground_db: Vec<f64>,
    reach: Reach,
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
    let spec = &world.spec().communication;
    if spec.requirement == CommRequirement::None || n == 0 {
        return;
    }
    let ch = world.channel();
    let dt = ch.step();
    // Not `f64::min`: a NaN horizon (a plan of NaN waypoints) keeps sweeping no step.
    let swept = if plan.horizon > MAX_SWEPT_S {
        for (u, p) in plan.paths.iter().enumerate() {
            if p.arrival > MAX_SWEPT_S {
                sink.add(
                    ViolationKind::Comm,
                    u,
                    p.arrival - MAX_SWEPT_S,
                    At::default(),
                    || {
                        format!(
                            "the flight lasts {:.3e} s: communication is assessed over the first {MAX_SWEPT_S} s only",
                            p.arrival
                        )
                    },
                );
            }
        }
        MAX_SWEPT_S
    } else {
        plan.horizon
    };
    let steps = (swept / dt).ceil() as usize;
    s.hints.clear();
    s.hints.resize(n, 0);
    s.pos.resize(n, DVec3::ZERO);
    s.db.clear();
    s.db.resize(n, 1.0);
    s.run.clear();
    s.run.resize(n, 0);
    s.run_start.resize(n, (0.0, DVec3::ZERO));
    // Only the count is read here, the same at every time.
    let ground = world.ground_nodes_at(crate::world::DEPARTURE);
    s.ground_db.clear();
    s.ground_db.resize(ground.len(), 1.0);
    let has_interference = !ch.interference().is_empty();
    let max_run = (spec.max_outage_s / dt + 1e-9).floor() as usize;
    for k in 0..=steps {
        let t = k as f64 * dt;
        plan.sample(t, &mut s.hints, &mut s.pos);
        if has_interference {
            for (d, p) in s.db.iter_mut().zip(&s.pos) {
                *d = ch.interference_factor(t, p.x, p.y);
            }
            for (d, g) in s.ground_db.iter_mut().zip(ground) {
                *d = ch.interference_factor(t, g.position.x, g.position.y);
            }
        }
        connect(world, k, &s.pos, &s.db, &s.ground_db, &mut s.reach);
        for u in 0..n {
            if s.reach.reached[u] {
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
                if s.reach.reached[v] {
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

/// How a UAV stands at one instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    /// Linked to a ground node directly.
    Direct,
    /// Connected through other UAVs (relay mode) or to a neighbour UAV (neighbour mode).
    Relayed,
    /// Neither.
    Out,
}

/// Who a step's contact search reached, with its buffers (reused so that the hot sweep
/// does not allocate).
#[derive(Debug, Clone, Default)]
pub struct Reach {
    /// Per UAV: in contact.
    pub reached: Vec<bool>,
    /// The UAVs in contact in the order found, ground links first.
    pub queue: Vec<usize>,
    /// UAVs not yet reached (scratch of the relay search).
    pending: Vec<usize>,
    /// Per UAV: the UAV that relayed it when last relayed (`usize::MAX`: none yet), tried
    /// first at the next step (an order only: the set reached is the same).
    relayed_by: Vec<usize>,
    /// Per ground node and UAV: the node's and the UAV's last positions asked and whether
    /// the node's horizon showed the UAV, in the world [`Self::world`] names (thread-local
    /// buffers serve every problem evaluated on their thread).
    seen: Vec<(DVec3, DVec3, bool)>,
    /// [`World::id`] of the world `seen` belongs to.
    world: Option<u64>,
}

/// Who is in contact at communication step `k` with UAVs at `pos` (absolute altitudes), into
/// `reach`; returns how many of them link to a ground node directly (the first of its queue).
/// `db` and `ground_db` are the interference range factors of each UAV and ground node.
pub fn connect(
    world: &World,
    k: usize,
    pos: &[DVec3],
    db: &[f64],
    ground_db: &[f64],
    reach: &mut Reach,
) -> usize {
    let ch = world.channel();
    #[allow(clippy::cast_precision_loss)]
    let ground = world.ground_nodes_at(k as f64 * ch.step());
    let n = pos.len();
    let link = |a: DVec3, da: f64, b: DVec3, dbb: f64| {
        within(a, b, ch.link_range(k, da, dbb)) && ch.line_of_sight(world.terrain(), a, b)
    };
    let Reach {
        reached,
        queue,
        pending,
        relayed_by,
        seen,
        world: seen_in,
    } = reach;
    if *seen_in != Some(world.id()) {
        *seen_in = Some(world.id());
        seen.clear();
    }
    reached.clear();
    reached.resize(n, false);
    queue.clear();
    // A UAV waiting on its launcher or landed stays put for many steps (most of a slotted
    // hundred-UAV mission): its horizon answer is kept per ground node and asked again only
    // when it or the node has moved, the same answer as asking each step.
    seen.resize(ground.len() * n, (DVec3::NAN, DVec3::NAN, false));
    // Per UAV, the ground nodes in turn until one reaches it (the set reached is the same
    // in any order; this one has no branch on who is already reached).
    for u in 0..n {
        for (gi, (g, gdb)) in ground.iter().zip(ground_db).enumerate() {
            let up = within(g.position, pos[u], ch.link_range(k, *gdb, db[u]))
                && g.horizon.as_ref().is_none_or(|h| {
                    let memo = &mut seen[gi * n + u];
                    if memo.0 != g.position || memo.1 != pos[u] {
                        *memo = (g.position, pos[u], h.visible(pos[u]));
                    }
                    memo.2
                });
            if up {
                reached[u] = true;
                queue.push(u);
                break;
            }
        }
    }
    let direct = queue.len();
    match world.spec().communication.requirement {
        CommRequirement::Relay => {
            // The set reached is the closure of the direct links under the links from a UAV
            // in contact to one not yet, whatever order they are tried in. So a UAV first
            // tries the one that relayed it at the last step asked, nearly always the same in
            // a fleet that flies in a chain, and the breadth-first search after it, over the
            // UAVs still unreached only, ends as soon as nobody is left.
            relayed_by.resize(n, usize::MAX);
            pending.clear();
            for u in 0..n {
                if reached[u] {
                    continue;
                }
                let by = relayed_by[u];
                if by < n && reached[by] && link(pos[by], db[by], pos[u], db[u]) {
                    reached[u] = true;
                    queue.push(u);
                } else {
                    pending.push(u);
                }
            }
            let mut head = 0;
            while head < queue.len() && !pending.is_empty() {
                let a = queue[head];
                head += 1;
                pending.retain(|&u| {
                    let up = link(pos[a], db[a], pos[u], db[u]);
                    if up {
                        reached[u] = true;
                        relayed_by[u] = a;
                        queue.push(u);
                    }
                    !up
                });
            }
        }
        CommRequirement::Neighbour => {
            for u in 0..n {
                if !reached[u] && (0..n).any(|v| v != u && link(pos[u], db[u], pos[v], db[v])) {
                    reached[u] = true;
                    queue.push(u);
                }
            }
        }
        CommRequirement::None => {}
    }
    direct
}

/// Whether `a` and `b` are at most `r` apart: `a.distance(b) <= r` bit for bit, with the
/// square root taken only where the squared distance lies within a relative 1e-12 of r^2
/// (issue 47; the bounds' own rounding is four orders of magnitude smaller).
#[inline]
fn within(a: DVec3, b: DVec3, r: f64) -> bool {
    let d2 = a.distance_squared(b);
    // Below 1e150 the squares cannot overflow.
    if (0.0..1e150).contains(&r) {
        let (inner, outer) = (r * (1.0 - 1e-12), r * (1.0 + 1e-12));
        if d2 <= inner * inner {
            return true;
        }
        if d2 > outer * outer {
            return false;
        }
    }
    d2.sqrt() <= r
}

/// Each UAV's contact status at time `t` for UAVs at `pos` (allocating; for reports,
/// figures and tests).
#[must_use]
pub fn contact_at(world: &World, t: f64, pos: &[DVec3]) -> Vec<Contact> {
    let ch = world.channel();
    let k = (t / ch.step()).round() as usize;
    let db: Vec<f64> = pos
        .iter()
        .map(|p| ch.interference_factor(t, p.x, p.y))
        .collect();
    let gdb: Vec<f64> = world
        .ground_nodes_at(t)
        .iter()
        .map(|g| ch.interference_factor(t, g.position.x, g.position.y))
        .collect();
    let mut reach = Reach::default();
    let direct = connect(world, k, pos, &db, &gdb, &mut reach);
    let mut out = vec![Contact::Out; pos.len()];
    for (i, u) in reach.queue.iter().enumerate() {
        out[*u] = if i < direct {
            Contact::Direct
        } else {
            Contact::Relayed
        };
    }
    out
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
        let tol = world.spec().communication.max_outage_s;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::band_route::tests::terrain;
    use crate::world::test_spec::one_uav_spec;

    /// The station at (100, 500) on the ground, a UAV's place 300 m east of it in range
    /// (350 m, no shadowing), UGV0 out of range; over `ground`.
    fn world(ground: impl Fn(f64) -> f64) -> World {
        let mut spec = one_uav_spec("reach", Vec::new(), [900.0, 500.0, 150.0]);
        spec.uavs[0].start = [100.0, 500.0, 150.0];
        spec.communication.range = 350.0;
        spec.communication.shadowing_sigma_db = 0.0;
        World::new(spec, terrain(ground)).unwrap()
    }

    #[test]
    fn within_answers_as_the_distance_does() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(47);
        let mut near = 0;
        for k in 0..100_000 {
            let s = [1.0, 700.0, 1e5][k % 3];
            let v = |rng: &mut rand_chacha::ChaCha8Rng| {
                DVec3::new(
                    rng.random_range(-s..s),
                    rng.random_range(-s..s),
                    rng.random_range(-s..s),
                )
            };
            let (a, b) = (v(&mut rng), v(&mut rng));
            let d = a.distance(b);
            // Ranges at the distance to the last bit, around it, and anywhere.
            let mut ranges = vec![d, d.next_up(), d.next_down(), d * (1.0 + 1e-13)];
            ranges.extend([d * (1.0 - 1e-13), rng.random_range(0.0..2.0 * s)]);
            for r in ranges {
                near += usize::from((d - r).abs() <= 1e-12 * r);
                assert_eq!(within(a, b, r), d <= r, "{a} {b} {r}");
            }
        }
        assert!(near > 100_000);
        for r in [f64::NAN, f64::INFINITY, -1.0, 0.0, 1e200] {
            let (a, b) = (DVec3::ZERO, DVec3::new(3.0, 4.0, 0.0));
            assert_eq!(within(a, b, r), a.distance(b) <= r, "{r}");
        }
    }

    #[test]
    fn buffers_shared_by_two_worlds_keep_each_worlds_line_of_sight() {
        // The same station and the same place in both worlds; in the second a ridge 600 m
        // high between them hides the place. Buffers reused from the first world must not
        // lend it the first world's view.
        let open = world(|_| 0.0);
        let ridge = world(|x| {
            if (240.0..=260.0).contains(&x) {
                600.0
            } else {
                0.0
            }
        });
        let place = [DVec3::new(400.0, 500.0, 150.0)];
        let mut shared = Reach::default();
        let contact = |w: &World, reach: &mut Reach| {
            connect(w, 0, &place, &[1.0], &[1.0, 1.0], reach);
            reach.reached[0]
        };
        assert!(contact(&open, &mut shared));
        assert!(!contact(&ridge, &mut Reach::default()));
        assert!(!contact(&ridge, &mut shared));
        assert!(contact(&open, &mut shared));
    }
}
