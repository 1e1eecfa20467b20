//! Terrain: a regular height grid H(x, y) with a sampling rule, and a block-maximum
//! pyramid so that clearance and line-of-sight tests can skip most samples.
//!
//! Grid node (i, j) stands at x = x0 + i dx, y = y0 + j dy, with j growing northwards
//! (readers flip north-up rasters). Two sampling rules: bilinear (the model's default) and
//! SPSO's nearest cell with MATLAB rounding (half away from zero), for the `spso` cross-check.
//! Outside the grid the height of the nearest edge node is used.

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

#[derive(Debug, Error, PartialEq)]
pub enum TerrainError {
    #[error("terrain grid must be at least 2 x 2 nodes, got {nx} x {ny}")]
    TooSmall { nx: usize, ny: usize },
    #[error("terrain grid has {got} heights, expected {nx} x {ny} = {}", nx * ny)]
    WrongLength { nx: usize, ny: usize, got: usize },
    #[error("terrain cell size must be positive and finite, got dx = {dx}, dy = {dy}")]
    BadCellSize { dx: f64, dy: f64 },
    #[error("terrain height at node (column {i}, row {j}) is not finite: {value}")]
    NotFinite { i: usize, j: usize, value: f64 },
}

/// Side of the square blocks (in nodes) whose maxima are cached.
const BLOCK: usize = 8;

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
    /// Max height over each block of nodes `[bi*BLOCK, (bi+1)*BLOCK]` (inclusive edge, so a
    /// bilinear cell never straddles two blocks without being covered by one).
    block_max: Vec<f64>,
    bnx: usize,
    bny: usize,
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
        let bnx = (nx - 1).div_ceil(BLOCK).max(1);
        let bny = (ny - 1).div_ceil(BLOCK).max(1);
        let mut block_max = vec![f64::NEG_INFINITY; bnx * bny];
        for bj in 0..bny {
            for bi in 0..bnx {
                let mut m = f64::NEG_INFINITY;
                for j in bj * BLOCK..=((bj + 1) * BLOCK).min(ny - 1) {
                    for i in bi * BLOCK..=((bi + 1) * BLOCK).min(nx - 1) {
                        m = m.max(heights[j * nx + i]);
                    }
                }
                block_max[bj * bnx + bi] = m;
            }
        }
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
            block_max,
            bnx,
            bny,
        })
    }

    /// A flat terrain at height `h` covering `[0, width] x [0, height]`.
    pub fn flat(width: f64, height: f64, h: f64) -> Self {
        Self::new(2, 2, (0.0, 0.0), (width, height), vec![h; 4], Sampling::Bilinear)
            .expect("a 2 x 2 flat grid with positive size is valid")
    }

    #[must_use]
    pub fn size(&self) -> (usize, usize) {
        (self.nx, self.ny)
    }
    #[must_use]
    pub fn origin(&self) -> (f64, f64) {
        (self.x0, self.y0)
    }
    #[must_use]
    pub fn cell(&self) -> (f64, f64) {
        (self.dx, self.dy)
    }
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
    #[must_use]
    pub fn min_height(&self) -> f64 {
        self.min
    }
    #[must_use]
    pub fn max_height(&self) -> f64 {
        self.max
    }
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
                // MATLAB round: half away from zero == f64::round.
                let i = u.round().clamp(0.0, (self.nx - 1) as f64) as usize;
                let j = v.round().clamp(0.0, (self.ny - 1) as f64) as usize;
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

    /// An upper bound of the ground height over the rectangle spanned by two points.
    /// Exact to the block resolution; never below the true maximum of either sampling rule.
    #[must_use]
    pub fn max_in_rect(&self, xa: f64, ya: f64, xb: f64, yb: f64) -> f64 {
        let to_block = |w: f64, origin: f64, d: f64, n: usize, bn: usize, round_up: bool| {
            let u = ((w - origin) / d).clamp(0.0, (n - 1) as f64);
            // Nearest sampling may read the node one half cell further out.
            let u = if round_up {
                (u + 0.5).min((n - 1) as f64)
            } else {
                (u - 0.5).max(0.0)
            };
            ((u as usize) / BLOCK).min(bn - 1)
        };
        if !(xa.is_finite() && ya.is_finite() && xb.is_finite() && yb.is_finite()) {
            return self.max;
        }
        let (x_lo, x_hi) = (xa.min(xb), xa.max(xb));
        let (y_lo, y_hi) = (ya.min(yb), ya.max(yb));
        let bi0 = to_block(x_lo, self.x0, self.dx, self.nx, self.bnx, false);
        let bi1 = to_block(x_hi, self.x0, self.dx, self.nx, self.bnx, true);
        let bj0 = to_block(y_lo, self.y0, self.dy, self.ny, self.bny, false);
        let bj1 = to_block(y_hi, self.y0, self.dy, self.ny, self.bny, true);
        let mut m = f64::NEG_INFINITY;
        for bj in bj0..=bj1 {
            let row = &self.block_max[bj * self.bnx..(bj + 1) * self.bnx];
            for v in &row[bi0..=bi1] {
                m = m.max(*v);
            }
        }
        m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
    fn rejects_bad_grids() {
        assert!(matches!(
            Terrain::new(1, 5, (0.0, 0.0), (1.0, 1.0), vec![0.0; 5], Sampling::Bilinear),
            Err(TerrainError::TooSmall { .. })
        ));
        assert!(matches!(
            Terrain::new(2, 2, (0.0, 0.0), (1.0, 1.0), vec![0.0; 3], Sampling::Bilinear),
            Err(TerrainError::WrongLength { .. })
        ));
        assert!(matches!(
            Terrain::new(2, 2, (0.0, 0.0), (1.0, 1.0), vec![0.0, f64::NAN, 0.0, 0.0], Sampling::Bilinear),
            Err(TerrainError::NotFinite { i: 1, j: 0, .. })
        ));
    }
}
