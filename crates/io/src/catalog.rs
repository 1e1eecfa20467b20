//! Every name a scenario can be loaded by: a built-in scenario (`paper-case1`), a
//! generated one (`gen-s3-u8-t12-w1`, [`crate::generate`]), an outside benchmark instance
//! (`outside-2-u1-delay`, [`crate::outside`]), or a file path.
//!
//! Why apart from [`crate::scenario`]: generated and outside scenarios are made from a
//! built-in template that `scenario` parses, so name resolution sits above both and the
//! parsing below them, with no module depending on one that depends on it.

use std::path::Path;

use crate::scenario::{
    load_builtin, load_file, made_from_name, LoadedSpec, ScenarioError, BUILTIN,
};

/// Whether `name` names a scenario (built-in, generated or an outside instance) rather than
/// a file: what [`load_spec`] tries before reading a path.
#[must_use]
pub fn is_scenario_name(name: &str) -> bool {
    BUILTIN.iter().any(|(n, _)| *n == name)
        || crate::generate::GenerateRequest::from_name(name).is_some()
        || crate::outside::parse_name(name).is_some()
}

/// Reads a built-in scenario by name, a generated one by its name
/// ([`crate::generate::GenerateRequest::name`], e.g. `gen-s3-u8-t12-w1`), an outside
/// instance by its name (`outside-0`), or a scenario file by path.
pub fn load_spec(name_or_path: &str) -> Result<LoadedSpec, ScenarioError> {
    if BUILTIN.iter().any(|(n, _)| *n == name_or_path) {
        return load_builtin(name_or_path);
    }
    if let Some(req) = crate::generate::GenerateRequest::from_name(name_or_path) {
        let spec = crate::generate::generate(&req).map_err(|e| e.to_string());
        return made_from_name("generated", name_or_path, spec);
    }
    if let Some(spec) = crate::outside::load_named(name_or_path) {
        let mut loaded = made_from_name("outside", name_or_path, spec.map_err(|e| e.to_string()))?;
        // Its terrain source is relative to the instances' folder.
        loaded.base_dir = crate::outside::instance_dir();
        return Ok(loaded);
    }
    load_file(Path::new(name_or_path))
}
