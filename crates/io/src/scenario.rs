//! Scenario files: the built-in scenarios, reading and writing the TOML format
//! (`docs/scenario.md`), and building a [`World`] with its terrain.
//!
//! A scenario is named either by a built-in name (`paper-case1`) or by a file path. Terrain
//! paths inside a file are relative to that file. `--terrain FILE` replaces the source but
//! keeps the scenario's frame and sampling, so SPSO's DEM drops into the paper cases.

use std::path::{Path, PathBuf};

use swarmplan_core::world::procedural::try_procedural_terrain;
use swarmplan_core::world::spec::{ScenarioSpec, TerrainFrame};
use swarmplan_core::world::{World, WorldError};
use thiserror::Error;

use crate::dem::{read_terrain, DemError, DemFrame, DemOptions};

/// Built-in scenarios: (name, TOML text).
pub const BUILTIN: [(&str, &str); 5] = [
    (
        "paper-case1",
        include_str!("../../../scenarios/paper-case1.toml"),
    ),
    (
        "paper-case2",
        include_str!("../../../scenarios/paper-case2.toml"),
    ),
    (
        "spso-case1",
        include_str!("../../../scenarios/spso-case1.toml"),
    ),
    (
        "spso-case2",
        include_str!("../../../scenarios/spso-case2.toml"),
    ),
    ("tiny", include_str!("../../../scenarios/tiny.toml")),
];

/// Why a scenario could not be loaded or built into a world.
#[derive(Debug, Error)]
pub enum ScenarioError {
    /// The name is no built-in, generated or outside scenario, and no file has that path.
    #[error("no built-in scenario and no file named `{name}`; built-in scenarios: {}; generated ones are named gen-sSEED-uUAVS-tTHREATS[-wWINDOWS][-shared][-pace][-delay], outside benchmark instances outside-K[-uUAVS][-delay]", builtin_names().join(", "))]
    Unknown {
        /// The name or path given.
        name: String,
    },
    /// The scenario file could not be read.
    #[error("{path}: cannot read: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// The TOML is malformed or not a scenario, or its `[geo] origin` is unusable.
    #[error("{origin}: {message}")]
    Parse {
        /// `builtin:NAME` or the file path.
        origin: String,
        /// What the TOML parser or the origin check said.
        message: String,
    },
    /// The scenario fails validation, or no world can be built from it.
    #[error("{origin}: {source}")]
    Invalid {
        /// Where the scenario came from: `builtin:NAME`, a file path, a generated scenario's
        /// name or an outside instance file.
        origin: String,
        /// What is wrong.
        source: WorldError,
    },
    /// The procedural terrain could not be made from `terrain.procedural`.
    #[error("{origin}: terrain.procedural: {message}")]
    Procedural {
        /// `builtin:NAME` or the file path.
        origin: String,
        /// What the terrain generator said.
        message: String,
    },
    /// The scenario's own terrain file could not be read.
    #[error("{origin}: terrain: {source}")]
    Terrain {
        /// `builtin:NAME` or the file path.
        origin: String,
        /// The DEM reader's error.
        source: DemError,
    },
    /// The DEM given with `--terrain` (not the scenario's own source) could not be read.
    #[error("--terrain {source}")]
    TerrainOverride {
        /// The DEM reader's error.
        source: DemError,
    },
    /// A scenario named as generated or outside could not be made.
    #[error("scenario `{name}`: {message}")]
    Generated {
        /// The scenario name.
        name: String,
        /// Why it could not be made.
        message: String,
    },
}

/// Names of the built-in scenarios.
#[must_use]
pub fn builtin_names() -> Vec<&'static str> {
    BUILTIN.iter().map(|(n, _)| *n).collect()
}

/// A scenario spec with where it came from.
#[derive(Debug, Clone)]
pub struct LoadedSpec {
    /// The parsed and validated scenario.
    pub spec: ScenarioSpec,
    /// `builtin:NAME` or the file path, for messages.
    pub origin: String,
    /// Folder that relative terrain paths are resolved against.
    pub base_dir: PathBuf,
    /// The text it was parsed from.
    pub text: String,
}

/// Reads the built-in scenario `name` (`paper-case1`, `tiny`, ...); `Unknown` for any other
/// name. Names of every kind (generated, outside instances) and files:
/// [`crate::catalog::load_spec`].
pub fn load_builtin(name: &str) -> Result<LoadedSpec, ScenarioError> {
    let Some((name, text)) = BUILTIN.iter().find(|(n, _)| *n == name) else {
        return Err(ScenarioError::Unknown {
            name: name.to_string(),
        });
    };
    let origin = format!("builtin:{name}");
    Ok(LoadedSpec {
        spec: parse_spec(text, &origin)?,
        origin,
        base_dir: PathBuf::from("."),
        text: (*text).to_string(),
    })
}

