//! Named benchmark suites: lists of scenarios that `bench --suite NAME` runs, so a
//! comparison over many instances is one flag and the same instances on every machine.
//!
//! Why generated instances: one hand-made scenario per case ranks methods on that case
//! only (Shehadeh & Kudela 2025, arXiv 2501.14503, rank UAV planners over 56 instances).
//! The generated suites are drawn by `scenario generate` from their seeds, and each is named
//! by its request (`gen-s3-u8-t12-w1`), so a record's scenario name rebuilds its instance
//! and resumed or sharded runs need nothing but the names.

use swarmplan_io::generate::GenerateRequest;

/// Instances per generated size.
pub const GENERATED_INSTANCES: u64 = 20;
/// Threats per generated instance.
pub const GENERATED_THREATS: usize = 12;
/// Interference windows per generated instance.
pub const GENERATED_WINDOWS: usize = 1;
/// Fleet sizes of the generated suites.
pub const GENERATED_SIZES: [usize; 3] = [8, 12, 20];

/// A suite's name and what it holds, for `--help` and errors.
pub const SUITES: [(&str, &str); 7] = [
    ("paper", "paper-case1 and paper-case2"),
    (
        "outside",
        "the 4 outside benchmark instances, 5 UAVs (needs ../shared/data/outside)",
    ),
    (
        "outside-delay",
        "the same with departure delays free (timing.max_delay 0.3: outside-K-delay)",
    ),
    (
        "generated-8",
        "20 generated instances, 8 UAVs, 12 threats, 1 interference window, spread starts",
    ),
    ("generated-12", "the same with 12 UAVs"),
    ("generated-20", "the same with 20 UAVs"),
    (
        "generated",
        "generated-8, generated-12 and generated-20 (60 instances)",
    ),
];

/// The generated instances with `uavs` UAVs (seeds 1 to [`GENERATED_INSTANCES`]).
fn generated(uavs: usize) -> impl Iterator<Item = String> {
    (1..=GENERATED_INSTANCES).map(move |seed| {
        GenerateRequest {
            seed,
            uavs,
            threats: GENERATED_THREATS,
            shared_start: false,
            comm_windows: GENERATED_WINDOWS,
            terrain: None,
            free_pace: false,
            free_delays: false,
        }
        .name()
    })
}

/// The scenarios of suite `name`, or `None` for an unknown name.
#[must_use]
pub fn suite(name: &str) -> Option<Vec<String>> {
    let list: Vec<String> = match name {
        "paper" => vec!["paper-case1".into(), "paper-case2".into()],
        "outside" => (0..swarmplan_io::outside::INSTANCES)
            .map(|k| format!("outside-{k}"))
            .collect(),
        "outside-delay" => (0..swarmplan_io::outside::INSTANCES)
            .map(|k| format!("outside-{k}-delay"))
            .collect(),
        "generated" => GENERATED_SIZES.into_iter().flat_map(generated).collect(),
        _ => {
            let uavs: usize = name.strip_prefix("generated-")?.parse().ok()?;
            if !GENERATED_SIZES.contains(&uavs) {
                return None;
            }
            generated(uavs).collect()
        }
    };
    Some(list)
}

/// The names of every suite, comma-separated.
#[must_use]
pub fn suite_names() -> String {
    SUITES.map(|(n, _)| n).join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarmplan_io::catalog::load_spec;

    #[test]
    fn every_suite_lists_distinct_loadable_scenarios() {
        for (name, _) in SUITES {
            let list = suite(name).unwrap_or_else(|| panic!("{name} is listed"));
            let mut sorted = list.clone();
            sorted.sort();
            sorted.dedup();
            assert_eq!(sorted.len(), list.len(), "{name} repeats a scenario");
        }
        assert_eq!(suite("generated").unwrap().len(), 60);
        let eight = suite("generated-8").unwrap();
        assert_eq!(eight[2], "gen-s3-u8-t12-w1");
        // Every instance name rebuilds a scenario of that name and size.
        for name in [&eight[0], &suite("generated-20").unwrap()[19]] {
            let loaded = load_spec(name).unwrap();
            assert_eq!(&loaded.spec.name, name);
            assert_eq!(loaded.spec.threats.len(), GENERATED_THREATS);
        }
        assert_eq!(load_spec(&eight[0]).unwrap().spec.uavs.len(), 8);
    }

    #[test]
    fn unknown_suites_are_none() {
        for bad in ["", "generated-9", "generated-", "generated-x", "Paper"] {
            assert_eq!(suite(bad), None, "{bad}");
        }
    }
}
