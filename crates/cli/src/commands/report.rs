//! `swarmplan report DIR`: a self-contained HTML report of a `plan` or `bench` folder.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_core::cost::assess;
use swarmplan_io::plan_folder::PlanFolder;
use swarmplan_io::scenario::build_world;

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
    check_out(&out)?;
    let folder = PlanFolder::new(dir);
    let html = if folder.holds_plan() {
        let world = build_world(&folder.load_scenario()?, None)?;
        let plan = folder.read_plan(&world)?;
        let a = assess(&world, &plan);
        let subtitle = match folder.read_run()? {
            Some(run) => run.describe(),
            None => "plan loaded from plan.json".into(),
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

/// The report goes to an `.html` file that is not already something else: `--out
/// DIR/plan.json` or `DIR/runs.jsonl` replaced the plan or every run record with HTML.
fn check_out(out: &Path) -> Result<()> {
    let html = out
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("html") || e.eq_ignore_ascii_case("htm"));
    anyhow::ensure!(
        html,
        "--out {}: expected a file ending in .html (the report is one HTML page)",
        out.display()
    );
    if out.is_file() {
        let mut head = [0u8; 256];
        let n = std::fs::File::open(out)
            .and_then(|mut f| std::io::Read::read(&mut f, &mut head))
            .with_context(|| format!("--out {}: cannot read what is there", out.display()))?;
        let start = String::from_utf8_lossy(&head[..n])
            .trim_start()
            .to_ascii_lowercase();
        anyhow::ensure!(
            start.starts_with("<!doctype html") || start.starts_with("<html"),
            "--out {}: holds something other than an HTML page; not replaced",
            out.display()
        );
    }
    Ok(())
}
