//! Terrain operations at real scale: crop a height grid to a region and resample it to
//! another cell size, keeping its frame (a point keeps its coordinates).
//!
//! - [`crop`] keeps the nodes needed to cover the region (snapped outwards to whole cells),
//!   so heights inside the region are unchanged under either sampling rule.
//! - [`resample`] builds a new grid over the same extent; [`Resample::Bilinear`] samples the
//!   old terrain at each new node (a plane stays exactly a plane), [`Resample::Max`] takes
//!   the highest old node within half a new cell of each new node, a conservative choice
//!   when coarsening (clearance is never over-estimated at the new nodes).

use swarmplan_core::world::terrain::{Terrain, TerrainError};
use thiserror::Error;

/// Why [`crop`] or [`resample`] could not make the terrain asked for.
#[derive(Debug, Error)]
pub enum DemOpsError {
    /// A crop range is not finite or not increasing.
    #[error("crop: {axis} range [{lo}, {hi}] must be finite and increasing")]
    BadRange {
        /// The axis, `x` or `y`.
        axis: char,
        /// Lower end of the range, m.
        lo: f64,
        /// Upper end of the range, m.
        hi: f64,
    },
    /// The crop region overlaps the terrain by less than one cell on some axis.
    #[error(
        "crop: region x [{x0}, {x1}], y [{y0}, {y1}] does not overlap the terrain \
         x [{tx0}, {tx1}], y [{ty0}, {ty1}] by at least one cell"
    )]
    Outside {
        /// West edge of the region, m.
        x0: f64,
        /// East edge of the region, m.
        x1: f64,
        /// South edge of the region, m.
        y0: f64,
        /// North edge of the region, m.
        y1: f64,
        /// West edge of the terrain, m.
        tx0: f64,
        /// East edge of the terrain, m.
        tx1: f64,
        /// South edge of the terrain, m.
        ty0: f64,
        /// North edge of the terrain, m.
        ty1: f64,
    },
    /// The resampling cell size (m) is not positive and finite.
    #[error("resample: cell size must be positive and finite, got {0}")]
    BadCell(f64),
    /// The resampling cell size gives fewer than 2 x 2 or more than 100 million nodes.
    #[error(
        "resample: a {cell} m cell gives {nx} x {ny} nodes over {w} x {h} m; expected at \
         least 2 x 2 and at most 100 million nodes"
    )]
    BadSize {
        /// The cell size asked for, m.
        cell: f64,
        /// Nodes along x it would give.
        nx: usize,
        /// Nodes along y it would give.
        ny: usize,
        /// East-west (x) extent of the terrain, m.
        w: f64,
        /// North-south (y) extent of the terrain, m.
        h: f64,
    },
    /// The new height grid is not a valid terrain.
    #[error(transparent)]
    Terrain(#[from] TerrainError),
}

/// The terrain restricted to x in `x`, y in `y` (plus the partial cells at the edges).
pub fn crop(t: &Terrain, x: [f64; 2], y: [f64; 2]) -> Result<Terrain, DemOpsError> {
    for (axis, r) in [('x', x), ('y', y)] {
        if !(r[0].is_finite() && r[1].is_finite() && r[0] < r[1]) {
            return Err(DemOpsError::BadRange {
                axis,
                lo: r[0],
                hi: r[1],
            });
        }
    }
    let (nx, ny) = t.size();
    let (x0, y0) = t.origin();
    let (dx, dy) = t.cell();
    // Node index ranges covering the region, clamped to the grid.
    let span = |lo: f64, hi: f64, o: f64, d: f64, n: usize| -> Option<(usize, usize)> {
        let a = ((lo - o) / d - 1e-9).floor().max(0.0);
        let b = ((hi - o) / d + 1e-9).ceil().min((n - 1) as f64);
        (b >= a + 1.0).then_some((a as usize, b as usize))
    };
    let (tx0, ty0, tx1, ty1) = t.extent();
    let outside = || DemOpsError::Outside {
        x0: x[0],
        x1: x[1],
        y0: y[0],
        y1: y[1],
        tx0,
        tx1,
        ty0,
        ty1,
    };
    let (i0, i1) = span(x[0], x[1], x0, dx, nx).ok_or_else(outside)?;
    let (j0, j1) = span(y[0], y[1], y0, dy, ny).ok_or_else(outside)?;
    let heights: Vec<f64> = (j0..=j1)
        .flat_map(|j| (i0..=i1).map(move |i| (i, j)))
        .map(|(i, j)| t.node(i, j))
        .collect();
    Ok(Terrain::new(
        i1 - i0 + 1,
        j1 - j0 + 1,
        (x0 + i0 as f64 * dx, y0 + j0 as f64 * dy),
        (dx, dy),
        heights,
        t.sampling(),
    )?)
}

/// How [`resample`] computes the new nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Resample {
    /// The old terrain's height at the new node (its own sampling rule).
    #[default]
    Bilinear,
    /// The highest old node within half a new cell (conservative when coarsening).
    Max,
}

