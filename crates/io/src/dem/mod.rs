//! Terrain readers: a DEM file becomes a [`Terrain`] plus what the file said about itself.
//!
//! Formats: GeoTIFF (`.tif`, `.tiff`; one band of 8- to 64-bit integers or 16- to 64-bit
//! floats, strips or tiles) and ESRI ASCII grid (`.asc`). The format is recognised by the
//! file's first bytes (TIFF magic, or an ASCII-grid keyword), then by its extension. Either
//! may be gzip-compressed (`.asc.gz`, recognised by the gzip magic).
//!
//! Two frames turn raster cells into plan coordinates ([`DemFrame`]):
//! - [`DemFrame::Georeferenced`] (for user files): x east, y north in metres, origin (0, 0)
//!   at the south-west node (the centre of the south-west cell), cell size from the file,
//!   rows flipped so terrain row 0 is the southern edge. [`LoadedDem::local_to_world`]
//!   maps back to the file's coordinates.
//! - [`DemFrame::SpsoPixels`] (the SPSO reference code): 1 unit per pixel, x = column + 1,
//!   y = file row + 1 (the first, northern file row is y = 1), i.e. terrain row j = file row
//!   j, origin (1, 1), cell (1, 1). With [`Sampling::NearestMatlab`] the terrain answers
//!   exactly SPSO's `H(round(y), round(x))`.
//!
//! Nodata: a cell is nodata if it is not finite, if it equals the file's nodata value
//! (GeoTIFF `GDAL_NODATA`, ASCII `NODATA_value`, default -9999 for ASCII grids; compared with
//! a relative tolerance of 1e-6 because GDAL writes the float32 minimum as "-3.402823e+38",
//! which is not that float), or if its magnitude exceeds 1e30 (a float-minimum sentinel with
//! a missing tag). Each nodata cell takes the value of the nearest valid cell, nearest
//! counted in 8-neighbour grid steps (ties: edge neighbours before corner neighbours, then
//! row-major file order); [`LoadedDem::nodata_filled`] says how many. A file with no valid
//! cell is an error ([`DemError::AllNodata`]). So no sentinel ever reaches the terrain.
//!
//! Reading never panics on bad input; every failure is a [`DemError`] naming the file.

mod error;
mod esri_ascii;
mod geotiff;
mod nodata;

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
pub use swarmplan_core::world::terrain::Sampling;
use swarmplan_core::world::terrain::Terrain;

pub use error::DemError;

/// How raster cells map to plan coordinates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum DemFrame {
    /// Metres east / north of the south-west node; cell size from the file.
    #[default]
    Georeferenced,
    /// SPSO's convention: 1 unit per pixel, (x, y) = (column + 1, file row + 1).
    SpsoPixels,
}

/// Options of [`read_terrain`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(deny_unknown_fields, default)]
pub struct DemOptions {
    /// Default [`DemFrame::Georeferenced`].
    pub frame: DemFrame,
    /// Default [`Sampling::Bilinear`].
    pub sampling: Sampling,
}

impl DemOptions {
    /// SPSO's reading of its DEM: pixel units and `H(round(y), round(x))`.
    pub const SPSO: Self = Self {
        frame: DemFrame::SpsoPixels,
        sampling: Sampling::NearestMatlab,
    };
}

/// The file format a DEM was read from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DemFormat {
    /// GeoTIFF (`.tif`, `.tiff`).
    GeoTiff,
    /// ESRI ASCII grid (`.asc`).
    EsriAscii,
}

/// How samples were stored in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SampleType {
    /// 8-bit unsigned integers.
    U8,
    /// 8-bit signed integers.
    I8,
    /// 16-bit unsigned integers.
    U16,
    /// 16-bit signed integers.
    I16,
    /// 32-bit unsigned integers.
    U32,
    /// 32-bit signed integers.
    I32,
    /// 64-bit unsigned integers.
    U64,
    /// 64-bit signed integers.
    I64,
    /// 16-bit floats.
    F16,
    /// 32-bit floats.
    F32,
    /// 64-bit floats.
    F64,
    /// Decimal text (ESRI ASCII grid).
    Text,
}

