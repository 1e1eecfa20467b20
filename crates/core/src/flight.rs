//! The flown path: what a vehicle with a minimum turning radius flies through a plan's
//! waypoints, and the turning-radius constraint that makes it exist.
//!
//! Why: the paper gives a 50 m turning radius but checks a plan as straight segments with a
//! turn-angle limit at each waypoint, so two 45 deg turns 3 m apart pass although no
//! vehicle flies them, and the corner an autopilot cuts is never checked against threats,
//! terrain or the other UAVs. Here each interior waypoint b (between a and c) is replaced by
//! the circular arc of radius R tangent to both segments (a fillet, the shortest path of a
//! vehicle that turns at most 1/R per metre through the corner; Dubins 1957, Am. J. Math.
//! 79(3):497-516, doi:10.2307/2372560, whose smoothing CCEA-ADVS applies to UAV plans):
//!
//! ```text
//! theta = angle between u1 = (b - a)/|b - a| and u2 = (c - b)/|c - b|  (3-D, in the plane
//!         of the two segments)
//! tangent length t = R tan(theta / 2): the arc starts at T1 = b - t u1, ends at T2 = b + t u2
//! centre C = b + R / cos(theta / 2) * unit(u2 - u1); arc length R theta
//! ```
//!
//! The arcs need room: on every segment the tangent lengths of its two ends must fit,
//! t_k + t_{k+1} <= L_k (the start and the goal have no turn). The missing metres are a
//! [`ViolationKind::TurnRadius`] violation. So that a flown path exists even then (to be
//! assessed and drawn), the tangent lengths of an overfull segment are scaled down to fit,
//! i.e. those corners are flown on a tighter radius, and the violation says so.
//!
//! An arc is flown as chords whose sagitta (the largest gap between chord and arc) is at
//! most [`SAGITTA_M`]; everything that follows the UAV in time (separation, communication,
//! energy, speed, clearance, threats) is then assessed on that polyline, exactly as on
//! straight segments.

use glam::DVec3;

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::timing::TimedPath;
use crate::world::threat::{point_segment_distance, segment_box_misses};
use crate::world::World;

/// Largest distance between an arc and the chords that fly it, metres.
pub const SAGITTA_M: f64 = 0.5;

/// Turns whose sine is below this are flown straight through the waypoint.
const STRAIGHT: f64 = 1e-9;

/// Turns with 1 + cos(theta) below this (a reversal) get no arc: its centre would be at
/// infinity, and the tangent length is infinite.
const REVERSAL: f64 = 1e-12;

/// The turn at a corner: unit directions in and out and the half-angle's tangent and
/// cosine, from the half-angle identities tan(theta/2) = sin / (1 + cos) and
/// cos(theta/2) = sqrt((1 + cos) / 2), so the hot path needs no trigonometric call.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Corner {
    u1: DVec3,
    u2: DVec3,
    tan_half: f64,
    cos_half: f64,
}

impl Corner {
    /// The turn at b of a-b-c; `None` when straight or when a segment is empty.
    fn at(a: DVec3, b: DVec3, c: DVec3) -> Option<Self> {
        let (u1, u2) = ((b - a).normalize_or_zero(), (c - b).normalize_or_zero());
        if u1 == DVec3::ZERO || u2 == DVec3::ZERO {
            return None;
        }
        let cos = u1.dot(u2).clamp(-1.0, 1.0);
        let sin = u1.cross(u2).length();
        if sin <= STRAIGHT && cos > 0.0 {
            return None;
        }
        let one_plus = 1.0 + cos;
        let (tan_half, cos_half) = if one_plus <= REVERSAL {
            (f64::INFINITY, 0.0)
        } else {
            (sin / one_plus, (0.5 * one_plus).sqrt())
        };
        Some(Self {
            u1,
            u2,
            tan_half,
            cos_half,
        })
    }

    fn angle(&self) -> f64 {
        2.0 * self.tan_half.atan()
    }
}

