//! What `plan` says after INFEASIBLE (issue 46, "honest outcomes"): either that no plan
//! exists, with the reason and its numbers, or that none was found, with what is left and
//! what the route layer knows of the way.
//!
//! Why: "INFEASIBLE" alone reads the same for a scenario that admits no plan and for one
//! the search did not solve; an operator needs to know which, and what to change.

use glam::DVec2;

use crate::band_route::{band_ways, BandWays};
use crate::cost::Assessment;
use crate::route::RouteMap;
use crate::world::spec::ScenarioSpec;
use crate::world::unreachable::unreachable_in_world;
use crate::world::World;

/// Widest margin beyond the hard zones that the route layer looks for, m.
const WIDEST_CAP_M: f64 = 100.0;

/// The line that follows an infeasible plan's verdict: `no plan exists: ...` when a cause
/// rules out every plan ([`unreachable_in_world`]), else `none found: ...`; `None` for a
/// feasible plan.
#[must_use]
pub fn infeasible_outcome(world: &World, assessment: &Assessment) -> Option<String> {
    infeasible_outcome_searched(world, assessment, true)
}

/// [`infeasible_outcome`], searching in height ([`crate::band_route`], a second or so per
/// start) only when `in_height` (a caller under a time limit leaves it out and says so).
#[must_use]
pub fn infeasible_outcome_searched(
    world: &World,
    assessment: &Assessment,
    in_height: bool,
) -> Option<String> {
    if assessment.feasible() {
        return None;
    }
    let spec = world.spec();
    let causes = unreachable_in_world(world);
    if let Some(first) = causes.first() {
        let more = match causes.len() {
            1 => String::new(),
            n => format!(" ({} more causes, listed in the warnings above)", n - 1),
        };
        return Some(format!("no plan exists: {first}{more}"));
    }
    let found = if in_height {
        ways_in_world(world)
    } else {
        ways(spec)
    };
    let mut ways: Vec<String> = found.into_iter().map(|w| w.sentence()).collect();
    if !in_height && !ways.is_empty() {
        ways.push(
            "the route layer in height was left out under the time limit (`scenario check` runs it)"
                .to_string(),
        );
    }
    match unsearched_starts(spec) {
        0 => {}
        n => ways.push(format!("{n} further starts not searched")),
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

/// What the route layer finds for one start (and the UAVs that share it and its size).
#[derive(Debug, Clone, PartialEq)]
pub struct StartWays {
    /// The UAVs flying from this start.
    pub uavs: Vec<usize>,
    /// The route grid's cell, m.
    pub cell: f64,
    /// A lower bound on the length of any way to UAV0's goal around the hard zones, m
    /// (`None`: no way).
    pub shortest_at_least: Option<f64>,
    /// The widest way's margin beyond the hard zones, m, capped at 100 m (`None`: no way).
    pub widest_margin: Option<f64>,
    /// What the route layer finds in height ([`crate::band_route`]), for the first UAV of
    /// the start; `None` where the terrain was not at hand ([`ways`]).
    pub band: Option<BandWays>,
    /// What to change when the way in height is out of every ground node's sight for longer
    /// than tolerated ([`relay_advice`]).
    pub advice: Option<String>,
}

impl StartWays {
    /// One sentence for humans.
    #[must_use]
    pub fn sentence(&self) -> String {
        let who = match self.uavs.as_slice() {
            [k] => format!("from UAV {k}'s start"),
            many => format!(
                "from the start of UAVs {}",
                many.iter()
                    .map(usize::to_string)
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
        };
        let planar = match (self.shortest_at_least, self.widest_margin) {
            (Some(l), Some(m)) => {
                let width = if m >= WIDEST_CAP_M {
                    format!("at least {WIDEST_CAP_M:.0} m")
                } else {
                    format!("{m:.1} m")
                };
                format!(
                    "{who} the widest way between the threats keeps {width} beyond their hard zones and the shortest is at least {l:.0} m long (route grid, {:.1} m cells)",
                    self.cell
                )
            }
            (Some(l), None) => format!(
                "{who} a way around the threats' hard zones can pass only through a gap narrower than the route grid resolves ({:.1} m cells; at least {l:.0} m long)",
                self.cell
            ),
            (None, _) => format!(
                "{who} no way around the threats' hard zones reaches UGV0 (route grid, {:.1} m cells)",
                self.cell
            ),
        };
        let with_band = match &self.band {
            Some(b) => format!("{planar}; {}", b.sentence()),
            None => planar,
        };
        match &self.advice {
            Some(a) => format!("{with_band}; what to change: {a}"),
            None => with_band,
        }
    }
}

/// The route layer's findings for the first [`crate::route::STARTS_SEARCHED`] distinct
/// starts (and UAV sizes) of `spec`; [`unsearched_starts`] counts the rest.
#[must_use]
pub fn ways(spec: &ScenarioSpec) -> Vec<StartWays> {
    let g = spec.goal.position;
    let goal = DVec2::new(g[0], g[1]);
    let mut out: Vec<(DVec2, f64, StartWays)> = Vec::new();
    for (k, u) in spec.uavs.iter().enumerate() {
        let start = DVec2::new(u.start[0], u.start[1]);
        if let Some((_, _, w)) = out.iter_mut().find(|(s, z, _)| *s == start && *z == u.size) {
            w.uavs.push(k);
            continue;
        }
        if out.len() >= crate::route::STARTS_SEARCHED {
            continue;
        }
        let map = RouteMap::new(&spec.map, &spec.threats, u.size);
        let found = StartWays {
            uavs: vec![k],
            cell: map.cell(),
            shortest_at_least: map.length_lower_bound(start, goal),
            widest_margin: map.widest_margin(start, goal, WIDEST_CAP_M),
            band: None,
            advice: None,
        };
        out.push((start, u.size, found));
    }
    out.into_iter().map(|(_, _, w)| w).collect()
}

/// [`ways`] with the route layer in height for each start searched (a second or so each
/// on the outside instances: [`crate::band_route`]). Only a start whose planar way exists
/// is searched in height.
#[must_use]
pub fn ways_in_world(world: &World) -> Vec<StartWays> {
    let mut out = ways(world.spec());
    for w in &mut out {
        if w.shortest_at_least.is_some() {
            let band = band_ways(
                world,
                w.uavs[0],
                crate::band_route::CELLS_ALONG,
                crate::band_route::LEVELS,
            );
            w.advice = relay_advice(world.spec(), &band);
            w.band = Some(band);
        }
    }
    out
}

/// What an operator can change where even the way that keeps direct ground contact best is
/// out of every ground node's sight for longer than tolerated ([`crate::contact_gap`]): a
/// lone UAV needs a relay or a ground node in sight; a fleet that leaves together under
/// common arrival stays bunched, and launch slots or free departure delays let it string
/// out along the way and relay across (outside-2 and -9: five UAVs 0 of 3 without, 3 of 3
/// with slots; docs/results.md). `None` when contact is not the question or the fleet can
/// already string out.
#[must_use]
pub fn relay_advice(spec: &ScenarioSpec, band: &BandWays) -> Option<String> {
    let gap = band.contact.as_ref()?;
    if !(gap.range.is_infinite() && gap.needs_relays()) {
        return None;
    }
    let timing = &spec.timing;
    if spec.uavs.len() == 1 {
        Some(
            "one UAV cannot relay for itself: add a UAV to relay, or a ground node (communication.ground_nodes) in sight of that stretch"
                .to_string(),
        )
    } else if timing.launch_interval <= 0.0 && !timing.delay_is_free() {
        Some(format!(
            "the {} UAVs leave together, so they cross that stretch together; launch slots (timing.launch_interval) or free departure delays (timing.max_delay) let the fleet string out along the way and relay across it",
            spec.uavs.len()
        ))
    } else {
        None
    }
}

/// How many distinct starts (and UAV sizes) of `spec` the route layer does not search
/// ([`crate::route::STARTS_SEARCHED`]).
#[must_use]
pub fn unsearched_starts(spec: &ScenarioSpec) -> usize {
    let mut seen: Vec<(DVec2, f64)> = Vec::new();
    for u in &spec.uavs {
        let key = (DVec2::new(u.start[0], u.start[1]), u.size);
        if !seen.contains(&key) {
            seen.push(key);
        }
    }
    seen.len().saturating_sub(crate::route::STARTS_SEARCHED)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_stretch_out_of_sight_says_what_to_change_for_one_uav_and_for_a_fleet() {
        // The plateau of `contact_gap`'s test: its middle 400 m are out of both nodes' sight.
        let terrain = crate::band_route::tests::terrain(crate::contact_gap::tests::plateau);
        let mut spec = crate::band_route::tests::world(10, terrain.clone())
            .spec()
            .clone();
        // A coarse grid (20 cells, 3 heights) keeps the test quick; `ways_in_world` asks the
        // same of the full one.
        let advice = |spec: &ScenarioSpec| {
            let w = World::new(spec.clone(), terrain.clone()).unwrap();
            relay_advice(spec, &band_ways(&w, 0, 20, 3))
        };
        let alone = advice(&spec).expect("advice for one UAV");
        assert!(
            alone.starts_with("one UAV cannot relay for itself"),
            "{alone}"
        );
        spec.uavs.push(spec.uavs[0]);
        let fleet = advice(&spec).expect("advice for two UAVs leaving together");
        assert!(
            fleet.contains("launch slots (timing.launch_interval)"),
            "{fleet}"
        );
        spec.timing.launch_interval = 10.0;
        assert_eq!(advice(&spec), None, "slots already string the fleet out");
    }
}
