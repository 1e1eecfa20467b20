//! UAV-UAV proximity at equal times: the paper's Eq. 8 made sound, and the separation
//! constraint, both in continuous time.
//!
//! Eq. 8 as printed sums 1/(|p_ij - p_kl|^2 + eps) over all waypoint pairs of two UAVs,
//! whatever their times, so two UAVs that pass the same place a minute apart are "close".
//! We integrate over the mission instead: for each UAV pair, the integral over time of
//! 1/(d(t)^2 + eps) (so the term is "per second"), plus the waypoint-to-threat part measured
//! to the cylinder surface. Separation: two UAVs closer than `timing.separation` at the same
//! time collide, except while either is inside the take-off or landing zone (radius
//! `timing.zone_radius` around its start or UGV0), which a shared start makes necessary.
//!
//! Both UAVs move linearly between the merged times of their waypoints, so on each such
//! interval the relative position is r0 + w tau: the closest approach is exact, and so is
//! the integral on every interval (`interval_batch.rs`; until issue 47 intervals beyond
//! 50 m took Simpson's rule, up to 12 % high). A UAV is exempt from
//! take-off until it first leaves the start zone and from landing once it last enters the
//! goal zone; a path that comes back into the start zone later is checked there (stricter).
//! A UAV with a departure delay hovers at its start until it leaves (a leading segment of
//! zero velocity), inside its start zone.

use glam::DVec3;

use super::interval_batch::IntervalBatch;
use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::plan::Plan;
use crate::points_key::{same_points, PointsKey};
use crate::timing::{TimedPath, TimedPlan};
use crate::world::spec::TimingPolicy;
use crate::world::threat::Threat;
use crate::world::World;

/// Reusable buffers of the proximity sweep, and its memo of pair results.
#[derive(Debug, Clone, Default)]
pub struct ProximityScratch {
    /// Per UAV of this evaluation: its motion in the time unit (see [`TimeUnit`]).
    motion: Vec<Motion>,
    /// The motions of the previous evaluation, which `pairs` belong to.
    previous: Vec<Motion>,
    /// The settings the memo was made under (epsilon, separation, zone radius, goal).
    settings: Option<[u64; 6]>,
    /// Per UAV: whether its motion differs from the previous evaluation's.
    changed: Vec<bool>,
    /// Per pair (i < j, row by row): its integral in the time unit and its separation
    /// episodes, from the last evaluation in which it was computed.
    pairs: Vec<PairResult>,
    /// Pairs swept (not taken from the memo) by the last evaluation.
    swept: usize,
    /// Per UAV: its waypoint-to-threat share and the waypoints, size, epsilon and threats
    /// it was computed from (a pure function of them, so kept while they are the same).
    threat_shares: Vec<ThreatShare>,
    /// The intervals of the pair being swept.
    batch: IntervalBatch,
}

/// One UAV's waypoint-to-threat part of Eq. 8 and what it was computed from.
#[derive(Debug, Clone, Default)]
struct ThreatShare {
    waypoints: PointsKey,
    /// UAV size and epsilon, as bits.
    settings: [u64; 2],
    /// The threats' (x, y, r), as bits.
    threats: Vec<[u64; 3]>,
    share: f64,
}

impl ThreatShare {
    /// The share of a UAV of `size` at `waypoints`, recomputed only if something it
    /// depends on differs bit for bit from the last call.
    fn of(&mut self, waypoints: &[DVec3], size: f64, eps: f64, threats: &[Threat]) -> f64 {
        let settings = [size.to_bits(), eps.to_bits()];
        let same = self.settings == settings
            && self.waypoints.matches(waypoints)
            && self.threats.len() == threats.len()
            && self
                .threats
                .iter()
                .zip(threats)
                .all(|(a, t)| *a == [t.x.to_bits(), t.y.to_bits(), t.r.to_bits()]);
        if !same {
            self.settings = settings;
            self.waypoints.set(waypoints);
            self.threats.clear();
            self.threats.extend(
                threats
                    .iter()
                    .map(|t| [t.x.to_bits(), t.y.to_bits(), t.r.to_bits()]),
            );
            self.share = 0.0;
            for w in waypoints {
                for t in threats {
                    let (dx, dy) = (w.x - t.x, w.y - t.y);
                    let d = ((dx * dx + dy * dy).sqrt() - t.r - size).max(0.0);
                    self.share += 1.0 / (d * d + eps);
                }
            }
        }
        self.share
    }
}

