//! Line of sight from a fixed ground antenna in O(1): a horizon table.
//!
//! Ground nodes never move, yet every communication step asks whether each UAV can see
//! them, and their antennas sit 2 m above the ground, where a sampled line-of-sight test has
//! to look closely. So each ground node gets a table, built once: for each azimuth bin and
//! each distance d = k * step along the bin's central ray, the largest slope
//! (H - z_antenna) / distance of the terrain seen so far. A point p is visible iff its own
//! slope from the antenna exceeds the table entry of the samples nearer than p.
//!
//! This samples the same points as the direct test (every `step` metres) but along the bin's
//! ray instead of the exact bearing. Bins are uniform in the "diamond angle" (a monotonic
//! stand-in for the bearing that needs one division instead of an `atan2`); 4096 of them
//! are at most 0.11 deg wide, so the ray is at most 2 m to the side of the true line at 1 km.
//!
//! The table is megabytes (4096 bins x 140 samples x 4 bytes for a 1 km map), so a look-up
//! is a cache miss more often than not. Each bin's entries never decrease with distance (a
//! running maximum), so a block of `BLOCK` entries lies between its first and last; a
//! coarse table of those two values per block (16 times smaller, it stays in cache) settles
//! most look-ups: a UAV whose slope is above the block's last entry sees the antenna, one at
//! or below its first does not, and only the rest read the full table. The answer is the
//! same bit for bit as reading the full table every time.

use glam::DVec3;

use super::terrain::Terrain;

/// Azimuth bins of a horizon table.
pub const HORIZON_BINS: usize = 4096;

/// Entries of a bin summarised by one entry of the coarse table.
const BLOCK: usize = 16;

/// The horizon table of one ground antenna: per azimuth bin and distance, the largest
/// terrain slope seen from it.
#[derive(Debug, Clone)]
pub struct Horizon {
    origin: DVec3,
    step: f64,
    steps: usize,
    /// Cumulative maximum slope, `steps` entries per bin.
    table: Vec<f32>,
    /// Per bin and block of [`BLOCK`] entries: (first entry, last entry), the bounds of
    /// every entry in the block; `blocks` per bin.
    coarse: Vec<(f32, f32)>,
    blocks: usize,
    /// Per bin: (first entry, last entry), the bounds of the whole bin (32 KB: it stays in
    /// cache and settles a UAV far above or below the bin's terrain without the others).
    bins: Vec<(f32, f32)>,
}

impl Horizon {
    /// Builds the table of an antenna at `origin` (absolute altitude) out to `reach` metres.
    #[must_use]
    pub fn new(terrain: &Terrain, origin: DVec3, reach: f64, step: f64) -> Self {
        let steps = ((reach / step).ceil() as usize).max(1);
        let mut table = Vec::with_capacity(HORIZON_BINS * steps);
        for b in 0..HORIZON_BINS {
            let (c, s) = diamond_direction((b as f64 + 0.5) * 4.0 / HORIZON_BINS as f64);
            let mut best = f64::NEG_INFINITY;
            for k in 1..=steps {
                let d = k as f64 * step;
                let h = terrain.height(origin.x + d * c, origin.y + d * s);
                best = best.max((h - origin.z) / d);
                table.push(best as f32);
            }
        }
        let blocks = steps.div_ceil(BLOCK);
        let coarse = table
            .chunks_exact(steps)
            .flat_map(|bin| bin.chunks(BLOCK).map(|b| (b[0], b[b.len() - 1])))
            .collect();
        let bins = table
            .chunks_exact(steps)
            .map(|bin| (bin[0], bin[steps - 1]))
            .collect();
        Self {
            origin,
            step,
            steps,
            table,
            coarse,
            blocks,
            bins,
        }
    }

    /// Whether `p` (absolute altitude) sees the antenna over the terrain.
    #[must_use]
    pub fn visible(&self, p: DVec3) -> bool {
        let Some((slope, bin, k)) = self.entry_of(p) else {
            return true;
        };
        let (first, last) = self.bins[bin];
        if slope > f64::from(last) {
            return true;
        }
        if slope <= f64::from(first) {
            return false;
        }
        let (low, high) = self.coarse[bin * self.blocks + (k - 1) / BLOCK];
        if slope > f64::from(high) {
            return true;
        }
        if slope <= f64::from(low) {
            return false;
        }
        slope > f64::from(self.table[bin * self.steps + k - 1])
    }

