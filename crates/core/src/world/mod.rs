//! The world a plan lives in: terrain, threats, fleet, channel, energy model and the
//! objective's settings, validated and precomputed once per scenario.
//!
//! [`ScenarioSpec`] is what a file says; [`World`] is what the cost function reads. Building
//! the world validates the spec, so evaluation never has to check anything.

pub mod channel;
pub mod enclosure;
pub mod energy;
pub mod flight_margin;
pub mod horizon;
pub mod objective;
pub mod procedural;
pub mod slots;
pub mod spec;
pub mod terrain;
#[cfg(test)]
pub(crate) mod test_spec;
pub mod threat;
pub mod unreachable;
pub mod validate;

use glam::DVec3;
use thiserror::Error;

pub use channel::Channel;
pub use spec::ScenarioSpec;
pub use terrain::{Sampling, Terrain};
pub use threat::Threat;
pub use validate::SpecError;

/// The time, in seconds from the fleet's departure, at which readers without a time of
/// their own look at what may move ([`World::goal_at`], [`World::ground_nodes_at`]): the
/// frame an encoding draws its paths in, threat-free corridors, the ground-coverage map.
/// Greppable, so that a moving UGV0 finds every such reader.
pub const DEPARTURE: f64 = 0.0;

/// A ground radio node (ground control station, UGV0, extra relays), absolute position.
#[derive(Debug, Clone)]
pub struct GroundNode {
    /// `GCS`, `UGV0`, or the extra node's name from the spec.
    pub name: String,
    /// Antenna position, absolute altitude.
    pub position: DVec3,
    /// Line-of-sight table of the antenna (built with the world).
    pub horizon: Option<horizon::Horizon>,
}

/// Why a world could not be built from a spec and a terrain.
#[derive(Debug, Error)]
pub enum WorldError {
    /// The spec failed validation.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// A UAV's start lies outside the map box.
    #[error("uavs[{uav}].start: ({x}, {y}) is outside the map box x {bx:?}, y {by:?}")]
    StartOutside {
        /// Index of the UAV.
        uav: usize,
        /// Start x, m.
        x: f64,
        /// Start y, m.
        y: f64,
        /// The map box's x range, m.
        bx: [f64; 2],
        /// The map box's y range, m.
        by: [f64; 2],
    },
    /// The map box reaches more than one terrain cell beyond the terrain's extent.
    #[error("map: the box x {bx:?}, y {by:?} reaches beyond the terrain, which covers x [{}, {}], y [{}, {}] (the edge heights would be stretched over the rest); shrink the map box or use a terrain that covers it", .extent.0, .extent.2, .extent.1, .extent.3)]
    MapBeyondTerrain {
        /// The map box's x range, m.
        bx: [f64; 2],
        /// The map box's y range, m.
        by: [f64; 2],
        /// (x_min, y_min, x_max, y_max) of the terrain.
        extent: (f64, f64, f64, f64),
    },
    /// The goal (UGV0) lies outside the map box.
    #[error("goal.position: ({x}, {y}) is outside the map box x {bx:?}, y {by:?}")]
    GoalOutside {
        /// Goal x, m.
        x: f64,
        /// Goal y, m.
        y: f64,
        /// The map box's x range, m.
        bx: [f64; 2],
        /// The map box's y range, m.
        by: [f64; 2],
    },
    /// An extra ground node lies outside the map box.
    #[error("communication.ground_nodes[{}] (`{}`).position: ({}, {}) is outside the map box x {:?}, y {:?}; positions are metres in the map's frame, like the starts, not geographic coordinates", .0.index, .0.name, .0.x, .0.y, .0.bx, .0.by)]
    GroundNodeOutside(Box<NodeOutside>),
}

/// An extra ground node placed outside the map box (boxed: the error stays small).
#[derive(Debug)]
pub struct NodeOutside {
    /// Its index in `communication.ground_nodes`.
    pub index: usize,
    /// Its name.
    pub name: String,
    /// Its x position, m.
    pub x: f64,
    /// Its y position, m.
    pub y: f64,
    /// The map box's x range, m.
    pub bx: [f64; 2],
    /// The map box's y range, m.
    pub by: [f64; 2],
}

