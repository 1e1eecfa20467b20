//! When each UAV is where. The paper needs time (Eq. 4 speeds, Eq. 6 time steps) but never
//! defines it; the timing policies of docs/model.md ("Time") do:
//! - *common arrival* (default): all UAVs leave at t = 0 and arrive together at T, each at
//!   constant speed v_i = L_i / T. T minimises sum_i (v_i - cruise_i)^2 in closed form
//!   (1/T = sum L_i c_i / sum L_i^2) and is then clamped into the interval where every v_i
//!   lies in [v_min, v_max]; when that interval is empty the speeds break their limits and the
//!   safety term and the feasibility checker say so.
//! - *cruise*: every UAV flies at its own cruise speed.
//!
//! A UAV may also wait before it leaves (its *departure delay*, a share delta_i of its
//! arrival time that the planner chooses where `timing.max_delay` > 0): it hovers at its
//! start until delta_i x arrival and flies the rest at constant speed. Under common arrival
//! everyone still arrives at T, so UAV i flies L_i in (1 - delta_i) T: its effective length
//! in the choice of T is L_i / (1 - delta_i). With every delay 0 (the default) nothing here
//! changes, bit for bit.
//!
//! Both scale the preferred speed by the plan's *pace* (1 unless the scenario's
//! `timing.pace` range lets the planner choose it): common arrival prefers T / pace, then
//! clamps as above; cruise flies pace times cruise. Why a pace: the channel varies in time,
//! and a fleet that must fly nearest cruise can find itself mid-route exactly when the range
//! drops (outside-1: R(t) under 500 m from 42 to 63 s with the UAVs 400 m from either ground
//! node); flying faster or slower moves the fleet's position in that window.
//!
//! Positions at any time come from arc-length interpolation along the absolute-altitude
//! polyline. Buffers are reused between evaluations (`fill` methods) to keep the hot path
//! free of allocations.

use glam::DVec3;

use crate::plan::{Path, Plan};
use crate::points_key::PointsKey;
use crate::world::spec::{TimingPolicy, MAX_DELAY_LIMIT};
use crate::world::World;

/// One UAV's path with absolute altitudes, arc lengths and speed.
#[derive(Debug, Clone, Default)]
pub struct TimedPath {
    /// Waypoints with absolute altitude (z + ground height).
    pub abs: Vec<DVec3>,
    /// Cumulative 3-D arc length at each waypoint (`cum[0]` = 0).
    pub cum: Vec<f64>,
    /// Total length L_i (metres).
    pub length: f64,
    /// Constant speed (m/s).
    pub speed: f64,
    /// Arrival time (s).
    pub arrival: f64,
    /// Departure delay as a share of the arrival time ([`Plan::delay`]): 0 leaves at once.
    pub delay: f64,
    /// Departure time (s): it waits at its start until then (on the launcher until
    /// `launch`, hovering after).
    pub depart: f64,
    /// When it takes off (s): no earlier than its launch slot ([`crate::world::slots`]);
    /// until then it stands on the launcher at its start, drawing no power. 0 without
    /// slots.
    pub launch: f64,
    /// Of a flown path ([`TimedPlan::fill_flown`]): where each segment comes from (an arc
    /// chord or a straight piece, of which waypoint segment). Empty for a waypoint path.
    pub flown: Vec<crate::flight::FlownSegment>,
    /// Of a flown path: the tangent length R tan(theta / 2) of each waypoint's turn
    /// ([`crate::flight::turn_tangents`]).
    pub tangents: Vec<f64>,
    /// Of a flown path: each corner's turn, at its first waypoint, found with the tangents
    /// and reused to build the arcs.
    pub(crate) turns: Vec<Option<crate::flight::Corner>>,
}

impl TimedPath {
    fn fill_geometry(&mut self, world: &World, path: &Path) {
        self.abs.clear();
        self.abs
            .extend(path.waypoints.iter().map(|p| world.absolute(*p)));
        self.fill_lengths();
    }

    /// The waypoint segment that segment `s` of this path lies on (itself for a waypoint
    /// path), so violations name the plan's segments.
    #[must_use]
    pub fn waypoint_segment(&self, s: usize) -> usize {
        self.flown.get(s).map_or(s, |f| f.waypoint_segment)
    }