impl ProximityScratch {
    /// Pairs the last evaluation swept rather than took from the memo.
    #[must_use]
    pub fn pairs_swept(&self) -> usize {
        self.swept
    }
}

/// One pair's share of the sweep, in the time unit: the Eq. 8 integral and the closest
/// approaches of its separation episodes (distance, time, place), in the order found.
#[derive(Debug, Clone, Default)]
struct PairResult {
    integral: f64,
    episodes: Vec<(f64, f64, DVec3)>,
}

/// The time in which the pair sweep works. Under *common arrival* every UAV's waypoint
/// times are T times its arc-length fractions, so the sweep runs on the fractions (unit T)
/// and a change to one UAV's path, which moves T, leaves every other pair's result valid
/// after the rescaling; under *cruise* the unit is one second.
#[derive(Debug, Clone, Copy)]
struct TimeUnit {
    /// Seconds per unit.
    seconds: f64,
    common_arrival: bool,
}

impl TimeUnit {
    fn of(world: &World, timed: &TimedPlan) -> Self {
        // With slots the windows differ by fixed seconds, so the fractions of T no longer
        // scale alike: the sweep runs in seconds, and a change of T changes every motion.
        let common_arrival =
            world.spec().timing.policy == TimingPolicy::CommonArrival && !world.slots().any();
        let seconds = if common_arrival {
            timed.paths.first().map_or(0.0, |p| p.arrival)
        } else {
            1.0
        };
        Self {
            seconds,
            common_arrival,
        }
    }

    /// Metres per unit of `p`'s flight: its length over the share of T it flies under
    /// common arrival, else its speed; 0 for a UAV that does not move.
    fn speed(self, p: &TimedPath) -> f64 {
        if p.speed <= 0.0 || self.seconds.is_nan() || self.seconds <= 0.0 {
            0.0
        } else if self.common_arrival {
            if p.delay > 0.0 {
                p.length / (1.0 - p.delay)
            } else {
                p.length
            }
        } else {
            p.speed
        }
    }

    /// When `p` departs, in units: its delay share under common arrival (the share of T
    /// it waits), else its departure in seconds.
    fn depart(self, p: &TimedPath) -> f64 {
        if self.common_arrival {
            p.delay
        } else {
            p.depart
        }
    }
}

/// One UAV's piecewise-linear motion in the time unit: its vertices, when it reaches
/// each, the end and velocity of each segment, and the stretch between leaving the start
/// zone and entering the goal zone (computed once per evaluation, then used by every pair
/// the UAV is in).
#[derive(Debug, Clone, Default)]
struct Motion {
    abs: Vec<DVec3>,
    times: Vec<f64>,
    /// Per segment, then one more for "arrived" (an infinite end and zero velocity).
    ends: Vec<f64>,
    velocities: Vec<DVec3>,
    /// (time it leaves the start zone, time it enters the goal zone).
    window: (f64, f64),
}

impl Motion {
    /// `depart` (in units, 0 for none) makes the UAV hover at its start until then: a
    /// leading segment of zero velocity.
    fn fill(&mut self, p: &TimedPath, unit_speed: f64, depart: f64, goal: DVec3, zone: f64) {
        self.abs.clear();
        self.times.clear();
        let waits = depart > 0.0 && unit_speed > 0.0;
        if waits {
            self.abs.push(p.abs[0]);
            self.times.push(0.0);
        }
        self.abs.extend_from_slice(&p.abs);
        self.times.extend(p.cum.iter().map(|&c| {
            if unit_speed <= 0.0 {
                0.0
            } else if waits {
                depart + c / unit_speed
            } else {
                c / unit_speed
            }
        }));
        self.ends.clear();
        self.velocities.clear();
        for k in 0..self.abs.len().saturating_sub(1) {
            let (end, v) = if unit_speed <= 0.0 {
                (f64::INFINITY, DVec3::ZERO)
            } else {
                let (t0, t1) = (self.times[k], self.times[k + 1]);
                if t1 <= t0 {
                    (t1, DVec3::ZERO)
                } else {
                    (t1, (self.abs[k + 1] - self.abs[k]) / (t1 - t0))
                }
            };
            self.ends.push(end);
            self.velocities.push(v);
        }
        // Past the last segment: arrived, for good.
        self.ends.push(f64::INFINITY);
        self.velocities.push(DVec3::ZERO);
        let start = self.abs[0];
        self.window = (
            self.leave_time(start.x, start.y, zone),
            self.enter_time(goal.x, goal.y, zone),
        );
    }