/// A scenario made from its name (`source` is `generated` or `outside`), or the reason it
/// could not be made.
pub fn made_from_name(
    source: &str,
    name: &str,
    spec: Result<ScenarioSpec, String>,
) -> Result<LoadedSpec, ScenarioError> {
    let spec = spec.map_err(|message| ScenarioError::Generated {
        name: name.to_string(),
        message,
    })?;
    Ok(LoadedSpec {
        text: to_toml(&spec),
        spec,
        origin: format!("{source}:{name}"),
        base_dir: PathBuf::from("."),
    })
}

/// Reads the scenario file at `path`; `Unknown` when there is none.
pub fn load_file(path: &Path) -> Result<LoadedSpec, ScenarioError> {
    if !path.exists() {
        return Err(ScenarioError::Unknown {
            name: path.display().to_string(),
        });
    }
    let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let origin = path.display().to_string();
    Ok(LoadedSpec {
        spec: parse_spec(&text, &origin)?,
        origin,
        base_dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
        text,
    })
}

/// Parses scenario TOML; errors name `origin`, the field and the line.
pub fn parse_spec(text: &str, origin: &str) -> Result<ScenarioSpec, ScenarioError> {
    let spec: ScenarioSpec = toml::from_str(text).map_err(|e| ScenarioError::Parse {
        origin: origin.to_string(),
        message: e.to_string().trim_end().replace('\n', "\n  "),
    })?;
    spec.validate().map_err(|e| ScenarioError::Invalid {
        origin: origin.to_string(),
        source: e.into(),
    })?;
    // Said here, naming the file, rather than by the first export that needs the frame.
    if let Some(g) = &spec.geo {
        let [lat, lon, alt] = g.origin;
        crate::geo::frame::check_tangent_origin(
            crate::geo::ellipsoid::Geodetic::new(lat, lon, alt),
            "geo.origin",
        )
        .map_err(|e| ScenarioError::Parse {
            origin: origin.to_string(),
            message: e.to_string(),
        })?;
    }
    Ok(spec)
}

/// The scenario as TOML (every field written out, so it can be edited and read back).
#[must_use]
pub fn to_toml(spec: &ScenarioSpec) -> String {
    toml::to_string_pretty(spec).expect("a scenario spec always serialises to TOML")
}

/// Builds the world of `loaded`, with `terrain_override` replacing its terrain source.
pub fn build_world(
    loaded: &LoadedSpec,
    terrain_override: Option<&Path>,
) -> Result<World, ScenarioError> {
    build_world_noted(loaded, terrain_override).map(|(w, _)| w)
}

