//! `scenario generate`: random planning scenarios for tests and benchmark suites.
//!
//! A generated scenario takes the calibrated settings of `paper-case1` (fleet limits,
//! channel, energy model, objective) and draws, from one seed, what makes an instance:
//! the procedural terrain (or the extent of a given DEM), the diagonal the fleet crosses,
//! the starts (shared, as in the paper, or spread on a grid 40 m apart from the start corner),
//! the threats and, optionally, interference windows on the way. Threats never cover a start
//! or the goal: each cylinder keeps `CLEAR_M` metres between its edge and every start and
//! the goal (and cylinders do not overlap), so the take-off and landing zones are free and the instance is not infeasible
//! by construction. The same request and seed give the same TOML.

use std::path::Path;

use rand::Rng as _;
use swarmplan_core::rng::{derive_seed, rng_from_seed, Rng};
use swarmplan_core::world::energy::G;
use swarmplan_core::world::spec::{InterferenceSpec, ScenarioSpec, UavSpec};
use swarmplan_core::world::terrain::Terrain;
use swarmplan_core::world::threat::Threat;
use thiserror::Error;

use crate::dem::{read_terrain, DemError, DemOptions};
use crate::scenario::ScenarioError;

use crate::scenario::load_builtin;

/// Clear distance between a threat's edge and every start and the goal, metres.
pub const CLEAR_M: f64 = 60.0;

/// Draws of a threat's place and radius allowed per threat asked for.
pub const THREAT_DRAWS_PER_THREAT: usize = 2000;

/// Spacing of spread starts, metres.
pub const START_SPACING_M: f64 = 40.0;

/// What to generate.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerateRequest {
    /// Seed of every random draw (the K of the name `gen-sK-...`).
    pub seed: u64,
    /// Number of UAVs (1 to 1000).
    pub uavs: usize,
    /// Number of threats (at most 500).
    pub threats: usize,
    /// All UAVs start at one point (the paper's setting); otherwise on a grid 40 m apart.
    pub shared_start: bool,
    /// Interference windows along the start-goal line (0: none).
    pub comm_windows: usize,
    /// A DEM whose extent becomes the map (default: procedural terrain from the seed).
    pub terrain: Option<String>,
    /// The fleet's pace free within the speed limits (`timing.pace` = [v_min, v_max] /
    /// cruise, a decision variable; docs/model.md, "Pace"); otherwise fixed at 1.
    pub free_pace: bool,
    /// Departure delays free up to [`FREE_MAX_DELAY`] of the mission (`timing.max_delay`, a
    /// decision variable per UAV; docs/model.md, "Departure delays"); otherwise none.
    pub free_delays: bool,
    /// Launch and recovery slots ([`SLOT_INTERVAL_S`] apart; docs/model.md, "Launch and
    /// recovery slots"): a mission an operator could fly. Off in the named suites'
    /// instances, which were measured without them; on by default in `scenario generate`.
    pub slots: bool,
}

/// `timing.launch_interval` and `timing.recovery_interval` of a generated scenario with
/// slots: 5 s after take-off a UAV at a cruise speed of about 15 m/s is 75 m along its way,
/// clear of the 30 m take-off zone and of the 10 m separation from the next one.
pub const SLOT_INTERVAL_S: f64 = 5.0;

/// The slot interval for a fleet of `uavs` sharing one take-off place or UGV0:
/// [`SLOT_INTERVAL_S`], less for a fleet so large that its slots would end past
/// [`swarmplan_core::world::slots::MAX_SLOT_SPAN_S`] (1,000 UAVs: 1800 / 999, about 1.8 s).
#[must_use]
pub fn slot_interval(uavs: usize) -> f64 {
    let gaps = uavs.saturating_sub(1).max(1) as f64;
    SLOT_INTERVAL_S.min(swarmplan_core::world::slots::MAX_SLOT_SPAN_S / gaps)
}

/// `timing.max_delay` of scenarios with free departure delays (generated with
/// `--free-delays`, and the outside `-delay` variants): a UAV may wait up to 30 % of the
/// mission at its start.
pub const FREE_MAX_DELAY: f64 = 0.3;

