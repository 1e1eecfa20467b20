//! Encodings: how a flat decision vector becomes a plan. Separate from the optimizers, so any
//! optimizer runs on any encoding (DLS-SMPSO = PSO + DLS on the spherical encoding).
//!
//! Every encoding gives each UAV a block of 3 n values (n free waypoints) laid out as three
//! runs of n (SPSO's `r, psi, phi` order; `x, y, z` for the others), and decodes into
//! start, n free waypoints, goal, with z as height above ground.

pub mod angle;
pub mod cartesian;
pub mod spherical;

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

    /// Decodes `x` into a new plan.
    fn decode(&self, x: &[f64]) -> Plan {
        let mut p = Plan::default();
        self.decode_into(x, &mut p);
        p
    }
}

/// The encodings on offer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
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
    pub const ALL: [EncodingKind; 3] = [Self::Spherical, Self::Cartesian, Self::Angle];

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

/// What every encoding needs to know about the world.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// Start of each UAV, [x, y, z_agl].
    pub starts: Vec<DVec3>,
    /// Goal, [x, y, z_agl].
    pub goal: DVec3,
    pub x: [f64; 2],
    pub y: [f64; 2],
    pub z: [f64; 2],
    /// Free waypoints per UAV.
    pub n: usize,
}

impl Frame {
    #[must_use]
    pub fn of(world: &World) -> Self {
        let m = &world.spec.map;
        Self {
            starts: (0..world.uav_count()).map(|i| world.start(i)).collect(),
            goal: world.goal,
            x: m.x,
            y: m.y,
            z: m.z_agl,
            n: world.spec.planning.waypoints,
        }
    }

    #[must_use]
    pub fn dimension(&self) -> usize {
        3 * self.n * self.starts.len()
    }

    /// Resizes `plan` to the fleet with n + 2 waypoints each, start and goal set.
    pub fn prepare(&self, plan: &mut Plan) {
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
    let frame = Frame::of(world);
    match kind {
        EncodingKind::Spherical => Box::new(spherical::Spherical::new(
            frame,
            if world.spec.planning.spso_angles {
                spherical::AngleConvention::Spso
            } else {
                spherical::AngleConvention::Consistent
            },
        )),
        EncodingKind::Cartesian => Box::new(cartesian::Cartesian::new(frame)),
        EncodingKind::Angle => Box::new(angle::Angle::new(frame, false)),
    }
}
