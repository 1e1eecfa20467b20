//! Errors of the DEM readers. Every message starts with the file's path and says what is
//! wrong with it, so a user can act on it without a debugger.

use std::path::PathBuf;

use swarmplan_core::world::terrain::TerrainError;
use thiserror::Error;

/// Why a DEM file could not be turned into a [`Terrain`](swarmplan_core::world::Terrain).
#[derive(Debug, Error)]
pub enum DemError {
    #[error("{}: cannot read the file: {source}", .path.display())]
    Io {
        path: PathBuf,
        source: std::io::Error,
    },
    #[error(
        "{}: unknown terrain file type (extension {ext:?}, content not recognised); \
         expected a GeoTIFF (.tif, .tiff) or an ESRI ASCII grid (.asc)",
        .path.display()
    )]
    UnknownFormat { path: PathBuf, ext: String },
    #[error("{}: the file ends early (truncated?): {detail}", .path.display())]
    Truncated { path: PathBuf, detail: String },
    #[error("{}: not a valid {format} file: {detail}", .path.display())]
    Corrupt {
        path: PathBuf,
        format: &'static str,
        detail: String,
    },
    #[error(
        "{}: unsupported sample type: {what} (supported: one band of 8-, 16-, 32- or 64-bit \
         integers or 16-, 32- or 64-bit floats)",
        .path.display()
    )]
    UnsupportedSampleType { path: PathBuf, what: String },
    #[error("{}: the raster has {bands} bands; a DEM must have exactly one", .path.display())]
    TooManyBands { path: PathBuf, bands: u16 },
    #[error("{}: unsupported TIFF feature: {what}", .path.display())]
    Unsupported { path: PathBuf, what: String },
    #[error("{}: bad georeferencing: {detail}", .path.display())]
    BadGeoreference { path: PathBuf, detail: String },
    #[error(
        "{}: line {line}: missing header field `{field}` (the header ended here without it)",
        .path.display()
    )]
    MissingField {
        path: PathBuf,
        field: &'static str,
        line: usize,
    },
    #[error("{}: line {line}: {detail}", .path.display())]
    BadHeader {
        path: PathBuf,
        line: usize,
        detail: String,
    },
    #[error("{}: line {line}: `{token}` is not a number", .path.display())]
    BadValue {
        path: PathBuf,
        line: usize,
        token: String,
    },
    #[error(
        "{}: wrong number of values: the header says {columns} x {rows} = {expected}, \
         the file holds {found}",
        .path.display()
    )]
    WrongValueCount {
        path: PathBuf,
        columns: usize,
        rows: usize,
        expected: usize,
        found: usize,
    },
    #[error("{}: every cell is nodata; there is no terrain to fill from", .path.display())]
    AllNodata { path: PathBuf },
    #[error("{}: {source}", .path.display())]
    Terrain { path: PathBuf, source: TerrainError },
}
