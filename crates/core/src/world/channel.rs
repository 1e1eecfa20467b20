//! The time-varying radio channel, generated once per scenario from its own seed so that
//! every algorithm and every run sees the same channel.
//!
//! Link a-b is up at time t iff its length is at most R(t, a, b) and (optionally) the straight
//! line a-b clears the terrain. R = R0 * 10^(-X_k / 20) * min(f_a, f_b), where X is
//! Gauss-Markov shadowing in dB, X_0 = sigma z_0, X_{k+1} = rho X_k + sqrt(1 - rho^2) sigma
//! z_{k+1} with rho = exp(-dt / tau) and z standard normal draws from ChaCha8 seeded with
//! `communication.seed`, and f_e = 10^(-I_e / 20) with I_e the summed loss of the windows
//! active at t whose disk holds end e: the link takes the worse end's loss. A loss of X dB
//! shrinks a free-space range by 10^(-X/20). The generator, to the bit: docs/model.md,
//! "Implementation reference".

use glam::DVec3;
use rand_distr::{Distribution, StandardNormal};

use super::spec::{CommSpec, InterferenceSpec};
use super::terrain::Terrain;
use crate::rng::rng_from_seed;

/// Shadowing is generated for this long; later times reuse the last value. Missions of the
/// built-in scenarios last about 70 s.
pub const CHANNEL_HORIZON_S: f64 = 3600.0;

/// The radio channel of a scenario: shadowing, interference windows and line-of-sight
/// settings, from which each link's range at a time follows.
#[derive(Debug, Clone)]
pub struct Channel {
    range: f64,
    step: f64,
    /// R0 * 10^(-X(t_k)/20) at t_k = k * step.
    range_at_step: Vec<f64>,
    /// X(t_k) in dB (kept for figures and reports).
    shadowing_db: Vec<f64>,
    interference: Vec<InterferenceSpec>,
    /// 10^(-loss/20) of each window.
    interference_factors: Vec<f64>,
    line_of_sight: bool,
    los_step: f64,
}

impl Channel {
    /// Generates the channel of `spec`: its shadowing series over [`CHANNEL_HORIZON_S`], from
    /// the spec's seed.
    #[must_use]
    pub fn new(spec: &CommSpec) -> Self {
        let step = spec.time_step;
        let n = (CHANNEL_HORIZON_S / step).ceil() as usize + 1;
        let mut rng = rng_from_seed(spec.seed);
        let rho = (-step / spec.shadowing_tau_s).exp();
        let innovation = (1.0 - rho * rho).sqrt() * spec.shadowing_sigma_db;
        let first: f64 = StandardNormal.sample(&mut rng);
        let mut x = spec.shadowing_sigma_db * first;
        let mut shadowing_db = Vec::with_capacity(n);
        for _ in 0..n {
            shadowing_db.push(x);
            let eps: f64 = StandardNormal.sample(&mut rng);
            x = rho * x + innovation * eps;
        }
        let range_at_step = shadowing_db
            .iter()
            .map(|db| spec.range * loss_factor(*db))
            .collect();
        Self {
            range: spec.range,
            step,
            range_at_step,
            shadowing_db,
            interference: spec.interference.clone(),
            interference_factors: spec
                .interference
                .iter()
                .map(|w| loss_factor(w.loss_db))
                .collect(),
            line_of_sight: spec.line_of_sight,
            los_step: spec.line_of_sight_step,
        }
    }

    /// Nominal range R0, before shadowing and interference, m.
    #[must_use]
    pub fn nominal_range(&self) -> f64 {
        self.range
    }
    /// Time step of the shadowing series and of the connectivity check, s.
    #[must_use]
    pub fn step(&self) -> f64 {
        self.step
    }
    /// The scheduled interference windows, as the spec gives them.
    #[must_use]
    pub fn interference(&self) -> &[InterferenceSpec] {
        &self.interference
    }

    /// Shadowing X at step k (dB).
    #[must_use]
    pub fn shadowing_db(&self, k: usize) -> f64 {
        self.shadowing_db[k.min(self.shadowing_db.len() - 1)]
    }

    /// Range after shadowing only, at step k.
    #[must_use]
    pub fn base_range(&self, k: usize) -> f64 {
        self.range_at_step[k.min(self.range_at_step.len() - 1)]
    }

    /// Range factor 10^(-I/20) of the interference at time t for a node at (x, y) (1 when
    /// no window applies). Windows add their losses, so their factors multiply.
    #[must_use]
    pub fn interference_factor(&self, t: f64, x: f64, y: f64) -> f64 {
        let mut f = 1.0;
        for (w, wf) in self.interference.iter().zip(&self.interference_factors) {
            if t >= w.time[0] && t <= w.time[1] {
                let (dx, dy) = (x - w.center[0], y - w.center[1]);
                if dx * dx + dy * dy <= w.radius * w.radius {
                    f *= wf;
                }
            }
        }
        f
    }

