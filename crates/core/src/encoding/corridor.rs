//! Threat-free corridors: for each start, the shortest planar path to the goal that keeps a
//! margin from every threat's hard zone, for the `corridor` initialisation.
//!
//! Why: on dense threat layouts (the outside benchmark's 15-30 threats, gaps of 36-140 m)
//! a start-goal line with a random bow crosses several cylinders, and the search spends its
//! budget pushing paths out of them one waypoint at a time (20-37 threat violations left
//! after 38,700 evaluations). Seeding from a path that already threads the gaps is the
//! "seed from single-UAV solutions" ingredient of issue 10, with the cheapest single-UAV
//! planner there is: Dijkstra on an 8-connected grid over the map box (Hart, Nilsson,
//! Raphael 1968, doi:10.1109/TSSC.1968.300136, without a heuristic), then shortened by
//! pulling the string (drop every vertex the straight line past it does not need, checked
//! exactly against the circles). Threats are vertical cylinders of unbounded height, so the
//! corridor is planar; terrain is left to the height-above-ground band.
//!
//! Margins are tried from the widest (the SPSO danger band plus a turn's corner cut) down to
//! the hard zone itself, and the first that leaves a way is kept; starts walled in even at
//! the hard zone ([`crate::world::enclosure`]) get no corridor and fall back to the line.

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use glam::DVec2;

use crate::world::World;

/// Cells along the longer side of the map box.
const CELLS_ALONG: f64 = 300.0;

/// SPSO's danger band, in drone sizes (as `cost::spso`).
const DANGER_FACTOR: f64 = 10.0;

/// Extra margin for the corner cut of a flown turn, metres.
const CORNER_CUT: f64 = 10.0;

/// One corridor per UAV, start to goal ([`corridors`]).
pub type Corridors = Vec<Vec<DVec2>>;

/// One corridor per UAV (the same for UAVs sharing a start and size): the polyline from the
/// start to the goal, or empty when none was found.
#[must_use]
pub fn corridors(world: &World) -> Corridors {
    let goal = world.goal_at(crate::world::DEPARTURE).truncate();
    let mut out: Vec<Vec<DVec2>> = Vec::new();
    let mut done: Vec<(DVec2, f64, usize)> = Vec::new();
    for (i, u) in world.spec().uavs.iter().enumerate() {
        let start = world.start(i).truncate();
        if let Some(&(_, _, j)) = done.iter().find(|(s, z, _)| *s == start && *z == u.size) {
            let c = out[j].clone();
            out.push(c);
            continue;
        }
        let circles: Vec<(DVec2, f64)> = world
            .spec()
            .threats
            .iter()
            .map(|t| (DVec2::new(t.x, t.y), t.r + u.size))
            .collect();
        let band = DANGER_FACTOR * u.size;
        let margins = [band + CORNER_CUT, band, 0.5 * band, 0.0];
        let found = margins.iter().find_map(|&m| {
            corridor(
                world.spec().map.x,
                world.spec().map.y,
                &circles,
                m,
                start,
                goal,
            )
        });
        done.push((start, u.size, i));
        out.push(found.unwrap_or_default());
    }
    out
}

