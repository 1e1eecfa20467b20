//! `swarmplan scenario generate`: a random scenario from a seed (what it draws:
//! `swarmplan_io::generate` and `docs/scenario.md`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_io::generate::{generate, GenerateRequest};
use swarmplan_io::scenario::to_toml;

#[derive(Debug, Args)]
pub struct ScenarioGenerateArgs {
    /// Seed: the same seed and flags give the same scenario.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::parse_seed)]
    pub seed: u64,
    /// Number of UAVs.
    #[arg(long, allow_negative_numbers = true)]
    pub uavs: usize,
    /// Number of cylindrical threats.
    #[arg(long, allow_negative_numbers = true)]
    pub threats: usize,
    /// All UAVs start at one point (the paper's setting); default: 40 m apart.
    #[arg(long)]
    pub shared_start: bool,
    /// Interference windows on the way (0: none).
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub comm_windows: usize,
    /// Let the planner choose the fleet's pace within the speed limits (timing.pace; a
    /// decision variable, docs/model.md "Pace"); default: fixed nearest cruise.
    #[arg(long)]
    pub free_pace: bool,
    /// Let the planner choose each UAV's departure delay, a hover at its start of up to
    /// 30 % of the mission (timing.max_delay; docs/model.md "Departure delays"); default:
    /// every UAV leaves at once.
    #[arg(long)]
    pub free_delays: bool,
    /// Launch everyone at once from a shared start and land everyone at UGV0 at once (the
    /// paper's layout); default: launch and recovery slots 5 s apart (timing.launch_interval
    /// and recovery_interval; docs/model.md "Launch and recovery slots").
    #[arg(long)]
    pub no_slots: bool,
    /// DEM (GeoTIFF or ESRI ASCII) whose extent becomes the map (default: procedural).
    #[arg(long)]
    pub terrain: Option<PathBuf>,
    /// Output file (default: print the TOML).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

pub fn run(args: &ScenarioGenerateArgs) -> Result<()> {
    let mut spec = generate(&GenerateRequest {
        seed: args.seed,
        uavs: args.uavs,
        threats: args.threats,
        shared_start: args.shared_start,
        comm_windows: args.comm_windows,
        terrain: args.terrain.as_ref().map(|p| p.display().to_string()),
        free_pace: args.free_pace,
        free_delays: args.free_delays,
        slots: !args.no_slots,
    })?;
    if let Some(terrain) = &args.terrain {
        spec.terrain.source = source_for(terrain, args.out.as_deref());
    }
    let text = format!(
        "# swarmplan scenario generate --seed {} --uavs {} --threats {}{}{}{}{}{}{}\n{}",
        args.seed,
        args.uavs,
        args.threats,
        if args.shared_start {
            " --shared-start"
        } else {
            ""
        },
        if args.comm_windows > 0 {
            format!(" --comm-windows {}", args.comm_windows)
        } else {
            String::new()
        },
        if args.free_pace { " --free-pace" } else { "" },
        if args.free_delays {
            " --free-delays"
        } else {
            ""
        },
        if args.no_slots { " --no-slots" } else { "" },
        args.terrain
            .as_ref()
            .map_or(String::new(), |t| format!(" --terrain {}", t.display())),
        to_toml(&spec)
    );
    match &args.out {
        Some(path) => {
            std::fs::write(path, text)
                .with_context(|| format!("{}: cannot write", path.display()))?;
            println!("wrote {} ({})", path.display(), spec.description);
        }
        None => print!("{text}"),
    }
    Ok(())
}

/// How the written scenario names the DEM: paths inside a scenario file are relative to that
/// file, so relative to the `--out` file's folder, or absolute when the TOML goes to stdout
/// (it may be saved anywhere). The DEM was just read, so it exists; should its path not
/// resolve, it is written as given.
fn source_for(terrain: &Path, out: Option<&Path>) -> String {
    let Ok(dem) = std::fs::canonicalize(terrain) else {
        return terrain.display().to_string();
    };
    let folder = out
        .and_then(|o| std::path::absolute(o).ok())
        .and_then(|o| o.parent().map(Path::to_path_buf));
    folder
        .and_then(|f| std::fs::canonicalize(f).ok())
        .and_then(|f| pathdiff::diff_paths(&dem, f))
        .unwrap_or(dem)
        .display()
        .to_string()
}
