//! `swarmplan evaluate`: cost breakdown and violations of a plan file.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use swarmplan_core::cost::assess;
use swarmplan_io::plan_file::{assessment_json, read_plan};

use crate::render;
use crate::ScenarioArgs;

#[derive(Debug, Args)]
pub struct EvaluateArgs {
    #[command(flatten)]
    pub scenario: ScenarioArgs,
    /// Plan file: {"uavs": [{"waypoints": [[x, y, z_agl], ...]}, ...]}.
    #[arg(long)]
    pub plan: PathBuf,
    /// Print one JSON object instead of tables.
    #[arg(long)]
    pub json: bool,
}

pub fn run(args: &EvaluateArgs) -> Result<()> {
    let world = super::load_world(&args.scenario)?;
    let plan = read_plan(&args.plan, &world)?;
    let a = assess(&world, &plan, true);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&assessment_json(&a))?);
    } else {
        print!("{}", render::assessment(&world, &a));
    }
    Ok(())
}
