//! A plan: one path per UAV, each a list of waypoints [x, y, z above ground] from the start
//! to the goal (both included), and the fleet's pace (1 unless the scenario lets the planner
//! choose it, `timing.pace`) and each UAV's departure delay (0 unless the scenario lets the
//! planner choose them, `timing.max_delay`). This is what encodings decode into and what
//! `evaluate` reads.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The waypoints of one UAV, start and goal included; z is height above ground.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Path {
    /// Start, free waypoints and goal, [x, y, z above ground] in m.
    pub waypoints: Vec<DVec3>,
}

/// All UAVs' paths and the fleet's pace.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// One path per UAV, in fleet order.
    pub uavs: Vec<Path>,
    /// Factor on the timing policy's preferred speed ([`crate::timing`]): 1 flies nearest
    /// cruise, 1.3 is 30 % faster where the speed limits allow. Written only when not 1.
    #[serde(default = "unit_pace", skip_serializing_if = "is_unit_pace")]
    pub pace: f64,
    /// Per UAV, its departure delay as a share of its arrival time ([`crate::timing`]):
    /// it hovers at its start until then. Empty (or missing entries) means 0; written only
    /// when some delay is not 0.
    #[serde(default, skip_serializing_if = "no_delays")]
    pub delays: Vec<f64>,
}

impl Default for Plan {
    fn default() -> Self {
        Self {
            uavs: Vec::new(),
            pace: 1.0,
            delays: Vec::new(),
        }
    }
}

/// Whether every delay is 0 (such a `delays` field is not written).
#[allow(clippy::float_cmp)]
#[must_use]
pub fn no_delays(d: &[f64]) -> bool {
    d.iter().all(|x| *x == 0.0)
}

/// Pace 1, the serde default of every `pace` field (plans, plan files).
#[must_use]
pub fn unit_pace() -> f64 {
    1.0
}

/// Whether `p` is pace 1 (such a `pace` field is not written).
#[allow(clippy::trivially_copy_pass_by_ref, clippy::float_cmp)]
#[must_use]
pub fn is_unit_pace(p: &f64) -> bool {
    *p == 1.0
}

impl Plan {
    /// A plan of straight lines from each start to the goal with `free` evenly spaced free
    /// waypoints (heights interpolated).
    #[must_use]
    pub fn straight(starts: &[DVec3], goal: DVec3, free: usize) -> Self {
        let uavs = starts
            .iter()
            .map(|s| Path {
                waypoints: (0..=free + 1)
                    .map(|k| s.lerp(goal, k as f64 / (free + 1) as f64))
                    .collect(),
            })
            .collect();
        Self {
            uavs,
            ..Self::default()
        }
    }

    /// UAV `u`'s departure delay, a share of its arrival time (0 when not set).
    #[must_use]
    pub fn delay(&self, u: usize) -> f64 {
        self.delays.get(u).copied().unwrap_or(0.0)
    }
}
