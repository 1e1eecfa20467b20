//! The route layer, first part (issue 46): planar ways from a start to UGV0 around the
//! threats' hard zones, the widest such way, and a lower bound on how far any plan must fly.
//!
//! Why: a search that refines waypoints cannot tell a scenario it has not solved from one
//! that has no solution, and on the outside instances it spent its whole budget on both
//! alike. Threats are vertical cylinders of unbounded height, so whether a way exists around
//! them is a planar question, answered here by A* (Hart, Nilsson, Raphael 1968,
//! doi:10.1109/TSSC.1968.300136; the `pathfinding` crate) on an 8-connected grid over the map
//! box. The answer holds at the grid's resolution, which is stated with it:
//!
//! - **Relaxed grid** (for "no way exists" and for length bounds): a cell is free when its
//!   centre is at least r + size - d/2 from every threat axis (d the cell diagonal), i.e.
//!   the hard zones shrunk by half a diagonal. Every cell that a continuous way outside the
//!   hard zones passes through is then free, so no way on the relaxed grid means no way at
//!   all; and a way of length L in the plane gives a grid way of at most L * 1.0824 + 2 d
//!   (8-connected steps are at most 1 / cos 22.5 deg longer than the straight line, plus a
//!   cell at each end), so grid length / 1.0824 - 2 d is a lower bound on L at this
//!   resolution.
//! - **Margin**: the same search keeping `margin` metres beyond every hard zone; the widest
//!   margin that still leaves a way (bisected to a tenth of a cell) is the half-width of
//!   the widest way through the threat field, beyond the hard zones.

use glam::DVec2;
use pathfinding::prelude::astar;

use crate::world::spec::MapSpec;
use crate::world::Threat;

/// Cells along the longer side of the map box.
pub const CELLS_ALONG: usize = 400;

/// Distinct starts (and UAV sizes) whose ways the route layer searches in a scenario;
/// the others are not searched, and what reports them says so. Each search is a few A*
/// runs on the grid (tens of milliseconds), which a fleet of a hundred UAVs from a hundred
/// starts would repeat a hundred times when a scenario loads (15 s measured at 100).
pub const STARTS_SEARCHED: usize = 8;