/// Turn angle (radians, in [0, pi]) at `b` between a->b and b->c; 0 if a segment is empty.
#[must_use]
pub fn turn_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (u1, u2) = ((b - a).normalize_or_zero(), (c - b).normalize_or_zero());
    if u1 == DVec3::ZERO || u2 == DVec3::ZERO {
        return 0.0;
    }
    // atan2 of |cross| and dot is accurate for small and for large angles alike.
    u1.cross(u2).length().atan2(u1.dot(u2))
}

/// Straight flight a turn of angle `theta` on radius `radius` needs on each side.
#[must_use]
pub fn tangent_length(radius: f64, theta: f64) -> f64 {
    if theta >= std::f64::consts::PI {
        f64::INFINITY
    } else {
        radius * (0.5 * theta).tan()
    }
}

/// The fillet of one corner.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Fillet {
    /// Where the arc leaves the incoming segment and joins the outgoing one.
    pub enter: DVec3,
    /// Where the arc joins the outgoing segment.
    pub leave: DVec3,
    /// Centre, radius (metres) and angle (radians) of the arc.
    pub centre: DVec3,
    /// Radius of the arc, m.
    pub radius: f64,
    /// Angle the arc turns through, rad.
    pub angle: f64,
    /// Direction of flight into the corner (the arc's tangent at `enter`).
    pub heading_in: DVec3,
}

impl Fillet {
    /// The fillet of radius `radius` at corner b of a-b-c, or `None` for a straight or
    /// reversing corner (or a zero radius).
    #[must_use]
    pub fn at(a: DVec3, b: DVec3, c: DVec3, radius: f64) -> Option<Self> {
        Self::of(b, &Corner::at(a, b, c)?, radius)
    }

    fn of(b: DVec3, corner: &Corner, radius: f64) -> Option<Self> {
        if radius <= 0.0 || !corner.tan_half.is_finite() {
            return None;
        }
        let t = radius * corner.tan_half;
        let inward = (corner.u2 - corner.u1).normalize_or_zero();
        Some(Self {
            enter: b - corner.u1 * t,
            leave: b + corner.u2 * t,
            centre: b + inward * (radius / corner.cos_half),
            radius,
            angle: corner.angle(),
            heading_in: corner.u1,
        })
    }

    /// Arc length R theta.
    #[must_use]
    pub fn length(&self) -> f64 {
        self.radius * self.angle
    }

    /// The point at arc angle `phi` in [0, angle] from `enter`.
    #[must_use]
    pub fn point(&self, phi: f64) -> DVec3 {
        let e1 = (self.enter - self.centre) / self.radius;
        self.centre + (e1 * phi.cos() + self.heading_in * phi.sin()) * self.radius
    }

    /// Chords that fly the arc with sagitta at most [`SAGITTA_M`].
    #[must_use]
    pub fn chords(&self) -> usize {
        // Sagitta of a chord spanning angle d: R (1 - cos(d / 2)).
        let cos_half = 1.0 - (SAGITTA_M / self.radius).min(1.0);
        let max_step = 2.0 * cos_half.acos();
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = (self.angle / max_step.max(1e-3)).ceil() as usize;
        n.clamp(1, 256)
    }

    /// Appends the ends of the arc's chords (not `enter`, but `leave`) to `out`, each as a
    /// segment from `seg`; one sine and cosine per arc (the chord points by rotation).
    fn push_chords(&self, out: &mut Vec<DVec3>, from: &mut Vec<FlownSegment>, seg: FlownSegment) {
        let m = self.chords();
        let (s, c) = (self.angle / m as f64).sin_cos();
        let e1 = (self.enter - self.centre) / self.radius;
        let (mut cos_i, mut sin_i) = (1.0, 0.0);
        for _ in 1..m {
            (cos_i, sin_i) = (cos_i * c - sin_i * s, sin_i * c + cos_i * s);
            let p = self.centre + (e1 * cos_i + self.heading_in * sin_i) * self.radius;
            push_point(out, from, p, seg);
        }
        push_point(out, from, self.leave, seg);
    }
}

