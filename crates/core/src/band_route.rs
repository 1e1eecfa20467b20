//! The route layer in height (issue 46, item 1): ways of waypoints held in the altitude
//! band, every segment within the climb limit, clear of the terrain and of the hard zones;
//! the fewest segments and the least energy such a way needs, at a stated resolution.
//!
//! Why: the planar route layer ([`crate::route`]) knows the threats only. On rugged
//! terrain a way around the threats can still be closed in height: free waypoints must stay
//! 100-200 m above the ground (`map.z_agl`) and every segment climbs or dives at most 45 deg
//! (`max_climb_deg`), so a start on a mountainside may need more waypoints than the scenario
//! gives (`planning.waypoints`) to come down into a valley, and a way over ridges may need
//! more energy than the battery holds. On outside-24 the search spent its whole budget on
//! plans 40 kJ over a 17.9 kJ battery without saying why.
//!
//! The search is constructive, on a grid: places at the centres of `cells` x `cells` cells
//! over the map box, each at `levels` heights evenly over the altitude band, plus the start
//! and UAV0's goal. Two places are joined when the straight segment between them keeps
//! the climb limit, passes outside every hard zone (exactly) and keeps `map.clearance` above
//! the terrain at every `map.clearance_step` (the model's own test,
//! [`crate::world::terrain::Terrain::samples_clear`]). A segment's energy is the cruise energy per metre at the
//! most economical speed times its length plus m g times its rise (docs/model.md,
//! "Energy"; turns and hovering are not counted). Then:
//! - breadth-first search gives the fewest segments from the start to the goal;
//! - Bellman-Ford limited to `planning.waypoints + 1` segments gives the least energy the
//!   scenario's waypoints allow, and the way (repeated waypoints fill the rest);
//! - Dijkstra (Dijkstra 1959, doi:10.1007/BF01386390) gives the least energy at any count;
//! - the same Bellman-Ford with each metre out of direct ground contact weighed as
//!   [`OUT_OF_CONTACT_WEIGHT`] metres of cruise gives the way the `band` start seeds where
//!   the scenario asks for contact ([`contact_way`]): a lone UAV has no relay, and a fleet
//!   on a way behind the hills needs one.
//!
//! What a way found here does not check: the turn limit at its waypoints (the `band` start
//! cuts the corners that break it, [`crate::encoding::sharp_corners`]), and the arcs the
//! flown path turns inside its corners (they may cut a ridge the straight segments clear).
//! What "no way" means: none on this grid; a finer grid, other heights or places off the
//! cell centres may find one. Every answer says its resolution.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::contact_gap::{contact_gap, ContactGap};
use crate::cost::coverage::ground_link_within;
use crate::route::RouteMap;
use crate::world::energy::G;
use crate::world::spec::CommRequirement;
use crate::world::World;

/// Cells along the longer side of the map box (22.5 m on the outside instances' 900 m).
pub const CELLS_ALONG: usize = 40;

/// Heights per place, evenly over the altitude band, both ends included.
pub const LEVELS: usize = 5;

/// What the height search finds from one UAV's start to UAV0's goal.
#[derive(Debug, Clone, PartialEq)]
pub struct BandWays {
    /// The grid's cell, m.
    pub cell: f64,
    /// Heights per place.
    pub levels: usize,
    /// Segments the scenario's free waypoints give (`planning.waypoints + 1`).
    pub allowed_segments: usize,
    /// The fewest segments of any way on the grid (`None`: no way).
    pub fewest_segments: Option<usize>,
    /// The least energy of a way of at most `allowed_segments` segments, J, and that way
    /// (absolute points, start and goal included, no repeats).
    pub within: Option<(f64, Vec<DVec3>)>,
    /// The least energy of a way of any number of segments, J.
    pub least_energy: Option<f64>,
    /// The UAV's usable battery, J.
    pub usable: f64,
    /// How close to the goal (horizontally) the places reachable from the start come, m.
    pub nearest_to_goal: f64,
    /// The altitude band searched (`map.z_agl`), m above ground.
    pub band: [f64; 2],
    /// The climb limit kept, deg.
    pub max_climb_deg: f64,
    /// Where the scenario asks for contact: the way that keeps direct ground contact best
    /// and its longest stretch without it ([`crate::contact_gap`]); `None` otherwise or
    /// when the grid holds no way.
    pub contact: Option<ContactGap>,
}

