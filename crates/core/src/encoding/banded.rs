//! Seeds of the `band` initialisation (issue 46, items 1, 3 and 5): per start, the route
//! layer's way in height ([`crate::band_route`]) that the scenario's free waypoints allow,
//! given to the optimizer as free waypoints with their heights: where the scenario asks
//! for contact, the way that also weighs the metres flown out of direct ground contact
//! ([`crate::band_route::contact_way`]) when its energy fits the battery, else the
//! least-energy way.
//!
//! Why: the `corridor` and `route` starts follow a planar way at one random height above
//! ground, so on rugged terrain the UAV climbs every ridge on it and runs out of battery or
//! breaks the climb limit (outside-2, -6). The height search's way keeps the climb limit,
//! clears the terrain and fits the battery where the grid holds one; the optimizer then
//! only has to smooth its turns and keep contact and separation. A start whose grid holds
//! no such way falls back to its threat-free corridor ([`super::corridor`]).
//!
//! The grid's way does not check the turn limit, so its corners sharper than the limit
//! allows are cut with the spare free waypoints first ([`super::sharp_corners`]); UAVs that
//! share the way fly it in layers of height ([`super::init::sample_band_plan`]).

use glam::{DVec2, DVec3};

use super::corridor::{corridors, Corridors};
use super::sharp_corners::{cut_sharp_corners, CutLimits};
use crate::band_route::{contact_way, least_energy_way, StraightTest, CELLS_ALONG, LEVELS};
use crate::route::{RouteMap, STARTS_SEARCHED};
use crate::world::spec::CommRequirement;
use crate::world::World;

/// Per UAV, the planar guide (for the heading sectors) and the free waypoints
/// (absolute) seeded from its way in height; no waypoints where it has none.
#[derive(Debug, Clone, Default)]
pub struct BandSeeds {
    /// Planar guides, one per UAV (its way's plan view, or its corridor).
    pub guides: Corridors,
    /// Free waypoints per UAV, absolute [x, y, z], empty where the UAV has no way.
    pub waypoints: Vec<Vec<DVec3>>,
}

/// The seeds of `world` (the same for UAVs sharing a start and size).
#[must_use]
pub fn band_seeds(world: &World) -> BandSeeds {
    let spec = world.spec();
    let n = spec.planning.waypoints;
    let [lo, hi] = spec.map.z_agl;
    let mut fallback: Option<Corridors> = None;
    let mut out = BandSeeds::default();
    let mut done: Vec<(DVec2, f64, usize)> = Vec::new();
    for (i, u) in spec.uavs.iter().enumerate() {
        let start = world.start(i).truncate();
        if let Some(&(_, _, j)) = done.iter().find(|(s, z, _)| *s == start && *z == u.size) {
            let (g, w) = (out.guides[j].clone(), out.waypoints[j].clone());
            out.guides.push(g);
            out.waypoints.push(w);
            continue;
        }
        done.push((start, u.size, i));
        // Past the route layer's first starts (a second or so each), the corridor.
        let found = (done.len() <= STARTS_SEARCHED)
            .then(|| way_for(world, i))
            .flatten();
        match found {
            Some((_, way)) if way.len() >= 2 && way.len() <= n + 2 => {
                let height = |q: DVec2| world.terrain().height(q.x, q.y);
                let way = flyable_corners(world, i, &way);
                let points = on_the_way(&way, n, [lo, hi], &height);
                // The guide runs through the seeded waypoints, so that the encoding's
                // heading sectors and move lengths are centred on them.
                let mut plan_view = vec![way[0].truncate()];
                plan_view.extend(points.iter().map(|p| p.truncate()));
                plan_view.push(way[way.len() - 1].truncate());
                out.guides.push(plan_view);
                out.waypoints.push(points);
            }
            _ => {
                let all = fallback.get_or_insert_with(|| corridors(world));
                out.guides.push(all[i].clone());
                out.waypoints.push(Vec::new());
            }
        }
    }
    out
}

/// Per UAV, the climb angle of each move to its seeded free waypoints in the encoding's
/// frame, where heights are above ground (rad; empty where the UAV has no seeds): what the
/// spherical encoding's climb bounds must hold for the seeds to be expressed
/// ([`crate::encoding::spherical::Spherical::along_guides`]).
#[must_use]
pub fn seeded_climbs(world: &World, seeds: &BandSeeds) -> Vec<Vec<f64>> {
    let above_ground = |p: DVec3| p.z - world.terrain().height(p.x, p.y);
    seeds
        .waypoints
        .iter()
        .enumerate()
        .map(|(i, points)| {
            let mut from = world.start(i);
            points
                .iter()
                .map(|&p| {
                    let to = DVec3::new(p.x, p.y, above_ground(p));
                    let climb = (to.z - from.z).atan2(to.truncate().distance(from.truncate()));
                    from = to;
                    climb
                })
                .collect()
        })
        .collect()
}

