//! What `plan` says after INFEASIBLE (issue 46, "honest outcomes"): either that no plan
//! exists, with the reason and its numbers, or that none was found, with what is left and
//! what the route layer knows of the way.
//!
//! Why: "INFEASIBLE" alone reads the same for a scenario that admits no plan and for one
//! the search did not solve; an operator needs to know which, and what to change.

use glam::DVec2;

use crate::cost::Assessment;
use crate::route::RouteMap;
use crate::world::unreachable::unreachable_feasibility;
use crate::world::World;

/// Widest margin beyond the hard zones that the route layer looks for, m.
const WIDEST_CAP_M: f64 = 100.0;

/// The line that follows an infeasible plan's verdict: `no plan exists: ...` when a cause
/// rules out every plan ([`unreachable_feasibility`]), else `none found: ...`; `None` for a
/// feasible plan.
#[must_use]
pub fn infeasible_outcome(world: &World, assessment: &Assessment) -> Option<String> {
    if assessment.feasible() {
        return None;
    }
    let spec = world.spec();
    let causes = unreachable_feasibility(spec);
    if let Some(first) = causes.first() {
        let more = match causes.len() {
            1 => String::new(),
            n => format!(" ({} more causes, listed in the warnings above)", n - 1),
        };
        return Some(format!("no plan exists: {first}{more}"));
    }
    let goal = world.goal_at(crate::world::DEPARTURE).truncate();
    let mut ways = Vec::new();
    let mut seen: Vec<(DVec2, f64)> = Vec::new();
    for (k, u) in spec.uavs.iter().enumerate() {
        let start = DVec2::new(u.start[0], u.start[1]);
        if seen.contains(&(start, u.size)) {
            continue;
        }
        seen.push((start, u.size));
        let map = RouteMap::new(&spec.map, &spec.threats, u.size);
        if let Some(m) = map.widest_margin(start, goal, WIDEST_CAP_M) {
            let width = if m >= WIDEST_CAP_M {
                format!("at least {WIDEST_CAP_M:.0} m")
            } else {
                format!("{m:.1} m")
            };
            ways.push(format!(
                "from UAV {k}'s start the widest way between the threats keeps {width} beyond their hard zones (route grid, {:.1} m cells)",
                map.cell()
            ));
        }
    }
    let counts = count_by_kind(assessment);
    Some(format!(
        "none found: the search ended with {counts} left, but no cause rules every plan out; {}",
        if ways.is_empty() {
            "the route layer found no way to measure".to_string()
        } else {
            ways.join("; ")
        }
    ))
}

/// `N hard violations (kind n, ...)`, from the assessment's list when it has one.
fn count_by_kind(a: &Assessment) -> String {
    let Some(list) = a.violations.as_deref() else {
        return format!("a violation measure of {:.1}", a.violation);
    };
    let mut counts = std::collections::BTreeMap::new();
    for v in list.iter().filter(|v| v.hard) {
        *counts.entry(v.kind.name()).or_insert(0_usize) += 1;
    }
    let n: usize = counts.values().sum();
    let kinds: Vec<String> = counts.iter().map(|(k, n)| format!("{k} {n}")).collect();
    format!("{n} hard violations ({})", kinds.join(", "))
}
