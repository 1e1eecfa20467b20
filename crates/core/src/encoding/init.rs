//! Initialisation: where a method's first population comes from.
//!
//! Part of a method's definition, as much as its optimizer and encoding: PSO on waypoint
//! coordinates drawn uniformly in the whole box starts from zig-zag plans that cross the map
//! (about 45 turn violations and 54 threat crossings each on Case 1), which is not how its
//! literature builds it. Phase-angle PSO for UAV routes (Fu, Ding, Zhou 2012, IEEE Trans.
//! Syst. Man Cybern. A 42(2):511-526) places the waypoints on planes across the start-goal
//! line; the `line` initialisation does that with a smooth random bow so each path is
//! flyable-looking from the start. Uniform phases in the angle encoding also pile
//! coordinates at the box edges (sin of a uniform angle has the arcsine law); going through
//! the `line` sampler and [`super::PathEncoding::encode_into`] avoids that too.
//!
//! Every sampler stays inside the decision box and draws only from the `&mut Rng` it is
//! given, so a run is still reproducible from its seed.

use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

use glam::{DVec2, DVec3};
use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::corridor::resample;
use super::Frame;
use crate::plan::Plan;
use crate::rng::Rng;

/// How the first population is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum InitKind {
    /// Uniform in the decision box (SPSO's code; the ablation for PSO and APSO).
    Uniform,
    /// Free waypoints on equally spaced planes across each UAV's start-goal line, displaced
    /// sideways by a smooth random bow `a1 sin(pi t) + a2 sin(2 pi t)` with
    /// `|a1| <= LINE_SPREAD L`, `|a2| <= LINE_SPREAD L / 2` (L the start-goal distance), at a
    /// random height above ground held along the path; then encoded.
    Line,
    /// Free waypoints on the UAV's threat-free corridor ([`super::corridor`]; at its corners
    /// and spread by length between them), displaced sideways by the `line` bow scaled to
    /// `CORRIDOR_SPREAD` of the start-goal distance, at a random height above ground held
    /// along the path; then encoded. A UAV without a corridor (walled in) is drawn as `line`.
    Corridor,
}

/// Largest sideways bow of a `corridor` path, as a share of its start-goal distance.
pub const CORRIDOR_SPREAD: f64 = 0.01;

/// Largest sideways bow of a `line` path, as a share of its start-goal distance.
pub const LINE_SPREAD: f64 = 0.25;

impl InitKind {
    pub const ALL: [Self; 3] = [Self::Uniform, Self::Line, Self::Corridor];

    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Line => "line",
            Self::Corridor => "corridor",
        }
    }
}

impl fmt::Display for InitKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for InitKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| {
                format!("unknown initialisation `{s}`; expected uniform, line or corridor")
            })
    }
}

fn uniform(lo: f64, hi: f64, rng: &mut Rng) -> f64 {
    let u: f64 = rng.random();
    lo + u * (hi - lo)
}

/// A plan drawn by the `line` sampler: every UAV's free waypoints near its start-goal line.
pub fn sample_line_plan(frame: &Frame, rng: &mut Rng, plan: &mut Plan) {
    sample_bowed_plan(frame, &[], rng, plan);
}

/// A plan drawn by the `corridor` sampler: every UAV's free waypoints near its corridor
/// (`corridors[i]`, from [`super::corridor::corridors`]; an empty one means the line).
pub fn sample_corridor_plan(
    frame: &Frame,
    corridors: &[Vec<DVec2>],
    rng: &mut Rng,
    plan: &mut Plan,
) {
    sample_bowed_plan(frame, corridors, rng, plan);
}

/// Free waypoints along each UAV's guide (its corridor, resampled with its corners, when it has one of at
/// least two points, else the start-goal line), bowed sideways, at one random height.
fn sample_bowed_plan(frame: &Frame, corridors: &[Vec<DVec2>], rng: &mut Rng, plan: &mut Plan) {
    frame.prepare(plan);
    let n = frame.n;
    for (i, (path, s)) in plan.uavs.iter_mut().zip(&frame.starts).enumerate() {
        let d = (frame.goal - *s).truncate();
        let length = d.length();
        let (dir, side) = if length > 0.0 {
            let u = d / length;
            (u, DVec2::new(-u.y, u.x))
        } else {
            (DVec2::X, DVec2::Y)
        };
        let guide = corridors.get(i).filter(|c| c.len() >= 2);
        let spread = if guide.is_some() {
            CORRIDOR_SPREAD
        } else {
            LINE_SPREAD
        };
        let h = spread * length;
        let a1 = uniform(-h, h, rng);
        let a2 = uniform(-0.5 * h, 0.5 * h, rng);
        let z = uniform(frame.z[0], frame.z[1], rng);
        let guided = guide.map(|c| resample(c, n));
        for k in 1..=n {
            let t = k as f64 / (n + 1) as f64;
            let bow = a1 * (PI * t).sin() + a2 * (2.0 * PI * t).sin();
            let on = guided
                .as_ref()
                .map_or_else(|| s.truncate() + dir * (t * length), |g| g[k - 1]);
            let p = on + side * bow;
            path.waypoints[k] = DVec3::new(
                p.x.clamp(frame.x[0], frame.x[1]),
                p.y.clamp(frame.y[0], frame.y[1]),
                z,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_from_seed;

    fn frame() -> Frame {
        Frame {
            starts: vec![DVec3::new(100.0, 100.0, 150.0); 2],
            goal: DVec3::new(900.0, 700.0, 150.0),
            x: [0.0, 1000.0],
            y: [0.0, 800.0],
            z: [100.0, 200.0],
            n: 8,
        }
    }

    #[test]
    fn line_paths_stay_near_the_start_goal_line_and_in_the_box() {
        let f = frame();
        let mut plan = Plan::default();
        let mut rng = rng_from_seed(4);
        for _ in 0..50 {
            sample_line_plan(&f, &mut rng, &mut plan);
            for path in &plan.uavs {
                assert_eq!(path.waypoints.len(), f.n + 2);
                for (k, w) in path.waypoints.iter().enumerate().skip(1).take(f.n) {
                    assert!((0.0..=1000.0).contains(&w.x) && (0.0..=800.0).contains(&w.y));
                    assert!((100.0..=200.0).contains(&w.z));
                    // Distance from the line is at most the bow's amplitude (1.5 h).
                    let along = (k as f64) / (f.n + 1) as f64;
                    let on_line =
                        f.starts[0].truncate() + (f.goal - f.starts[0]).truncate() * along;
                    assert!((w.truncate() - on_line).length() <= 1.5 * LINE_SPREAD * 1000.0);
                }
            }
        }
    }

    #[test]
    fn names_round_trip() {
        for k in InitKind::ALL {
            assert_eq!(k.name().parse::<InitKind>(), Ok(k));
        }
        assert!("box".parse::<InitKind>().is_err());
    }
}
