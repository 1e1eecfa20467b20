//! A memo of each UAV's own geometric terms: what its waypoints, and the arcs through them,
//! decide whatever the timing.
//!
//! Why: swarmplan's cooperative method and the dimensional-learning probes change one UAV
//! of n between evaluations on the same buffers, yet SPSO's terms, the turn, climb and
//! turning-radius checks, the arcs' threat check and the terrain clearance of the n - 1
//! others were computed again each time. They are pure functions of the UAV's waypoints
//! and turning radius, given the world (the memo is keyed on the world's identity too:
//! thread-local buffers serve every problem evaluated on their thread), and the amounts
//! of their violations do not depend on time (time only places a violation, in a
//! report). So a UAV whose waypoints are bit for bit those of the last evaluation takes
//! these terms from the memo, and their violations are added again in the order they were
//! found, which gives the violation sums the same bits as computing them afresh.
//! Reports (a sink that keeps the list) and exact clearances are never memoised.

use glam::DVec3;

use super::WaypointTerms;
use crate::feasibility::{Deferred, ViolationSink};
use crate::points_key::PointsKey;

/// Per UAV, its memoised terms, in the world they were computed in.
#[derive(Debug, Clone, Default)]
pub(super) struct OwnMemo {
    /// [`crate::world::World::id`] of the world the entries belong to.
    world: Option<u64>,
    entries: Vec<Entry>,
}

/// What one UAV's waypoints decided, and the waypoints and radius they were.
#[derive(Debug, Clone, Default)]
struct Entry {
    waypoints: PointsKey,
    radius: u64,
    /// Its terms on the waypoints, if computed for these waypoints.
    on_waypoints: Option<WaypointTerms>,
    waypoint_violations: Vec<Deferred>,
    /// Its least clearance from the flown path's geometric checks, if computed for these
    /// waypoints.
    flown: Option<f64>,
    flown_violations: Vec<Deferred>,
}

impl Entry {
    /// Whether this entry is of `waypoints` and `radius`; if not, it is made theirs, empty.
    fn bind(&mut self, waypoints: &[DVec3], radius: f64) {
        if self.radius != radius.to_bits() || !self.waypoints.matches(waypoints) {
            self.radius = radius.to_bits();
            self.waypoints.set(waypoints);
            self.on_waypoints = None;
            self.flown = None;
        }
    }
}

impl OwnMemo {
    /// Serves world `id` from now on: the entries of another are forgotten (thread-local
    /// buffers serve every problem evaluated on their thread).
    pub(super) fn serve(&mut self, id: u64) {
        if self.world != Some(id) {
            self.world = Some(id);
            self.entries.clear();
        }
    }

    /// UAV `u`'s terms on `waypoints` (turning radius `radius`): from the memo, its
    /// violations added to `sink` again, or from `compute`, which adds them to the sink it
    /// is given. Without the memo when `sink` keeps the list or `memoise` is false.
    pub(super) fn waypoint_terms(
        &mut self,
        (u, waypoints, radius): (usize, &[DVec3], f64),
        memoise: bool,
        sink: &mut ViolationSink,
        compute: impl FnOnce(&mut ViolationSink) -> WaypointTerms,
    ) -> WaypointTerms {
        self.part((u, waypoints, radius), memoise, sink, compute, |e| {
            (&mut e.on_waypoints, &mut e.waypoint_violations)
        })
    }

    /// UAV `u`'s least clearance from the geometric checks of what it flies, likewise.
    pub(super) fn flown_checks(
        &mut self,
        (u, waypoints, radius): (usize, &[DVec3], f64),
        memoise: bool,
        sink: &mut ViolationSink,
        compute: impl FnOnce(&mut ViolationSink) -> f64,
    ) -> f64 {
        self.part((u, waypoints, radius), memoise, sink, compute, |e| {
            (&mut e.flown, &mut e.flown_violations)
        })
    }

    /// The memoised part `slot` of UAV `u`'s entry, or `compute`d into it.
    fn part<T: Copy>(
        &mut self,
        (u, waypoints, radius): (usize, &[DVec3], f64),
        memoise: bool,
        sink: &mut ViolationSink,
        compute: impl FnOnce(&mut ViolationSink) -> T,
        slot: fn(&mut Entry) -> (&mut Option<T>, &mut Vec<Deferred>),
    ) -> T {
        if !memoise || sink.is_collecting() {
            return compute(sink);
        }
        if self.entries.len() <= u {
            self.entries.resize_with(u + 1, Entry::default);
        }
        let entry = &mut self.entries[u];
        entry.bind(waypoints, radius);
        let (value, found) = slot(entry);
        if let Some(v) = *value {
            sink.replay(found);
            return v;
        }
        // Computed into `sink` itself, recording what it adds: into `found` for the span
        // of the call, or, if the sink records already (a bounded assessment's), from its
        // record.
        let v = match &sink.deferred {
            None => {
                found.clear();
                sink.deferred = Some(std::mem::take(found));
                let v = compute(sink);
                *found = sink.deferred.take().unwrap_or_default();
                v
            }
            Some(record) => {
                let from = record.len();
                let v = compute(sink);
                found.clear();
                found.extend_from_slice(&sink.deferred.as_deref().unwrap_or_default()[from..]);
                v
            }
        };
        *value = Some(v);
        v
    }
}
