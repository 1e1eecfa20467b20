//! A built-in procedural terrain, deterministic from a seed, for runs without a DEM file.
//!
//! The paper plans over a real DEM (SPSO's Christmas Island tile: 1045 x 879 pixels, 49-296 m).
//! This generator produces terrain of the same character without any file: a sum of random
//! Gaussian hills (broad relief, a few of them negative so valleys form) plus a few octaves
//! of smooth value noise (ridges and gullies at shorter wavelengths), rescaled linearly to
//! `[min_height, max_height]`.
//!
//! Grid: `nx = ceil(width / cell) + 1` nodes along x (likewise y) at exactly `cell` spacing,
//! origin (0, 0), so the grid covers the map box `[0, width] x [0, height]` (it may overhang it
//! by less than one cell). With the defaults that is 210 x 177 nodes at 5 m.
//!
//! Every random number comes from one [`Rng`] seeded with `seed`, drawn in a fixed order, so
//! the same parameters give bit-identical heights (on a given platform: `exp` comes from the
//! platform's libm).

use rand::Rng as _;
use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::terrain::{Sampling, Terrain};
use crate::rng::{rng_from_seed, Rng};

/// Most grid nodes a procedural terrain may have (about 400 MB of heights).
pub const MAX_NODES: usize = 50_000_000;
/// Most Gaussian hills (generation time grows with nodes x hills).
pub const MAX_HILLS: usize = 10_000;

/// Parameters of the procedural terrain.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProceduralParams {
    /// Seed of the generator; the same seed gives the same terrain. Default 1.
    pub seed: u64,
    /// Extent along x (east), metres. Default 1045 (the SPSO DEM's width in pixels).
    pub width: f64,
    /// Extent along y (north), metres. Default 879 (the SPSO DEM's height in pixels).
    pub height: f64,
    /// Grid spacing, metres, the same along x and y. Default 5.
    pub cell: f64,
    /// Lowest ground height after rescaling, metres. Default 50.
    pub min_height: f64,
    /// Highest ground height after rescaling, metres. Default 300.
    pub max_height: f64,
    /// Number of random Gaussian hills (about a quarter of them are valleys). Default 12.
    pub hills: usize,
}

impl ProceduralParams {
    /// The defaults (one place, used by `Default` and serde).
    pub const DEFAULT: Self = Self {
        seed: 1,
        width: 1045.0,
        height: 879.0,
        cell: 5.0,
        min_height: 50.0,
        max_height: 300.0,
        hills: 12,
    };

    /// Grid size (nodes along x, nodes along y) these parameters produce. Meaningful only
    /// for valid parameters.
    #[must_use]
    pub fn grid_size(&self) -> (usize, usize) {
        let n = |extent: f64| (extent / self.cell - 1e-9).ceil().max(1.0) as usize + 1;
        (n(self.width), n(self.height))
    }

    /// Checks every field; the error names the first field that is wrong.
    pub fn validate(&self) -> Result<(), ProceduralError> {
        let positive = |field: &'static str, value: f64| {
            if value > 0.0 && value.is_finite() {
                Ok(())
            } else {
                Err(ProceduralError::NotPositive { field, value })
            }
        };
        positive("width", self.width)?;
        positive("height", self.height)?;
        positive("cell", self.cell)?;
        if !self.min_height.is_finite() {
            return Err(ProceduralError::NotFinite {
                field: "min_height",
                value: self.min_height,
            });
        }
        if !self.max_height.is_finite() {
            return Err(ProceduralError::NotFinite {
                field: "max_height",
                value: self.max_height,
            });
        }
        if self.max_height <= self.min_height {
            return Err(ProceduralError::EmptyHeightRange {
                min: self.min_height,
                max: self.max_height,
            });
        }
        if self.hills > MAX_HILLS {
            return Err(ProceduralError::TooManyHills { hills: self.hills });
        }
        let nx = self.width / self.cell + 2.0;
        let ny = self.height / self.cell + 2.0;
        if nx * ny > MAX_NODES as f64 {
            return Err(ProceduralError::TooManyNodes {
                cell: self.cell,
                nodes: nx * ny,
            });
        }
        Ok(())
    }
}

