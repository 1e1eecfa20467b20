//! DEM readers against files written here (tiff encoder, a hand-made tiled TIFF, ASCII grids)
//! and, when the shared data folder is present, against SPSO's reference terrain.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use swarmplan_core::world::terrain::Sampling;
use swarmplan_io::dem::{
    read_terrain, Crs, DemError, DemFormat, DemFrame, DemOptions, LoadedDem, SampleType,
};
use swarmplan_io::reference_data::reference_file;
use tiff::encoder::colortype::{self, ColorType};
use tiff::encoder::{Compression, DeflateLevel, TiffEncoder, TiffValue};
use tiff::tags::Tag;

/// A fresh directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(label: &str) -> Self {
        static COUNTER: AtomicUsize = AtomicUsize::new(0);
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos());
        let dir = std::env::temp_dir().join(format!(
            "swarmplan-dem-{label}-{}-{}-{nanos}",
            std::process::id(),
            COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        std::fs::create_dir_all(&dir).expect("create temp dir");
        Self(dir)
    }
    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Georeferencing written into test GeoTIFFs.
struct Geo {
    scale: (f64, f64),
    tie: (f64, f64),
    /// (key id, value) pairs of the GeoKeyDirectory.
    keys: Vec<(u16, u16)>,
    nodata: Option<&'static str>,
}

fn mga48(scale: (f64, f64), tie: (f64, f64)) -> Geo {
    Geo {
        scale,
        tie,
        // Projected model, PixelIsArea, GDA94 / MGA zone 48.
        keys: vec![(1024, 1), (1025, 1), (3072, 28348)],
        nodata: None,
    }
}

fn write_tiff<C: ColorType>(
    path: &Path,
    w: u32,
    h: u32,
    data: &[C::Inner],
    geo: Option<&Geo>,
    compression: Compression,
) where
    [C::Inner]: TiffValue,
{
    let file = std::fs::File::create(path).expect("create tiff");
    let mut enc = TiffEncoder::new(std::io::BufWriter::new(file))
        .expect("encoder")
        .with_compression(compression);
    let mut img = enc.new_image::<C>(w, h).expect("image");
    if let Some(g) = geo {
        let dir = img.encoder();
        dir.write_tag(Tag::ModelPixelScaleTag, &[g.scale.0, g.scale.1, 0.0][..])
            .expect("scale");
        dir.write_tag(
            Tag::ModelTiepointTag,
            &[0.0, 0.0, 0.0, g.tie.0, g.tie.1, 0.0][..],
        )
        .expect("tie");
        let mut keys = vec![1u16, 1, 0, g.keys.len() as u16];
        for &(id, v) in &g.keys {
            keys.extend([id, 0, 1, v]);
        }
        dir.write_tag(Tag::GeoKeyDirectoryTag, &keys[..])
            .expect("geokeys");
        if let Some(nd) = g.nodata {
            dir.write_tag(Tag::GdalNodata, nd).expect("nodata");
        }
    }
    img.write_data(data).expect("data");
}

/// File-order test raster: value = 10 * row + column (row 0 = north).
fn grid_values(w: u32, h: u32) -> Vec<f32> {
    (0..h)
        .flat_map(|r| (0..w).map(move |c| (10 * r + c) as f32))
        .collect()
}

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

// ---------------------------------------------------------------- SPSO reference terrain

#[test]
fn spso_reference_terrain() {
    let Some(path) = reference_file("spso/ChrismasTerrain.tif").unwrap() else {
        return;
    };
    let t0 = Instant::now();
    let dem = read_terrain(&path, &DemOptions::SPSO).expect("SPSO DEM reads");
    println!(
        "read {} in {:.1} ms",
        path.display(),
        t0.elapsed().as_secs_f64() * 1e3
    );
    let t = &dem.terrain;
    assert_eq!((dem.columns, dem.rows), (1045, 879));
    assert_eq!(t.size(), (1045, 879));
    assert_eq!(dem.format, DemFormat::GeoTiff);
    assert_eq!(dem.sample_type, SampleType::F32);
    assert_eq!(dem.nodata_filled, 0);
    assert!(close(t.min_height(), 48.92, 0.01), "{}", t.min_height());
    assert!(close(t.max_height(), 296.04, 0.01), "{}", t.max_height());
    // SPSO's H(round(y), round(x)) at its start and end points (README of the data).
    assert!(
        close(t.height(200.0, 100.0), 216.93, 0.01),
        "{}",
        t.height(200.0, 100.0)
    );
    assert!(
        close(t.height(800.0, 800.0), 166.53, 0.01),
        "{}",
        t.height(800.0, 800.0)
    );
    // MATLAB rounding: 199.5 -> 200.
    assert_eq!(t.height(199.5, 99.5), t.height(200.0, 100.0));
    let mean = t.heights().iter().sum::<f64>() / t.heights().len() as f64;
    assert!(close(mean, 198.575, 0.01), "{mean}");

    let geo = read_terrain(&path, &DemOptions::default()).expect("georeferenced");
    assert_eq!(geo.file_cell_size(), Some((5.0, 5.0)));
    assert_eq!(geo.cell_metres, (5.0, 5.0));
    let g = geo.georef.clone().expect("GeoTIFF tags");
    // ProjectedCSTypeGeoKey is user-defined in this file; ProjectionGeoKey (UTM zone 48S)
    // and the GDA94 datum give GDA94 / MGA zone 48.
    assert_eq!(g.crs, Crs::Projected(28348), "GDA94 / MGA zone 48");
    assert!(g.crs_inferred);
    assert_eq!(g.citation.as_deref(), Some("GDA94 / MGA zone 48"));
    // The file stores x as 566710.0000000009.
    let tp = g.tie_point.expect("tie point");
    assert_eq!(tp.raster, [0.0, 0.0, 0.0]);
    assert!(close(tp.model[0], 566_710.0, 1e-6) && close(tp.model[1], 8_842_640.0, 1e-6));
    let (ulx, uly) = g.upper_left_corner;
    assert!(close(ulx, 566_710.0, 1e-6) && close(uly, 8_842_640.0, 1e-6));
    let (llx, lly) = geo.lower_left().expect("georef");
    assert!(close(llx, 566_710.0, 1e-6) && close(lly, 8_842_640.0 - 879.0 * 5.0, 1e-6));
    assert!(geo.nodata.is_some_and(|v| v < -3e38), "{:?}", geo.nodata);
    // Same samples, rows flipped, 5 m cells.
    let tg = &geo.terrain;
    assert_eq!(tg.cell(), (5.0, 5.0));
    assert_eq!(tg.extent(), (0.0, 0.0, 1044.0 * 5.0, 878.0 * 5.0));
    assert_eq!(tg.node(199, 878 - 99), t.node(199, 99));
    // Both frames agree on where a pixel is in the world.
    let a = dem.local_to_world(200.0, 100.0).expect("georef");
    let b = geo
        .local_to_world(199.0 * 5.0, (878.0 - 99.0) * 5.0)
        .expect("georef");
    assert!(
        close(a.0, b.0, 1e-6) && close(a.1, b.1, 1e-6),
        "{a:?} {b:?}"
    );

    // The real file, truncated anywhere, is an error rather than a panic.
    let bytes = std::fs::read(&path).expect("read");
    let dir = TempDir::new("spso");
    for cut in [0, 7, 100, 7_000, 7_626, 1_000_000, bytes.len() - 1] {
        let p = dir.path("cut.tif");
        std::fs::write(&p, &bytes[..cut]).expect("write");
        let err = read_terrain(&p, &DemOptions::SPSO).expect_err("truncated");
        assert!(err.to_string().contains("cut.tif"), "{err}");
    }
}

// ---------------------------------------------------------------- GeoTIFF round trips

#[test]
fn float32_geotiff_round_trip() {
    let dir = TempDir::new("f32");
    let p = dir.path("grid.tif");
    let geo = mga48((5.0, 10.0), (1000.0, 2000.0));
    write_tiff::<colortype::Gray32Float>(
        &p,
        4,
        3,
        &grid_values(4, 3),
        Some(&geo),
        Compression::Uncompressed,
    );

    let dem = read_terrain(&p, &DemOptions::default()).expect("reads");
    assert_eq!(dem.format, DemFormat::GeoTiff);
    assert_eq!(dem.sample_type, SampleType::F32);
    assert_eq!((dem.columns, dem.rows), (4, 3));
    let t = &dem.terrain;
    assert_eq!(t.size(), (4, 3));
    assert_eq!(t.origin(), (0.0, 0.0));
    assert_eq!(t.cell(), (5.0, 10.0));
    assert_eq!(t.sampling(), Sampling::Bilinear);
    // Terrain row 0 is the southern (last) file row.
    assert_eq!(t.node(0, 0), 20.0);
    assert_eq!(t.node(3, 2), 3.0);
    assert_eq!(t.height(5.0, 0.0), 21.0);
    assert_eq!(t.height(2.5, 20.0), 0.5);
    let g = dem.georef.clone().expect("georeferenced");
    assert_eq!(g.crs, Crs::Projected(28348));
    assert_eq!(g.crs.epsg(), Some(28348));
    assert!(!g.crs_inferred);
    assert_eq!(g.upper_left_corner, (1000.0, 2000.0));
    assert_eq!(dem.lower_left(), Some((1000.0, 1970.0)));
    assert_eq!(g.south_west_node, (1002.5, 1975.0));
    assert_eq!(dem.local_to_world(0.0, 0.0), Some((1002.5, 1975.0)));
    assert_eq!(dem.world_to_local(1012.5, 1995.0), Some((10.0, 20.0)));
    assert!(!g.pixel_is_point);

    let spso = read_terrain(&p, &DemOptions::SPSO).expect("reads");
    let t = &spso.terrain;
    assert_eq!((t.origin(), t.cell()), ((1.0, 1.0), (1.0, 1.0)));
    // x = column + 1, y = file row + 1.
    assert_eq!(t.height(1.0, 1.0), 0.0);
    assert_eq!(t.height(4.0, 1.0), 3.0);
    assert_eq!(t.height(2.0, 3.0), 21.0);
    assert_eq!(t.height(2.5, 2.5), 22.0); // rounds half away from zero
    assert_eq!(spso.local_to_world(1.0, 1.0), Some((1002.5, 1995.0)));
}

#[test]
fn int16_geotiff_with_nodata_is_filled() {
    let dir = TempDir::new("i16");
    let p = dir.path("grid.tiff");
    let mut geo = mga48((2.0, 2.0), (0.0, 100.0));
    geo.nodata = Some("-32768");
    #[rustfmt::skip]
    let data: Vec<i16> = vec![
        100, 110, 120,
        130, -32768, 150,
        160, 170, -32768,
    ];
    write_tiff::<colortype::GrayI16>(&p, 3, 3, &data, Some(&geo), Compression::Uncompressed);
    let dem = read_terrain(&p, &DemOptions::SPSO).expect("reads");
    assert_eq!(dem.sample_type, SampleType::I16);
    assert_eq!(dem.nodata, Some(-32768.0));
    assert_eq!(dem.nodata_filled, 2);
    let t = &dem.terrain;
    // Centre: edge neighbours first, in row-major order -> the one above (110).
    assert_eq!(t.node(1, 1), 110.0);
    // Corner: its edge neighbours are 150 (above) and 170 (left); 150 comes first.
    assert_eq!(t.node(2, 2), 150.0);
    assert!(t.min_height() >= 100.0);
}

#[test]
fn other_sample_types_and_compression() {
    let dir = TempDir::new("types");
    let geo = mga48((1.0, 1.0), (0.0, 0.0));
    let values = grid_values(5, 4);
    let check = |p: &Path, sample_type: SampleType| {
        let dem = read_terrain(p, &DemOptions::SPSO).expect("reads");
        assert_eq!(dem.sample_type, sample_type);
        assert_eq!(dem.terrain.height(5.0, 4.0), 34.0);
        assert_eq!(dem.terrain.height(1.0, 2.0), 10.0);
    };
    let p = dir.path("f64.tif");
    let v64: Vec<f64> = values.iter().map(|v| f64::from(*v)).collect();
    let deflate = Compression::Deflate(DeflateLevel::Balanced);
    write_tiff::<colortype::Gray64Float>(&p, 5, 4, &v64, Some(&geo), deflate);
    check(&p, SampleType::F64);
    let p = dir.path("u16.tif");
    let v16: Vec<u16> = values.iter().map(|v| *v as u16).collect();
    write_tiff::<colortype::Gray16>(&p, 5, 4, &v16, None, Compression::Lzw);
    check(&p, SampleType::U16);
    let p = dir.path("i32.tif");
    let v32: Vec<i32> = values.iter().map(|v| *v as i32).collect();
    write_tiff::<colortype::GrayI32>(&p, 5, 4, &v32, None, Compression::Packbits);
    check(&p, SampleType::I32);
    let p = dir.path("u8.tif");
    let v8: Vec<u8> = values.iter().map(|v| *v as u8).collect();
    write_tiff::<colortype::Gray8>(&p, 5, 4, &v8, None, Compression::Uncompressed);
    check(&p, SampleType::U8);
    // Without georeferencing the georeferenced frame falls back to 1 m cells.
    let plain = read_terrain(&p, &DemOptions::default()).expect("reads");
    assert!(plain.georef.is_none());
    assert_eq!(plain.terrain.cell(), (1.0, 1.0));
    assert_eq!(plain.local_to_world(0.0, 0.0), None);
}

#[test]
fn geographic_and_pixel_is_point_georeferencing() {
    let dir = TempDir::new("geo");
    let p = dir.path("wgs84.tif");
    let arcsec = 1.0 / 3600.0;
    let geo = Geo {
        scale: (arcsec, arcsec),
        tie: (105.5, 0.0005),
        // Geographic model, PixelIsPoint, WGS 84.
        keys: vec![(1024, 2), (1025, 2), (2048, 4326)],
        nodata: None,
    };
    write_tiff::<colortype::Gray32Float>(
        &p,
        4,
        3,
        &grid_values(4, 3),
        Some(&geo),
        Compression::Uncompressed,
    );
    let dem = read_terrain(&p, &DemOptions::default()).expect("reads");
    let g = dem.georef.clone().expect("georef");
    assert_eq!(g.crs, Crs::Geographic(4326));
    assert!(g.pixel_is_point);
    // The tie point is the first pixel's centre, so the corner is half a cell further out.
    assert!(close(g.upper_left_corner.0, 105.5 - 0.5 * arcsec, 1e-12));
    assert!(close(g.south_west_node.1, 0.0005 - 2.0 * arcsec, 1e-12));
    // About 30.9 m east-west and 30.7 m north-south near the equator.
    assert!(
        close(dem.cell_metres.0, 30.92, 0.01),
        "{:?}",
        dem.cell_metres
    );
    assert!(
        close(dem.cell_metres.1, 30.72, 0.01),
        "{:?}",
        dem.cell_metres
    );
    assert_eq!(dem.terrain.cell(), dem.cell_metres);
    let w = dem.local_to_world(dem.cell_metres.0, 0.0).expect("georef");
    assert!(close(w.0, g.south_west_node.0 + arcsec, 1e-12));
}

// ---------------------------------------------------------------- hand-made TIFFs

/// A little-endian baseline TIFF written byte by byte, to cover what the `tiff` encoder
/// cannot write: tiles, several bands, odd sample types.
struct RawTiff {
    width: u32,
    height: u32,
    bits: u16,
    format: u16,
    bands: u16,
    /// Square tile size, or one strip for the whole image.
    tile: Option<u32>,
}

impl RawTiff {
    fn bytes(&self, value: impl Fn(u32, u32) -> f32) -> Vec<u8> {
        let sample_bytes = usize::from(self.bits / 8) * usize::from(self.bands);
        let pixel = |c: u32, r: u32| -> Vec<u8> {
            if c >= self.width || r >= self.height {
                return vec![0; sample_bytes];
            }
            if self.bits == 32 && self.format == 3 {
                value(c, r).to_le_bytes().repeat(usize::from(self.bands))
            } else {
                vec![0x11; sample_bytes]
            }
        };
        // Chunks: tiles (padded to full size) or one strip.
        let mut chunks: Vec<Vec<u8>> = Vec::new();
        match self.tile {
            Some(t) => {
                for tr in 0..self.height.div_ceil(t) {
                    for tc in 0..self.width.div_ceil(t) {
                        let mut chunk = Vec::new();
                        for r in 0..t {
                            for c in 0..t {
                                chunk.extend(pixel(tc * t + c, tr * t + r));
                            }
                        }
                        chunks.push(chunk);
                    }
                }
            }
            None => {
                let mut chunk = Vec::new();
                for r in 0..self.height {
                    for c in 0..self.width {
                        chunk.extend(pixel(c, r));
                    }
                }
                chunks.push(chunk);
            }
        }
        let mut out = b"II*\0".to_vec();
        out.extend(8u32.to_le_bytes()); // IFD right after the header
        let (off_tag, count_tag, size_tag) = match self.tile {
            Some(_) => (324u16, 325u16, 322u16),
            None => (273, 279, 278),
        };
        let n = chunks.len() as u32;
        // (tag, type, count, value or offset placeholder); type 3 = SHORT, 4 = LONG.
        let mut entries: Vec<(u16, u16, u32, u32)> = vec![
            (256, 4, 1, self.width),
            (257, 4, 1, self.height),
            (258, 3, 1, u32::from(self.bits)),
            (259, 3, 1, 1),
            (262, 3, 1, 1),
            (277, 3, 1, u32::from(self.bands)),
            (339, 3, 1, u32::from(self.format)),
        ];
        match self.tile {
            Some(t) => {
                entries.push((size_tag, 4, 1, t));
                entries.push((size_tag + 1, 4, 1, t));
            }
            None => entries.push((size_tag, 4, 1, self.height)),
        }
        let ifd_len = 2 + 12 * (entries.len() + 2) + 4;
        let arrays_at = 8 + ifd_len as u32;
        let data_at = arrays_at + 8 * n;
        let offsets_value = if n == 1 { data_at } else { arrays_at };
        let counts_value = if n == 1 {
            chunks[0].len() as u32
        } else {
            arrays_at + 4 * n
        };
        entries.push((off_tag, 4, n, offsets_value));
        entries.push((count_tag, 4, n, counts_value));
        entries.sort_by_key(|e| e.0);
        out.extend((entries.len() as u16).to_le_bytes());
        for (tag, ty, count, value) in entries {
            out.extend(tag.to_le_bytes());
            out.extend(ty.to_le_bytes());
            out.extend(count.to_le_bytes());
            if ty == 3 {
                out.extend((value as u16).to_le_bytes());
                out.extend([0, 0]);
            } else {
                out.extend(value.to_le_bytes());
            }
        }
        out.extend(0u32.to_le_bytes()); // no next IFD
        let mut at = data_at;
        for c in &chunks {
            out.extend(at.to_le_bytes());
            at += c.len() as u32;
        }
        for c in &chunks {
            out.extend((c.len() as u32).to_le_bytes());
        }
        assert_eq!(out.len() as u32, data_at);
        for c in chunks {
            out.extend(c);
        }
        out
    }
}

#[test]
fn tiled_geotiff_reads_like_a_stripped_one() {
    let dir = TempDir::new("tiles");
    let value = |c: u32, r: u32| (100 * r + c) as f32 + 0.5;
    let spec = RawTiff {
        width: 20,
        height: 18,
        bits: 32,
        format: 3,
        bands: 1,
        tile: Some(16),
    };
    let p = dir.path("tiled.tif");
    std::fs::write(&p, spec.bytes(value)).expect("write");
    let tiled = read_terrain(&p, &DemOptions::SPSO).expect("tiled reads");
    let p = dir.path("stripped.tif");
    std::fs::write(&p, RawTiff { tile: None, ..spec }.bytes(value)).expect("write");
    let stripped = read_terrain(&p, &DemOptions::SPSO).expect("stripped reads");
    assert_eq!(tiled.terrain.size(), (20, 18));
    assert_eq!(tiled.terrain.heights(), stripped.terrain.heights());
    for (c, r) in [(0, 0), (19, 0), (17, 16), (0, 17), (19, 17)] {
        let h = tiled.terrain.height(f64::from(c) + 1.0, f64::from(r) + 1.0);
        assert_eq!(h, f64::from(value(c, r)), "({c}, {r})");
    }
}

#[test]
fn several_bands_and_odd_sample_types_are_rejected() {
    let dir = TempDir::new("reject");
    let base = RawTiff {
        width: 4,
        height: 4,
        bits: 32,
        format: 3,
        bands: 1,
        tile: None,
    };
    let read = |name: &str, spec: RawTiff| {
        let p = dir.path(name);
        std::fs::write(&p, spec.bytes(|_, _| 1.0)).expect("write");
        let e = read_terrain(&p, &DemOptions::default()).expect_err("rejected");
        assert!(e.to_string().contains(name), "{e}");
        e
    };
    let e = read("bands.tif", RawTiff { bands: 2, ..base });
    assert!(matches!(e, DemError::TooManyBands { bands: 2, .. }), "{e}");
    let e = read("complex.tif", RawTiff { format: 6, ..base });
    assert!(matches!(e, DemError::UnsupportedSampleType { .. }), "{e}");
    assert!(e.to_string().contains("complex float"), "{e}");
    let e = read("f8.tif", RawTiff { bits: 8, ..base });
    assert!(matches!(e, DemError::UnsupportedSampleType { .. }), "{e}");
    assert!(e.to_string().contains("8-bit float"), "{e}");

    let p = dir.path("rgb.tif");
    write_tiff::<colortype::RGB8>(&p, 2, 2, &[0; 12], None, Compression::Uncompressed);
    let e = read_terrain(&p, &DemOptions::default()).expect_err("rgb");
    assert!(matches!(e, DemError::TooManyBands { bands: 3, .. }), "{e}");
}

// ---------------------------------------------------------------- ESRI ASCII grids

fn read_asc(
    dir: &TempDir,
    name: &str,
    text: &str,
    opts: &DemOptions,
) -> Result<LoadedDem, DemError> {
    let p = dir.path(name);
    std::fs::write(&p, text).expect("write asc");
    read_terrain(&p, opts)
}

#[test]
fn ascii_grid_first_row_is_north() {
    let dir = TempDir::new("asc");
    let text = "ncols 3\nnrows 2\nxllcorner 100\nyllcorner 200\ncellsize 10\n\
                NODATA_value -9999\n1 2 3\n4 5 -9999\n";
    let dem = read_asc(&dir, "grid.asc", text, &DemOptions::default()).expect("reads");
    assert_eq!(dem.format, DemFormat::EsriAscii);
    assert_eq!(dem.sample_type, SampleType::Text);
    assert_eq!((dem.columns, dem.rows), (3, 2));
    assert_eq!(dem.nodata, Some(-9999.0));
    assert_eq!(dem.nodata_filled, 1);
    let t = &dem.terrain;
    assert_eq!(t.cell(), (10.0, 10.0));
    // Terrain row 1 (north) is the first data row.
    assert_eq!([t.node(0, 1), t.node(1, 1), t.node(2, 1)], [1.0, 2.0, 3.0]);
    assert_eq!([t.node(0, 0), t.node(1, 0)], [4.0, 5.0]);
    assert_eq!(t.node(2, 0), 3.0); // filled from the edge neighbour above
    assert_eq!(t.height(0.0, 10.0), 1.0);
    assert_eq!(t.height(0.0, 5.0), 2.5);
    let g = dem.georef.clone().expect("asc has georeferencing");
    assert_eq!(dem.lower_left(), Some((100.0, 200.0)));
    assert_eq!(g.upper_left_corner, (100.0, 220.0));
    assert_eq!(g.south_west_node, (105.0, 205.0));
    assert_eq!(g.crs.epsg(), None);

    let spso = read_asc(&dir, "grid2.asc", text, &DemOptions::SPSO).expect("reads");
    assert_eq!(spso.terrain.height(1.0, 1.0), 1.0);
    assert_eq!(spso.terrain.height(2.0, 2.0), 5.0);
}

#[test]
fn gzip_compressed_grids_read_like_plain_ones() {
    use std::io::Write as _;
    let dir = TempDir::new("asc-gz");
    let text = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 5\n1 2 3\n4 5 6\n";
    let plain = read_asc(&dir, "g.asc", text, &DemOptions::default()).expect("reads");
    let gz = dir.path("g.asc.gz");
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(text.as_bytes()).unwrap();
    std::fs::write(&gz, enc.finish().unwrap()).unwrap();
    let packed = read_terrain(&gz, &DemOptions::default()).expect("reads .asc.gz");
    assert_eq!(packed.format, DemFormat::EsriAscii);
    assert_eq!(packed.terrain.fingerprint(), plain.terrain.fingerprint());
    // A gzip stream cut short is an error naming the file, not a panic.
    let bytes = std::fs::read(&gz).unwrap();
    let cut = dir.path("cut.asc.gz");
    std::fs::write(&cut, &bytes[..bytes.len() / 2]).unwrap();
    let e = read_terrain(&cut, &DemOptions::default()).expect_err("truncated gzip");
    assert!(e.to_string().contains("cut.asc.gz"), "{e}");
}

#[test]
fn ascii_grid_header_variants() {
    let dir = TempDir::new("asc-var");
    // Centre registration, dx/dy, odd case, a row wrapped over two lines, blank lines,
    // no NODATA_value, CRLF line ends.
    let text = "NCOLS 4\r\nNRows 2\r\nXLLCENTER 5\r\nyllcenter 10\r\ndx 10\r\ndy 20\r\n\r\n\
                1 2\r\n3 4\r\n5 6 7 8\r\n";
    let dem = read_asc(&dir, "v.asc", text, &DemOptions::default()).expect("reads");
    assert_eq!(dem.terrain.cell(), (10.0, 20.0));
    assert_eq!(dem.lower_left(), Some((0.0, 0.0)));
    assert_eq!(dem.terrain.node(3, 1), 4.0);
    assert_eq!(dem.terrain.node(0, 0), 5.0);
    assert_eq!(dem.nodata_filled, 0);
    // Recognised by content even without the extension, also behind a UTF-8 byte-order mark.
    let dem = read_asc(&dir, "grid.txt", text, &DemOptions::default()).expect("reads");
    assert_eq!(dem.format, DemFormat::EsriAscii);
    let bom = format!("\u{feff}{text}");
    let dem = read_asc(&dir, "bom.txt", &bom, &DemOptions::default()).expect("reads");
    assert_eq!(dem.terrain.node(0, 0), 5.0);
}

#[test]
fn ascii_grid_errors_name_the_problem() {
    let dir = TempDir::new("asc-err");
    let opts = DemOptions::default();
    let err = |name: &str, text: &str| {
        let e = read_asc(&dir, name, text, &opts).expect_err("invalid");
        let msg = e.to_string();
        assert!(msg.contains(name), "{msg}");
        (e, msg)
    };

    let (e, msg) = err(
        "missing.asc",
        "ncols 2\nnrows 2\nxllcorner 0\ncellsize 1\n1 2\n3 4\n",
    );
    assert!(
        matches!(
            e,
            DemError::MissingField {
                field: "yllcorner",
                line: 5,
                ..
            }
        ),
        "{msg}"
    );
    assert!(msg.contains("yllcorner") && msg.contains("line 5"), "{msg}");

    let (e, msg) = err(
        "short.asc",
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3\n",
    );
    assert!(
        matches!(
            e,
            DemError::WrongValueCount {
                expected: 4,
                found: 3,
                ..
            }
        ),
        "{msg}"
    );
    let (e, _) = err(
        "long.asc",
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n5\n",
    );
    assert!(matches!(e, DemError::WrongValueCount { found: 5, .. }));

    let (e, msg) = err(
        "value.asc",
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 x4\n",
    );
    assert!(matches!(e, DemError::BadValue { line: 7, .. }), "{msg}");
    assert!(msg.contains("`x4`"), "{msg}");

    let (_, msg) = err(
        "twice.asc",
        "ncols 2\nncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n",
    );
    assert!(msg.contains("line 2") && msg.contains("twice"), "{msg}");
    let (_, msg) = err(
        "unknown.asc",
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nzunits m\n1 2\n3 4\n",
    );
    assert!(msg.contains("line 6") && msg.contains("zunits"), "{msg}");
    let (_, msg) = err(
        "cols.asc",
        "ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n",
    );
    assert!(msg.contains("line 1") && msg.contains("ncols"), "{msg}");
    let (_, msg) = err(
        "cell.asc",
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -1\n1 2\n3 4\n",
    );
    assert!(msg.contains("line 5") && msg.contains("cellsize"), "{msg}");
    let (e, _) = err(
        "empty.asc",
        "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nNODATA_value -1\n-1 -1\n-1 -1\n",
    );
    assert!(matches!(e, DemError::AllNodata { .. }));
    // One row cannot make a terrain grid: an error, not a panic.
    let (e, msg) = err(
        "row.asc",
        "ncols 3\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n",
    );
    assert!(matches!(e, DemError::Terrain { .. }), "{msg}");
    let (e, _) = err("header-only.asc", "ncols 2\nnrows 2\n");
    assert!(matches!(e, DemError::MissingField { line: 3, .. }), "{e}");
    let (e, _) = err("control.asc", "ncols 2\n\u{0}\u{ff}");
    assert!(matches!(e, DemError::BadHeader { line: 2, .. }), "{e}");
    let p = dir.path("binary.asc");
    std::fs::write(&p, b"ncols 2\n\xff\xfe").expect("write");
    let e = read_terrain(&p, &opts).expect_err("not UTF-8");
    assert!(matches!(e, DemError::Corrupt { .. }), "{e}");
    assert!(
        e.to_string().contains("binary.asc") && e.to_string().contains("byte 8"),
        "{e}"
    );
}

// ---------------------------------------------------------------- bad files never panic

/// A small deterministic generator for garbage bytes.
fn lcg(state: &mut u64) -> u8 {
    *state = state
        .wrapping_mul(6_364_136_223_846_793_005)
        .wrapping_add(1_442_695_040_888_963_407);
    (*state >> 56) as u8
}

#[test]
fn truncated_and_garbage_files_are_errors() {
    let dir = TempDir::new("bad");
    let p = dir.path("good.tif");
    write_tiff::<colortype::Gray32Float>(
        &p,
        9,
        7,
        &grid_values(9, 7),
        Some(&mga48((5.0, 5.0), (0.0, 0.0))),
        Compression::Uncompressed,
    );
    let good = std::fs::read(&p).expect("read");
    let tiled = RawTiff {
        width: 20,
        height: 18,
        bits: 32,
        format: 3,
        bands: 1,
        tile: Some(16),
    }
    .bytes(|c, r| (c + r) as f32);
    let asc = b"ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2 3\n4 5 6\n".to_vec();
    // A truncated TIFF is an error unless only bytes the decoder never reads were cut (the
    // padding at the end of the last tile): then the terrain must be the full one.
    let cut = dir.path("cut.tif");
    // Last tile: 16 x 16 samples of which the decoder needs 1 row + 4 (columns 16..20).
    let unread_tail = (16 * 16 - (16 + 4)) * 4;
    for (file, unread) in [(&good, 0), (&tiled, unread_tail)] {
        std::fs::write(&cut, file).expect("write");
        let full = read_terrain(&cut, &DemOptions::default()).expect("full file reads");
        let mut errors = 0;
        for len in 0..file.len() {
            std::fs::write(&cut, &file[..len]).expect("write");
            match read_terrain(&cut, &DemOptions::default()) {
                Err(e) => {
                    assert!(e.to_string().contains("cut.tif"), "{e}");
                    errors += 1;
                }
                Ok(dem) => assert_eq!(dem.terrain.heights(), full.terrain.heights(), "{len}"),
            }
        }
        assert_eq!(errors, file.len() - unread);
    }
    let cut_asc = dir.path("cut.asc");
    for len in 0..asc.len() - 1 {
        std::fs::write(&cut_asc, &asc[..len]).expect("write");
        assert!(
            read_terrain(&cut_asc, &DemOptions::default()).is_err(),
            "{len}"
        );
    }

    // Garbage, with and without a TIFF signature; single-byte corruption of valid files:
    // any outcome but a panic is acceptable there, and no decoded value may be a sentinel.
    let mut state = 7u64;
    let junk = dir.path("junk.tif");
    for k in 0..300 {
        let len = 1 + usize::from(lcg(&mut state)) * 4;
        let mut bytes: Vec<u8> = (0..len).map(|_| lcg(&mut state)).collect();
        if k % 2 == 0 && len >= 4 {
            bytes[..4].copy_from_slice(b"II*\0");
        }
        std::fs::write(&junk, &bytes).expect("write");
        let e = read_terrain(&junk, &DemOptions::default()).expect_err("garbage");
        assert!(e.to_string().contains("junk.tif"), "{e}");
    }
    let flipped = dir.path("flipped.tif");
    for file in [&good, &tiled] {
        for k in 0..file.len() {
            let mut bytes = file.clone();
            bytes[k] ^= 1 << (k % 8);
            bytes[(k * 7919) % file.len()] = lcg(&mut state);
            std::fs::write(&flipped, &bytes).expect("write");
            if let Ok(dem) = read_terrain(&flipped, &DemOptions::default()) {
                assert!(dem.terrain.heights().iter().all(|h| h.abs() <= 1e30));
            }
        }
    }
}

#[test]
fn unknown_and_missing_files() {
    let dir = TempDir::new("unknown");
    let p = dir.path("terrain.xyz");
    std::fs::write(&p, "hello").expect("write");
    let e = read_terrain(&p, &DemOptions::default()).expect_err("unknown");
    assert!(matches!(e, DemError::UnknownFormat { .. }), "{e}");
    assert!(e.to_string().contains("terrain.xyz") && e.to_string().contains("xyz"));
    let p = dir.path("absent.tif");
    let e = read_terrain(&p, &DemOptions::default()).expect_err("missing");
    assert!(matches!(e, DemError::Io { .. }), "{e}");
    assert!(e.to_string().contains("absent.tif"), "{e}");
    let p = dir.path("text.tif");
    std::fs::write(&p, "not a tiff at all").expect("write");
    let e = read_terrain(&p, &DemOptions::default()).expect_err("not a tiff");
    assert!(matches!(e, DemError::Corrupt { .. }), "{e}");
}

#[test]
fn options_parse_from_toml_style_names() {
    let o: DemOptions =
        serde_json::from_str(r#"{"frame": "spso-pixels", "sampling": "nearest-matlab"}"#)
            .expect("parses");
    assert_eq!(o, DemOptions::SPSO);
    assert_eq!(
        serde_json::from_str::<DemOptions>("{}").expect("defaults"),
        DemOptions {
            frame: DemFrame::Georeferenced,
            sampling: Sampling::Bilinear
        }
    );
    assert!(serde_json::from_str::<DemOptions>(r#"{"frames": "x"}"#).is_err());
}
