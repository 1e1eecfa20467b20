//! Scenarios that no plan can make feasible, found before any search.
//!
//! A start inside a threat's hard zone, a goal under a threat, a start below ground or a
//! payload above the airframe's maximum are valid numbers, so validation accepts them; but
//! every plan then violates a hard constraint, and a search would spend its whole budget to
//! report INFEASIBLE. The CLI prints these as warnings when it loads a scenario (planning
//! still runs: the user may want the least-bad plan, or be testing the model).

use glam::DVec2;

use super::enclosure::walled_in_starts;
use super::spec::ScenarioSpec;
use super::threat::Threat;
use super::validate::number;

/// One reason no plan can be feasible: the field at fault and why.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Unreachable {
    /// Path of the field at fault (`uavs[2].start`).
    pub field: String,
    /// Why it rules out every feasible plan, for humans.
    pub reason: String,
}

impl std::fmt::Display for Unreachable {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{}: {}; no plan can be feasible",
            self.field, self.reason
        )
    }
}

/// Every cause found in `spec` (empty when none is known). Needs no terrain, so a bench can
/// check its scenarios before building any world.
#[must_use]
pub fn unreachable_feasibility(spec: &ScenarioSpec) -> Vec<Unreachable> {
    let mut out = Vec::new();
    let g = spec.goal.position;
    let goal = DVec2::new(g[0], g[1]);
    for (k, u) in spec.uavs.iter().enumerate() {
        let start = DVec2::new(u.start[0], u.start[1]);
        for (j, t) in spec.threats.iter().enumerate() {
            let centre = DVec2::new(t.x, t.y);
            let hard = t.r + u.size;
            let d = start.distance(centre);
            if d < hard {
                out.push(Unreachable {
                    field: format!("uavs[{k}].start"),
                    reason: in_threat(start, d, j, t, u.size),
                });
            }
        }
        if u.start[2] < 0.0 {
            out.push(Unreachable {
                field: format!("uavs[{k}].start"),
                reason: format!(
                    "its height above ground is {} m, below the terrain",
                    u.start[2]
                ),
            });
        }
        let cruise = spec.timing.policy == super::spec::TimingPolicy::Cruise;
        // The `cruise` policy flies pace x cruise, the pace within timing.pace.
        let [lo, hi] = spec.timing.pace;
        let reachable = u.cruise_speed * hi >= u.speed[0] && u.cruise_speed * lo <= u.speed[1];
        if cruise && !reachable {
            let paced = if spec.timing.pace_is_free() {
                format!(" times a pace in timing.pace [{lo}, {hi}]")
            } else {
                String::new()
            };
            out.push(Unreachable {
                field: format!("uavs[{k}].cruise_speed"),
                reason: format!(
                    "{} m/s{paced} is outside uavs[{k}].speed [{}, {}] m/s and the `cruise` timing policy flies every segment at it",
                    u.cruise_speed, u.speed[0], u.speed[1]
                ),
            });
        }
        if u.payload_kg > u.max_payload_kg {
            out.push(Unreachable {
                field: format!("uavs[{k}].payload_kg"),
                reason: format!(
                    "{} kg is above max_payload_kg {} kg",
                    u.payload_kg, u.max_payload_kg
                ),
            });
        }
    }
    // The smallest UAV decides whether the goal itself is reachable.
    let size = spec
        .uavs
        .iter()
        .map(|u| u.size)
        .fold(f64::INFINITY, f64::min);
    for (j, t) in spec.threats.iter().enumerate() {
        let d = goal.distance(DVec2::new(t.x, t.y));
        if d < t.r + size {
            out.push(Unreachable {
                field: "goal.position".into(),
                reason: in_threat(goal, d, j, t, size),
            });
        }
    }
    if g[2] < 0.0 {
        out.push(Unreachable {
            field: "goal.position".into(),
            reason: format!("its height above ground is {} m, below the terrain", g[2]),
        });
    }
    walled_in(spec, &mut out);
    battery_short(spec, |_| 0.0, &mut out);
    out
}