    /// Extra loss in dB at time t for a node at (x, y).
    #[must_use]
    pub fn interference_db(&self, t: f64, x: f64, y: f64) -> f64 {
        let mut db = 0.0;
        for w in &self.interference {
            if t >= w.time[0] && t <= w.time[1] {
                let (dx, dy) = (x - w.center[0], y - w.center[1]);
                if dx * dx + dy * dy <= w.radius * w.radius {
                    db += w.loss_db;
                }
            }
        }
        db
    }

    /// Range of a link at step k whose ends have interference factors `fa` and `fb` (see
    /// [`Self::interference_factor`]): the link takes the worse end's loss.
    #[must_use]
    pub fn link_range(&self, k: usize, fa: f64, fb: f64) -> f64 {
        self.base_range(k) * fa.min(fb)
    }

    /// Whether the straight line a-b (absolute altitudes) clears the terrain, resolved to
    /// the line-of-sight step (see [`Terrain::segment_clears`]).
    #[must_use]
    pub fn line_of_sight(&self, terrain: &Terrain, a: DVec3, b: DVec3) -> bool {
        !self.line_of_sight || terrain.segment_clears(a, b, 0.0, self.los_step)
    }
}

/// Range factor of a loss of `db` decibels.
#[must_use]
pub fn loss_factor(db: f64) -> f64 {
    10f64.powf(-db / 20.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> CommSpec {
        CommSpec {
            range: 500.0,
            ..CommSpec::default()
        }
    }

    #[test]
    fn same_seed_same_channel() {
        let a = Channel::new(&spec());
        let b = Channel::new(&spec());
        assert_eq!(a.range_at_step[..100], b.range_at_step[..100]);
        let mut s = spec();
        s.seed += 1;
        assert_ne!(
            a.range_at_step[..100],
            Channel::new(&s).range_at_step[..100]
        );
    }

    #[test]
    fn shadowing_has_the_requested_spread() {
        let c = Channel::new(&spec());
        let n = c.shadowing_db.len() as f64;
        let mean = c.shadowing_db.iter().sum::<f64>() / n;
        let sd = (c
            .shadowing_db
            .iter()
            .map(|x| (x - mean).powi(2))
            .sum::<f64>()
            / n)
            .sqrt();
        // 3600 s with a 10 s correlation time: about 180 independent samples.
        assert!((sd - 4.0).abs() < 1.2, "sd = {sd}");
        assert!(mean.abs() < 1.5, "mean = {mean}");
    }

    #[test]
    fn interference_shrinks_range_inside_its_window_and_disk() {
        let mut s = spec();
        s.shadowing_sigma_db = 0.0;
        s.interference.push(InterferenceSpec {
            time: [10.0, 20.0],
            center: [0.0, 0.0],
            radius: 50.0,
            loss_db: 20.0,
        });
        let c = Channel::new(&s);
        assert_eq!(c.interference_db(15.0, 10.0, 10.0), 20.0);
        assert_eq!(c.interference_db(25.0, 10.0, 10.0), 0.0);
        assert_eq!(c.interference_db(15.0, 100.0, 0.0), 0.0);
        let inside = c.interference_factor(15.0, 10.0, 10.0);
        assert!((inside - 0.1).abs() < 1e-12);
        assert!((c.link_range(15, inside, 1.0) - 50.0).abs() < 1e-9);
        assert!((c.link_range(15, 1.0, 1.0) - 500.0).abs() < 1e-9);
    }

    #[test]
    fn a_ridge_blocks_line_of_sight() {
        // A 300 m ridge along x = 50 between two low points.
        let nx = 101;
        let h: Vec<f64> = (0..11)
            .flat_map(|_| (0..nx).map(|i| if (45..=55).contains(&i) { 300.0 } else { 0.0 }))
            .collect();
        let t = Terrain::new(
            nx,
            11,
            (0.0, 0.0),
            (1.0, 1.0),
            h,
            super::super::terrain::Sampling::Bilinear,
        )
        .unwrap();
        let c = Channel::new(&spec());
        assert!(!c.line_of_sight(
            &t,
            DVec3::new(0.0, 5.0, 100.0),
            DVec3::new(100.0, 5.0, 100.0)
        ));
        assert!(c.line_of_sight(
            &t,
            DVec3::new(0.0, 5.0, 400.0),
            DVec3::new(100.0, 5.0, 400.0)
        ));
    }
}