impl BandWays {
    /// Whether the grid holds a way the scenario's waypoints and the battery allow.
    #[must_use]
    pub fn flyable(&self) -> bool {
        self.within.as_ref().is_some_and(|(e, _)| *e <= self.usable)
    }

    /// One clause for humans, after "in height": what the grid holds, with its resolution.
    #[must_use]
    pub fn sentence(&self) -> String {
        let (band, climb_deg) = (self.band, self.max_climb_deg);
        let grid = format!(
            "{:.1} m cells, {} heights over the band [{}, {}] m above ground, climbs within {} deg",
            self.cell,
            self.levels,
            crate::world::validate::number(band[0]),
            crate::world::validate::number(band[1]),
            crate::world::validate::number(climb_deg)
        );
        let kj = |e: f64| format!("{:.1} kJ", e / 1000.0);
        let usable = kj(self.usable);
        let allowed = self.allowed_segments;
        let what = match (&self.within, self.fewest_segments, self.least_energy) {
            (Some((e, way)), _, _) if *e <= self.usable => format!(
                "a way of {} segments (of the {allowed} the free waypoints give) needs {} of the {usable} usable",
                way.len() - 1,
                kj(*e)
            ),
            (Some((e, _)), _, _) => format!(
                "the least energy of a way within the {allowed} segments the free waypoints give is {}, more than the {usable} usable ({:.2} Wh short)",
                kj(*e),
                (e - self.usable) / 3600.0
            ),
            (None, Some(f), least) => format!(
                "every way needs at least {f} segments, more than the {allowed} the free waypoints give (planning.waypoints = {} would allow it){}",
                f - 1,
                least.map_or(String::new(), |e| format!(
                    ", and the least energy of any is {} against the {usable} usable",
                    kj(e)
                ))
            ),
            (None, None, _) => format!(
                "no way from the start to UGV0 found at this resolution (not a proof that none exists): the places reached come no nearer to UGV0 than {:.0} m",
                self.nearest_to_goal
            ),
        };
        match &self.contact {
            Some(c) => format!("in height ({grid}): {what}; {}", c.sentence()),
            None => format!("in height ({grid}): {what}"),
        }
    }
}

/// The height search for UAV `uav` of `world` on a grid of `cells` cells along the map
/// box's longer side and `levels` heights (at least 2).
#[must_use]
pub fn band_ways(world: &World, uav: usize, cells: usize, levels: usize) -> BandWays {
    let graph = Graph::build(world, uav, cells, levels.max(2), None);
    let spec = world.spec();
    let u = &spec.uavs[uav];
    let allowed = spec.planning.waypoints + 1;
    let goal = graph.points.len() - 1;
    let fewest = graph.fewest_segments(0, goal);
    let within = graph.least_energy_within(0, goal, allowed);
    let least_energy = graph.least_energy(0, goal);
    let reach = graph.reachable(0);
    let g = graph.points[goal].truncate();
    let nearest_to_goal = reach
        .iter()
        .zip(&graph.points)
        .filter(|(r, _)| **r)
        .map(|(_, p)| p.truncate().distance(g))
        .fold(f64::INFINITY, f64::min);
    BandWays {
        cell: graph.cell,
        levels: levels.max(2),
        allowed_segments: allowed,
        fewest_segments: fewest,
        within,
        least_energy,
        usable: crate::cost::energy::usable_energy(world, uav),
        nearest_to_goal,
        band: spec.map.z_agl,
        max_climb_deg: u.max_climb_deg,
        contact: (spec.communication.requirement != CommRequirement::None && fewest.is_some())
            .then(|| contact_gap(world, uav, cells, levels))
            .flatten(),
    }
}

