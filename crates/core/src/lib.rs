//! swarmplan-core: the planning problem of "Cooperative Path Planning for Multi-UAVs with
//! Time-Varying Communication and Energy Consumption Constraints" (the DLS-SMPSO paper:
//! Guo, Gan, Hu 2024, Drones 8(11):654, doi:10.3390/drones8110654), as docs/model.md
//! resolves and extends it, and the optimizers that solve it. References: docs/references.md.
//!
//! The crate does no I/O. It is split the way OMPL splits motion planning:
//! - [`world`]: what exists (terrain, threats, fleet, channel, energy model, scenario);
//! - [`plan`] and [`timing`]: a candidate plan and when each UAV is where;
//! - [`cost`] and [`feasibility`]: how good a plan is and which hard limits it breaks;
//! - [`encoding`]: how a flat `&[f64]` becomes a plan (spherical motion, cartesian, angle);
//! - [`problem`]: the `Problem` trait optimizers see (bounds + evaluate);
//! - [`optim`]: the optimizers and the solve loop;
//! - [`method`]: a method = optimizer + encoding + initialisation, and the named presets.

pub mod attempts;
pub mod band_route;
pub mod contact_gap;
pub mod cost;
pub mod encoding;
pub mod feasibility;
pub mod flight;
pub mod json_f64;
pub mod method;
pub mod optim;
pub mod outcome;
pub mod plan;
pub mod planning;
mod points_key;
pub mod problem;
pub mod quadrature;
pub mod rng;
pub mod route;
pub mod run;
pub mod timing;
pub mod world;
pub mod zone_slot;

pub use glam::DVec3;
