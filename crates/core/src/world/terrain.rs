//! Terrain: a regular height grid H(x, y) with a sampling rule, and a block-maximum
//! pyramid so that clearance and line-of-sight tests can skip most samples.
//!
//! Grid node (i, j) stands at x = x0 + i dx, y = y0 + j dy, with j growing northwards
//! (readers flip north-up rasters). Two sampling rules: bilinear (the model's default) and
//! SPSO's nearest cell with MATLAB rounding (half away from zero), for the `spso` cross-check.
//! Outside the grid the height of the nearest edge node is used.

use std::hash::Hasher as _;

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// How heights between grid nodes are obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum Sampling {
    /// Bilinear interpolation between the four surrounding nodes.
    #[default]
    Bilinear,
    /// SPSO's `H(round(y), round(x))`: nearest node, ties rounded away from zero.
    NearestMatlab,
}

/// Why a height grid was refused.
#[derive(Debug, Error, PartialEq)]
pub enum TerrainError {
    /// The grid has fewer than 2 nodes along x or y.
    #[error("terrain grid must be at least 2 x 2 nodes, got {nx} x {ny}")]
    TooSmall {
        /// Nodes along x.
        nx: usize,
        /// Nodes along y.
        ny: usize,
    },
    /// The number of heights is not `nx * ny`.
    #[error("terrain grid has {got} heights, expected {nx} x {ny} = {}", nx * ny)]
    WrongLength {
        /// Nodes along x.
        nx: usize,
        /// Nodes along y.
        ny: usize,
        /// Heights given.
        got: usize,
    },
    /// A cell size is zero, negative or not finite.
    #[error("terrain cell size must be positive and finite, got dx = {dx}, dy = {dy}")]
    BadCellSize {
        /// Cell size along x, m.
        dx: f64,
        /// Cell size along y, m.
        dy: f64,
    },
    /// A height is NaN or infinite.
    #[error("terrain height at node (column {i}, row {j}) is not finite: {value}")]
    NotFinite {
        /// Column of the node.
        i: usize,
        /// Row of the node.
        j: usize,
        /// The height found there.
        value: f64,
    },
}

/// A validated height grid.
#[derive(Debug, Clone)]
pub struct Terrain {
    nx: usize,
    ny: usize,
    x0: f64,
    y0: f64,
    dx: f64,
    dy: f64,
    heights: Vec<f64>,
    sampling: Sampling,
    min: f64,
    max: f64,
    /// Max pyramid: level l cell (i, j) holds the maximum over nodes
    /// [i 2^l, (i + 1) 2^l] x [j 2^l, (j + 1) 2^l] (edges included, so every bilinear cell
    /// lies inside one cell of every level). Level 0 cells are the bilinear cells.
    pyramid: Vec<MaxLevel>,
}

#[derive(Debug, Clone)]
struct MaxLevel {
    nx: usize,
    ny: usize,
    max: Vec<f64>,
}

impl Terrain {
    /// Builds a terrain from row-major heights (`heights[j * nx + i]`, row j at y0 + j dy).
    pub fn new(
        nx: usize,
        ny: usize,
        origin: (f64, f64),
        cell: (f64, f64),
        heights: Vec<f64>,
        sampling: Sampling,
    ) -> Result<Self, TerrainError> {
        if nx < 2 || ny < 2 {
            return Err(TerrainError::TooSmall { nx, ny });
        }
        if heights.len() != nx * ny {
            return Err(TerrainError::WrongLength {
                nx,
                ny,
                got: heights.len(),
            });
        }
        let (dx, dy) = cell;
        if !(dx > 0.0 && dy > 0.0 && dx.is_finite() && dy.is_finite()) {
            return Err(TerrainError::BadCellSize { dx, dy });
        }
        if let Some(k) = heights.iter().position(|h| !h.is_finite()) {
            return Err(TerrainError::NotFinite {
                i: k % nx,
                j: k / nx,
                value: heights[k],
            });
        }
        let min = heights.iter().copied().fold(f64::INFINITY, f64::min);
        let max = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let pyramid = build_pyramid(nx, ny, &heights);
        Ok(Self {
            nx,
            ny,
            x0: origin.0,
            y0: origin.1,
            dx,
            dy,
            heights,
            sampling,
            min,
            max,
            pyramid,
        })
    }

