//! The `swarmplan` command-line tool: plan cooperative UAV paths, evaluate plans, inspect
//! scenarios. Errors are printed with their causes (`{:#}`) and exit with status 2.

// clap turns doc comments into help text, where `[x]` is literal (`LAT,LON[,ALT]`,
// `[[param_sets]]`), not a link.
#![allow(rustdoc::broken_intra_doc_links)]

mod commands;
mod figures;
mod mission_export;
mod out_folder;
mod render;
mod report;
mod settings_args;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};

#[derive(Debug, Parser)]
#[command(
    name = "swarmplan",
    version,
    about = "Cooperative path planning for UAV fleets (DLS-SMPSO and baselines)"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// List built-in scenarios or print one as TOML.
    #[command(subcommand)]
    Scenario(ScenarioCommand),
    /// Plan a scenario (default: paper Case 1 with the swarmplan method) and write plan.json.
    Plan(commands::plan::PlanArgs),
    /// Cost breakdown and every violation of a plan file.
    Evaluate(commands::evaluate::EvaluateArgs),
    /// Run an experiment (default: the paper's Tables 4-5: both cases, 7 algorithms, 200 runs).
    Bench(commands::bench::BenchArgs),
    /// Merge the folders of a sharded experiment into one summary.
    Aggregate(commands::bench::AggregateArgs),
    /// Write a self-contained HTML report of a plan or bench folder.
    Report(commands::report::ReportArgs),
    /// Draw the figures of a plan or bench folder (PNG and SVG).
    Plot(commands::plot::PlotArgs),
    /// Write a planned mission for autopilots and GIS (QGroundControl .plan, WPL, GeoJSON, KML, CSV).
    Export(commands::export::ExportArgs),
}

#[derive(Debug, Subcommand)]
enum ScenarioCommand {
    /// The built-in scenarios, one per line.
    List,
    /// Print a scenario (built-in name or file) as complete TOML.
    Show {
        /// Built-in name (see `scenario list`) or path to a TOML file.
        scenario: String,
    },
    /// Say, before any search, whether a way around the threats exists from each start (the
    /// route layer: widest way, shortest length) and every cause that rules all plans out
    /// (exit status 3 when there is one).
    Check {
        /// Built-in name (see `scenario list`) or path to a TOML file.
        scenario: String,
    },
    /// Write an editable scenario on a georeferenced DEM from start/goal latitude and longitude.
    New(commands::scenario_new::ScenarioNewArgs),
    /// Write a random scenario (threats, starts, goal, terrain) from a seed.
    Generate(commands::scenario_generate::ScenarioGenerateArgs),
}

/// A scenario and an optional terrain file that replaces its terrain source.
#[derive(Debug, Clone, Args)]
pub struct ScenarioArgs {
    /// Built-in scenario name (see `swarmplan scenario list`) or path to a TOML file.
    #[arg(long, default_value = "paper-case1")]
    pub scenario: String,
    /// GeoTIFF or ESRI ASCII grid replacing the scenario's terrain source.
    #[arg(long)]
    pub terrain: Option<PathBuf>,
    /// Feasibility profile replacing the scenario's `planning.profile`: `strict` (every
    /// constraint hard) or `paper` (threats, terrain, turns and energy hard; the rest cost
    /// only, as the paper's FR counts).
    #[arg(long, value_parser = parse_profile)]
    pub profile: Option<swarmplan_core::feasibility::FeasibilityProfile>,
}

/// A feasibility profile by name.
pub fn parse_profile(s: &str) -> Result<swarmplan_core::feasibility::FeasibilityProfile, String> {
    swarmplan_core::feasibility::FeasibilityProfile::from_name(s)
        .ok_or_else(|| format!("expected `strict` or `paper`, got `{s}`"))
}

/// A seed: a whole number in [0, 2^64 - 1]. Negative numbers reach this parser (the flag
/// allows hyphen values) so they get this message instead of "unexpected argument".
pub fn parse_seed(s: &str) -> Result<u64, String> {
    s.trim()
        .parse::<u64>()
        .map_err(|_| format!("expected a whole number in [0, {}], got `{s}`", u64::MAX))
}

/// Largest `--threads` accepted (a count above the cores runs one thread per core, with a
/// note: `swarmplan_experiment::workers`).
pub const MAX_THREADS: usize = 4096;

/// `--threads` of `plan` and `bench`: 0 (one per core) to [`MAX_THREADS`]. Negative numbers
/// reach this parser too, so they get its message.
pub fn parse_threads(s: &str) -> Result<usize, String> {
    let n: usize = s.trim().parse().map_err(|_| {
        format!("expected a whole number, 0 (one per core) to {MAX_THREADS}, got `{s}`")
    })?;
    if n <= MAX_THREADS {
        Ok(n)
    } else {
        Err(format!(
            "expected 0 (one per core) to {MAX_THREADS}, got {n}"
        ))
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Scenario(ScenarioCommand::List) => commands::scenario::list(),
        Command::Scenario(ScenarioCommand::Show { scenario }) => {
            commands::scenario::show(&scenario)
        }
        Command::Scenario(ScenarioCommand::Check { scenario }) => {
            commands::scenario::check(&scenario)
        }
        Command::Plan(args) => commands::plan::run_command(&args),
        Command::Evaluate(args) => commands::evaluate::run(&args),
        Command::Bench(args) => commands::bench::run_bench(&args),
        Command::Aggregate(args) => commands::bench::run_aggregate(&args),
        Command::Report(args) => commands::report::run(&args),
        Command::Plot(args) => commands::plot::run(&args),
        Command::Export(args) => commands::export::run(&args),
        Command::Scenario(ScenarioCommand::New(args)) => commands::scenario_new::run(&args),
        Command::Scenario(ScenarioCommand::Generate(args)) => {
            commands::scenario_generate::run(&args)
        }
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) if e.downcast_ref::<commands::plan::Infeasible>().is_some() => {
            eprintln!("error: {}", message(&e));
            ExitCode::from(commands::plan::EXIT_INFEASIBLE)
        }
        Err(e) => {
            eprintln!("error: {}", message(&e));
            ExitCode::from(2)
        }
    }
}

/// The error with its causes, each said once: library errors already put their source's
/// text in their own message (`{origin}: {source}`), so a cause whose text the message so
/// far contains is left out instead of being printed again.
fn message(e: &anyhow::Error) -> String {
    let mut out = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if out.is_empty() {
            out = text;
        } else if !out.contains(&text) {
            out.push_str(": ");
            out.push_str(&text);
        }
    }
    out
}