/// [`build_world`], with notes a user should see about how the terrain was read (cells
/// that were nodata and took a neighbour's height), each naming the file.
pub fn build_world_noted(
    loaded: &LoadedSpec,
    terrain_override: Option<&Path>,
) -> Result<(World, Vec<String>), ScenarioError> {
    let mut notes = Vec::new();
    let mut spec = loaded.spec.clone();
    let t = &spec.terrain;
    let source: Option<PathBuf> = match terrain_override {
        Some(p) => Some(p.to_path_buf()),
        None if t.source == "procedural" => None,
        None => Some(loaded.base_dir.join(&t.source)),
    };
    let terrain = match &source {
        None => try_procedural_terrain(&t.procedural).map_err(|e| ScenarioError::Procedural {
            origin: loaded.origin.clone(),
            message: e.to_string(),
        })?,
        Some(path) => {
            let opts = DemOptions {
                frame: match t.frame {
                    TerrainFrame::SpsoPixels => DemFrame::SpsoPixels,
                    TerrainFrame::Georeferenced => DemFrame::Georeferenced,
                },
                sampling: t.sampling,
            };
            read_terrain(path, &opts)
                .map_err(|source| {
                    if terrain_override.is_some() {
                        ScenarioError::TerrainOverride { source }
                    } else {
                        ScenarioError::Terrain {
                            origin: loaded.origin.clone(),
                            source,
                        }
                    }
                })
                .map(|dem| {
                    if dem.nodata_filled > 0 {
                        let (nx, ny) = dem.terrain.size();
                        notes.push(format!(
                            "{}: {} of {} cells were nodata (the nodata value, NaN or |h| > 1e30) and took the height of their nearest valid cell",
                            path.display(),
                            dem.nodata_filled,
                            nx * ny
                        ));
                    }
                    dem.terrain
                })?
        }
    };
    if let Some(p) = source {
        spec.terrain.source = p.display().to_string();
    }
    let world = World::new(spec, terrain).map_err(|source| ScenarioError::Invalid {
        origin: loaded.origin.clone(),
        source,
    })?;
    Ok((world, notes))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalog::load_spec;

    #[test]
    fn every_builtin_parses_and_builds() {
        for name in builtin_names() {
            let l = load_spec(name).unwrap();
            assert_eq!(l.spec.name, name);
            build_world(&l, None).unwrap();
        }
    }

    #[test]
    fn show_round_trips() {
        for name in builtin_names() {
            let l = load_spec(name).unwrap();
            let again = parse_spec(&to_toml(&l.spec), "round-trip").unwrap();
            assert_eq!(again, l.spec);
        }
    }

    #[test]
    fn unknown_fields_are_rejected_with_their_name() {
        let text = BUILTIN[4].1.replace("[goal]", "[goal]\naltitude = 3");
        let e = parse_spec(&text, "x.toml").unwrap_err().to_string();
        assert!(e.starts_with("x.toml:"), "{e}");
        assert!(e.contains("altitude"), "{e}");
    }

    #[test]
    fn arrays_of_the_wrong_length_are_rejected_either_way() {
        let tiny = to_toml(&load_spec("tiny").expect("built in").spec);
        for (from, to) in [
            (
                "speed = [\n    5.0,\n    25.0,\n]",
                "speed = [5.0, 25.0, 30.0]",
            ),
            ("speed = [\n    5.0,\n    25.0,\n]", "speed = [5.0]"),
            ("x = [\n    0.0,\n    300.0,\n]", "x = [0.0, 300.0, 500.0]"),
            (
                "position = [\n    270.0,\n    170.0,\n    60.0,\n]",
                "position = [270.0, 170.0, 60.0, 1.0]",
            ),
        ] {
            assert!(tiny.contains(from), "{from}");
            let e = parse_spec(&tiny.replacen(from, to, 1), "t.toml")
                .expect_err("wrong length")
                .to_string();
            assert!(
                e.contains("t.toml") && e.contains(to) && e.contains("expected an array of"),
                "{e}"
            );
        }
    }

    #[test]
    fn bad_values_name_the_field() {
        let text = BUILTIN[4]
            .1
            .replacen("battery_wh = 2.0", "battery_wh = -2.0", 1);
        let e = parse_spec(&text, "x.toml").unwrap_err().to_string();
        assert!(e.contains("uavs[0].battery_wh"), "{e}");
        assert!(e.contains("-2"), "{e}");
        // A pace range must be open (the planner's choice) or exactly [1, 1]: a fixed pace
        // other than 1 would otherwise be silently flown at 1.
        for bad in ["[1.3, 1.3]", "[1.5, 0.5]", "[0.0, 1.0]"] {
            let text = format!("{}\n[timing]\npace = {bad}\n", BUILTIN[4].1);
            let e = parse_spec(&text, "x.toml").unwrap_err().to_string();
            assert!(
                e.contains("timing.pace") && e.contains("[1, 1]"),
                "{bad}: {e}"
            );
        }
        for good in ["[1.0, 1.0]", "[0.5, 1.5]"] {
            let text = format!("{}\n[timing]\npace = {good}\n", BUILTIN[4].1);
            assert!(parse_spec(&text, "x.toml").is_ok(), "{good}");
        }
        // The procedural terrain's fields are named like the others, and the climb limit's
        // range is said the same way whatever is wrong with it.
        let tiny = to_toml(&load_spec("tiny").expect("built in").spec);
        for (from, to, says) in [
            ("max_height = ", "max_height = nan\nx_max_height = ", "terrain.procedural.max_height: a finite number, got NaN"),
            ("hills = ", "hills = 1000000\nx_hills = ", "terrain.procedural.hills: at most 10000, got 1000000"),
            ("max_climb_deg = 45.0", "max_climb_deg = 120.0", "uavs[0].max_climb_deg: a climb angle in (0, 90] degrees (90: vertical climbs allowed, as SPSO), got 120"),
            ("max_climb_deg = 45.0", "max_climb_deg = 0.0", "uavs[0].max_climb_deg: a climb angle in (0, 90] degrees (90: vertical climbs allowed, as SPSO), got 0"),
        ] {
            assert!(tiny.contains(from), "{from}");
            let text: String = tiny
                .replacen(from, to, 1)
                .lines()
                .filter(|l| !l.starts_with("x_"))
                .map(|l| format!("{l}\n"))
                .collect();
            let e = parse_spec(&text, "x.toml").unwrap_err().to_string();
            assert_eq!(e, format!("x.toml: {says}"));
        }
    }

    #[test]
    fn unknown_scenario_lists_the_builtins() {
        let e = load_spec("no-such-scenario").unwrap_err().to_string();
        assert!(
            e.contains("paper-case1") && e.contains("no-such-scenario"),
            "{e}"
        );
    }
}
