//! Georeferencing against independent values: geodetic <-> ECEF against PROJ (through
//! pyproj; the constants below, with the versions that produced them) and textbook points
//! on the axes; ENU properties and round trips; the tangent-plane frame against its
//! definition evaluated with PROJ's geocentric conversion; UTM / MGA against PROJ and the
//! ICSM worked example (Flinders Peak); DEM frames from GeoTIFFs written here (and SPSO's
//! DEM when the shared folder is present); and `scenario new` on a DEM.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use std::path::Path;

use glam::DVec3;
use swarmplan_core::cost::assess_as_searched;
use swarmplan_core::plan::Plan;
use swarmplan_io::dem::{read_terrain, DemOptions};
use swarmplan_io::export::{export_plan, ExportFormat};
use swarmplan_io::geo::{
    ecef_to_geodetic, geodetic_to_ecef, load_spec_with_origin, new_scenario, parse_lat_lon,
    resolve_frame, scenario_toml_with_origin, Ellipsoid, EnuFrame, FrameSource, Geodetic,
    LocalFrame, NewScenarioRequest, UtmZone,
};
use swarmplan_io::import::read_exported_plan;
use swarmplan_io::scenario::build_world;
use tiff::encoder::{colortype, TiffEncoder};
use tiff::tags::Tag;

// Reference values: `python3 gen.py` with pyproj (EPSG:4979 -> 4978 for ECEF; the UTM /
// MGA EPSG codes against their geographic CRS, GDA94 and GDA2020 on GRS 80).
// Produced with pyproj 3.7.2 PROJ 9.5.1
const ECEF_POINTS: [[f64; 6]; 7] = [
    [
        47.3977,
        8.5456,
        488.0,
        4277554.500694052,
        642765.6349354209,
        4672165.524512972,
    ],
    [
        -10.45,
        105.62,
        150.0,
        -1689092.7024603928,
        6041507.482123917,
        -1149259.3024812425,
    ],
    [
        -37.95103341666667,
        144.42486788888888,
        0.0,
        -4095863.3403117927,
        2929662.0883788653,
        -3901159.6253409404,
    ],
    [
        89.5,
        -120.0,
        3000.0,
        -27936.223112941996,
        -48386.95780319554,
        6359508.523192351,
    ],
    [
        -33.8688,
        151.2093,
        58.0,
        -4646093.477288303,
        2553229.5358170713,
        -3534404.710910369,
    ],
    [
        0.5,
        -179.9,
        -400.0,
        -6377486.067542746,
        -11130.824290014274,
        55282.959665547074,
    ],
    [
        64.1466,
        -21.9426,
        8848.0,
        2590432.7497682553,
        -1043585.2186876229,
        5724822.7515651705,
    ],
];
/// (EPSG, easting, northing, latitude, longitude)
const UTM_POINTS: [(u16, f64, f64, f64, f64); 7] = [
    (
        28348,
        566710.0,
        8842640.0,
        -10.46925317615047,
        105.60957693186803,
    ),
    (
        28355,
        273741.29664593353,
        5796489.776865904,
        -37.95103341666667,
        144.42486788888888,
    ),
    (32633, 500000.0000000011, 5761038.212590415, 52.0, 15.0),
    (
        32633,
        13040.240825557557,
        5269590.845027376,
        47.3977,
        8.5456,
    ),
    (32748, 567854.88849221, 8844766.651919464, -10.45, 105.62),
    (
        7856,
        334368.6336472522,
        6250948.345488558,
        -33.8688,
        151.2093,
    ),
    (32601, 480914.55221758824, 7765951.3899121145, 70.0, -177.5),
];
/// Tangent plane at (47.3977, 8.5456, 400): (east, north, latitude, longitude)
const TANGENT_POINTS: [[f64; 4]; 3] = [
    [1234.5, -987.25, 47.388819528118795, 8.561949431242835],
    [-20000.0, 35000.0, 47.71216772363317, 8.279094765763698],
    [3000.0, 4000.0, 47.43366887527013, 8.585365039820802],
];

fn metres_lat(dlat_deg: f64) -> f64 {
    dlat_deg.to_radians() * 6_378_137.0
}

