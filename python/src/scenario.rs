//! Scenarios by name or path, with a terrain override and a feasibility profile, exactly as
//! the CLI's `--scenario`, `--terrain` and `--profile` load them.

use std::path::PathBuf;

use pyo3::prelude::*;
use swarmplan_core::world::unreachable::unreachable_feasibility;
use swarmplan_core::world::World;
use swarmplan_io::scenario::{build_world_noted, builtin_names};

use swarmplan_io::catalog::load_spec;

use crate::args;
use crate::errors::to_py;

/// A built world and what a user should be told about it.
pub struct Loaded {
    pub world: World,
    /// Notes on how the terrain was read and warnings about causes that make every plan
    /// infeasible (the lines the CLI prints on stderr).
    pub notes: Vec<String>,
}

/// Loads `scenario` (built-in name, generated name or TOML path).
pub fn load(scenario: &str, terrain: Option<PathBuf>, profile: Option<&str>) -> PyResult<Loaded> {
    let mut loaded = load_spec(scenario).map_err(to_py)?;
    if let Some(p) = profile {
        loaded.spec.planning.profile = args::profile(p)?;
    }
    let (world, notes) = build_world_noted(&loaded, terrain.as_deref()).map_err(to_py)?;
    let mut notes: Vec<String> = notes.into_iter().map(|n| format!("note: {n}")).collect();
    notes.extend(
        unreachable_feasibility(world.spec())
            .into_iter()
            .map(|u| format!("warning: {}: {u}", loaded.origin)),
    );
    Ok(Loaded { world, notes })
}

/// Names of the built-in scenarios (generated `gen-...` and `outside-K` names load too).
#[pyfunction]
pub fn scenarios() -> Vec<&'static str> {
    builtin_names()
}

/// Whether `name` loads as a name (built-in, generated or outside) rather than as a file:
/// names take precedence, so a pickled problem keeps such a string as it is and makes
/// only a file's path absolute.
#[pyfunction]
pub fn is_scenario_name(name: &str) -> bool {
    swarmplan_io::catalog::is_scenario_name(name)
}