impl GenerateRequest {
    /// The scenario's name, `gen-sK-uN-tM[-wW][-shared][-pace][-delay][-slots]` (and `-on-DEM`, the
    /// DEM file's stem, for a request on a DEM), from which [`Self::from_name`]
    /// gets the request back: a generated scenario can be named wherever a built-in one can
    /// (`plan --scenario gen-s3-u8-t12-w1`, `bench --scenarios`, suites), and a record's
    /// scenario name is enough to rebuild it. Only procedural-terrain requests have names
    /// that rebuild them (a DEM path is not part of the name).
    #[must_use]
    pub fn name(&self) -> String {
        let mut name = format!("gen-s{}-u{}-t{}", self.seed, self.uavs, self.threats);
        if self.comm_windows > 0 {
            name.push_str(&format!("-w{}", self.comm_windows));
        }
        if self.shared_start {
            name.push_str("-shared");
        }
        if self.free_pace {
            name.push_str("-pace");
        }
        if self.free_delays {
            name.push_str("-delay");
        }
        if self.slots {
            name.push_str("-slots");
        }
        if let Some(path) = &self.terrain {
            // Tells it from the procedural scenario of the same numbers in titles and
            // records; such a name rebuilds nothing (`from_name` takes no `-on-`).
            let stem = Path::new(path)
                .file_stem()
                .map_or_else(|| "dem".into(), |s| s.to_string_lossy().into_owned());
            let stem: String = stem
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                        c
                    } else {
                        '_'
                    }
                })
                .collect();
            name.push_str("-on-");
            name.push_str(&stem);
        }
        name
    }

    /// The request named `name` (see [`Self::name`]), or `None` when `name` is not of that
    /// form.
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        let mut parts = name.strip_prefix("gen-")?.split('-');
        let mut number = |tag: char| -> Option<u64> {
            let p = parts.next()?;
            let digits = p.strip_prefix(tag)?;
            if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
                return None;
            }
            digits.parse().ok()
        };
        let seed = number('s')?;
        let uavs = usize::try_from(number('u')?).ok()?;
        let threats = usize::try_from(number('t')?).ok()?;
        let mut req = Self {
            seed,
            uavs,
            threats,
            shared_start: false,
            comm_windows: 0,
            terrain: None,
            free_pace: false,
            free_delays: false,
            slots: false,
        };
        for p in parts {
            match p {
                "slots" if !req.slots => req.slots = true,
                "pace" if !req.free_pace => req.free_pace = true,
                "delay" if !req.free_delays => req.free_delays = true,
                "shared" if !req.shared_start => req.shared_start = true,
                w if w.starts_with('w') && req.comm_windows == 0 && !req.shared_start => {
                    let digits = &w[1..];
                    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
                        return None;
                    }
                    req.comm_windows = digits.parse().ok().filter(|&n| n > 0)?;
                }
                _ => return None,
            }
        }
        // Only the canonical spelling names a request, so one scenario has one name.
        (req.name() == name).then_some(req)
    }
}