/// The terrain on a grid of `cell` metres over the same extent (the last row and column
/// fall on or inside the old edge), same origin and sampling rule.
pub fn resample(t: &Terrain, cell: f64, mode: Resample) -> Result<Terrain, DemOpsError> {
    if !(cell.is_finite() && cell > 0.0) {
        return Err(DemOpsError::BadCell(cell));
    }
    let (x0, y0, x1, y1) = t.extent();
    let (w, h) = (x1 - x0, y1 - y0);
    let count = |len: f64| (len / cell + 1e-9).floor() + 1.0;
    let (cx, cy) = (count(w), count(h));
    if cx < 2.0 || cy < 2.0 || cx * cy > 1e8 {
        return Err(DemOpsError::BadSize {
            cell,
            nx: cx.min(1e9) as usize,
            ny: cy.min(1e9) as usize,
            w,
            h,
        });
    }
    let (nx, ny) = (cx as usize, cy as usize);
    let (onx, ony) = t.size();
    let (dx, dy) = t.cell();
    let sample = |x: f64, y: f64| match mode {
        Resample::Bilinear => t.height(x, y),
        Resample::Max => {
            let lo = |v: f64, o: f64, d: f64| ((v - 0.5 * cell - o) / d - 1e-9).ceil().max(0.0);
            let hi = |v: f64, o: f64, d: f64, n: usize| {
                ((v + 0.5 * cell - o) / d + 1e-9)
                    .floor()
                    .min((n - 1) as f64)
            };
            let (i0, i1) = (lo(x, x0, dx), hi(x, x0, dx, onx));
            let (j0, j1) = (lo(y, y0, dy), hi(y, y0, dy, ony));
            let mut m = t.height(x, y);
            if i1 >= i0 && j1 >= j0 {
                for j in j0 as usize..=j1 as usize {
                    for i in i0 as usize..=i1 as usize {
                        m = m.max(t.node(i, j));
                    }
                }
            }
            m
        }
    };
    let heights: Vec<f64> = (0..ny)
        .flat_map(|j| (0..nx).map(move |i| (i, j)))
        .map(|(i, j)| sample(x0 + i as f64 * cell, y0 + j as f64 * cell))
        .collect();
    Ok(Terrain::new(
        nx,
        ny,
        (x0, y0),
        (cell, cell),
        heights,
        t.sampling(),
    )?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarmplan_core::world::terrain::Sampling;

    /// A plane h = 10 + 0.5 x - 0.25 y on 11 x 6 nodes of 10 x 20 m from (100, 200).
    fn plane() -> Terrain {
        let (nx, ny) = (11, 6);
        let h: Vec<f64> = (0..ny)
            .flat_map(|j| (0..nx).map(move |i| (i, j)))
            .map(|(i, j)| 10.0 + 0.5 * (100.0 + 10.0 * i as f64) - 0.25 * (200.0 + 20.0 * j as f64))
            .collect();
        Terrain::new(nx, ny, (100.0, 200.0), (10.0, 20.0), h, Sampling::Bilinear).unwrap()
    }

    #[test]
    fn crop_keeps_positions_and_heights() {
        let t = plane();
        let c = crop(&t, [125.0, 161.0], [230.0, 290.0]).unwrap();
        assert_eq!(c.origin(), (120.0, 220.0));
        assert_eq!(c.size(), (6, 5)); // x 120..170, y 220..300
        assert_eq!(c.cell(), (10.0, 20.0));
        for (x, y) in [(125.0, 230.0), (161.0, 290.0), (143.3, 251.7)] {
            assert!((c.height(x, y) - t.height(x, y)).abs() < 1e-12);
        }
        // A region larger than the terrain is clamped to it.
        let all = crop(&t, [-1e6, 1e6], [-1e6, 1e6]).unwrap();
        assert_eq!(all.size(), t.size());
        assert_eq!(all.heights(), t.heights());
    }

    #[test]
    fn crop_errors_say_what_is_wrong() {
        let t = plane();
        let e = crop(&t, [10.0, 5.0], [0.0, 1.0]).unwrap_err().to_string();
        assert!(e.contains("x range [10, 5]"), "{e}");
        let e = crop(&t, [0.0, 50.0], [0.0, 1.0]).unwrap_err().to_string();
        assert!(e.contains("does not overlap"), "{e}");
        assert!(crop(&t, [f64::NAN, 1.0], [0.0, 1.0]).is_err());
    }

    #[test]
    fn resampling_a_plane_keeps_the_plane() {
        let t = plane();
        for cell in [3.0, 7.5, 25.0] {
            let r = resample(&t, cell, Resample::Bilinear).unwrap();
            assert_eq!(r.cell(), (cell, cell));
            assert_eq!(r.origin(), t.origin());
            let (_, _, x1, y1) = r.extent();
            assert!(x1 <= 200.0 + 1e-9 && x1 > 200.0 - cell);
            assert!(y1 <= 300.0 + 1e-9 && y1 > 300.0 - cell);
            for (x, y) in [(100.0, 200.0), (133.0, 277.0), (x1, y1)] {
                assert!(
                    (r.height(x, y) - t.height(x, y)).abs() < 1e-9,
                    "{cell} {x} {y}"
                );
            }
        }
    }

    #[test]
    fn max_resampling_never_lowers_the_ground() {
        let t = plane();
        let m = resample(&t, 25.0, Resample::Max).unwrap();
        let b = resample(&t, 25.0, Resample::Bilinear).unwrap();
        assert!(m.heights().iter().zip(b.heights()).all(|(a, b)| a >= b));
        // Node (1, 0) at x = 125 sees old nodes x in [112.5, 137.5]: 120 and 130.
        assert_eq!(m.node(1, 0), 10.0 + 0.5 * 130.0 - 0.25 * 200.0);
    }

    #[test]
    fn resample_errors() {
        let t = plane();
        assert!(resample(&t, 0.0, Resample::Bilinear)
            .unwrap_err()
            .to_string()
            .contains("positive"));
        assert!(resample(&t, 500.0, Resample::Bilinear)
            .unwrap_err()
            .to_string()
            .contains("at least 2 x 2"));
        assert!(resample(&t, 1e-4, Resample::Bilinear).is_err());
    }
}
