//! swarmplan-io: everything that touches files. Scenario TOML, plan JSON, terrain readers,
//! georeferencing and mission exports live here so that `swarmplan-core` stays free of I/O.

pub mod artifact;
pub mod catalog;

pub mod atomic;
pub mod convergence;
pub mod dem;
pub mod dem_ops;
pub mod export;
pub mod generate;
pub mod geo;
pub mod import;
pub mod outside;
pub mod plan_file;
pub mod plan_folder;
pub mod reference_data;
pub mod scenario;
