//! ESRI ASCII grid reader (`.asc`, also called Arc/Info ASCII grid or AAIGrid).
//!
//! The header is a list of `keyword value` lines, keywords case-insensitive and in any order:
//! `ncols`, `nrows`, `xllcorner` or `xllcenter`, `yllcorner` or `yllcenter`, `cellsize` (or
//! GDAL's `dx` and `dy`), optional `NODATA_value` (ESRI's default is -9999 when absent).
//! Then `nrows x ncols` numbers separated by any whitespace, rows north-first. Line breaks
//! need not fall at row ends (some writers wrap long rows), so values are counted, not lines.

use std::path::Path;

use super::{Crs, DemError, GeoReference, RawRaster, SampleType};

const FORMAT: &str = "ESRI ASCII grid";

/// Keywords recognised in the header, lower case.
pub(super) const KEYWORDS: [&str; 10] = [
    "ncols",
    "nrows",
    "xllcorner",
    "xllcenter",
    "yllcorner",
    "yllcenter",
    "cellsize",
    "dx",
    "dy",
    "nodata_value",
];

#[derive(Default)]
struct Header {
    values: [Option<(f64, usize)>; KEYWORDS.len()],
}

impl Header {
    fn get(&self, key: &str) -> Option<(f64, usize)> {
        KEYWORDS
            .iter()
            .position(|k| *k == key)
            .and_then(|i| self.values[i])
    }
}

/// The bad-header error of `path` at `line`.
fn bad_header(path: &Path, line: usize, detail: String) -> DemError {
    DemError::BadHeader {
        path: path.into(),
        line,
        detail,
    }
}

