//! Sharp corners of a seeded way cut into turns the UAV may fly (issue 46, items 1 and 5).
//!
//! Why: the route layer in height joins places by straight segments and does not check the
//! turn limit at its corners ([`crate::band_route`], module doc). On instances of the outside
//! generator that swarmplan had never been run on (docs/results.md, "Fresh instances"), one
//! UAV with communication off ended every failed run of two instances on one turn over the
//! 45 deg limit, at a corner of the seeded way, while the way's spare free waypoints sat on
//! its straights where they turn nothing. So before the spare waypoints are spread, each
//! corner turning more than [`TURN_SHARE`] of the limit is replaced by two points on its
//! two segments, `d` metres from it, each turning half as much, while spare waypoints
//! last: the sharpest corner first, the largest `d` whose new straight passes the route
//! layer's own test (climb, hard zones, terrain clearance) with its points moved into the
//! altitude band, as the encoding holds free waypoints (the segments to them tested too). `d` is at least what the flown arcs need (two turns of theta/2 with the
//! turning radius R need a chord of 2 R tan(theta/4), and the chord is 2 d cos(theta/2))
//! and at most [`MAX_SHARE`] of either segment, so the cuts of neighbouring corners never
//! cross.

use glam::DVec3;

/// Corners turning more than this share of `max_turn_deg` are cut while spare waypoints
/// last: the search's bows turn the seeded way a little, so a way turning just under the
/// limit would leave its draws over it.
pub const TURN_SHARE: f64 = 0.8;

/// The cut's distance from the corner, at most this share of the shorter segment's plan
/// length.
pub const MAX_SHARE: f64 = 0.45;

/// Each distance tried is this share of the one before, from the largest down.
const SHRINK: f64 = 0.8;

/// The horizontal turn at `c` between a-c and c-b, radians (0 where a segment is vertical
/// or empty): the turn the kinematics term tests ([`crate::cost::kinematics`]).
#[must_use]
pub fn turn_at(a: DVec3, c: DVec3, b: DVec3) -> f64 {
    let (u, v) = ((c - a).truncate(), (b - c).truncate());
    if u.length_squared() == 0.0 || v.length_squared() == 0.0 {
        return 0.0;
    }
    u.perp_dot(v).abs().atan2(u.dot(v))
}

/// The limits a cut must keep.
pub struct CutLimits<'a> {
    /// `max_turn_deg`, radians.
    pub max_turn: f64,
    /// `turn_radius`, m.
    pub turn_radius: f64,
    /// Whether a straight segment between two absolute points holds (the route layer's
    /// test).
    pub holds: &'a dyn Fn(DVec3, DVec3) -> bool,
    /// An absolute point moved up or down into the altitude band, as the encoding holds
    /// a free waypoint.
    pub into_band: &'a dyn Fn(DVec3) -> DVec3,
}

/// `way` (absolute, start and goal included) with its corners sharper than [`TURN_SHARE`]
/// of the limit cut while `spare` points may be added; corners no cut clears stay.
#[must_use]
pub fn cut_sharp_corners(way: &[DVec3], spare: usize, limits: &CutLimits) -> Vec<DVec3> {
    let mut way: Vec<DVec3> = way.to_vec();
    way.dedup();
    let mut spare = spare;
    let mut kept: Vec<DVec3> = Vec::new();
    while spare > 0 {
        let sharpest = (1..way.len().saturating_sub(1))
            .filter(|&k| !kept.contains(&way[k]))
            .map(|k| (k, turn_at(way[k - 1], way[k], way[k + 1])))
            .filter(|&(_, turn)| turn > TURN_SHARE * limits.max_turn)
            .max_by(|a, b| a.1.total_cmp(&b.1));
        let Some((k, turn)) = sharpest else { break };
        match cut(way[k - 1], way[k], way[k + 1], turn, limits) {
            Some((p, q)) => {
                way.splice(k..=k, [p, q]);
                spare -= 1;
            }
            None => kept.push(way[k]),
        }
    }
    way
}

/// The two points replacing corner `c` of a-c-b (turning `turn`), or `None`: the largest
/// distance whose points the band moves by at most [`BAND_MOVE_M`] together, else the
/// largest the test passes at all. (A way high over a valley, its cut moved down into the
/// band, climbs back out of it: on fresh instance 17 that traded the turn over the limit
/// for a battery over it; on 19 only a cut the band moves clears the turn.)
fn cut(a: DVec3, c: DVec3, b: DVec3, turn: f64, limits: &CutLimits) -> Option<(DVec3, DVec3)> {
    let before = (c - a).truncate().length();
    let after = (b - c).truncate().length();
    let least = limits.turn_radius * (turn / 4.0).tan() / (turn / 2.0).cos().max(0.05);
    let largest = MAX_SHARE * before.min(after);
    let tried = std::iter::successors(Some(largest), |d| Some(d * SHRINK))
        .take_while(|&d| d >= least && d > 0.0);
    let cuts: Vec<(f64, DVec3, DVec3)> = tried
        .filter_map(|d| {
            let (p, q) = (c.lerp(a, d / before), c.lerp(b, d / after));
            let (pb, qb) = ((limits.into_band)(p), (limits.into_band)(q));
            let holds = (limits.holds)(a, pb) && (limits.holds)(pb, qb) && (limits.holds)(qb, b);
            holds.then(|| (p.distance(pb) + q.distance(qb), pb, qb))
        })
        .collect();
    cuts.iter()
        .find(|(moved, _, _)| *moved <= BAND_MOVE_M)
        .or(cuts.first())
        .map(|&(_, p, q)| (p, q))
}

