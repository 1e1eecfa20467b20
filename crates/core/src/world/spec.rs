//! The scenario as written in a TOML file: plain serde structs, every field documented with
//! its default. Unknown fields are rejected. [`ScenarioSpec::validate`] checks values and
//! names the offending field; [`crate::world::World::new`] turns a valid spec into the
//! precomputed world the cost function reads.

use serde::{Deserialize, Deserializer, Serialize};

use super::energy::RotaryWing;
use super::threat::Threat;

pub use super::objective::{ObjectivePreset, ObjectiveSpec};

/// A fixed-length array of numbers that refuses extra values: serde's own arrays read the
/// first N of a longer TOML array and drop the rest without a word (`x = [0, 300, 500]`
/// would load as [0, 300]).
fn exactly<'de, D: Deserializer<'de>, const N: usize>(d: D) -> Result<[f64; N], D::Error> {
    let values = Vec::<f64>::deserialize(d)?;
    let len = values.len();
    values.try_into().map_err(|_| {
        serde::de::Error::invalid_length(len, &format!("an array of {N} numbers").as_str())
    })
}

/// One scenario: terrain, map, threats, fleet, goal, channel, energy, objective, timing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ScenarioSpec {
    /// Short identifier (e.g. `paper-case1`).
    pub name: String,
    /// One line for humans.
    #[serde(default)]
    pub description: String,
    /// Where the height grid comes from and how it is read (procedural by default).
    #[serde(default)]
    pub terrain: TerrainSpec,
    /// Geodetic origin of the local frame, for exports (optional; a georeferenced GeoTIFF
    /// also gives one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub geo: Option<GeoSpec>,
    /// The box waypoints live in and the altitude band above ground.
    #[serde(default)]
    pub map: MapSpec,
    /// Threat cylinders (none).
    #[serde(default)]
    pub threats: Vec<Threat>,
    /// UGV0: where every UAV lands.
    pub goal: GoalSpec,
    /// One entry per UAV.
    pub uavs: Vec<UavSpec>,
    /// The radio channel and what counts as in contact.
    #[serde(default)]
    pub communication: CommSpec,
    /// Eq. 5's weights and the battery's power model.
    #[serde(default)]
    pub energy: EnergySpec,
    /// Which objective is minimised and the weights of its terms.
    #[serde(default)]
    pub objective: ObjectiveSpec,
    /// Schedule, separation, zones, pace and departure delays.
    #[serde(default)]
    pub timing: TimingSpec,
    /// Free waypoints per UAV, default seed and feasibility profile.
    #[serde(default)]
    pub planning: PlanningSpec,
}

/// Where the local frame sits on the Earth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GeoSpec {
    /// WGS 84 latitude (deg), longitude (deg) and altitude (m above mean sea level) of the
    /// local point (0, 0) at local height 0.
    #[serde(deserialize_with = "exactly")]
    pub origin: [f64; 3],
}

/// Where the height grid comes from and how it is read.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TerrainSpec {
    /// `procedural` (built in, from `procedural` below) or a path to a GeoTIFF / ESRI ASCII
    /// grid, relative to the scenario file.
    pub source: String,
    /// `spso-pixels`: one cell = 1 m, x = column + 1, y = file row + 1 (SPSO's convention);
    /// `georeferenced`: cell size and orientation from the file, origin at its south-west node.
    pub frame: TerrainFrame,
    /// `bilinear` (default) or `nearest-matlab` (SPSO's `H(round(y), round(x))`).
    pub sampling: super::terrain::Sampling,
    /// Parameters of the procedural terrain (used when `source = "procedural"`).
    pub procedural: super::procedural::ProceduralParams,
}

impl Default for TerrainSpec {
    fn default() -> Self {
        Self {
            source: "procedural".into(),
            frame: TerrainFrame::SpsoPixels,
            sampling: super::terrain::Sampling::Bilinear,
            procedural: super::procedural::ProceduralParams::default(),
        }
    }
}

