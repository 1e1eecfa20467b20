//! The built-in scenarios for core's own tests, without swarmplan-io: the scenario files
//! parsed as `ScenarioSpec` and their procedural terrain built, as `swarmplan_io`'s
//! `load_spec` and `build_world` do for a built-in scenario (same names and call shapes,
//! so a test reads the same in either crate).

#![allow(dead_code, clippy::unwrap_used)] // each test binary uses a subset

use std::path::Path;

use swarmplan_core::world::procedural::try_procedural_terrain;
use swarmplan_core::world::spec::ScenarioSpec;
use swarmplan_core::world::World;

/// A built-in scenario, parsed (the part of `swarmplan_io::scenario::LoadedSpec` tests use).
#[derive(Debug, Clone)]
pub struct LoadedSpec {
    /// The parsed and validated scenario.
    pub spec: ScenarioSpec,
}

/// The built-in scenario `name` (`paper-case1`, `paper-case2` or `tiny`).
pub fn load_spec(name: &str) -> Result<LoadedSpec, String> {
    let text = match name {
        "paper-case1" => include_str!("../../../../scenarios/paper-case1.toml"),
        "paper-case2" => include_str!("../../../../scenarios/paper-case2.toml"),
        "tiny" => include_str!("../../../../scenarios/tiny.toml"),
        other => {
            return Err(format!(
                "{other}: not a built-in scenario with procedural terrain"
            ))
        }
    };
    let spec: ScenarioSpec = toml::from_str(text).map_err(|e| format!("{name}: {e}"))?;
    spec.validate().map_err(|e| format!("{name}: {e}"))?;
    Ok(LoadedSpec { spec })
}

/// The world of `loaded` on its procedural terrain (`terrain_override` must be `None`: a
/// DEM needs swarmplan-io).
pub fn build_world(loaded: &LoadedSpec, terrain_override: Option<&Path>) -> Result<World, String> {
    assert!(
        terrain_override.is_none(),
        "a DEM needs swarmplan-io's reader"
    );
    let spec = loaded.spec.clone();
    assert_eq!(
        spec.terrain.source, "procedural",
        "{}: not on procedural terrain",
        spec.name
    );
    let terrain = try_procedural_terrain(&spec.terrain.procedural).map_err(|e| e.to_string())?;
    World::new(spec, terrain).map_err(|e| e.to_string())
}
