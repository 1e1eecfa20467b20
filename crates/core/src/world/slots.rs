//! Launch and recovery slots: a fleet that shares a take-off place leaves it one UAV after
//! another, and UGV0 takes its UAVs back one at a time (docs/model.md, "Launch and recovery
//! slots"; not in the paper, which launches and recovers everyone at once).
//!
//! Why: under the paper's simultaneous departure and common arrival, five UAVs that share a
//! start must fan out through the take-off zone's edge at the same moment, 19 deg apart on
//! a 30 m circle, and a hundred reach UGV0's landing zone together, a few metres apart on
//! its edge: separation cannot hold however the paths are drawn. An operator launches from
//! one place in turn and recovers in turn, so the model does.
//!
//! Which UAVs share a take-off place: UAV i joins the group of the first earlier UAV whose
//! start lies within `timing.zone_radius` of its own (horizontally), and its launch slot is
//! its rank in that group times `timing.launch_interval`. Every UAV lands at UGV0, so its
//! recovery slot is its index times `timing.recovery_interval`: UAV 0 lands first. Both
//! intervals default to 0 (everyone at once: the paper's layout, bit for bit).

use super::spec::{ScenarioSpec, TimingPolicy};

/// Longest span of the slots, seconds: the latest take-off a slot asks for. Half the
/// channel's modelled [`super::channel::CHANNEL_HORIZON_S`], so a mission and its slots fit
/// in the channel with 30 minutes left to fly (beyond it the channel would stand still).
pub const MAX_SLOT_SPAN_S: f64 = 0.5 * super::channel::CHANNEL_HORIZON_S;

/// Each UAV's launch and recovery offsets and how far its flight moves, seconds.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Slots {
    launch: Vec<f64>,
    recovery: Vec<f64>,
    shift: Vec<f64>,
}

impl Slots {
    /// The slots `spec`'s timing asks for (all 0 when both intervals are 0).
    #[must_use]
    pub fn of(spec: &ScenarioSpec) -> Self {
        let t = &spec.timing;
        let n = spec.uavs.len();
        let mut launch = vec![0.0; n];
        if t.launch_interval > 0.0 {
            // group[i]: the first UAV of i's group; rank within it counted as we go.
            let mut group = vec![0usize; n];
            let mut members = vec![0usize; n];
            for i in 0..n {
                let [xi, yi, _] = spec.uavs[i].start;
                let first = (0..i)
                    .find(|&j| {
                        let [xj, yj, _] = spec.uavs[j].start;
                        group[j] == j && (xi - xj).hypot(yi - yj) <= t.zone_radius
                    })
                    .unwrap_or(i);
                group[i] = first;
                launch[i] = members[first] as f64 * t.launch_interval;
                members[first] += 1;
            }
        }
        let recovery: Vec<f64> = (0..n).map(|i| i as f64 * t.recovery_interval).collect();
        // Under common arrival UAV i lands at T + c + b_i, where c = max(0, max_i (a_i - b_i))
        // is the least common lag that lets every UAV take off no earlier than its launch
        // slot; under cruise it takes off at its launch slot.
        let shift = if t.policy == TimingPolicy::CommonArrival {
            let lag = launch
                .iter()
                .zip(&recovery)
                .map(|(a, b)| a - b)
                .fold(0.0, f64::max);
            recovery.iter().map(|b| lag + b).collect()
        } else {
            launch.clone()
        };
        Self {
            launch,
            recovery,
            shift,
        }
    }

    /// How much later than without slots UAV `u`'s whole flight is (it waits that long on
    /// the launcher).
    #[must_use]
    pub fn shift(&self, u: usize) -> f64 {
        self.shift.get(u).copied().unwrap_or(0.0)
    }

    /// The latest shift, s: how long the slots stretch the mission.
    #[must_use]
    pub fn span(&self) -> f64 {
        self.shift.iter().copied().fold(0.0, f64::max)
    }

    /// Seconds after the mission's start at which UAV `u` may leave its start.
    #[must_use]
    pub fn launch(&self, u: usize) -> f64 {
        self.launch.get(u).copied().unwrap_or(0.0)
    }

    /// Seconds after the fleet's common arrival time T at which UAV `u` lands.
    #[must_use]
    pub fn recovery(&self, u: usize) -> f64 {
        self.recovery.get(u).copied().unwrap_or(0.0)
    }

    /// Whether any UAV has a slot other than 0.
    #[must_use]
    pub fn any(&self) -> bool {
        self.launch.iter().chain(&self.recovery).any(|&s| s > 0.0)
    }
}
