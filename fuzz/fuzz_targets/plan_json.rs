//! Plan JSON read into the `tiny` world, then evaluated in full (the time bound is
//! libFuzzer's -timeout): whatever parses must evaluate without a panic or a hang.
#![no_main]

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use swarmplan_core::cost::assess;
use swarmplan_core::world::World;
use swarmplan_io::plan_file::{parse_plan, Provenance};
use swarmplan_io::catalog::load_spec;
use swarmplan_io::scenario::build_world;

fn world() -> &'static World {
    static WORLD: OnceLock<World> = OnceLock::new();
    WORLD.get_or_init(|| build_world(&load_spec("tiny").unwrap(), None).unwrap())
}

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    if let Ok(plan) = parse_plan(text, "fuzz.json", world(), Provenance::AllowOther) {
        let a = assess(world(), &plan);
        assert!(!a.total.is_nan(), "a NaN cost");
    }
});
