//! The one driver of every assessment, full or bounded: the terms in three phases
//! ([`super::term::Phase`]: each UAV's waypoints, each UAV's flown path, the fleet), and a
//! plan assessed only to learn whether it beats a cutoff given up once it is known not to.
//!
//! Why: most evaluations of a search ask just that (is the moved particle better than its
//! pbest, the candidate than its food source, the probe than what was accepted), and most
//! answers are "no" early: a plan that breaks more constraints on its waypoints than the
//! cutoff allows need not have its arcs built or its fleet swept. The order of the work
//! (waypoint terms, then flown terms, then the communication sweep, then proximity) puts
//! the cheap, decisive parts first; what is found is replayed in one fixed order (the
//! fleet's violations, then each UAV's own), so a plan not given up gets the same bits
//! whatever the cutoff, and a full assessment ([`Cutoff::NONE`], or a report that keeps
//! the violation list) is the same code never giving up ([`super::assess_bounded`]).
//! Under the `spso-mycost` objective preset (SPSO's MyCost, one UAV, no fleet terms) the waypoint terms are
//! the whole cost, and a collision makes it +inf: under a finite cutoff SPSO's terms stop at
//! the first collision and the plan is given up.

use super::spso::Collisions;
use super::{
    comm, fleet_terms, flown_terms, fly, penalty, waypoint_terms, FleetBuffers, Scratch, TermId,
    UavAssessment, WaypointTerms,
};
use crate::feasibility::ViolationSink;
use crate::plan::Plan;
use crate::timing::TimedPlan;
use crate::world::World;

/// What a bounded assessment ([`super::assess_bounded`]) may give up above: a plan whose
/// violation measure exceeds `violation`, or whose total cost exceeds `cost`, is of no use
/// to the caller (+inf: no bound).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cutoff {
    /// The violation measure above which the plan is of no use (+inf: no bound).
    pub violation: f64,
    /// The total cost above which the plan is of no use (+inf: no bound).
    pub cost: f64,
}

impl Cutoff {
    /// No bound: a full assessment.
    pub const NONE: Self = Self {
        violation: f64::INFINITY,
        cost: f64::INFINITY,
    };

    /// Only plans with a violation measure up to `v` matter (Deb's rules against one whose
    /// violation is `v`).
    #[must_use]
    pub const fn violation(v: f64) -> Self {
        Self {
            violation: v,
            ..Self::NONE
        }
    }

    /// Only plans with a total cost up to `c` matter (penalised cost against one costing `c`).
    #[must_use]
    pub const fn cost(c: f64) -> Self {
        Self {
            cost: c,
            ..Self::NONE
        }
    }
}

/// The terms of [`super::assess_bounded`]: every UAV's terms on its waypoints, then (the
/// flown paths built only now) its terms on what it flies, then the fleet's terms, giving up
/// (false) as soon as the plan is known to exceed `cutoff` (never with [`Cutoff::NONE`]).
/// The own violations go to a deferring sink (one that keeps the list too when `sink`
/// does) and are replayed into `sink` after the fleet's, UAV by UAV (waypoint terms, then
/// flown terms).
pub(super) fn staged_terms(
    world: &World,
    plan: &Plan,
    scratch: &mut Scratch,
    sink: &mut ViolationSink,
    exact: bool,
    cutoff: Cutoff,
) -> bool {
    let n = plan.uavs.len();
    let flies_arcs = world.flies_arcs();
    let objective = &world.spec().objective;
    let weights = objective.weights();
    // Under the `spso-mycost` objective preset SPSO's terms are the whole cost and there are no fleet terms;
    // a plan with a collision costs +inf, beyond any finite cutoff, so its terms may stop
    // there.
    let collisions = Collisions::of(objective, cutoff.cost);
    let spso_preset = collisions != Collisions::Penalised;
    let mut own = own_sink(sink, std::mem::take(&mut scratch.deferred));
    // The least the plan can cost: its terms known so far (the rest are >= 0) and the
    // penalty of the violations found so far.
    let least_cost = |reports: &[UavAssessment], own: &ViolationSink| {
        let mut terms = 0.0;
        for r in reports {
            terms += r.raw.weighted(&weights).sum();
        }
        terms
            + penalty(
                world,
                reordered_lower_bound(own.measure + own.soft, own.count),
            )
    };
    let over_violation =
        |own: &ViolationSink| reordered_lower_bound(own.measure, own.count) > cutoff.violation;
    let over_cost = |reports: &[UavAssessment], own: &ViolationSink| {
        cutoff.cost < f64::INFINITY && least_cost(reports, own) > cutoff.cost
    };
    let mut given_up = false;
    scratch.on_waypoints.resize(n, WaypointTerms::default());
    if flies_arcs {
        scratch.flown.fill_tangents(world, &scratch.timed);
    }
    let flown = flies_arcs.then_some(&scratch.flown);
    for u in 0..n {
        let on_waypoints = waypoint_terms(
            world,
            u,
            plan,
            (&scratch.timed, flown),
            collisions,
            &mut scratch.own_terms,
            &mut own,
        );
        scratch.on_waypoints[u] = on_waypoints;
        scratch.reports[u] = UavAssessment {
            raw: on_waypoints.raw(),
            ..UavAssessment::default()
        };
        // A term at +inf makes the total +inf (or NaN, which is +inf too), whatever the
        // weights.
        if over_violation(&own)
            || (collisions == Collisions::InfiniteAndStop && on_waypoints.spso.infinite())
        {
            given_up = true;
            break;
        }
    }
    given_up = given_up || over_cost(&scratch.reports, &own);
    if !given_up {
        let motion = fly(world, &scratch.timed, &mut scratch.flown);
        for u in 0..n {
            scratch.reports[u] = flown_terms(
                world,
                u,
                plan,
                (&scratch.timed, motion),
                (flies_arcs, exact),
                scratch.on_waypoints[u],
                &mut scratch.own_terms,
                &mut own,
            );
            if over_violation(&own) {
                given_up = true;
                break;
            }
        }
        given_up = given_up || over_cost(&scratch.reports, &own);
        if !given_up && !spso_preset {
            let fleet = (
                &mut scratch.comm,
                &mut scratch.comm_out,
                &mut scratch.prox,
                &mut scratch.prox_out,
            );
            given_up = !bounded_fleet_terms(
                world,
                plan,
                motion,
                fleet,
                (&scratch.reports, &own),
                sink,
                cutoff,
            );
        }
    }
    if !given_up {
        replay_own(&mut own, sink);
    }
    scratch.deferred = own.deferred.take().unwrap_or_default();
    !given_up
}