/// UAV `uav`'s way: where the scenario asks for contact, the one that keeps direct ground
/// contact best within the battery ([`contact_way`]), else the least-energy one.
fn way_for(world: &World, uav: usize) -> Option<(f64, Vec<DVec3>)> {
    if world.spec().communication.requirement != CommRequirement::None {
        if let Some(found) = contact_way(world, uav, CELLS_ALONG, LEVELS) {
            if found.0 <= crate::cost::energy::usable_energy(world, uav) {
                return Some(found);
            }
        }
    }
    least_energy_way(world, uav, CELLS_ALONG, LEVELS)
}

/// `way` with its corners sharper than the turn limit allows cut, with the free waypoints
/// it leaves spare ([`super::sharp_corners`]).
fn flyable_corners(world: &World, uav: usize, way: &[DVec3]) -> Vec<DVec3> {
    let spec = world.spec();
    let u = &spec.uavs[uav];
    let spare = (spec.planning.waypoints + 2).saturating_sub(way.len());
    let planar = RouteMap::with_cells(&spec.map, &spec.threats, u.size, CELLS_ALONG);
    let straight = StraightTest::new(world, &planar, uav);
    let [lo, hi] = spec.map.z_agl;
    let holds = |a: DVec3, b: DVec3| straight.holds(a, b);
    let into_band = |p: DVec3| {
        let ground = world.terrain().height(p.x, p.y);
        DVec3::new(p.x, p.y, p.z.clamp(ground + lo, ground + hi))
    };
    cut_sharp_corners(
        way,
        spare,
        &CutLimits {
            max_turn: u.max_turn_deg.to_radians(),
            turn_radius: u.turn_radius,
            holds: &holds,
            into_band: &into_band,
        },
    )
}

/// Spacing of the places tried along a segment for the extra waypoints, m.
const ALONG_STEP_M: f64 = 5.0;

/// `n` absolute points on `way` (at most `n` interior vertices): its interior vertices,
/// and the rest at even shares of the way's length among the places on its segments whose
/// height above ground lies in `band`, so that the free waypoints, held in the band,
/// fly exactly the way (a point halfway along a segment high over a valley, pulled down
/// into the band, would dive steeper than the climb limit). Where fewer such places exist
/// than points are needed, the rest sit on the way at even shares, clamped later.
fn on_the_way(
    way: &[DVec3],
    n: usize,
    band: [f64; 2],
    height: &dyn Fn(DVec2) -> f64,
) -> Vec<DVec3> {
    let mut along = 0.0;
    let mut corners: Vec<(f64, DVec3)> = Vec::new();
    let mut places: Vec<(f64, DVec3)> = Vec::new();
    for (k, w) in way.windows(2).enumerate() {
        if k > 0 {
            corners.push((along, w[0]));
        }
        let length = w[0].distance(w[1]);
        let steps = (length / ALONG_STEP_M).ceil().max(1.0) as usize;
        for m in 1..steps {
            let t = m as f64 / steps as f64;
            let p = w[0].lerp(w[1], t);
            let agl = p.z - height(p.truncate());
            if agl >= band[0] && agl <= band[1] {
                places.push((along + t * length, p));
            }
        }
        along += length;
    }
    let extra = n.saturating_sub(corners.len());
    let mut chosen: Vec<(f64, DVec3)> = if places.len() >= extra {
        (0..extra)
            .map(|k| places[((k as f64 + 0.5) * places.len() as f64 / extra as f64) as usize])
            .collect()
    } else {
        (0..extra)
            .map(|k| {
                let share = (k + 1) as f64 / (extra + 1) as f64;
                (share * along, point_at(way, share * along))
            })
            .collect()
    };
    chosen.extend(corners);
    chosen.sort_by(|a, b| a.0.total_cmp(&b.0));
    chosen.truncate(n);
    chosen.into_iter().map(|(_, p)| p).collect()
}

