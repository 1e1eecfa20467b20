//! The outside benchmark instances (`../shared/data/outside/outside-K.json` with
//! `outside-K.asc.gz`) as swarmplan scenarios, loadable by name (`outside-0`,
//! `outside-2-u8`) wherever a built-in scenario is.
//!
//! Why: a planner tuned on its own procedural maps may fail on terrain and threat layouts it
//! has never seen. These instances come from the generator of Shehadeh & Kudela's UAV
//! path-planning benchmark (arXiv 2501.14503, as packaged in MetaBox v2): 900 x 900 m of
//! rugged terrain, 15-30 threats, one start and one goal. An instance gives only the
//! geometry; the fleet, channel, energy model and objective are `paper-case1`'s (as for
//! `scenario generate`), all UAVs share the instance's start (the paper's setting), UGV0
//! waits at its goal, and batteries are sized for detours of 80 % over the straight line.
//! Threats keep their axis and radius; their drawn height is the template's (the model's
//! cylinders are unbounded in height, and the instance's drawn heights go below zero).
//! The terrain is read in the `spso-pixels` frame the data's README states.
//!
//! The fleet's pace is free within the speed limits (`timing.pace` = [v_min, v_max] /
//! cruise, [`swarmplan_core::encoding::paced`]): the instances give no timing, their routes
//! are longer than Case 1's, and at the template's fixed pace nearest cruise every plan of
//! 20 runs had the whole fleet mid-route, out of range of both ground nodes, while the
//! channel's range was at its lowest (outside-1: R(t) below 500 m from 42 to 63 s). The
//! paper cases keep the fixed pace.
//!
//! `outside-K-delay` (and `outside-K-uN-delay`) is the same instance with departure delays
//! free up to [`OUTSIDE_MAX_DELAY`] of the mission (`timing.max_delay`,
//! [`swarmplan_core::encoding::delayed`]): a UAV may hover at the shared start, above the
//! ground station, while the others fly out of its sight (docs/results.md, "Departure
//! delays"). A variant, not the instance itself, so that every result on `outside-K` stands.
//!
//! `outside-K[-uN][-delay]-slots` adds launch and recovery slots
//! ([`crate::generate::SLOT_INTERVAL_S`] apart; docs/model.md, "Launch and recovery slots"):
//! the fleet shares its start, so it takes off in turn, and UGV0 recovers it in turn.
//! `...-nocomm` turns communication off (`requirement = "none"`), to judge the route alone
//! (issue 46: one UAV with communication off is feasible wherever a route exists).

use std::path::{Path, PathBuf};

use serde::Deserialize;
use swarmplan_core::world::spec::{ScenarioSpec, TerrainFrame};
use swarmplan_core::world::terrain::Sampling;
use swarmplan_core::world::threat::Threat;
use thiserror::Error;

use crate::generate::{free_pace, size_batteries};
use crate::reference_data::shared_dir;
use crate::scenario::ScenarioError;

use crate::scenario::load_builtin;

/// UAVs of an outside scenario named without `-uN` (the paper's fleet).
pub const DEFAULT_UAVS: usize = 5;

/// Instances in the shared folder (`outside-0` to `outside-27`; its README says how they
/// were made).
pub const INSTANCES: usize = 28;

/// The held-out instances (the shared folder's README): run only to report a design already
/// kept, never to choose between variants; the others are the development instances.
pub const HELD_OUT: [usize; 6] = [7, 11, 15, 19, 23, 27];

/// `timing.max_delay` of the `-delay` variants: a UAV may wait up to 30 % of the mission,
/// as in generated scenarios with free delays.
pub const OUTSIDE_MAX_DELAY: f64 = crate::generate::FREE_MAX_DELAY;

/// An instance file as the outside generator writes it.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Instance {
    /// [x, y, drawn height, r] per vertical cylinder.
    threats_x_y_height_r: Vec<[f64; 4]>,
    /// [x, y, z AGL].
    start: [f64; 3],
    goal: [f64; 3],
    /// [columns, rows] of the terrain grid (1 m cells).
    map: [usize; 2],
}

