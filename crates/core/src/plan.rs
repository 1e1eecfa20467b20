//! A plan: one path per UAV, each a list of waypoints [x, y, z above ground] from the start
//! to the goal (both included). This is what encodings decode into and what `evaluate` reads.

use glam::DVec3;
use serde::{Deserialize, Serialize};

/// The waypoints of one UAV, start and goal included; z is height above ground.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Path {
    pub waypoints: Vec<DVec3>,
}

/// All UAVs' paths.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    pub uavs: Vec<Path>,
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
        Self { uavs }
    }
}