/// Why a scenario could not be generated.
#[derive(Debug, Error)]
pub enum GenerateError {
    /// The number of UAVs is 0 or more than 1000.
    #[error("--uavs: expected 1 to 1000, got {0}")]
    Uavs(usize),
    /// More than 500 threats were asked for.
    #[error("--threats: expected at most 500, got {0}")]
    Threats(usize),
    /// More than 20 interference windows were asked for.
    #[error("--comm-windows: expected at most 20, got {0}")]
    Windows(usize),
    /// Not every threat asked for could be placed within the allowed random draws.
    #[error("--threats {threats}: placed only {placed} in {THREAT_DRAWS_PER_THREAT} random draws per threat on the {width:.0} x {height:.0} m map, disjoint and {CLEAR_M} m clear of the starts and the goal (how many fit depends on the draws); ask for fewer")]
    Crowded {
        /// Threats asked for.
        threats: usize,
        /// Threats placed.
        placed: usize,
        /// East-west (x) extent of the map, m.
        width: f64,
        /// North-south (y) extent of the map, m.
        height: f64,
    },
    /// The grid of spread starts does not fit on the map.
    #[error("--uavs {0}: a grid of starts 40 m apart does not fit on the map; use --shared-start")]
    StartsDoNotFit(usize),
    /// The DEM given for the terrain could not be read.
    #[error(transparent)]
    Dem(#[from] DemError),
    /// The template scenario could not be loaded, or the generated scenario is invalid.
    #[error(transparent)]
    Template(#[from] ScenarioError),
}

/// Frees the fleet's pace within the first UAV's speed limits: `timing.pace` = [v_min,
/// v_max] / cruise (a factor outside it only clamps against the limits). Unchanged when the
/// cruise speed is not positive.
pub(crate) fn free_pace(spec: &mut ScenarioSpec) {
    if let Some(u) = spec.uavs.first().filter(|u| u.cruise_speed > 0.0) {
        spec.timing.pace = [u.speed[0] / u.cruise_speed, u.speed[1] / u.cruise_speed];
    }
}

/// Raises every UAV's battery to room for detours of 80 % over the straight start-goal
/// line of `length` metres at cruise (about 9.2 J/m), within the usable share of the
/// battery, so an instance is not infeasible by energy alone.
pub(crate) fn size_batteries(spec: &mut ScenarioSpec, length: f64) {
    for u in &mut spec.uavs {
        let needed_wh = 1.8 * length * 9.24 / 3600.0 / (1.0 - u.reserve);
        u.battery_wh = u.battery_wh.max((needed_wh * 10.0).ceil() / 10.0);
    }
}

/// Where the fleet's starts go: `columns` wide, from the start towards the interior.
struct StartGrid {
    columns: usize,
    towards: [f64; 2],
    uavs: usize,
    shared: bool,
}

impl StartGrid {
    fn starts(&self, start: [f64; 2]) -> Vec<[f64; 2]> {
        (0..self.uavs)
            .map(|i| {
                let (c, r) = if self.shared {
                    (0.0, 0.0)
                } else {
                    ((i % self.columns) as f64, (i / self.columns) as f64)
                };
                [
                    start[0] + self.towards[0] * c * START_SPACING_M,
                    start[1] + self.towards[1] * r * START_SPACING_M,
                ]
            })
            .collect()
    }
}

/// Offsets (fractions of the map's width and height, positive inwards) tried around a
/// corner's place (0.15 or 0.85) on a DEM: -0.10 to 0.20 in steps of 0.02.
const CORNER_OFFSETS: [f64; 16] = [
    -0.10, -0.08, -0.06, -0.04, -0.02, 0.0, 0.02, 0.04, 0.06, 0.08, 0.10, 0.12, 0.14, 0.16, 0.18,
    0.20,
];

/// The place near `corner` (fractions of the map) whose ground is gentlest around every
/// point `points` puts there (the starts of the fleet, or UGV0 alone). Why: a UAV starts and
/// arrives at a fixed height above ground and its first and last legs are one waypoint
/// spacing long, so on a DEM a start at the foot of a cliff can need a climb beyond the
/// limit whatever the planner does (the procedural terrain is gentle, and the generated
/// suites are fixed instances, so this is only done on a DEM). Candidates are tried in a
/// fixed order, the corner's own place first, and the first of the gentlest whose points
/// all lie on the map is kept (the corner's own place if none does: the caller says the
/// starts do not fit).
fn gentlest_near(
    terrain: &Terrain,
    corner: [f64; 2],
    points: impl Fn([f64; 2]) -> Vec<[f64; 2]>,
    at: impl Fn([f64; 2]) -> [f64; 2],
) -> [f64; 2] {
    let (x0, y0, x1, y1) = terrain.extent();
    let inside = |q: [f64; 2]| (x0..=x1).contains(&q[0]) && (y0..=y1).contains(&q[1]);
    let inward = |f: f64, o: f64| if f < 0.5 { f + o } else { f - o };
    let mut offsets = CORNER_OFFSETS;
    offsets.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
    let mut best = (f64::INFINITY, at(corner));
    for &ox in &offsets {
        for &oy in &offsets {
            let p = at([inward(corner[0], ox), inward(corner[1], oy)]);
            let placed = points(p);
            if !placed.iter().all(|&q| inside(q)) {
                continue;
            }
            let steepest = placed
                .iter()
                .map(|&q| steepest_slope(terrain, q))
                .fold(0.0, f64::max);
            if steepest < best.0 {
                best = (steepest, p);
            }
        }
    }
    best.1
}

/// The steepest mean slope (rise over run) from `p` to the ground 50 and 100 m away, over 16
/// bearings.
fn steepest_slope(terrain: &Terrain, p: [f64; 2]) -> f64 {
    let h = terrain.height(p[0], p[1]);
    let mut steepest: f64 = 0.0;
    for k in 0..16 {
        let (sin, cos) = (f64::from(k) * std::f64::consts::PI / 8.0).sin_cos();
        for r in [50.0, 100.0] {
            let rise = terrain.height(p[0] + r * cos, p[1] + r * sin) - h;
            steepest = steepest.max(rise.abs() / r);
        }
    }
    steepest
}

/// Metres a path at constant height above ground climbs from `a` to `b` on the straight
/// line, in `segments` equal legs (the ground sampled where its waypoints would be).
fn ascent_along(terrain: &Terrain, a: [f64; 2], b: [f64; 2], segments: usize) -> f64 {
    let at = |k: usize| {
        let f = k as f64 / segments.max(1) as f64;
        terrain.height(a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]))
    };
    (0..segments.max(1))
        .map(|k| (at(k + 1) - at(k)).max(0.0))
        .sum()
}

