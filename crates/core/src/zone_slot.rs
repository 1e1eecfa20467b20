//! Bearing slots at a shared take-off or landing zone: where a UAV may cross the zone's
//! edge so that it keeps its separation from the others that cross it.
//!
//! Why: separation is not required inside the zone around a start or UGV0
//! (`timing.zone_radius`), but outside it is, and under common arrival the whole fleet
//! leaves a shared start together and reaches UGV0 together. Two UAVs that cross the edge at
//! once need bearings at least 2 asin(separation / (2 radius)) apart (19 deg for 10 m at
//! 30 m). The runs left infeasible on the outside instances mostly hold one such loss, with
//! the two UAVs' last legs a few degrees apart over hundreds of metres: turning such a leg by
//! 20 deg moves its far end by a hundred metres or more, beyond a nudge's reach. A slot move
//! instead puts the UAV's first (or last) free waypoint near the zone, at the nearest bearing
//! that is clear of every other UAV's, so that only the leg into (or out of) the zone turns.

use glam::{DVec2, DVec3};
use rand::Rng as _;

use crate::rng::Rng;

/// Bearings at least this factor times the minimum angle apart count as clear (a margin for
/// the arcs flown through the corners and for UAVs that cross a little inside the edge).
pub const SLOT_MARGIN: f64 = 1.25;

/// The waypoint of a slot move is placed this many zone radii from the zone's centre, drawn
/// uniformly.
pub const SLOT_DISTANCE: [f64; 2] = [2.0, 4.0];

/// Smallest bearing difference (radians) of two UAVs crossing the edge of a zone of
/// `radius` at once with `separation` between them.
#[must_use]
pub fn min_angle(separation: f64, radius: f64) -> f64 {
    2.0 * (separation / (2.0 * radius)).clamp(0.0, 1.0).asin()
}

/// The bearing nearest `own` (radians) that is at least `gap` from every bearing of
/// `others`, on the nearer side with probability 2/3 and on the other with 1/3; `None` when
/// no bearing is clear (too many UAVs for the circle) or `own` is clear already.
pub fn clear_bearing(own: f64, others: &[f64], gap: f64, rng: &mut Rng) -> Option<f64> {
    use std::f64::consts::{PI, TAU};
    // Signed angle from `own` to `b` in (-pi, pi].
    let offset = |b: f64| {
        let d = (b - own).rem_euclid(TAU);
        if d > PI {
            d - TAU
        } else {
            d
        }
    };
    let clear = |d: f64| {
        others.iter().all(|&o| {
            let x = (d - offset(o)).rem_euclid(TAU);
            x.min(TAU - x) >= gap
        })
    };
    if clear(0.0) {
        return None;
    }
    // Candidates: the edges of every forbidden arc, as offsets from `own`.
    let mut left: Option<f64> = None; // smallest positive clear offset
    let mut right: Option<f64> = None; // largest negative clear offset
    for &o in others {
        for edge in [offset(o) + gap, offset(o) - gap] {
            let d = (edge + PI).rem_euclid(TAU) - PI;
            // A hair further out, so that rounding keeps it clear of the arc it bounds.
            let d = d + d.signum() * 1e-9;
            if !clear(d) {
                continue;
            }
            if d > 0.0 {
                left = Some(left.map_or(d, |l: f64| l.min(d)));
            } else {
                right = Some(right.map_or(d, |r: f64| r.max(d)));
            }
        }
    }
    let pick = match (left, right) {
        (Some(l), Some(r)) => {
            let (near, far) = if l <= -r { (l, r) } else { (r, l) };
            if rng.random::<f64>() < 2.0 / 3.0 {
                near
            } else {
                far
            }
        }
        (Some(d), None) | (None, Some(d)) => d,
        (None, None) => return None,
    };
    Some(own + pick)
}

/// Horizontal bearing of `p` seen from `centre`.
#[must_use]
pub fn bearing(centre: DVec3, p: DVec3) -> f64 {
    let d = p.truncate() - centre.truncate();
    d.y.atan2(d.x)
}

/// The point `distance` from `centre` at `bearing`, at height `z`.
#[must_use]
pub fn at_bearing(centre: DVec3, bearing: f64, distance: f64, z: f64) -> DVec3 {
    let (s, c) = bearing.sin_cos();
    (centre.truncate() + DVec2::new(c, s) * distance).extend(z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_from_seed;

    fn gap_to(b: f64, others: &[f64]) -> f64 {
        use std::f64::consts::TAU;
        others
            .iter()
            .map(|o| {
                let d = (b - o).rem_euclid(TAU);
                d.min(TAU - d)
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn nineteen_degrees_part_two_uavs_by_ten_metres_at_thirty() {
        let a = min_angle(10.0, 30.0);
        assert!((a.to_degrees() - 19.19).abs() < 0.01, "{}", a.to_degrees());
        // The chord at the edge is the separation.
        assert!((2.0 * 30.0 * (a / 2.0).sin() - 10.0).abs() < 1e-12);
    }

    #[test]
    fn a_crowded_bearing_moves_to_the_nearest_clear_one_and_a_clear_one_stays() {
        let gap = 20f64.to_radians();
        let others: Vec<f64> = [0.0f64, 10.0, 60.0]
            .iter()
            .map(|d| d.to_radians())
            .collect();
        let mut rng = rng_from_seed(1);
        let mut seen = [0, 0];
        for _ in 0..300 {
            let b = clear_bearing(8f64.to_radians(), &others, gap, &mut rng).unwrap();
            assert!(gap_to(b, &others) >= gap - 1e-12, "{}", b.to_degrees());
            // The nearest clear bearings are 30 deg (22 deg away) and -20 deg (28 away).
            let deg = b.to_degrees();
            if (deg - 30.0).abs() < 1e-6 {
                seen[0] += 1;
            } else {
                assert!((deg + 20.0).abs() < 1e-6, "{deg}");
                seen[1] += 1;
            }
        }
        // The nearer side in about two draws of three.
        assert!((170..=230).contains(&seen[0]), "{seen:?}");
        assert_eq!(
            clear_bearing(100f64.to_radians(), &others, gap, &mut rng),
            None
        );
        // Across the +-pi seam.
        let others = [179f64.to_radians()];
        let b = clear_bearing((-179f64).to_radians(), &others, gap, &mut rng).unwrap();
        assert!(gap_to(b, &others) >= gap - 1e-12, "{}", b.to_degrees());
        // Nothing clear on a full circle.
        let full: Vec<f64> = (0..36).map(|k| f64::from(k) * 10f64.to_radians()).collect();
        assert_eq!(clear_bearing(0.05, &full, gap, &mut rng), None);
    }

    #[test]
    fn a_point_at_a_bearing_is_seen_at_that_bearing() {
        let c = DVec3::new(100.0, 50.0, 7.0);
        let p = at_bearing(c, 1.0, 80.0, 120.0);
        assert!((bearing(c, p) - 1.0).abs() < 1e-12);
        assert!((p.truncate().distance(c.truncate()) - 80.0).abs() < 1e-9);
        assert_eq!(p.z, 120.0);
    }
}
