//! `swarmplan plot DIR`: draws the figures of a `plan` folder (top view, 3-D view,
//! convergence, communication timeline) or of a `bench` folder (box plots and FR bars,
//! convergence across runs, per scenario), as PNG and SVG next to the records. `plan` and
//! `bench` call the same functions when they finish.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_core::plan::Plan;
use swarmplan_core::world::World;
use swarmplan_experiment::record::RunRecord;
use swarmplan_experiment::store::read_records;
use swarmplan_io::artifact::RunArtifact;
use swarmplan_io::plan_file::{read_plan, Provenance};
use swarmplan_io::scenario::{build_world, load_spec};

#[derive(Debug, Args)]
pub struct PlotArgs {
    /// A folder written by `plan` (plan.json, scenario.toml) or `bench` (runs.jsonl).
    pub dir: PathBuf,
}

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

/// A plan folder's `convergence.csv`, as columns.
struct TraceColumns {
    /// The iteration column, when the file has one (a long run's rows skip iterations).
    iterations: Option<Vec<usize>>,
    total: Vec<f64>,
    per_uav: Vec<Vec<f64>>,
}

/// Reads `convergence.csv` of a plan folder: the iteration and best_cost columns and, when
/// present, one `uavI_cost` column per UAV (as series).
fn read_trace(path: &Path) -> Result<TraceColumns> {
    let text = std::fs::read_to_string(path)
        .with_context(|| format!("{}: cannot read", path.display()))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "best_cost")
        .with_context(|| format!("{}: no best_cost column in the header", path.display()))?;
    let iteration_col = header.iter().position(|h| *h == "iteration");
    let uav_cols: Vec<usize> = (0..header.len())
        .filter(|c| header[*c].starts_with("uav") && header[*c].ends_with("_cost"))
        .collect();
    let mut iterations = iteration_col.map(|_| Vec::new());
    let mut total = Vec::new();
    let mut per_uav = vec![Vec::new(); uav_cols.len()];
    for (i, l) in lines.enumerate() {
        let fields: Vec<&str> = l.split(',').collect();
        let line = i + 2;
        let num = |c: usize| {
            fields
                .get(c)
                .and_then(|v| v.parse::<f64>().ok())
                .with_context(|| {
                    format!(
                        "{}: line {line}: expected a number in column {}",
                        path.display(),
                        header[c]
                    )
                })
        };
        if let (Some(c), Some(its)) = (iteration_col, iterations.as_mut()) {
            let k = fields
                .get(c)
                .and_then(|v| v.parse::<usize>().ok())
                .with_context(|| {
                    format!(
                        "{}: line {line}: expected a whole number in column iteration",
                        path.display()
                    )
                })?;
            if let Some(&before) = its.last() {
                anyhow::ensure!(
                    k > before,
                    "{}: line {line}: iteration {k} does not follow iteration {before}",
                    path.display()
                );
            }
            its.push(k);
        }
        total.push(num(col)?);
        for (series, c) in per_uav.iter_mut().zip(&uav_cols) {
            series.push(num(*c)?);
        }
    }
    Ok(TraceColumns {
        iterations,
        total,
        per_uav,
    })
}

/// The title of a plan's figures: scenario, method (its three parts when it is no preset),
/// seed, and INFEASIBLE when the plan is.
#[must_use]
pub fn plan_title(scenario: &str, run: &RunArtifact) -> String {
    let verdict = if run.report.feasible {
        ""
    } else {
        " - INFEASIBLE"
    };
    format!("{scenario} - {} - seed {}{verdict}", run.method, run.seed)
}

pub fn run(args: &PlotArgs) -> Result<()> {
    let dir = &args.dir;
    let files = if dir.join("plan.json").exists() {
        let scenario = dir.join("scenario.toml");
        anyhow::ensure!(
            scenario.exists(),
            "{}: missing; `swarmplan plan --out {}` writes it",
            scenario.display(),
            dir.display()
        );
        let world = build_world(&load_spec(&scenario.display().to_string())?, None)?;
        let plan = read_plan(&dir.join("plan.json"), &world, Provenance::MustMatch)?;
        let TraceColumns {
            iterations,
            total: trace,
            per_uav,
        } = read_trace(&dir.join("convergence.csv"))?;
        let run_json = dir.join("run.json");
        let title = if run_json.exists() {
            let run = RunArtifact::read(&run_json)?;
            plan_title(&world.spec().name, &run)
        } else {
            world.spec().name.clone()
        };
        let per_uav = if per_uav.is_empty() {
            swarmplan_plot::PerUav::None
        } else {
            swarmplan_plot::PerUav::Columns(&per_uav)
        };
        plan_figures(
            dir,
            &world,
            &plan,
            iterations.as_deref(),
            &trace,
            per_uav,
            &title,
        )?
    } else if dir.join("runs.jsonl").exists() {
        let records = read_records(dir, false)?;
        anyhow::ensure!(
            !records.is_empty(),
            "{}: no run records",
            dir.join("runs.jsonl").display()
        );
        bench_figures(dir, &records)?
    } else {
        if dir.join("summary.json").exists() {
            // `aggregate` writes the summary and figures of shards, not their records.
            anyhow::bail!(
                "{}: holds a summary but no runs.jsonl (an `aggregate` folder keeps no records); `swarmplan aggregate SHARD... --out {}` draws its figures again",
                dir.display(),
                dir.display()
            );
        }
        anyhow::bail!("{}: holds neither plan.json nor runs.jsonl", dir.display());
    };
    for f in files {
        println!("wrote {} (and .svg)", f.display());
    }
    Ok(())
}