/// [`unreachable_feasibility`] with what the terrain adds: the battery bound counts the
/// net climb from each UAV's start to UGV0 (absolute altitudes), which every plan flies at
/// least (metres climbed sum the rises, and the rises outweigh the falls by the net climb).
#[must_use]
pub fn unreachable_in_world(world: &super::World) -> Vec<Unreachable> {
    let spec = world.spec();
    let mut out = unreachable_feasibility(spec);
    out.retain(|c| !c.field.ends_with(".battery_wh"));
    let goal = world.absolute(world.goal_at(super::DEPARTURE)).z;
    battery_short(
        spec,
        |k| (goal - world.absolute(world.start(k)).z).max(0.0),
        &mut out,
    );
    out
}

/// One entry per UAV whose usable battery cannot cover even the shortest way around the
/// threats ([`crate::route::RouteMap::length_lower_bound`], at the route grid's resolution)
/// at its most economical speed plus m g times `net_climb(k)` (metres UAV k must rise from
/// its start to UGV0): a lower bound on the energy of every plan (further climbs, turns and
/// hovering only add to it).
fn battery_short(
    spec: &ScenarioSpec,
    net_climb: impl Fn(usize) -> f64,
    out: &mut Vec<Unreachable>,
) {
    let goal = DVec2::new(spec.goal.position[0], spec.goal.position[1]);
    let mut bounds: Vec<(DVec2, f64, Option<f64>)> = Vec::new();
    // UAVs alike (same start, size and energy settings) are named in their first one's entry.
    let alike = |a: &super::spec::UavSpec, b: &super::spec::UavSpec| {
        a.start == b.start
            && a.size == b.size
            && a.battery_wh == b.battery_wh
            && a.reserve == b.reserve
            && a.payload_kg == b.payload_kg
            && a.speed == b.speed
    };
    for (k, u) in spec.uavs.iter().enumerate() {
        if spec.uavs[..k].iter().any(|v| alike(u, v)) {
            continue;
        }
        let others: Vec<usize> = (k + 1..spec.uavs.len())
            .filter(|&j| alike(u, &spec.uavs[j]))
            .collect();
        let start = DVec2::new(u.start[0], u.start[1]);
        let length = match bounds.iter().find(|(s, z, _)| *s == start && *z == u.size) {
            Some(&(_, _, l)) => l,
            // Past the starts the route layer searches, no bound is claimed.
            None if bounds.len() >= crate::route::STARTS_SEARCHED => continue,
            None => {
                let map = crate::route::RouteMap::new(&spec.map, &spec.threats, u.size);
                let l = map.length_lower_bound(start, goal);
                bounds.push((start, u.size, l));
                l
            }
        };
        let Some(length) = length else {
            // No way: said by `walled_in` when the start is walled in; otherwise the
            // threats wall the goal off, which only the route grid sees.
            // Already said: a start walled in or in a hard zone, a goal in a hard zone.
            let start_field = format!("uavs[{k}].start");
            let walled = out
                .iter()
                .any(|c| c.field == start_field || c.field == "goal.position");
            let first_of_start = spec.uavs[..k]
                .iter()
                .all(|v| v.start[..2] != u.start[..2] || v.size != u.size);
            if !walled && first_of_start {
                out.push(Unreachable {
                    field: "threats".into(),
                    reason: format!(
                        "no way from uavs[{k}].start ({}, {}) to the goal ({}, {}) passes between their hard zones (radius + UAV size {}), even on a route grid that shrinks each by half a cell diagonal ({:.1} m cells): they wall the goal off",
                        u.start[0],
                        u.start[1],
                        goal.x,
                        goal.y,
                        number(u.size),
                        crate::route::RouteMap::new(&spec.map, &[], u.size).cell()
                    ),
                });
            }
            continue;
        };
        let model = &spec.energy.model;
        let (speed, cruise) =
            most_economical(|v| model.power(v, u.payload_kg) * length / v, u.speed);
        let rise = net_climb(k);
        let climb = model.mass(u.payload_kg) * super::energy::G * rise;
        let joules = cruise + climb;
        let usable = (1.0 - u.reserve) * u.battery_wh * 3600.0;
        if joules > usable {
            out.push(Unreachable {
                field: format!("uavs[{k}].battery_wh"),
                reason: format!(
                    "the shortest way around the threats is at least {length:.0} m (route grid, {:.1} m cells), {cruise:.0} J at its most economical speed {speed:.1} m/s{}, so at least {joules:.0} J, more than the usable {usable:.0} J ({} Wh less a {} reserve): {:.2} Wh short{}",
                    crate::route::RouteMap::new(&spec.map, &[], u.size).cell(),
                    if rise > 0.0 {
                        format!(", plus {climb:.0} J to rise the {rise:.0} m from its start to UGV0")
                    } else {
                        String::new()
                    },
                    number(u.battery_wh),
                    number(u.reserve),
                    (joules - usable) / 3600.0,
                    if others.is_empty() {
                        String::new()
                    } else {
                        format!(" (so are uavs {}, alike)", list(&others))
                    }
                ),
            });
        }
    }
}