/// How a terrain file's grid is placed in the local frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum TerrainFrame {
    /// One cell = 1 m, x = column + 1, y = file row + 1 (SPSO's convention; default).
    #[default]
    SpsoPixels,
    /// Cell size and orientation from the file, origin at its south-west node.
    Georeferenced,
}

/// The box waypoints live in, and the altitude band above ground.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MapSpec {
    /// x range, metres ([1, 1045], SPSO's map).
    #[serde(deserialize_with = "exactly")]
    pub x: [f64; 2],
    /// y range, metres ([1, 879]).
    #[serde(deserialize_with = "exactly")]
    pub y: [f64; 2],
    /// Height above ground of free waypoints, metres ([100, 200], SPSO's z band).
    #[serde(deserialize_with = "exactly")]
    pub z_agl: [f64; 2],
    /// Minimum clearance above terrain along every segment, metres (10).
    pub clearance: f64,
    /// Spacing of the terrain samples along a segment, metres (5).
    pub clearance_step: f64,
}

impl Default for MapSpec {
    fn default() -> Self {
        Self {
            x: [1.0, 1045.0],
            y: [1.0, 879.0],
            z_agl: [100.0, 200.0],
            clearance: 10.0,
            clearance_step: 5.0,
        }
    }
}

/// UGV0, the landing point shared by the fleet.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalSpec {
    /// Position `[x, y]` and arrival height above ground `[z]` of the UAVs, metres.
    #[serde(deserialize_with = "exactly")]
    pub position: [f64; 3],
    /// Antenna height of UGV0 above ground, metres (2).
    #[serde(default = "default_antenna")]
    pub antenna: f64,
}

fn default_antenna() -> f64 {
    2.0
}

/// One UAV: start, kinematic limits, payload, battery.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UavSpec {
    /// Start [x, y, z above ground], metres ((200, 100, 150) in the paper).
    #[serde(deserialize_with = "exactly")]
    pub start: [f64; 3],
    /// Maximum turn angle at a waypoint, degrees (45).
    pub max_turn_deg: f64,
    /// Minimum turning radius R, metres (50, the paper's). Under the strict profile the
    /// vehicle flies an arc of radius R through each corner, which needs R tan(theta / 2)
    /// of straight flight on each side of a turn of angle theta; 0 flies the corners
    /// sharp (docs/model.md, "Turning radius and the flown path").
    pub turn_radius: f64,
    /// Maximum climb / dive angle of a segment, degrees (45).
    pub max_climb_deg: f64,
    /// Speed range [v_min, v_max], m/s ([5, 25]).
    #[serde(deserialize_with = "exactly")]
    pub speed: [f64; 2],
    /// Preferred cruise speed, m/s (15).
    pub cruise_speed: f64,
    /// Payload W_i, kg (0.5).
    pub payload_kg: f64,
    /// Maximum payload W_max, kg (1.0).
    pub max_payload_kg: f64,
    /// Battery capacity, watt-hours (see docs/model.md for the calibration).
    pub battery_wh: f64,
    /// Fraction of the battery kept in reserve (0.2).
    pub reserve: f64,
    /// Drone size for the threat and danger distances, metres (1, as SPSO).
    pub size: f64,
}

impl Default for UavSpec {
    fn default() -> Self {
        Self {
            start: [200.0, 100.0, 150.0],
            max_turn_deg: 45.0,
            turn_radius: 50.0,
            max_climb_deg: 45.0,
            speed: [5.0, 25.0],
            cruise_speed: 15.0,
            payload_kg: 0.5,
            max_payload_kg: 1.0,
            battery_wh: 6.0,
            reserve: 0.2,
            size: 1.0,
        }
    }
}

/// Which connectivity counts as "in contact".
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum CommRequirement {
    /// Every UAV is connected to a ground node, possibly through other UAVs (default).
    #[default]
    Relay,
    /// Every UAV has at least one link to any node (the paper's wording, relaxed).
    Neighbour,
    /// Communication is not checked.
    None,
}

