//! ESRI ASCII grid bytes through the DEM reader.
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarmplan_io::dem::{read_terrain_bytes, DemOptions};

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.asc");
    if let Ok(dem) = read_terrain_bytes(path, data.to_vec(), &DemOptions::default()) {
        let (x0, y0, x1, y1) = dem.terrain.extent();
        assert!(dem.terrain.height(0.5 * (x0 + x1), 0.5 * (y0 + y1)).is_finite());
    }
});