/// Only the least-energy way of [`band_ways`] within the scenario's segments (what the
/// `band` start needs), without the other searches.
#[must_use]
pub fn least_energy_way(
    world: &World,
    uav: usize,
    cells: usize,
    levels: usize,
) -> Option<(f64, Vec<DVec3>)> {
    let graph = Graph::build(world, uav, cells, levels.max(2), None);
    let allowed = world.spec().planning.waypoints + 1;
    graph.least_energy_within(0, graph.points.len() - 1, allowed)
}

/// Longest piece of a segment read as one for [`contact_way`], m (about 3 s of flight at
/// the outside instances' speeds; `communication.max_outage_s` is 5 s).
const CONTACT_STEP_M: f64 = 50.0;

/// At most this many pieces per segment (50 m pieces up to 3.2 km segments, longer pieces
/// beyond), so that a map tens of kilometres wide does not multiply the graph's build time.
const MAX_CONTACT_PIECES: f64 = 64.0;

/// How much a metre flown out of direct ground contact weighs against a metre of cruise
/// in [`contact_way`]. Chosen on the development instances (docs/results.md, "Ways that
/// keep contact").
pub const OUT_OF_CONTACT_WEIGHT: f64 = 1.5;

/// The way within the scenario's segments that least weighs its energy plus
/// [`OUT_OF_CONTACT_WEIGHT`] times the cruise energy of each metre flown out of direct
/// ground contact, with its true energy (J): what the `band` start seeds when the
/// scenario asks for contact.
///
/// Direct contact here is the nominal one: some ground node within the median range R0
/// (`communication.range`) sees the place over its horizon
/// ([`crate::cost::coverage::direct_ground_link`], as the map of places without a ground link); shadowing, interference and relays through other UAVs are left out,
/// so the way is a seed, not a verdict. A segment's share out of contact is read at the
/// middles of equal pieces of at most 50 m (64 pieces at most).
#[must_use]
pub fn contact_way(
    world: &World,
    uav: usize,
    cells: usize,
    levels: usize,
) -> Option<(f64, Vec<DVec3>)> {
    let nominal = world.channel().nominal_range();
    contact_way_weighted(world, uav, cells, levels, OUT_OF_CONTACT_WEIGHT, nominal)
}

/// [`contact_way`] with each metre out of direct ground contact within `range` (infinite:
/// out of every ground node's sight) weighing `weight` metres of cruise.
#[must_use]
pub fn contact_way_weighted(
    world: &World,
    uav: usize,
    cells: usize,
    levels: usize,
    weight: f64,
    range: f64,
) -> Option<(f64, Vec<DVec3>)> {
    let graph = Graph::build(world, uav, cells, levels.max(2), Some((weight, range)));
    let allowed = world.spec().planning.waypoints + 1;
    let (_, way) = graph.least_energy_within(0, graph.points.len() - 1, allowed)?;
    let energy = way.windows(2).map(|w| graph.energy(w[0], w[1])).sum();
    Some((energy, way))
}

/// The energy of flying straight from `a` to `b`, J: `per_metre` J/m of cruise and the
/// UAV's `weight` (N) times the rise.
/// The test that joins two places of the grid: the straight segment keeps the climb limit,
/// passes outside every hard zone (exactly) and keeps `map.clearance` above the terrain at
/// every `map.clearance_step`. Also used off the grid, where a seed cuts a corner
/// ([`crate::encoding::sharp_corners`]).
pub(crate) struct StraightTest<'a> {
    world: &'a World,
    planar: &'a RouteMap,
    tan_climb: f64,
}

