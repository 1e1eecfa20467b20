//! swarmplan-experiment: repeated planning runs and what they show. An experiment is a
//! matrix (scenarios x parameter sets x algorithms x runs); every run is one flat record in
//! `runs.jsonl`, and statistics are a separate step over records (as OMPL's benchmark
//! tool does), so shards and resumed runs aggregate the same way.

pub mod aggregate;
pub mod matrix;
pub mod ranking;
pub mod record;
pub mod runner;
pub mod scenario_summary;
pub mod settings;
pub mod stats;
pub mod store;
pub mod suite;
pub mod summary;
pub mod workers;
