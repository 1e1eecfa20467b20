//! Checks a [`ScenarioSpec`] before anything is built from it, so the hot path can assume
//! valid values. Each error names the field (`uavs[2].speed`) and what was expected.
//!
//! **Work limits.** Some valid-looking values would make one evaluation take hours or a
//! table take terabytes (a clearance sample every nanometre, a channel step of a
//! nanosecond). The limits below are derived from the scenario's own size, so a large map
//! may use a coarse step and a small one a fine step:
//!
//! | field | limit | why |
//! |---|---|---|
//! | `map.clearance_step` | >= map diagonal / [`MAX_SAMPLES_PER_SEGMENT`] | terrain samples per segment |
//! | `communication.line_of_sight_step` | >= map diagonal / [`MAX_SAMPLES_PER_SEGMENT`] | line-of-sight samples per link, horizon table length per azimuth |
//! | `communication.time_step` | >= [`MIN_TIME_STEP_S`] | channel table entries over its horizon, steps per evaluation |
//! | map box | within [`MAX_MAP_EXTENT_M`] on each axis | keeps every table and sample count above finite |

use thiserror::Error;

use super::horizon::HORIZON_BINS;
use super::procedural::{ProceduralError, MAX_HILLS, MAX_NODES};
use super::spec::{CommRequirement, ObjectivePreset, ScenarioSpec};

/// A field with a bad value.
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{field}: {expected}, got {got}")]
pub struct SpecError {
    /// Path of the field (`uavs[2].speed`).
    pub field: String,
    /// What values it accepts, in words.
    pub expected: String,
    /// The value it was given, as displayed.
    pub got: String,
}

fn err(field: impl Into<String>, expected: impl Into<String>, got: impl ToString) -> SpecError {
    SpecError {
        field: field.into(),
        expected: expected.into(),
        got: got.to_string(),
    }
}

/// The procedural terrain's complaint as the field it is about.
fn procedural_field(e: ProceduralError) -> SpecError {
    let at = |f: &str| format!("terrain.procedural.{f}");
    match e {
        ProceduralError::NotPositive { field, value } => {
            err(at(field), "a positive finite number", value)
        }
        ProceduralError::NotFinite { field, value } => err(at(field), "a finite number", value),
        ProceduralError::EmptyHeightRange { min, max } => err(
            at("max_height"),
            format!("more than min_height ({min})"),
            max,
        ),
        ProceduralError::TooManyHills { hills } => {
            err(at("hills"), format!("at most {MAX_HILLS}"), hills)
        }
        ProceduralError::TooManyNodes { cell, nodes } => err(
            at("cell"),
            format!("a cell giving at most {MAX_NODES} grid nodes (this one: about {nodes:.0}); a larger cell"),
            cell,
        ),
    }
}

fn finite(field: &str, v: f64) -> Result<(), SpecError> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(err(field, "a finite number", v))
    }
}

fn positive(field: &str, v: f64) -> Result<(), SpecError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(err(field, "a positive number", v))
    }
}

fn non_negative(field: &str, v: f64) -> Result<(), SpecError> {
    if v.is_finite() && v >= 0.0 {
        Ok(())
    } else {
        Err(err(field, "a number >= 0", v))
    }
}

/// Longest launch or recovery interval, seconds.
pub const MAX_SLOT_INTERVAL_S: f64 = 600.0;

/// Most samples one segment (or one link) is checked at; see the module's table.
pub const MAX_SAMPLES_PER_SEGMENT: f64 = 10_000.0;
/// Smallest communication time step, seconds: the channel table then has at most
/// 3600 / 0.01 = 360,000 entries.
pub const MIN_TIME_STEP_S: f64 = 0.01;
/// Largest side of the map box, metres (a 1,000 km square).
pub const MAX_MAP_EXTENT_M: f64 = 1.0e6;
/// Most horizon-table entries of all ground nodes together (4 bytes each: 1 GiB). Each node
/// holds [`HORIZON_BINS`] bearings x (map diagonal / line-of-sight step) entries: 164 MB at
/// the finest step this limit's table allows, so ten relays took 1.5 GB and a thousand at
/// the default step 2 GB, without a word.
pub const MAX_HORIZON_ENTRIES: f64 = 268_435_456.0;
/// Largest size of a horizontal coordinate (the map box, starts, goal, threats, ground
/// nodes, interference centres), metres: room for projected coordinates such as UTM
/// northings (up to 10,000 km), while squares and differences of positions stay finite (a
/// coordinate of 1e200 made a path length NaN, and its plan was counted feasible).
pub const MAX_COORDINATE_M: f64 = 1.0e8;
/// Largest size of a height (starts, goal, threats, the map's altitude band, the procedural
/// terrain's heights), metres: 100 km, the edge of space.
pub const MAX_HEIGHT_M: f64 = 1.0e5;