    /// When this path passes each of the plan's waypoints, `waypoints` (absolute places,
    /// [`TimedPath::abs`] of the waypoint path): for a flown path the middle of the arc
    /// through a corner, or the corner itself when it is flown straight; for a waypoint
    /// path [`TimedPath::time_at`]. A run of equal waypoints is one place passed once, and
    /// every waypoint of the run gets that time: the departure for a run at the start, the
    /// arrival for one at the goal (docs/model.md, "Waypoint times").
    #[must_use]
    pub fn waypoint_times(&self, waypoints: &[DVec3]) -> Vec<f64> {
        let m = waypoints.len();
        if self.flown.is_empty() || m < 2 {
            return (0..m)
                .map(|k| self.time_at(k.min(self.abs.len().saturating_sub(1))))
                .collect();
        }
        // Per corner k (the first waypoint of its run): the span of its arc, and when the
        // straight piece into it ends (at the corner, or where its arc begins).
        let mut arc_span: Vec<Option<(f64, f64)>> = vec![None; m];
        let mut reached: Vec<Option<f64>> = vec![None; m];
        for (s, f) in self.flown.iter().enumerate() {
            let (t0, t1) = (self.time_at(s), self.time_at(s + 1));
            let k = f.waypoint_segment + 1;
            if k >= m {
                continue;
            }
            if f.arc {
                let span = arc_span[k].get_or_insert((t0, t1));
                span.1 = t1;
            } else {
                reached[k] = Some(t1);
            }
        }
        let mut times = vec![0.0; m];
        let mut first = 0;
        while first < m {
            let mut last = first;
            while last + 1 < m && waypoints[last + 1] == waypoints[first] {
                last += 1;
            }
            let t = if first == 0 {
                // It leaves its start at its departure (it hovered there until then).
                self.depart
            } else if last == m - 1 {
                self.arrival
            } else {
                match (arc_span[first], reached[first]) {
                    (Some((t0, t1)), _) => 0.5 * (t0 + t1),
                    (None, Some(t)) => t,
                    (None, None) => times[first - 1],
                }
            };
            times[first..=last].fill(t);
            first = last + 1;
        }
        times
    }

    /// Recomputes the arc lengths of `abs`.
    fn fill_lengths(&mut self) {
        self.cum.clear();
        let mut s = 0.0;
        for (k, a) in self.abs.iter().enumerate() {
            if k > 0 {
                s += a.distance(self.abs[k - 1]);
            }
            self.cum.push(s);
        }
        self.length = s;
    }

    /// Time at which waypoint k is reached.
    #[must_use]
    pub fn time_at(&self, k: usize) -> f64 {
        let flying = if self.speed > 0.0 {
            self.cum[k] / self.speed
        } else {
            0.0
        };
        if self.depart > 0.0 {
            self.depart + flying
        } else {
            flying
        }
    }

    /// Arc length flown by time t (negative before departure, which positions clamp to the
    /// start).
    #[must_use]
    pub fn length_at_time(&self, t: f64) -> f64 {
        if self.depart > 0.0 {
            self.speed * (t - self.depart)
        } else {
            self.speed * t
        }
    }

    /// Position at arc length `s` (clamped to the path), searching from segment `hint`
    /// onwards; returns the position and the segment used (a hint for the next call).
    #[must_use]
    pub fn position_at_length(&self, s: f64, hint: usize) -> (DVec3, usize) {
        let last = self.abs.len() - 1;
        if last == 0 || s <= 0.0 {
            return (self.abs[0], 0);
        }
        if s >= self.length {
            return (self.abs[last], last - 1);
        }
        let mut k = hint.min(last - 1);
        while k > 0 && self.cum[k] > s {
            k -= 1;
        }
        while k + 1 < last && self.cum[k + 1] < s {
            k += 1;
        }
        let seg = self.cum[k + 1] - self.cum[k];
        let f = if seg > 0.0 {
            (s - self.cum[k]) / seg
        } else {
            0.0
        };
        (self.abs[k].lerp(self.abs[k + 1], f), k)
    }