/// On a DEM the ground can rise hundreds of metres between start and goal, and climbing
/// costs m g per metre ([`swarmplan_core::world::energy`]), which the length rule of
/// [`size_batteries`] does not cover (the procedural terrain is gentle, and the generated
/// suites are fixed instances, so it stays as it is there). Each battery gets room for the
/// straight line's `ascent` half again (a detour may climb more), on top of that rule.
fn add_climb_allowance(spec: &mut ScenarioSpec, ascent: f64) {
    if ascent <= 0.0 {
        return;
    }
    let airframe = spec.energy.model.weight_n;
    for u in &mut spec.uavs {
        let weight = airframe + u.payload_kg * G;
        let climb_wh = 1.5 * weight * ascent / 3600.0 / (1.0 - u.reserve);
        u.battery_wh = ((u.battery_wh + climb_wh) * 10.0).ceil() / 10.0;
    }
}

fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    let u: f64 = rng.random();
    lo + u * (hi - lo)
}

/// A map box as (x_min, y_min, x_max, y_max), metres.
type Extent = (f64, f64, f64, f64);

/// Generates the scenario of `req`.
pub fn generate(req: &GenerateRequest) -> Result<ScenarioSpec, GenerateError> {
    if req.uavs == 0 || req.uavs > 1000 {
        return Err(GenerateError::Uavs(req.uavs));
    }
    if req.threats > 500 {
        return Err(GenerateError::Threats(req.threats));
    }
    if req.comm_windows > 20 {
        return Err(GenerateError::Windows(req.comm_windows));
    }
    let mut spec = load_builtin("paper-case1")?.spec;
    let mut rng = rng_from_seed(derive_seed(req.seed, &["scenario-generate"], 0));
    let name = req.name();
    spec.description = format!(
        "generated: seed {}, {} UAVs, {} threats, {} start{}",
        req.seed,
        req.uavs,
        req.threats,
        if req.shared_start { "shared" } else { "spread" },
        if req.comm_windows > 0 {
            format!(", {} interference windows", req.comm_windows)
        } else {
            String::new()
        }
    );
    spec.name = name;
    let (extent, dem_terrain) = place_terrain(req, &mut spec)?;
    // Random draws in a fixed order: the corner, the threats, the windows.
    let (start, goal) = place_fleet(req, &mut spec, &mut rng, extent, dem_terrain.as_ref())?;
    let starts: Vec<[f64; 2]> = spec.uavs.iter().map(|u| [u.start[0], u.start[1]]).collect();
    spec.threats = draw_threats(req, &mut rng, extent, &starts, goal)?;
    let (dx, dy) = (goal[0] - start[0], goal[1] - start[1]);
    let length = dx.hypot(dy);
    spec.communication.interference = (0..req.comm_windows)
        .map(|_| {
            let t = uniform(&mut rng, 0.3, 0.7);
            let t0 = uniform(&mut rng, 10.0, 40.0);
            InterferenceSpec {
                time: [t0, t0 + 35.0],
                center: [start[0] + t * dx, start[1] + t * dy],
                radius: 0.12 * length,
                loss_db: 10.0,
            }
        })
        .collect();
    size_batteries(&mut spec, length);
    if let Some(terrain) = &dem_terrain {
        let segments = spec.planning.waypoints + 1;
        let ascent = ascent_along(terrain, start, goal, segments);
        add_climb_allowance(&mut spec, ascent);
    }
    if req.free_pace {
        free_pace(&mut spec);
    }
    if req.free_delays {
        spec.timing.max_delay = FREE_MAX_DELAY;
    }
    if req.slots {
        let interval = slot_interval(spec.uavs.len());
        spec.timing.launch_interval = interval;
        spec.timing.recovery_interval = interval;
    }
    spec.planning.seed = 1;
    spec.validate().map_err(|e| {
        GenerateError::Template(ScenarioError::Invalid {
            origin: spec.name.clone(),
            source: e.into(),
        })
    })?;
    Ok(spec)
}

