//! Hard constraints, each violation named: kind, UAV (and the other UAV for separation),
//! place and time, and how far past the limit. FR in Tables 4-5 is the share of runs whose
//! best plan has none.
//!
//! The same code path serves the optimizer's hot loop and the report: a [`ViolationSink`]
//! always sums a scalar measure of violation, and keeps the list only when asked to, so the
//! hot loop does not allocate.

use glam::DVec3;
use serde::{Deserialize, Serialize};

use crate::cost::assess;
use crate::plan::Plan;
use crate::world::World;

/// Which violation kinds are hard (decide feasibility) and which only cost.
///
/// `strict` (the default) makes every kind hard: the plan must fly. `paper` follows the
/// paper's FR definition (Section 4): obstacle avoidance (threats and terrain), the
/// turning-angle limit and the energy limit are hard; every other kind (communication,
/// UAV-UAV separation, climb, altitude band, map box, speed, payload) is *soft*: it still
/// adds its penalty to the cost, as the paper's Eqs. 6 and 8 make communication and
/// proximity cost terms, but it does not make the plan infeasible. Tables 4-5 in both
/// profiles let a reader hold our FR against the paper's.
///
/// The profiles also differ in what is assessed (issue 15, [`World::flies_arcs`]): `strict`
/// assesses the *flown* path, an arc of each UAV's turning radius through every corner, and
/// requires the straight flight those arcs need; `paper` keeps the paper's model of straight
/// segments with a turn-angle limit, and no turning radius.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FeasibilityProfile {
    /// Every kind is hard, and the flown path with its turning arcs is assessed (default).
    #[default]
    Strict,
    /// The paper's FR: threats, terrain, turn angle and energy are hard, the rest soft;
    /// straight segments, no turning radius.
    Paper,
}

impl FeasibilityProfile {
    /// Both profiles.
    pub const ALL: [Self; 2] = [Self::Strict, Self::Paper];

    /// The name used in scenario files and records (`strict`, `paper`).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Strict => "strict",
            Self::Paper => "paper",
        }
    }

    /// Whether a violation of `kind` makes a plan infeasible under this profile.
    #[must_use]
    pub const fn is_hard(self, kind: ViolationKind) -> bool {
        match self {
            Self::Strict => true,
            Self::Paper => matches!(
                kind,
                ViolationKind::Threat
                    | ViolationKind::Terrain
                    | ViolationKind::Turn
                    | ViolationKind::Energy
            ),
        }
    }

    /// The profile named `name`.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.name() == name)
    }
}

impl std::fmt::Display for FeasibilityProfile {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// What was violated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ViolationKind {
    /// Inside a threat cylinder (r + drone size); amount in metres.
    Threat,
    /// Below terrain + clearance along a segment; amount in metres.
    Terrain,
    /// A free waypoint outside the altitude band above ground; amount in metres.
    Altitude,
    /// A waypoint outside the map box; amount in metres.
    Bounds,
    /// Turn angle above the limit at a waypoint; amount in degrees.
    Turn,
    /// Climb or dive angle above the limit on a segment; amount in degrees.
    Climb,
    /// Too little straight flight between turns for the turning radius: the tangent lengths
    /// R tan(theta / 2) of a segment's two ends exceed it; amount in metres (strict profile,
    /// issue 15; the paper's model has no turning radius).
    TurnRadius,
    /// Speed outside [v_min, v_max]; amount in m/s.
    Speed,
    /// Payload above W_max; amount in kg.
    Payload,
    /// Energy above the usable battery; amount in percent of the usable energy.
    Energy,
    /// Two UAVs closer than the separation distance; amount in metres.
    Separation,
    /// A UAV out of contact longer than tolerated; amount in seconds beyond the tolerance.
    Comm,
}

impl ViolationKind {
    /// Every kind.
    pub const ALL: [ViolationKind; 12] = [
        Self::Threat,
        Self::Terrain,
        Self::Altitude,
        Self::Bounds,
        Self::Turn,
        Self::Climb,
        Self::TurnRadius,
        Self::Speed,
        Self::Payload,
        Self::Energy,
        Self::Separation,
        Self::Comm,
    ];