/// A validated scenario with its terrain and channel.
#[derive(Debug, Clone)]
pub struct World {
    spec: ScenarioSpec,
    terrain: Terrain,
    channel: Channel,
    /// Ground nodes: the ground station (if on), UGV0, then the extra nodes.
    ground_nodes: Vec<GroundNode>,
    /// Goal [x, y, z_agl].
    goal: DVec3,
    /// Each UAV's launch and recovery slot.
    slots: slots::Slots,
    /// Which built world this is, for memos of what depends on it.
    id: WorldId,
}

/// Tells built worlds apart: evaluation buffers keep results that depend on the world (a
/// UAV's own terms, `crate::cost`) and must not serve them to another. Each world gets a
/// fresh one when built *and when cloned*, since a clone is what one edits (a world is not
/// to be edited in place once evaluated).
#[derive(Debug, PartialEq, Eq)]
pub struct WorldId(u64);

impl WorldId {
    fn fresh() -> Self {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
        Self(NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
    }

    /// The number, unique among the worlds of this process.
    #[must_use]
    pub fn get(&self) -> u64 {
        self.0
    }
}

impl Clone for WorldId {
    /// A fresh identity: the clone may be edited, and memos of the original must not serve it.
    fn clone(&self) -> Self {
        Self::fresh()
    }
}

impl World {
    /// The validated scenario, as its file says it.
    #[must_use]
    pub fn spec(&self) -> &ScenarioSpec {
        &self.spec
    }

    /// The terrain's height grid.
    #[must_use]
    pub fn terrain(&self) -> &Terrain {
        &self.terrain
    }

    /// The time-varying channel: range R(t), interference windows, shadowing.
    #[must_use]
    pub fn channel(&self) -> &Channel {
        &self.channel
    }

    /// The ground radio nodes at time `t` (seconds from the fleet's departure): the ground
    /// station (if on), UGV0, then the extra nodes. Static today, the same at every `t`;
    /// a moving UGV0 changes this accessor and the timing, not its readers (docs/model.md,
    /// "A world that can move").
    #[must_use]
    pub fn ground_nodes_at(&self, t: f64) -> &[GroundNode] {
        let _ = t;
        &self.ground_nodes
    }

    /// Where UGV0 recovers the fleet at time `t` (seconds from departure): [x, y, z above
    /// ground]. Static today; readers pass the time they mean (a UAV's arrival), so a
    /// moving UGV0 hooks in here.
    #[must_use]
    pub fn goal_at(&self, t: f64) -> DVec3 {
        let _ = t;
        self.goal
    }

    /// Each UAV's launch and recovery slot (all 0 unless `timing` asks for slots).
    #[must_use]
    pub fn slots(&self) -> &slots::Slots {
        &self.slots
    }

    /// This world's identity (fresh for each world built or cloned).
    #[must_use]
    pub fn id(&self) -> u64 {
        self.id.get()
    }