/// The terrain: the DEM of `req.terrain`, or the procedural relief seeded by `req.seed`;
/// the map box is its extent. Returns the extent and the DEM's terrain.
fn place_terrain(
    req: &GenerateRequest,
    spec: &mut ScenarioSpec,
) -> Result<(Extent, Option<Terrain>), GenerateError> {
    let mut dem_terrain = None;
    let (x0, y0, x1, y1) = match &req.terrain {
        Some(path) => {
            let dem = read_terrain(Path::new(path), &DemOptions::default())?;
            spec.terrain.source.clone_from(path);
            spec.terrain.frame = swarmplan_core::world::spec::TerrainFrame::Georeferenced;
            let extent = dem.terrain.extent();
            dem_terrain = Some(dem.terrain);
            extent
        }
        None => {
            spec.terrain.source = "procedural".into();
            spec.terrain.procedural.seed = req.seed;
            let p = &spec.terrain.procedural;
            (0.0, 0.0, p.width, p.height)
        }
    };
    spec.map.x = [x0, x1];
    spec.map.y = [y0, y1];
    Ok(((x0, y0, x1, y1), dem_terrain))
}

/// The fleet at a start near a random corner (a grid 40 m apart when starts are spread) and
/// UGV0 near the opposite one (on a DEM, the gentlest ground nearby); returns start and goal.
fn place_fleet(
    req: &GenerateRequest,
    spec: &mut ScenarioSpec,
    rng: &mut Rng,
    (x0, y0, x1, y1): Extent,
    dem_terrain: Option<&Terrain>,
) -> Result<([f64; 2], [f64; 2]), GenerateError> {
    let (w, h) = (x1 - x0, y1 - y0);
    // The diagonal: start near one corner, goal near the opposite one.
    let corner = rng.random_range(0..4_u32);
    let (fx, fy): (f64, f64) = match corner {
        0 => (0.15, 0.15),
        1 => (0.85, 0.15),
        2 => (0.85, 0.85),
        _ => (0.15, 0.85),
    };
    // Spread starts: a square grid 40 m apart from the start corner towards the interior.
    let grid = StartGrid {
        columns: (req.uavs as f64).sqrt().ceil() as usize,
        towards: [(0.5 - fx).signum(), (0.5 - fy).signum()],
        uavs: req.uavs,
        shared: req.shared_start,
    };
    let at = |f: [f64; 2]| [x0 + f[0] * w, y0 + f[1] * h];
    let (start, goal) = match dem_terrain {
        None => (at([fx, fy]), at([1.0 - fx, 1.0 - fy])),
        Some(t) => (
            gentlest_near(t, [fx, fy], |p| grid.starts(p), at),
            gentlest_near(t, [1.0 - fx, 1.0 - fy], |p| vec![p], at),
        ),
    };
    let z = spec.goal.position[2];
    spec.goal.position = [goal[0], goal[1], z];
    let template = spec.uavs.first().copied().unwrap_or_default();
    let starts = grid.starts(start);
    if starts
        .iter()
        .any(|p| p[0] < x0 || p[0] > x1 || p[1] < y0 || p[1] > y1)
    {
        return Err(GenerateError::StartsDoNotFit(req.uavs));
    }
    spec.uavs = starts
        .iter()
        .map(|p| UavSpec {
            start: [p[0], p[1], z],
            ..template
        })
        .collect();
    Ok((start, goal))
}