    /// The name used in reports and records (`threat`, `turn-radius`, ...).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Threat => "threat",
            Self::Terrain => "terrain",
            Self::Altitude => "altitude",
            Self::Bounds => "bounds",
            Self::Turn => "turn",
            Self::Climb => "climb",
            Self::TurnRadius => "turn-radius",
            Self::Speed => "speed",
            Self::Payload => "payload",
            Self::Energy => "energy",
            Self::Separation => "separation",
            Self::Comm => "comm",
        }
    }

    /// The amount that counts as one unit of violation, in the kind's unit. The violation
    /// measure adds `1 + amount / scale` per violation, so metres, degrees, seconds, per cent
    /// and kilograms are put on one footing before they are summed: any violation counts at
    /// least 1, and each further unit adds 1. A unit is the resolution at which a violation
    /// still matters to an operator and at which the penalty (1000 per unit by default)
    /// outweighs what the objective pays for avoiding it (about 5-15 per metre of path):
    /// 1 m of geometry (threat, terrain, altitude band, map box, separation, straight flight
    /// missing for the turning radius), 1 deg of turn
    /// or climb, 0.1 m/s of speed, 0.01 kg of payload, 1 % of the usable battery, 1 s of
    /// contact beyond the tolerated outage. (The first build summed raw amounts, which
    /// made a kilogram of payload weigh as much as a metre of threat intrusion.)
    #[must_use]
    pub const fn scale(self) -> f64 {
        match self {
            Self::Threat
            | Self::Terrain
            | Self::Altitude
            | Self::Bounds
            | Self::Separation
            | Self::TurnRadius => 1.0,
            Self::Turn | Self::Climb => 1.0,
            Self::Speed => 0.1,
            Self::Payload => 0.01,
            Self::Energy | Self::Comm => 1.0,
        }
    }

    /// Unit of the amount.
    #[must_use]
    pub const fn unit(self) -> &'static str {
        match self {
            Self::Threat
            | Self::Terrain
            | Self::Altitude
            | Self::Bounds
            | Self::Separation
            | Self::TurnRadius => "m",
            Self::Turn | Self::Climb => "deg",
            Self::Speed => "m/s",
            Self::Payload => "kg",
            Self::Energy => "%",
            Self::Comm => "s",
        }
    }
}

/// One broken hard constraint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Violation {
    /// What was violated.
    pub kind: ViolationKind,
    /// Index of the UAV that violated it.
    pub uav: usize,
    /// The other UAV of a separation violation.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub other: Option<usize>,
    /// Waypoint or segment index where it applies (segment k joins waypoints k and k + 1).
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub index: Option<usize>,
    /// Where (x, y, absolute altitude), when a place applies.
    #[serde(skip_serializing_if = "Option::is_none", default)]
    pub position: Option<[f64; 3]>,
    /// When (seconds after departure), when a time applies.
    #[serde(
        skip_serializing_if = "Option::is_none",
        default,
        with = "crate::json_f64::option"
    )]
    pub time: Option<f64>,
    /// How far past the limit, in the unit of the kind.
    #[serde(with = "crate::json_f64")]
    pub amount: f64,
    /// A sentence for humans.
    pub detail: String,
    /// Whether it decides feasibility under the profile (false: it only costs).
    #[serde(default = "hard_default", skip_serializing_if = "is_true")]
    pub hard: bool,
}

const fn hard_default() -> bool {
    true
}

#[allow(clippy::trivially_copy_pass_by_ref)] // serde's skip_serializing_if passes a reference
const fn is_true(b: &bool) -> bool {
    *b
}

/// Collects violations: always their scalar measure, the list only on request.
#[derive(Debug, Default)]
pub struct ViolationSink {
    /// Sum over hard violations of (1 + amount / scale of its kind): any violation counts at
    /// least 1 ([`ViolationKind::scale`]).
    pub measure: f64,
    /// The same sum over soft violations (those the profile counts in the cost only).
    pub soft: f64,
    /// How many violations, hard and soft, were added.
    pub count: usize,
    /// Which kinds are hard and which only cost.
    pub profile: FeasibilityProfile,
    /// Every violation added, hard and soft, with place and detail, when collecting (`None`
    /// otherwise).
    pub list: Option<Vec<Violation>>,
    /// Each UAV's share of `measure`, on request: a violation counts for its UAV and, for a
    /// pair (separation), for the other UAV too. Lets a decomposing optimizer see which
    /// UAVs' paths hold the violations.
    pub by_uav: Option<Vec<f64>>,
    /// Every violation added, as [`Deferred`], on request: lets a bounded assessment check
    /// one part of a plan before the rest and still add the violations in the usual order
    /// ([`ViolationSink::replay_into`]), so the sums come out the same bits.
    pub deferred: Option<Vec<Deferred>>,
}