/// The shortest grid path from `start` to `goal` in the box keeping `margin` beyond every
/// circle (centre, radius), string-pulled; `None` when the grid has no such way.
#[must_use]
pub fn corridor(
    x: [f64; 2],
    y: [f64; 2],
    circles: &[(DVec2, f64)],
    margin: f64,
    start: DVec2,
    goal: DVec2,
) -> Option<Vec<DVec2>> {
    let (wx, wy) = (x[1] - x[0], y[1] - y[0]);
    if !(wx > 0.0 && wy > 0.0 && wx.is_finite() && wy.is_finite()) {
        return None;
    }
    let cell = wx.max(wy) / CELLS_ALONG;
    let nx = (wx / cell).floor() as usize + 1;
    let ny = (wy / cell).floor() as usize + 1;
    // Grid nodes at the cell corners x0 + i cell (clamped into the box).
    let node = |i: usize, j: usize| {
        DVec2::new(
            (x[0] + i as f64 * cell).min(x[1]),
            (y[0] + j as f64 * cell).min(y[1]),
        )
    };
    let clear = |p: DVec2| {
        circles
            .iter()
            .all(|&(c, r)| p.distance_squared(c) >= (r + margin) * (r + margin))
    };
    let index_of = |p: DVec2| {
        let i = (((p.x - x[0]) / cell).round().max(0.0) as usize).min(nx - 1);
        let j = (((p.y - y[0]) / cell).round().max(0.0) as usize).min(ny - 1);
        j * nx + i
    };
    let (from, to) = (index_of(start), index_of(goal));
    let free: Vec<bool> = (0..nx * ny)
        .map(|k| k == from || k == to || clear(node(k % nx, k / nx)))
        .collect();
    let mut dist = vec![f64::INFINITY; nx * ny];
    let mut prev = vec![usize::MAX; nx * ny];
    let mut heap = BinaryHeap::new();
    dist[from] = 0.0;
    heap.push(Entry(0.0, from));
    while let Some(Entry(d, k)) = heap.pop() {
        if k == to {
            break;
        }
        if d > dist[k] {
            continue;
        }
        let (i, j) = (k % nx, k / nx);
        for (di, dj) in crate::route::NEIGHBOURS {
            let (di, dj) = (i64::from(di), i64::from(dj));
            let (ni, nj) = (i as i64 + di, j as i64 + dj);
            if ni < 0 || nj < 0 || ni >= nx as i64 || nj >= ny as i64 {
                continue;
            }
            let n = nj as usize * nx + ni as usize;
            if !free[n] {
                continue;
            }
            let step = if di != 0 && dj != 0 {
                std::f64::consts::SQRT_2
            } else {
                1.0
            };
            let nd = d + step * cell;
            if nd < dist[n] {
                dist[n] = nd;
                prev[n] = k;
                heap.push(Entry(nd, n));
            }
        }
    }
    if !dist[to].is_finite() {
        return None;
    }
    let mut cells = vec![to];
    while let Some(&k) = cells.last() {
        if k == from {
            break;
        }
        cells.push(prev[k]);
    }
    cells.reverse();
    let mut points: Vec<DVec2> = cells.iter().map(|&k| node(k % nx, k / nx)).collect();
    points[0] = start;
    if let Some(last) = points.last_mut() {
        *last = goal;
    }
    Some(pull_string(&points, circles, margin))
}

/// Keeps from `points` only the vertices a straight line past them would need: from each
/// kept vertex, the farthest later one reachable by a segment that keeps the margin.
fn pull_string(points: &[DVec2], circles: &[(DVec2, f64)], margin: f64) -> Vec<DVec2> {
    let mut out = vec![points[0]];
    let mut i = 0;
    while i + 1 < points.len() {
        let mut j = i + 1;
        for k in (i + 2..points.len()).rev() {
            if segment_clear(points[i], points[k], circles, margin) {
                j = k;
                break;
            }
        }
        out.push(points[j]);
        i = j;
    }
    out
}

