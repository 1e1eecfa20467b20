//! Mission CSV and GeoJSON import into the `tiny` world (first byte chooses the format),
//! then evaluation of what imports.
#![no_main]

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use swarmplan_core::cost::assess;
use swarmplan_core::world::World;
use swarmplan_io::geo::{Geodetic, LocalFrame};
use swarmplan_io::import::{parse_csv, parse_geojson};
use swarmplan_io::catalog::load_spec;
use swarmplan_io::scenario::build_world;

fn world() -> &'static World {
    static WORLD: OnceLock<World> = OnceLock::new();
    WORLD.get_or_init(|| build_world(&load_spec("tiny").unwrap(), None).unwrap())
}

fn frame() -> &'static LocalFrame {
    static FRAME: OnceLock<LocalFrame> = OnceLock::new();
    FRAME.get_or_init(|| {
        LocalFrame::tangent(Geodetic {
            lat_deg: 47.0,
            lon_deg: 8.0,
            alt_m: 400.0,
        })
        .unwrap()
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&which, rest)) = data.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let plan = if which % 2 == 0 {
        parse_csv(text, "fuzz.csv", world(), frame())
    } else {
        parse_geojson(text, "fuzz.geojson", world(), frame())
    };
    if let Ok(plan) = plan {
        let a = assess(world(), &plan);
        assert!(!a.total.is_nan(), "a NaN cost");
    }
});