    /// A flat terrain at height `h` covering `[0, width] x [0, height]`.
    pub fn flat(width: f64, height: f64, h: f64) -> Self {
        Self::new(
            2,
            2,
            (0.0, 0.0),
            (width, height),
            vec![h; 4],
            Sampling::Bilinear,
        )
        .expect("a 2 x 2 flat grid with positive size is valid")
    }

    /// Nodes along x and along y.
    #[must_use]
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    /// Position (x0, y0) of node (0, 0), m.
    #[must_use]
    pub fn origin(&self) -> (f64, f64) {
        (self.x0, self.y0)
    }
    /// Node spacing (dx, dy), m.
    #[must_use]
    pub fn cell(&self) -> (f64, f64) {
        (self.dx, self.dy)
    }
    /// How heights between nodes are obtained.
    #[must_use]
    pub fn sampling(&self) -> Sampling {
        self.sampling
    }
    /// Extent covered by the grid nodes: (x_min, y_min, x_max, y_max).
    #[must_use]
    pub fn extent(&self) -> (f64, f64, f64, f64) {
        (
            self.x0,
            self.y0,
            self.x0 + (self.nx - 1) as f64 * self.dx,
            self.y0 + (self.ny - 1) as f64 * self.dy,
        )
    }
    /// Lowest node height, m.
    #[must_use]
    pub fn min_height(&self) -> f64 {
        self.min
    }
    /// Highest node height, m.
    #[must_use]
    pub fn max_height(&self) -> f64 {
        self.max
    }
    /// A 64-bit FNV-1a hash of the grid (size, origin, cell and every height's bits) as 16
    /// hex digits: plan files record it so a plan is not evaluated on other terrain by
    /// mistake.
    #[must_use]
    pub fn fingerprint(&self) -> String {
        let (nx, ny) = self.size();
        let (ox, oy) = self.origin();
        let (cx, cy) = self.cell();
        let mut h = fnv::FnvHasher::default();
        let words = [
            nx as u64,
            ny as u64,
            ox.to_bits(),
            oy.to_bits(),
            cx.to_bits(),
            cy.to_bits(),
        ];
        for w in words
            .into_iter()
            .chain(self.heights().iter().map(|v| v.to_bits()))
        {
            h.write(&w.to_le_bytes());
        }
        format!("{:016x}", h.finish())
    }

    /// Node heights, row-major (`heights[j * nx + i]`), m.
    #[must_use]
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// Height of grid node (i, j) (0-based, row j at y0 + j dy).
    #[must_use]
    pub fn node(&self, i: usize, j: usize) -> f64 {
        self.heights[j * self.nx + i]
    }

    /// Ground height at (x, y) by the terrain's sampling rule.
    #[must_use]
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let u = (x - self.x0) / self.dx;
        let v = (y - self.y0) / self.dy;
        match self.sampling {
            Sampling::Bilinear => self.bilinear(u, v),
            Sampling::NearestMatlab => {
                let i = nearest_node(u, self.nx);
                let j = nearest_node(v, self.ny);
                self.node(i, j)
            }
        }
    }

    fn bilinear(&self, u: f64, v: f64) -> f64 {
        let u = if u.is_nan() { 0.0 } else { u };
        let v = if v.is_nan() { 0.0 } else { v };
        let u = u.clamp(0.0, (self.nx - 1) as f64);
        let v = v.clamp(0.0, (self.ny - 1) as f64);
        let i = (u as usize).min(self.nx - 2);
        let j = (v as usize).min(self.ny - 2);
        let fu = u - i as f64;
        let fv = v - j as f64;
        let k = j * self.nx + i;
        let h00 = self.heights[k];
        let h10 = self.heights[k + 1];
        let h01 = self.heights[k + self.nx];
        let h11 = self.heights[k + self.nx + 1];
        let a = h00 + (h10 - h00) * fu;
        let b = h01 + (h11 - h01) * fu;
        a + (b - a) * fv
    }

    /// An upper bound of the ground height over the rectangle spanned by two points, never
    /// below the true maximum under either sampling rule. Four look-ups in the max pyramid,
    /// at the finest level where the rectangle spans at most two cells per axis.
    #[must_use]
    pub fn max_in_rect(&self, xa: f64, ya: f64, xb: f64, yb: f64) -> f64 {
        if !(xa.is_finite() && ya.is_finite() && xb.is_finite() && yb.is_finite()) {
            return self.max;
        }
        // Cell range at level 0; nearest sampling may read a node half a cell further out.
        let cells = |a: f64, b: f64, origin: f64, d: f64, n: usize| {
            let last = (n - 2) as f64;
            // Clamped into [0, last] first, truncation is floor (and NaN becomes 0 as
            // before): no libm call on the hot path.
            let lo = ((a.min(b) - origin) / d - 0.5).clamp(0.0, last) as usize;
            let hi = ((a.max(b) - origin) / d + 0.5).clamp(0.0, last) as usize;
            (lo, hi)
        };
        let (mut i0, mut i1) = cells(xa, xb, self.x0, self.dx, self.nx);
        let (mut j0, mut j1) = cells(ya, yb, self.y0, self.dy, self.ny);
        let mut level = 0;
        while (i1 - i0 > 1 || j1 - j0 > 1) && level + 1 < self.pyramid.len() {
            level += 1;
            i0 >>= 1;
            i1 >>= 1;
            j0 >>= 1;
            j1 >>= 1;
        }
        let l = &self.pyramid[level];
        let mut m = f64::NEG_INFINITY;
        for j in j0..=j1.min(l.ny - 1) {
            for i in i0..=i1.min(l.nx - 1) {
                m = m.max(l.max[j * l.nx + i]);
            }
        }
        m
    }
}