    /// `p`'s slope from the antenna, its bin and the number k >= 1 of samples nearer than
    /// it (its entry is the bin's k-th); `None` when no sample is nearer.
    fn entry_of(&self, p: DVec3) -> Option<(f64, usize, usize)> {
        let dx = p.x - self.origin.x;
        let dy = p.y - self.origin.y;
        let d = (dx * dx + dy * dy).sqrt();
        // Samples strictly nearer than p: k * step < d. Signed casts: one instruction each
        // way where an unsigned one takes several; d / step >= 0 (or NaN, which casts to 0),
        // and a saturated cast lands far above `steps` as an unsigned one would.
        let k = ceil_index(d / self.step) - 1;
        if k <= 0 {
            return None;
        }
        #[allow(clippy::cast_possible_wrap)]
        let last_bin = (HORIZON_BINS - 1) as i64;
        let bin = ((diamond_angle(dx, dy) * 0.25 * HORIZON_BINS as f64) as i64).clamp(0, last_bin);
        #[allow(clippy::cast_sign_loss)]
        Some((
            (p.z - self.origin.z) / d,
            bin as usize,
            (k as usize).min(self.steps),
        ))
    }
}

/// ceil(q) for q >= 0 (saturating at `i64::MAX`; 0 for NaN), without a libm call.
fn ceil_index(q: f64) -> i64 {
    let k = q as i64;
    if (k as f64) < q {
        k.saturating_add(1)
    } else {
        k
    }
}

/// The diamond angle of (dx, dy) in [0, 4): increases with the bearing, one quadrant per unit.
#[must_use]
pub fn diamond_angle(dx: f64, dy: f64) -> f64 {
    if dy >= 0.0 {
        if dx >= 0.0 {
            dy / (dx + dy)
        } else {
            1.0 - dx / (-dx + dy)
        }
    } else if dx < 0.0 {
        2.0 - dy / (-dx - dy)
    } else {
        3.0 + dx / (dx - dy)
    }
}