/// Tangent lengths t_k of each waypoint of `abs` (0 at the start and the goal) for radius
/// `radius`, into `out`.
///
/// A waypoint repeated (k..=last at one place) is one corner, between the places before and
/// after the run; every waypoint of the run gets its tangent length, so the segments into
/// and out of it must hold it (a repeat must not hide a turn: the UAV cannot stop to turn).
pub fn tangent_lengths(abs: &[DVec3], radius: f64, out: &mut Vec<f64>) {
    tangents_and_corners(abs, radius, out, &mut Vec::new());
}

/// [`tangent_lengths`], also keeping each corner's turn at the index of its first waypoint
/// in `turns` (`None` elsewhere), so that [`flown_polyline_at`] need not work it out again
/// (issue 47: `Corner::at` ran twice per corner).
pub(crate) fn tangents_and_corners(
    abs: &[DVec3],
    radius: f64,
    out: &mut Vec<f64>,
    turns: &mut Vec<Option<Corner>>,
) {
    no_turns(abs.len(), out, turns);
    for (k, last) in corners(abs) {
        if let Some(c) = Corner::at(abs[k - 1], abs[k], abs[last + 1]) {
            out[k..=last].fill(radius * c.tan_half);
            turns[k] = Some(c);
        }
    }
}

/// `len` zero tangent lengths and no turns.
fn no_turns(len: usize, out: &mut Vec<f64>, turns: &mut Vec<Option<Corner>>) {
    out.clear();
    out.resize(len, 0.0);
    turns.clear();
    turns.resize(len, None);
}

/// The corners of the path through `abs`: (first, last) index of each run of equal inner
/// waypoints (first = last for a waypoint not repeated), with a different place before
/// and after it. A run at the start or the goal is not a corner.
fn corners(abs: &[DVec3]) -> impl Iterator<Item = (usize, usize)> + '_ {
    let n = abs.len();
    let mut k = 1;
    std::iter::from_fn(move || {
        while k + 1 < n {
            let first = k;
            let mut last = k;
            while last + 1 < n && abs[last + 1] == abs[first] {
                last += 1;
            }
            k = last + 1;
            // A run that reaches the goal, or repeats the place before it, is no corner.
            if last + 1 < n && abs[first - 1] != abs[first] {
                return Some((first, last));
            }
        }
        None
    })
}

/// Reports, for UAV `uav` with waypoints `abs`, turning radius `radius` and the tangent
/// lengths `tangents` of its corners ([`tangent_lengths`]), every segment too short for
/// the tangent lengths of its ends. `times(k)` is when waypoint k is reached.
pub fn check_turn_radius(
    uav: usize,
    abs: &[DVec3],
    times: impl Fn(usize) -> f64,
    radius: f64,
    tangents: &[f64],
    sink: &mut ViolationSink,
) {
    if radius <= 0.0 || tangents.len() != abs.len() {
        return;
    }
    for k in 0..abs.len().saturating_sub(1) {
        if abs[k] == abs[k + 1] {
            // Inside a repeated waypoint: its turn is held by the segments around it.
            continue;
        }
        let need = tangents[k] + tangents[k + 1];
        let have = abs[k].distance(abs[k + 1]);
        if need > have + 1e-9 {
            let missing = if need.is_finite() {
                need - have
            } else {
                radius
            };
            sink.add(
                ViolationKind::TurnRadius,
                uav,
                missing,
                At {
                    index: Some(k),
                    position: Some(abs[k].lerp(abs[k + 1], 0.5)),
                    time: Some(0.5 * (times(k) + times(k + 1))),
                    ..At::default()
                },
                || {
                    format!(
                        "segment {k} is {have:.1} m long but its turns need {need:.1} m of straight flight at radius {radius} m"
                    )
                },
            );
        }
    }
}

