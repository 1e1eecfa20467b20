//! Python bindings of swarmplan (`swarmplan._native`; the package `swarmplan` wraps it).
//!
//! Why a binding and not a port: most optimiser comparisons in this field are run in Python
//! (mealpy, pyswarms, pymoo, nevergrad) on models far simpler than swarmplan's. Exposing the
//! Rust model itself, not a re-implementation, means a Python optimiser and a Rust one are
//! scored by the same code, so their results can be compared, and it lets outside
//! implementations cross-check ours (docs/python.md).
//!
//! Every result crosses the boundary either as a numpy array (bounds, batches of costs) or as
//! the JSON the CLI writes (plan files, `evaluate --json` reports, `run.json`, bench records),
//! which the Python layer turns into dicts: one serialisation, so Python sees exactly what the
//! CLI prints. Errors become `swarmplan.SwarmplanError` (a `ValueError`) with the CLI's
//! message; long work runs with the interpreter released.

use pyo3::prelude::*;

mod args;
mod bench;
mod errors;
mod interrupt;
mod planner;
mod problem;
mod replay;
mod scenario;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    // `plan` and `Problem.evaluate` run on rayon's global pool: held to the cores as the CLI
    // holds its own (`RAYON_NUM_THREADS` beyond them only slows a run; the results are the
    // same on any number). An error means the pool was started already, and is left be.
    let threads = swarmplan_experiment::workers::Asked::from_count_or_env(0)
        .threads(swarmplan_experiment::workers::cores());
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build_global();
    m.add(
        "SwarmplanError",
        m.py().get_type::<errors::SwarmplanError>(),
    )?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<problem::Problem>()?;
    m.add_function(wrap_pyfunction!(planner::plan, m)?)?;
    m.add_function(wrap_pyfunction!(bench::bench, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::scenarios, m)?)?;
    m.add_function(wrap_pyfunction!(scenario::is_scenario_name, m)?)?;
    Ok(())
}