impl<'a> StraightTest<'a> {
    /// The test for UAV `uav`, with `planar` the route map of its size.
    pub(crate) fn new(world: &'a World, planar: &'a RouteMap, uav: usize) -> Self {
        let tan_climb = world.spec().uavs[uav].max_climb_deg.to_radians().tan();
        Self {
            world,
            planar,
            tan_climb,
        }
    }

    /// Whether the straight segment a-b (absolute) holds.
    pub(crate) fn holds(&self, a: DVec3, b: DVec3) -> bool {
        let map = &self.world.spec().map;
        let h = a.truncate().distance(b.truncate());
        (b.z - a.z).abs() <= self.tan_climb * h
            && self.planar.segment_clear(a.truncate(), b.truncate(), 0.0)
            && self.world.terrain().samples_clear(
                a,
                b,
                crate::world::terrain::Terrain::samples_on(a, b, map.clearance_step),
                map.clearance,
            )
    }
}

fn straight_energy(per_metre: f64, weight: f64, a: DVec3, b: DVec3) -> f64 {
    per_metre * a.distance(b) + weight * (b.z - a.z).max(0.0)
}

/// Places and the segments between them, with their energies (plus, when asked, a weight
/// on the metres out of direct ground contact).
struct Graph {
    cell: f64,
    /// Cruise energy per metre at the most economical speed, J/m, and the UAV's weight, N.
    per_metre: f64,
    weight: f64,
    /// Absolute points: the start first, the goal last.
    points: Vec<DVec3>,
    /// The segments out of point a are `targets[offsets[a]..offsets[a + 1]]`, with their
    /// joules beside them: compressed rows of narrow types, because the outside instances'
    /// grids hold some ten million segments (the energy's single precision moves a way's
    /// sum by less than a millijoule per kilojoule).
    offsets: Vec<usize>,
    targets: Vec<u32>,
    joules: Vec<f32>,
}