/// How far the band may move a cut's two points together for it to be preferred, m.
pub const BAND_MOVE_M: f64 = 10.0;

#[cfg(test)]
mod tests {
    use super::*;

    fn free(_: DVec3, _: DVec3) -> bool {
        true
    }

    fn band(p: DVec3) -> DVec3 {
        p
    }

    fn limits<'a>(
        holds: &'a dyn Fn(DVec3, DVec3) -> bool,
        into_band: &'a dyn Fn(DVec3) -> DVec3,
    ) -> CutLimits<'a> {
        CutLimits {
            max_turn: 45f64.to_radians(),
            turn_radius: 50.0,
            holds,
            into_band,
        }
    }

    fn max_turn(way: &[DVec3]) -> f64 {
        way.windows(3)
            .map(|w| turn_at(w[0], w[1], w[2]))
            .fold(0.0, f64::max)
    }

    #[test]
    fn a_right_angle_is_cut_into_two_turns_of_45_and_then_four() {
        let way = [
            DVec3::new(0.0, 0.0, 150.0),
            DVec3::new(600.0, 0.0, 150.0),
            DVec3::new(600.0, 600.0, 150.0),
        ];
        let l = limits(&free, &band);
        let once = cut_sharp_corners(&way, 1, &l);
        assert_eq!(once.len(), 4, "{once:?}");
        assert!((max_turn(&once) - 45f64.to_radians()).abs() < 1e-9);
        // 45 deg is over 0.8 of the limit: with spare points each half is cut again.
        let more = cut_sharp_corners(&way, 5, &l);
        assert_eq!(more.len(), 6, "{more:?}");
        assert!(
            max_turn(&more) < 0.8 * 45f64.to_radians() + 1e-9,
            "{more:?}"
        );
        assert_eq!(more[0], way[0]);
        assert_eq!(more[5], way[2]);
    }

    #[test]
    fn a_corner_around_an_obstacle_is_cut_only_as_far_as_the_test_allows() {
        // The inside of the corner is blocked beyond 60 m from it: the cut is the largest
        // distance (a share 0.8 of the one before) whose chord stays within, and at least
        // the 29.3 m two 45 deg arcs of 50 m radius need.
        let way = [
            DVec3::new(0.0, 0.0, 150.0),
            DVec3::new(400.0, 0.0, 150.0),
            DVec3::new(400.0, 400.0, 150.0),
        ];
        let corner = way[1];
        // Only straights that keep within 60 m of the corner or along the legs hold.
        let near = move |p: DVec3, q: DVec3| {
            let on_leg = |r: DVec3| r.y == 0.0 || r.x == 400.0;
            (on_leg(p) && on_leg(q) && (p.x == q.x || p.y == q.y))
                || (corner.distance(p) <= 60.0 + 1e-9 && corner.distance(q) <= 60.0 + 1e-9)
        };
        let cut_way = cut_sharp_corners(&way, 1, &limits(&near, &band));
        assert_eq!(cut_way.len(), 4);
        let d = corner.distance(cut_way[1]);
        assert!(d <= 60.0 && d > 60.0 * 0.8, "{d}");
        // Closed everywhere, or held in a band that lifts the cut's points 80 m over a
        // climb limit the test enforces: the corner stays.
        let closed = |_: DVec3, _: DVec3| false;
        assert_eq!(
            cut_sharp_corners(&way, 3, &limits(&closed, &band)),
            way.to_vec()
        );
        let lifted = |p: DVec3| DVec3::new(p.x, p.y, 230.0);
        let level = |p: DVec3, q: DVec3| p.z == q.z;
        assert_eq!(
            cut_sharp_corners(&way, 3, &limits(&level, &lifted)),
            way.to_vec()
        );
    }

    #[test]
    fn a_short_leg_leaves_no_room_for_the_arcs_and_gentle_corners_stay() {
        // 20 m legs cannot hold two arcs of 50 m radius turning 45 deg each.
        let short = [
            DVec3::new(0.0, 0.0, 150.0),
            DVec3::new(20.0, 0.0, 150.0),
            DVec3::new(20.0, 20.0, 150.0),
        ];
        assert_eq!(
            cut_sharp_corners(&short, 2, &limits(&free, &band)),
            short.to_vec()
        );
        let gentle = [
            DVec3::new(0.0, 0.0, 150.0),
            DVec3::new(500.0, 0.0, 150.0),
            DVec3::new(1000.0, 200.0, 150.0),
        ];
        assert_eq!(
            cut_sharp_corners(&gentle, 2, &limits(&free, &band)),
            gentle.to_vec()
        );
    }
}
