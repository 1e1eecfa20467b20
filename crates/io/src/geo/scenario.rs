//! Where a scenario's georeferencing comes from: the `[geo]` table of its TOML, its DEM, or
//! an explicit origin; [`resolve_frame`] picks one (precedence in the `geo` module docs).
//!
//! The `[geo]` table is part of the scenario spec (`ScenarioSpec::geo`, validated there);
//! this module turns it, or the DEM's georeferencing, into a local frame.

use std::path::{Path, PathBuf};

use super::ellipsoid::Geodetic;
use super::frame::LocalFrame;
use super::GeoError;
use crate::dem::{read_terrain, DemFrame, DemOptions};
use crate::scenario::LoadedSpec;

use crate::catalog::load_spec;
use swarmplan_core::world::spec::TerrainFrame;

/// Which input a frame came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FrameSource {
    /// `--origin` (or an origin passed by a caller).
    Explicit,
    /// The terrain file's own georeferencing.
    Dem,
    /// The scenario's `[geo] origin`.
    Scenario,
}

impl FrameSource {
    /// The input in words, for messages (e.g. "the --origin flag").
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Self::Explicit => "the --origin flag",
            Self::Dem => "the terrain file's georeferencing",
            Self::Scenario => "the scenario's [geo] origin",
        }
    }
}

/// The scenario's `[geo] origin` (latitude, longitude in degrees, altitude in metres AMSL
/// of local height 0), or None without one. The spec validated its ranges already.
#[must_use]
pub fn scenario_origin(loaded: &LoadedSpec) -> Option<Geodetic> {
    loaded
        .spec
        .geo
        .map(|g| Geodetic::new(g.origin[0], g.origin[1], g.origin[2]))
}

/// [`load_spec`] plus the scenario's `[geo] origin`.
pub fn load_spec_with_origin(
    name_or_path: &str,
) -> Result<(LoadedSpec, Option<Geodetic>), GeoError> {
    let loaded = load_spec(name_or_path)?;
    let origin = scenario_origin(&loaded);
    Ok((loaded, origin))
}

/// The frame of the scenario's terrain file, or why there is none (procedural terrain,
/// `spso-pixels` frame, no or unsupported CRS, unreadable file). `terrain_override`
/// replaces the terrain source as `--terrain` does.
pub fn dem_frame_of_spec(
    loaded: &LoadedSpec,
    terrain_override: Option<&Path>,
) -> Result<LocalFrame, String> {
    let t = &loaded.spec.terrain;
    let path: PathBuf = match terrain_override {
        Some(p) => p.to_path_buf(),
        None if t.source == "procedural" => {
            return Err("its terrain is procedural".into());
        }
        None => loaded.base_dir.join(&t.source),
    };
    if t.frame != TerrainFrame::Georeferenced {
        return Err(format!(
            "its terrain {} is read in the `spso-pixels` frame, which is not georeferenced",
            path.display()
        ));
    }
    let opts = DemOptions {
        frame: DemFrame::Georeferenced,
        sampling: t.sampling,
    };
    let dem = read_terrain(&path, &opts).map_err(|e| e.to_string())?;
    LocalFrame::from_dem(&dem).map_err(|e| e.to_string())
}

/// The frame of a scenario: `explicit` if given, else the DEM's, else `[geo] origin`
/// (`scenario_origin`), else [`GeoError::NoOrigin`] saying why the DEM gave none.
pub fn resolve_frame(
    loaded: &LoadedSpec,
    scenario_origin: Option<Geodetic>,
    terrain_override: Option<&Path>,
    explicit: Option<Geodetic>,
) -> Result<(LocalFrame, FrameSource), GeoError> {
    if let Some(o) = explicit {
        return Ok((LocalFrame::tangent(o)?, FrameSource::Explicit));
    }
    match dem_frame_of_spec(loaded, terrain_override) {
        Ok(frame) => Ok((frame, FrameSource::Dem)),
        Err(why) => match scenario_origin {
            Some(o) => Ok((LocalFrame::tangent(o)?, FrameSource::Scenario)),
            None => Err(GeoError::NoOrigin {
                scenario: loaded.spec.name.clone(),
                why: format!(" ({why})"),
            }),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn geo_table_is_read_and_checked() {
        let base = crate::scenario::BUILTIN[4].1;
        let with = format!("{base}\n[geo]\norigin = [-10.5, 105, 12.5]\n");
        let spec = crate::scenario::parse_spec(&with, "s.toml").unwrap();
        let loaded = LoadedSpec {
            spec,
            origin: "s.toml".into(),
            base_dir: PathBuf::from("."),
            text: with.clone(),
        };
        assert_eq!(
            scenario_origin(&loaded),
            Some(Geodetic::new(-10.5, 105.0, 12.5))
        );
        assert_eq!(scenario_origin(&load_spec("tiny").unwrap()), None);
        for (bad, needle) in [
            ("[geo]\norigin = [1, 2]\n", "origin"),
            ("[geo]\norigin = [91, 2, 0]\n", "latitude"),
            // Checked at load like the rest, not by the first export.
            ("[geo]\norigin = [10, 20, 1e9]\n", "geo.origin: altitude"),
            ("[geo]\norigin = [89.9999, 2, 0]\n", "within 89.999 degrees"),
            ("[geo]\norign = [1, 2, 0]\n", "orign"),
            ("[geo]\n", "origin"),
        ] {
            let e = crate::scenario::parse_spec(&format!("{base}\n{bad}"), "s.toml")
                .unwrap_err()
                .to_string();
            assert!(e.starts_with("s.toml") && e.contains(needle), "{bad}: {e}");
        }
    }

    #[test]
    fn procedural_scenarios_need_an_origin() {
        let loaded = load_spec("tiny").unwrap();
        let e = resolve_frame(&loaded, None, None, None)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("no geodetic origin")
                && e.contains("[geo] origin")
                && e.contains("--origin"),
            "{e}"
        );
        let (f, src) =
            resolve_frame(&loaded, Some(Geodetic::new(1.0, 2.0, 3.0)), None, None).unwrap();
        assert_eq!(src, FrameSource::Scenario);
        assert_eq!(f.altitude_offset(), 3.0);
        let (_, src) = resolve_frame(
            &loaded,
            Some(Geodetic::new(1.0, 2.0, 3.0)),
            None,
            Some(Geodetic::new(4.0, 5.0, 0.0)),
        )
        .unwrap();
        assert_eq!(src, FrameSource::Explicit);
    }
}
