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
use swarmplan_core::world::spec::ScenarioSpec;
use swarmplan_core::world::unreachable::{unreachable_feasibility, unreachable_in_world};
use swarmplan_core::world::World;
use swarmplan_io::scenario::build_world_noted;

use swarmplan_io::catalog::load_spec;

use crate::ScenarioArgs;

/// Loads the scenario and builds its world (terrain included); warns, once, about causes
/// that make every plan infeasible.
pub fn load_world(args: &ScenarioArgs) -> Result<World> {
    let mut loaded = load_spec(&args.scenario)?;
    if let Some(p) = args.profile {
        loaded.spec.planning.profile = p;
    }
    let (world, notes) = build_world_noted(&loaded, args.terrain.as_deref())?;
    for n in notes {
        eprintln!("note: {n}");
    }
    warn_unreachable_in_world(&loaded.origin, &world);
    Ok(world)
}

/// Prints `warning: ORIGIN: FIELD: WHY; no plan can be feasible` for each cause found in
/// `spec` alone (before any terrain is read).
pub fn warn_unreachable(origin: &str, spec: &ScenarioSpec) {
    for u in unreachable_feasibility(spec) {
        eprintln!("warning: {origin}: {u}");
    }
}

/// [`warn_unreachable`] with the causes the terrain adds ([`unreachable_in_world`]).
pub fn warn_unreachable_in_world(origin: &str, world: &World) {
    for u in unreachable_in_world(world) {
        eprintln!("warning: {origin}: {u}");
    }
}

/// Said once when `--threads` (or `RAYON_NUM_THREADS`), named by `what`, asked for more
/// threads than the process has cores ([`swarmplan_experiment::workers`]).
pub fn threads_note(what: &str, cores: usize) -> String {
    let (cores, threads) = match cores {
        1 => ("1 core".to_string(), "1 thread runs".to_string()),
        n => (format!("{n} cores"), format!("{n} threads run")),
    };
    format!(
        "note: {what}: this process may use {cores}, so {threads} (more would only wait on each other; the results are the same on any number)"
    )
}
