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
pub const SUITES: [(&str, &str); 21] = [
    ("paper", "paper-case1 and paper-case2"),
    (
        "outside",
        "the 28 outside benchmark instances outside-0..27, 5 UAVs (needs ../shared/data/outside)",
    ),
    (
        "outside-delay",
        "the same with departure delays free (timing.max_delay 0.3: outside-K-delay)",
    ),
    ("outside-u1", "the same with one UAV (outside-K-u1)"),
    (
        "outside-u1-nocomm",
        "one UAV with communication off (outside-K-u1-nocomm): the route alone",
    ),
    (
        "outside-slots",
        "the same with launch and recovery slots 5 s apart (outside-K-slots; -delay-slots: both)",
    ),
    (
        "outside-dev",
        "the 22 development instances (all but the held-out 7, 11, 15, 19, 23, 27)",
    ),
    ("outside-dev-delay", "the same with departure delays free"),
    ("outside-dev-u1", "the same with one UAV"),
    (
        "outside-dev-u1-nocomm",
        "the same with one UAV, communication off",
    ),
    ("outside-dev-slots", "the same with slots"),
    (
        "outside-dev-delay-slots",
        "the same with slots and delays free",
    ),
    (
        "outside-held",
        "the 6 held-out instances 7, 11, 15, 19, 23, 27: only to report a design already kept",
    ),
    ("outside-held-delay", "the same with departure delays free"),
    ("outside-held-u1", "the same with one UAV"),
    (
        "outside-held-u1-nocomm",
        "the same with one UAV, communication off",
    ),
    ("outside-held-slots", "the same with slots"),
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

/// The outside instances of suite `name` (`outside[-dev|-held][-delay|-u1]`), or `None`
/// when `name` is not of that form.
fn outside(name: &str) -> Option<Vec<String>> {
    use swarmplan_io::outside::{HELD_OUT, INSTANCES};
    let rest = name.strip_prefix("outside")?;
    let (split, rest) = if let Some(r) = rest.strip_prefix("-dev") {
        (Some(false), r)
    } else if let Some(r) = rest.strip_prefix("-held") {
        (Some(true), r)
    } else {
        (None, rest)
    };
    let suffix = match rest {
        "" => "",
        "-delay" => "-delay",
        "-u1" => "-u1",
        "-slots" => "-slots",
        "-delay-slots" => "-delay-slots",
        "-u1-nocomm" => "-u1-nocomm",
        _ => return None,
    };
    Some(
        (0..INSTANCES)
            .filter(|k| split.is_none_or(|held| HELD_OUT.contains(k) == held))
            .map(|k| format!("outside-{k}{suffix}"))
            .collect(),
    )
}

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
            slots: false,
        }
        .name()
    })
}

/// The scenarios of suite `name`, or `None` for an unknown name.
#[must_use]
pub fn suite(name: &str) -> Option<Vec<String>> {
    if let Some(list) = outside(name) {
        return Some(list);
    }
    let list: Vec<String> = match name {
        "paper" => vec!["paper-case1".into(), "paper-case2".into()],
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
        // The outside splits partition the set; held-out instances stay out of dev.
        let (dev, held) = (
            suite("outside-dev").unwrap(),
            suite("outside-held").unwrap(),
        );
        assert_eq!((dev.len(), held.len()), (22, 6));
        assert!(held.contains(&"outside-7".to_string()));
        assert!(!dev.contains(&"outside-7".to_string()));
        assert_eq!(suite("outside-held-u1").unwrap()[5], "outside-27-u1");
        assert_eq!(suite("outside-delay").unwrap().len(), 28);
    }

    #[test]
    fn unknown_suites_are_none() {
        for bad in [
            "",
            "generated-9",
            "generated-",
            "generated-x",
            "Paper",
            "outside-held-u2",
            "outside-",
            "outside-dev-delay-u1",
        ] {
            assert_eq!(suite(bad), None, "{bad}");
        }
    }
}