/// `v` finite and at most `limit` in size (a coordinate or a height).
fn bounded(field: &str, v: f64, limit: f64) -> Result<(), SpecError> {
    if v.is_finite() && v.abs() <= limit {
        Ok(())
    } else {
        Err(err(
            field,
            format!("a number in [-{limit:e}, {limit:e}] m"),
            number(v),
        ))
    }
}

/// `v` for a message: as written, or as an exponent from a billion on (1e300 is a valid
/// number and would otherwise print as 301 digits).
pub(crate) fn number(v: f64) -> String {
    if v.abs() >= 1e9 {
        format!("{v:e}")
    } else {
        v.to_string()
    }
}

fn coordinate(field: &str, v: f64) -> Result<(), SpecError> {
    bounded(field, v, MAX_COORDINATE_M)
}

fn height(field: &str, v: f64) -> Result<(), SpecError> {
    bounded(field, v, MAX_HEIGHT_M)
}

/// A sampling step `v` (m) fine enough for a map of this `diagonal`: at most
/// `MAX_SAMPLES_PER_SEGMENT` samples along it.
fn fine_enough(field: &str, v: f64, diagonal: f64) -> Result<(), SpecError> {
    let min_step = diagonal / MAX_SAMPLES_PER_SEGMENT;
    if v >= min_step {
        Ok(())
    } else {
        Err(err(
            field,
            format!("at least {min_step:.3} m on this map (its diagonal {diagonal:.0} m / {MAX_SAMPLES_PER_SEGMENT:.0} samples)"),
            v,
        ))
    }
}

fn range(field: &str, r: [f64; 2]) -> Result<(), SpecError> {
    if r[0].is_finite() && r[1].is_finite() && r[0] < r[1] {
        Ok(())
    } else {
        Err(err(field, "[lo, hi] with lo < hi", format!("{r:?}")))
    }
}

impl ScenarioSpec {
    /// Checks every value; the first problem found is returned.
    pub fn validate(&self) -> Result<(), SpecError> {
        if self.name.trim().is_empty() {
            return Err(err("name", "a non-empty name", "\"\""));
        }
        self.validate_geo()?;
        self.validate_map()?;
        self.validate_terrain()?;
        self.validate_threats_and_goal()?;
        self.validate_uavs()?;
        self.validate_communication()?;
        self.validate_energy()?;
        self.validate_objective()?;
        self.validate_timing_and_planning()
    }

    /// The map's diagonal, m: what the finest sampling steps are measured against.
    fn map_diagonal(&self) -> f64 {
        let m = &self.map;
        (m.x[1] - m.x[0]).hypot(m.y[1] - m.y[0])
    }

    /// `[geo]`: an origin on the Earth.
    fn validate_geo(&self) -> Result<(), SpecError> {
        if let Some(g) = &self.geo {
            let [lat, lon, alt] = g.origin;
            if !(lat.is_finite() && (-90.0..=90.0).contains(&lat)) {
                return Err(err(
                    "geo.origin",
                    "a latitude in [-90, 90] degrees first",
                    lat,
                ));
            }
            if !(lon.is_finite() && (-180.0..=180.0).contains(&lon)) {
                return Err(err(
                    "geo.origin",
                    "a longitude in [-180, 180] degrees second",
                    lon,
                ));
            }
            finite("geo.origin", alt)?;
        }
        Ok(())
    }

