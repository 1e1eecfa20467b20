//! Starts that threats wall off from the goal: no plan can leave them without entering a
//! hard zone.
//!
//! Why: dense threat layouts (the outside benchmark's 30-threat instances) can close every
//! way out of a start. Each threat alone leaves the start and goal clear, so the per-field
//! checks of [`super::unreachable`] pass, and a search would spend its whole budget to report
//! threat violations the operator could not have told apart from a weak planner.
//!
//! The test is planar: threats are vertical cylinders of unbounded height (hard zone within
//! r + drone size of the axis) and every waypoint stays in the map box, so the flown path (a
//! polyline with arcs inside its corners) stays in the box too. The box is cut into square
//! cells; a cell is *blocked* when it lies wholly inside one hard zone (its farthest corner is
//! inside). A feasible path passes only through cells that are not blocked, and two cells it
//! visits in a row share at least a corner, so if no 8-connected chain of open cells joins the
//! start's cell to the goal's, no feasible path exists. The converse does not hold (a gap
//! narrower than a cell can look open), so the test never claims a goal reachable inside the
//! map box is walled off (a hand-made plan may leave the box, a bounds violation, which the
//! `paper` profile only costs; planners' waypoints stay in it).

use std::collections::BTreeSet;

use super::spec::ScenarioSpec;

/// Cells along the longer side of the map box (about 1 m on the paper's 1 km maps).
const CELLS_ALONG: f64 = 1000.0;

/// The threats (indices into `spec.threats`) that wall the start `start` of a UAV of size
/// `size` off from the goal, or `None` when an open way exists (or start or goal lies outside
/// the map box or inside a hard zone: other checks report those).
#[must_use]
pub fn walling_threats(spec: &ScenarioSpec, start: [f64; 2], size: f64) -> Option<Vec<usize>> {
    let grid = Grid::new(spec, size)?;
    let g = spec.goal.position;
    let to = grid.open_cell([g[0], g[1]])?;
    let from = grid.open_cell(start)?;
    let (seen, walls) = grid.component(from);
    (!seen[to]).then_some(walls)
}

/// For every UAV whose start threats wall off from the goal: (UAV index, walling threats).
/// One flood from the goal per distinct UAV size, and one more per walled-in start.
#[must_use]
pub fn walled_in_starts(spec: &ScenarioSpec) -> Vec<(usize, Vec<usize>)> {
    let g = spec.goal.position;
    let mut out = Vec::new();
    let mut sizes: Vec<f64> = spec.uavs.iter().map(|u| u.size).collect();
    sizes.sort_by(f64::total_cmp);
    sizes.dedup();
    for size in sizes {
        let Some(grid) = Grid::new(spec, size) else {
            continue;
        };
        let Some(to) = grid.open_cell([g[0], g[1]]) else {
            continue;
        };
        let (reached, _) = grid.component(to);
        for (k, u) in spec.uavs.iter().enumerate() {
            if u.size != size {
                continue;
            }
            let Some(from) = grid.open_cell([u.start[0], u.start[1]]) else {
                continue;
            };
            if !reached[from] {
                out.push((k, grid.component(from).1));
            }
        }
    }
    out.sort_by_key(|(k, _)| *k);
    out
}

/// A cell no hard zone holds whole.
const OPEN: u32 = u32::MAX;

/// The map box in cells, each marked with the first threat whose hard zone holds it whole.
struct Grid {
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Per cell: the index of the first threat whose hard zone holds it whole, or [`OPEN`].
    blocked: Vec<u32>,
}

impl Grid {
    fn new(spec: &ScenarioSpec, size: f64) -> Option<Self> {
        let ([x0, x1], [y0, y1]) = (spec.map.x, spec.map.y);
        let (wx, wy) = (x1 - x0, y1 - y0);
        if !(wx > 0.0 && wy > 0.0 && wx.is_finite() && wy.is_finite()) {
            return None;
        }
        let cell = wx.max(wy) / CELLS_ALONG;
        let nx = (wx / cell).ceil().max(1.0) as usize;
        let ny = (wy / cell).ceil().max(1.0) as usize;
        let mut blocked = vec![OPEN; nx * ny];
        for (k, t) in spec.threats.iter().enumerate() {
            let reach = t.r + size;
            if !(reach > 0.0 && reach.is_finite()) {
                continue;
            }
            let span = |c: f64, lo: f64, n: usize| {
                let a = ((c - reach - lo) / cell).floor().max(0.0) as usize;
                let b = (((c + reach - lo) / cell).ceil().max(0.0) as usize).min(n);
                a..b
            };
            for j in span(t.y, y0, ny) {
                let (cy0, cy1) = (y0 + j as f64 * cell, (y0 + (j + 1) as f64 * cell).min(y1));
                let dy = (cy0 - t.y).abs().max((cy1 - t.y).abs());
                for i in span(t.x, x0, nx) {
                    let (cx0, cx1) = (x0 + i as f64 * cell, (x0 + (i + 1) as f64 * cell).min(x1));
                    let dx = (cx0 - t.x).abs().max((cx1 - t.x).abs());
                    let slot = &mut blocked[j * nx + i];
                    if *slot == OPEN && dx * dx + dy * dy < reach * reach {
                        *slot = u32::try_from(k).unwrap_or(OPEN - 1);
                    }
                }
            }
        }
        Some(Self {
            x0,
            x1,
            y0,
            y1,
            cell,
            nx,
            ny,
            blocked,
        })
    }

    /// The open cell holding `p`, or `None` outside the box or in a blocked cell.
    fn open_cell(&self, p: [f64; 2]) -> Option<usize> {
        self.cell_of(p).filter(|&c| self.blocked[c] == OPEN)
    }