/// Where each segment of a flown polyline comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct FlownSegment {
    /// A chord of the arc through a corner (else a straight piece of a waypoint segment).
    pub arc: bool,
    /// The waypoint segment it lies on, or for an arc the one it turns out of.
    pub waypoint_segment: usize,
}

/// The tangent lengths of a flown path through `abs` for turning radius `radius`, into
/// `out`: [`tangent_lengths`], or zeros when there is no corner to fly or no radius (what
/// [`flown_polyline`] expects).
pub fn turn_tangents(abs: &[DVec3], radius: f64, out: &mut Vec<f64>) {
    turn_tangents_and_corners(abs, radius, out, &mut Vec::new());
}

/// [`turn_tangents`], keeping the corners' turns as [`tangents_and_corners`] does.
pub(crate) fn turn_tangents_and_corners(
    abs: &[DVec3],
    radius: f64,
    out: &mut Vec<f64>,
    turns: &mut Vec<Option<Corner>>,
) {
    if abs.len() < 3 || radius <= 0.0 {
        no_turns(abs.len(), out, turns);
    } else {
        tangents_and_corners(abs, radius, out, turns);
    }
}

/// The flown polyline through the waypoints `abs` for turning radius `radius` into `out`,
/// and where each of its segments comes from into `from`; `tangents` are the corners'
/// tangent lengths, [`turn_tangents`] of the same waypoints and radius (computed once for
/// the turning-radius check too). Overfull segments have their tangent lengths scaled down
/// to fit (a tighter turn, which [`check_turn_radius`] reports).
pub fn flown_polyline(
    abs: &[DVec3],
    radius: f64,
    tangents: &[f64],
    out: &mut Vec<DVec3>,
    from: &mut Vec<FlownSegment>,
) {
    flown_polyline_at(abs, radius, tangents, None, out, from);
}

/// [`flown_polyline`] with the corners' turns of [`turn_tangents_and_corners`] of the same
/// waypoints when `turns` is given (the same turns, so the same path bit for bit).
pub(crate) fn flown_polyline_at(
    abs: &[DVec3],
    radius: f64,
    tangents: &[f64],
    turns: Option<&[Option<Corner>]>,
    out: &mut Vec<DVec3>,
    from: &mut Vec<FlownSegment>,
) {
    out.clear();
    from.clear();
    let n = abs.len();
    if n < 3 || radius <= 0.0 {
        out.extend_from_slice(abs);
        from.extend((0..n.saturating_sub(1)).map(|k| FlownSegment {
            arc: false,
            waypoint_segment: k,
        }));
        return;
    }
    debug_assert_eq!(tangents.len(), n, "tangents of the same waypoints");
    // Scale of each segment: how much of its ends' tangent lengths fit.
    let fit = |k: usize| {
        let need = tangents[k] + tangents[k + 1];
        let have = abs[k].distance(abs[k + 1]);
        if need > have {
            have / need
        } else {
            1.0
        }
    };
    out.push(abs[0]);
    let mut k = 1;
    while k < n - 1 {
        let straight = FlownSegment {
            arc: false,
            waypoint_segment: k - 1,
        };
        // A repeated waypoint (k..=last) is flown as one corner; a repeat of the place
        // before it adds nothing.
        let mut last = k;
        while last + 2 < n && abs[last + 1] == abs[k] {
            last += 1;
        }
        let corner = if abs[k - 1] == abs[k] {
            None
        } else if let Some(turns) = turns {
            turns[k]
        } else {
            Corner::at(abs[k - 1], abs[k], abs[last + 1])
        };
        let fillet = corner.and_then(|c| {
            // An overfull segment's corners are flown on the radius that fits.
            let scale = fit(k - 1).min(fit(last));
            Fillet::of(abs[k], &c, radius * scale)
        });
        match fillet {
            Some(f) if f.radius > 1e-9 => {
                push_point(out, from, f.enter, straight);
                let chord = FlownSegment {
                    arc: true,
                    ..straight
                };
                f.push_chords(out, from, chord);
            }
            _ => push_point(out, from, abs[k], straight),
        }
        k = last + 1;
    }
    let last = FlownSegment {
        arc: false,
        waypoint_segment: n - 2,
    };
    push_point(out, from, abs[n - 1], last);
}