    /// Position at time t (the UAV waits at its start before departing and at its goal
    /// after arriving).
    #[must_use]
    pub fn position_at_time(&self, t: f64) -> DVec3 {
        self.position_at_length(self.length_at_time(t), 0).0
    }
}

/// Every UAV's timed path and the mission horizon.
#[derive(Debug, Clone)]
pub struct TimedPlan {
    /// One timed path per UAV, in fleet order.
    pub paths: Vec<TimedPath>,
    /// The plan's pace ([`Plan::pace`]).
    pub pace: f64,
    /// Latest arrival (s).
    pub horizon: f64,
    /// Per UAV, what its flown geometry in `paths` was last made from by
    /// [`TimedPlan::fill_flown`], so that a UAV whose waypoints did not change keeps it.
    flown_from: Vec<FlownSource>,
}

impl Default for TimedPlan {
    fn default() -> Self {
        Self {
            paths: Vec::new(),
            pace: 1.0,
            horizon: 0.0,
            flown_from: Vec::new(),
        }
    }
}

/// The inputs of one UAV's flown geometry: its turning radius and waypoints (absolute
/// altitudes), as bits so that -0.0 and 0.0 (or two NaNs) are told apart. Its tangent
/// lengths are of these inputs; its geometry too once `built`.
#[derive(Debug, Clone, Default)]
struct FlownSource {
    radius: u64,
    abs: PointsKey,
    built: bool,
}

impl FlownSource {
    fn is(&self, radius: f64, abs: &[DVec3]) -> bool {
        self.radius == radius.to_bits() && self.abs.matches(abs)
    }

    /// New inputs: their tangents are to be computed, their geometry built.
    fn set(&mut self, radius: f64, abs: &[DVec3]) {
        self.radius = radius.to_bits();
        self.abs.set(abs);
        self.built = false;
    }
}

impl TimedPlan {
    /// Geometry and schedule of `plan` in `world` ([`TimedPlan::fill`] on a new value).
    #[must_use]
    pub fn new(world: &World, plan: &Plan) -> Self {
        let mut t = Self::default();
        t.fill(world, plan);
        t
    }

    /// Recomputes geometry and schedule for `plan`, reusing buffers.
    pub fn fill(&mut self, world: &World, plan: &Plan) {
        let n = plan.uavs.len();
        self.pace = plan.pace;
        self.paths.resize_with(n, TimedPath::default);
        for (u, (tp, path)) in self.paths.iter_mut().zip(&plan.uavs).enumerate() {
            tp.fill_geometry(world, path);
            tp.flown.clear();
            tp.tangents.clear();
            tp.turns.clear();
            tp.delay = delay_share(plan.delay(u));
        }
        self.schedule(world);
    }

    /// The tangent lengths of the turns of `waypoints` (each UAV's turning radius) into
    /// `paths`, the first half of [`TimedPlan::fill_flown`]: enough for the turning-radius
    /// check, which a bounded assessment makes before it builds any arc. A UAV whose
    /// waypoints are bit for bit those of the previous fill keeps its tangents; the others'
    /// geometry is out of date until [`TimedPlan::fill_flown`].
    pub fn fill_tangents(&mut self, world: &World, waypoints: &TimedPlan) {
        let n = waypoints.paths.len();
        if self.flown_from.len() != self.paths.len() {
            self.flown_from.clear();
        }
        self.paths.resize_with(n, TimedPath::default);
        self.flown_from.resize_with(n, FlownSource::default);
        let sources = self.paths.iter_mut().zip(&mut self.flown_from);
        for (u, ((tp, source), wp)) in sources.zip(&waypoints.paths).enumerate() {
            let radius = world.spec().uavs[u].turn_radius;
            if source.is(radius, &wp.abs) {
                continue;
            }
            crate::flight::turn_tangents_and_corners(
                &wp.abs,
                radius,
                &mut tp.tangents,
                &mut tp.turns,
            );
            source.set(radius, &wp.abs);
        }
    }

