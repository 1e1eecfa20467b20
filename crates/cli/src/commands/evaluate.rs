//! `swarmplan evaluate`: cost breakdown and violations of a plan file.

use std::path::PathBuf;

use anyhow::Result;
use clap::Args;
use swarmplan_core::cost::assess;
use swarmplan_io::artifact::AssessmentRecord;
use swarmplan_io::plan_file::{read_plan, Provenance};

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
    /// Evaluate a plan recorded for another scenario or terrain (refused otherwise).
    #[arg(long)]
    pub allow_other_terrain: bool,
}

pub fn run(args: &EvaluateArgs) -> Result<()> {
    let world = super::load_world(&args.scenario)?;
    let provenance = if args.allow_other_terrain {
        Provenance::AllowOther
    } else {
        Provenance::MustMatch
    };
    let plan = read_plan(&args.plan, &world, provenance)?;
    let a = assess(&world, &plan);
    if args.json {
        println!(
            "{}",
            serde_json::to_string_pretty(&AssessmentRecord::of(&a))?
        );
    } else {
        print!("{}", render::assessment(&world, &a));
    }
    Ok(())
}
