//! `swarmplan scenario list|show|check`.

use anyhow::Result;
use swarmplan_io::scenario::{to_toml, BUILTIN};

use swarmplan_io::catalog::load_spec;

pub fn list() -> Result<()> {
    for (name, _) in BUILTIN {
        let spec = load_spec(name)?.spec;
        println!("{name:<12} {}", spec.description);
    }
    Ok(())
}

pub fn show(scenario: &str) -> Result<()> {
    let loaded = load_spec(scenario)?;
    print!("{}", to_toml(&loaded.spec));
    Ok(())
}

/// `scenario check`: what the route layer finds before any search, and every cause that
/// rules all plans out; exit status 3 when there is one.
pub fn check(scenario: &str) -> Result<()> {
    let loaded = load_spec(scenario)?;
    let world = swarmplan_io::scenario::build_world(&loaded, None)?;
    let spec = world.spec();
    for w in swarmplan_core::outcome::ways_in_world(&world) {
        println!("{}", w.sentence());
    }
    match swarmplan_core::outcome::unsearched_starts(spec) {
        0 => {}
        n => println!(
            "{n} further starts not searched (the route layer searches the first {})",
            swarmplan_core::route::STARTS_SEARCHED
        ),
    }
    let causes = swarmplan_core::world::unreachable::unreachable_in_world(&world);
    if causes.is_empty() {
        println!(
            "no cause found that rules every plan out (terrain, climbs, turns, separation and contact are for the search to settle)"
        );
        return Ok(());
    }
    for c in &causes {
        println!("no plan exists: {c}");
    }
    Err(crate::commands::plan::Infeasible(format!(
        "{}: {} causes rule every plan out",
        loaded.origin,
        causes.len()
    ))
    .into())
}
