//! Scenario TOML: parse and validate, then build the world when its procedural terrain is
//! small enough for a fuzzer's pace (the terrain size limit itself is a unit test).
#![no_main]

use libfuzzer_sys::fuzz_target;
use swarmplan_io::scenario::{build_world, parse_spec, LoadedSpec};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(spec) = parse_spec(text, "fuzz.toml") else {
        return;
    };
    let p = &spec.terrain.procedural;
    let nodes = (p.width / p.cell + 2.0) * (p.height / p.cell + 2.0);
    if spec.terrain.source != "procedural" || !(nodes <= 250_000.0) {
        return;
    }
    let loaded = LoadedSpec {
        spec,
        origin: "fuzz.toml".into(),
        base_dir: std::path::PathBuf::from("."),
        text: text.to_owned(),
    };
    let _ = build_world(&loaded, None);
});