/// The 8 neighbours of a grid cell, as index steps.
pub(crate) const NEIGHBOURS: [(i32, i32); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

/// How much longer an 8-connected grid way is at most than the straight line it follows:
/// 1 / cos(22.5 deg).
const OCTILE_STRETCH: f64 = 1.082_392_200_292_394;

/// The plane of one UAV size: the map box and the threats' hard-zone discs.
#[derive(Debug, Clone)]
pub struct RouteMap {
    origin: DVec2,
    cell: f64,
    nx: i32,
    ny: i32,
    /// (axis, hard radius r + size) of every threat.
    discs: Vec<(DVec2, f64)>,
}

/// A way found on the grid: its cell centres from start to goal (the start and the goal
/// themselves at the ends) and its length along them.
#[derive(Debug, Clone, PartialEq)]
pub struct Way {
    /// The way's points, m.
    pub points: Vec<DVec2>,
    /// Its length along the points, m.
    pub length: f64,
}

impl RouteMap {
    /// The plane of the map box `map` and `threats` for a UAV of size `size`, at
    /// [`CELLS_ALONG`] cells along the longer side.
    #[must_use]
    pub fn new(map: &MapSpec, threats: &[Threat], size: f64) -> Self {
        Self::with_cells(map, threats, size, CELLS_ALONG)
    }

    /// [`RouteMap::new`] with `cells` cells along the longer side.
    #[must_use]
    pub fn with_cells(map: &MapSpec, threats: &[Threat], size: f64, cells: usize) -> Self {
        let [x0, x1] = map.x;
        let [y0, y1] = map.y;
        let cell = (x1 - x0).max(y1 - y0) / cells.max(1) as f64;
        #[allow(clippy::cast_possible_truncation)] // at most `cells` + 1
        let count = |extent: f64| (extent / cell).ceil().max(1.0) as i32;
        Self {
            origin: DVec2::new(x0, y0),
            cell,
            nx: count(x1 - x0),
            ny: count(y1 - y0),
            discs: threats
                .iter()
                .map(|t| (DVec2::new(t.x, t.y), t.r + size))
                .collect(),
        }
    }

    /// The grid's cell size, m: the resolution every answer holds at.
    #[must_use]
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// Half the cell diagonal, m.
    fn half_diagonal(&self) -> f64 {
        0.5 * self.cell * std::f64::consts::SQRT_2
    }

    fn centre(&self, (i, j): (i32, i32)) -> DVec2 {
        self.origin
            + DVec2::new(
                (f64::from(i) + 0.5) * self.cell,
                (f64::from(j) + 0.5) * self.cell,
            )
    }

    fn cell_of(&self, p: DVec2) -> (i32, i32) {
        let q = (p - self.origin) / self.cell;
        #[allow(clippy::cast_possible_truncation)] // clamped into the grid
        let clamp = |v: f64, n: i32| (v.floor() as i32).clamp(0, n - 1);
        (clamp(q.x, self.nx), clamp(q.y, self.ny))
    }

    /// Whether the segment a-b keeps `margin` beyond every hard zone.
    #[must_use]
    pub fn segment_clear(&self, a: DVec2, b: DVec2, margin: f64) -> bool {
        let ab = b - a;
        let len2 = ab.length_squared();
        self.discs.iter().all(|(c, r)| {
            let t = if len2 > 0.0 {
                ((*c - a).dot(ab) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (a + ab * t).distance_squared(*c) >= (r + margin).max(0.0).powi(2)
        })
    }

    /// Whether `p` keeps `margin` beyond every hard zone.
    fn clear(&self, p: DVec2, margin: f64) -> bool {
        self.discs
            .iter()
            .all(|(c, r)| p.distance_squared(*c) >= (r + margin).max(0.0).powi(2))
    }

    /// The shortest grid way from `start` to `goal` whose cell centres keep `margin` beyond
    /// every hard zone (a negative margin shrinks them: [`RouteMap::relaxed_way`]), or
    /// `None`. The start's and the goal's cells are taken as free.
    #[must_use]
    pub fn way(&self, start: DVec2, goal: DVec2, margin: f64) -> Option<Way> {
        self.cheapest_way(start, goal, margin, &|a, b| a.distance(b), 1.0)
    }

    /// The grid way from `start` to `goal` keeping `margin` beyond every hard zone whose
    /// summed `step_cost(from, to)` over its steps (between cell centres) is least, or
    /// `None`. `per_metre` must be a lower bound of `step_cost` per metre of the straight
    /// line (it makes A*'s heuristic, which must not overestimate).
    #[must_use]
    pub fn cheapest_way(
        &self,
        start: DVec2,
        goal: DVec2,
        margin: f64,
        step_cost: &dyn Fn(DVec2, DVec2) -> f64,
        per_metre: f64,
    ) -> Option<Way> {
        let (from, to) = (self.cell_of(start), self.cell_of(goal));
        // Costs in thousandths, rounded up: integers, as A* needs a total order.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let milli = |c: f64| (c * 1000.0).ceil().max(0.0) as u64;
        let end = self.centre(to);
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let heuristic = |c: &(i32, i32)| {
            // Rounded down, so it never exceeds a rounded-up cost.
            (self.centre(*c).distance(end) * per_metre * 1000.0)
                .floor()
                .max(0.0) as u64
        };
        let free = |c: (i32, i32)| c == to || self.clear(self.centre(c), margin);
        let (cells, _) = astar(
            &from,
            |&(i, j)| {
                let here = self.centre((i, j));
                let mut next = Vec::with_capacity(8);
                for (di, dj) in NEIGHBOURS {
                    let c = (i + di, j + dj);
                    if c.0 < 0 || c.1 < 0 || c.0 >= self.nx || c.1 >= self.ny || !free(c) {
                        continue;
                    }
                    next.push((c, milli(step_cost(here, self.centre(c)))));
                }
                next
            },
            heuristic,
            |c| *c == to,
        )?;
        let mut points = Vec::with_capacity(cells.len() + 2);
        points.push(start);
        points.extend(
            cells
                .iter()
                .skip(1)
                .take(cells.len().saturating_sub(2))
                .map(|c| self.centre(*c)),
        );
        points.push(goal);
        let length = points.windows(2).map(|w| w[0].distance(w[1])).sum();
        Some(Way { points, length })
    }

    /// [`RouteMap::way`] on the relaxed grid (hard zones shrunk by half a cell diagonal):
    /// `None` proves that no way outside the hard zones exists.
    #[must_use]
    pub fn relaxed_way(&self, start: DVec2, goal: DVec2) -> Option<Way> {
        self.way(start, goal, -self.half_diagonal())
    }

    /// A lower bound on the length of any planar way from `start` to `goal` outside the hard
    /// zones, at this grid's resolution (module doc), never below the straight line; `None`
    /// when there is no way.
    #[must_use]
    pub fn length_lower_bound(&self, start: DVec2, goal: DVec2) -> Option<f64> {
        let way = self.relaxed_way(start, goal)?;
        let bound = way.length / OCTILE_STRETCH - 2.0 * self.cell * std::f64::consts::SQRT_2;
        Some(bound.max(start.distance(goal)))
    }

    /// The widest margin beyond the hard zones that still leaves a way from `start` to
    /// `goal` (the half-width of the widest way through the threats), to a tenth of a cell,
    /// at most `cap`; `None` when there is no way even at the hard zones themselves.
    #[must_use]
    pub fn widest_margin(&self, start: DVec2, goal: DVec2, cap: f64) -> Option<f64> {
        self.way(start, goal, 0.0)?;
        if self.way(start, goal, cap).is_some() {
            return Some(cap);
        }
        let (mut lo, mut hi) = (0.0, cap);
        while hi - lo > 0.1 * self.cell {
            let mid = 0.5 * (lo + hi);
            if self.way(start, goal, mid).is_some() {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(lo)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn map(threats: &[Threat], size: f64) -> RouteMap {
        let map = MapSpec {
            x: [0.0, 400.0],
            y: [0.0, 400.0],
            ..MapSpec::default()
        };
        RouteMap::new(&map, threats, size)
    }

    fn threat(x: f64, y: f64, r: f64) -> Threat {
        Threat { x, y, z: 150.0, r }
    }

    #[test]
    fn an_open_map_has_the_straight_way() {
        let m = map(&[], 1.0);
        let (a, b) = (DVec2::new(20.0, 20.0), DVec2::new(380.0, 380.0));
        let way = m.way(a, b, 0.0).unwrap();
        assert!(
            (way.length - a.distance(b)).abs() < 2.0 * m.cell(),
            "{}",
            way.length
        );
        assert_eq!(m.length_lower_bound(a, b), Some(a.distance(b)));
    }

    #[test]
    fn a_twelve_metre_gap_is_threaded_and_its_width_measured() {
        // A wall across y = 200: discs of hard radius 41 m (40 + size 1) every 80 m overlap,
        // but the two at x = 165 and 259 leave 259 - 165 - 82 = 12 m between their hard
        // zones, from x = 206 to 218.
        let threats: Vec<Threat> = [5.0, 85.0, 165.0, 259.0, 339.0, 419.0]
            .into_iter()
            .map(|x| threat(x, 200.0, 40.0))
            .collect();
        let m = map(&threats, 1.0);
        let (a, b) = (DVec2::new(200.0, 20.0), DVec2::new(200.0, 380.0));
        let way = m.way(a, b, 0.0).expect("the gap is a way");
        // It passes through the gap.
        let at_wall = way
            .points
            .iter()
            .min_by(|p, q| (p.y - 200.0).abs().total_cmp(&(q.y - 200.0).abs()))
            .unwrap();
        assert!(at_wall.x > 206.0 && at_wall.x < 218.0, "{at_wall}");
        let half = m.widest_margin(a, b, 100.0).unwrap();
        assert!((half - 6.0).abs() <= m.cell(), "half-width {half}");
    }

    #[test]
    fn a_walled_in_start_has_no_way_even_relaxed() {
        // Eight discs of hard radius 31 m on a ring of radius 60 m around (200, 200): the
        // chords between neighbours (46 m) are shorter than two radii.
        let ring: Vec<Threat> = (0..8)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::FRAC_PI_4;
                threat(200.0 + 60.0 * a.cos(), 200.0 + 60.0 * a.sin(), 30.0)
            })
            .collect();
        let m = map(&ring, 1.0);
        let (a, b) = (DVec2::new(200.0, 200.0), DVec2::new(380.0, 380.0));
        assert_eq!(m.relaxed_way(a, b), None);
        assert_eq!(m.length_lower_bound(a, b), None);
        assert_eq!(m.widest_margin(a, b, 50.0), None);
    }
}