    /// Bit for bit the same motion (so every pair result it is in stands).
    fn same_as(&self, other: &Self) -> bool {
        same_points(&self.abs, &other.abs)
            && self
                .times
                .iter()
                .zip(&other.times)
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }

    /// Index of the segment flown at time t (segments past the last mean "arrived").
    fn segment_at(&self, t: f64) -> usize {
        self.times[1..].partition_point(|&tk| tk <= t)
    }

    /// Position at time t on segment k with velocity v.
    fn position(&self, k: usize, v: DVec3, t: f64) -> DVec3 {
        let last = self.abs.len() - 1;
        if k >= last {
            self.abs[last]
        } else {
            self.abs[k] + v * (t - self.times[k])
        }
    }

    /// First time the UAV is farther than `r` (horizontally) from (cx, cy); infinite if
    /// never.
    fn leave_time(&self, cx: f64, cy: f64, r: f64) -> f64 {
        for k in 0..self.abs.len().saturating_sub(1) {
            let (a, b) = (self.abs[k], self.abs[k + 1]);
            if let Some(f) = first_crossing(a, b, cx, cy, r) {
                return self.times[k] + f * (self.times[k + 1] - self.times[k]);
            }
        }
        f64::INFINITY
    }

    /// Last time the UAV comes within `r` (horizontally) of (cx, cy) for good; 0 if always
    /// inside.
    fn enter_time(&self, cx: f64, cy: f64, r: f64) -> f64 {
        for k in (0..self.abs.len().saturating_sub(1)).rev() {
            let (a, b) = (self.abs[k + 1], self.abs[k]);
            if let Some(f) = first_crossing(a, b, cx, cy, r) {
                // Walking backwards from waypoint k + 1: fraction f of the way back to k.
                return self.times[k + 1] - f * (self.times[k + 1] - self.times[k]);
            }
        }
        0.0
    }
}

/// Adds each UAV's share of Eq. 8 to `out` and reports separation violations.
///
/// Pairs of UAVs whose motions (in the time unit) are bit for bit those of the previous
/// call on the same scratch take their result from it, so an evaluation that changes one
/// UAV of n sweeps n - 1 pairs instead of n (n - 1) / 2; the result is the same bit for bit
/// as a sweep of every pair (the memo is a pure function of the motions and the settings).
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
    let eps = world.spec().objective.obstacle_epsilon;
    // Waypoint-to-threat part (summed from 0 in the same order as a fresh sweep would).
    s.threat_shares
        .resize_with(plan.uavs.len(), ThreatShare::default);
    for (u, path) in plan.uavs.iter().enumerate() {
        let size = world.spec().uavs[u].size;
        out[u] = s.threat_shares[u].of(&path.waypoints, size, eps, &world.spec().threats);
    }
    if n < 2 {
        return;
    }
    let timing = &world.spec().timing;
    let (zone, sep, goal) = (
        timing.zone_radius,
        timing.separation,
        world.goal_at(crate::world::DEPARTURE),
    );
    let unit = TimeUnit::of(world, timed);
    s.motion.resize_with(n, Motion::default);
    for (m, tp) in s.motion.iter_mut().zip(&timed.paths) {
        m.fill(tp, unit.speed(tp), unit.depart(tp), goal, zone);
    }
    let settings = [eps, sep, zone, goal.x, goal.y, goal.z].map(f64::to_bits);
    let memo_valid = s.settings == Some(settings) && s.previous.len() == n;
    s.changed.clear();
    s.changed
        .extend((0..n).map(|u| !memo_valid || !s.motion[u].same_as(&s.previous[u])));
    s.pairs.resize_with(n * (n - 1) / 2, PairResult::default);
    let mut index = 0;
    s.swept = 0;
    for i in 0..n {
        for j in i + 1..n {
            let pair = &mut s.pairs[index];
            index += 1;
            if s.changed[i] || s.changed[j] {
                sweep_pair(&s.motion[i], &s.motion[j], (eps, sep), &mut s.batch, pair);
                s.swept += 1;
            }
            for &(d, t, at) in &pair.episodes {
                report(sink, i, j, sep, (d, t * unit.seconds, at));
            }
            let integral = pair.integral * unit.seconds;
            out[i] += 0.5 * integral;
            out[j] += 0.5 * integral;
        }
    }
    s.settings = Some(settings);
    std::mem::swap(&mut s.motion, &mut s.previous);
}

