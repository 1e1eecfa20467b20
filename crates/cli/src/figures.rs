//! The figures of a plan folder and of a bench folder, drawn by `plan` and `bench` when
//! they finish and by `plot` from the files they wrote: one place, so a command never
//! reaches into another.

use std::path::{Path, PathBuf};

use anyhow::Result;
use swarmplan_core::plan::Plan;
use swarmplan_core::world::World;
use swarmplan_experiment::record::RunRecord;
use swarmplan_io::artifact::RunArtifact;

/// The stems of the figures of one plan (each written as .png and .svg).
pub const PLAN_FIGURES: [&str; 4] = ["top_view", "view_3d", "convergence", "comm_timeline"];

/// The figures of one plan; `title` names scenario, algorithm and seed; `trace[k]` is the
/// best cost after iteration `iterations[k]` (after iteration k when `None`).
pub fn plan_figures(
    dir: &Path,
    world: &World,
    plan: &Plan,
    iterations: Option<&[usize]>,
    trace: &[f64],
    per_uav: swarmplan_plot::PerUav<'_>,
    title: &str,
) -> Result<Vec<PathBuf>> {
    let stem = |name: &str| dir.join(name);
    let mut drawn = Vec::new();
    let mut keep = |name: &str, made: Result<_, swarmplan_plot::PlotError>| -> Result<()> {
        match made {
            Ok(_) => drawn.push(stem(name).with_extension("png")),
            // A run whose every cost is infinite has no convergence line: the plan and the
            // other figures stay, and the missing one is said.
            Err(e @ swarmplan_plot::PlotError::NoData { .. }) => {
                eprintln!("note: {e}; that figure is left out");
            }
            Err(e) => return Err(e.into()),
        }
        Ok(())
    };
    let [top, view, convergence, comm] = PLAN_FIGURES;
    keep(top, swarmplan_plot::top_view(world, plan, title, stem(top)))?;
    keep(
        view,
        swarmplan_plot::view_3d(world, plan, title, stem(view)),
    )?;
    keep(
        convergence,
        swarmplan_plot::convergence_run(iterations, trace, per_uav, title, stem(convergence)),
    )?;
    keep(
        comm,
        swarmplan_plot::comm_timeline(world, plan, title, stem(comm)),
    )?;
    Ok(drawn)
}

/// The figures of a bench, one set per scenario.
pub fn bench_figures(dir: &Path, records: &[RunRecord]) -> Result<Vec<PathBuf>> {
    let mut scenarios: Vec<&str> = records.iter().map(|r| r.scenario.as_str()).collect();
    scenarios.sort_unstable();
    scenarios.dedup();
    let scenario_count = scenarios.len();
    let mut out = Vec::new();
    // File-name stems given so far: `sc/u9.toml` and `sc_u9.toml` both make `sc_u9_toml`,
    // and one scenario's figures used to replace the other's.
    let mut taken = std::collections::HashSet::new();
    for sc in scenarios {
        let base: String = sc
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '-' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        let mut safe = base.clone();
        for k in 2.. {
            if taken.insert(safe.clone()) {
                break;
            }
            safe = format!("{base}_{k}");
        }
        let boxes = dir.join(format!("bench_{safe}"));
        swarmplan_plot::bench_boxplots(records, sc, &boxes)?;
        let conv = dir.join(format!("convergence_{safe}"));
        swarmplan_plot::convergence_bench(records, sc, &conv)?;
        out.push(boxes.with_extension("png"));
        out.push(conv.with_extension("png"));
    }
    if scenario_count > 1 {
        let profile = dir.join("performance_profile");
        match swarmplan_plot::performance_profile(records, &profile) {
            Ok(_) => out.push(profile.with_extension("png")),
            // Scenarios without a method in common: nothing to profile, said once.
            Err(e @ swarmplan_plot::PlotError::NoData { .. }) => {
                eprintln!("no performance profile: {e}");
            }
            Err(e) => return Err(e.into()),
        }
    }
    Ok(out)
}

/// The title of a plan's figures: scenario, method (its three parts when it is no preset),
/// seed, and INFEASIBLE when the plan is.
#[must_use]
pub fn plan_title(scenario: &str, run: &RunArtifact) -> String {
    let verdict = if run.assessment.feasible {
        ""
    } else {
        " - INFEASIBLE"
    };
    format!("{scenario} - {} - seed {}{verdict}", run.method, run.seed)
}
