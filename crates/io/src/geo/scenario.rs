//! Where a scenario's georeferencing comes from: the `[geo]` table of its TOML, its DEM, or
//! an explicit origin; [`resolve_frame`] picks one (precedence in the `geo` module docs).
//!
//! The `[geo]` table is read from the scenario text here, so this works whether or not the
//! core `ScenarioSpec` declares the field yet: [`load_spec_with_origin`] reads a file whose
//! `[geo]` the spec parser rejects by parsing it without that table.

use std::path::{Path, PathBuf};

use super::ellipsoid::Geodetic;
use super::frame::LocalFrame;
use super::{check_geodetic, GeoError};
use crate::dem::{read_terrain, DemFrame, DemOptions};
use crate::scenario::{load_spec, parse_spec, LoadedSpec};
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
    #[must_use]
    pub fn describe(self) -> &'static str {
        match self {
            Self::Explicit => "the --origin flag",
            Self::Dem => "the terrain file's georeferencing",
            Self::Scenario => "the scenario's [geo] origin",
        }
    }
}

/// The `[geo]` table of scenario TOML text, `origin = [lat, lon, alt]` (degrees, degrees,
/// metres AMSL of local height 0), or None without one; `origin` names the text in errors.
pub fn scenario_origin(text: &str, origin: &str) -> Result<Option<Geodetic>, GeoError> {
    let spec_err = |message: String| GeoError::Spec {
        origin: origin.to_string(),
        message,
    };
    let table: toml::Table = toml::from_str(text)
        .map_err(|e| spec_err(format!("not TOML: {}", e.to_string().trim_end())))?;
    let Some(geo) = table.get("geo") else {
        return Ok(None);
    };
    let expected = "a table `[geo]` with `origin = [lat, lon, alt]`";
    let geo = geo
        .as_table()
        .ok_or_else(|| spec_err(format!("expected {expected}, got `{geo}`")))?;
    if let Some(key) = geo.keys().find(|k| k.as_str() != "origin") {
        return Err(spec_err(format!(
            "unknown field `{key}`, expected `origin`"
        )));
    }
    let value = geo
        .get("origin")
        .ok_or_else(|| spec_err(format!("missing `origin`: expected {expected}")))?;
    let numbers: Option<Vec<f64>> = value.as_array().map(|a| {
        a.iter()
            .filter_map(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
            .collect()
    });
    match numbers {
        Some(v) if v.len() == 3 && value.as_array().is_some_and(|a| a.len() == 3) => {
            check_geodetic(
                Geodetic::new(v[0], v[1], v[2]),
                &format!("{origin}: geo.origin"),
            )
            .map(Some)
        }
        _ => Err(spec_err(format!(
            "origin: expected [lat, lon, alt] (three numbers: degrees, degrees, metres), got \
             `{value}`"
        ))),
    }
}

/// [`load_spec`] plus the scenario's `[geo] origin`. A file whose `[geo]` table the spec
/// parser does not know is parsed without it.
pub fn load_spec_with_origin(
    name_or_path: &str,
) -> Result<(LoadedSpec, Option<Geodetic>), GeoError> {
    let first = match load_spec(name_or_path) {
        Ok(loaded) => {
            let origin = scenario_origin(&loaded.text, &loaded.origin)?;
            return Ok((loaded, origin));
        }
        Err(e) => e,
    };
    let path = Path::new(name_or_path);
    let Ok(text) = std::fs::read_to_string(path) else {
        return Err(first.into());
    };
    let Ok(mut table) = toml::from_str::<toml::Table>(&text) else {
        return Err(first.into());
    };
    if table.remove("geo").is_none() {
        return Err(first.into());
    }
    let name = path.display().to_string();
    let origin = scenario_origin(&text, &name)?;
    let stripped = toml::to_string(&table).map_err(|e| GeoError::Spec {
        origin: name.clone(),
        message: e.to_string(),
    })?;
    let spec = parse_spec(&stripped, &name)?;
    Ok((
        LoadedSpec {
            spec,
            origin: name,
            base_dir: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            text,
        },
        origin,
    ))
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
        let text = "name = \"x\"\n[geo]\norigin = [-10.5, 105, 12.5]\n";
        let o = scenario_origin(text, "s.toml").unwrap().unwrap();
        assert_eq!(o, Geodetic::new(-10.5, 105.0, 12.5));
        assert_eq!(scenario_origin("name = \"x\"\n", "s.toml").unwrap(), None);
        for (bad, needle) in [
            ("[geo]\norigin = [1, 2]\n", "three numbers"),
            ("[geo]\norigin = [1, 2, \"a\"]\n", "three numbers"),
            ("[geo]\norigin = [91, 2, 0]\n", "latitude"),
            ("[geo]\norign = [1, 2, 0]\n", "unknown field `orign`"),
            ("[geo]\n", "missing `origin`"),
            ("geo = 3\n", "expected a table"),
        ] {
            let e = scenario_origin(bad, "s.toml").unwrap_err().to_string();
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
            e.contains("no geodetic origin") && e.contains("[geo] origin") && e.contains("--origin"),
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