/// The Eq. 8 integral and the separation episodes of UAVs `a` and `b` over the stretch
/// where neither is exempt, in the time unit, into `out`.
///
/// Three passes over the pair's intervals: the merge of the two motions writes each
/// interval's relative position and velocity into `batch`; one loop without branches
/// computes every interval's closest approach and integral (`interval_batch.rs`); a scan
/// finds the separation episodes among the closest approaches, and the integrals are added
/// in order.
fn sweep_pair(
    a: &Motion,
    b: &Motion,
    (eps, sep): (f64, f64),
    batch: &mut IntervalBatch,
    out: &mut PairResult,
) {
    out.integral = 0.0;
    out.episodes.clear();
    let t_from = a.window.0.max(b.window.0);
    let t_to = a.window.1.min(b.window.1);
    if t_to <= t_from {
        return;
    }
    // Each interval but the last ends a segment of a or b (the last index of each is
    // "arrived" and never ends), so there are at most as many as both have indices.
    batch.fill(a.ends.len() + b.ends.len(), |filler| {
        for_each_interval(a, b, t_from, t_to, |t0, dt, segments, r0, w| {
            filler.push(t0, dt, segments, r0, w);
        });
    });
    batch.compute(eps);
    let mut episode: Option<(f64, f64, DVec3)> = None;
    for i in 0..batch.len() {
        let (dmin2, tau) = batch.closest(i);
        if dmin2 < sep * sep {
            let (t0, (ka, kb)) = batch.start(i);
            let (va, vb) = (a.velocities[ka], b.velocities[kb]);
            let (pa, pb) = (a.position(ka, va, t0), b.position(kb, vb, t0));
            let d = dmin2.max(0.0).sqrt();
            let at = pa.lerp(pb, 0.5) + (va + vb) * (0.5 * tau);
            let e = episode.get_or_insert((d, t0 + tau, at));
            if d < e.0 {
                *e = (d, t0 + tau, at);
            }
        } else if let Some(e) = episode.take() {
            out.episodes.push(e);
        }
    }
    if let Some(e) = episode {
        out.episodes.push(e);
    }
    out.integral = batch.sum();
}

/// Calls `f(t0, dt, (ka, kb), r0, w)` for each interval of [from, to] on which both UAVs
/// move linearly: its start, length, the two segments flown (the last index of each means
/// "arrived"), and the relative position at t0 and relative velocity (a's less b's).
fn for_each_interval(
    ma: &Motion,
    mb: &Motion,
    from: f64,
    to: f64,
    mut f: impl FnMut(f64, f64, (usize, usize), DVec3, DVec3),
) {
    let (mut ka, mut kb) = (ma.segment_at(from), mb.segment_at(from));
    let mut t = from;
    while t < to {
        let (ea, va) = (ma.ends[ka], ma.velocities[ka]);
        let (eb, vb) = (mb.ends[kb], mb.velocities[kb]);
        // Comparisons, not `f64::min`: one instruction each instead of a NaN check (times
        // are never NaN here: a NaN `to` ends the loop before it starts).
        let t1 = if ea < eb { ea } else { eb };
        let t1 = if t1 < to { t1 } else { to };
        if t1 > t {
            let pa = ma.position(ka, va, t);
            let pb = mb.position(kb, vb, t);
            f(t, t1 - t, (ka, kb), pa - pb, va - vb);
        }
        ka += usize::from(ea <= t1);
        kb += usize::from(eb <= t1);
        if t1 <= t && ea > t1 && eb > t1 {
            break;
        }
        t = if t1 > t { t1 } else { t };
        if t >= to {
            break;
        }
    }
}

