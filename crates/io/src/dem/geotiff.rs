//! GeoTIFF reader: one band of integer or float samples (strips or tiles, any compression
//! the `tiff` crate decodes), plus the georeferencing tags a DEM needs.
//!
//! Tags read (GeoTIFF 1.0 / OGC 19-008r4):
//! - ModelPixelScaleTag (33550) and ModelTiepointTag (33922), or a non-rotated
//!   ModelTransformationTag (34264): cell size and where the raster sits;
//! - GeoKeyDirectoryTag (34735): GTModelTypeGeoKey (1024), GTRasterTypeGeoKey (1025:
//!   PixelIsArea / PixelIsPoint), GeographicTypeGeoKey (2048), ProjectedCSTypeGeoKey (3072),
//!   ProjLinearUnitsGeoKey (3076); when ProjectedCSTypeGeoKey is user-defined, a UTM
//!   ProjectionGeoKey (3074) with a known datum (GeogGeodeticDatumGeoKey 2050) still yields
//!   the EPSG code (SPSO's DEM is written that way: MGA zone 48 = EPSG 28348); the citation
//!   (GTCitationGeoKey 1026 or PCSCitationGeoKey 3073, in GeoAsciiParamsTag 34737) is kept;
//! - GDAL_NODATA (42113), an ASCII number.
//!
//! Only the first image (IFD) is read: later ones are overviews or masks in DEM files.

use std::io::Cursor;
use std::path::Path;

use tiff::decoder::{ifd::Value, Decoder, DecodingResult, Limits};
use tiff::tags::Tag;
use tiff::TiffError;

use super::{Crs, DemError, GeoReference, RawRaster, SampleType, TiePoint};

/// Largest decoded image accepted (bytes of samples): 8 GiB, far above any DEM we plan on.
const MAX_IMAGE_BYTES: usize = 8 << 30;
/// Most bytes of samples one byte of file may decode to. LZW, the most expansive codec the
/// crate reads, stays below 4096:1 (a 12-bit code stands for at most 4096 bytes), so a
/// header asking for more is corrupt; the bound keeps a corrupt size field from making the
/// decoder allocate gigabytes for a small file.
const MAX_EXPANSION: usize = 4096;

const FORMAT: &str = "TIFF";

/// `ModelTransformationTag` and `GeoAsciiParamsTag`, absent from `tiff::tags::Tag`.
const MODEL_TRANSFORMATION: u16 = 34264;
const GEO_ASCII_PARAMS: u16 = 34737;

// GeoKey ids.
const GT_MODEL_TYPE: u16 = 1024;
const GT_RASTER_TYPE: u16 = 1025;
const GT_CITATION: u16 = 1026;
const GEOGRAPHIC_TYPE: u16 = 2048;
const GEODETIC_DATUM: u16 = 2050;
const PROJECTED_CS_TYPE: u16 = 3072;
const PCS_CITATION: u16 = 3073;
const PROJECTION: u16 = 3074;
const PROJ_LINEAR_UNITS: u16 = 3076;
/// GeoKey value meaning "user-defined" (no EPSG code).
const USER_DEFINED: u16 = 32767;

pub(super) fn read(path: &Path, bytes: &[u8]) -> Result<RawRaster, DemError> {
    if let Some(why) = unusable_indexed_tag(bytes) {
        return Err(DemError::Corrupt {
            path: path.into(),
            format: FORMAT,
            detail: why,
        });
    }
    // Last line of defence: a panic inside the TIFF decoder on a crafted file is a corrupt
    // file, not a crash of the planner (the known one is screened above).
    std::panic::catch_unwind(|| read_checked(path, bytes)).unwrap_or_else(|_| {
        Err(DemError::Corrupt {
            path: path.into(),
            format: FORMAT,
            detail: "the TIFF decoder failed on this file".into(),
        })
    })
}

/// Tags the `tiff` 0.10 decoder indexes at `[0]` without checking for an empty list: a
/// count of 0 panics there, and so does a value of a non-integer type, which the decoder
/// reads as an empty list (both found by the `geotiff` fuzz target).
const INDEXED_TAGS: [(u16, &str); 1] = [(339, "SampleFormat")];

/// TIFF field types of unsigned integers: BYTE, SHORT, LONG, LONG8.
const UNSIGNED_TYPES: [u64; 4] = [1, 3, 4, 16];

