//! SPSO's single-UAV cost terms (Phung & Ha 2021, `MyCost.m`), exactly:
//! - J1: length of the path with absolute altitudes;
//! - J2: threat band: per segment and cylinder, with d the distance from the axis to the
//!   xy-projected segment, 0 beyond r + size + 10 size, collision inside r + size, else
//!   (r + size + 10 size) - d;
//! - J3: sum over free waypoints of |z - (z_min + z_max) / 2| (z above ground; z < 0 crashes);
//! - J4: at each interior waypoint, |turn| if the turn between xy projections exceeds 45 deg
//!   and |change of climb angle| if it exceeds 45 deg (degrees; zero-length projections are
//!   skipped by looking further back / ahead).
//!
//! Under the `spso-mycost` objective preset ([`Collisions::Infinite`]) a collision or a crash makes the term
//! +inf as in SPSO. Otherwise the band keeps growing linearly inside the cylinder, so the
//! search has a slope to follow, and the hard violation is reported to the sink.

use glam::DVec3;

use crate::feasibility::{At, ViolationKind, ViolationSink};
use crate::plan::Path;
use crate::timing::TimedPath;
use crate::world::spec::{ObjectivePreset, ObjectiveSpec};
use crate::world::threat::{point_segment_distance, segment_box_misses};
use crate::world::World;

/// SPSO's danger distance is 10 drone sizes.
pub const DANGER_FACTOR: f64 = 10.0;
/// SPSO's turn and climb-change thresholds (degrees) in J4.
pub const SPSO_SMOOTH_LIMIT_DEG: f64 = 45.0;

/// J1..J4 of one path.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SpsoTerms {
    /// J1: length of the path with absolute altitudes, m.
    pub length: f64,
    /// J2: threat danger-band cost (SPSO's MyCost).
    pub threat: f64,
    /// J3: altitude deviation from the band's centre at the free waypoints, m.
    pub altitude: f64,
    /// J4: turn and climb-angle excess over their limits, deg.
    pub smoothness: f64,
}

impl SpsoTerms {
    /// Whether a collision or a crash made a term +inf (under [`Collisions::Infinite`]).
    #[must_use]
    pub fn infinite(&self) -> bool {
        self.threat == f64::INFINITY || self.altitude == f64::INFINITY
    }
}

/// What a collision with a threat, or a waypoint below ground, costs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Collisions {
    /// The threat band keeps growing inside the cylinder (the violation goes to the sink).
    Penalised,
    /// +inf, as in SPSO's MyCost (the `spso-mycost` objective preset).
    Infinite,
    /// +inf, and the terms stop at the first (the rest at 0, the later violations not
    /// reported): for a bounded assessment, to which a plan costing +inf is of no use.
    InfiniteAndStop,
}

impl Collisions {
    /// What a collision costs under `objective` for an assessment that only matters below
    /// `cost_cutoff` (+inf: a full one): +inf under the `spso-mycost` objective preset, stopping there when the
    /// cutoff is finite; penalised otherwise.
    #[must_use]
    pub fn of(objective: &ObjectiveSpec, cost_cutoff: f64) -> Self {
        match (objective.preset, cost_cutoff < f64::INFINITY) {
            (ObjectivePreset::Cooperative, _) => Self::Penalised,
            (ObjectivePreset::SpsoMycost, false) => Self::Infinite,
            (ObjectivePreset::SpsoMycost, true) => Self::InfiniteAndStop,
        }
    }
}

/// Computes J1..J4 for UAV `uav` and reports threat and altitude violations.
pub fn spso_terms(
    world: &World,
    uav: usize,
    path: &Path,
    tp: &TimedPath,
    collisions: Collisions,
    sink: &mut ViolationSink,
) -> SpsoTerms {
    let size = world.spec().uavs[uav].size;
    let mut terms = SpsoTerms {
        length: tp.length,
        threat: threat_term(world, uav, size, path, tp, collisions, sink),
        ..SpsoTerms::default()
    };
    let stop = collisions == Collisions::InfiniteAndStop;
    if stop && terms.infinite() {
        return terms;
    }
    terms.altitude = altitude_term(world, uav, path, tp, collisions, sink);
    if stop && terms.infinite() {
        return terms;
    }
    terms.smoothness = smoothness_term(path, &tp.abs);
    terms
}