    /// The open cells 8-connected to open cell `from`, and the threats of the blocked cells
    /// around them.
    fn component(&self, from: usize) -> (Vec<bool>, Vec<usize>) {
        let mut seen = vec![false; self.blocked.len()];
        let mut walls = BTreeSet::new();
        let mut stack = vec![from];
        seen[from] = true;
        while let Some(c) = stack.pop() {
            let (i, j) = (c % self.nx, c / self.nx);
            let (i0, i1) = (i.saturating_sub(1), (i + 1).min(self.nx - 1));
            let (j0, j1) = (j.saturating_sub(1), (j + 1).min(self.ny - 1));
            for nj in j0..=j1 {
                for ni in i0..=i1 {
                    let n = nj * self.nx + ni;
                    if seen[n] {
                        continue;
                    }
                    if self.blocked[n] == OPEN {
                        seen[n] = true;
                        stack.push(n);
                    } else {
                        walls.insert(self.blocked[n] as usize);
                    }
                }
            }
        }
        (seen, walls.into_iter().collect())
    }

    /// The cell holding point `p`, or `None` outside the box.
    fn cell_of(&self, p: [f64; 2]) -> Option<usize> {
        let inside = (self.x0..=self.x1).contains(&p[0]) && (self.y0..=self.y1).contains(&p[1]);
        inside.then(|| {
            // A point on the far edge belongs to the last cell.
            let i = (((p[0] - self.x0) / self.cell) as usize).min(self.nx - 1);
            let j = (((p[1] - self.y0) / self.cell) as usize).min(self.ny - 1);
            j * self.nx + i
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::spec::UavSpec;
    use crate::world::threat::Threat;

    fn spec(threats: Vec<Threat>) -> ScenarioSpec {
        crate::world::test_spec::one_uav_spec("walls", threats, [900.0, 900.0, 150.0])
    }

    fn threat(x: f64, y: f64, r: f64) -> Threat {
        Threat { x, y, z: 150.0, r }
    }

    /// The first `count` of eight threats of radius 60 on a circle of radius 150 around
    /// (300, 300): neighbours are 115 m apart, so their hard zones (60 + 1) overlap.
    fn ring(count: usize) -> Vec<Threat> {
        (0..count)
            .map(|k| {
                let a = k as f64 * std::f64::consts::FRAC_PI_4;
                threat(300.0 + 150.0 * a.cos(), 300.0 + 150.0 * a.sin(), 60.0)
            })
            .collect()
    }

    #[test]
    fn a_ring_of_threats_walls_the_start_in() {
        let walls = walling_threats(&spec(ring(8)), [300.0, 300.0], 1.0);
        assert_eq!(walls, Some((0..8).collect()));
    }

    #[test]
    fn a_ring_with_a_gap_wider_than_the_uav_is_open() {
        // Seven of the eight: the missing one leaves a gap of about 115 m.
        assert_eq!(walling_threats(&spec(ring(7)), [300.0, 300.0], 1.0), None);
    }

    #[test]
    fn a_wall_from_edge_to_edge_separates_and_a_gap_opens_it() {
        // A row of threats across the map at y = 500, each reaching the next.
        let row = |skip: Option<usize>| {
            (0..11)
                .filter(|&k| Some(k) != skip)
                .map(|k| threat(k as f64 * 100.0, 500.0, 60.0))
                .collect::<Vec<_>>()
        };
        assert_eq!(
            walling_threats(&spec(row(None)), [100.0, 100.0], 1.0),
            Some((0..11).collect())
        );
        assert_eq!(
            walling_threats(&spec(row(Some(5))), [100.0, 100.0], 1.0),
            None
        );
    }

    #[test]
    fn a_gap_a_bigger_uav_cannot_pass_is_closed_for_it_only() {
        // Two threats whose edges are 20 m apart, from the map's west and east edges.
        let s = spec(vec![
            threat(245.0, 500.0, 255.0),
            threat(765.0, 500.0, 245.0),
        ]);
        assert_eq!(walling_threats(&s, [100.0, 100.0], 1.0), None);
        assert_eq!(walling_threats(&s, [100.0, 100.0], 11.0), Some(vec![0, 1]));
    }

    #[test]
    fn starts_inside_a_zone_or_outside_the_box_are_left_to_other_checks() {
        let s = spec(vec![threat(100.0, 100.0, 50.0)]);
        assert_eq!(walling_threats(&s, [100.0, 100.0], 1.0), None);
        assert_eq!(walling_threats(&s, [-5.0, 100.0], 1.0), None);
    }

    #[test]
    fn only_the_walled_in_starts_are_listed_and_the_warning_names_them() {
        let mut s = spec(ring(8));
        let inside = UavSpec {
            start: [300.0, 320.0, 150.0],
            ..UavSpec::default()
        };
        let outside = UavSpec {
            start: [700.0, 100.0, 150.0],
            ..UavSpec::default()
        };
        s.uavs = vec![outside, inside, inside];
        let walled = walled_in_starts(&s);
        assert_eq!(walled.iter().map(|w| w.0).collect::<Vec<_>>(), vec![1, 2]);
        let warnings = crate::world::unreachable::unreachable_feasibility(&s);
        let walls: Vec<_> = warnings
            .iter()
            .filter(|u| u.reason.contains("walled off"))
            .collect();
        assert_eq!(walls.len(), 1, "{warnings:?}");
        assert_eq!(walls[0].field, "uavs[1].start");
        assert!(walls[0].reason.contains("threats [0, 1, 2, 3, 4, 5, 6, 7]"));
        assert!(walls[0].reason.contains("uavs [2]"));
    }
}