fn metres_lon(dlon_deg: f64, lat_deg: f64) -> f64 {
    dlon_deg.to_radians() * 6_378_137.0 * lat_deg.to_radians().cos()
}

#[test]
fn ecef_matches_proj_to_a_millimetre() {
    let mut worst: f64 = 0.0;
    for [lat, lon, h, x, y, z] in ECEF_POINTS {
        let p = geodetic_to_ecef(Geodetic::new(lat, lon, h));
        let err = p.distance(DVec3::new(x, y, z));
        worst = worst.max(err);
        assert!(
            err < 1e-3,
            "({lat}, {lon}, {h}): {p} vs ({x}, {y}, {z}): {err} m"
        );
        let g = ecef_to_geodetic(DVec3::new(x, y, z));
        let back = metres_lat(g.lat_deg - lat)
            .abs()
            .max(metres_lon(g.lon_deg - lon, lat).abs())
            .max((g.alt_m - h).abs());
        worst = worst.max(back);
        assert!(
            back < 1e-3,
            "({x}, {y}, {z}) -> {g:?}, expected ({lat}, {lon}, {h})"
        );
    }
    println!("geodetic <-> ECEF against PROJ: worst {worst:.2e} m");
}

#[test]
fn textbook_points_on_the_axes() {
    let a = Ellipsoid::WGS84.a;
    let b = Ellipsoid::WGS84.b();
    assert!((b - 6_356_752.314_245).abs() < 1e-6, "{b}");
    let cases = [
        ((0.0, 0.0, 0.0), DVec3::new(a, 0.0, 0.0)),
        ((0.0, 90.0, 100.0), DVec3::new(0.0, a + 100.0, 0.0)),
        ((0.0, 180.0, 0.0), DVec3::new(-a, 0.0, 0.0)),
        ((90.0, 0.0, 10.0), DVec3::new(0.0, 0.0, b + 10.0)),
        ((-90.0, 0.0, 0.0), DVec3::new(0.0, 0.0, -b)),
    ];
    for ((lat, lon, h), want) in cases {
        let p = geodetic_to_ecef(Geodetic::new(lat, lon, h));
        assert!(p.distance(want) < 1e-6, "({lat}, {lon}, {h}): {p}");
        let g = ecef_to_geodetic(want);
        assert!(
            (g.lat_deg - lat).abs() < 1e-12 && (g.alt_m - h).abs() < 1e-6,
            "{g:?}"
        );
    }
}

#[test]
fn geodetic_ecef_round_trips_everywhere() {
    let mut worst_deg: f64 = 0.0;
    let mut worst_m: f64 = 0.0;
    for lat10 in -900_i32..=900 {
        if lat10 % 7 != 0 && lat10.abs() < 895 {
            continue;
        }
        let lat = f64::from(lat10) / 10.0;
        for lon in [-180.0, -123.4, -45.0, 0.0, 0.001, 77.7, 179.99] {
            for h in [-430.0, 0.0, 150.0, 8_848.0, 40_000.0] {
                let g = Geodetic::new(lat, lon, h);
                let p = geodetic_to_ecef(g);
                let back = ecef_to_geodetic(p);
                let q = geodetic_to_ecef(back);
                worst_m = worst_m.max(p.distance(q)).max((back.alt_m - h).abs());
                if lat.abs() < 90.0 {
                    let dlon = (back.lon_deg - lon + 540.0).rem_euclid(360.0) - 180.0;
                    worst_deg = worst_deg.max((back.lat_deg - lat).abs()).max(dlon.abs());
                }
            }
        }
    }
    println!("geodetic -> ECEF -> geodetic: worst {worst_deg:.2e} deg, {worst_m:.2e} m");
    assert!(worst_deg < 1e-9, "{worst_deg} deg");
    assert!(worst_m < 1e-6, "{worst_m} m");
}

