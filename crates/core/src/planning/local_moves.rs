//! The planning problem's block-wise side ([`BlockProblem`]), which `coop` uses: each
//! UAV's share of the violation, and the local moves that repair what is left near
//! feasibility. A nudge moves one free waypoint (or a departure delay) where the UAV's
//! violations are; at a zone the fleet shares it is a *zone move* to a clear bearing
//! ([`zone_slot`]); a shifted copy flies another UAV's way beside it. Why each exists and
//! what it bought is measured in docs/results.md ("Nudges", "Aimed nudges", "Zone moves",
//! "Shifted copies").

use rand_distr::{Distribution, StandardNormal};

use super::{PlanningProblem, BUFFERS};
use crate::cost::{assess, assess_bounded, Cutoff};
use crate::feasibility::{ViolationKind, ViolationSink};
use crate::plan::Plan;
use crate::problem::{BlockProblem, Evaluation};
use crate::rng::Rng;
use crate::zone_slot;

/// Horizontal spread of a nudge ([`BlockProblem::nudge`]), in separation distances: enough to
/// turn two converging approaches apart at the edge of the landing zone.
pub const NUDGE_SEPARATIONS: f64 = 2.0;

/// A nudge of a departure delay: the standard deviation of its Gaussian move, as a share of
/// `timing.max_delay`.
pub const NUDGE_DELAY_SHARE: f64 = 0.25;

/// Share of the nudges of a UAV's first or last free waypoint that are zone moves
/// ([`zone_slot`]) when another UAV shares that start zone (or, always, UGV0's): 1, as
/// measured (docs/results.md, "Zone moves"); the rest are Gaussian nudges.
pub const ZONE_MOVE_SHARE: f64 = 1.0;

/// Horizontal offset of a shifted copy ([`BlockProblem::shifted_copy`]), in separation
/// distances, drawn uniformly from this range.
pub const SHIFT_SEPARATIONS: [f64; 2] = [1.5, 3.0];