impl Terrain {
    /// Whether the straight line a-b (absolute altitudes) stays more than `margin` above the
    /// ground, resolved to `step` metres horizontally.
    ///
    /// Recursive bisection: a piece whose lower end is above every pyramid cell of its
    /// bounding box (plus margin) is clear; otherwise its midpoint is tested and both halves
    /// recurse until pieces are shorter than `step`. Most pieces are accepted at once, so a
    /// long segment costs a few look-ups instead of one per sample.
    #[must_use]
    pub fn segment_clears(&self, a: glam::DVec3, b: glam::DVec3, margin: f64, step: f64) -> bool {
        // Non-finite ends never clear; the depth bound only matters for absurd inputs
        // (2^40 halvings resolve any finite segment far below a millimetre).
        a.is_finite() && b.is_finite() && self.clears(a, b, margin, step, 40)
    }

    /// Samples of segment a-b in a clearance check every `step` metres: the points
    /// `a.lerp(b, i / n)`, i = 0..=n, with n = ceil(horizontal length / step) (at least 1).
    #[must_use]
    pub fn samples_on(a: glam::DVec3, b: glam::DVec3, step: f64) -> usize {
        ((a.truncate().distance(b.truncate()) / step).ceil() as usize).max(1)
    }

    /// Whether every sample `a.lerp(b, i / n)`, i = 0..=n, is at least `min_clearance`
    /// above the ground: the verdict of testing each sample, found faster. A range of samples
    /// whose lower end is above the pyramid's bound over its box plus `min_clearance` is
    /// clear at once (every sample of it lies in that box, since lerp is monotone in its
    /// parameter, and no higher than the ground under it allows); other ranges are halved
    /// down to three samples, which are tested one by one.
    #[must_use]
    pub fn samples_clear(
        &self,
        a: glam::DVec3,
        b: glam::DVec3,
        n: usize,
        min_clearance: f64,
    ) -> bool {
        let n = n.max(1);
        self.sample_range_clears(a, b, n, (0, n), min_clearance)
    }

    /// [`Terrain::samples_clear`] over samples `i0..=i1` of `n` (recursion depth log2 n, no
    /// allocation: it runs inside every evaluation).
    fn sample_range_clears(
        &self,
        a: glam::DVec3,
        b: glam::DVec3,
        n: usize,
        (i0, i1): (usize, usize),
        min_clearance: f64,
    ) -> bool {
        let at = |i: usize| a.lerp(b, i as f64 / n as f64);
        let (p0, p1) = (at(i0), at(i1));
        if p0.is_finite()
            && p1.is_finite()
            && p0.z.min(p1.z) - min_clearance > self.max_in_rect(p0.x, p0.y, p1.x, p1.y)
        {
            return true;
        }
        if i1 - i0 <= 2 {
            return (i0..=i1).all(|i| {
                let q = at(i);
                q.z - self.height(q.x, q.y) >= min_clearance
            });
        }
        let mid = i0 + (i1 - i0) / 2;
        self.sample_range_clears(a, b, n, (i0, mid), min_clearance)
            && self.sample_range_clears(a, b, n, (mid, i1), min_clearance)
    }