    /// The flown trajectory of `waypoints` (an arc of each UAV's turning radius through
    /// every corner, [`crate::flight`]), timed by the same policy on its own lengths.
    ///
    /// The geometry is a pure function of a UAV's waypoints and radius, so a UAV whose
    /// waypoints are bit for bit those of the previous fill of this plan keeps the arcs it
    /// has (the optimizers that change one UAV at a time rebuild one of n); only the timing
    /// is redone for all. Nothing else may write the geometry of `paths` in between.
    pub fn fill_flown(&mut self, world: &World, waypoints: &TimedPlan) {
        self.fill_tangents(world, waypoints);
        self.pace = waypoints.pace;
        let sources = self.paths.iter_mut().zip(&mut self.flown_from);
        for (u, ((tp, source), wp)) in sources.zip(&waypoints.paths).enumerate() {
            tp.delay = wp.delay;
            if source.built {
                continue;
            }
            let radius = world.spec().uavs[u].turn_radius;
            crate::flight::flown_polyline_at(
                &wp.abs,
                radius,
                &tp.tangents,
                Some(&tp.turns),
                &mut tp.abs,
                &mut tp.flown,
            );
            tp.fill_lengths();
            source.built = true;
        }
        self.schedule(world);
    }

    /// What is flown and assessed: the flown path when the world flies arcs
    /// ([`World::flies_arcs`]), else the waypoint polyline (for figures, reports, exports).
    #[must_use]
    pub fn flown(world: &World, plan: &Plan) -> Self {
        let waypoints = Self::new(world, plan);
        if !world.flies_arcs() {
            return waypoints;
        }
        let mut flown = Self::default();
        flown.fill_flown(world, &waypoints);
        flown
    }

    /// Speeds, departures, arrivals and the horizon from the paths' lengths and delays under
    /// the timing policy.
    fn schedule(&mut self, world: &World) {
        let uavs = &world.spec().uavs;
        let slots = world.slots();
        match world.spec().timing.policy {
            TimingPolicy::Cruise => {
                for (tp, u) in self.paths.iter_mut().zip(uavs) {
                    tp.speed = u.cruise_speed * self.pace;
                    tp.launch = 0.0;
                    let flight = tp.length / tp.speed;
                    if tp.delay > 0.0 {
                        // delta of the arrival time waiting: depart = delta / (1 - delta) x flight.
                        tp.depart = tp.delay / (1.0 - tp.delay) * flight;
                        tp.arrival = tp.depart + flight;
                    } else {
                        tp.depart = 0.0;
                        tp.arrival = flight;
                    }
                }
            }
            TimingPolicy::CommonArrival => {
                // A UAV that waits delta T flies its length in (1 - delta) T.
                let effective = |p: &TimedPath| {
                    if p.delay > 0.0 {
                        p.length / (1.0 - p.delay)
                    } else {
                        p.length
                    }
                };
                let t = common_arrival_time_at_pace(
                    self.paths
                        .iter()
                        .zip(uavs)
                        .map(|(p, u)| (effective(p), u.cruise_speed, u.speed[0], u.speed[1])),
                    self.pace,
                );
                for tp in &mut self.paths {
                    tp.launch = 0.0;
                    tp.speed = if t > 0.0 { effective(tp) / t } else { 0.0 };
                    tp.depart = if tp.delay > 0.0 { tp.delay * t } else { 0.0 };
                    tp.arrival = t;
                }
            }
        }
        if slots.any() {
            self.shift_into_slots(world);
        }
        self.horizon = self.paths.iter().map(|p| p.arrival).fold(0.0, f64::max);
    }

    /// Moves each UAV's whole flight later to fit the launch and recovery slots
    /// ([`crate::world::slots::Slots::shift`]): its speed, hover and flight time stay those of
    /// the schedule without slots, and it waits on the launcher (drawing nothing) until it
    /// takes off.
    fn shift_into_slots(&mut self, world: &World) {
        let slots = world.slots();
        for (i, tp) in self.paths.iter_mut().enumerate() {
            let shift = slots.shift(i);
            tp.launch = shift;
            tp.depart += shift;
            tp.arrival += shift;
        }
    }
}