/// Why the first tag of [`INDEXED_TAGS`] in the first IFD of a classic or BigTIFF file
/// cannot be read (no value, or not an unsigned integer); `None` when all can, or the header
/// cannot be read (the decoder then reports the problem itself).
fn unusable_indexed_tag(b: &[u8]) -> Option<String> {
    let little = match b.get(..2)? {
        b"II" => true,
        b"MM" => false,
        _ => return None,
    };
    let int = |at: usize, len: usize| -> Option<u64> {
        let raw = b.get(at..at.checked_add(len)?)?;
        let mut v = 0_u64;
        for k in 0..len {
            let byte = u64::from(raw[if little { len - 1 - k } else { k }]);
            v = (v << 8) | byte;
        }
        Some(v)
    };
    let big = int(2, 2)? == 43;
    let (ifd, count_len, entry_len, n_len) = if big {
        (int(8, 8)?, 8, 20, 8)
    } else {
        (int(4, 4)?, 2, 12, 4)
    };
    let ifd = usize::try_from(ifd).ok()?;
    let entries = usize::try_from(int(ifd, count_len)?).ok()?;
    for e in 0..entries.min(4096) {
        // Offsets come from the file: checked, so a huge one ends the scan instead of
        // overflowing.
        let at = ifd.checked_add(count_len)?.checked_add(e * entry_len)?;
        let tag = u16::try_from(int(at, 2)?).ok()?;
        let kind = int(at.checked_add(2)?, 2)?;
        let count = int(at.checked_add(4)?, n_len)?;
        if let Some((_, name)) = INDEXED_TAGS.iter().find(|(t, _)| *t == tag) {
            if count == 0 {
                return Some(format!("tag {name} has no value"));
            }
            if !UNSIGNED_TYPES.contains(&kind) {
                return Some(format!(
                    "tag {name} is of TIFF type {kind}, expected an unsigned integer type (1, 3, 4 or 16)"
                ));
            }
        }
    }
    None
}

fn read_checked(path: &Path, bytes: &[u8]) -> Result<RawRaster, DemError> {
    let err = |e: TiffError| tiff_error(path, e);
    let mut limits = Limits::default();
    limits.decoding_buffer_size = bytes
        .len()
        .saturating_mul(MAX_EXPANSION)
        .clamp(1 << 20, MAX_IMAGE_BYTES);
    // Tag values are stored in the file, so none can be larger than it.
    limits.ifd_value_size = bytes.len().max(1024);
    limits.intermediate_buffer_size = limits.decoding_buffer_size;
    let mut dec = Decoder::new(Cursor::new(bytes))
        .map_err(err)?
        .with_limits(limits);
    let (w, h) = dec.dimensions().map_err(err)?;
    let (columns, rows) = (w as usize, h as usize);

    let bands = dec
        .find_tag_unsigned::<u16>(Tag::SamplesPerPixel)
        .map_err(err)?
        .unwrap_or(1);
    if bands != 1 {
        return Err(DemError::TooManyBands {
            path: path.into(),
            bands,
        });
    }
    match dec
        .find_tag_unsigned::<u16>(Tag::PhotometricInterpretation)
        .map_err(err)?
    {
        // The decoder inverts WhiteIsZero samples, which would turn hills into valleys.
        Some(0) => {
            return Err(DemError::Unsupported {
                path: path.into(),
                what: "photometric interpretation WhiteIsZero (values would be inverted)".into(),
            })
        }
        Some(3) => {
            return Err(DemError::UnsupportedSampleType {
                path: path.into(),
                what: "palette-colour image".into(),
            })
        }
        _ => {}
    }
    let bits = first_or(&mut dec, Tag::BitsPerSample, 1).map_err(err)?;
    let format = first_or(&mut dec, Tag::SampleFormat, 1).map_err(err)?;
    let supported = match format {
        1 | 2 => matches!(bits, 8 | 16 | 32 | 64),
        3 => matches!(bits, 16 | 32 | 64),
        _ => false,
    };
    if !supported {
        let kind = match format {
            1 => "unsigned integer",
            2 => "signed integer",
            3 => "float",
            4 => "void (undefined)",
            5 => "complex integer",
            6 => "complex float",
            _ => "unknown sample format",
        };
        return Err(DemError::UnsupportedSampleType {
            path: path.into(),
            what: format!("{bits}-bit {kind}"),
        });
    }

    let (sample_type, values) = match dec.read_image().map_err(err)? {
        DecodingResult::U8(v) => (SampleType::U8, to_f64(v)),
        DecodingResult::I8(v) => (SampleType::I8, to_f64(v)),
        DecodingResult::U16(v) => (SampleType::U16, to_f64(v)),
        DecodingResult::I16(v) => (SampleType::I16, to_f64(v)),
        DecodingResult::U32(v) => (SampleType::U32, to_f64(v)),
        DecodingResult::I32(v) => (SampleType::I32, to_f64(v)),
        // Heights beyond 2^53 are not terrain; the rounding is irrelevant.
        DecodingResult::U64(v) => (SampleType::U64, v.into_iter().map(|x| x as f64).collect()),
        DecodingResult::I64(v) => (SampleType::I64, v.into_iter().map(|x| x as f64).collect()),
        DecodingResult::F16(v) => (SampleType::F16, v.into_iter().map(|x| x.to_f64()).collect()),
        DecodingResult::F32(v) => (SampleType::F32, to_f64(v)),
        DecodingResult::F64(v) => (SampleType::F64, v),
    };
    if values.len() != columns * rows {
        return Err(DemError::Corrupt {
            path: path.into(),
            format: FORMAT,
            detail: format!(
                "decoded {} samples for a {columns} x {rows} raster",
                values.len()
            ),
        });
    }

    let nodata = match dec.find_tag(Tag::GdalNodata).map_err(err)? {
        Some(v) => Some(parse_nodata(path, v)?),
        None => None,
    };
    let georef = read_georef(path, &mut dec, rows)?;
    Ok(RawRaster {
        columns,
        rows,
        values,
        nodata,
        sample_type,
        georef,
    })
}