/// `req.threats` threats, clear of the starts and the goal, disjoint from each other, of
/// radius 3-7 % of the map's shorter side; too crowded a map is an error.
fn draw_threats(
    req: &GenerateRequest,
    rng: &mut Rng,
    (x0, y0, x1, y1): Extent,
    starts: &[[f64; 2]],
    goal: [f64; 2],
) -> Result<Vec<Threat>, GenerateError> {
    let (w, h) = (x1 - x0, y1 - y0);
    let short = w.min(h);
    let mut threats: Vec<Threat> = Vec::with_capacity(req.threats);
    let mut attempts = 0;
    while threats.len() < req.threats && attempts < THREAT_DRAWS_PER_THREAT * req.threats.max(1) {
        attempts += 1;
        let r = uniform(rng, 0.03 * short, 0.07 * short);
        let (x, y) = (uniform(rng, x0 + r, x1 - r), uniform(rng, y0 + r, y1 - r));
        let clear_of = |p: &[f64; 2]| (x - p[0]).hypot(y - p[1]) >= r + CLEAR_M;
        if !starts.iter().all(clear_of) || !clear_of(&goal) {
            continue;
        }
        if threats.iter().any(|t| (x - t.x).hypot(y - t.y) < r + t.r) {
            continue;
        }
        threats.push(Threat { x, y, z: 300.0, r });
    }
    if threats.len() < req.threats {
        return Err(GenerateError::Crowded {
            threats: req.threats,
            placed: threats.len(),
            width: w,
            height: h,
        });
    }
    Ok(threats)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{build_world, parse_spec, to_toml};

    fn request(seed: u64, uavs: usize, threats: usize) -> GenerateRequest {
        GenerateRequest {
            seed,
            uavs,
            threats,
            shared_start: false,
            comm_windows: 1,
            terrain: None,
            free_pace: false,
            free_delays: false,
            slots: false,
        }
    }

    #[test]
    fn names_give_the_request_back() {
        for (seed, uavs, threats, windows, shared, free_pace, free_delays) in [
            (3, 8, 12, 1, false, false, false),
            (1, 20, 0, 0, true, false, true),
            (17, 5, 30, 2, true, true, false),
            (4, 12, 10, 0, false, true, true),
        ] {
            let req = GenerateRequest {
                comm_windows: windows,
                shared_start: shared,
                free_pace,
                free_delays,
                slots: shared,
                ..request(seed, uavs, threats)
            };
            let name = req.name();
            assert_eq!(
                GenerateRequest::from_name(&name),
                Some(req.clone()),
                "{name}"
            );
            let spec = generate(&req).unwrap();
            assert_eq!(spec.name, name);
            assert_eq!(spec.timing.pace_is_free(), free_pace, "{name}");
            assert_eq!(spec.timing.delay_is_free(), free_delays, "{name}");
            if free_delays {
                assert_eq!(spec.timing.max_delay, FREE_MAX_DELAY, "{name}");
            }
            assert_eq!(slot_interval(1000), 1800.0 / 999.0);
            assert_eq!(slot_interval(1), SLOT_INTERVAL_S);
            let slots = [spec.timing.launch_interval, spec.timing.recovery_interval];
            let want = if shared { SLOT_INTERVAL_S } else { 0.0 };
            assert_eq!(slots, [want; 2], "{name}");
            if free_pace {
                let u = &spec.uavs[0];
                assert_eq!(spec.timing.pace[1], u.speed[1] / u.cruise_speed);
            }
        }
        for bad in [
            "gen-s1-u8",
            "gen-s1-u8-t",
            "gen-s1-u8-t12-x",
            "gen-s01-u8-t12",
            "gen-s1-u8-t12-w0",
            "gen-s1-u8-t12-shared-w1",
            "gen-s1-u8-t12-pace-shared",
            "gen-s1-u8-t12-pace-pace",
            "gen-s1-u8-t12-delay-pace",
            "gen-s1-u8-t12-delay-delay",
            "gen-s1-u8-t12-slots-delay",
            "gen-s1-u8-t12-slots-slots",
            "gen-s-1-u8-t12",
            "paper-case1",
        ] {
            assert_eq!(GenerateRequest::from_name(bad), None, "{bad}");
        }
    }

    #[test]
    fn same_seed_same_scenario_and_it_loads() {
        let a = to_toml(&generate(&request(3, 8, 12)).expect("generates"));
        assert_eq!(
            a,
            to_toml(&generate(&request(3, 8, 12)).expect("generates"))
        );
        assert_ne!(
            a,
            to_toml(&generate(&request(4, 8, 12)).expect("generates"))
        );
        let spec = parse_spec(&a, "generated").expect("reads back");
        assert_eq!(spec.uavs.len(), 8);
        assert_eq!(spec.threats.len(), 12);
        let loaded = crate::scenario::LoadedSpec {
            spec,
            origin: "generated".into(),
            base_dir: ".".into(),
            text: a,
        };
        build_world(&loaded, None).expect("builds a world");
    }

    #[test]
    fn starts_and_goal_are_clear_of_every_threat() {
        for seed in 0..20 {
            let s = generate(&GenerateRequest {
                shared_start: seed % 2 == 0,
                ..request(seed, 12, 25)
            })
            .expect("generates");
            let g = s.goal.position;
            for t in &s.threats {
                for p in s.uavs.iter().map(|u| u.start).chain([g]) {
                    assert!((p[0] - t.x).hypot(p[1] - t.y) >= t.r + CLEAR_M);
                }
            }
            let distinct = s.uavs.windows(2).all(|w| {
                (w[0].start[0] - w[1].start[0]).hypot(w[0].start[1] - w[1].start[1]) > 1.0
            });
            assert_eq!(distinct, seed % 2 != 0, "seed {seed}");
        }
    }

    #[test]
    fn impossible_requests_are_clear_errors() {
        let e = generate(&request(1, 5, 400)).expect_err("too many threats");
        assert!(e.to_string().contains("only"), "{e}");
        assert!(generate(&request(1, 0, 3)).is_err());
        let e = generate(&request(1, 600, 3)).expect_err("600 spread starts do not fit");
        assert!(e.to_string().contains("--shared-start"), "{e}");
    }

    /// Writes an ESRI ASCII grid of `nx` x `ny` cells of `cell` metres, its lower left corner
    /// at (x0, y0), heights from `height(x, y)` (x, y relative to that corner).
    fn write_asc(
        path: &Path,
        (nx, ny, cell): (usize, usize, f64),
        (x0, y0): (f64, f64),
        height: impl Fn(f64, f64) -> f64,
    ) {
        let mut text = format!(
            "ncols {nx}\nnrows {ny}\nxllcorner {x0}\nyllcorner {y0}\ncellsize {cell}\nNODATA_value -9999\n"
        );
        for row in 0..ny {
            let y = (ny - 1 - row) as f64 * cell;
            let line: Vec<String> = (0..nx)
                .map(|c| format!("{:.2}", height(c as f64 * cell, y)))
                .collect();
            text.push_str(&line.join(" "));
            text.push('\n');
        }
        std::fs::write(path, text).expect("writes the grid");
    }

    fn on_dem(path: &Path, seed: u64, uavs: usize) -> ScenarioSpec {
        generate(&GenerateRequest {
            terrain: Some(path.display().to_string()),
            comm_windows: 0,
            ..request(seed, uavs, 6)
        })
        .expect("generates on the DEM")
    }

    #[test]
    fn a_dem_sets_the_map_to_its_extent() {
        // Not square, so that x and y cannot be mixed up; the DEM's frame puts its lower left
        // corner at (0, 0).
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("flat.asc");
        write_asc(&dem, (121, 81, 10.0), (500_000.0, 4_000_000.0), |_, _| {
            300.0
        });
        for seed in 1..5 {
            let s = on_dem(&dem, seed, 12);
            // Named apart from the procedural scenario of the same numbers, and no name of
            // one that its name would rebuild.
            assert_eq!(s.name, format!("gen-s{seed}-u12-t6-on-flat"));
            assert!(GenerateRequest::from_name(&s.name).is_none());
            assert_eq!(s.map.x, [0.0, 1200.0]);
            assert_eq!(s.map.y, [0.0, 800.0]);
            for p in s.uavs.iter().map(|u| u.start).chain([s.goal.position]) {
                assert!((0.0..=1200.0).contains(&p[0]), "{p:?}");
                assert!((0.0..=800.0).contains(&p[1]), "{p:?}");
            }
            // Flat ground: no climb to pay for, the length rule alone, as on procedural maps.
            let length = (s.goal.position[0] - s.uavs[0].start[0])
                .hypot(s.goal.position[1] - s.uavs[0].start[1]);
            let mut by_length = s.clone();
            by_length.uavs.iter_mut().for_each(|u| u.battery_wh = 6.0);
            size_batteries(&mut by_length, length);
            assert_eq!(s.uavs[0].battery_wh, by_length.uavs[0].battery_wh);
            let text = to_toml(&s);
            let loaded = crate::scenario::LoadedSpec {
                spec: parse_spec(&text, "generated").expect("reads back"),
                origin: "generated".into(),
                base_dir: std::path::PathBuf::new(),
                text,
            };
            build_world(&loaded, None).expect("builds with its DEM");
        }
    }

    #[test]
    fn batteries_pay_for_the_climb_on_a_dem() {
        let dir = tempfile::tempdir().unwrap();
        let (flat, slope) = (dir.path().join("flat.asc"), dir.path().join("slope.asc"));
        write_asc(&flat, (101, 101, 10.0), (0.0, 0.0), |_, _| 0.0);
        // Rising 0.5 m per metre along the diagonal, the way the fleet goes from one corner
        // or the other: a pyramid's sides climb whichever corner the seed picks to the middle.
        write_asc(&slope, (101, 101, 10.0), (0.0, 0.0), |x, y| {
            500.0 - 0.5 * ((x - 500.0).abs() + (y - 500.0).abs())
        });
        let (a, b) = (on_dem(&flat, 3, 4), on_dem(&slope, 3, 4));
        let airframe = a.energy.model.weight_n;
        let weight = airframe + a.uavs[0].payload_kg * G;
        // The path climbs to the top in the middle, about 350 m.
        let extra_wh = b.uavs[0].battery_wh - a.uavs[0].battery_wh;
        let climb_m = extra_wh * 3600.0 * (1.0 - a.uavs[0].reserve) / 1.5 / weight;
        assert!(
            (300.0..400.0).contains(&climb_m),
            "{climb_m} m of climb paid for"
        );
    }

    #[test]
    fn starts_and_goal_are_moved_off_a_cliff_on_a_dem() {
        // A 300 m wall across the map at 12-18 % of its width from the west edge, flat
        // elsewhere: the corners' own places (15 %, 85 %) stand on or at its foot in the west.
        let dir = tempfile::tempdir().unwrap();
        let dem = dir.path().join("wall.asc");
        let wall = |x: f64, _| {
            if (120.0..=180.0).contains(&x) {
                300.0
            } else {
                0.0
            }
        };
        write_asc(&dem, (101, 101, 10.0), (0.0, 0.0), wall);
        let terrain = read_terrain(&dem, &DemOptions::default()).unwrap().terrain;
        for seed in 1..9 {
            let s = on_dem(&dem, seed, 4);
            for p in s.uavs.iter().map(|u| u.start).chain([s.goal.position]) {
                let steepest = steepest_slope(&terrain, [p[0], p[1]]);
                assert!(
                    steepest < 1e-9,
                    "seed {seed}: {p:?} by the wall ({steepest})"
                );
            }
        }
    }
}
