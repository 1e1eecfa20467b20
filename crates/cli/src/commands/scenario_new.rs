//! `swarmplan scenario new`: writes an editable scenario TOML on a georeferenced DEM from a
//! start and a goal in latitude and longitude (what it sets: the module docs of
//! `swarmplan_io::geo::new_scenario`, and `docs/export.md`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_io::geo::{
    new_scenario, parse_lat_lon, scenario_toml_with_origin, NewScenarioRequest,
};

#[derive(Debug, Args)]
pub struct ScenarioNewArgs {
    /// DEM (GeoTIFF) in WGS 84 / UTM, GDA94 or GDA2020 / MGA, or geographic WGS 84.
    #[arg(long)]
    pub terrain: PathBuf,
    /// Start of every UAV: LAT,LON in degrees (WGS 84).
    #[arg(long, allow_hyphen_values = true)]
    pub start: String,
    /// Goal (UGV0): LAT,LON in degrees (WGS 84).
    #[arg(long, allow_hyphen_values = true)]
    pub goal: String,
    /// Number of UAVs.
    #[arg(long, allow_negative_numbers = true)]
    pub uavs: usize,
    /// Output file (default: print the TOML).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Scenario name (default: the output file's or the DEM's file stem).
    #[arg(long)]
    pub name: Option<String>,
    /// Height above ground of the start and the goal, metres.
    #[arg(long, default_value_t = 150.0, allow_negative_numbers = true)]
    pub agl: f64,
    /// Map box = the start-goal box plus this margin in metres, clipped to the DEM
    /// (default: the whole DEM).
    #[arg(long, allow_negative_numbers = true)]
    pub margin: Option<f64>,
}

/// `terrain.source` for the TOML: relative to the output file's folder (scenario files
/// resolve terrain paths from their own folder); as given when the TOML is printed
/// (relative paths then resolve from the folder the TOML is saved in, usually the current
/// one).
fn terrain_source(terrain: &Path, out: Option<&Path>) -> String {
    let Some(out) = out else {
        return terrain.display().to_string();
    };
    let dir = out
        .parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    match (terrain.canonicalize(), dir.canonicalize()) {
        (Ok(t), Ok(d)) => relative(&t, &d).display().to_string(),
        _ => terrain.display().to_string(),
    }
}

/// `target` relative to the folder `base` (both absolute): `..` for each component of
/// `base` past their common prefix, then the rest of `target`.
fn relative(target: &Path, base: &Path) -> PathBuf {
    let t: Vec<_> = target.components().collect();
    let b: Vec<_> = base.components().collect();
    let common = t.iter().zip(&b).take_while(|(x, y)| x == y).count();
    if common == 0 {
        return target.to_path_buf();
    }
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &t[common..] {
        out.push(c);
    }
    out
}

fn stem(p: &Path) -> Option<String> {
    p.file_stem().map(|s| s.to_string_lossy().into_owned())
}

pub fn run(args: &ScenarioNewArgs) -> Result<()> {
    let start = parse_lat_lon(&args.start, "--start")?;
    let goal = parse_lat_lon(&args.goal, "--goal")?;
    if let Some(dir) = args
        .out
        .as_deref()
        .and_then(Path::parent)
        .filter(|d| !d.as_os_str().is_empty())
    {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create", dir.display()))?;
    }
    let name = args
        .name
        .clone()
        .or_else(|| args.out.as_deref().and_then(stem))
        .or_else(|| stem(&args.terrain))
        .unwrap_or_else(|| "dem".into());
    let req = NewScenarioRequest {
        terrain: &args.terrain,
        terrain_source: terrain_source(&args.terrain, args.out.as_deref()),
        start,
        goal,
        uavs: args.uavs,
        agl: args.agl,
        name,
        margin: args.margin,
    };
    let new = new_scenario(&req)?;
    let header = format!(
        "Written by `swarmplan scenario new --terrain {}`.\n\
         start {}, {} -> local ({:.2}, {:.2}) m; goal {}, {} -> local ({:.2}, {:.2}) m.\n\
         Frame: {}.\n\
         No threats yet; communication range and battery scaled to the distance. Edit freely \
         (docs/scenario.md).",
        args.terrain.display(),
        start.lat_deg,
        start.lon_deg,
        new.start_local.x,
        new.start_local.y,
        goal.lat_deg,
        goal.lon_deg,
        new.goal_local.x,
        new.goal_local.y,
        new.frame.describe()
    );
    let text = scenario_toml_with_origin(&new.spec, new.origin, &header);
    match &args.out {
        Some(p) => {
            std::fs::write(p, &text).with_context(|| format!("{}: cannot write", p.display()))?;
            eprintln!("wrote {}", p.display());
        }
        None => print!("{text}"),
    }
    Ok(())
}
