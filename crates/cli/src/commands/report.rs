//! `swarmplan report DIR`: a self-contained HTML report of a `plan` or `bench` folder.

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_core::cost::assess;
use swarmplan_io::artifact::RunArtifact;
use swarmplan_io::plan_file::{read_plan, Provenance};
use swarmplan_io::scenario::{build_world, load_spec};

use crate::report::{bench_report, plan_report};

#[derive(Debug, Args)]
pub struct ReportArgs {
    /// A folder written by `plan` (plan.json, scenario.toml) or `bench` (summary.md).
    pub dir: PathBuf,
    /// Output file (default DIR/report.html).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(args: &ReportArgs) -> Result<()> {
    let dir = &args.dir;
    let out = args.out.clone().unwrap_or_else(|| dir.join("report.html"));
    let html = if dir.join("plan.json").exists() {
        let scenario = dir.join("scenario.toml");
        let loaded = if scenario.exists() {
            load_spec(&scenario.display().to_string())?
        } else {
            anyhow::bail!(
                "{}: missing; `swarmplan plan --out {}` writes it next to plan.json",
                scenario.display(),
                dir.display()
            );
        };
        let world = build_world(&loaded, None)?;
        let plan = read_plan(&dir.join("plan.json"), &world, Provenance::MustMatch)?;
        let a = assess(&world, &plan, true);
        let run_json = dir.join("run.json");
        let subtitle = if run_json.exists() {
            RunArtifact::read(&run_json)?.describe()
        } else {
            "plan loaded from plan.json".into()
        };
        plan_report(dir, &world, &plan, &a, &subtitle)?
    } else if dir.join("summary.md").exists() {
        let md = std::fs::read_to_string(dir.join("summary.md"))
            .with_context(|| format!("{}: cannot read", dir.join("summary.md").display()))?;
        bench_report(dir, &md)?
    } else if dir.join("runs.jsonl").exists() {
        // An interrupted bench, or one run from Python: the records are there, the summary
        // is written at the end.
        anyhow::bail!(
            "{}: holds run records but no summary.md; `swarmplan bench --resume --out {}` runs what is missing and writes it",
            dir.display(),
            dir.display()
        );
    } else {
        anyhow::bail!(
            "{}: holds neither plan.json nor summary.md; run `swarmplan plan --out DIR` or `swarmplan bench --out DIR` first",
            dir.display()
        );
    };
    swarmplan_io::atomic::write_atomic(&out, html.as_bytes())
        .with_context(|| format!("{}: cannot write", out.display()))?;
    println!("wrote {}", out.display());
    Ok(())
}