/// A ground node besides UGV0 and the ground station.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundNodeSpec {
    /// Name of the node, as reports and error messages give it.
    pub name: String,
    /// [x, y], metres.
    #[serde(deserialize_with = "exactly")]
    pub position: [f64; 2],
    /// Antenna height above ground, metres (2).
    #[serde(default = "default_antenna")]
    pub antenna: f64,
}

/// A scheduled interference window: extra loss on every link with an end inside the disk.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InterferenceSpec {
    /// [start, end] time, seconds.
    #[serde(deserialize_with = "exactly")]
    pub time: [f64; 2],
    /// Disk centre [x, y], metres.
    #[serde(deserialize_with = "exactly")]
    pub center: [f64; 2],
    /// Disk radius, metres.
    pub radius: f64,
    /// Extra path loss, dB.
    pub loss_db: f64,
}

/// The time-varying channel.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CommSpec {
    /// Which connectivity counts as in contact (`relay`).
    pub requirement: CommRequirement,
    /// Nominal range R0, metres.
    pub range: f64,
    /// Shadowing standard deviation sigma, dB (4).
    pub shadowing_sigma_db: f64,
    /// Shadowing correlation time tau, seconds (10).
    pub shadowing_tau_s: f64,
    /// Seed of the shadowing process (the channel is generated once per scenario).
    pub seed: u64,
    /// Time step of the connectivity check, seconds (1).
    pub time_step: f64,
    /// Longest tolerated outage of one UAV, seconds in a row (5).
    pub max_outage_s: f64,
    /// Check line of sight against the terrain (true).
    pub line_of_sight: bool,
    /// Spacing of line-of-sight samples, metres (10).
    pub line_of_sight_step: f64,
    /// A ground control station at the shared start (true).
    pub ground_station: bool,
    /// Cost of each UAV-second out of contact, metres-equivalent (10), added to the gap.
    pub outage_base_cost: f64,
    /// Ground nodes besides UGV0 and the ground station (none).
    pub ground_nodes: Vec<GroundNodeSpec>,
    /// Scheduled interference windows (none).
    pub interference: Vec<InterferenceSpec>,
}

impl Default for CommSpec {
    fn default() -> Self {
        Self {
            requirement: CommRequirement::Relay,
            range: 700.0,
            shadowing_sigma_db: 4.0,
            shadowing_tau_s: 10.0,
            seed: 1,
            time_step: 1.0,
            max_outage_s: 5.0,
            line_of_sight: true,
            line_of_sight_step: 10.0,
            ground_station: true,
            outage_base_cost: 10.0,
            ground_nodes: Vec::new(),
            interference: Vec::new(),
        }
    }
}

/// Energy: the paper's Eq. 5 objective weights and the physical model for the battery.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EnergySpec {
    /// alpha of Eq. 5: weight of |dz| (per metre of altitude change) (1).
    pub alpha: f64,
    /// beta of Eq. 5: weight of |d heading| (per radian) (10).
    pub beta: f64,
    /// Rotary-wing power model (Zeng, Xu, Zhang 2019).
    pub model: RotaryWing,
}

impl Default for EnergySpec {
    fn default() -> Self {
        Self {
            alpha: 1.0,
            beta: 10.0,
            model: RotaryWing::default(),
        }
    }
}

/// How UAVs are scheduled along their paths.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum TimingPolicy {
    /// All leave at t = 0 and arrive together; speeds L_i / T nearest to cruise (default).
    #[default]
    CommonArrival,
    /// Every UAV flies at its own cruise speed.
    Cruise,
}