fn to_f64<T: Into<f64>>(v: Vec<T>) -> Vec<f64> {
    v.into_iter().map(Into::into).collect()
}

/// First value of an unsigned tag that may be a list (BitsPerSample, SampleFormat).
fn first_or(dec: &mut Decoder<Cursor<&[u8]>>, tag: Tag, default: u16) -> Result<u16, TiffError> {
    Ok(dec
        .find_tag_unsigned_vec::<u16>(tag)?
        .and_then(|v| v.first().copied())
        .unwrap_or(default))
}

fn parse_nodata(path: &Path, v: Value) -> Result<f64, DemError> {
    let bad = |detail: String| DemError::BadGeoreference {
        path: path.into(),
        detail,
    };
    let text = match v {
        Value::Ascii(s) => s,
        other => return Err(bad(format!("GDAL_NODATA is not text: {other:?}"))),
    };
    let t = text.trim_matches(|c: char| c == '\0' || c.is_whitespace());
    t.parse::<f64>()
        .map_err(|_| bad(format!("GDAL_NODATA `{t}` is not a number")))
}

fn f64_list(
    path: &Path,
    dec: &mut Decoder<Cursor<&[u8]>>,
    tag: Tag,
    name: &str,
) -> Result<Option<Vec<f64>>, DemError> {
    match dec.find_tag(tag).map_err(|e| tiff_error(path, e))? {
        None => Ok(None),
        Some(v) => v
            .into_f64_vec()
            .map(Some)
            .map_err(|_| DemError::BadGeoreference {
                path: path.into(),
                detail: format!("{name} is not a list of doubles"),
            }),
    }
}

/// The GeoKey directory: keys with a SHORT value stored in the directory itself, and the
/// citation (GTCitationGeoKey, else PCSCitationGeoKey) from GeoAsciiParamsTag.
struct GeoKeys {
    shorts: Vec<(u16, u16)>,
    citation: Option<String>,
}

impl GeoKeys {
    fn get(&self, id: u16) -> Option<u16> {
        self.shorts.iter().find(|k| k.0 == id).map(|k| k.1)
    }
}

fn geo_keys(path: &Path, dec: &mut Decoder<Cursor<&[u8]>>) -> Result<GeoKeys, DemError> {
    let dir = dec
        .find_tag_unsigned_vec::<u16>(Tag::GeoKeyDirectoryTag)
        .map_err(|e| tiff_error(path, e))?;
    let Some(dir) = dir else {
        return Ok(GeoKeys {
            shorts: Vec::new(),
            citation: None,
        });
    };
    if dir.len() < 4 {
        return Err(DemError::BadGeoreference {
            path: path.into(),
            detail: format!(
                "GeoKeyDirectoryTag holds {} values, fewer than 4",
                dir.len()
            ),
        });
    }
    let entries: Vec<&[u16]> = dir[4..].chunks_exact(4).take(usize::from(dir[3])).collect();
    let shorts = entries
        .iter()
        .filter(|k| k[1] == 0 && k[2] == 1)
        .map(|k| (k[0], k[3]))
        .collect();
    // The citation is a convenience: an unreadable one is dropped, not an error.
    let ascii = dec
        .find_tag(Tag::Unknown(GEO_ASCII_PARAMS))
        .ok()
        .flatten()
        .and_then(|v| v.into_string().ok());
    let citation = ascii.and_then(|text| {
        [GT_CITATION, PCS_CITATION].iter().find_map(|id| {
            let k = entries
                .iter()
                .find(|k| k[0] == *id && k[1] == GEO_ASCII_PARAMS)?;
            let start = usize::from(k[3]);
            let piece = text.get(start..start + usize::from(k[2]))?;
            let piece = piece.trim_matches(|c: char| c == '|' || c == '\0' || c.is_whitespace());
            (!piece.is_empty()).then(|| piece.to_string())
        })
    });
    Ok(GeoKeys { shorts, citation })
}