impl Default for ProceduralParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// What is wrong with a [`ProceduralParams`].
#[derive(Debug, Clone, Error, PartialEq)]
pub enum ProceduralError {
    /// `width`, `height` or `cell` is zero, negative or not finite.
    #[error("procedural terrain: {field} must be positive and finite, got {value}")]
    NotPositive {
        /// Name of the field.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// `min_height` or `max_height` is NaN or infinite.
    #[error("procedural terrain: {field} must be finite, got {value}")]
    NotFinite {
        /// Name of the field.
        field: &'static str,
        /// Its value.
        value: f64,
    },
    /// `max_height` is not above `min_height`.
    #[error("procedural terrain: max_height ({max}) must be greater than min_height ({min})")]
    EmptyHeightRange {
        /// `min_height`, m.
        min: f64,
        /// `max_height`, m.
        max: f64,
    },
    /// More hills than [`MAX_HILLS`].
    #[error("procedural terrain: hills must be at most {MAX_HILLS}, got {hills}")]
    TooManyHills {
        /// Hills asked for.
        hills: usize,
    },
    /// The grid would have more nodes than [`MAX_NODES`].
    #[error(
        "procedural terrain: cell {cell} m gives about {nodes:.0} grid nodes, \
         more than {MAX_NODES}; use a larger cell"
    )]
    TooManyNodes {
        /// Grid spacing, m.
        cell: f64,
        /// Estimated number of grid nodes.
        nodes: f64,
    },
}

/// Generates the terrain, validating the parameters first.
pub fn try_procedural_terrain(params: &ProceduralParams) -> Result<Terrain, ProceduralError> {
    params.validate()?;
    Ok(generate(params))
}

/// Generates the terrain (bilinear sampling, origin (0, 0)).
///
/// # Panics
/// If `params.validate()` fails; use [`try_procedural_terrain`] for parameters read from a
/// user.
#[must_use]
pub fn procedural_terrain(params: &ProceduralParams) -> Terrain {
    match try_procedural_terrain(params) {
        Ok(t) => t,
        Err(e) => panic!("{e}"),
    }
}

/// One Gaussian bump: `amplitude * exp(-|p - centre|^2 / (2 sigma^2))`.
struct Hill {
    cx: f64,
    cy: f64,
    inv_two_sigma2: f64,
    amplitude: f64,
}

/// One octave of value noise: random values on a square lattice, smoothly interpolated.
struct Octave {
    /// Lattice spacing, metres.
    spacing: f64,
    /// Random shift of the lattice so octaves do not share nodes at the origin.
    shift: (f64, f64),
    amplitude: f64,
    lx: usize,
    values: Vec<f64>,
}

impl Octave {
    fn new(rng: &mut Rng, spacing: f64, amplitude: f64, width: f64, height: f64) -> Self {
        let shift = (rng.random::<f64>() * spacing, rng.random::<f64>() * spacing);
        let lx = ((width + spacing) / spacing).ceil() as usize + 2;
        let ly = ((height + spacing) / spacing).ceil() as usize + 2;
        let values = (0..lx * ly)
            .map(|_| rng.random::<f64>() * 2.0 - 1.0)
            .collect();
        Self {
            spacing,
            shift,
            amplitude,
            lx,
            values,
        }
    }

    fn sample(&self, x: f64, y: f64) -> f64 {
        // Quintic fade: continuous slope and curvature across lattice lines, so no creases.
        let fade = |t: f64| t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
        let u = (x + self.shift.0) / self.spacing;
        let v = (y + self.shift.1) / self.spacing;
        let (i, j) = (u.floor(), v.floor());
        let (fu, fv) = (fade(u - i), fade(v - j));
        let k = j as usize * self.lx + i as usize;
        let (a, b) = (self.values[k], self.values[k + 1]);
        let (c, d) = (self.values[k + self.lx], self.values[k + self.lx + 1]);
        let lower = a + (b - a) * fu;
        let upper = c + (d - c) * fu;
        self.amplitude * (lower + (upper - lower) * fv)
    }
}