/// Coordinate reference system named by the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Crs {
    /// Projected CRS with this EPSG code (GeoTIFF `ProjectedCSTypeGeoKey`, 3072).
    Projected(u16),
    /// Geographic CRS (longitude, latitude in degrees) with this EPSG code
    /// (`GeographicTypeGeoKey`, 2048); 0 when the model type says geographic but gives no code.
    Geographic(u16),
    /// No EPSG code: user-defined, absent (ESRI ASCII grids carry none), or geocentric.
    /// `model_type` is `GTModelTypeGeoKey` (1024) when present.
    Unknown {
        /// `GTModelTypeGeoKey` (1: projected, 2: geographic, 3: geocentric), if present.
        model_type: Option<u16>,
    },
}

impl Crs {
    /// The EPSG code, if the file gave one.
    #[must_use]
    pub fn epsg(&self) -> Option<u16> {
        match *self {
            Self::Projected(c) | Self::Geographic(c) if c != 0 => Some(c),
            _ => None,
        }
    }
}

/// A GeoTIFF tie point: raster (i, j, k) -> model (x, y, z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TiePoint {
    /// Raster position (i, j, k): column and row in pixels, k usually 0.
    pub raster: [f64; 3],
    /// Model position (x, y, z) in CRS units.
    pub model: [f64; 3],
}

/// Where the raster sits in the file's coordinate system (all in CRS units).
#[derive(Debug, Clone, PartialEq)]
pub struct GeoReference {
    /// Outer north-west corner of the raster.
    pub upper_left_corner: (f64, f64),
    /// Outer south-west corner of the raster (the "lower-left corner").
    pub lower_left_corner: (f64, f64),
    /// Centre of the south-west cell: where local (0, 0) of the georeferenced frame lies.
    pub south_west_node: (f64, f64),
    /// Cell size (x, y), positive, in CRS units (degrees for a geographic CRS).
    pub cell: (f64, f64),
    /// The coordinate reference system the file names.
    pub crs: Crs,
    /// True when the EPSG code was derived from the projection (UTM zone) and datum keys
    /// because `ProjectedCSTypeGeoKey` was user-defined.
    pub crs_inferred: bool,
    /// The CRS citation text of a GeoTIFF (e.g. "GDA94 / MGA zone 48"), if any.
    pub citation: Option<String>,
    /// The first GeoTIFF tie point as written (None for ASCII grids or a transformation tag).
    pub tie_point: Option<TiePoint>,
    /// GeoTIFF `GTRasterTypeGeoKey` = PixelIsPoint (already accounted for in the corners).
    pub pixel_is_point: bool,
    /// Metres per CRS linear unit (`ProjLinearUnitsGeoKey`: metre, foot, US survey foot).
    pub metres_per_unit: f64,
}

/// A DEM read from a file: the terrain in the requested frame plus the file's metadata.
#[derive(Debug, Clone)]
pub struct LoadedDem {
    /// The heights as a terrain in the requested frame, nodata filled.
    pub terrain: Terrain,
    /// The file read.
    pub path: PathBuf,
    /// The file's format.
    pub format: DemFormat,
    /// How the file stored its samples.
    pub sample_type: SampleType,
    /// The options the terrain was built with.
    pub options: DemOptions,
    /// Raster size: columns (x) and rows (y).
    pub columns: usize,
    /// Raster rows (y).
    pub rows: usize,
    /// Georeferencing, if the file has any (ESRI ASCII grids always do, without a CRS).
    pub georef: Option<GeoReference>,
    /// Cell size in metres used by the georeferenced frame: the file's cell size times
    /// `metres_per_unit`, or for a geographic CRS the cell's ground size at the raster's
    /// centre latitude (WGS 84 ellipsoid; the east-west size varies with latitude, by
    /// about 1.7 % across a 1-degree tile at 45 degrees). (1, 1) without georeferencing.
    pub cell_metres: (f64, f64),
    /// The file's nodata value, if any.
    pub nodata: Option<f64>,
    /// Number of nodata cells that were filled from their nearest valid neighbour.
    pub nodata_filled: usize,
}

impl LoadedDem {
    /// World coordinates of the raster's outer lower-left corner, if georeferenced.
    #[must_use]
    pub fn lower_left(&self) -> Option<(f64, f64)> {
        self.georef.as_ref().map(|g| g.lower_left_corner)
    }

    /// Cell size as written in the file (CRS units), if georeferenced.
    #[must_use]
    pub fn file_cell_size(&self) -> Option<(f64, f64)> {
        self.georef.as_ref().map(|g| g.cell)
    }