impl BlockProblem for PlanningProblem<'_> {
    fn evaluate_blocks(&self, x: &[f64], by_block: &mut Vec<f64>) -> Evaluation {
        self.evaluate_blocks_bounded(x, by_block, f64::INFINITY)
            .unwrap_or_else(Evaluation::worst)
    }

    /// Gives up once the violation measure passes `cutoff` ([`crate::cost::assess_bounded`]).
    fn evaluate_blocks_bounded(
        &self,
        x: &[f64],
        by_block: &mut Vec<f64>,
        cutoff: f64,
    ) -> Option<Evaluation> {
        BUFFERS.with(|b| {
            let mut b = b.borrow_mut();
            let (plan, scratch) = &mut *b;
            self.encoding.decode_into(x, plan);
            let mut sink = ViolationSink::new(self.world.spec().planning.profile)
                .sharing(self.world.uav_count(), std::mem::take(by_block));
            let assessed = assess_bounded(
                self.world,
                plan,
                scratch,
                &mut sink,
                false,
                Cutoff::violation(cutoff),
            );
            *by_block = sink.by_uav.take().unwrap_or_default();
            assessed.map(|(cost, violation)| Evaluation::new(cost, violation))
        })
    }

    /// One UAV's path: 3 values per free waypoint, its pace value when the pace is free
    /// ([`crate::encoding::paced`]) and its departure delay when delays are free
    /// ([`crate::encoding::delayed`]).
    fn block_size(&self) -> usize {
        let timing = &self.world.spec().timing;
        3 * self.frame.n + usize::from(timing.pace_is_free()) + usize::from(timing.delay_is_free())
    }

    /// Free waypoint k of UAV `block` (`site` + 1, or uniform among them) moved by a
    /// Gaussian offset, [`NUDGE_SEPARATIONS`] separation distances wide horizontally and one
    /// vertically, clamped into the map box and the altitude band; the plan is then encoded
    /// again, so in a motion encoding only the moves into and out of that waypoint change.
    /// When departure delays are free, site n (after the n free waypoints) is the UAV's
    /// delay, moved by a Gaussian of [`NUDGE_DELAY_SHARE`] of `timing.max_delay`. A nudge
    /// of the first or last free waypoint of a UAV that shares that zone with another is a
    /// zone move instead (`zone_move`, in a share [`ZONE_MOVE_SHARE`] of them).
    fn nudge(
        &self,
        x: &[f64],
        block: usize,
        site: Option<usize>,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        let size = self.block_size();
        let f = &self.frame;
        if f.n == 0 || block >= self.world.uav_count() || out.len() != size {
            return false;
        }
        let mut plan = self.encoding.decode(x);
        let timing = &self.world.spec().timing;
        if site == Some(f.n) && timing.delay_is_free() && block < plan.delays.len() {
            let d: f64 = StandardNormal.sample(rng);
            let delay = &mut plan.delays[block];
            *delay =
                (*delay + NUDGE_DELAY_SHARE * timing.max_delay * d).clamp(0.0, timing.max_delay);
            self.write_block(&plan, block, out);
            return true;
        }
        let k = match site {
            Some(s) if s < f.n => s + 1,
            _ => rand::Rng::random_range(rng, 1..=f.n),
        };
        if (k == 1 || k == f.n)
            && rand::Rng::random::<f64>(rng) < ZONE_MOVE_SHARE
            && self.zone_move(&mut plan, block, k == 1, rng)
        {
            self.write_block(&plan, block, out);
            return true;
        }
        let sep = timing.separation.max(1.0);
        let mut normal = || -> f64 { StandardNormal.sample(rng) };
        let (dx, dy, dz) = (normal(), normal(), normal());
        let Some(w) = plan
            .uavs
            .get_mut(block)
            .and_then(|p| p.waypoints.get_mut(k))
        else {
            return false;
        };
        w.x = (w.x + NUDGE_SEPARATIONS * sep * dx).clamp(f.x[0], f.x[1]);
        w.y = (w.y + NUDGE_SEPARATIONS * sep * dy).clamp(f.y[0], f.y[1]);
        w.z = (w.z + sep * dz).clamp(f.z[0], f.z[1]);
        self.write_block(&plan, block, out);
        true
    }

    /// Per free waypoint of UAV `block`, the hard violations of the plan that it or a pair
    /// it belongs to holds next to that waypoint: each violation's measure (1 + amount /
    /// scale) goes to the two ends of the waypoint segment nearest its place (horizontally;
    /// a start or goal end gets nothing). A violation placed at a waypoint (a turn, a
    /// climb) is as near the segments on both sides of it, and goes to either, as the
    /// rounding of `nearest_segment` falls: mapping each UAV's own violations by their
    /// index instead was measured and lost (docs/results.md, "Aimed nudges"). Violations without a place (energy, speed) add
    /// nothing there. When departure delays are free one more site, the UAV's delay, takes
    /// the violations on its first leg (UAVs leaving the take-off zone together) and its
    /// energy violation while it waits (hovering spends energy). Assessed with a report, so
    /// the places come from the same checks as `swarmplan evaluate`'s.
    fn hot_spots(&self, x: &[f64], block: usize, out: &mut Vec<f64>) -> bool {
        out.clear();
        let n = self.frame.n;
        if n == 0 || block >= self.world.uav_count() {
            return false;
        }
        let plan = self.encoding.decode(x);
        let assessed = assess(self.world, &plan);
        let path = &plan.uavs[block].waypoints;
        let delayed = self.world.spec().timing.delay_is_free();
        out.resize(n + usize::from(delayed), 0.0);
        for v in assessed.violations.iter().flatten() {
            if !v.hard || (v.uav != block && v.other != Some(block)) {
                continue;
            }
            let weight = 1.0 + v.amount / v.kind.scale();
            // A UAV waiting at its start spends energy hovering, and a later (or earlier)
            // departure parts UAVs that leave the take-off zone together.
            if delayed
                && v.kind == ViolationKind::Energy
                && v.uav == block
                && plan.delay(block) > 0.0
            {
                out[n] += weight;
            }
            let Some([px, py, _]) = v.position else {
                continue;
            };
            let s = nearest_segment(path.iter().map(|w| (w.x, w.y)), (px, py));
            if delayed && s == 0 {
                out[n] += weight;
            }
            for k in [s, s + 1] {
                if (1..=n).contains(&k) {
                    out[k - 1] += weight;
                }
            }
        }
        true
    }

    fn shifted_copy(
        &self,
        x: &[f64],
        block: usize,
        donor: usize,
        rng: &mut Rng,
        out: &mut [f64],
    ) -> bool {
        let size = self.block_size();
        let f = &self.frame;
        let uavs = self.world.uav_count();
        if f.n == 0 || block >= uavs || donor >= uavs || out.len() != size {
            return false;
        }
        let mut plan = self.encoding.decode(x);
        let sep = self.world.spec().timing.separation.max(1.0);
        let angle = rand::Rng::random::<f64>(rng) * std::f64::consts::TAU;
        let reach = sep
            * (SHIFT_SEPARATIONS[0]
                + (SHIFT_SEPARATIONS[1] - SHIFT_SEPARATIONS[0]) * rand::Rng::random::<f64>(rng));
        let dz: f64 = StandardNormal.sample(rng);
        let (ox, oy, oz) = (reach * angle.cos(), reach * angle.sin(), sep * dz);
        let source: Vec<_> = plan.uavs[donor].waypoints[1..=f.n].to_vec();
        for (w, s) in plan.uavs[block].waypoints[1..=f.n].iter_mut().zip(source) {
            w.x = (s.x + ox).clamp(f.x[0], f.x[1]);
            w.y = (s.y + oy).clamp(f.y[0], f.y[1]);
            w.z = (s.z + oz).clamp(f.z[0], f.z[1]);
        }
        self.write_block(&plan, block, out);
        true
    }
}