#[test]
fn enu_axes_and_round_trips() {
    let origin = Geodetic::new(-10.45, 105.62, 150.0);
    let f = EnuFrame::new(origin);
    assert!(f.geodetic_to_enu(origin).length() < 1e-9);
    // Straight up along the normal.
    let up = f.geodetic_to_enu(Geodetic::new(-10.45, 105.62, 1150.0));
    assert!((up - DVec3::new(0.0, 0.0, 1000.0)).length() < 1e-8, "{up}");
    // East and north of the origin have positive east and north coordinates.
    let e = f.geodetic_to_enu(Geodetic::new(-10.45, 105.63, 150.0));
    let n = f.geodetic_to_enu(Geodetic::new(-10.44, 105.62, 150.0));
    assert!(e.x > 1000.0 && e.y.abs() < 1.0 && e.z < 0.0, "{e}");
    assert!(n.y > 1000.0 && n.x.abs() < 1e-9 && n.z < 0.0, "{n}");
    // ENU preserves distances (a rotation of ECEF).
    let (a, b) = (
        Geodetic::new(-10.5, 105.6, 90.0),
        Geodetic::new(-10.4, 105.7, 300.0),
    );
    let d_ecef = geodetic_to_ecef(a).distance(geodetic_to_ecef(b));
    let d_enu = f.geodetic_to_enu(a).distance(f.geodetic_to_enu(b));
    assert!((d_ecef - d_enu).abs() < 1e-8);
    let mut worst: f64 = 0.0;
    for p in [
        DVec3::new(123.4, -567.8, 90.0),
        DVec3::new(-25_000.0, 40_000.0, -100.0),
        DVec3::new(0.0, 0.0, 5_000.0),
    ] {
        let q = f.geodetic_to_enu(f.enu_to_geodetic(p));
        worst = worst.max(q.distance(p));
    }
    println!("ENU -> geodetic -> ENU: worst {worst:.2e} m");
    assert!(worst < 1e-6);
}

#[test]
fn tangent_frame_matches_its_definition_computed_with_proj() {
    let f = LocalFrame::tangent(Geodetic::new(47.3977, 8.5456, 400.0)).unwrap();
    let mut worst: f64 = 0.0;
    for [x, y, lat, lon] in TANGENT_POINTS {
        let g = f.to_geodetic(DVec3::new(x, y, 0.0)).unwrap();
        let err = metres_lat(g.lat_deg - lat)
            .abs()
            .hypot(metres_lon(g.lon_deg - lon, lat).abs());
        worst = worst.max(err);
        assert!(err < 1e-3, "({x}, {y}): {g:?} vs ({lat}, {lon}): {err} m");
        let back = f.from_geodetic(Geodetic::new(lat, lon, 0.0)).unwrap();
        assert!(
            back.truncate().distance(glam::DVec2::new(x, y)) < 1e-3,
            "{back}"
        );
    }
    println!("tangent plane against PROJ-based definition: worst {worst:.2e} m");
}

#[test]
fn tangent_frame_is_not_flat_earth_and_round_trips() {
    let origin = Geodetic::new(-10.45, 105.62, 0.0);
    let f = LocalFrame::tangent(origin).unwrap();
    // 20 km north: a flat-earth conversion with the equatorial radius would put the point
    // about 128 m short of the meridian arc (radius of curvature 6338 km here, not 6378);
    // the tangent plane follows the arc to within its foreshortening (~0.03 m at 20 km).
    let g = f.to_geodetic(DVec3::new(0.0, 20_000.0, 0.0)).unwrap();
    let flat = origin.lat_deg + (20_000.0 / 6_378_137.0_f64).to_degrees();
    let short = metres_lat(g.lat_deg - flat);
    assert!((120.0..135.0).contains(&short), "{short} m, {g:?}");
    let mut worst: f64 = 0.0;
    for x in [-30_000.0, -1_000.0, 0.0, 2_500.0, 45_000.0] {
        for y in [-30_000.0, 0.0, 999.0, 45_000.0] {
            let p = DVec3::new(x, y, 123.0);
            let q = f.from_geodetic(f.to_geodetic(p).unwrap()).unwrap();
            worst = worst.max(q.distance(p));
        }
    }
    println!("tangent frame local -> WGS 84 -> local: worst {worst:.2e} m");
    assert!(worst < 1e-6);
}