/// EPSG code of a UTM-based projected CRS described by parts: a user-defined
/// ProjectedCSTypeGeoKey with ProjectionGeoKey = EPSG "UTM zone nN" (16000 + n) or "UTM zone
/// nS" (16100 + n) and a known datum. Covers the common UTM families only; anything else
/// stays without a code rather than guessing.
fn utm_epsg(projection: u16, datum: u16) -> Option<u16> {
    let (zone, south) = match projection {
        16001..=16060 => (projection - 16000, false),
        16101..=16160 => (projection - 16100, true),
        _ => return None,
    };
    match (datum, south) {
        (6326, false) => Some(32600 + zone), // WGS 84 / UTM zone nN
        (6326, true) => Some(32700 + zone),  // WGS 84 / UTM zone nS
        (6283, true) if (48..=58).contains(&zone) => Some(28300 + zone), // GDA94 / MGA zone n
        (1168, true) if (46..=59).contains(&zone) => Some(7800 + zone), // GDA2020 / MGA zone n
        (6269, false) if (1..=23).contains(&zone) => Some(26900 + zone), // NAD83 / UTM zone nN
        (6258, false) if (28..=38).contains(&zone) => Some(25800 + zone), // ETRS89 / UTM zone nN
        _ => None,
    }
}

/// Datum code of a geographic CRS code, for the datums [`utm_epsg`] knows.
fn datum_of(geographic: u16) -> Option<u16> {
    match geographic {
        4326 => Some(6326),
        4283 => Some(6283),
        7844 => Some(1168),
        4269 => Some(6269),
        4258 => Some(6258),
        _ => None,
    }
}

fn read_georef(
    path: &Path,
    dec: &mut Decoder<Cursor<&[u8]>>,
    rows: usize,
) -> Result<Option<GeoReference>, DemError> {
    let bad = |detail: String| DemError::BadGeoreference {
        path: path.into(),
        detail,
    };
    let scale = f64_list(path, dec, Tag::ModelPixelScaleTag, "ModelPixelScaleTag")?;
    let ties = f64_list(path, dec, Tag::ModelTiepointTag, "ModelTiepointTag")?;
    let transform = f64_list(
        path,
        dec,
        Tag::Unknown(MODEL_TRANSFORMATION),
        "ModelTransformationTag",
    )?;
    let keys = geo_keys(path, dec)?;
    let key = |id: u16| keys.get(id);

    // Raster-space (0, 0) -> model (x0, y0), with cell (sx, sy) and y decreasing downwards.
    let (x0, y0, sx, sy, tie_point) = match (scale, ties, transform) {
        (Some(s), Some(t), _) => {
            if s.len() < 2 {
                return Err(bad(format!(
                    "ModelPixelScaleTag holds {} values, expected 3",
                    s.len()
                )));
            }
            if t.len() < 6 {
                return Err(bad(format!(
                    "ModelTiepointTag holds {} values, expected a multiple of 6",
                    t.len()
                )));
            }
            let tp = TiePoint {
                raster: [t[0], t[1], t[2]],
                model: [t[3], t[4], t[5]],
            };
            let x0 = t[3] - t[0] * s[0];
            let y0 = t[4] + t[1] * s[1];
            (x0, y0, s[0], s[1], Some(tp))
        }
        (_, _, Some(m)) => {
            if m.len() < 16 {
                return Err(bad(format!(
                    "ModelTransformationTag holds {} values, expected 16",
                    m.len()
                )));
            }
            if m[1] != 0.0 || m[4] != 0.0 {
                return Err(DemError::Unsupported {
                    path: path.into(),
                    what: "rotated or sheared raster (ModelTransformationTag)".into(),
                });
            }
            (m[3], m[7], m[0], -m[5], None)
        }
        (Some(_), None, None) => {
            return Err(bad("ModelPixelScaleTag without ModelTiepointTag".into()));
        }
        _ => return Ok(None),
    };
    let finite = [x0, y0, sx, sy].iter().all(|v| v.is_finite());
    if !(finite && sx > 0.0 && sy > 0.0) {
        return Err(bad(format!(
            "cell size ({sx}, {sy}) and origin ({x0}, {y0}) must be finite with a positive \
             cell size (north-up raster)"
        )));
    }
    let pixel_is_point = key(GT_RASTER_TYPE) == Some(2);
    // PixelIsPoint ties raster (0, 0) to the first pixel's centre, PixelIsArea to its corner.
    let (ulx, uly) = if pixel_is_point {
        (x0 - 0.5 * sx, y0 + 0.5 * sy)
    } else {
        (x0, y0)
    };
    let model_type = key(GT_MODEL_TYPE);
    let known = |code: Option<u16>| code.filter(|c| *c != USER_DEFINED && *c != 0);
    let datum =
        known(key(GEODETIC_DATUM)).or_else(|| known(key(GEOGRAPHIC_TYPE)).and_then(datum_of));
    let inferred = known(key(PROJECTION))
        .zip(datum)
        .and_then(|(p, d)| utm_epsg(p, d));
    let projected = known(key(PROJECTED_CS_TYPE));
    let geographic = known(key(GEOGRAPHIC_TYPE));
    let (crs, crs_inferred) = match (projected, inferred, geographic) {
        (Some(code), _, _) => (Crs::Projected(code), false),
        (None, Some(code), _) if model_type != Some(2) => (Crs::Projected(code), true),
        (None, _, Some(code)) if model_type != Some(1) => (Crs::Geographic(code), false),
        _ if model_type == Some(2) => (Crs::Geographic(0), false),
        _ => (Crs::Unknown { model_type }, false),
    };
    let metres_per_unit = match key(PROJ_LINEAR_UNITS) {
        Some(9002) => 0.3048,
        Some(9003) => 1200.0 / 3937.0,
        _ => 1.0,
    };
    Ok(Some(GeoReference {
        upper_left_corner: (ulx, uly),
        lower_left_corner: (ulx, uly - rows as f64 * sy),
        south_west_node: (ulx + 0.5 * sx, uly - (rows as f64 - 0.5) * sy),
        cell: (sx, sy),
        crs,
        crs_inferred,
        citation: keys.citation,
        tie_point,
        pixel_is_point,
        metres_per_unit,
    }))
}