/// The point `distance` metres along polyline `way`.
fn point_at(way: &[DVec3], distance: f64) -> DVec3 {
    let mut left = distance;
    for w in way.windows(2) {
        let l = w[0].distance(w[1]);
        if left <= l && l > 0.0 {
            return w[0].lerp(w[1], left / l);
        }
        left -= l;
    }
    way[way.len() - 1]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::band_route::tests::{steps, terrain, world};
    use crate::encoding::init::CORRIDOR_SPREAD;
    use crate::encoding::{EncodingKind, InitKind};
    use crate::planning::PlanningProblem;
    use crate::problem::Problem;
    use crate::rng::rng_from_seed;

    #[test]
    fn seeded_plans_fly_the_way_in_height_within_the_band_and_the_climb_limit() {
        // Two steps down (1700 m, 1000 m, then the plain) with ten free waypoints: the way
        // has long straights high over the lower steps, where a waypoint halfway would have
        // to be pulled down into the band and dive steeper than 45 deg.
        let w = world(10, terrain(steps));
        let seeds = band_seeds(&w);
        assert_eq!(seeds.waypoints[0].len(), 10, "{seeds:?}");
        let p = PlanningProblem::new(&w, EncodingKind::Spherical, InitKind::Band);
        let mut rng = rng_from_seed(7);
        let mut x = vec![0.0; p.dimension()];
        // The way keeps 45 deg; the sideways bow shortens some straights a little (a way at
        // the limit then exceeds it by a fraction of a degree, for the search to settle),
        // where a waypoint pulled into the band would dive at 60 deg and more.
        let tan = (w.spec().uavs[0].max_climb_deg + 1.0).to_radians().tan();
        let goal = w.goal_at(crate::world::DEPARTURE).truncate();
        for _ in 0..20 {
            p.sample_initial(&mut rng, &mut x);
            let plan = p.decode(&x);
            let points: Vec<DVec3> = plan.uavs[0]
                .waypoints
                .iter()
                .map(|&q| w.absolute(q))
                .collect();
            for q in &plan.uavs[0].waypoints[1..11] {
                assert!((100.0..=200.0).contains(&q.z), "{q:?}");
            }
            // Every free waypoint where its seed is, but for the sideways bow (at most 1.5
            // times the corridor's spread): the encoding's climb bounds hold the seeded
            // moves that change height above ground faster than 45 deg.
            let bow = 1.5 * CORRIDOR_SPREAD * w.start(0).truncate().distance(goal) + 1e-6;
            for (q, seed) in plan.uavs[0].waypoints[1..11]
                .iter()
                .zip(&seeds.waypoints[0])
            {
                let off = q.truncate().distance(seed.truncate());
                assert!(off <= bow, "{off} m off, bow {bow} m: {q:?} {seed:?}");
            }
            for s in points.windows(2) {
                let h = s[0].truncate().distance(s[1].truncate());
                assert!((s[1].z - s[0].z).abs() <= tan * h + 1e-6, "{points:?}");
            }
        }
    }

    #[test]
    fn a_fleet_sharing_its_way_flies_it_in_layers() {
        // Five UAVs from one start over flat ground: the way is the straight line at 150 m,
        // so the shifts that keep it in the band span 100 m, five strata of 20 m, each
        // draw in the middle half of its own: every two UAVs at least 10 m apart in height
        // at every free waypoint, in the same order all along.
        let mut spec =
            crate::world::test_spec::one_uav_spec("layers", Vec::new(), [900.0, 500.0, 150.0]);
        spec.uavs[0].start = [100.0, 500.0, 150.0];
        spec.planning.waypoints = 6;
        let lead = spec.uavs[0];
        spec.uavs.extend(std::iter::repeat_n(lead, 4));
        let w = World::new(
            spec,
            crate::world::terrain::Terrain::flat(1000.0, 1000.0, 0.0),
        )
        .unwrap();
        let seeds = band_seeds(&w);
        assert!(seeds.waypoints.iter().all(|p| p == &seeds.waypoints[0]));
        let p = PlanningProblem::new(&w, EncodingKind::Spherical, InitKind::Band);
        let mut rng = rng_from_seed(11);
        let mut x = vec![0.0; p.dimension()];
        let mut orders = std::collections::HashSet::new();
        for _ in 0..20 {
            p.sample_initial(&mut rng, &mut x);
            let plan = p.decode(&x);
            let mut order: Vec<usize> = (0..5).collect();
            order.sort_by(|&a, &b| {
                plan.uavs[a].waypoints[1]
                    .z
                    .total_cmp(&plan.uavs[b].waypoints[1].z)
            });
            for k in 1..=6 {
                let z: Vec<f64> = order.iter().map(|&u| plan.uavs[u].waypoints[k].z).collect();
                assert!(
                    z.windows(2).all(|h| h[1] - h[0] >= 10.0 - 1e-6),
                    "{k}: {z:?}"
                );
            }
            orders.insert(order);
        }
        assert!(orders.len() > 1, "the layers' order is drawn");
    }

    #[test]
    fn extra_waypoints_sit_where_the_way_is_in_the_band() {
        // A straight from 1800 m down to 150 m over 1600 m of plain: in the band only
        // near its end (above ground 0 it is in [100, 200] m for its last 3 %).
        let way = [DVec3::new(0.0, 0.0, 1800.0), DVec3::new(1600.0, 0.0, 150.0)];
        let ground = |q: DVec2| if q.x < 10.0 { 1700.0 } else { 0.0 };
        let points = on_the_way(&way, 4, [100.0, 200.0], &ground);
        assert_eq!(points.len(), 4);
        for p in &points {
            let agl = p.z - ground(p.truncate());
            assert!((100.0..=200.0).contains(&agl), "{points:?}");
        }
        assert!(points.windows(2).all(|w| w[0].x < w[1].x), "{points:?}");
    }
}