#[test]
fn utm_and_mga_match_proj() {
    let mut worst: f64 = 0.0;
    for (epsg, e, n, lat, lon) in UTM_POINTS {
        let zone = UtmZone::from_epsg(epsg).unwrap();
        let (glat, glon) = zone.to_lat_lon(e, n).unwrap();
        let err = metres_lat(glat - lat)
            .abs()
            .hypot(metres_lon(glon - lon, lat).abs());
        let (ge, gn) = zone.from_lat_lon(lat, lon).unwrap();
        let err_grid = (ge - e).hypot(gn - n);
        worst = worst.max(err).max(err_grid);
        assert!(
            err < 0.005 && err_grid < 0.005,
            "{}: {err} m, {err_grid} m",
            zone.name()
        );
        // Round trip through the crate.
        let (re, rn) = zone.from_lat_lon(glat, glon).unwrap();
        assert!((re - e).hypot(rn - n) < 1e-6, "{}", zone.name());
    }
    println!("UTM / MGA against PROJ: worst {worst:.2e} m");
}

#[test]
fn flinders_peak_is_the_icsm_worked_example() {
    // GDA technical manual: Flinders Peak, -37 57 03.72030, 144 25 29.52440 ->
    // MGA zone 55, E 273 741.297, N 5 796 489.777.
    let zone = UtmZone::from_epsg(28355).unwrap();
    let lat = -(37.0 + 57.0 / 60.0 + 3.720_30 / 3600.0);
    let lon = 144.0 + 25.0 / 60.0 + 29.524_40 / 3600.0;
    let (e, n) = zone.from_lat_lon(lat, lon).unwrap();
    assert!(
        (e - 273_741.297).abs() < 0.001 && (n - 5_796_489.777).abs() < 0.001,
        "{e} {n}"
    );
}

#[test]
fn spso_tie_point_in_mga_48_is_on_christmas_island() {
    let zone = UtmZone::from_epsg(28348).unwrap();
    assert_eq!(zone.name(), "GDA94 / MGA zone 48 (EPSG 28348)");
    let (lat, lon) = zone.to_lat_lon(566_710.0, 8_842_640.0).unwrap();
    println!("SPSO DEM tie point (566710, 8842640) in MGA 48: {lat:.8}, {lon:.8}");
    assert!(
        (-10.6..-10.3).contains(&lat) && (105.5..105.8).contains(&lon),
        "{lat} {lon}"
    );
    let (e, n) = zone.from_lat_lon(lat, lon).unwrap();
    let err = (e - 566_710.0).hypot(n - 8_842_640.0);
    println!("  and back: {err:.2e} m");
    assert!(err < 0.01);
}

// ------------------------------------------------------------------ GeoTIFF DEM frames

/// Writes a float32 GeoTIFF of w x h cells (value 10 + column + 2 row) with a tie point at
/// the outer north-west corner and the given GeoKeys (PixelIsArea).
fn write_geotiff(
    path: &Path,
    w: u32,
    h: u32,
    cell: (f64, f64),
    tie: (f64, f64),
    keys: &[(u16, u16)],
) {
    let file = std::fs::File::create(path).unwrap();
    let mut enc = TiffEncoder::new(std::io::BufWriter::new(file)).unwrap();
    let mut img = enc.new_image::<colortype::Gray32Float>(w, h).unwrap();
    let dir = img.encoder();
    dir.write_tag(Tag::ModelPixelScaleTag, &[cell.0, cell.1, 0.0][..])
        .unwrap();
    dir.write_tag(
        Tag::ModelTiepointTag,
        &[0.0, 0.0, 0.0, tie.0, tie.1, 0.0][..],
    )
    .unwrap();
    let mut gk = vec![1u16, 1, 0, keys.len() as u16];
    for &(id, v) in keys {
        gk.extend([id, 0, 1, v]);
    }
    dir.write_tag(Tag::GeoKeyDirectoryTag, &gk[..]).unwrap();
    let data: Vec<f32> = (0..h)
        .flat_map(|r| (0..w).map(move |c| 10.0 + c as f32 + 2.0 * r as f32))
        .collect();
    img.write_data(&data).unwrap();
}

const MGA48: [(u16, u16); 3] = [(1024, 1), (1025, 1), (3072, 28348)];