    /// Calls `not_clear(s)` for each segment s of the polyline `points` (from `points[s]` to
    /// `points[s + 1]`) of which some sample of a clearance check every `step` metres
    /// ([`Terrain::samples_on`]) is less than `min_clearance` above the ground, in order: the
    /// verdicts of testing every sample of every segment, found faster.
    ///
    /// A run of segments whose lowest point is above the pyramid's bound over the run's
    /// bounding box plus `min_clearance` is clear at once (that bound is never below the
    /// ground at any point of the box); runs that fail are halved down to single segments,
    /// which [`Terrain::samples_clear`] decides. The arcs of a flown path are many short
    /// chords, so most of a path clears in a few look-ups.
    pub fn for_each_segment_not_clear(
        &self,
        points: &[glam::DVec3],
        min_clearance: f64,
        step: f64,
        not_clear: &mut impl FnMut(usize),
    ) {
        self.run_not_clear(points, 0, min_clearance, step, not_clear);
    }

    fn run_not_clear(
        &self,
        points: &[glam::DVec3],
        first: usize,
        min_clearance: f64,
        step: f64,
        not_clear: &mut impl FnMut(usize),
    ) {
        match points.len() {
            0 | 1 => {}
            2 => {
                let (a, b) = (points[0], points[1]);
                if !self.samples_clear(a, b, Self::samples_on(a, b, step), min_clearance) {
                    not_clear(first);
                }
            }
            len => {
                let (mut lo, mut hi) = (points[0], points[0]);
                let mut finite = true;
                for p in points {
                    finite &= p.is_finite();
                    lo = lo.min(*p);
                    hi = hi.max(*p);
                }
                if finite && lo.z - min_clearance > self.max_in_rect(lo.x, lo.y, hi.x, hi.y) {
                    return;
                }
                let mid = len / 2;
                self.run_not_clear(&points[..=mid], first, min_clearance, step, not_clear);
                self.run_not_clear(&points[mid..], first + mid, min_clearance, step, not_clear);
            }
        }
    }

    fn clears(&self, a: glam::DVec3, b: glam::DVec3, margin: f64, step: f64, depth: u32) -> bool {
        if a.z.min(b.z) - margin > self.max_in_rect(a.x, a.y, b.x, b.y) {
            return true;
        }
        if depth == 0 || (b - a).truncate().length() <= step {
            return true;
        }
        let m = a.lerp(b, 0.5);
        m.z - margin > self.height(m.x, m.y)
            && self.clears(a, m, margin, step, depth - 1)
            && self.clears(m, b, margin, step, depth - 1)
    }
}

/// Builds the max pyramid of a validated grid.
fn build_pyramid(nx: usize, ny: usize, h: &[f64]) -> Vec<MaxLevel> {
    let (cx, cy) = (nx - 1, ny - 1);
    let mut base = Vec::with_capacity(cx * cy);
    for j in 0..cy {
        for i in 0..cx {
            let k = j * nx + i;
            base.push(h[k].max(h[k + 1]).max(h[k + nx]).max(h[k + nx + 1]));
        }
    }
    let mut levels = vec![MaxLevel {
        nx: cx,
        ny: cy,
        max: base,
    }];
    while levels.last().is_some_and(|l| l.nx > 1 || l.ny > 1) {
        let prev = levels.last().expect("at least one level");
        let (px, py) = (prev.nx, prev.ny);
        let (qx, qy) = (px.div_ceil(2), py.div_ceil(2));
        let mut max = Vec::with_capacity(qx * qy);
        for j in 0..qy {
            for i in 0..qx {
                let mut m = f64::NEG_INFINITY;
                for jj in 2 * j..(2 * j + 2).min(py) {
                    for ii in 2 * i..(2 * i + 2).min(px) {
                        m = m.max(prev.max[jj * px + ii]);
                    }
                }
                max.push(m);
            }
        }
        levels.push(MaxLevel {
            nx: qx,
            ny: qy,
            max,
        });
    }
    levels
}