    /// `[map]`: the box, its size, heights and the clearance sampling.
    fn validate_map(&self) -> Result<(), SpecError> {
        let m = &self.map;
        range("map.x", m.x)?;
        range("map.y", m.y)?;
        range("map.z_agl", m.z_agl)?;
        for (field, r) in [("map.x", m.x), ("map.y", m.y)] {
            if r[1] - r[0] > MAX_MAP_EXTENT_M {
                return Err(err(
                    field,
                    format!("a side of at most {MAX_MAP_EXTENT_M:.0} m"),
                    format!("{r:?} ({:.3e} m)", r[1] - r[0]),
                ));
            }
        }
        for (field, r, check) in [
            (
                "map.x",
                m.x,
                coordinate as fn(&str, f64) -> Result<(), SpecError>,
            ),
            ("map.y", m.y, coordinate),
            ("map.z_agl", m.z_agl, height),
        ] {
            r.iter().try_for_each(|&v| check(field, v))?;
        }
        non_negative("map.clearance", m.clearance)?;
        positive("map.clearance_step", m.clearance_step)?;
        let diagonal = (m.x[1] - m.x[0]).hypot(m.y[1] - m.y[0]);
        fine_enough("map.clearance_step", m.clearance_step, diagonal)?;
        Ok(())
    }

    /// `[terrain]`: the procedural generator's parameters.
    fn validate_terrain(&self) -> Result<(), SpecError> {
        self.terrain
            .procedural
            .validate()
            .map_err(procedural_field)?;
        let pr = &self.terrain.procedural;
        height("terrain.procedural.min_height", pr.min_height)?;
        height("terrain.procedural.max_height", pr.max_height)?;
        if self.terrain.source == "procedural" && pr.cell > 0.5 * pr.width.min(pr.height) {
            return Err(err(
                "terrain.procedural.cell",
                format!(
                    "at most half the terrain's smaller side ({} m)",
                    0.5 * pr.width.min(pr.height)
                ),
                pr.cell,
            ));
        }
        Ok(())
    }

    /// `[[threats]]` and `[goal]`.
    fn validate_threats_and_goal(&self) -> Result<(), SpecError> {
        for (k, t) in self.threats.iter().enumerate() {
            coordinate(&format!("threats[{k}].x"), t.x)?;
            coordinate(&format!("threats[{k}].y"), t.y)?;
            height(&format!("threats[{k}].z"), t.z)?;
            positive(&format!("threats[{k}].r"), t.r)?;
        }
        let g = &self.goal;
        for (c, v) in ["x", "y"].iter().zip(g.position) {
            coordinate(&format!("goal.position.{c}"), v)?;
        }
        height("goal.position.z", g.position[2])?;
        non_negative("goal.antenna", g.antenna)?;
        Ok(())
    }

    /// `[[uavs]]`: at least one, each within its limits.
    fn validate_uavs(&self) -> Result<(), SpecError> {
        if self.uavs.is_empty() {
            return Err(err("uavs", "at least one UAV", 0));
        }
        for (k, u) in self.uavs.iter().enumerate() {
            let f = |s: &str| format!("uavs[{k}].{s}");
            for (c, v) in ["x", "y"].iter().zip(u.start) {
                coordinate(&f(&format!("start.{c}")), v)?;
            }
            height(&f("start.z"), u.start[2])?;
            if !(u.max_turn_deg > 0.0 && u.max_turn_deg <= 180.0) {
                return Err(err(
                    f("max_turn_deg"),
                    "an angle in (0, 180] degrees",
                    u.max_turn_deg,
                ));
            }
            if !(u.max_climb_deg > 0.0 && u.max_climb_deg <= 90.0) {
                return Err(err(
                    f("max_climb_deg"),
                    "a climb angle in (0, 90] degrees (90: vertical climbs allowed, as SPSO)",
                    u.max_climb_deg,
                ));
            }
            range(&f("speed"), u.speed)?;
            if u.speed[0] <= 0.0 {
                return Err(err(f("speed"), "v_min > 0", u.speed[0]));
            }
            positive(&f("cruise_speed"), u.cruise_speed)?;
            non_negative(&f("payload_kg"), u.payload_kg)?;
            non_negative(&f("max_payload_kg"), u.max_payload_kg)?;
            positive(&f("battery_wh"), u.battery_wh)?;
            if !(0.0..1.0).contains(&u.reserve) {
                return Err(err(f("reserve"), "a fraction in [0, 1)", u.reserve));
            }
            non_negative(&f("size"), u.size)?;
            non_negative(&f("turn_radius"), u.turn_radius)?;
        }
        Ok(())
    }