impl Graph {
    /// The graph of UAV `uav`; with `contact` = (weight, range), a segment weighs its energy
    /// plus weight times the cruise energy of its metres out of direct ground contact within
    /// range ([`contact_way_weighted`]).
    fn build(
        world: &World,
        uav: usize,
        cells: usize,
        levels: usize,
        contact: Option<(f64, f64)>,
    ) -> Self {
        let (out_of_contact, range) = contact.unwrap_or((0.0, 0.0));
        let spec = world.spec();
        let u = &spec.uavs[uav];
        let map = &spec.map;
        let planar = RouteMap::with_cells(map, &spec.threats, u.size, cells);
        let cell = planar.cell();
        let start = world.absolute(world.start(uav));
        let goal = world.absolute(world.goal_at(crate::world::DEPARTURE));
        let [lo, hi] = map.z_agl;
        let mut points = vec![start];
        let (nx, ny) = (
            ((map.x[1] - map.x[0]) / cell).ceil().max(1.0) as usize,
            ((map.y[1] - map.y[0]) / cell).ceil().max(1.0) as usize,
        );
        for j in 0..ny {
            for i in 0..nx {
                let p = DVec2::new(
                    (map.x[0] + (i as f64 + 0.5) * cell).min(map.x[1]),
                    (map.y[0] + (j as f64 + 0.5) * cell).min(map.y[1]),
                );
                if !planar.segment_clear(p, p, 0.0) {
                    continue;
                }
                for l in 0..levels {
                    let agl = lo + (hi - lo) * l as f64 / (levels - 1) as f64;
                    points.push(world.absolute(DVec3::new(p.x, p.y, agl)));
                }
            }
        }
        points.push(goal);
        let straight = StraightTest::new(world, &planar, uav);
        let model = &spec.energy.model;
        let (_, per_metre) = crate::world::unreachable::most_economical(
            |v| model.power(v, u.payload_kg) / v,
            u.speed,
        );
        let weight = model.mass(u.payload_kg) * G;
        let joined = |a: DVec3, b: DVec3| straight.holds(a, b);
        let energy = |a: DVec3, b: DVec3| straight_energy(per_metre, weight, a, b);
        let blind = |p: DVec3| !ground_link_within(world, p, range);
        let weigh_contact = out_of_contact > 0.0;
        // Metres of segment a-b out of direct contact, read at the middles of equal
        // pieces of at most CONTACT_STEP_M (MAX_CONTACT_PIECES at most).
        let out_metres = |a: usize, b: usize| {
            if !weigh_contact {
                return 0.0;
            }
            let (pa, pb) = (points[a], points[b]);
            let length = pa.distance(pb);
            let pieces = (length / CONTACT_STEP_M)
                .ceil()
                .clamp(1.0, MAX_CONTACT_PIECES);
            let blind_pieces = (0..pieces as usize)
                .filter(|&k| blind(pa.lerp(pb, (k as f64 + 0.5) / pieces)))
                .count();
            length * blind_pieces as f64 / pieces
        };
        // Each pair is tested once, by its lower index; rows are built in parallel and
        // collected in order, so the graph is the same on any number of threads.
        let rows: Vec<Vec<(u32, f32)>> = (0..points.len())
            .into_par_iter()
            .map(|a| {
                (a + 1..points.len())
                    .filter(|&b| joined(points[a], points[b]))
                    .map(|b| (b as u32, out_metres(a, b) as f32))
                    .collect()
            })
            .collect();
        // Each point's segments: those to lower points (in the order those rows come),
        // then its own row.
        let mut degree = vec![0usize; points.len()];
        for (a, row) in rows.iter().enumerate() {
            degree[a] += row.len();
            for &(b, _) in row {
                degree[b as usize] += 1;
            }
        }
        let mut offsets = Vec::with_capacity(points.len() + 1);
        offsets.push(0);
        for d in &degree {
            offsets.push(offsets[offsets.len() - 1] + d);
        }
        let total = offsets[points.len()];
        let (mut targets, mut joules) = (vec![0u32; total], vec![0f32; total]);
        let mut next = offsets[..points.len()].to_vec();
        for (a, row) in rows.into_iter().enumerate() {
            for (b, out) in row {
                let bi = b as usize;
                let blind_part = out_of_contact * per_metre * f64::from(out);
                for (from, to, slot) in [(a, bi, next[a]), (bi, a, next[bi])] {
                    targets[slot] = to as u32;
                    joules[slot] = (energy(points[from], points[to]) + blind_part) as f32;
                }
                next[a] += 1;
                next[bi] += 1;
            }
        }
        Self {
            cell,
            per_metre,
            weight,
            points,
            offsets,
            targets,
            joules,
        }
    }

    /// The energy of flying straight from `a` to `b`, J.
    fn energy(&self, a: DVec3, b: DVec3) -> f64 {
        straight_energy(self.per_metre, self.weight, a, b)
    }

    /// The segments out of point `a`: (to, joules).
    fn out(&self, a: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let range = self.offsets[a]..self.offsets[a + 1];
        self.targets[range.clone()]
            .iter()
            .zip(&self.joules[range])
            .map(|(&b, &e)| (b as usize, f64::from(e)))
    }

    fn reachable(&self, from: usize) -> Vec<bool> {
        let mut seen = vec![false; self.points.len()];
        seen[from] = true;
        let mut stack = vec![from];
        while let Some(a) = stack.pop() {
            for (b, _) in self.out(a) {
                if !seen[b] {
                    seen[b] = true;
                    stack.push(b);
                }
            }
        }
        seen
    }

    fn fewest_segments(&self, from: usize, to: usize) -> Option<usize> {
        pathfinding::prelude::bfs(&from, |&a| self.out(a).map(|(b, _)| b), |&a| a == to)
            .map(|way| way.len() - 1)
    }