/// A violation as [`ViolationSink::add`] received it (amount already made finite), to be
/// added again elsewhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Deferred {
    /// What was violated.
    pub kind: ViolationKind,
    /// Index of the UAV that violated it.
    pub uav: usize,
    /// How far past the limit, in the unit of the kind.
    pub amount: f64,
    /// The other UAV of a separation violation.
    pub other: Option<usize>,
}

/// Where and when a violation happened (all optional).
#[derive(Debug, Clone, Copy, Default)]
pub struct At {
    /// The other UAV of a separation violation.
    pub other: Option<usize>,
    /// Waypoint or segment index where it applies.
    pub index: Option<usize>,
    /// Where (x, y, absolute altitude), m.
    pub position: Option<DVec3>,
    /// When, s after departure.
    pub time: Option<f64>,
}

impl ViolationSink {
    /// A sink that sums only, under `profile`.
    #[must_use]
    pub fn new(profile: FeasibilityProfile) -> Self {
        Self {
            profile,
            ..Self::default()
        }
    }

    /// A sink that also keeps the list, under `profile`.
    #[must_use]
    pub fn collecting(profile: FeasibilityProfile) -> Self {
        Self {
            list: Some(Vec::new()),
            ..Self::new(profile)
        }
    }

    /// Also sums each UAV's share of the hard measure into [`ViolationSink::by_uav`]
    /// (`uavs` entries, cleared).
    #[must_use]
    pub fn sharing(mut self, uavs: usize, mut buffer: Vec<f64>) -> Self {
        buffer.clear();
        buffer.resize(uavs, 0.0);
        self.by_uav = Some(buffer);
        self
    }

    /// Whether the sink keeps the list of violations.
    #[must_use]
    pub fn is_collecting(&self) -> bool {
        self.list.is_some()
    }

    /// Also records every violation into `buffer` (cleared) for
    /// [`ViolationSink::replay_into`].
    #[must_use]
    pub fn deferring(mut self, mut buffer: Vec<Deferred>) -> Self {
        buffer.clear();
        self.deferred = Some(buffer);
        self
    }

    /// Adds the recorded violations to `other`, in the order they came: the sums of `other`
    /// are then what they would be had they been added there in the first place. When this
    /// sink keeps the list, the list is replayed, places, times and details included (for an
    /// `other` that keeps one); otherwise the record, which carries none (so `other` must not
    /// be keeping a list).
    pub fn replay_into(&self, other: &mut ViolationSink) {
        match &self.list {
            Some(list) => {
                for v in list {
                    let at = At {
                        other: v.other,
                        index: v.index,
                        position: v.position.map(DVec3::from_array),
                        time: v.time,
                    };
                    other.add(v.kind, v.uav, v.amount, at, || v.detail.clone());
                }
            }
            None => other.replay(self.deferred.as_deref().unwrap_or_default()),
        }
    }

    /// Adds violations recorded by a deferring sink, in their order (no place, time or
    /// detail, so this sink must not be collecting a list).
    pub fn replay(&mut self, found: &[Deferred]) {
        debug_assert!(!self.is_collecting(), "a replay carries no details");
        for d in found {
            self.add(
                d.kind,
                d.uav,
                d.amount,
                At {
                    other: d.other,
                    ..At::default()
                },
                String::new,
            );
        }
    }

    /// Records a violation; `detail` is only built when the list is kept.
    pub fn add(
        &mut self,
        kind: ViolationKind,
        uav: usize,
        amount: f64,
        at: At,
        detail: impl FnOnce() -> String,
    ) {
        let amount = if amount.is_finite() {
            amount.max(0.0)
        } else {
            1e9
        };
        if let Some(d) = &mut self.deferred {
            d.push(Deferred {
                kind,
                uav,
                amount,
                other: at.other,
            });
        }
        self.count += 1;
        let hard = self.profile.is_hard(kind);
        if hard {
            let m = 1.0 + amount / kind.scale();
            self.measure += m;
            if let Some(shares) = &mut self.by_uav {
                for u in std::iter::once(uav).chain(at.other) {
                    if let Some(s) = shares.get_mut(u) {
                        *s += m;
                    }
                }
            }
        } else {
            self.soft += 1.0 + amount / kind.scale();
        }
        if let Some(list) = &mut self.list {
            list.push(Violation {
                kind,
                uav,
                other: at.other,
                index: at.index,
                position: at.position.map(|p| p.to_array()),
                time: at.time,
                amount,
                detail: detail(),
                hard,
            });
        }
    }
}

/// Every violation of `plan` in `world`.
#[must_use]
pub fn check(world: &World, plan: &Plan) -> Vec<Violation> {
    assess(world, plan).violations.unwrap_or_default()
}
