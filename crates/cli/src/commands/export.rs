//! `swarmplan export DIR`: a planned mission in WGS 84 for autopilots and GIS, from the
//! `plan.json` and `scenario.toml` that `plan` writes into DIR; and [`PlannedExport`],
//! which `plan --export` settles before planning and writes after. Formats and altitude
//! references: `docs/export.md`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use swarmplan_core::plan::Plan;
use swarmplan_core::world::World;
use swarmplan_io::export::{write_mission, ExportFormat, Mission};
use swarmplan_io::geo::{load_spec_with_origin, parse_lat_lon_alt, resolve_frame, FrameSource};
use swarmplan_io::plan_file::{read_plan, Provenance};
use swarmplan_io::scenario::build_world;

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

/// Converts `plan` and writes `formats` into `out`; prints nothing.
fn write_all(
    world: &World,
    plan: &Plan,
    frame: &swarmplan_io::geo::LocalFrame,
    formats: &[ExportFormat],
    out: &Path,
) -> Result<Vec<PathBuf>> {
    let mission = Mission::new(world, plan, frame)?;
    if let Some(v) = &mission.infeasible {
        eprintln!("warning: exporting a plan that is {v}; the files say so in their description (WPL has none)");
    }
    let mut files = Vec::new();
    for f in formats {
        files.extend(write_mission(&mission, *f, out)?);
    }
    Ok(files)
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
            let p = args.dir.join("scenario.toml");
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
        .unwrap_or_else(|| args.dir.join("plan.json"));
    let plan = read_plan(&plan_path, &world, Provenance::MustMatch)?;
    let (frame, source) = resolve_frame(&loaded, origin, terrain.as_deref(), explicit)?;
    let out = args.out.clone().unwrap_or_else(|| args.dir.clone());
    super::out_folder::ensure_writable(&out, "--out")?;
    let files = write_all(&world, &plan, &frame, &formats, &out)?;
    eprintln!("{}", georeferenced_by(source, &frame));
    for f in &files {
        println!("{}", f.display());
    }
    Ok(())
}

fn georeferenced_by(source: FrameSource, frame: &swarmplan_io::geo::LocalFrame) -> String {
    format!(
        "georeferenced by {}: {}",
        source.describe(),
        frame.describe()
    )
}

/// What `plan --export FORMATS [--origin LAT,LON[,ALT]]` will write, settled before the
/// planning starts, so that a mistyped format or a scenario without a georeference is said
/// at once instead of after the run, with its results unwritten.
pub struct PlannedExport {
    formats: Vec<ExportFormat>,
    frame: swarmplan_io::geo::LocalFrame,
    source: FrameSource,
}

impl PlannedExport {
    /// `scenario` and `terrain` are the plan command's `--scenario` and `--terrain`.
    pub fn prepare(
        scenario: &str,
        terrain: Option<&Path>,
        formats: &str,
        origin: Option<&str>,
    ) -> Result<Self> {
        let formats = ExportFormat::parse_list(formats).context("--export")?;
        let explicit = origin
            .map(|o| parse_lat_lon_alt(o, "--origin"))
            .transpose()?;
        let (loaded, scenario_origin) = load_spec_with_origin(scenario)?;
        let (frame, source) =
            resolve_frame(&loaded, scenario_origin, terrain, explicit).context("--export")?;
        Ok(Self {
            formats,
            frame,
            source,
        })
    }

    /// Exports the plan just made into `out`. Writes only to stderr (one line on the
    /// georeferencing), so `plan --json` stays clean; returns the files written.
    pub fn write(&self, world: &World, plan: &Plan, out: &Path) -> Result<Vec<PathBuf>> {
        let files = write_all(world, plan, &self.frame, &self.formats, out)?;
        eprintln!("{}", georeferenced_by(self.source, &self.frame));
        Ok(files)
    }
}