impl TimedPlan {
    /// Positions of every UAV at time `t` into `out`; `hints` (one per UAV, start at 0) make
    /// a forward sweep over increasing times linear in samples plus segments.
    pub fn sample(&self, t: f64, hints: &mut [usize], out: &mut [DVec3]) {
        for ((tp, h), o) in self.paths.iter().zip(hints.iter_mut()).zip(out.iter_mut()) {
            let (p, k) = tp.position_at_length(tp.length_at_time(t), *h);
            *h = k;
            *o = p;
        }
    }
}

/// A plan's delay as the schedule takes it: in [0, [`MAX_DELAY_LIMIT`]], 0 for a NaN or a
/// negative one. Plan files and imports refuse such delays; this keeps a plan built in code
/// (or a decision vector outside its bounds) timed, instead of a UAV that never leaves.
fn delay_share(d: f64) -> f64 {
    if d > 0.0 {
        d.min(MAX_DELAY_LIMIT)
    } else {
        0.0
    }
}

/// The common arrival time T for paths given as (length, cruise, v_min, v_max).
#[must_use]
pub fn common_arrival_time(paths: impl Iterator<Item = (f64, f64, f64, f64)> + Clone) -> f64 {
    common_arrival_time_at_pace(paths, 1.0)
}

/// [`common_arrival_time`] with the preferred time divided by `pace` (the speeds nearest
/// `pace` times cruise) before it is clamped to the speed limits.
#[must_use]
pub fn common_arrival_time_at_pace(
    paths: impl Iterator<Item = (f64, f64, f64, f64)> + Clone,
    pace: f64,
) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    let (mut lo, mut hi) = (0.0_f64, f64::INFINITY);
    for (l, c, vmin, vmax) in paths {
        num += l * l;
        den += l * c;
        lo = lo.max(l / vmax);
        hi = hi.min(l / vmin);
    }
    if num == 0.0 {
        return 0.0;
    }
    let preferred = num / den / pace;
    if lo <= hi {
        preferred.clamp(lo, hi)
    } else {
        // No T satisfies every UAV: take the middle of the conflict so both sides break
        // their limits as little as possible (in ratio).
        (lo * hi).sqrt()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn preferred_time_is_cruise_for_equal_paths() {
        let t = common_arrival_time([(1500.0, 15.0, 5.0, 25.0); 3].into_iter());
        assert!((t - 100.0).abs() < 1e-9);
    }

    #[test]
    fn time_is_clamped_so_every_speed_is_legal() {
        // 1000 m and 4000 m paths: the cruise-optimal T = 226.7 s would make the short one
        // fly at 4.4 m/s, so T is clamped to 200 s (5 m/s for it, 20 m/s for the long one).
        let t =
            common_arrival_time([(1000.0, 15.0, 5.0, 25.0), (4000.0, 15.0, 5.0, 25.0)].into_iter());
        assert!(4000.0 / t <= 25.0 + 1e-9 && 1000.0 / t >= 5.0 - 1e-9);
        assert!((t - 200.0).abs() < 1e-9);
    }

    #[test]
    fn impossible_spread_breaks_limits() {
        let t = common_arrival_time(
            [(100.0, 15.0, 5.0, 25.0), (10_000.0, 15.0, 5.0, 25.0)].into_iter(),
        );
        assert!(100.0 / t < 5.0 || 10_000.0 / t > 25.0);
    }

    #[test]
    fn position_interpolates_by_arc_length() {
        let tp = TimedPath {
            abs: vec![
                DVec3::ZERO,
                DVec3::new(10.0, 0.0, 0.0),
                DVec3::new(10.0, 10.0, 0.0),
            ],
            cum: vec![0.0, 10.0, 20.0],
            length: 20.0,
            speed: 2.0,
            arrival: 10.0,
            ..TimedPath::default()
        };
        assert!(tp.position_at_time(2.5).distance(DVec3::new(5.0, 0.0, 0.0)) < 1e-12);
        assert!(
            tp.position_at_time(7.5)
                .distance(DVec3::new(10.0, 5.0, 0.0))
                < 1e-12
        );
        assert!(
            tp.position_at_time(99.0)
                .distance(DVec3::new(10.0, 10.0, 0.0))
                < 1e-12
        );
    }
}
