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
use swarmplan_core::world::spec::{InterferenceSpec, ScenarioSpec, UavSpec};
use swarmplan_core::world::threat::Threat;
use thiserror::Error;

use crate::dem::{read_terrain, DemError, DemOptions};
use crate::scenario::{load_spec, ScenarioError};

/// Clear distance between a threat's edge and every start and the goal, metres.
pub const CLEAR_M: f64 = 60.0;

/// Spacing of spread starts, metres.
pub const START_SPACING_M: f64 = 40.0;

/// What to generate.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerateRequest {
    pub seed: u64,
    pub uavs: usize,
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
}

/// `timing.max_delay` of scenarios with free departure delays (generated with
/// `--free-delays`, and the outside `-delay` variants): a UAV may wait up to 30 % of the
/// mission at its start.
pub const FREE_MAX_DELAY: f64 = 0.3;

impl GenerateRequest {
    /// The scenario's name, `gen-sK-uN-tM[-wW][-shared][-pace][-delay]`, from which [`Self::from_name`]
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
        };
        for p in parts {
            match p {
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

#[derive(Debug, Error)]
pub enum GenerateError {
    #[error("--uavs: expected 1 to 1000, got {0}")]
    Uavs(usize),
    #[error("--threats: expected at most 500, got {0}")]
    Threats(usize),
    #[error("--comm-windows: expected at most 20, got {0}")]
    Windows(usize),
    #[error("--threats {threats}: only {placed} fit on the {width:.0} x {height:.0} m map with {CLEAR_M} m clear of the starts and the goal; ask for fewer")]
    Crowded {
        threats: usize,
        placed: usize,
        width: f64,
        height: f64,
    },
    #[error("--uavs {0}: a grid of starts 40 m apart does not fit on the map; use --shared-start")]
    StartsDoNotFit(usize),
    #[error(transparent)]
    Dem(#[from] DemError),
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

fn uniform(rng: &mut Rng, lo: f64, hi: f64) -> f64 {
    let u: f64 = rng.random();
    lo + u * (hi - lo)
}

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
    let mut spec = load_spec("paper-case1")?.spec;
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
    let (x0, x1, y0, y1) = match &req.terrain {
        Some(path) => {
            let dem = read_terrain(Path::new(path), &DemOptions::default())?;
            spec.terrain.source.clone_from(path);
            spec.terrain.frame = swarmplan_core::world::spec::TerrainFrame::Georeferenced;
            dem.terrain.extent()
        }
        None => {
            spec.terrain.source = "procedural".into();
            spec.terrain.procedural.seed = req.seed;
            let p = &spec.terrain.procedural;
            (0.0, p.width, 0.0, p.height)
        }
    };
    spec.map.x = [x0, x1];
    spec.map.y = [y0, y1];
    let (w, h) = (x1 - x0, y1 - y0);

    // The diagonal: start near one corner, goal near the opposite one.
    let corner = rng.random_range(0..4_u32);
    let (fx, fy) = match corner {
        0 => (0.15, 0.15),
        1 => (0.85, 0.15),
        2 => (0.85, 0.85),
        _ => (0.15, 0.85),
    };
    let start = [x0 + fx * w, y0 + fy * h];
    let goal = [x0 + (1.0 - fx) * w, y0 + (1.0 - fy) * h];
    let z = spec.goal.position[2];
    spec.goal.position = [goal[0], goal[1], z];
    let (dx, dy) = (goal[0] - start[0], goal[1] - start[1]);
    let length = dx.hypot(dy);
    let template = spec.uavs.first().copied().unwrap_or_default();
    // Spread starts: a square grid 40 m apart from the start corner towards the interior.
    let columns = (req.uavs as f64).sqrt().ceil() as usize;
    let (sx, sy) = (dx.signum(), dy.signum());
    let mut starts = Vec::with_capacity(req.uavs);
    for i in 0..req.uavs {
        let (c, r) = if req.shared_start {
            (0.0, 0.0)
        } else {
            ((i % columns) as f64, (i / columns) as f64)
        };
        let p = [
            start[0] + sx * c * START_SPACING_M,
            start[1] + sy * r * START_SPACING_M,
        ];
        if p[0] < x0 || p[0] > x1 || p[1] < y0 || p[1] > y1 {
            return Err(GenerateError::StartsDoNotFit(req.uavs));
        }
        starts.push(p);
    }
    spec.uavs = starts
        .iter()
        .map(|p| UavSpec {
            start: [p[0], p[1], z],
            ..template
        })
        .collect();

    // Threats, clear of the starts and the goal, disjoint from each other.
    let short = w.min(h);
    let mut threats: Vec<Threat> = Vec::with_capacity(req.threats);
    let mut attempts = 0;
    while threats.len() < req.threats && attempts < 2000 * req.threats.max(1) {
        attempts += 1;
        let r = uniform(&mut rng, 0.03 * short, 0.07 * short);
        let (x, y) = (
            uniform(&mut rng, x0 + r, x1 - r),
            uniform(&mut rng, y0 + r, y1 - r),
        );
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
    spec.threats = threats;

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
    if req.free_pace {
        free_pace(&mut spec);
    }
    if req.free_delays {
        spec.timing.max_delay = FREE_MAX_DELAY;
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
}
