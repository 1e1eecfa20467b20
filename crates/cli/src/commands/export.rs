//! `swarmplan export DIR`: a planned mission in WGS 84 for autopilots and GIS, from the
//! `plan.json` and `scenario.toml` that `plan` writes into DIR (the writing is shared with
//! `plan --export`: [`crate::mission_export`]). Formats and altitude
//! references: `docs/export.md`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_io::export::ExportFormat;
use swarmplan_io::geo::{load_spec_with_origin, parse_lat_lon_alt, resolve_frame};
use swarmplan_io::plan_file::{read_plan, Provenance};
use swarmplan_io::plan_folder::PlanFolder;
use swarmplan_io::scenario::build_world;

use crate::mission_export::{georeferenced_by, write_all};

#[derive(Debug, Args)]
pub struct ExportArgs {
    /// Folder written by `swarmplan plan` (holds plan.json and scenario.toml).
    pub dir: PathBuf,
    /// Formats, comma-separated: qgc-plan, wpl, geojson, kml, csv, or all.
    #[arg(long, default_value = "all")]
    pub format: String,
    /// Output folder (default: DIR).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Geodetic origin of local (0, 0): LAT,LON[,ALT] in degrees and metres AMSL of local
    /// height 0; overrides the scenario's `[geo] origin` and the terrain file's CRS.
    #[arg(long, allow_hyphen_values = true)]
    pub origin: Option<String>,
    /// Terrain file, when the scenario's terrain path does not resolve from DIR.
    #[arg(long)]
    pub terrain: Option<PathBuf>,
    /// Plan file (default: DIR/plan.json).
    #[arg(long)]
    pub plan: Option<PathBuf>,
    /// Scenario (built-in name or file; default: DIR/scenario.toml).
    #[arg(long)]
    pub scenario: Option<String>,
}

/// The terrain file to use: `--terrain`, else the scenario's source when it does not
/// resolve from the scenario's folder but does from the current one (`plan` writes the
/// source as it resolved it from where it ran).
fn terrain_override(
    loaded: &swarmplan_io::scenario::LoadedSpec,
    flag: Option<&Path>,
) -> Option<PathBuf> {
    if let Some(p) = flag {
        return Some(p.to_path_buf());
    }
    let source = &loaded.spec.terrain.source;
    if source == "procedural" {
        return None;
    }
    let from_dir = loaded.base_dir.join(source);
    let here = PathBuf::from(source);
    (!from_dir.exists() && here.exists()).then_some(here)
}

pub fn run(args: &ExportArgs) -> Result<()> {
    let formats = ExportFormat::parse_list(&args.format).context("--format")?;
    let explicit = args
        .origin
        .as_deref()
        .map(|o| parse_lat_lon_alt(o, "--origin"))
        .transpose()?;
    let scenario = match &args.scenario {
        Some(s) => s.clone(),
        None => {
            let p = PlanFolder::new(&args.dir).scenario_path();
            anyhow::ensure!(
                p.exists(),
                "{}: not found (written by `swarmplan plan`); name the scenario with \
                 --scenario NAME|FILE",
                p.display()
            );
            p.display().to_string()
        }
    };
    let (loaded, origin) = load_spec_with_origin(&scenario)
        .with_context(|| format!("{}: the scenario of the plan", args.dir.display()))?;
    let terrain = terrain_override(&loaded, args.terrain.as_deref());
    let world = build_world(&loaded, terrain.as_deref())?;
    let plan_path = args
        .plan
        .clone()
        .unwrap_or_else(|| PlanFolder::new(&args.dir).plan_path());
    let plan = read_plan(&plan_path, &world, Provenance::MustMatch)?;
    let (frame, source) = resolve_frame(&loaded, origin, terrain.as_deref(), explicit)?;
    let out = args.out.clone().unwrap_or_else(|| args.dir.clone());
    crate::out_folder::ensure_writable(&out, "--out")?;
    let files = write_all(&world, &plan, &frame, &formats, &out)?;
    eprintln!("{}", georeferenced_by(source, &frame));
    for f in &files {
        println!("{}", f.display());
    }
    Ok(())
}