/// How the fleet is timed: schedule, separation, take-off and landing zones, pace and
/// departure delays.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TimingSpec {
    /// How UAVs are scheduled along their paths (`common-arrival`).
    pub policy: TimingPolicy,
    /// Minimum distance between two UAVs at the same time, metres (10).
    pub separation: f64,
    /// Radius of the take-off and landing zones where separation is not required, m (30).
    pub zone_radius: f64,
    /// Range [lo, hi] of the fleet's pace, a factor on the policy's preferred speed
    /// ([`crate::timing`]) that the planner chooses as a decision variable when lo < hi
    /// (one more variable per UAV block; the fleet flies at their mean). [1, 1] (the
    /// default): no choice, the paper's layout (and not written out).
    #[serde(skip_serializing_if = "is_fixed_unit_pace")]
    #[serde(deserialize_with = "exactly")]
    pub pace: [f64; 2],
    /// Largest departure delay, as a share of the mission: UAV i may wait (hovering at its
    /// start) for delta_i x its arrival time before it leaves, with delta_i in
    /// [0, max_delay] chosen by the planner (one more variable per UAV block). Why: a UAV
    /// that waits above the ground station can relay for the others while they fly out of
    /// its sight (docs/model.md, "Departure delays"). 0 (the default): everyone leaves at
    /// t = 0, the paper's layout (and not written out).
    #[serde(skip_serializing_if = "is_zero")]
    pub max_delay: f64,
    /// Seconds between two launches from one take-off place ([`crate::world::slots`]): UAVs
    /// whose starts lie within `zone_radius` of each other leave one after another, in the
    /// scenario's order. 0 (the default): everyone may leave at t = 0, the paper's layout
    /// (and not written out).
    #[serde(skip_serializing_if = "is_zero")]
    pub launch_interval: f64,
    /// Seconds between two recoveries at UGV0 under common arrival: UAV i lands at
    /// T + i x this. 0 (the default): everyone lands at T, the paper's layout (and not
    /// written out).
    #[serde(skip_serializing_if = "is_zero")]
    pub recovery_interval: f64,
}

impl Default for TimingSpec {
    fn default() -> Self {
        Self {
            policy: TimingPolicy::CommonArrival,
            separation: 10.0,
            zone_radius: 30.0,
            pace: [1.0, 1.0],
            max_delay: 0.0,
            launch_interval: 0.0,
            recovery_interval: 0.0,
        }
    }
}

#[allow(clippy::trivially_copy_pass_by_ref, clippy::float_cmp)]
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

#[allow(clippy::trivially_copy_pass_by_ref, clippy::float_cmp)]
fn is_fixed_unit_pace(p: &[f64; 2]) -> bool {
    *p == [1.0, 1.0]
}

impl TimingSpec {
    /// Whether the pace is a decision variable (`pace[0] < pace[1]`).
    #[must_use]
    pub fn pace_is_free(&self) -> bool {
        self.pace[0] < self.pace[1]
    }

    /// Whether a plan may fly at pace `p` here (inside `pace`, bounds included), as plan
    /// files and re-imported missions are checked.
    #[must_use]
    pub fn allows_pace(&self, p: f64) -> bool {
        (self.pace[0]..=self.pace[1]).contains(&p)
    }

    /// Whether departure delays are decision variables (`max_delay > 0`).
    #[must_use]
    pub fn delay_is_free(&self) -> bool {
        self.max_delay > 0.0
    }

    /// Whether a plan may delay a departure by share `d` here (in [0, max_delay]).
    #[must_use]
    pub fn allows_delay(&self, d: f64) -> bool {
        (0.0..=self.max_delay).contains(&d)
    }
}

/// The largest `timing.max_delay`: every UAV keeps at least a tenth of the mission to fly.
pub const MAX_DELAY_LIMIT: f64 = 0.9;

/// Decision-variable layout and seeds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PlanningSpec {
    /// Free waypoints per UAV (10, as SPSO).
    pub waypoints: usize,
    /// Spherical encoding with SPSO's angle convention (x uses sin phi) (false).
    pub spso_angles: bool,
    /// Default seed of `plan` when none is given.
    pub seed: u64,
    /// Which violations decide feasibility: `strict` (all) or `paper` (threats, terrain,
    /// turns, energy; the rest only cost) ([`crate::feasibility::FeasibilityProfile`]).
    pub profile: crate::feasibility::FeasibilityProfile,
}

impl Default for PlanningSpec {
    fn default() -> Self {
        Self {
            waypoints: 10,
            spso_angles: false,
            seed: 1,
            profile: crate::feasibility::FeasibilityProfile::Strict,
        }
    }
}