/// The grid a header describes: size, cell, lower-left corner of the outer edge, no-data.
struct Grid {
    columns: usize,
    rows: usize,
    cell: (f64, f64),
    xll: f64,
    yll: f64,
    nodata: Option<f64>,
}

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<RawRaster, DemError> {
    let text = std::str::from_utf8(bytes).map_err(|e| DemError::Corrupt {
        path: path.into(),
        format: FORMAT,
        detail: format!("not text (invalid UTF-8 at byte {})", e.valid_up_to()),
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = text.lines().enumerate().map(|(k, l)| (k + 1, l)).peekable();
    let header = read_header(path, &mut lines)?;
    let data_line = lines.peek().map_or(text.lines().count() + 1, |&(no, _)| no);
    let grid = grid_of(path, &header, data_line)?;
    let (columns, rows, cell, xll, yll) = (grid.columns, grid.rows, grid.cell, grid.xll, grid.yll);
    let values = read_values(path, lines, (columns, rows), data_line, bytes.len())?;
    let top = yll + rows as f64 * cell.1;
    Ok(RawRaster {
        columns,
        rows,
        values,
        nodata: grid.nodata,
        sample_type: SampleType::Text,
        georef: Some(GeoReference {
            upper_left_corner: (xll, top),
            lower_left_corner: (xll, yll),
            south_west_node: (xll + 0.5 * cell.0, yll + 0.5 * cell.1),
            cell,
            crs: Crs::Unknown { model_type: None },
            crs_inferred: false,
            citation: None,
            tie_point: None,
            pixel_is_point: false,
            metres_per_unit: 1.0,
        }),
    })
}

/// The header: lines whose first token is a keyword (blank lines are skipped), up to the
/// first data line, which is left in `lines`.
fn read_header<'a>(
    path: &Path,
    lines: &mut std::iter::Peekable<impl Iterator<Item = (usize, &'a str)>>,
) -> Result<Header, DemError> {
    let bad_header = |line: usize, detail: String| bad_header(path, line, detail);
    let mut header = Header::default();
    // Header: lines whose first token is a keyword (blank lines are skipped).
    while let Some(&(no, line)) = lines.peek() {
        let mut tokens = line.split_ascii_whitespace();
        let Some(first) = tokens.next() else {
            lines.next();
            continue;
        };
        let key = first.to_ascii_lowercase();
        let Some(slot) = KEYWORDS.iter().position(|k| *k == key) else {
            if first.parse::<f64>().is_ok() {
                break; // the first data line
            }
            return Err(bad_header(
                no,
                format!(
                    "unknown header field `{first}` (expected one of ncols, nrows, \
                     xllcorner, xllcenter, yllcorner, yllcenter, cellsize, dx, dy, \
                     NODATA_value)"
                ),
            ));
        };
        let value = tokens
            .next()
            .ok_or_else(|| bad_header(no, format!("header field `{first}` has no value")))?;
        let value: f64 = value
            .parse()
            .map_err(|_| bad_header(no, format!("`{first}` value `{value}` is not a number")))?;
        if let Some(extra) = tokens.next() {
            return Err(bad_header(
                no,
                format!("unexpected `{extra}` after the `{first}` value"),
            ));
        }
        if header.values[slot].is_some() {
            return Err(bad_header(
                no,
                format!("header field `{first}` given twice"),
            ));
        }
        header.values[slot] = Some((value, no));
        lines.next();
    }
    Ok(header)
}

/// The grid the header describes; a missing field is said at `data_line`.
fn grid_of(path: &Path, header: &Header, data_line: usize) -> Result<Grid, DemError> {
    let bad_header = |line: usize, detail: String| bad_header(path, line, detail);
    let missing = |field: &'static str| DemError::MissingField {
        path: path.into(),
        field,
        line: data_line,
    };

    let count = |key: &'static str| -> Result<usize, DemError> {
        let (v, no) = header.get(key).ok_or_else(|| missing(key))?;
        if v >= 1.0 && v.fract() == 0.0 && v <= 1e9 {
            Ok(v as usize)
        } else {
            Err(bad_header(
                no,
                format!("`{key}` must be a positive whole number, got {v}"),
            ))
        }
    };
    let columns = count("ncols")?;
    let rows = count("nrows")?;
    let positive = |key: &'static str, (v, no): (f64, usize)| {
        if v > 0.0 && v.is_finite() {
            Ok(v)
        } else {
            Err(bad_header(
                no,
                format!("`{key}` must be positive and finite, got {v}"),
            ))
        }
    };
    let cell = match (header.get("cellsize"), header.get("dx"), header.get("dy")) {
        (Some(c), None, None) => {
            let c = positive("cellsize", c)?;
            (c, c)
        }
        (None, Some(dx), Some(dy)) => (positive("dx", dx)?, positive("dy", dy)?),
        (Some(_), Some((_, no)), _) | (Some(_), _, Some((_, no))) => {
            return Err(bad_header(
                no,
                "give either `cellsize` or `dx` and `dy`, not both".into(),
            ))
        }
        (None, Some(_), None) => return Err(missing("dy")),
        (None, None, Some(_)) => return Err(missing("dx")),
        (None, None, None) => return Err(missing("cellsize")),
    };
    // Lower-left corner of the raster's outer edge.
    let corner = |corner_key: &'static str, center_key: &'static str, half: f64| match (
        header.get(corner_key),
        header.get(center_key),
    ) {
        (Some((v, no)), None) | (None, Some((v, no))) if !v.is_finite() => Err(bad_header(
            no,
            format!("`{corner_key}`/`{center_key}` must be finite, got {v}"),
        )),
        (Some((v, _)), None) => Ok(v),
        (None, Some((v, _))) => Ok(v - half),
        (Some(_), Some((_, no))) => Err(bad_header(
            no,
            format!("give either `{corner_key}` or `{center_key}`, not both"),
        )),
        (None, None) => Err(missing(corner_key)),
    };
    let xll = corner("xllcorner", "xllcenter", 0.5 * cell.0)?;
    let yll = corner("yllcorner", "yllcenter", 0.5 * cell.1)?;
    let nodata = Some(header.get("nodata_value").map_or(-9999.0, |(v, _)| v));
    Ok(Grid {
        columns,
        rows,
        cell,
        xll,
        yll,
        nodata,
    })
}

/// The `columns x rows` values after the header, row by row; a file of `file_bytes` bytes
/// reserves no more than it could hold (a corrupt header must not allocate GBs).
fn read_values<'a>(
    path: &Path,
    lines: impl Iterator<Item = (usize, &'a str)>,
    (columns, rows): (usize, usize),
    data_line: usize,
    file_bytes: usize,
) -> Result<Vec<f64>, DemError> {
    let expected = columns
        .checked_mul(rows)
        .filter(|n| *n <= 2_000_000_000)
        .ok_or_else(|| {
            bad_header(
                path,
                data_line,
                format!("{columns} x {rows} cells is too many"),
            )
        })?;
    let mut values = Vec::with_capacity(expected.min(file_bytes / 2 + 1));
    let mut found = 0usize;
    for (no, line) in lines {
        for token in line.split_ascii_whitespace() {
            found += 1;
            if found > expected {
                continue; // keep counting to report the total
            }
            let v: f64 = token.parse().map_err(|_| DemError::BadValue {
                path: path.into(),
                line: no,
                token: token.into(),
            })?;
            values.push(v);
        }
    }
    if found != expected {
        return Err(DemError::WrongValueCount {
            path: path.into(),
            columns,
            rows,
            expected,
            found,
        });
    }
    Ok(values)
}