#[test]
fn projected_dem_frame_goes_through_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mga48.tif");
    write_geotiff(&path, 40, 30, (5.0, 5.0), (566_710.0, 8_842_640.0), &MGA48);
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let f = LocalFrame::from_dem(&dem).unwrap();
    let zone = UtmZone::from_epsg(28348).unwrap();
    // Local (0, 0) is the south-west node: the centre of the south-west cell.
    let sw = (566_710.0 + 2.5, 8_842_640.0 - 30.0 * 5.0 + 2.5);
    let o = f.origin().unwrap();
    let (lat, lon) = zone.to_lat_lon(sw.0, sw.1).unwrap();
    assert_eq!((o.lat_deg, o.lon_deg, o.alt_m), (lat, lon, 0.0));
    let mut worst: f64 = 0.0;
    for (x, y) in [(0.0, 0.0), (195.0, 145.0), (-50.0, 1000.0), (77.7, 12.3)] {
        let g = f.to_geodetic(DVec3::new(x, y, 250.0)).unwrap();
        let want = zone.to_lat_lon(sw.0 + x, sw.1 + y).unwrap();
        assert_eq!((g.lat_deg, g.lon_deg, g.alt_m), (want.0, want.1, 250.0));
        let back = f.from_geodetic(g).unwrap();
        worst = worst.max(back.distance(DVec3::new(x, y, 250.0)));
        // The DEM reader's own map agrees.
        let (wx, wy) = dem.local_to_world(x, y).unwrap();
        assert!((wx - sw.0 - x).abs() < 1e-9 && (wy - sw.1 - y).abs() < 1e-9);
    }
    println!("MGA 48 DEM frame local -> WGS 84 -> local: worst {worst:.2e} m");
    assert!(worst < 0.01);
    // The spso-pixels frame is not at real scale: refused, with the way out.
    let px = read_terrain(&path, &DemOptions::SPSO).unwrap();
    let e = LocalFrame::from_dem(&px).unwrap_err().to_string();
    assert!(
        e.contains("spso-pixels") && e.contains("[geo] origin"),
        "{e}"
    );
    // An unsupported projected CRS names its code.
    let other = dir.path().join("lambert.tif");
    write_geotiff(
        &other,
        4,
        4,
        (5.0, 5.0),
        (700_000.0, 6_600_000.0),
        &[(1024, 1), (3072, 2154)],
    );
    let dem = read_terrain(&other, &DemOptions::default()).unwrap();
    let e = LocalFrame::from_dem(&dem).unwrap_err().to_string();
    assert!(
        e.contains("EPSG 2154") && e.contains("not supported"),
        "{e}"
    );
}

#[test]
fn geographic_dem_frame_agrees_with_the_reader() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("wgs84.tif");
    let cell = 1.0 / 3600.0;
    write_geotiff(
        &path,
        50,
        40,
        (cell, cell),
        (105.6, -10.4),
        &[(1024, 2), (1025, 1), (2048, 4326)],
    );
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let f = LocalFrame::from_dem(&dem).unwrap();
    for (x, y) in [(0.0, 0.0), (300.0, 900.0), (1500.0, 1200.0)] {
        let g = f.to_geodetic(DVec3::new(x, y, 0.0)).unwrap();
        let (lon, lat) = dem.local_to_world(x, y).unwrap();
        assert!((g.lat_deg - lat).abs() < 1e-12 && (g.lon_deg - lon).abs() < 1e-12);
        let back = f.from_geodetic(g).unwrap();
        assert!(back.distance(DVec3::new(x, y, 0.0)) < 1e-6);
    }
}

#[test]
fn a_geographic_dem_across_the_antimeridian_gives_longitudes_in_range_and_none_past_a_pole() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dateline.tif");
    // 200 x 200 cells of 0.0001 deg from longitude 179.99: the last 0.01 deg are east of 180.
    let keys = [(1024, 2), (1025, 1), (2048, 4326)];
    write_geotiff(&path, 200, 200, (1e-4, 1e-4), (179.99, 10.0), &keys);
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let f = LocalFrame::from_dem(&dem).unwrap();
    let (_, _, x1, y1) = dem.terrain.extent();
    let east = f.to_geodetic(DVec3::new(x1, y1, 0.0)).unwrap();
    assert!((-180.0..-179.97).contains(&east.lon_deg), "{east:?}");
    // A point east of 180 lies inside the raster, not 40,000 km west of it.
    let back = f
        .from_geodetic(Geodetic::new(9.995, -179.995, 0.0))
        .unwrap();
    assert!(
        (0.0..=x1).contains(&back.x) && (0.0..=y1).contains(&back.y),
        "{back:?}"
    );
    let again = f.to_geodetic(back).unwrap();
    assert!((again.lon_deg + 179.995).abs() < 1e-9, "{again:?}");
    // West of the antimeridian, as before.
    let west = f.from_geodetic(Geodetic::new(9.995, 179.995, 0.0)).unwrap();
    assert!(west.x > 0.0 && west.x < back.x, "{west:?} {back:?}");

    let path = dir.path().join("past-pole.tif");
    write_geotiff(&path, 50, 40, (1e-3, 1e-3), (10.0, 95.0), &keys);
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let e = LocalFrame::from_dem(&dem).unwrap_err().to_string();
    assert!(
        e.contains("beyond the poles") && e.contains("past-pole.tif"),
        "{e}"
    );
}

