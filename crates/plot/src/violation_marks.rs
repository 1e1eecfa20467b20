//! What the figures mark of a plan's broken constraints: the segments that cross a threat,
//! dip under the clearance or climb too steeply, and the places of the other violations
//! with a place (a turn, an altitude or map-box breach, a separation breach between two
//! UAVs). Contact losses are marked by the outage trace ([`crate::sampling`]), which shows
//! every step out of contact, not only the first.
//!
//! Why here and not in the model: the model reports each violation with its UAV, index and
//! position ([`swarmplan_core::feasibility::Violation`]); a figure needs them grouped into
//! what to draw, and violations without a place (speed, payload, energy) counted for the
//! legend so that an infeasible picture never looks clean. Soft violations (the `paper`
//! profile's cost-only kinds) are not marked.

use glam::DVec3;
use swarmplan_core::feasibility::{check, Violation, ViolationKind};
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;

use crate::legend::{Entry, Shape};
use crate::style::{self, Scale};

/// A segment of one UAV's path that breaks a constraint along its length.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BadSegment {
    pub uav: usize,
    /// Ends at absolute altitude.
    pub ends: [DVec3; 2],
    pub kind: ViolationKind,
}

/// A place where a constraint breaks.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct BadPlace {
    pub uav: usize,
    /// At absolute altitude.
    pub at: DVec3,
    /// Short label: the kind, and for separation the pair (`sep 0-3`).
    pub label: String,
}

/// Everything a figure marks of `plan`'s violations.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct ViolationMarks {
    pub segments: Vec<BadSegment>,
    pub places: Vec<BadPlace>,
    /// Violations that have no place (speed, payload, energy), by kind name.
    pub unplaced: Vec<(&'static str, usize)>,
}

/// Kinds whose index names the segment k (waypoints k to k + 1) along which they break.
fn is_segment_kind(kind: ViolationKind) -> bool {
    matches!(
        kind,
        ViolationKind::Threat | ViolationKind::Terrain | ViolationKind::Climb
    )
}

impl ViolationMarks {
    /// The marks of `plan` in `world` (one assessment with the violation list).
    pub(crate) fn new(world: &World, plan: &Plan) -> Self {
        let timed = TimedPlan::new(world, plan);
        Self::from_violations(&check(world, plan), |uav, k| {
            let abs = &timed.paths.get(uav)?.abs;
            Some([*abs.get(k)?, *abs.get(k + 1)?])
        })
    }

    /// Groups `violations`; `segment(uav, k)` gives segment k's ends of `uav`.
    pub(crate) fn from_violations(
        violations: &[Violation],
        segment: impl Fn(usize, usize) -> Option<[DVec3; 2]>,
    ) -> Self {
        let mut marks = Self::default();
        for v in violations.iter().filter(|v| v.hard) {
            if v.kind == ViolationKind::Comm {
                continue;
            }
            if is_segment_kind(v.kind) {
                if let Some(ends) = v.index.and_then(|k| segment(v.uav, k)) {
                    let seg = BadSegment {
                        uav: v.uav,
                        ends,
                        kind: v.kind,
                    };
                    if !marks.segments.contains(&seg) {
                        marks.segments.push(seg);
                    }
                }
            }
            // Threat crossings are the segments themselves; every other placed kind gets a
            // marker (terrain at its worst point, separation at the closest approach).
            match v.position.map(DVec3::from_array) {
                Some(at) if v.kind != ViolationKind::Threat => {
                    let label = match (v.kind, v.other) {
                        (ViolationKind::Separation, Some(o)) => format!("sep {}-{o}", v.uav),
                        (kind, _) => kind.name().to_string(),
                    };
                    marks.places.push(BadPlace {
                        uav: v.uav,
                        at,
                        label,
                    });
                }
                Some(_) => {}
                None => match marks.unplaced.iter_mut().find(|(k, _)| *k == v.kind.name()) {
                    Some((_, n)) => *n += 1,
                    None => marks.unplaced.push((v.kind.name(), 1)),
                },
            }
        }
        marks
    }

    /// The legend entries of the marks drawn (none for a plan without violations).
    pub(crate) fn legend_entries(&self, s: Scale) -> Vec<Entry> {
        let mut e = Vec::new();
        if !self.segments.is_empty() {
            e.push(Entry::line(
                "violating segment",
                style::VIOLATION,
                s.px(9.0),
            ));
        }
        if !self.places.is_empty() {
            e.push(Entry::marker(
                "violation (kind)",
                Shape::Diamond,
                style::VIOLATION,
            ));
        }
        if let Some(note) = self.unplaced_note() {
            e.push(Entry::Note(note));
        }
        e
    }

    /// One legend line for the violations without a place, e.g. `also: speed 2, energy 1`.
    pub(crate) fn unplaced_note(&self) -> Option<String> {
        if self.unplaced.is_empty() {
            return None;
        }
        let parts: Vec<String> = self
            .unplaced
            .iter()
            .map(|(k, n)| format!("{k} {n}"))
            .collect();
        Some(format!("not drawn: {}", parts.join(", ")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn violation(kind: ViolationKind, uav: usize, index: Option<usize>) -> Violation {
        Violation {
            kind,
            uav,
            other: None,
            index,
            position: index.map(|k| [k as f64, 0.0, 100.0]),
            time: None,
            amount: 1.0,
            detail: String::new(),
            hard: true,
        }
    }

    fn segment(uav: usize, k: usize) -> Option<[DVec3; 2]> {
        (k < 3).then(|| {
            let a = DVec3::new(k as f64, uav as f64, 100.0);
            [a, a + DVec3::X]
        })
    }

    #[test]
    fn segment_kinds_mark_their_segment_and_point_kinds_their_place() {
        let mut sep = violation(ViolationKind::Separation, 1, Some(2));
        sep.other = Some(4);
        let vs = [
            violation(ViolationKind::Threat, 0, Some(1)),
            violation(ViolationKind::Threat, 0, Some(1)),
            violation(ViolationKind::Turn, 2, Some(1)),
            sep,
            violation(ViolationKind::Terrain, 3, Some(0)),
            violation(ViolationKind::Comm, 0, Some(0)),
            violation(ViolationKind::Speed, 0, None),
            violation(ViolationKind::Speed, 1, None),
            violation(ViolationKind::Energy, 1, None),
        ];
        let m = ViolationMarks::from_violations(&vs, segment);
        // Two threat violations on one segment mark it once; terrain marks its segment too.
        let kinds: Vec<_> = m.segments.iter().map(|s| (s.uav, s.kind)).collect();
        assert_eq!(
            kinds,
            [(0, ViolationKind::Threat), (3, ViolationKind::Terrain)]
        );
        assert_eq!(m.segments[0].ends, segment(0, 1).unwrap());
        let labels: Vec<_> = m.places.iter().map(|p| p.label.as_str()).collect();
        assert_eq!(labels, ["turn", "sep 1-4", "terrain"]);
        assert_eq!(m.unplaced, [("speed", 2), ("energy", 1)]);
        assert_eq!(
            m.unplaced_note().as_deref(),
            Some("not drawn: speed 2, energy 1")
        );
    }

    #[test]
    fn a_feasible_plan_has_no_marks() {
        let m = ViolationMarks::from_violations(&[], segment);
        assert_eq!(m, ViolationMarks::default());
        assert!(m.legend_entries(Scale::of((1200, 900))).is_empty());
        assert_eq!(m.unplaced_note(), None);
    }
}