/// The node nearest to grid coordinate `u` on an axis of `count` nodes, by MATLAB's
/// `round` (half away from zero, as `f64::round`), clamped to the grid; NaN gives 0.
/// Clamping first and rounding the clamped value by its integer part gives the same node as
/// `u.round().clamp(..)` (the fraction `u - trunc(u)` is exact for u >= 0, Sterbenz), without
/// a call to libm's `round`.
fn nearest_node(u: f64, count: usize) -> usize {
    let u = u.clamp(0.0, (count - 1) as f64);
    let i = u as usize;
    if u - i as f64 >= 0.5 {
        i + 1
    } else {
        i
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_node_is_matlabs_round_clamped_to_the_grid() {
        let by_round = |u: f64, count: usize| u.round().clamp(0.0, (count - 1) as f64) as usize;
        let mut values = vec![
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            -0.5,
            -0.49,
            0.0,
            0.5,
            0.49999999999999994,
            1.5,
            2.5,
            8.5,
            8.9,
            9.0,
            9.4,
            9.5,
            1e300,
        ];
        let mut u = -3.0;
        while u < 13.0 {
            values.push(u);
            values.push(f64::from_bits(u.to_bits() + 1));
            u += 0.125;
        }
        for u in values {
            assert_eq!(nearest_node(u, 10), by_round(u, 10), "u = {u}");
        }
    }

    fn ramp() -> Terrain {
        // h = 2 x + 3 y on a 1 m grid, 40 x 30 nodes.
        let (nx, ny) = (40, 30);
        let h = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| 2.0 * i as f64 + 3.0 * j as f64))
            .collect();
        Terrain::new(nx, ny, (0.0, 0.0), (1.0, 1.0), h, Sampling::Bilinear).unwrap()
    }

    #[test]
    fn bilinear_reproduces_a_plane() {
        let t = ramp();
        for &(x, y) in &[(0.0, 0.0), (3.25, 7.5), (38.9, 28.1), (12.0, 0.3)] {
            assert!((t.height(x, y) - (2.0 * x + 3.0 * y)).abs() < 1e-9);
        }
    }

    #[test]
    fn outside_the_grid_uses_the_edge() {
        let t = ramp();
        assert!((t.height(-5.0, 2.0) - 6.0).abs() < 1e-9);
        assert!((t.height(100.0, 0.0) - 78.0).abs() < 1e-9);
    }

    #[test]
    fn nearest_matlab_rounds_half_away_from_zero() {
        let (nx, ny) = (4, 2);
        let h = vec![0.0, 1.0, 2.0, 3.0, 10.0, 11.0, 12.0, 13.0];
        let t = Terrain::new(nx, ny, (1.0, 1.0), (1.0, 1.0), h, Sampling::NearestMatlab).unwrap();
        assert_eq!(t.height(1.5, 1.0), 1.0); // u = 0.5 rounds to 1
        assert_eq!(t.height(2.49, 1.0), 1.0);
        assert_eq!(t.height(2.0, 1.5), 11.0);
    }

    #[test]
    fn block_max_bounds_every_sample() {
        let t = ramp();
        let m = t.max_in_rect(3.0, 4.0, 17.0, 9.0);
        assert!(m >= 2.0 * 17.0 + 3.0 * 9.0);
        assert!(m <= t.max_height());
    }

    #[test]
    fn max_in_rect_bounds_a_brute_force_maximum() {
        // A bumpy grid and many rectangles: the bound is never below any sampled height.
        let (nx, ny) = (53, 37);
        let h: Vec<f64> = (0..ny)
            .flat_map(|j| {
                (0..nx).map(move |i| ((i * 7 + j * 13) % 17) as f64 + (i as f64 * 0.3).sin() * 5.0)
            })
            .collect();
        for sampling in [Sampling::Bilinear, Sampling::NearestMatlab] {
            let t = Terrain::new(nx, ny, (2.0, -3.0), (1.5, 2.0), h.clone(), sampling).unwrap();
            for r in 0..200 {
                let f =
                    |k: usize, m: f64| ((r * k * 7919 + k * 104_729) % 1000) as f64 / 1000.0 * m;
                let (xa, xb) = (2.0 + f(1, 80.0), 2.0 + f(2, 80.0));
                let (ya, yb) = (-3.0 + f(3, 75.0), -3.0 + f(5, 75.0));
                let bound = t.max_in_rect(xa, ya, xb, yb);
                for a in 0..=20 {
                    for b in 0..=20 {
                        let x = xa + (xb - xa) * a as f64 / 20.0;
                        let y = ya + (yb - ya) * b as f64 / 20.0;
                        assert!(t.height(x, y) <= bound + 1e-12);
                    }
                }
            }
        }
    }

    #[test]
    fn runs_of_segments_get_the_verdicts_of_every_sample() {
        // A bumpy grid under zig-zag polylines that graze it, some points non-finite.
        let (nx, ny) = (64, 48);
        let h: Vec<f64> = (0..ny)
            .flat_map(|j| {
                (0..nx).map(move |i| ((i * 7 + j * 13) % 17) as f64 + (i as f64 * 0.3).sin() * 5.0)
            })
            .collect();
        let t = Terrain::new(nx, ny, (0.0, 0.0), (2.0, 2.0), h, Sampling::Bilinear).unwrap();
        let (mut clear, mut failing) = (0, 0);
        for r in 0..300_usize {
            let f = |k: usize, m: f64| ((r * k * 7919 + k * 104_729) % 1000) as f64 / 1000.0 * m;
            let n = 2 + r % 40;
            let mut points: Vec<glam::DVec3> = (0..n)
                .map(|k| {
                    let x = 4.0 + f(2 * k + 1, 118.0);
                    let y = 4.0 + f(2 * k + 2, 86.0);
                    glam::DVec3::new(x, y, 6.0 + f(3 * k + 7, 24.0) + (r % 5) as f64 * 3.0)
                })
                .collect();
            if r % 37 == 0 {
                points[n / 2].z = f64::NAN;
            }
            let margin = (r % 3) as f64;
            let step = [1.0, 0.7, 5.0][r % 3];
            let mut found = Vec::new();
            t.for_each_segment_not_clear(&points, margin, step, &mut |s| found.push(s));
            // Every sample tested one by one, as a report's exact check does.
            let expected: Vec<usize> = (0..n - 1)
                .filter(|&s| {
                    let (a, b) = (points[s], points[s + 1]);
                    let k = Terrain::samples_on(a, b, step);
                    !(0..=k).all(|i| {
                        let q = a.lerp(b, i as f64 / k as f64);
                        q.z - t.height(q.x, q.y) >= margin
                    })
                })
                .collect();
            assert_eq!(found, expected, "polyline {r}");
            failing += expected.len();
            clear += n - 1 - expected.len();
        }
        assert!(clear > 500 && failing > 500, "{clear} clear, {failing} not");
    }

    #[test]
    fn segment_clearance_finds_a_thin_spike() {
        let (nx, ny) = (201, 3);
        let mut h = vec![0.0; nx * ny];
        for j in 0..ny {
            h[j * nx + 137] = 100.0;
        }
        let t = Terrain::new(nx, ny, (0.0, 0.0), (1.0, 1.0), h, Sampling::Bilinear).unwrap();
        let a = glam::DVec3::new(0.0, 1.0, 50.0);
        let b = glam::DVec3::new(200.0, 1.0, 50.0);
        assert!(!t.segment_clears(a, b, 10.0, 0.5));
        let high = glam::DVec3::new(200.0, 1.0, 200.0);
        assert!(t.segment_clears(glam::DVec3::new(0.0, 1.0, 200.0), high, 10.0, 0.5));
    }

    #[test]
    fn rejects_bad_grids() {
        assert!(matches!(
            Terrain::new(
                1,
                5,
                (0.0, 0.0),
                (1.0, 1.0),
                vec![0.0; 5],
                Sampling::Bilinear
            ),
            Err(TerrainError::TooSmall { .. })
        ));
        assert!(matches!(
            Terrain::new(
                2,
                2,
                (0.0, 0.0),
                (1.0, 1.0),
                vec![0.0; 3],
                Sampling::Bilinear
            ),
            Err(TerrainError::WrongLength { .. })
        ));
        assert!(matches!(
            Terrain::new(
                2,
                2,
                (0.0, 0.0),
                (1.0, 1.0),
                vec![0.0, f64::NAN, 0.0, 0.0],
                Sampling::Bilinear
            ),
            Err(TerrainError::NotFinite { i: 1, j: 0, .. })
        ));
    }
}
