//! One module per subcommand.
pub mod bench;
pub mod evaluate;
pub mod export;
pub mod plan;
pub mod plot;
pub mod report;
pub mod scenario;
pub mod scenario_generate;
pub mod scenario_new;

use anyhow::Result;
use swarmplan_core::world::World;
use swarmplan_io::scenario::{build_world, load_spec};

use crate::ScenarioArgs;

/// Loads the scenario and builds its world (terrain included).
pub fn load_world(args: &ScenarioArgs) -> Result<World> {
    let mut loaded = load_spec(&args.scenario)?;
    if let Some(p) = args.profile {
        loaded.spec.planning.profile = p;
    }
    Ok(build_world(&loaded, args.terrain.as_deref())?)
}
