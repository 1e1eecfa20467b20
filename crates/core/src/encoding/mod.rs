//! Encodings: how a flat decision vector becomes a plan. Separate from the optimizers, so any
//! optimizer runs on any encoding (DLS-SMPSO = PSO + DLS on the spherical encoding).
//!
//! Every encoding gives each UAV a block of 3 n values (n free waypoints) laid out as three
//! runs of n (SPSO's `r, psi, phi` order; `x, y, z` for the others), and decodes into
//! start, n free waypoints, goal, with z as height above ground.

pub mod angle;
pub mod banded;
pub mod cartesian;
pub mod corridor;
pub mod delayed;
pub mod init;
pub mod paced;
mod per_block;
pub mod routed;
pub mod sharp_corners;
pub mod spherical;

pub use init::InitKind;

use std::fmt;
use std::str::FromStr;

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::plan::Plan;
use crate::problem::Bound;
use crate::world::World;

/// A decoder from decision vectors to plans.
pub trait PathEncoding: Send + Sync {
    /// One bound per decision variable.
    fn bounds(&self) -> &[Bound];

    /// Decodes `x` into `plan`, reusing its buffers.
    fn decode_into(&self, x: &[f64], plan: &mut Plan);

    /// The decision vector whose decoding is nearest to `plan` (exact where `plan` is
    /// inside what the encoding can express; otherwise each value is clamped into its
    /// bound). Used to start a search from given plans.
    fn encode_into(&self, plan: &Plan, out: &mut [f64]);

    /// Decodes `x` into a new plan.
    fn decode(&self, x: &[f64]) -> Plan {
        let mut p = Plan::default();
        self.decode_into(x, &mut p);
        p
    }
}

/// The encodings on offer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EncodingKind {
    /// Spherical motion vectors (SPSO, DLS-SMPSO).
    Spherical,
    /// Waypoint coordinates (PSO, QPSO, GWO, ABC).
    Cartesian,
    /// Phase angles, coordinate = mid + half-range sin(theta) (APSO / theta-PSO).
    Angle,
}

impl EncodingKind {
    /// Every encoding.
    pub const ALL: [EncodingKind; 3] = [Self::Spherical, Self::Cartesian, Self::Angle];

    /// The name used on the command line and in records (`spherical`, ...).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Spherical => "spherical",
            Self::Cartesian => "cartesian",
            Self::Angle => "angle",
        }
    }
}

impl fmt::Display for EncodingKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for EncodingKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name() == s)
            .ok_or_else(|| {
                format!("unknown encoding `{s}`; expected one of spherical, cartesian, angle")
            })
    }
}

/// What every encoding needs to know about the world to draw paths in it: the starts, the
/// goal, the box and the number of free waypoints. (The geographic frames are others:
/// `LocalFrame` and `EnuFrame` in swarmplan-io, a terrain's `TerrainFrame`, a DEM's
/// `DemFrame`.)
#[derive(Debug, Clone, PartialEq)]
pub struct PathFrame {
    /// Start of each UAV, [x, y, z_agl].
    pub starts: Vec<DVec3>,
    /// Goal, [x, y, z_agl].
    pub goal: DVec3,
    /// x range of free waypoints, m.
    pub x: [f64; 2],
    /// y range of free waypoints, m.
    pub y: [f64; 2],
    /// Height band of free waypoints above ground, m.
    pub z: [f64; 2],
    /// Free waypoints per UAV.
    pub n: usize,
}

impl PathFrame {
    /// The frame of `world`: its UAVs' starts, the goal at departure, the map box and the
    /// number of free waypoints.
    #[must_use]
    pub fn of(world: &World) -> Self {
        let m = &world.spec().map;
        Self {
            starts: (0..world.uav_count()).map(|i| world.start(i)).collect(),
            goal: world.goal_at(crate::world::DEPARTURE),
            x: m.x,
            y: m.y,
            z: m.z_agl,
            n: world.spec().planning.waypoints,
        }
    }

    /// Length of a decision vector: 3 n values per UAV.
    #[must_use]
    pub fn dimension(&self) -> usize {
        3 * self.n * self.starts.len()
    }

    /// Resizes `plan` to the fleet with n + 2 waypoints each, start and goal set, pace 1.
    pub fn prepare(&self, plan: &mut Plan) {
        plan.pace = 1.0;
        plan.delays.clear();
        plan.uavs.resize_with(self.starts.len(), Default::default);
        for (path, s) in plan.uavs.iter_mut().zip(&self.starts) {
            path.waypoints.resize(self.n + 2, DVec3::ZERO);
            path.waypoints[0] = *s;
            path.waypoints[self.n + 1] = self.goal;
        }
    }
}

