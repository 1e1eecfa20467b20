//! What a flight replay needs of a plan (`swarmplan.fly`, docs/flight.md), in the
//! scenario's frame: each UAV's path as assessed (the waypoint polyline with an arc through
//! every corner, densified), time-stamped on the mission clock, with its launch and
//! departure, and the scenario's hard limits the flown fleet is judged by.
//!
//! Why here: the flown path is the Rust model's (`TimedPlan::flown`); the replay must follow
//! exactly what `evaluate` assessed, not a re-implementation of it.

use serde::Serialize;
use swarmplan_core::cost::assess;
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;

/// One UAV's planned flight.
#[derive(Debug, Serialize)]
pub struct PlannedFlight {
    /// Index in the scenario.
    pub uav: usize,
    /// When it leaves the launcher (s; before it, it stands on it drawing nothing).
    pub launch_s: f64,
    /// When it leaves its start (s; from launch until then it hovers there).
    pub depart_s: f64,
    /// When it reaches UGV0 (s).
    pub arrival_s: f64,
    /// Planned speed, m/s.
    pub speed_mps: f64,
    /// Drone size, m (the threats' hard zones are r + size).
    pub size_m: f64,
    /// The model's physical energy of the flight, J.
    pub model_energy_j: f64,
    /// Usable battery, (1 - reserve) x battery, J.
    pub usable_j: f64,
    /// UGV0 when this UAV arrives (x, y, absolute altitude): the centre of its landing
    /// zone.
    pub landing: [f64; 3],
    /// The flown path's vertices: time (s), x, y (m) and absolute altitude (m).
    pub t: Vec<f64>,
    /// x of each vertex, m.
    pub x: Vec<f64>,
    /// y of each vertex, m.
    pub y: Vec<f64>,
    /// Absolute altitude of each vertex, m.
    pub z: Vec<f64>,
}

/// A threat's cylinder.
#[derive(Debug, Serialize)]
pub struct Cylinder {
    /// Axis x, m.
    pub x: f64,
    /// Axis y, m.
    pub y: f64,
    /// Radius, m.
    pub r: f64,
}

/// A plan's flights and the limits they are judged by.
#[derive(Debug, Serialize)]
pub struct FlightPlan {
    /// Scenario name.
    pub scenario: String,
    /// One per UAV, in fleet order.
    pub uavs: Vec<PlannedFlight>,
    /// The threats.
    pub threats: Vec<Cylinder>,
    /// Least distance between UAVs at equal times, m.
    pub separation_m: f64,
    /// Radius of the take-off and landing zones where separation is waived, m.
    pub zone_radius_m: f64,
    /// Least height above the terrain, m.
    pub clearance_m: f64,
    /// UGV0 at departure: x, y, absolute altitude.
    pub goal: [f64; 3],
    /// The map box: [x0, x1], [y0, y1].
    pub map: [[f64; 2]; 2],
    /// Whether the model assessed the plan feasible.
    pub feasible: bool,
}

/// The flights of `plan` on `world`.
pub fn flight_plan(world: &World, plan: &Plan) -> FlightPlan {
    let spec = world.spec();
    let flown = TimedPlan::flown(world, plan);
    let assessment = assess(world, plan);
    let uavs = flown
        .paths
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let u = &spec.uavs[i];
            let n = p.abs.len();
            let landing = world.absolute(world.goal_at(p.arrival));
            PlannedFlight {
                uav: i,
                launch_s: p.launch,
                depart_s: p.depart,
                arrival_s: p.arrival,
                speed_mps: p.speed,
                size_m: u.size,
                model_energy_j: assessment.per_uav.get(i).map_or(f64::NAN, |r| r.energy_j),
                usable_j: (1.0 - u.reserve) * u.battery_wh * 3600.0,
                landing: [landing.x, landing.y, landing.z],
                t: (0..n).map(|k| p.time_at(k)).collect(),
                x: p.abs.iter().map(|a| a.x).collect(),
                y: p.abs.iter().map(|a| a.y).collect(),
                z: p.abs.iter().map(|a| a.z).collect(),
            }
        })
        .collect();
    let goal = world.absolute(world.goal_at(swarmplan_core::world::DEPARTURE));
    FlightPlan {
        scenario: spec.name.clone(),
        uavs,
        threats: spec
            .threats
            .iter()
            .map(|t| Cylinder {
                x: t.x,
                y: t.y,
                r: t.r,
            })
            .collect(),
        separation_m: spec.timing.separation,
        zone_radius_m: spec.timing.zone_radius,
        clearance_m: spec.map.clearance,
        goal: [goal.x, goal.y, goal.z],
        map: [spec.map.x, spec.map.y],
        feasible: assessment.feasible(),
    }
}