/// Why an outside instance could not be turned into a scenario.
#[derive(Debug, Error)]
pub enum OutsideError {
    /// The instance file could not be read.
    #[error("{}: cannot read: {source} (the outside instances are read from $SWARMPLAN_SHARED/data/outside, else from shared/data/outside in the current folder, the program's folder or one of their ancestors)", .path.display())]
    Read {
        /// The instance file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The instance file is not the JSON the outside generator writes.
    #[error("{}: not an outside instance: {message}", .path.display())]
    Parse {
        /// The instance file.
        path: PathBuf,
        /// What the JSON parser said.
        message: String,
    },
    /// Neither `outside-K.asc.gz` nor `outside-K.asc` is beside the instance file.
    #[error("{}: no terrain beside it (looked for {})", .path.display(), .looked.display())]
    NoTerrain {
        /// The instance file.
        path: PathBuf,
        /// The terrain file named in the message (the `.asc.gz` one).
        looked: PathBuf,
    },
    /// The number of UAVs asked for is 0 or more than 1000.
    #[error("{name}: expected 1 to 1000 UAVs")]
    Uavs {
        /// The scenario name.
        name: String,
    },
    /// The template scenario could not be loaded, or the built scenario is invalid.
    #[error(transparent)]
    Template(#[from] Box<ScenarioError>),
}

/// What an outside scenario's name asks for.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutsideName {
    /// The instance's file stem, `outside-K`.
    pub stem: String,
    /// UAVs (5 unless `-uN`).
    pub uavs: usize,
    /// Departure delays free (`-delay`).
    pub delay: bool,
    /// Launch and recovery slots (`-slots`).
    pub slots: bool,
    /// Communication off (`-nocomm`: `communication.requirement = "none"`), to judge the
    /// route alone.
    pub no_comm: bool,
}

/// The scenario name `outside-K[-uN][-delay][-slots][-nocomm]` as what it asks for, or
/// `None`.
#[must_use]
pub fn parse_name(name: &str) -> Option<OutsideName> {
    let (name, no_comm) = match name.strip_suffix("-nocomm") {
        Some(base) => (base, true),
        None => (name, false),
    };
    let (name, slots) = match name.strip_suffix("-slots") {
        Some(base) => (base, true),
        None => (name, false),
    };
    let (base, delay) = match name.strip_suffix("-delay") {
        Some(base) => (base, true),
        None => (name, false),
    };
    let rest = base.strip_prefix("outside-")?;
    let (k, uavs) = match rest.split_once("-u") {
        Some((k, n)) => (k, n),
        None => (rest, ""),
    };
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if !digits(k) || (!uavs.is_empty() && !digits(uavs)) {
        return None;
    }
    let n = if uavs.is_empty() {
        DEFAULT_UAVS
    } else {
        uavs.parse().ok()?
    };
    let canonical = if n == DEFAULT_UAVS {
        format!("outside-{k}")
    } else {
        format!("outside-{k}-u{n}")
    };
    (canonical == base && (k == "0" || !k.starts_with('0'))).then(|| OutsideName {
        stem: format!("outside-{k}"),
        uavs: n,
        delay,
        slots,
        no_comm,
    })
}

/// The folder of the instances: `data/outside` in the shared folder
/// ([`crate::reference_data::shared_dir`], found when the program runs).
#[must_use]
pub fn instance_dir() -> PathBuf {
    shared_dir().join("data/outside")
}

/// The file of instance `stem` in the shared folder.
#[must_use]
pub fn instance_path(stem: &str) -> PathBuf {
    instance_dir().join(format!("{stem}.json"))
}

/// The scenario named `name` (`outside-K[-uN][-delay][-slots]`) from the shared folder, or `None` when the
/// name is not of that form.
pub fn load_named(name: &str) -> Option<Result<ScenarioSpec, OutsideError>> {
    let asked = parse_name(name)?;
    Some(
        from_instance(&instance_path(&asked.stem), asked.uavs, name).map(|mut spec| {
            if asked.delay {
                spec.timing.max_delay = OUTSIDE_MAX_DELAY;
            }
            if asked.slots {
                spec.timing.launch_interval = crate::generate::SLOT_INTERVAL_S;
                spec.timing.recovery_interval = crate::generate::SLOT_INTERVAL_S;
            }
            if asked.no_comm {
                spec.communication.requirement = swarmplan_core::world::spec::CommRequirement::None;
            }
            spec
        }),
    )
}

/// The last part of `path`, for messages and the terrain source.
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The scenario of instance file `path` with `uavs` UAVs, named `name`; its terrain source
/// is the terrain file's name, relative to `path`'s folder (the base folder of the
/// scenario, [`crate::scenario::LoadedSpec::base_dir`]).
pub fn from_instance(path: &Path, uavs: usize, name: &str) -> Result<ScenarioSpec, OutsideError> {
    if uavs == 0 || uavs > 1000 {
        return Err(OutsideError::Uavs { name: name.into() });
    }
    let text = std::fs::read_to_string(path).map_err(|source| OutsideError::Read {
        path: path.into(),
        source,
    })?;
    let inst: Instance = serde_json::from_str(&text).map_err(|e| OutsideError::Parse {
        path: path.into(),
        message: e.to_string(),
    })?;
    let terrain = [path.with_extension("asc.gz"), path.with_extension("asc")]
        .into_iter()
        .find(|p| p.exists())
        .ok_or_else(|| OutsideError::NoTerrain {
            path: path.into(),
            looked: path.with_extension("asc.gz"),
        })?;

    let mut spec = load_builtin("paper-case1").map_err(Box::new)?.spec;
    spec.name = name.into();
    spec.description = format!(
        "outside benchmark instance {} (Shehadeh & Kudela's generator): {} threats, {} UAVs from one start",
        file_name(path),
        inst.threats_x_y_height_r.len(),
        uavs
    );
    // Relative to the instance's folder (the scenario's base folder), so that nothing
    // written names a folder of this machine.
    spec.terrain.source = file_name(&terrain);
    spec.terrain.frame = TerrainFrame::SpsoPixels;
    spec.terrain.sampling = Sampling::Bilinear;
    spec.map.x = [1.0, inst.map[0] as f64];
    spec.map.y = [1.0, inst.map[1] as f64];
    let draw = spec.threats.first().map_or(150.0, |t| t.z);
    spec.threats = inst
        .threats_x_y_height_r
        .iter()
        .map(|&[x, y, _, r]| Threat { x, y, z: draw, r })
        .collect();
    let template = spec.uavs.first().copied().unwrap_or_default();
    spec.uavs = vec![
        swarmplan_core::world::spec::UavSpec {
            start: inst.start,
            ..template
        };
        uavs
    ];
    spec.goal.position = inst.goal;
    free_pace(&mut spec);
    spec.communication.interference.clear();
    let length = (inst.goal[0] - inst.start[0]).hypot(inst.goal[1] - inst.start[1]);
    size_batteries(&mut spec, length);
    spec.validate().map_err(|e| {
        Box::new(ScenarioError::Invalid {
            origin: path.display().to_string(),
            source: e.into(),
        })
    })?;
    Ok(spec)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names() {
        assert_eq!(
            parse_name("outside-0"),
            Some(OutsideName {
                stem: "outside-0".into(),
                uavs: 5,
                delay: false,
                slots: false,
                no_comm: false,
            })
        );
        assert_eq!(
            parse_name("outside-3-u12"),
            Some(OutsideName {
                stem: "outside-3".into(),
                uavs: 12,
                delay: false,
                slots: false,
                no_comm: false,
            })
        );
        assert_eq!(
            parse_name("outside-2-delay"),
            Some(OutsideName {
                stem: "outside-2".into(),
                uavs: 5,
                delay: true,
                slots: false,
                no_comm: false,
            })
        );
        assert_eq!(
            parse_name("outside-2-u8-delay"),
            Some(OutsideName {
                stem: "outside-2".into(),
                uavs: 8,
                delay: true,
                slots: false,
                no_comm: false,
            })
        );
        assert_eq!(
            parse_name("outside-2-u8-delay-slots"),
            Some(OutsideName {
                stem: "outside-2".into(),
                uavs: 8,
                delay: true,
                slots: true,
                no_comm: false,
            })
        );
        assert_eq!(
            parse_name("outside-2-u1-nocomm").map(|n| (n.uavs, n.no_comm)),
            Some((1, true))
        );
        for bad in [
            "outside-1-nocomm-u1",
            "outside-1-slots-delay",
            "outside-1-slots-slots",
            "outside-slots",
            "outside-",
            "outside-x",
            "outside-01",
            "outside-1-u",
            "outside-1-u5",
            "outside-1-u05",
            "outside-1-v3",
            "outside-1-delay-u8",
            "outside-1-delay-delay",
            "outside-delay",
            "inside-1",
        ] {
            assert_eq!(parse_name(bad), None, "{bad}");
        }
    }
}
