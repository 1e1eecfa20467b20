//! A planned mission written in WGS 84 for autopilots and GIS: what `export` writes from a
//! plan folder and `plan --export` writes after planning, settled before it starts
//! ([`PlannedExport`]). Formats and altitude references: `docs/export.md`.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use swarmplan_core::plan::Plan;
use swarmplan_core::world::World;
use swarmplan_io::export::{write_mission, ExportFormat, Mission};
use swarmplan_io::geo::{load_spec_with_origin, parse_lat_lon_alt, resolve_frame, FrameSource};

/// Converts `plan` and writes `formats` into `out`; prints nothing.
pub fn write_all(
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

pub fn georeferenced_by(source: FrameSource, frame: &swarmplan_io::geo::LocalFrame) -> String {
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
