//! swarmplan-io: everything that touches files. Scenario TOML, plan JSON and terrain
//! readers live here so that `swarmplan-core` stays free of I/O.

pub mod dem;
pub mod plan_file;
pub mod scenario;