    /// `[communication]`: the channel, the ground nodes (and their horizon tables' memory) and the interference windows.
    fn validate_communication(&self) -> Result<(), SpecError> {
        let c = &self.communication;
        positive("communication.range", c.range)?;
        non_negative("communication.shadowing_sigma_db", c.shadowing_sigma_db)?;
        positive("communication.shadowing_tau_s", c.shadowing_tau_s)?;
        positive("communication.time_step", c.time_step)?;
        if c.time_step < MIN_TIME_STEP_S {
            return Err(err(
                "communication.time_step",
                format!("at least {MIN_TIME_STEP_S} s"),
                c.time_step,
            ));
        }
        non_negative("communication.max_outage_s", c.max_outage_s)?;
        positive("communication.line_of_sight_step", c.line_of_sight_step)?;
        fine_enough(
            "communication.line_of_sight_step",
            c.line_of_sight_step,
            self.map_diagonal(),
        )?;
        non_negative("communication.outage_base_cost", c.outage_base_cost)?;
        for (k, n) in c.ground_nodes.iter().enumerate() {
            coordinate(
                &format!("communication.ground_nodes[{k}].position.x"),
                n.position[0],
            )?;
            coordinate(
                &format!("communication.ground_nodes[{k}].position.y"),
                n.position[1],
            )?;
            non_negative(
                &format!("communication.ground_nodes[{k}].antenna"),
                n.antenna,
            )?;
        }
        if c.line_of_sight && c.requirement != CommRequirement::None {
            let fixed = usize::from(c.ground_station) + 1; // the station and UGV0
            let nodes = fixed + c.ground_nodes.len();
            #[allow(clippy::cast_precision_loss)] // 4096 bins, a checked number of steps
            let per_node =
                HORIZON_BINS as f64 * (self.map_diagonal() / c.line_of_sight_step).ceil().max(1.0);
            #[allow(clippy::cast_precision_loss)]
            if nodes as f64 * per_node > MAX_HORIZON_ENTRIES {
                let most = (MAX_HORIZON_ENTRIES / per_node).floor() - fixed as f64;
                return Err(err(
                    "communication.ground_nodes",
                    format!(
                        "at most {most:.0} relays at communication.line_of_sight_step {} m on this map (each ground node holds a horizon table of {:.0} MB; {nodes} nodes would take {:.1} GB); fewer relays or a coarser line_of_sight_step",
                        c.line_of_sight_step,
                        per_node * 4.0 / 1e6,
                        nodes as f64 * per_node * 4.0 / 1e9
                    ),
                    c.ground_nodes.len(),
                ));
            }
        }
        for (k, w) in c.interference.iter().enumerate() {
            let f = |s: &str| format!("communication.interference[{k}].{s}");
            range(&f("time"), w.time)?;
            coordinate(&f("center.x"), w.center[0])?;
            coordinate(&f("center.y"), w.center[1])?;
            positive(&f("radius"), w.radius)?;
            non_negative(&f("loss_db"), w.loss_db)?;
        }
        Ok(())
    }