/// Unit direction (cos, sin) whose diamond angle is `p` in [0, 4).
#[must_use]
pub fn diamond_direction(p: f64) -> (f64, f64) {
    let q = p.floor();
    let f = p - q;
    let (x, y) = match q as i64 {
        0 => (1.0 - f, f),
        1 => (-f, 1.0 - f),
        2 => (f - 1.0, -f),
        _ => (f, f - 1.0),
    };
    let n = (x * x + y * y).sqrt();
    (x / n, y / n)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::terrain::Sampling;
    use std::f64::consts::TAU;

    #[test]
    fn diamond_angle_inverts_and_is_monotonic() {
        let mut last = -1.0;
        for k in 0..400 {
            let theta = k as f64 * TAU / 400.0;
            let p = diamond_angle(theta.cos(), theta.sin());
            assert!(p > last && (0.0..4.0).contains(&p));
            last = p;
            let (c, s) = diamond_direction(p);
            assert!((c - theta.cos()).abs() < 1e-9 && (s - theta.sin()).abs() < 1e-9);
        }
    }

    /// The full table's answer alone, without the coarse bounds.
    fn visible_by_full_table(hz: &Horizon, p: DVec3) -> bool {
        hz.entry_of(p)
            .is_none_or(|(slope, b, k)| slope > f64::from(hz.table[b * hz.steps + k - 1]))
    }

    #[test]
    fn signed_sample_counts_are_the_unsigned_ones() {
        // The entry index as it was computed with unsigned casts.
        fn unsigned(q: f64, steps: usize) -> Option<usize> {
            let k = q as usize;
            let k = if (k as f64) < q {
                k.saturating_add(1)
            } else {
                k
            };
            let k = k.saturating_sub(1);
            (k != 0).then(|| k.min(steps))
        }
        let steps = 140;
        let mut qs = vec![
            0.0, -0.0, 1e-300, 0.5, 1.0, 2.0, 139.0, 140.0, 141.0, 1e18, 1e19,
        ];
        qs.extend([2f64.powi(63), 2f64.powi(64), 1e300, f64::INFINITY, f64::NAN]);
        qs.extend((0..2000).map(|i| i as f64 * 0.0731));
        qs.extend((1..200).flat_map(|i| [f64::from(i).next_down(), f64::from(i).next_up()]));
        for q in qs {
            let k = ceil_index(q) - 1;
            #[allow(clippy::cast_sign_loss)]
            let signed = (k > 0).then(|| (k as usize).min(steps));
            assert_eq!(signed, unsigned(q, steps), "{q}");
        }
    }

    #[test]
    fn coarse_bounds_answer_as_the_full_table() {
        // Hills, a 23-sample ray (blocks of 16 and a short last one), points at every
        // distance and at heights around each entry, exactly on it included.
        let n = 61;
        let h: Vec<f64> = (0..n)
            .flat_map(|j| (0..n).map(move |i| 40.0 * ((i * 3 + j * 5) % 11) as f64))
            .collect();
        let t = Terrain::new(n, n, (0.0, 0.0), (5.0, 5.0), h, Sampling::Bilinear).unwrap();
        let o = DVec3::new(150.0, 150.0, t.height(150.0, 150.0) + 2.0);
        let hz = Horizon::new(&t, o, 225.0, 10.0);
        assert_eq!((hz.steps, hz.blocks), (23, 2));
        let (mut seen, mut hidden, mut settled) = (0, 0, 0);
        for a in 0..97 {
            let ang = a as f64 * TAU / 97.0;
            for r in 0..260 {
                let d = r as f64 + 0.5;
                let (x, y) = (o.x + d * ang.cos(), o.y + d * ang.sin());
                // The bin and sample count depend on (x, y) alone.
                let Some((_, b, k)) = hz.entry_of(DVec3::new(x, y, o.z)) else {
                    continue;
                };
                let entry = f64::from(hz.table[b * hz.steps + k - 1]);
                for dz in [-30.0, -1e-9, 0.0, 1e-9, 30.0] {
                    let p = DVec3::new(x, y, o.z + (entry + dz / d) * d);
                    let full = visible_by_full_table(&hz, p);
                    assert_eq!(hz.visible(p), full, "{p}");
                    let (lo, hi) = hz.coarse[b * hz.blocks + (k - 1) / BLOCK];
                    let slope = (p.z - o.z) / d;
                    settled += usize::from(slope > f64::from(hi) || slope <= f64::from(lo));
                    if full {
                        seen += 1;
                    } else {
                        hidden += 1;
                    }
                }
            }
        }
        // Both answers occur, and the coarse bounds settle some of them on their own.
        assert!(
            seen > 1000 && hidden > 1000 && settled > 1000,
            "{seen} {hidden} {settled}"
        );
    }

    #[test]
    fn agrees_with_sampled_line_of_sight_away_from_grazing_rays() {
        // Rolling hills: compare with the direct sampled test over many points.
        let n = 201;
        let h: Vec<f64> = (0..n)
            .flat_map(|j| {
                (0..n).map(move |i| {
                    60.0 * ((i as f64) * 0.07).sin() * ((j as f64) * 0.05).cos() + 60.0
                })
            })
            .collect();
        let t = Terrain::new(n, n, (0.0, 0.0), (5.0, 5.0), h, Sampling::Bilinear).unwrap();
        let o = DVec3::new(500.0, 500.0, t.height(500.0, 500.0) + 2.0);
        let hz = Horizon::new(&t, o, 1500.0, 10.0);
        let (mut agree, mut total) = (0, 0);
        for a in 0..60 {
            for r in 1..12 {
                let ang = a as f64 * TAU / 60.0 + 0.01;
                let d = r as f64 * 80.0;
                let (x, y) = (o.x + d * ang.cos(), o.y + d * ang.sin());
                let p = DVec3::new(x, y, t.height(x, y) + 40.0 + 10.0 * (r % 3) as f64);
                let direct = (1..(d / 10.0).ceil() as usize).all(|k| {
                    let q = o.lerp(p, k as f64 * 10.0 / d);
                    q.z > t.height(q.x, q.y)
                });
                total += 1;
                agree += usize::from(direct == hz.visible(p));
            }
        }
        // Bins are 0.056-0.112 deg wide: only near-grazing rays may disagree.
        assert!(agree as f64 >= 0.97 * total as f64, "{agree}/{total}");
    }
}