#[test]
fn spso_reference_dem_is_georeferenced_when_present() {
    let Some(path) =
        swarmplan_io::reference_data::reference_file("spso/ChrismasTerrain.tif").unwrap()
    else {
        return;
    };
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let f = LocalFrame::from_dem(&dem).unwrap();
    let o = f.origin().unwrap();
    println!(
        "SPSO DEM south-west node: {:.8}, {:.8}",
        o.lat_deg, o.lon_deg
    );
    assert!(
        (-10.6..-10.3).contains(&o.lat_deg) && (105.5..105.8).contains(&o.lon_deg),
        "{o:?}"
    );
    let (_, _, x1, y1) = dem.terrain.extent();
    let ne = f.to_geodetic(DVec3::new(x1, y1, 0.0)).unwrap();
    assert!(ne.lat_deg > o.lat_deg && ne.lon_deg > o.lon_deg);
    let back = f.from_geodetic(ne).unwrap();
    assert!(back.distance(DVec3::new(x1, y1, 0.0)) < 0.01);
}

// ------------------------------------------------------------------ scenario new

fn new_request<'a>(path: &'a Path, start: Geodetic, goal: Geodetic) -> NewScenarioRequest<'a> {
    NewScenarioRequest {
        terrain: path,
        terrain_source: "dem.tif".into(),
        start,
        goal,
        uavs: 3,
        agl: 150.0,
        name: "dem-test".into(),
        margin: None,
    }
}

#[test]
fn scenario_new_names_a_dem_whose_corners_are_no_places_on_earth() {
    // 1e6 m cells put the far corner 200,000 km east: no inverse projection exists there.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("utm-huge.tif");
    write_geotiff(
        &path,
        200,
        200,
        (1e6, 1e6),
        (566_710.0, 8_842_640.0),
        &MGA48,
    );
    let somewhere = Geodetic::new(-10.0, 105.0, 0.0);
    let e = new_scenario(&new_request(&path, somewhere, somewhere))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("--terrain: expected a DEM whose corners are places on Earth")
            && e.contains("utm-huge.tif"),
        "{e}"
    );
}