    /// `[energy]`: Eq. 5's weights and the rotary-wing model.
    fn validate_energy(&self) -> Result<(), SpecError> {
        let e = &self.energy;
        non_negative("energy.alpha", e.alpha)?;
        non_negative("energy.beta", e.beta)?;
        let em = &e.model;
        for (name, v) in [
            ("weight_n", em.weight_n),
            ("air_density", em.air_density),
            ("rotor_radius", em.rotor_radius),
            ("disc_area", em.disc_area),
            ("blade_angular_velocity", em.blade_angular_velocity),
            ("tip_speed", em.tip_speed),
            ("solidity", em.solidity),
        ] {
            positive(&format!("energy.model.{name}"), v)?;
        }
        for (name, v) in [
            ("fuselage_drag_ratio", em.fuselage_drag_ratio),
            ("induced_correction", em.induced_correction),
            ("profile_drag", em.profile_drag),
            ("turn_energy_per_rad", em.turn_energy_per_rad),
        ] {
            non_negative(&format!("energy.model.{name}"), v)?;
        }
        Ok(())
    }

    /// `[objective]`: non-negative weights; the `spso-mycost` objective preset for one UAV only.
    fn validate_objective(&self) -> Result<(), SpecError> {
        let o = &self.objective;
        for (t, v) in o.weights.iter() {
            non_negative(&format!("objective.{}", t.name()), v)?;
        }
        non_negative("objective.violation_penalty", o.violation_penalty)?;
        positive("objective.obstacle_epsilon", o.obstacle_epsilon)?;
        if o.preset == ObjectivePreset::SpsoMycost && self.uavs.len() != 1 {
            return Err(err(
                "objective.preset",
                "exactly one UAV for the `spso-mycost` objective preset (SPSO's MyCost is single-UAV)",
                format!("{} UAVs", self.uavs.len()),
            ));
        }
        Ok(())
    }

    /// `[timing]` and `[planning]`.
    fn validate_timing_and_planning(&self) -> Result<(), SpecError> {
        let t = &self.timing;
        non_negative("timing.separation", t.separation)?;
        non_negative("timing.zone_radius", t.zone_radius)?;
        let positive = t.pace.iter().all(|p| p.is_finite() && *p > 0.0);
        if !(positive && (t.pace[0] < t.pace[1] || t.pace == [1.0, 1.0])) {
            return Err(err(
                "timing.pace",
                "[lo, hi] with 0 < lo < hi (the planner's range for a factor on the preferred speed), or [1, 1] for no choice",
                format!("{:?}", t.pace),
            ));
        }
        if !(0.0..=super::spec::MAX_DELAY_LIMIT).contains(&t.max_delay) {
            return Err(err(
                "timing.max_delay",
                format!(
                    "a share of the mission in [0, {}] (0: every UAV leaves at t = 0)",
                    super::spec::MAX_DELAY_LIMIT
                ),
                t.max_delay,
            ));
        }
        for (field, v) in [
            ("timing.launch_interval", t.launch_interval),
            ("timing.recovery_interval", t.recovery_interval),
        ] {
            if !(v.is_finite() && (0.0..=MAX_SLOT_INTERVAL_S).contains(&v)) {
                return Err(err(
                    field,
                    format!("seconds in [0, {MAX_SLOT_INTERVAL_S}] (0: everyone at once)"),
                    v,
                ));
            }
        }
        if t.recovery_interval > 0.0 && t.policy != super::spec::TimingPolicy::CommonArrival {
            return Err(err(
                "timing.recovery_interval",
                "0 under policy `cruise` (recovery slots are offsets from the common arrival time; use policy = \"common-arrival\")",
                t.recovery_interval,
            ));
        }
        let span = super::slots::Slots::of(self).span();
        if span > super::slots::MAX_SLOT_SPAN_S {
            return Err(err(
                "timing.launch_interval",
                format!(
                    "slots that end within {} s (half the channel's modelled hour, so the flight fits after them): with recovery_interval {} s and these {} UAVs the last takes off {span:.0} s late; take intervals of about {:.2} s",
                    super::slots::MAX_SLOT_SPAN_S,
                    t.recovery_interval,
                    self.uavs.len(),
                    super::slots::MAX_SLOT_SPAN_S / span * t.launch_interval.max(t.recovery_interval),
                ),
                t.launch_interval,
            ));
        }
        if self.planning.waypoints == 0 || self.planning.waypoints > 1000 {
            return Err(err(
                "planning.waypoints",
                "between 1 and 1000",
                self.planning.waypoints,
            ));
        }
        Ok(())
    }
}