fn generate(p: &ProceduralParams) -> Terrain {
    let mut rng = rng_from_seed(p.seed);
    let (nx, ny) = p.grid_size();
    let (w, h) = ((nx - 1) as f64 * p.cell, (ny - 1) as f64 * p.cell);
    let scale = w.min(h);

    // Hills: centres may fall a little outside the box so the edges are not all low ground.
    let hills: Vec<Hill> = (0..p.hills)
        .map(|_| {
            let cx = (rng.random::<f64>() * 1.2 - 0.1) * w;
            let cy = (rng.random::<f64>() * 1.2 - 0.1) * h;
            let sigma = scale * (0.06 + 0.18 * rng.random::<f64>());
            let valley = rng.random::<f64>() < 0.25;
            let amplitude = (0.4 + 0.6 * rng.random::<f64>()) * if valley { -0.6 } else { 1.0 };
            Hill {
                cx,
                cy,
                inv_two_sigma2: 1.0 / (2.0 * sigma * sigma),
                amplitude,
            }
        })
        .collect();

    // Value noise: wavelengths from about a third of the map down, amplitude halving
    // per octave (a 1/f-like spectrum, as in real relief).
    let octaves: Vec<Octave> = (0..4)
        .map(|o| {
            let spacing = (scale / 3.0) / f64::from(1u32 << o);
            let amplitude = 0.35 / f64::from(1u32 << o);
            Octave::new(&mut rng, spacing.max(p.cell), amplitude, w, h)
        })
        .collect();

    let mut heights = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        let y = j as f64 * p.cell;
        for i in 0..nx {
            let x = i as f64 * p.cell;
            let mut z = 0.0;
            for hill in &hills {
                let (ddx, ddy) = (x - hill.cx, y - hill.cy);
                z += hill.amplitude * (-(ddx * ddx + ddy * ddy) * hill.inv_two_sigma2).exp();
            }
            for octave in &octaves {
                z += octave.sample(x, y);
            }
            heights.push(z);
        }
    }

    let lo = heights.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = heights.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let span = hi - lo;
    for z in &mut heights {
        *z = if span > 0.0 {
            p.min_height + (*z - lo) / span * (p.max_height - p.min_height)
        } else {
            0.5 * (p.min_height + p.max_height)
        };
    }
    Terrain::new(
        nx,
        ny,
        (0.0, 0.0),
        (p.cell, p.cell),
        heights,
        Sampling::Bilinear,
    )
    .expect("validated parameters give at least 2 x 2 finite heights at a positive cell")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn std_dev(v: &[f64]) -> f64 {
        let n = v.len() as f64;
        let mean = v.iter().sum::<f64>() / n;
        (v.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / n).sqrt()
    }

    #[test]
    fn default_grid_covers_the_spso_extent() {
        let t = procedural_terrain(&ProceduralParams::default());
        assert_eq!(t.size(), (210, 177));
        let (x0, y0, x1, y1) = t.extent();
        assert_eq!((x0, y0), (0.0, 0.0));
        assert!((1045.0..1050.0 + 1e-9).contains(&x1));
        assert!((879.0..884.0 + 1e-9).contains(&y1));
    }

    #[test]
    fn same_seed_is_bit_identical() {
        let p = ProceduralParams::default();
        let a = procedural_terrain(&p);
        let b = procedural_terrain(&p);
        assert!(a
            .heights()
            .iter()
            .zip(b.heights())
            .all(|(x, y)| x.to_bits() == y.to_bits()));
    }

    #[test]
    fn different_seeds_differ() {
        let a = procedural_terrain(&ProceduralParams::default());
        let b = procedural_terrain(&ProceduralParams {
            seed: 2,
            ..ProceduralParams::default()
        });
        let differing = a
            .heights()
            .iter()
            .zip(b.heights())
            .filter(|(x, y)| (*x - *y).abs() > 1.0)
            .count();
        assert!(differing > a.heights().len() / 2, "{differing}");
    }

    #[test]
    fn range_is_respected_and_terrain_is_not_flat() {
        for seed in 0..8 {
            let p = ProceduralParams {
                seed,
                ..ProceduralParams::default()
            };
            let t = procedural_terrain(&p);
            assert!((t.min_height() - 50.0).abs() < 1e-9, "{}", t.min_height());
            assert!((t.max_height() - 300.0).abs() < 1e-9, "{}", t.max_height());
            let sd = std_dev(t.heights());
            assert!(sd > 20.0, "seed {seed}: std dev {sd}");
        }
    }

    #[test]
    fn neighbouring_nodes_change_smoothly() {
        // Real 5 m DEMs rarely step more than a few tens of metres between neighbours.
        let t = procedural_terrain(&ProceduralParams::default());
        let (nx, ny) = t.size();
        let mut worst: f64 = 0.0;
        for j in 0..ny {
            for i in 1..nx {
                worst = worst.max((t.node(i, j) - t.node(i - 1, j)).abs());
            }
        }
        assert!(worst < 25.0, "largest step {worst} m");
    }

    #[test]
    fn default_generation_is_fast() {
        // The target is < 20 ms for the default grid (about 6 ms measured, release build);
        // the bound here is loose so a loaded CI machine does not fail it.
        let p = ProceduralParams::default();
        let start = std::time::Instant::now();
        let runs = 5;
        for _ in 0..runs {
            let _ = procedural_terrain(&p);
        }
        let ms = start.elapsed().as_secs_f64() * 1e3 / f64::from(runs);
        println!("procedural terrain (default): {ms:.2} ms per terrain");
        assert!(ms < 200.0, "{ms} ms");
    }

    #[test]
    fn no_hills_still_gives_relief() {
        let t = procedural_terrain(&ProceduralParams {
            hills: 0,
            ..ProceduralParams::default()
        });
        assert!(std_dev(t.heights()) > 20.0);
    }

    #[test]
    fn validate_names_the_field() {
        let bad = |f: fn(&mut ProceduralParams)| {
            let mut p = ProceduralParams::default();
            f(&mut p);
            p.validate().expect_err("invalid").to_string()
        };
        assert!(bad(|p| p.cell = 0.0).contains("cell"));
        assert!(bad(|p| p.width = f64::NAN).contains("width"));
        assert!(bad(|p| p.height = -1.0).contains("height"));
        assert!(bad(|p| p.max_height = 10.0).contains("max_height"));
        assert!(bad(|p| p.min_height = f64::INFINITY).contains("min_height"));
        assert!(bad(|p| p.hills = MAX_HILLS + 1).contains("hills"));
        assert!(bad(|p| p.cell = 1e-3).contains("cell"));
        assert!(try_procedural_terrain(&ProceduralParams {
            cell: -5.0,
            ..ProceduralParams::default()
        })
        .is_err());
    }

    #[test]
    fn serde_fills_defaults_and_rejects_unknown_fields() {
        let p: ProceduralParams = serde_json::from_str(r#"{"seed": 9}"#).expect("valid");
        assert_eq!(
            p,
            ProceduralParams {
                seed: 9,
                ..ProceduralParams::DEFAULT
            }
        );
        assert!(serde_json::from_str::<ProceduralParams>(r#"{"sead": 9}"#).is_err());
    }

    #[test]
    fn odd_cell_sizes_cover_the_box() {
        let p = ProceduralParams {
            width: 100.0,
            height: 7.0,
            cell: 3.0,
            ..ProceduralParams::default()
        };
        let t = procedural_terrain(&p);
        assert_eq!(t.size(), (35, 4));
        let exact = ProceduralParams {
            width: 100.0,
            height: 10.0,
            cell: 10.0,
            ..ProceduralParams::default()
        };
        assert_eq!(exact.grid_size(), (11, 2));
    }
}
