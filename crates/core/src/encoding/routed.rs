//! Guides of the `route` initialisation (issue 46): per start, the route layer's cheapest
//! way by energy over the terrain, around the threats with half the widest way's margin.
//!
//! Why: on the outside instances the `line` and `corridor` starts fail on batteries and
//! climbs as much as on threats (development instances, one UAV: energy on 8, 14, 17, 21,
//! 22 and 24, climbs on 8, 17, 21, 22 and 24), because both follow the shortest planar way
//! and the UAV, holding its height above ground, climbs every ridge on it. Here the way is
//! the cheapest in joules: each grid step costs its length at the cruise speed's energy per
//! metre plus m g per metre the ground rises (descents are free), and a step steeper than
//! the climb limit costs ten times its length more. Its staircase is then straightened
//! where a straight piece keeps the margin and stays within `STRAIGHTEN_M` of the way, so
//! the guide keeps to the valleys. A UAV whose start has no way gets no guide (it is drawn
//! as `line`).

use glam::DVec2;

use super::corridor::Corridors;
use crate::route::RouteMap;
use crate::world::energy::G;
use crate::world::World;

/// Largest margin kept beyond the hard zones, m (the corridor's widest: the SPSO danger
/// band of a 1 m UAV plus a turn's corner cut).
const MAX_MARGIN_M: f64 = 20.0;

/// How far a straightened piece may stray from the way it replaces, m.
const STRAIGHTEN_M: f64 = 15.0;

/// Extra cost of a step steeper than the climb limit, in lengths of the step at the cruise
/// energy per metre.
const STEEP_FACTOR: f64 = 10.0;

/// One guide per UAV (the same for UAVs sharing a start and size), empty when no way exists.
#[must_use]
pub fn route_guides(world: &World) -> Corridors {
    let spec = world.spec();
    let goal = world.goal_at(crate::world::DEPARTURE).truncate();
    let mut out: Corridors = Vec::new();
    let mut done: Vec<(DVec2, f64, usize)> = Vec::new();
    for (i, u) in spec.uavs.iter().enumerate() {
        let start = world.start(i).truncate();
        if let Some(&(_, _, j)) = done.iter().find(|(s, z, _)| *s == start && *z == u.size) {
            let g = out[j].clone();
            out.push(g);
            continue;
        }
        done.push((start, u.size, i));
        let map = RouteMap::new(&spec.map, &spec.threats, u.size);
        let Some(widest) = map.widest_margin(start, goal, 2.0 * MAX_MARGIN_M) else {
            out.push(Vec::new());
            continue;
        };
        let margin = (0.5 * widest).min(MAX_MARGIN_M);
        let model = &spec.energy.model;
        let per_metre = model.power(u.cruise_speed, u.payload_kg) / u.cruise_speed.max(1e-3);
        let per_climb = model.mass(u.payload_kg) * G;
        let steep = u.max_climb_deg.to_radians().tan();
        let ground = |p: DVec2| world.terrain().height(p.x, p.y);
        let step = |a: DVec2, b: DVec2| {
            let d = a.distance(b);
            let rise = ground(b) - ground(a);
            let mut c = d * per_metre + rise.max(0.0) * per_climb;
            if rise.abs() > steep * d {
                c += STEEP_FACTOR * d * per_metre;
            }
            c
        };
        let way = map.cheapest_way(start, goal, margin, &step, per_metre);
        out.push(way.map_or_else(Vec::new, |w| straighten(&w.points, &map, margin)));
    }
    out
}

/// Keeps from `points` only the vertices needed for straight pieces that keep `margin`
/// beyond the hard zones and stay within [`STRAIGHTEN_M`] of every point they replace.
fn straighten(points: &[DVec2], map: &RouteMap, margin: f64) -> Vec<DVec2> {
    let mut out = vec![points[0]];
    let mut i = 0;
    while i + 1 < points.len() {
        let mut j = i + 1;
        for k in (i + 2..points.len()).rev() {
            let (a, b) = (points[i], points[k]);
            let close = points[i + 1..k]
                .iter()
                .all(|p| distance_to_segment(*p, a, b) <= STRAIGHTEN_M);
            if close && map.segment_clear(a, b, margin) {
                j = k;
                break;
            }
        }
        out.push(points[j]);
        i = j;
    }
    out
}

fn distance_to_segment(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    p.distance(a + ab * t)
}