    /// Least energy from `from` to `to` in at most `segments` segments, and the way.
    fn least_energy_within(
        &self,
        from: usize,
        to: usize,
        segments: usize,
    ) -> Option<(f64, Vec<DVec3>)> {
        let n = self.points.len();
        let mut best = vec![f64::INFINITY; n];
        best[from] = 0.0;
        // came[k][b]: the point before b on the best way of at most k + 1 segments.
        let mut came: Vec<Vec<usize>> = Vec::with_capacity(segments);
        for _ in 0..segments {
            let mut next = best.clone();
            let mut before: Vec<usize> = (0..n).collect();
            for a in (0..n).filter(|&a| best[a].is_finite()) {
                for (b, e) in self.out(a) {
                    if best[a] + e < next[b] {
                        next[b] = best[a] + e;
                        before[b] = a;
                    }
                }
            }
            came.push(before);
            best = next;
        }
        if !best[to].is_finite() {
            return None;
        }
        let mut way = vec![self.points[to]];
        let mut at = to;
        for before in came.iter().rev() {
            if before[at] != at {
                at = before[at];
                way.push(self.points[at]);
            }
        }
        way.reverse();
        Some((best[to], way))
    }

    /// Least energy from `from` to `to` at any number of segments (millijoule steps).
    fn least_energy(&self, from: usize, to: usize) -> Option<f64> {
        let mj = |e: f64| (e * 1000.0).round() as u64;
        pathfinding::prelude::dijkstra(
            &from,
            |&a| self.out(a).map(move |(b, e)| (b, mj(e))),
            |&a| a == to,
        )
        .map(|(_, c)| c as f64 / 1000.0)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::world::terrain::{Sampling, Terrain};
    use crate::world::test_spec::one_uav_spec;

    /// One UAV from (100, 500) to (900, 500) over a 1000 m map without threats, with
    /// `waypoints` free waypoints, over `terrain`.
    pub(crate) fn world(waypoints: usize, terrain: Terrain) -> World {
        let mut spec = one_uav_spec("band", Vec::new(), [900.0, 500.0, 150.0]);
        spec.uavs[0].start = [100.0, 500.0, 150.0];
        spec.planning.waypoints = waypoints;
        World::new(spec, terrain).unwrap()
    }

    /// Terrain over a 1000 m square from heights `h(x)` at 10 m nodes.
    pub(crate) fn terrain(h: impl Fn(f64) -> f64) -> Terrain {
        let n = 101;
        let heights = (0..n * n).map(|k| h((k % n) as f64 * 10.0)).collect();
        Terrain::new(n, n, (0.0, 0.0), (10.0, 10.0), heights, Sampling::Bilinear).unwrap()
    }

    #[test]
    fn flat_ground_is_one_segment_at_the_cruise_energy() {
        let b = band_ways(&world(10, Terrain::flat(1000.0, 1000.0, 0.0)), 0, 20, 3);
        assert_eq!(b.fewest_segments, Some(1));
        let (e, way) = b.within.clone().unwrap();
        assert_eq!(way.len(), 2, "{way:?}");
        assert!((b.least_energy.unwrap() - e).abs() < 1e-2);
        assert!(b.flyable());
        assert_eq!(b.nearest_to_goal, 0.0);
    }

    /// A plateau 1700 m up for x < 195, a terrace 1000 m up to x = 495, a plain beyond.
    pub(crate) fn steps(x: f64) -> f64 {
        if x < 195.0 {
            1700.0
        } else if x < 495.0 {
            1000.0
        } else {
            0.0
        }
    }

    #[test]
    fn two_steps_down_need_three_free_waypoints() {
        // Free waypoints are 100-200 m above the ground and segments dive 45 deg at most
        // over a map whose longest segment is 1414 m. From the plateau (1800 m and up) the
        // plain (200 m at most) is out of reach, and so is the goal at 150 m (at most 1030 m
        // away); the terrace (1200 m at most) is out of the start's reach (650 m down, at
        // most 637 m away) but not of other places on the plateau; from the terrace (1100 m
        // and up) the goal is out of reach (at most 864 m away), the plain is not. So:
        // start, plateau, terrace, plain, goal.
        let two = band_ways(&world(2, terrain(steps)), 0, 20, 3);
        assert_eq!(two.fewest_segments, Some(4), "{two:?}");
        assert_eq!(two.allowed_segments, 3);
        assert!(two.within.is_none() && !two.flyable(), "{two:?}");
        let three = band_ways(&world(3, terrain(steps)), 0, 20, 3);
        let (_, way) = three.within.clone().expect("a way in 4 segments");
        assert_eq!(way.len(), 5, "{way:?}");
        let ground = [1700.0, 1700.0, 1000.0, 0.0, 0.0];
        for (p, g) in way.iter().zip(ground).skip(1).take(3) {
            assert!((100.0..=200.0).contains(&(p.z - g)), "{way:?}");
        }
        assert!(way
            .windows(2)
            .all(|s| (s[1].z - s[0].z).abs() <= s[0].truncate().distance(s[1].truncate()) + 1e-9));
    }

    #[test]
    fn a_cliff_higher_than_the_band_and_the_map_allow_closes_every_way() {
        // A plateau 2000 m up for x < 195: every place beyond is at most 200 m up, at least
        // 1900 m below any place on it, farther than the 1414 m diagonal of the map.
        let cliff = |x: f64| if x < 195.0 { 2000.0 } else { 0.0 };
        let b = band_ways(&world(10, terrain(cliff)), 0, 20, 3);
        assert_eq!(b.fewest_segments, None, "{b:?}");
        assert!(b.within.is_none() && b.least_energy.is_none());
        assert!(b.nearest_to_goal > 700.0, "{b:?}");
    }

    /// Metres of `way` out of direct contact by [`contact_way`]'s rule, sampled every 5 m.
    fn blind_metres(w: &World, way: &[DVec3]) -> f64 {
        crate::cost::coverage::blind_stretches(w, way, 5.0, w.channel().nominal_range())
            .iter()
            .sum()
    }

    #[test]
    fn the_contact_way_bends_towards_a_ground_node_the_straight_way_misses() {
        // Range 350 m: the station at the start and UGV0 cover the line's first and last
        // 317 m (horizontally, from 150 m above ground); its middle 166 m is in range of
        // nobody, but a node at (500, 850) covers everything north of y = 533 there.
        let mut spec =
            crate::world::test_spec::one_uav_spec("contact", Vec::new(), [900.0, 500.0, 150.0]);
        spec.uavs[0].start = [100.0, 500.0, 150.0];
        spec.communication.range = 350.0;
        spec.communication.ground_nodes = vec![crate::world::spec::GroundNodeSpec {
            name: "north".into(),
            position: [500.0, 850.0],
            antenna: 2.0,
        }];
        let w = World::new(spec, Terrain::flat(1000.0, 1000.0, 0.0)).unwrap();
        let (cheapest, straight) = least_energy_way(&w, 0, 20, 3).unwrap();
        let (energy, bent) = contact_way(&w, 0, 20, 3).unwrap();
        assert_eq!(straight.len(), 2, "{straight:?}");
        let (before, after) = (blind_metres(&w, &straight), blind_metres(&w, &bent));
        assert!(before > 150.0, "{before}");
        assert!(after < 0.25 * before, "{after} of {before}: {bent:?}");
        assert!(
            energy > cheapest && energy < 1.2 * cheapest,
            "{energy} against {cheapest}"
        );
    }

    #[test]
    fn the_same_graph_on_one_thread_and_on_two() {
        let w = world(10, terrain(steps));
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap()
            .install(|| band_ways(&w, 0, 20, 3));
        let two = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap()
            .install(|| band_ways(&w, 0, 20, 3));
        assert_eq!(one, two);
    }
}