    /// Maps terrain coordinates (x, y) to the file's world coordinates (CRS units).
    /// Exact for projected CRSs; for a geographic CRS it uses the same centre-latitude scale
    /// as [`Self::cell_metres`]. None when the file has no georeferencing.
    #[must_use]
    pub fn local_to_world(&self, x: f64, y: f64) -> Option<(f64, f64)> {
        let g = self.georef.as_ref()?;
        Some(match self.options.frame {
            DemFrame::Georeferenced => (
                g.south_west_node.0 + x * g.cell.0 / self.cell_metres.0,
                g.south_west_node.1 + y * g.cell.1 / self.cell_metres.1,
            ),
            // Pixel (x, y) is the centre of column x - 1, file row y - 1 (from the north).
            DemFrame::SpsoPixels => (
                g.upper_left_corner.0 + (x - 0.5) * g.cell.0,
                g.upper_left_corner.1 - (y - 0.5) * g.cell.1,
            ),
        })
    }

    /// The inverse of [`Self::local_to_world`].
    #[must_use]
    pub fn world_to_local(&self, wx: f64, wy: f64) -> Option<(f64, f64)> {
        let g = self.georef.as_ref()?;
        Some(match self.options.frame {
            DemFrame::Georeferenced => (
                (wx - g.south_west_node.0) * self.cell_metres.0 / g.cell.0,
                (wy - g.south_west_node.1) * self.cell_metres.1 / g.cell.1,
            ),
            DemFrame::SpsoPixels => (
                (wx - g.upper_left_corner.0) / g.cell.0 + 0.5,
                (g.upper_left_corner.1 - wy) / g.cell.1 + 0.5,
            ),
        })
    }
}

/// A raster as decoded, before nodata filling and framing.
pub(crate) struct RawRaster {
    pub columns: usize,
    pub rows: usize,
    /// Row-major in file order: the first row is the northern edge.
    pub values: Vec<f64>,
    pub nodata: Option<f64>,
    pub sample_type: SampleType,
    pub georef: Option<GeoReference>,
}

/// Reads a DEM file into a terrain. See the module docs for frames and nodata handling.
pub fn read_terrain(path: &Path, opts: &DemOptions) -> Result<LoadedDem, DemError> {
    let bytes = std::fs::read(path).map_err(|source| DemError::Io {
        path: path.into(),
        source,
    })?;
    read_terrain_bytes(path, bytes, opts)
}

/// [`read_terrain`] on the content of a file already in memory; `path` names it in errors
/// and its extension helps recognise the format (as for a file).
pub fn read_terrain_bytes(
    path: &Path,
    bytes: Vec<u8>,
    opts: &DemOptions,
) -> Result<LoadedDem, DemError> {
    let (bytes, named) = if bytes.starts_with(&GZIP_MAGIC) {
        // `x.asc.gz` is sniffed as `x.asc`.
        (gunzip(path, &bytes)?, path.with_extension(""))
    } else {
        (bytes, path.to_path_buf())
    };
    let format = sniff(&named, &bytes)?;
    let raw = match format {
        DemFormat::GeoTiff => geotiff::read(path, &bytes)?,
        DemFormat::EsriAscii => esri_ascii::read(path, &bytes)?,
    };
    drop(bytes);
    build(path, format, raw, *opts)
}

/// The first two bytes of a gzip stream (RFC 1952).
const GZIP_MAGIC: [u8; 2] = [0x1f, 0x8b];

/// Largest decompressed DEM, bytes: a 1 GiB grid is far beyond any map this planner flies,
/// and the limit keeps a crafted file from filling the memory.
const GUNZIP_LIMIT: u64 = 1 << 30;

/// The decompressed content of the gzip file `path`.
fn gunzip(path: &Path, bytes: &[u8]) -> Result<Vec<u8>, DemError> {
    use std::io::Read as _;
    let mut out = Vec::new();
    flate2::read::MultiGzDecoder::new(bytes)
        .take(GUNZIP_LIMIT + 1)
        .read_to_end(&mut out)
        .map_err(|e| DemError::Corrupt {
            path: path.into(),
            format: "gzip",
            detail: e.to_string(),
        })?;
    if out.len() as u64 > GUNZIP_LIMIT {
        return Err(DemError::Corrupt {
            path: path.into(),
            format: "gzip",
            detail: format!("decompresses to more than {GUNZIP_LIMIT} bytes"),
        });
    }
    Ok(out)
}