fn tiff_error(path: &Path, e: TiffError) -> DemError {
    match e {
        TiffError::IoError(io) if io.kind() == std::io::ErrorKind::UnexpectedEof => {
            DemError::Truncated {
                path: path.into(),
                detail: io.to_string(),
            }
        }
        TiffError::UnsupportedError(u) => DemError::Unsupported {
            path: path.into(),
            what: u.to_string(),
        },
        TiffError::LimitsExceeded => DemError::Corrupt {
            path: path.into(),
            format: FORMAT,
            detail: format!(
                "a size field asks for more data than the file can hold \
                 (or more than the reader's {} GiB limit)",
                MAX_IMAGE_BYTES >> 30
            ),
        },
        other => DemError::Corrupt {
            path: path.into(),
            format: FORMAT,
            detail: other.to_string(),
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tag_screen_survives_offsets_at_the_end_of_the_address_space() {
        // BigTIFF header whose first IFD sits at u64::MAX.
        let mut b = b"II+\0\x08\0\0\0".to_vec();
        b.extend_from_slice(&u64::MAX.to_le_bytes());
        assert_eq!(unusable_indexed_tag(&b), None);
        let mut c = b"MM\0*".to_vec();
        c.extend_from_slice(&u32::MAX.to_be_bytes());
        assert_eq!(unusable_indexed_tag(&c), None);
    }

    #[test]
    fn utm_codes_from_projection_and_datum() {
        assert_eq!(utm_epsg(16148, 6283), Some(28348)); // GDA94 / MGA zone 48 (SPSO)
        assert_eq!(utm_epsg(16148, 6326), Some(32748)); // WGS 84 / UTM zone 48S
        assert_eq!(utm_epsg(16032, 6326), Some(32632)); // WGS 84 / UTM zone 32N
        assert_eq!(utm_epsg(16156, 1168), Some(7856)); // GDA2020 / MGA zone 56
        assert_eq!(utm_epsg(16018, 6269), Some(26918)); // NAD83 / UTM zone 18N
        assert_eq!(utm_epsg(16032, 6258), Some(25832)); // ETRS89 / UTM zone 32N
        assert_eq!(utm_epsg(16048, 6283), None); // GDA94 is southern only
        assert_eq!(utm_epsg(16148, 6999), None); // unknown datum
        assert_eq!(utm_epsg(9807, 6326), None); // not a UTM zone
        assert_eq!(datum_of(4326), Some(6326));
    }
}