#[test]
fn scenario_new_places_start_and_goal_and_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dem.tif");
    write_geotiff(
        &path,
        120,
        100,
        (10.0, 10.0),
        (566_710.0, 8_842_640.0),
        &MGA48,
    );
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let f = LocalFrame::from_dem(&dem).unwrap();
    let start = f.to_geodetic(DVec3::new(100.0, 120.0, 0.0)).unwrap();
    let goal = f.to_geodetic(DVec3::new(1000.0, 850.0, 0.0)).unwrap();
    let new = new_scenario(&new_request(&path, start, goal)).unwrap();
    let spec = &new.spec;
    assert_eq!(spec.uavs.len(), 3);
    for u in &spec.uavs {
        assert!((u.start[0] - 100.0).abs() < 0.01 && (u.start[1] - 120.0).abs() < 0.01);
        assert_eq!(u.start[2], 150.0);
    }
    assert!((spec.goal.position[0] - 1000.0).abs() < 0.01);
    assert!((spec.goal.position[1] - 850.0).abs() < 0.01);
    assert_eq!(spec.map.x, [0.0, 1190.0]);
    assert_eq!(spec.map.y, [0.0, 990.0]);
    assert!(spec.threats.is_empty() && spec.communication.interference.is_empty());
    let d = 900.0_f64.hypot(730.0);
    assert!((spec.communication.range - 700.0 * d / 600.0_f64.hypot(700.0)).abs() < 0.1);
    assert!((new.origin.lat_deg - f.origin().unwrap().lat_deg).abs() < 1e-12);

    // Written next to the DEM, the TOML reads back (with its [geo] table) and builds.
    let text = scenario_toml_with_origin(spec, new.origin, "test header\nsecond line");
    assert!(text.starts_with("# test header\n# second line\n"));
    let toml_path = dir.path().join("dem-test.toml");
    std::fs::write(&toml_path, &text).unwrap();
    let (loaded, origin) = load_spec_with_origin(toml_path.to_str().unwrap()).unwrap();
    assert_eq!(origin, Some(new.origin));
    // (Field by field: a core that knows `[geo]` adds it to the spec.)
    assert_eq!(loaded.spec.name, spec.name);
    assert_eq!(loaded.spec.uavs, spec.uavs);
    assert_eq!(loaded.spec.goal, spec.goal);
    assert_eq!(loaded.spec.map, spec.map);
    assert_eq!(loaded.spec.terrain, spec.terrain);
    assert_eq!(loaded.spec.communication, spec.communication);
    let world = build_world(&loaded, None).unwrap();
    // The DEM's grid wins over [geo] origin, and export + re-import keeps the cost.
    let (frame, source) = resolve_frame(&loaded, origin, None, None).unwrap();
    assert_eq!(source, FrameSource::Dem);
    let starts: Vec<DVec3> = (0..3).map(|i| world.start(i)).collect();
    let plan = Plan::straight(&starts, world.goal_at(swarmplan_core::world::DEPARTURE), 4);
    let out = dir.path().join("out");
    let files = export_plan(&world, &plan, &frame, ExportFormat::Csv, &out).unwrap();
    let again = read_exported_plan(&files[0], &world, &frame).unwrap();
    let (a, b) = (
        assess_as_searched(&world, &plan),
        assess_as_searched(&world, &again),
    );
    assert!((a.total - b.total).abs() < 1e-6, "{} {}", a.total, b.total);
}

#[test]
fn scenario_new_errors_name_the_flag() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dem.tif");
    write_geotiff(
        &path,
        60,
        50,
        (10.0, 10.0),
        (566_710.0, 8_842_640.0),
        &MGA48,
    );
    let dem = read_terrain(&path, &DemOptions::default()).unwrap();
    let f = LocalFrame::from_dem(&dem).unwrap();
    let inside = f.to_geodetic(DVec3::new(100.0, 100.0, 0.0)).unwrap();
    let inside2 = f.to_geodetic(DVec3::new(400.0, 300.0, 0.0)).unwrap();
    let far = Geodetic::new(-10.0, 105.0, 0.0);
    let e = new_scenario(&new_request(&path, far, inside))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("--start: expected a point inside the DEM"),
        "{e}"
    );
    assert!(e.contains("latitude") && e.contains("-10,105"), "{e}");
    let e = new_scenario(&new_request(&path, inside, far))
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("--goal:"), "{e}");
    let e = new_scenario(&new_request(&path, inside, inside))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--goal") && e.contains("1 m from --start"),
        "{e}"
    );
    let mut req = new_request(&path, inside, inside2);
    req.uavs = 0;
    let e = new_scenario(&req).unwrap_err().to_string();
    assert!(e.starts_with("--uavs"), "{e}");
    let missing = dir.path().join("missing.tif");
    let e = new_scenario(&new_request(&missing, inside, inside2))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("--terrain") && e.contains("missing.tif"),
        "{e}"
    );
    let asc = dir.path().join("grid.asc");
    std::fs::write(
        &asc,
        "ncols 3\nnrows 3\nxllcorner 0\nyllcorner 0\ncellsize 10\n1 2 3\n4 5 6\n7 8 9\n",
    )
    .unwrap();
    let e = new_scenario(&new_request(&asc, inside, inside2))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("--terrain") && e.contains("no EPSG code"),
        "{e}"
    );
    let e = parse_lat_lon("-91,105", "--start").unwrap_err().to_string();
    assert!(
        e.contains("--start: latitude must be a number in [-90, 90]"),
        "{e}"
    );
}