/// Recognises the format by magic bytes first, then by extension.
fn sniff(path: &Path, bytes: &[u8]) -> Result<DemFormat, DemError> {
    let magic = bytes.get(..4);
    if matches!(magic, Some(b"II*\0" | b"MM\0*" | b"II+\0" | b"MM\0+")) {
        return Ok(DemFormat::GeoTiff);
    }
    let text = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    let head = &text[..text.len().min(64)];
    let first_word: String = head
        .iter()
        .skip_while(|b| b.is_ascii_whitespace())
        .take_while(|b| b.is_ascii_alphabetic() || **b == b'_')
        .map(|b| char::from(b.to_ascii_lowercase()))
        .collect();
    if esri_ascii::KEYWORDS.contains(&first_word.as_str()) {
        return Ok(DemFormat::EsriAscii);
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "tif" | "tiff" | "gtif" | "gtiff" => Ok(DemFormat::GeoTiff),
        "asc" => Ok(DemFormat::EsriAscii),
        _ => Err(DemError::UnknownFormat {
            path: path.into(),
            ext,
        }),
    }
}

/// WGS 84 ground size in metres of a (dlon, dlat) degree cell at latitude `lat` degrees.
fn degree_cell_metres(cell: (f64, f64), lat: f64) -> (f64, f64) {
    const A: f64 = 6_378_137.0;
    const E2: f64 = 0.006_694_379_990_14;
    let phi = lat.clamp(-89.9, 89.9).to_radians();
    let w = 1.0 - E2 * phi.sin().powi(2);
    let n = A / w.sqrt(); // prime vertical radius of curvature
    let m = A * (1.0 - E2) / (w * w.sqrt()); // meridional radius of curvature
    (cell.0.to_radians() * n * phi.cos(), cell.1.to_radians() * m)
}

fn build(
    path: &Path,
    format: DemFormat,
    raw: RawRaster,
    options: DemOptions,
) -> Result<LoadedDem, DemError> {
    let RawRaster {
        columns,
        rows,
        mut values,
        nodata,
        sample_type,
        georef,
    } = raw;
    let nodata_filled = nodata::fill(&mut values, columns.max(1), nodata)
        .ok_or_else(|| DemError::AllNodata { path: path.into() })?;
    let cell_metres = match &georef {
        None => (1.0, 1.0),
        Some(g) if matches!(g.crs, Crs::Geographic(_)) => {
            let centre_lat = 0.5 * (g.upper_left_corner.1 + g.lower_left_corner.1);
            degree_cell_metres(g.cell, centre_lat)
        }
        Some(g) => (g.cell.0 * g.metres_per_unit, g.cell.1 * g.metres_per_unit),
    };
    let terrain = match options.frame {
        DemFrame::Georeferenced => {
            // Terrain row j (south-first) is file row rows - 1 - j.
            let flipped: Vec<f64> = values
                .chunks_exact(columns.max(1))
                .rev()
                .flatten()
                .copied()
                .collect();
            Terrain::new(
                columns,
                rows,
                (0.0, 0.0),
                cell_metres,
                flipped,
                options.sampling,
            )
        }
        DemFrame::SpsoPixels => Terrain::new(
            columns,
            rows,
            (1.0, 1.0),
            (1.0, 1.0),
            values,
            options.sampling,
        ),
    }
    .map_err(|source| DemError::Terrain {
        path: path.into(),
        source,
    })?;
    Ok(LoadedDem {
        terrain,
        path: path.into(),
        format,
        sample_type,
        options,
        columns,
        rows,
        georef,
        cell_metres,
        nodata,
        nodata_filled,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degree_cells_have_the_expected_ground_size() {
        // One arc-second at the equator: about 30.9 m both ways.
        let (dx, dy) = degree_cell_metres((1.0 / 3600.0, 1.0 / 3600.0), 0.0);
        assert!((dx - 30.92).abs() < 0.01, "{dx}");
        assert!((dy - 30.72).abs() < 0.01, "{dy}");
        let (dx60, _) = degree_cell_metres((1.0 / 3600.0, 1.0 / 3600.0), 60.0);
        assert!((dx60 / dx - 0.5).abs() < 0.01);
    }
}
