//! `swarmplan scenario list|show`.

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