    /// Validates `spec` and builds the world on `terrain`.
    pub fn new(spec: ScenarioSpec, terrain: Terrain) -> Result<Self, WorldError> {
        spec.validate()?;
        let (bx, by) = (spec.map.x, spec.map.y);
        // One cell of slack: a DEM's nodes and a box drawn to its edges differ by rounding.
        let extent = terrain.extent();
        let (cx, cy) = terrain.cell();
        if bx[0] < extent.0 - cx
            || by[0] < extent.1 - cy
            || bx[1] > extent.2 + cx
            || by[1] > extent.3 + cy
        {
            return Err(WorldError::MapBeyondTerrain { bx, by, extent });
        }
        let inside = |x: f64, y: f64| x >= bx[0] && x <= bx[1] && y >= by[0] && y <= by[1];
        for (k, u) in spec.uavs.iter().enumerate() {
            if !inside(u.start[0], u.start[1]) {
                return Err(WorldError::StartOutside {
                    uav: k,
                    x: u.start[0],
                    y: u.start[1],
                    bx,
                    by,
                });
            }
        }
        let g = spec.goal.position;
        if !inside(g[0], g[1]) {
            return Err(WorldError::GoalOutside {
                x: g[0],
                y: g[1],
                bx,
                by,
            });
        }
        for (index, n) in spec.communication.ground_nodes.iter().enumerate() {
            let [x, y] = n.position;
            if !inside(x, y) {
                return Err(WorldError::GroundNodeOutside(Box::new(NodeOutside {
                    index,
                    name: n.name.clone(),
                    x,
                    y,
                    bx,
                    by,
                })));
            }
        }
        let ground =
            |x: f64, y: f64, antenna: f64| DVec3::new(x, y, terrain.height(x, y) + antenna);
        let mut ground_nodes = Vec::new();
        if spec.communication.ground_station {
            let s = spec.uavs[0].start;
            ground_nodes.push(GroundNode {
                name: "GCS".into(),
                position: ground(s[0], s[1], spec.goal.antenna),
                horizon: None,
            });
        }
        ground_nodes.push(GroundNode {
            name: "UGV0".into(),
            position: ground(g[0], g[1], spec.goal.antenna),
            horizon: None,
        });
        for n in &spec.communication.ground_nodes {
            ground_nodes.push(GroundNode {
                name: n.name.clone(),
                position: ground(n.position[0], n.position[1], n.antenna),
                horizon: None,
            });
        }
        let channel = Channel::new(&spec.communication);
        let checks_comm = spec.communication.requirement != spec::CommRequirement::None;
        if spec.communication.line_of_sight && checks_comm {
            let (bx, by) = (spec.map.x, spec.map.y);
            let step = spec.communication.line_of_sight_step;
            for g in &mut ground_nodes {
                // Far enough to reach every corner of the map box.
                let reach = [bx[0], bx[1]]
                    .iter()
                    .flat_map(|x| {
                        [by[0], by[1]].map(|y| (x - g.position.x).hypot(y - g.position.y))
                    })
                    .fold(0.0, f64::max);
                g.horizon = Some(horizon::Horizon::new(&terrain, g.position, reach, step));
            }
        }
        Ok(Self {
            goal: DVec3::from_array(g),
            slots: slots::Slots::of(&spec),
            spec,
            terrain,
            channel,
            ground_nodes,
            id: WorldId::fresh(),
        })
    }

    /// The number of UAVs in the fleet.
    #[must_use]
    pub fn uav_count(&self) -> usize {
        self.spec.uavs.len()
    }

    /// Start of UAV i as [x, y, z_agl].
    #[must_use]
    pub fn start(&self, i: usize) -> DVec3 {
        DVec3::from_array(self.spec.uavs[i].start)
    }

    /// Whether plans are assessed as flown, with an arc of each UAV's turning radius
    /// through every corner and the turning-radius constraint ([`crate::flight`]): under
    /// the strict profile. The paper profile and SPSO's objective keep the paper's straight
    /// segments, so the reference cross-checks still hold.
    #[must_use]
    pub fn flies_arcs(&self) -> bool {
        self.spec.planning.profile == crate::feasibility::FeasibilityProfile::Strict
            && self.spec.objective.preset != spec::ObjectivePreset::SpsoMycost
    }

    /// Absolute altitude of a point given as [x, y, z_agl].
    ///
    /// Under SPSO's nearest-cell sampling the sum is rounded to single precision, as MATLAB
    /// does when SPSO adds a double z to its `single` DEM (`z + H(...)` is `single`); this
    /// is what lets the `spso` cross-check match the reference to 1e-9.
    #[must_use]
    pub fn absolute(&self, p: DVec3) -> DVec3 {
        let h = self.terrain.height(p.x, p.y);
        let z = match self.terrain.sampling() {
            Sampling::Bilinear => p.z + h,
            Sampling::NearestMatlab => f64::from(p.z as f32 + h as f32),
        };
        DVec3::new(p.x, p.y, z)
    }
}