/// Whether segment a-b keeps `margin` beyond every circle.
fn segment_clear(a: DVec2, b: DVec2, circles: &[(DVec2, f64)], margin: f64) -> bool {
    let ab = b - a;
    let len2 = ab.length_squared();
    circles.iter().all(|&(c, r)| {
        let t = if len2 > 0.0 {
            ((c - a).dot(ab) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (a + ab * t).distance_squared(c) >= (r + margin) * (r + margin)
    })
}

/// A heap entry ordered by smallest distance first.
#[derive(PartialEq)]
struct Entry(f64, usize);

impl Eq for Entry {}

impl PartialOrd for Entry {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Entry {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

/// `n` points along polyline `p` (start and end excluded) that include every interior vertex
/// of `p` when there are at most `n` of them, the rest spread evenly over the segments by
/// length (largest remainder); more vertices than points: `n` points at equal shares of the
/// length. Keeping the corners keeps the chords between waypoints on the corridor.
#[must_use]
pub fn resample(p: &[DVec2], n: usize) -> Vec<DVec2> {
    let corners = p.len().saturating_sub(2);
    if p.len() < 2 || corners > n {
        return (1..=n)
            .map(|k| point_at_share(p, k as f64 / (n + 1) as f64))
            .collect();
    }
    let lengths: Vec<f64> = p.windows(2).map(|w| w[0].distance(w[1])).collect();
    let total: f64 = lengths.iter().sum();
    let spare = n - corners;
    // Points strictly inside each segment: the floor of its share, then the largest
    // remainders (ties to the earlier segment).
    let share: Vec<f64> = lengths
        .iter()
        .map(|l| {
            if total > 0.0 {
                spare as f64 * l / total
            } else {
                0.0
            }
        })
        .collect();
    let mut inside: Vec<usize> = share.iter().map(|s| s.floor() as usize).collect();
    let mut order: Vec<usize> = (0..lengths.len()).collect();
    order.sort_by(|&a, &b| (share[b] - share[b].floor()).total_cmp(&(share[a] - share[a].floor())));
    let missing = spare - inside.iter().sum::<usize>();
    for &k in order.iter().take(missing) {
        inside[k] += 1;
    }
    let mut out = Vec::with_capacity(n);
    for (k, w) in p.windows(2).enumerate() {
        let q = inside[k];
        for m in 1..=q {
            out.push(w[0] + (w[1] - w[0]) * (m as f64 / (q + 1) as f64));
        }
        if k + 2 < p.len() {
            out.push(w[1]);
        }
    }
    out
}

/// The point at share `t` (0 to 1) of the length of polyline `p`.
#[must_use]
pub fn point_at_share(p: &[DVec2], t: f64) -> DVec2 {
    let total: f64 = p.windows(2).map(|w| w[0].distance(w[1])).sum();
    let mut left = t.clamp(0.0, 1.0) * total;
    for w in p.windows(2) {
        let l = w[0].distance(w[1]);
        if left <= l && l > 0.0 {
            return w[0] + (w[1] - w[0]) * (left / l);
        }
        left -= l;
    }
    p.last().copied().unwrap_or(DVec2::ZERO)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_corridor_goes_around_a_threat_on_the_line_and_keeps_the_margin() {
        let circles = [(DVec2::new(500.0, 500.0), 100.0)];
        let (s, g) = (DVec2::new(100.0, 100.0), DVec2::new(900.0, 900.0));
        let c = corridor([0.0, 1000.0], [0.0, 1000.0], &circles, 20.0, s, g).unwrap();
        assert_eq!(c[0], s);
        assert_eq!(*c.last().unwrap(), g);
        for w in c.windows(2) {
            assert!(segment_clear(w[0], w[1], &circles, 20.0 - 1e-9), "{c:?}");
        }
        // Pulled: a handful of vertices, and not much longer than the way round the circle
        // (two tangents and an arc: about 1,190 m at radius 120).
        assert!(c.len() <= 8, "{c:?}");
        let length: f64 = c.windows(2).map(|w| w[0].distance(w[1])).sum();
        assert!(length > s.distance(g) && length < 1250.0, "{length}");
    }

    #[test]
    fn a_closed_wall_has_no_corridor_and_a_gap_has_one() {
        let wall: Vec<_> = (0..11)
            .map(|k| (DVec2::new(k as f64 * 100.0, 500.0), 60.0))
            .collect();
        let (s, g) = (DVec2::new(100.0, 100.0), DVec2::new(900.0, 900.0));
        assert!(corridor([0.0, 1000.0], [0.0, 1000.0], &wall, 0.0, s, g).is_none());
        let gap: Vec<_> = wall.iter().copied().filter(|(c, _)| c.x != 500.0).collect();
        let c = corridor([0.0, 1000.0], [0.0, 1000.0], &gap, 5.0, s, g).unwrap();
        for w in c.windows(2) {
            assert!(segment_clear(w[0], w[1], &gap, 5.0 - 1e-9));
        }
        assert!(corridor([0.0, 1000.0], [0.0, 1000.0], &gap, 50.0, s, g).is_none());
    }

    #[test]
    fn resampling_keeps_every_corner_and_spreads_the_rest_by_length() {
        let p = [
            DVec2::ZERO,
            DVec2::new(300.0, 0.0),
            DVec2::new(300.0, 100.0),
        ];
        let r = resample(&p, 4);
        assert_eq!(r.len(), 4);
        assert!(r.contains(&DVec2::new(300.0, 0.0)));
        // 3 spare points over 300 m and 100 m: 2.25 and 0.75, so 2 (+1 largest remainder: the
        // second, 0.75 > 0.25) -> 2 on the first segment, 1 on the second.
        assert_eq!(
            r,
            vec![
                DVec2::new(100.0, 0.0),
                DVec2::new(200.0, 0.0),
                DVec2::new(300.0, 0.0),
                DVec2::new(300.0, 50.0)
            ]
        );
        // More corners than points: equal shares.
        assert_eq!(resample(&p, 0), Vec::<DVec2>::new());
        assert_eq!(
            resample(&[DVec2::ZERO, DVec2::new(4.0, 0.0)], 3)[1],
            DVec2::new(2.0, 0.0)
        );
    }

    #[test]
    fn points_at_a_share_of_the_length() {
        let p = [DVec2::ZERO, DVec2::new(10.0, 0.0), DVec2::new(10.0, 10.0)];
        assert_eq!(point_at_share(&p, 0.0), DVec2::ZERO);
        assert_eq!(point_at_share(&p, 0.25), DVec2::new(5.0, 0.0));
        assert_eq!(point_at_share(&p, 0.75), DVec2::new(10.0, 5.0));
        assert_eq!(point_at_share(&p, 1.0), DVec2::new(10.0, 10.0));
    }
}