/// The sink of the own phases: it records every violation into `buffer`, and keeps the
/// list too when `sink` does.
fn own_sink(sink: &ViolationSink, buffer: Vec<crate::feasibility::Deferred>) -> ViolationSink {
    let own = if sink.is_collecting() {
        ViolationSink::collecting(sink.profile)
    } else {
        ViolationSink::new(sink.profile)
    };
    own.deferring(buffer)
}

/// Adds the own phases' violations to `sink`, after the fleet's: UAV by UAV, waypoint terms
/// before flown terms (a stable sort: within one UAV's share of either part the order found
/// stands).
fn replay_own(own: &mut ViolationSink, sink: &mut ViolationSink) {
    if let Some(d) = &mut own.deferred {
        d.sort_by_key(|v| v.uav);
    }
    if let Some(list) = &mut own.list {
        list.sort_by_key(|v| v.uav);
    }
    own.replay_into(sink);
}

/// The fleet's terms of a bounded assessment ([`fleet_terms`]), given up (false) once the
/// violation passes `cutoff.violation` or, after the communication sweep, the least the
/// plan can cost (all but the obstacle term, with the violations found so far in `own`
/// and the fleet's) passes `cutoff.cost`.
fn bounded_fleet_terms(
    world: &World,
    plan: &Plan,
    motion: &TimedPlan,
    fleet: FleetBuffers<'_>,
    (reports, own): (&[UavAssessment], &ViolationSink),
    sink: &mut ViolationSink,
    cutoff: Cutoff,
) -> bool {
    let weights = world.spec().objective.weights();
    let too_costly = |fleet: &ViolationSink, comm_out: &[comm::CommOutcome]| {
        if cutoff.cost == f64::INFINITY {
            return false;
        }
        let mut terms = 0.0;
        for (r, c) in reports.iter().zip(comm_out) {
            let mut raw = r.raw;
            raw[TermId::Communication] = c.cost;
            terms += raw.weighted(&weights).sum();
        }
        let measure = fleet.measure + own.measure + fleet.soft + own.soft;
        let count = fleet.count + own.count;
        terms + penalty(world, reordered_lower_bound(measure, count)) > cutoff.cost
    };
    fleet_terms(
        world,
        plan,
        motion,
        fleet,
        sink,
        cutoff.violation,
        too_costly,
    )
}

/// What a full assessment's sum of a plan's violations is at least, given `partial`, the
/// sum of `count` of them added in another order. Rounding makes sums of m positive terms
/// in two orders differ by at most about 2 m 2^-53 of their value, so below a million
/// violations a margin of 1e-9 covers it (beyond, no bound is claimed: 0).
pub(super) fn reordered_lower_bound(partial: f64, count: usize) -> f64 {
    if count < 1_000_000 {
        partial * (1.0 - 1e-9)
    } else {
        0.0
    }
}