/// Fraction along a-b where the horizontal distance to (cx, cy) first exceeds r, if it does.
fn first_crossing(a: DVec3, b: DVec3, cx: f64, cy: f64, r: f64) -> Option<f64> {
    let (px, py) = (a.x - cx, a.y - cy);
    if px * px + py * py > r * r {
        return Some(0.0);
    }
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let qa = dx * dx + dy * dy;
    if qa == 0.0 {
        return None;
    }
    let qb = 2.0 * (px * dx + py * dy);
    let qc = px * px + py * py - r * r;
    let disc = qb * qb - 4.0 * qa * qc;
    // Inside at a (qc <= 0): the larger root is where the segment leaves the disk.
    let f = (-qb + disc.max(0.0).sqrt()) / (2.0 * qa);
    (f <= 1.0).then_some(f.max(0.0))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The slow reference: adaptive Simpson quadrature of 1 / (|r0 + w tau|^2 + eps) on
    /// [0, dt] to a relative tolerance far below the checks'.
    fn reference(r0: DVec3, w: DVec3, eps: f64, dt: f64) -> f64 {
        let f = |tau: f64| 1.0 / ((r0 + w * tau).length_squared() + eps);
        crate::quadrature::adaptive_simpson(&f, (0.0, dt), 1e-12, 50)
    }

    /// One interval's integral as the sweep computes it, with its coefficients computed here.
    fn integral(r0: DVec3, w: DVec3, eps: f64, dt: f64) -> f64 {
        let q = (
            w.length_squared(),
            2.0 * r0.dot(w),
            r0.length_squared() + eps,
        );
        super::super::interval_batch::interval_integral(
            q.0,
            q.1,
            q.2,
            w.cross(r0).length_squared(),
            dt,
            eps,
        )
    }

    #[test]
    fn closed_form_integral_matches_the_slow_reference_within_1e_9() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(47);
        let v = |rng: &mut rand_chacha::ChaCha8Rng, s: f64| {
            DVec3::new(
                rng.random_range(-s..s),
                rng.random_range(-s..s),
                rng.random_range(-s..s),
            )
        };
        for k in 0..600 {
            // Near and far pairs, slow and fast, short and long intervals.
            let scale = [5.0, 50.0, 500.0][k % 3];
            let r0 = v(&mut rng, scale);
            let w = v(&mut rng, [0.5, 20.0, 40.0][(k / 3) % 3]);
            let eps = [1.0, 0.01, 25.0][(k / 9) % 3];
            let dt = rng.random_range(0.01..30.0);
            let got = integral(r0, w, eps, dt);
            let want = reference(r0, w, eps, dt);
            assert!(
                (got - want).abs() <= 1e-9 * want,
                "r0 {r0} w {w} eps {eps} dt {dt}: {got} against {want}"
            );
        }
        // Crossing the closest approach mid-interval (2c + b dt < 0), and at rest.
        for (r0, w) in [
            (DVec3::new(-100.0, 0.5, 0.0), DVec3::new(10.0, 0.0, 0.0)),
            (DVec3::new(3.0, 4.0, 0.0), DVec3::ZERO),
        ] {
            let (got, want) = (integral(r0, w, 1.0, 20.0), reference(r0, w, 1.0, 20.0));
            assert!((got - want).abs() <= 1e-9 * want, "{got} {want}");
        }
    }

    #[test]
    fn a_far_interval_is_exact_where_simpson_was_twelve_percent_high() {
        // Issue 47's example: dt = 7 s, relative speed 20 m/s, closest approach 55 m at
        // mid-interval, eps = 1: exact 1.645e-3; three-point Simpson gave 1.837e-3.
        let (r0, w) = (DVec3::new(-70.0, 55.0, 0.0), DVec3::new(20.0, 0.0, 0.0));
        let got = integral(r0, w, 1.0, 7.0);
        assert!((got - 1.645e-3).abs() < 5e-7, "{got}");
        let g = |t: f64| 1.0 / ((r0 + w * t).length_squared() + 1.0);
        let simpson = 7.0 / 6.0 * (g(0.0) + 4.0 * g(3.5) + g(7.0));
        assert!((simpson - 1.837e-3).abs() < 5e-7, "{simpson}");
    }
}
