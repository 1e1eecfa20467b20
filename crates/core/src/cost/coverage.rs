//! Where a UAV can reach the ground directly at all: the map of direct ground links at one
//! height above the terrain, under the channel's nominal range and the line of sight.
//!
//! Why: an infeasible plan whose UAVs are out of contact leaves an operator with a question
//! the violation list does not answer, whether another path would do or no path can. On the
//! outside benchmark's instance 2 (docs/results.md, "why instance 2 stays infeasible") the
//! only way between the threats runs behind the hills from both ground nodes, and a UAV
//! there has no direct link at any height the altitude band allows; only a relay chain could
//! close that outage. This map shows such places: the top view hatches them and `plan` and
//! `evaluate` say how many outages begin there.
//!
//! A cell is *linked* when its centre, `agl` metres above the ground, lies within the
//! nominal range R0 of a ground node (the median of the shadowed range, no interference) and
//! sees it (the ground node's horizon table, or the sampled line of sight). The shadowing
//! moves the range around R0 over time, so the map says where a direct link is usual, not
//! where it holds at every step.

use glam::DVec3;

use crate::world::World;

/// Most cells along either axis of a coverage map.
const MAX_CELLS: usize = 200;

/// Direct ground links over the map box, one flag per cell.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundCoverage {
    /// Height above ground of the map, metres.
    pub agl: f64,
    /// Range used (the channel's nominal range), metres.
    pub range: f64,
    x0: f64,
    y0: f64,
    cell: f64,
    nx: usize,
    ny: usize,
    /// Row by row from (x0, y0): whether a UAV at the cell's centre links to the ground.
    linked: Vec<bool>,
}

impl GroundCoverage {
    /// The map at height `agl` above ground, in square cells of at least `cell` metres (more
    /// when the box would need over 200 cells along an axis).
    #[must_use]
    pub fn new(world: &World, agl: f64, cell: f64) -> Self {
        let m = &world.spec().map;
        let (wx, wy) = (m.x[1] - m.x[0], m.y[1] - m.y[0]);
        let cell = cell
            .max(wx.max(wy) / MAX_CELLS as f64)
            .max(f64::MIN_POSITIVE);
        let count = |w: f64| ((w / cell).ceil() as usize).clamp(1, MAX_CELLS);
        let (nx, ny) = (count(wx), count(wy));
        let mut linked = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let x = m.x[0] + (i as f64 + 0.5) * cell;
                let y = m.y[0] + (j as f64 + 0.5) * cell;
                let p = DVec3::new(x, y, world.terrain().height(x, y) + agl);
                linked.push(direct_ground_link(world, p));
            }
        }
        Self {
            agl,
            range: world.channel().nominal_range(),
            x0: m.x[0],
            y0: m.y[0],
            cell,
            nx,
            ny,
            linked,
        }
    }

    /// The map at the top of the altitude band (where the line of sight is best), in cells
    /// of [`GroundCoverage::default_cell`].
    #[must_use]
    pub fn at_band_top(world: &World) -> Self {
        Self::new(world, world.spec().map.z_agl[1], Self::default_cell(world))
    }

    /// The cell size reports and figures use: 10 m, or the terrain's cell if coarser.
    #[must_use]
    pub fn default_cell(world: &World) -> f64 {
        let (dx, dy) = world.terrain().cell();
        dx.max(dy).max(10.0)
    }

    /// Whether the cell holding (x, y) links to the ground; points outside the box take the
    /// nearest cell.
    #[must_use]
    pub fn linked(&self, x: f64, y: f64) -> bool {
        let index = |v: f64, origin: f64, n: usize| {
            let k = ((v - origin) / self.cell).floor();
            if k.is_nan() {
                0
            } else {
                k.clamp(0.0, (n - 1) as f64) as usize
            }
        };
        self.linked[index(y, self.y0, self.ny) * self.nx + index(x, self.x0, self.nx)]
    }

    /// Share of the cells without a direct ground link, in [0, 1].
    #[must_use]
    pub fn dead_share(&self) -> f64 {
        let dead = self.linked.iter().filter(|l| !**l).count();
        dead as f64 / self.linked.len().max(1) as f64
    }

    /// Cell size, metres.
    #[must_use]
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// Cells along x and along y.
    #[must_use]
    pub fn shape(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }

    /// The (x, y) corner of the first cell: the map box's minimum.
    #[must_use]
    pub fn origin(&self) -> (f64, f64) {
        (self.x0, self.y0)
    }

    /// The flags row by row (row j at y0 + j cell, column i at x0 + i cell).
    #[must_use]
    pub fn flags(&self) -> &[bool] {
        &self.linked
    }

    /// Every cell as (x0, y0, x1, y1, linked), row by row, for figures.
    pub fn cells(&self) -> impl Iterator<Item = ([f64; 4], bool)> + '_ {
        self.linked.iter().enumerate().map(|(k, l)| {
            let (i, j) = (k % self.nx, k / self.nx);
            let x = self.x0 + i as f64 * self.cell;
            let y = self.y0 + j as f64 * self.cell;
            ([x, y, x + self.cell, y + self.cell], *l)
        })
    }
}

/// Whether a UAV at `p` (absolute altitude) links directly to some ground node under the
/// nominal range and the line of sight (no shadowing, no interference).
#[must_use]
pub fn direct_ground_link(world: &World, p: DVec3) -> bool {
    ground_link_within(world, p, world.channel().nominal_range())
}

/// Whether a UAV at `p` (absolute altitude) is within `range` of some ground node that sees
/// it over the terrain (an infinite range asks for the line of sight alone).
#[must_use]
pub fn ground_link_within(world: &World, p: DVec3, range: f64) -> bool {
    world
        .ground_nodes_at(crate::world::DEPARTURE)
        .iter()
        .any(|g| {
            g.position.distance(p) <= range
                && match &g.horizon {
                    Some(h) => h.visible(p),
                    None => world
                        .channel()
                        .line_of_sight(world.terrain(), g.position, p),
                }
        })
}

/// The stretches of `way` (absolute points) out of direct ground contact within `range`
/// ([`ground_link_within`]), metres each, in flight order: each segment is read at the
/// middles of equal pieces of at most `step` metres, and a stretch runs on across
/// waypoints.
#[must_use]
pub fn blind_stretches(world: &World, way: &[DVec3], step: f64, range: f64) -> Vec<f64> {
    let mut stretches = Vec::new();
    let mut run = 0.0;
    for s in way.windows(2) {
        let length = s[0].distance(s[1]);
        let pieces = (length / step).ceil().max(1.0);
        for k in 0..pieces as usize {
            if ground_link_within(world, s[0].lerp(s[1], (k as f64 + 0.5) / pieces), range) {
                if run > 0.0 {
                    stretches.push(run);
                }
                run = 0.0;
            } else {
                run += length / pieces;
            }
        }
    }
    if run > 0.0 {
        stretches.push(run);
    }
    stretches
}