/// Reports every arc chord of UAV `uav`'s flown path `tp` that enters a threat cylinder
/// (radius r + drone size): a corner the waypoint segments clear can be cut into one. The
/// straight pieces lie on the waypoint segments, which the threat term checks already.
///
/// An arc is flown as many short chords; the threats whose square the box of the whole arc
/// misses are missed by every chord's box inside it, so each arc first picks the threats it
/// may touch (among the first 64; later ones are checked chord by chord) and its chords are
/// checked against those only, in the same order as chord by chord.
pub fn check_arc_threats(world: &World, uav: usize, tp: &TimedPath, sink: &mut ViolationSink) {
    let size = world.spec().uavs[uav].size;
    let threats = &world.spec().threats;
    let mut s = 0;
    while s < tp.flown.len() {
        let seg = tp.flown[s];
        if !seg.arc {
            s += 1;
            continue;
        }
        // The arc: chords s..end, all from the same corner.
        let end = s + tp.flown[s..]
            .iter()
            .take_while(|f| f.arc && f.waypoint_segment == seg.waypoint_segment)
            .count();
        let (mut lo, mut hi) = (tp.abs[s], tp.abs[s]);
        for p in &tp.abs[s + 1..=end] {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        let mut near: u64 = 0;
        for (i, t) in threats.iter().enumerate().take(64) {
            if !segment_box_misses(t, lo, hi, t.r + size) {
                near |= 1 << i;
            }
        }
        for c in s..end {
            let (a, b) = (tp.abs[c], tp.abs[c + 1]);
            for (i, t) in threats.iter().enumerate() {
                if i < 64 && near & (1 << i) == 0 {
                    continue;
                }
                let hard = t.r + size;
                if segment_box_misses(t, a, b, hard) {
                    continue;
                }
                let d = point_segment_distance((t.x, t.y), (a.x, a.y), (b.x, b.y));
                if d < hard {
                    sink.add(
                        ViolationKind::Threat,
                        uav,
                        hard - d,
                        At {
                            index: Some(seg.waypoint_segment),
                            position: Some(a.lerp(b, 0.5)),
                            time: Some(0.5 * (tp.time_at(c) + tp.time_at(c + 1))),
                            ..At::default()
                        },
                        || {
                            format!(
                                "the flown arc passes {d:.1} m from the axis of threat ({:.0}, {:.0}, r {:.0}); limit {hard:.1} m",
                                t.x, t.y, t.r
                            )
                        },
                    );
                }
            }
        }
        s = end;
    }
}

/// Appends `p`, the end of a segment that comes from `seg`, dropping a zero-length one.
fn push_point(out: &mut Vec<DVec3>, from: &mut Vec<FlownSegment>, p: DVec3, seg: FlownSegment) {
    if out.last().is_some_and(|q| *q == p) {
        return;
    }
    out.push(p);
    from.push(seg);
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    #[test]
    fn a_right_angle_has_tangent_length_r_and_arc_length_r_pi_over_2() {
        let (a, b, c) = (
            DVec3::new(0.0, 0.0, 100.0),
            DVec3::new(200.0, 0.0, 100.0),
            DVec3::new(200.0, 200.0, 100.0),
        );
        assert!((turn_angle(a, b, c) - FRAC_PI_2).abs() < 1e-12);
        let f = Fillet::at(a, b, c, 50.0).unwrap();
        assert!((f.enter - DVec3::new(150.0, 0.0, 100.0)).length() < 1e-9);
        assert!((f.leave - DVec3::new(200.0, 50.0, 100.0)).length() < 1e-9);
        assert!((f.centre - DVec3::new(150.0, 50.0, 100.0)).length() < 1e-9);
        assert!((f.length() - 50.0 * FRAC_PI_2).abs() < 1e-9);
        // Every point of the arc is R from the centre, and the arc ends where it should.
        for i in 0..=10 {
            let p = f.point(f.angle * f64::from(i) / 10.0);
            assert!((p.distance(f.centre) - 50.0).abs() < 1e-9);
        }
        assert!(f.point(f.angle).distance(f.leave) < 1e-9);
    }

    #[test]
    fn a_60_degree_climbing_turn_is_tangent_to_both_segments() {
        let a = DVec3::new(0.0, 0.0, 0.0);
        let b = DVec3::new(100.0, 0.0, 30.0);
        let c = b + DVec3::new(60f64.to_radians().cos(), 60f64.to_radians().sin(), 0.2) * 100.0;
        let theta = turn_angle(a, b, c);
        let f = Fillet::at(a, b, c, 40.0).unwrap();
        let t = 40.0 * (0.5 * theta).tan();
        assert!((f.enter.distance(b) - t).abs() < 1e-9);
        assert!((f.leave.distance(b) - t).abs() < 1e-9);
        // Radius perpendicular to both segments at the tangent points.
        assert!((f.enter - f.centre).dot(b - a).abs() < 1e-6);
        assert!((f.leave - f.centre).dot(c - b).abs() < 1e-6);
        // The chord polyline is within the sagitta of the arc and of the right length.
        let m = f.chords();
        let mut len = 0.0;
        let mut prev = f.enter;
        for i in 1..=m {
            let p = f.point(f.angle * i as f64 / m as f64);
            let mid = (prev + p) * 0.5;
            assert!(f.radius - mid.distance(f.centre) <= SAGITTA_M + 1e-9);
            len += p.distance(prev);
            prev = p;
        }
        // Chords of angle d are shorter than their arc by a factor of about 1 - d^2 / 24,
        // i.e. 1 - sagitta / (3 R).
        assert!(len < f.length() && len > f.length() * (1.0 - SAGITTA_M / f.radius));
    }

    #[test]
    fn two_sharp_turns_three_metres_apart_break_the_turning_radius() {
        let abs = [
            DVec3::new(0.0, 0.0, 100.0),
            DVec3::new(100.0, 0.0, 100.0),
            DVec3::new(102.1, 2.1, 100.0),   // 3 m on, 45 deg left
            DVec3::new(102.1, 102.1, 100.0), // 45 deg left again
        ];
        let mut sink = ViolationSink::collecting(crate::feasibility::FeasibilityProfile::Strict);
        let mut t = Vec::new();
        tangent_lengths(&abs, 50.0, &mut t);
        check_turn_radius(0, &abs, |k| k as f64, 50.0, &t, &mut sink);
        let list = sink.list.unwrap();
        assert_eq!(list.len(), 1);
        assert_eq!(list[0].kind, ViolationKind::TurnRadius);
        assert_eq!(list[0].index, Some(1));
        // Each 45 deg turn needs 50 tan(22.5 deg) = 20.7 m; the segment has 2.97 m.
        let need = 2.0 * 50.0 * (22.5f64).to_radians().tan();
        assert!((list[0].amount - (need - abs[1].distance(abs[2]))).abs() < 1e-9);
        // A wide spacing is fine.
        let mut ok = ViolationSink::collecting(crate::feasibility::FeasibilityProfile::Strict);
        let wide = [
            abs[0],
            abs[1],
            DVec3::new(170.0, 70.0, 100.0),
            DVec3::new(170.0, 170.0, 100.0),
        ];
        tangent_lengths(&wide, 50.0, &mut t);
        check_turn_radius(0, &wide, |k| k as f64, 50.0, &t, &mut ok);
        assert!(ok.list.unwrap().is_empty());
    }

    #[test]
    fn the_flown_polyline_cuts_the_corner_and_keeps_the_ends() {
        let abs = [
            DVec3::new(0.0, 0.0, 100.0),
            DVec3::new(200.0, 0.0, 100.0),
            DVec3::new(200.0, 200.0, 100.0),
        ];
        let (mut t, mut out, mut from) = (Vec::new(), Vec::new(), Vec::new());
        turn_tangents(&abs, 50.0, &mut t);
        flown_polyline(&abs, 50.0, &t, &mut out, &mut from);
        assert_eq!(out[0], abs[0]);
        assert_eq!(*out.last().unwrap(), abs[2]);
        assert_eq!(from.len(), out.len() - 1);
        let last = from[from.len() - 1];
        assert!(!from[0].arc && !last.arc && from[1].arc);
        assert_eq!((from[0].waypoint_segment, last.waypoint_segment), (0, 1));
        let len: f64 = out.windows(2).map(|w| w[0].distance(w[1])).sum();
        let exact = 150.0 + 150.0 + 50.0 * FRAC_PI_2;
        let arc_deficit = 50.0 * FRAC_PI_2 * SAGITTA_M / 50.0;
        assert!(len < exact && len > exact - arc_deficit, "{len} vs {exact}");
        // The corner itself is not flown: the path stays R (sqrt 2 - 1) inside it.
        let nearest = out
            .iter()
            .map(|p| p.distance(abs[1]))
            .fold(f64::INFINITY, f64::min);
        assert!((nearest - 50.0 * (2f64.sqrt() - 1.0)).abs() < SAGITTA_M + 1e-6);
        // Radius 0: the waypoints themselves.
        turn_tangents(&abs, 0.0, &mut t);
        assert_eq!(t, [0.0; 3]);
        flown_polyline(&abs, 0.0, &t, &mut out, &mut from);
        assert_eq!(out, abs);
    }

    #[test]
    fn a_repeated_waypoint_is_the_same_corner() {
        let (a, b, c) = (
            DVec3::new(0.0, 0.0, 100.0),
            DVec3::new(30.0, 0.0, 100.0),
            DVec3::new(30.0, 30.0, 100.0),
        );
        let verdicts = |abs: &[DVec3], radius: f64| {
            let mut t = Vec::new();
            tangent_lengths(abs, radius, &mut t);
            let mut sink =
                ViolationSink::collecting(crate::feasibility::FeasibilityProfile::Strict);
            check_turn_radius(0, abs, |k| k as f64, radius, &t, &mut sink);
            let amounts: Vec<f64> = sink.list.unwrap().iter().map(|v| v.amount).collect();
            let (mut out, mut from) = (Vec::new(), Vec::new());
            turn_tangents(abs, radius, &mut t);
            flown_polyline(abs, radius, &t, &mut out, &mut from);
            (amounts, out)
        };
        for radius in [10.0, 50.0] {
            // At radius 50 the right angle needs 50 m on each side of the 30 m segments.
            let (amounts, flown) = verdicts(&[a, b, c], radius);
            assert_eq!(amounts.len(), if radius > 30.0 { 2 } else { 0 });
            for repeated in [vec![a, b, b, c], vec![a, b, b, b, c]] {
                assert_eq!(
                    verdicts(&repeated, radius),
                    (amounts.clone(), flown.clone())
                );
            }
        }
        // Repeats of the start or the goal turn nowhere, and do not fail.
        for abs in [
            vec![a, a, b, c],
            vec![a, b, c, c],
            vec![a, a, a],
            vec![a, b, b],
        ] {
            let (amounts, flown) = verdicts(&abs, 50.0);
            assert_eq!((flown.first(), flown.last()), (abs.first(), abs.last()));
            let expected = usize::from(abs.len() == 4 && abs[1] != abs[2]) * 2;
            assert_eq!(amounts.len(), expected, "{abs:?}");
        }
    }
}
