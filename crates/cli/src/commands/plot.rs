//! `swarmplan plot DIR`: draws the figures of a `plan` folder (top view, 3-D view,
//! convergence, communication timeline) or of a `bench` folder (box plots and FR bars,
//! convergence across runs, per scenario), as PNG and SVG next to the records, with the
//! functions `plan` and `bench` call when they finish ([`crate::figures`]).

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use swarmplan_experiment::store::read_records;
use swarmplan_io::scenario::build_world;

use swarmplan_io::convergence::ConvergenceColumns;
use swarmplan_io::plan_folder::PlanFolder;

use crate::figures::{bench_figures, plan_figures, plan_title};

#[derive(Debug, Args)]
pub struct PlotArgs {
    /// A folder written by `plan` (plan.json, scenario.toml) or `bench` (runs.jsonl).
    pub dir: PathBuf,
}

pub fn run(args: &PlotArgs) -> Result<()> {
    let dir = &args.dir;
    let folder = PlanFolder::new(dir);
    let files = if folder.holds_plan() {
        let world = build_world(&folder.load_scenario()?, None)?;
        let plan = folder.read_plan(&world)?;
        let ConvergenceColumns {
            iterations,
            total: trace,
            per_uav,
        } = folder.read_convergence()?;
        let title = match folder.read_run()? {
            Some(run) => plan_title(&world.spec().name, &run),
            None => world.spec().name.clone(),
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
