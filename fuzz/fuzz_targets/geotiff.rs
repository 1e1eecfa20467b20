//! GeoTIFF bytes through the DEM reader (georeferenced and SPSO pixel frames).
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarmplan_io::dem::{read_terrain_bytes, DemOptions};

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.tif");
    for opts in [DemOptions::default(), DemOptions::SPSO] {
        if let Ok(dem) = read_terrain_bytes(path, data.to_vec(), &opts) {
            let (x0, y0, x1, y1) = dem.terrain.extent();
            assert!(dem.terrain.height(0.5 * (x0 + x1), 0.5 * (y0 + y1)).is_finite());
        }
    }
});