impl PlanningProblem<'_> {
    /// A *zone move* ([`zone_slot`]): UAV `block`'s first (`at_start`) or last free
    /// waypoint placed between [`zone_slot::SLOT_DISTANCE`] zone radii from its start (or
    /// UGV0), at the bearing nearest its own that is clear of the other UAVs' there (its
    /// own if clear), at a height drawn uniformly in the altitude band. False (nothing
    /// changed) when no other UAV's start (or goal) is within the zone of its own.
    fn zone_move(&self, plan: &mut Plan, block: usize, at_start: bool, rng: &mut Rng) -> bool {
        let timing = &self.world.spec().timing;
        let f = &self.frame;
        let (n, zone) = (f.n, timing.zone_radius);
        if n == 0 || zone <= 0.0 {
            return false;
        }
        let k = if at_start { 1 } else { n };
        let centre_of = |u: usize| {
            if at_start {
                plan.uavs[u].waypoints[0]
            } else {
                self.world.goal_at(crate::world::DEPARTURE)
            }
        };
        let centre = centre_of(block);
        let others: Vec<f64> = (0..plan.uavs.len())
            .filter(|&u| u != block && centre_of(u).truncate().distance(centre.truncate()) <= zone)
            .map(|u| zone_slot::bearing(centre, plan.uavs[u].waypoints[k]))
            .collect();
        if others.is_empty() {
            return false;
        }
        let own = zone_slot::bearing(centre, plan.uavs[block].waypoints[k]);
        let gap = zone_slot::SLOT_MARGIN * zone_slot::min_angle(timing.separation, zone);
        let to = zone_slot::clear_bearing(own, &others, gap, rng).unwrap_or(own);
        let z = f.z[0] + (f.z[1] - f.z[0]) * rand::Rng::random::<f64>(rng);
        let [lo, hi] = zone_slot::SLOT_DISTANCE;
        let distance = zone * (lo + (hi - lo) * rand::Rng::random::<f64>(rng));
        let p = zone_slot::at_bearing(centre, to, distance, z);
        plan.uavs[block].waypoints[k] =
            glam::DVec3::new(p.x.clamp(f.x[0], f.x[1]), p.y.clamp(f.y[0], f.y[1]), z);
        true
    }
}

/// Index of the segment (k joins points k and k + 1) of the polyline through `points`
/// nearest `p` in the plane; 0 for fewer than two points. Distances are measured to the
/// projection of `p` clamped onto each segment, so a point at a shared waypoint is at 0
/// from the later segment and at a rounding error (or 0) from the earlier one.
fn nearest_segment(points: impl Iterator<Item = (f64, f64)>, p: (f64, f64)) -> usize {
    let mut best = (f64::INFINITY, 0);
    let mut prev: Option<(f64, f64)> = None;
    for (k, b) in points.enumerate() {
        if let Some(a) = prev {
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (qx, qy) = (a.0 + t * dx - p.0, a.1 + t * dy - p.1);
            let d2 = qx * qx + qy * qy;
            if d2 < best.0 {
                best = (d2, k - 1);
            }
        }
        prev = Some(b);
    }
    best.1
}
