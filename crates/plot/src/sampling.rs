//! Who is where and in contact, at every communication step of a plan's mission: what the
//! top view marks as outages and the timeline draws row by row. Sampled at the channel's
//! own step (1 s by default), the same instants the cost function checks.

use glam::DVec3;
use swarmplan_core::cost::comm::{contact_at, Contact};
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;

/// Positions and contact of every UAV at t_k = k * dt, k = 0 ..= ceil(horizon / dt).
pub(crate) struct ContactTrace {
    pub timed: TimedPlan,
    /// Communication step, seconds.
    pub dt: f64,
    pub times: Vec<f64>,
    /// `positions[k][i]`: UAV i at t_k, absolute altitude.
    pub positions: Vec<Vec<DVec3>>,
    /// `contact[k][i]`: UAV i's status at t_k.
    pub contact: Vec<Vec<Contact>>,
}

/// A run of consecutive steps `first ..= last` with one status.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Run {
    pub first: usize,
    pub last: usize,
    pub status: Contact,
}

impl ContactTrace {
    pub(crate) fn new(world: &World, plan: &Plan) -> Self {
        // Where the UAVs are when: what is flown, as the assessment sees it.
        let timed = TimedPlan::flown(world, plan);
        let dt = world.channel().step();
        let steps = if timed.horizon.is_finite() && dt > 0.0 {
            (timed.horizon / dt).ceil() as usize
        } else {
            0
        };
        let times: Vec<f64> = (0..=steps).map(|k| k as f64 * dt).collect();
        let positions: Vec<Vec<DVec3>> = times
            .iter()
            .map(|t| {
                timed
                    .paths
                    .iter()
                    .map(|p| {
                        if p.abs.is_empty() {
                            DVec3::ZERO
                        } else {
                            p.position_at_time(*t)
                        }
                    })
                    .collect()
            })
            .collect();
        let contact = times
            .iter()
            .zip(&positions)
            .map(|(t, pos)| contact_at(world, *t, pos))
            .collect();
        Self {
            timed,
            dt,
            times,
            positions,
            contact,
        }
    }

    pub(crate) fn uav_count(&self) -> usize {
        self.timed.paths.len()
    }

    /// UAV `i`'s statuses as runs, in time order.
    pub(crate) fn runs(&self, i: usize) -> Vec<Run> {
        let mut out: Vec<Run> = Vec::new();
        for (k, c) in self.contact.iter().enumerate() {
            let status = c[i];
            match out.last_mut() {
                Some(r) if r.status == status && r.last + 1 == k => r.last = k,
                _ => out.push(Run {
                    first: k,
                    last: k,
                    status,
                }),
            }
        }
        out
    }

    /// Seconds UAV `i` spent with `status` (steps x dt).
    pub(crate) fn seconds(&self, i: usize, status: Contact) -> f64 {
        self.contact.iter().filter(|c| c[i] == status).count() as f64 * self.dt
    }
}
