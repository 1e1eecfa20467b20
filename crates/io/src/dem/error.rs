//! Errors of the DEM readers. Every message starts with the file's path and says what is
//! wrong with it, so a user can act on it without a debugger.

use std::path::PathBuf;

use swarmplan_core::world::terrain::TerrainError;
use thiserror::Error;

/// Why a DEM file could not be turned into a [`Terrain`](swarmplan_core::world::Terrain).
#[derive(Debug, Error)]
pub enum DemError {
    /// The file could not be read.
    #[error("{}: cannot read the file: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// Neither the first bytes nor the extension name a supported format.
    #[error(
        "{}: unknown terrain file type (extension {ext:?}, content not recognised); \
         expected a GeoTIFF (.tif, .tiff) or an ESRI ASCII grid (.asc)",
        .path.display()
    )]
    UnknownFormat {
        /// The file.
        path: PathBuf,
        /// Its extension, lower-cased (empty if none).
        ext: String,
    },
    /// A TIFF ends before the data its structure points to.
    #[error("{}: the file ends early (truncated?): {detail}", .path.display())]
    Truncated {
        /// The file.
        path: PathBuf,
        /// What the decoder said.
        detail: String,
    },
    /// The file does not follow its format: bad TIFF structure, text that is not UTF-8, or a
    /// gzip stream that fails or decompresses too large.
    #[error("{}: not a valid {format} file: {detail}", .path.display())]
    Corrupt {
        /// The file.
        path: PathBuf,
        /// The format it was read as ("TIFF", "ESRI ASCII grid", "gzip").
        format: &'static str,
        /// What is wrong.
        detail: String,
    },
    /// A GeoTIFF's samples are of a kind no DEM is read from (e.g. palette colours, 1-bit).
    #[error(
        "{}: unsupported sample type: {what} (supported: one band of 8-, 16-, 32- or 64-bit \
         integers or 16-, 32- or 64-bit floats)",
        .path.display()
    )]
    UnsupportedSampleType {
        /// The file.
        path: PathBuf,
        /// The sample type found.
        what: String,
    },
    /// A GeoTIFF has more than one band.
    #[error("{}: the raster has {bands} bands; a DEM must have exactly one", .path.display())]
    TooManyBands {
        /// The file.
        path: PathBuf,
        /// Number of bands (samples per pixel).
        bands: u16,
    },
    /// A GeoTIFF uses a feature the reader does not handle (e.g. a rotated raster).
    #[error("{}: unsupported TIFF feature: {what}", .path.display())]
    Unsupported {
        /// The file.
        path: PathBuf,
        /// The feature.
        what: String,
    },
    /// A GeoTIFF's georeferencing tags or keys are malformed or inconsistent.
    #[error("{}: bad georeferencing: {detail}", .path.display())]
    BadGeoreference {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        detail: String,
    },
    /// An ESRI ASCII grid's header lacks a required field.
    #[error(
        "{}: line {line}: missing header field `{field}` (the header ended here without it)",
        .path.display()
    )]
    MissingField {
        /// The file.
        path: PathBuf,
        /// The missing field.
        field: &'static str,
        /// Line where the header ended (1-based).
        line: usize,
    },
    /// An ESRI ASCII grid's header line is malformed or holds a bad value.
    #[error("{}: line {line}: {detail}", .path.display())]
    BadHeader {
        /// The file.
        path: PathBuf,
        /// The line (1-based).
        line: usize,
        /// What is wrong.
        detail: String,
    },
    /// An ESRI ASCII grid's data holds a token that is not a number.
    #[error("{}: line {line}: `{token}` is not a number", .path.display())]
    BadValue {
        /// The file.
        path: PathBuf,
        /// The line (1-based).
        line: usize,
        /// The token.
        token: String,
    },
    /// An ESRI ASCII grid holds more or fewer values than its header's columns x rows.
    #[error(
        "{}: wrong number of values: the header says {columns} x {rows} = {expected}, \
         the file holds {found}",
        .path.display()
    )]
    WrongValueCount {
        /// The file.
        path: PathBuf,
        /// Columns in the header.
        columns: usize,
        /// Rows in the header.
        rows: usize,
        /// Values expected: columns x rows.
        expected: usize,
        /// Values found.
        found: usize,
    },
    /// No cell has a valid height.
    #[error("{}: every cell is nodata; there is no terrain to fill from", .path.display())]
    AllNodata {
        /// The file.
        path: PathBuf,
    },
    /// The heights read do not make a valid terrain grid (e.g. fewer than 2 x 2 nodes).
    #[error("{}: {source}", .path.display())]
    Terrain {
        /// The file.
        path: PathBuf,
        /// Why the terrain was refused.
        source: TerrainError,
    },
}