/// Builds the encoding `kind` for `world`.
#[must_use]
pub fn build(kind: EncodingKind, world: &World) -> Box<dyn PathEncoding> {
    build_along(kind, world, &[], &[])
}

/// Builds the encoding `kind` for `world`, the spherical one with its heading sectors along
/// `guides` and its climb bounds wide enough for `climbs`
/// ([`spherical::Spherical::along_guides`]; the others ignore both).
#[must_use]
pub fn build_along(
    kind: EncodingKind,
    world: &World,
    guides: &[Vec<glam::DVec2>],
    climbs: &[Vec<f64>],
) -> Box<dyn PathEncoding> {
    let frame = PathFrame::of(world);
    match kind {
        EncodingKind::Spherical => Box::new(spherical::Spherical::along_guides(
            frame,
            if world.spec().planning.spso_angles {
                spherical::AngleConvention::Spso
            } else {
                spherical::AngleConvention::Consistent
            },
            guides,
            climbs,
        )),
        EncodingKind::Cartesian => Box::new(cartesian::Cartesian::new(frame)),
        EncodingKind::Angle => Box::new(angle::Angle::new(frame, false)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_from_seed;

    fn frame() -> PathFrame {
        frame_with(6)
    }

    /// Two UAVs from near (100, 80) to (800, 700) on a 1000 x 900 m map, `n` free waypoints
    /// (also the encoding wrappers' tests).
    pub(super) fn frame_with(n: usize) -> PathFrame {
        PathFrame {
            starts: vec![
                DVec3::new(100.0, 80.0, 150.0),
                DVec3::new(120.0, 60.0, 150.0),
            ],
            goal: DVec3::new(800.0, 700.0, 150.0),
            x: [0.0, 1000.0],
            y: [0.0, 900.0],
            z: [100.0, 200.0],
            n,
        }
    }

    fn encodings() -> Vec<(&'static str, Box<dyn PathEncoding>)> {
        vec![
            ("cartesian", Box::new(cartesian::Cartesian::new(frame()))),
            ("angle", Box::new(angle::Angle::new(frame(), false))),
            (
                "spherical",
                Box::new(spherical::Spherical::new(
                    frame(),
                    spherical::AngleConvention::Consistent,
                )),
            ),
            (
                "spherical-spso",
                Box::new(spherical::Spherical::new(
                    frame(),
                    spherical::AngleConvention::Spso,
                )),
            ),
        ]
    }

    #[test]
    fn encoding_a_decoded_plan_decodes_to_the_same_plan() {
        // Exact where the plan is expressible: a spherical decode that hit the box (a
        // clamped waypoint) may need a heading outside its bound to be re-encoded.
        let f = frame();
        let on_box = |w: &DVec3| {
            [w.x, w.y, w.z]
                .iter()
                .zip([f.x, f.y, f.z])
                .any(|(v, r)| *v == r[0] || *v == r[1])
        };
        let mut rng = rng_from_seed(8);
        for (name, enc) in encodings() {
            let mut x = vec![0.0; enc.bounds().len()];
            let mut y = x.clone();
            let mut checked = 0;
            for _ in 0..400 {
                crate::problem::fill_uniform(enc.bounds(), &mut rng, &mut x);
                if name.starts_with("spherical") {
                    // Short, nearly level motions, which rarely reach the box.
                    for (k, v) in x.iter_mut().enumerate() {
                        match (k % (3 * f.n)) / f.n {
                            0 => *v *= 0.3,
                            1 => *v *= 0.1,
                            _ => {}
                        }
                    }
                }
                let plan = enc.decode(&x);
                let clamped = plan
                    .uavs
                    .iter()
                    .any(|p| p.waypoints[1..=f.n].iter().any(on_box));
                if name.starts_with("spherical") && clamped {
                    continue;
                }
                checked += 1;
                enc.encode_into(&plan, &mut y);
                assert!(
                    y.iter().zip(enc.bounds()).all(|(v, b)| b.contains(*v)),
                    "{name}: encoded outside the bounds"
                );
                let again = enc.decode(&y);
                for (p, q) in plan.uavs.iter().zip(&again.uavs) {
                    for (a, b) in p.waypoints.iter().zip(&q.waypoints) {
                        assert!(a.distance(*b) < 1e-6, "{name}: {a} vs {b}");
                    }
                }
            }
            assert!(checked >= 40, "{name}: only {checked} expressible samples");
        }
    }

    #[test]
    fn line_plans_encode_inside_the_bounds_of_every_encoding() {
        let mut rng = rng_from_seed(9);
        let mut plan = Plan::default();
        for (name, enc) in encodings() {
            let mut x = vec![0.0; enc.bounds().len()];
            for _ in 0..50 {
                init::sample_line_plan(&frame(), &mut rng, &mut plan);
                enc.encode_into(&plan, &mut x);
                assert!(
                    x.iter().zip(enc.bounds()).all(|(v, b)| b.contains(*v)),
                    "{name}"
                );
            }
        }
    }

    #[test]
    fn a_corridor_plan_round_trips_only_with_sectors_along_it() {
        // A corridor that first heads north-west, 80 degrees off the start-goal bearing of
        // 41.6 degrees (round a threat), then turns to the goal.
        let f = frame();
        let corridor = vec![
            f.starts[0].truncate(),
            glam::DVec2::new(60.0, 400.0),
            glam::DVec2::new(350.0, 650.0),
            f.goal.truncate(),
        ];
        let guides = vec![corridor.clone(), corridor];
        let mut rng = rng_from_seed(10);
        let mut plan = Plan::default();
        let frame1 = PathFrame {
            starts: vec![f.starts[0]; 2],
            ..f.clone()
        };
        init::sample_corridor_plan(&frame1, &guides, &mut rng, &mut plan);
        let gap = |enc: &dyn PathEncoding| {
            let mut x = vec![0.0; enc.bounds().len()];
            enc.encode_into(&plan, &mut x);
            assert!(x.iter().zip(enc.bounds()).all(|(v, b)| b.contains(*v)));
            let again = enc.decode(&x);
            plan.uavs
                .iter()
                .zip(&again.uavs)
                .flat_map(|(p, q)| p.waypoints.iter().zip(&q.waypoints))
                .map(|(a, b)| a.distance(*b))
                .fold(0.0, f64::max)
        };
        let along = spherical::Spherical::along_guides(
            frame1.clone(),
            spherical::AngleConvention::Consistent,
            &guides,
            &[],
        );
        let plain = spherical::Spherical::new(frame1, spherical::AngleConvention::Consistent);
        assert!(gap(&along) < 1e-6, "{}", gap(&along));
        assert!(gap(&plain) > 50.0, "{}", gap(&plain));
    }

    #[test]
    fn a_seeded_move_steeper_above_ground_than_45_deg_round_trips_only_with_its_climb() {
        use crate::problem::Bound;
        use glam::DVec3;
        use std::f64::consts::FRAC_PI_4;
        // Off a cliff: the way keeps its absolute altitude while the ground under it rises,
        // so its height above ground falls 80 m over 27 m between two free waypoints.
        let f = PathFrame {
            starts: vec![DVec3::new(100.0, 80.0, 150.0)],
            ..frame_with(3)
        };
        let waypoints = [
            DVec3::new(300.0, 250.0, 180.0),
            DVec3::new(327.0, 250.0, 100.0),
            DVec3::new(600.0, 480.0, 140.0),
        ];
        let guide: Vec<glam::DVec2> = std::iter::once(f.starts[0])
            .chain(waypoints)
            .chain(std::iter::once(f.goal))
            .map(|p| p.truncate())
            .collect();
        let mut from = f.starts[0];
        let climbs: Vec<f64> = waypoints
            .iter()
            .map(|&to| {
                let climb = (to.z - from.z).atan2(to.truncate().distance(from.truncate()));
                from = to;
                climb
            })
            .collect();
        assert!(climbs[1].abs() > 1.2, "{climbs:?}");
        let mut plan = Plan::default();
        f.prepare(&mut plan);
        plan.uavs[0].waypoints[1..4].copy_from_slice(&waypoints);
        let gap = |enc: &dyn PathEncoding| {
            let mut x = vec![0.0; enc.bounds().len()];
            enc.encode_into(&plan, &mut x);
            let again = enc.decode(&x);
            plan.uavs[0]
                .waypoints
                .iter()
                .zip(&again.uavs[0].waypoints)
                .map(|(a, b)| a.distance(*b))
                .fold(0.0, f64::max)
        };
        let convention = spherical::AngleConvention::Consistent;
        let guides = [guide];
        let steepest = climbs[1].abs();
        let steep = spherical::Spherical::along_guides(f.clone(), convention, &guides, &[climbs]);
        let level = spherical::Spherical::along_guides(f, convention, &guides, &[]);
        assert!(gap(&steep) < 1e-6, "{}", gap(&steep));
        assert!(gap(&level) > 20.0, "{}", gap(&level));
        // Only the steep move's bound widened, to 1.1 times its angle.
        let psi = &steep.bounds()[3..6];
        assert_eq!(psi[0], Bound::new(-FRAC_PI_4, FRAC_PI_4));
        assert_eq!(psi[1], Bound::new(-1.1 * steepest, 1.1 * steepest));
        assert_eq!(psi[2], Bound::new(-FRAC_PI_4, FRAC_PI_4));
    }
}