fn threat_term(
    world: &World,
    uav: usize,
    size: f64,
    path: &Path,
    tp: &TimedPath,
    collisions: Collisions,
    sink: &mut ViolationSink,
) -> f64 {
    let inf = collisions != Collisions::Penalised;
    let danger = DANGER_FACTOR * size;
    let mut j2 = 0.0;
    let w = &path.waypoints;
    for t in &world.spec().threats {
        let hard = t.r + size;
        let outer = hard + danger;
        for k in 0..w.len().saturating_sub(1) {
            let (a, b) = (w[k], w[k + 1]);
            // Cheap reject: both ends far beyond the band on the same side is not enough,
            // but a segment whose bounding box misses the band's box is clear.
            if segment_box_misses(t, a, b, outer) {
                continue;
            }
            let d = point_segment_distance((t.x, t.y), (a.x, a.y), (b.x, b.y));
            if d > outer {
                continue;
            }
            if d < hard {
                if inf {
                    j2 = f64::INFINITY;
                } else {
                    j2 += outer - d;
                }
                sink.add(
                    ViolationKind::Threat,
                    uav,
                    hard - d,
                    At {
                        index: Some(k),
                        position: Some(tp.abs[k].lerp(tp.abs[k + 1], 0.5)),
                        time: Some(0.5 * (tp.time_at(k) + tp.time_at(k + 1))),
                        ..At::default()
                    },
                    || {
                        format!(
                            "segment {k} passes {d:.1} m from the axis of threat ({:.0}, {:.0}, r {:.0}); limit {hard:.1} m",
                            t.x, t.y, t.r
                        )
                    },
                );
                if collisions == Collisions::InfiniteAndStop {
                    return j2;
                }
            } else {
                j2 += outer - d;
            }
        }
    }
    j2
}

fn altitude_term(
    world: &World,
    uav: usize,
    path: &Path,
    tp: &TimedPath,
    collisions: Collisions,
    sink: &mut ViolationSink,
) -> f64 {
    let inf = collisions != Collisions::Penalised;
    let [zmin, zmax] = world.spec().map.z_agl;
    let mid = 0.5 * (zmin + zmax);
    let w = &path.waypoints;
    let mut j3 = 0.0;
    for k in 1..w.len().saturating_sub(1) {
        let z = w[k].z;
        j3 += if z < 0.0 && inf {
            if collisions == Collisions::InfiniteAndStop {
                return f64::INFINITY;
            }
            f64::INFINITY
        } else {
            (z - mid).abs()
        };
        let excess = (zmin - z).max(z - zmax);
        if excess > 1e-9 {
            sink.add(
                ViolationKind::Altitude,
                uav,
                excess,
                At {
                    index: Some(k),
                    position: Some(tp.abs[k]),
                    time: Some(tp.time_at(k)),
                    ..At::default()
                },
                || format!("waypoint {k} is {z:.1} m above ground; band [{zmin}, {zmax}] m"),
            );
        }
    }
    j3
}

fn norm2(v: (f64, f64)) -> f64 {
    (v.0 * v.0 + v.1 * v.1).sqrt()
}

/// (horizontal, vertical) of a segment for the climb angle; atan2(0, 0) = 0 in SPSO, so a
/// null vector stands for a level one.
fn climb_vector(h: f64, v: f64) -> (f64, f64) {
    if h == 0.0 && v == 0.0 {
        (1.0, 0.0)
    } else {
        (h, v)
    }
}

/// SPSO's J4 on the waypoints (xy from `path`, absolute z from `abs`).
#[must_use]
pub fn smoothness_term(path: &Path, abs: &[DVec3]) -> f64 {
    let w = &path.waypoints;
    let n = w.len();
    let proj = |j: usize| (w[j + 1].x - w[j].x, w[j + 1].y - w[j].y);
    let mut j4 = 0.0;
    for i in 0..n.saturating_sub(2) {
        // Segment i (waypoints i -> i+1), looking back past zero-length projections.
        let mut s1 = proj(i);
        let mut j = i;
        while s1 == (0.0, 0.0) && j > 0 {
            j -= 1;
            s1 = proj(j);
        }
        // Segment i+1, looking ahead past zero-length projections.
        let mut s2 = proj(i + 1);
        let mut j = i + 1;
        while s2 == (0.0, 0.0) && j + 1 < n - 1 {
            j += 1;
            s2 = proj(j);
        }
        // The angles only count beyond 45 deg, so each atan2 is taken only then: a turn
        // exceeds 45 deg iff |cross| > dot, and so does a change of climb angle, computed
        // as the angle between the (horizontal, vertical) vectors of the two segments.
        let cross = (s1.0 * s2.1 - s1.1 * s2.0).abs();
        let dot = s1.0 * s2.0 + s1.1 * s2.1;
        if cross > dot {
            let turn = cross.atan2(dot).to_degrees();
            if turn > SPSO_SMOOTH_LIMIT_DEG {
                j4 += turn;
            }
        }
        let (h1, v1) = climb_vector(norm2(s1), abs[i + 1].z - abs[i].z);
        let (h2, v2) = climb_vector(norm2(s2), abs[i + 2].z - abs[i + 1].z);
        let (c, d) = (h1 * v2 - v1 * h2, h1 * h2 + v1 * v2);
        if c.abs() > d {
            let dclimb = (v2.atan2(h2) - v1.atan2(h1)).abs().to_degrees();
            if dclimb > SPSO_SMOOTH_LIMIT_DEG {
                j4 += dclimb;
            }
        }
    }
    j4
}