/// The speed in `[lo, hi]` where `energy` is least, and that energy: a golden-section
/// search (the rotary-wing energy per metre is unimodal in speed), then the ends.
pub(crate) fn most_economical(energy: impl Fn(f64) -> f64, [lo, hi]: [f64; 2]) -> (f64, f64) {
    let lo = lo.max(1e-3);
    let hi = hi.max(lo);
    let phi = 0.5 * (5f64.sqrt() - 1.0);
    let (mut a, mut b) = (lo, hi);
    for _ in 0..80 {
        let (c, d) = (b - phi * (b - a), a + phi * (b - a));
        if energy(c) < energy(d) {
            b = d;
        } else {
            a = c;
        }
    }
    [0.5 * (a + b), lo, hi]
        .into_iter()
        .map(|v| (v, energy(v)))
        .fold(
            (lo, f64::INFINITY),
            |best, x| if x.1 < best.1 { x } else { best },
        )
}

/// One entry per start that threats wall off from the goal (UAVs sharing it named once).
fn walled_in(spec: &ScenarioSpec, out: &mut Vec<Unreachable>) {
    let mut groups: Vec<(Vec<usize>, Vec<usize>)> = Vec::new();
    for (k, walls) in walled_in_starts(spec) {
        let start = spec.uavs[k].start;
        match groups
            .iter_mut()
            .find(|(uavs, _)| spec.uavs[uavs[0]].start == start)
        {
            Some((uavs, _)) => uavs.push(k),
            None => groups.push((vec![k], walls)),
        }
    }
    for (uavs, walls) in groups {
        let (k, start) = (uavs[0], spec.uavs[uavs[0]].start);
        let also = if uavs.len() > 1 {
            format!(" (so is the start of uavs {})", list(&uavs[1..]))
        } else {
            String::new()
        };
        out.push(Unreachable {
            field: format!("uavs[{k}].start"),
            reason: format!(
                "({}, {}) is walled off from the goal by the hard zones (radius + UAV size {}) of threats {}: every way out of the region around it inside the map box crosses one{also}",
                start[0],
                start[1],
                spec.uavs[k].size,
                list(&walls)
            ),
        });
    }
}

/// `[a, b, c]` for indices, the middle elided past 12 entries.
fn list(ix: &[usize]) -> String {
    let shown: Vec<String> = if ix.len() > 12 {
        ix[..6]
            .iter()
            .map(usize::to_string)
            .chain(std::iter::once(format!("... ({} in all)", ix.len())))
            .chain(ix[ix.len() - 3..].iter().map(usize::to_string))
            .collect()
    } else {
        ix.iter().map(usize::to_string).collect()
    };
    format!("[{}]", shown.join(", "))
}

fn in_threat(p: DVec2, d: f64, j: usize, t: &Threat, size: f64) -> String {
    format!(
        "({:.1}, {:.1}) is {} m from the axis of threats[{j}] at ({}, {}), inside its hard zone of {} m (radius {} + UAV size {})",
        p.x,
        p.y,
        metres(d, 1),
        t.x,
        t.y,
        metres(t.r + size, 1),
        metres(t.r, 0),
        metres(size, 0)
    )
}

/// A length for a message: with `decimals` decimals, or as [`number`] writes it when that
/// is 0 or the length is huge.
fn metres(v: f64, decimals: usize) -> String {
    if decimals == 0 || v.abs() >= 1e9 {
        number(v)
    } else {
        format!("{v:.decimals$}")
    }
}
