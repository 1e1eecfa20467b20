//! Feasibility profiles: `paper` moves the cost-only kinds out of the feasibility verdict
//! and assesses the waypoint segments instead of the flown path; with a turning radius of
//! 0 (so the flown path is the waypoint polyline) nothing else changes.

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use swarmplan_core::cost::{assess, assess_as_searched};
use swarmplan_core::feasibility::{FeasibilityProfile, ViolationKind};
use swarmplan_core::plan::Plan;
use swarmplan_io::scenario::build_world;

use swarmplan_io::catalog::load_spec;

#[test]
fn the_paper_profile_counts_only_its_hard_kinds_and_costs_the_same() {
    for case in ["paper-case1", "paper-case2"] {
        let mut loaded = load_spec(case).unwrap();
        let arcs_world = build_world(&loaded, None).unwrap();
        for u in &mut loaded.spec.uavs {
            u.turn_radius = 0.0;
        }
        let strict_world = build_world(&loaded, None).unwrap();
        loaded.spec.planning.profile = FeasibilityProfile::Paper;
        let paper_world = build_world(&loaded, None).unwrap();
        // Straight lines from the shared start: separation at take-off, threat crossings.
        let starts: Vec<_> = (0..strict_world.uav_count())
            .map(|i| strict_world.start(i))
            .collect();
        let plan = Plan::straight(
            &starts,
            strict_world.goal_at(swarmplan_core::world::DEPARTURE),
            10,
        );
        let strict = assess(&strict_world, &plan);
        let paper = assess(&paper_world, &plan);
        // The flown path (radius 50 m) is another trajectory: another cost.
        let arcs = assess(&arcs_world, &plan);
        assert_ne!(arcs.total, strict.total, "{case}");
        let paper_default_radius = {
            let mut l = load_spec(case).unwrap();
            l.spec.planning.profile = FeasibilityProfile::Paper;
            build_world(&l, None).unwrap()
        };
        assert_eq!(
            assess_as_searched(&paper_default_radius, &plan)
                .total
                .to_bits(),
            paper.total.to_bits(),
            "{case}: the paper profile ignores the turning radius"
        );
        let sv = strict.violations.clone().unwrap();
        let pv = paper.violations.clone().unwrap();
        assert_eq!(sv.len(), pv.len(), "{case}: the same violations are found");
        assert!(
            sv.iter().all(|v| v.hard),
            "{case}: strict makes every kind hard"
        );
        assert!(
            sv.iter().any(|v| v.kind == ViolationKind::Separation),
            "{case}: the straight plan should break separation"
        );
        for v in &pv {
            assert_eq!(
                v.hard,
                FeasibilityProfile::Paper.is_hard(v.kind),
                "{case}: {v:?}"
            );
        }
        assert!(pv.iter().any(|v| !v.hard));
        // The cost is the same: soft violations keep their penalty.
        // (Summed in another order, so equal to rounding.)
        assert!(
            (strict.total - paper.total).abs() <= 1e-12 * strict.total.abs(),
            "{case}: {} vs {}",
            strict.total,
            paper.total
        );
        assert!((strict.violation - paper.violation - paper.soft_violation).abs() < 1e-9);
        assert_eq!(paper.feasible(), pv.iter().all(|v| !v.hard), "{case}");
        assert!(
            paper.verdict().contains("soft violations in the cost only"),
            "{}",
            paper.verdict()
        );
        assert_eq!(strict.profile, FeasibilityProfile::Strict);
        assert_eq!(paper.profile, FeasibilityProfile::Paper);
    }
}

#[test]
fn the_profile_is_a_scenario_field() {
    let mut loaded = load_spec("tiny").unwrap();
    assert_eq!(loaded.spec.planning.profile, FeasibilityProfile::Strict);
    loaded.spec.planning.profile = FeasibilityProfile::Paper;
    let text = swarmplan_io::scenario::to_toml(&loaded.spec);
    assert!(text.contains("profile = \"paper\""), "{text}");
    let again = swarmplan_io::scenario::parse_spec(&text, "t").unwrap();
    assert_eq!(again.planning.profile, FeasibilityProfile::Paper);
    let e = swarmplan_io::scenario::parse_spec(
        &text.replace("profile = \"paper\"", "profile = \"lenient\""),
        "t.toml",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("t.toml") && e.contains("profile"), "{e}");
}
