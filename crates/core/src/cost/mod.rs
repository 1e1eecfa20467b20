//! The objective: SPSO's per-UAV terms plus the paper's cooperative terms (Eq. 2), each
//! reported per UAV and per term, and the hard-constraint measure.
//!
//! J = sum over UAVs of [ b1 J1 + b2 J2 + b3 J3 + b4 J4 (SPSO)
//!                        + w2 J_safety + w3 J_energy + w4 J_comm + w5 J_turning + w6 J_obstacle ]
//!     + penalty x (violation measure)
//!
//! The `spso-mycost` objective preset keeps only SPSO's MyCost (5 J1 + J2 + 10 J3 + J4, +inf on collision)
//! for single-UAV cross-checks. Every term lives in its own file; this one only combines them.
//! [`assess`] is the one entry point: the optimizer's hot path and the report use the same
//! code, the report merely asks for the violation list and exact clearances.

pub mod clearance;
pub mod comm;
pub mod coverage;
pub mod energy;
mod interval_batch;
pub mod kinematics;
mod own_memo;
pub mod proximity;
pub mod safety;
pub mod spso;
mod staged;
pub mod term;

pub use staged::Cutoff;
pub use term::{TermId, Terms, TERM_COUNT};

use serde::{Deserialize, Serialize};

use crate::feasibility::{FeasibilityProfile, Violation, ViolationSink};
use crate::plan::Plan;
use crate::timing::TimedPlan;
use crate::world::spec::ObjectivePreset;
use crate::world::World;

/// A fleet's cost per UAV, as the paper's tables report it: `total` over the number of
/// UAVs (at least 1). The one place this is computed: reports, run records, convergence
/// traces and progress lines all call it.
#[must_use]
pub fn cost_per_uav(total: f64, uavs: usize) -> f64 {
    total / uavs.max(1) as f64
}

/// What a report says about one UAV.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct UavAssessment {
    /// Each term's value before weighting, in its unit ([`TermId::unit`]).
    pub raw: Terms,
    /// Each term's value times its weight in the scenario's `[objective]`.
    pub weighted: Terms,
    /// Weighted sum of this UAV's terms (no penalty).
    pub cost: f64,
    /// Length of the path the UAV flies (with its arcs where it flies them), m.
    pub length_m: f64,
    /// Its constant speed over that length, m/s.
    pub speed_mps: f64,
    /// When it reaches UGV0, s from the fleet's departure.
    pub arrival_s: f64,
    /// Energy the flight takes by the rotary-wing model (docs/model.md, "Energy"), J.
    pub energy_j: f64,
    /// Energy over battery capacity.
    pub battery_ratio: f64,
    /// Minimum clearance above terrain (exact only in reports).
    pub min_clearance_m: f64,
    /// Seconds out of contact with every ground node (communication steps).
    pub outage_s: f64,
}

/// The full assessment of a plan.
#[derive(Debug, Clone, Default, Serialize, Deserialize)]
pub struct Assessment {
    /// What the assessment says of each UAV, in fleet order.
    pub per_uav: Vec<UavAssessment>,
    /// Sum of the UAVs' weighted terms.
    pub terms_cost: f64,
    /// Penalty for hard violations (0 under `spso`, where collisions are +inf instead).
    pub penalty: f64,
    /// terms_cost + penalty, +inf if not finite.
    pub total: f64,
    /// Measure of hard violation: 0 iff feasible.
    pub violation: f64,
    /// Measure of soft violation (kinds the profile counts in the cost only).
    #[serde(default)]
    pub soft_violation: f64,
    /// The feasibility profile it was assessed under.
    #[serde(default)]
    pub profile: FeasibilityProfile,
    /// Every violation by name, UAV, place and time, when the assessment was asked for
    /// them (a report); `None` on the optimizer's hot path.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub violations: Option<Vec<Violation>>,
}

impl Assessment {
    /// No hard constraint is violated (the violation measure is 0).
    #[must_use]
    pub fn feasible(&self) -> bool {
        self.violation == 0.0
    }

    /// One line for humans: `FEASIBLE: ...` or `INFEASIBLE: N violations (kind n, ...)`
    /// (the counts need the violation list, i.e. an assessment made with `report`).
    #[must_use]
    pub fn verdict(&self) -> String {
        let list = self.violations.as_deref().unwrap_or_default();
        let count = |hard: bool| {
            let mut counts = std::collections::BTreeMap::new();
            for v in list.iter().filter(|v| v.hard == hard) {
                *counts.entry(v.kind).or_insert(0_usize) += 1;
            }
            let n: usize = counts.values().sum();
            let by_kind: Vec<String> = counts
                .iter()
                .map(|(k, n)| format!("{} {n}", k.name()))
                .collect();
            (n, by_kind.join(", "))
        };
        let (soft_n, soft) = count(false);
        let soft_note = if soft_n > 0 {
            format!(
                "; {soft_n} soft violations in the cost only ({soft}; profile {})",
                self.profile
            )
        } else {
            String::new()
        };
        if self.feasible() {
            return format!("FEASIBLE: no hard constraint violated{soft_note}");
        }
        let (n, hard) = count(true);
        format!("INFEASIBLE: {n} violations ({hard}){soft_note}")
    }

    /// Cost per UAV, as the paper's tables report it ([`cost_per_uav`]).
    #[must_use]
    pub fn per_uav_cost(&self) -> f64 {
        cost_per_uav(self.total, self.per_uav.len())
    }

    /// Weighted terms summed over UAVs.
    #[must_use]
    pub fn term_totals(&self) -> Terms {
        let mut t = Terms::default();
        for u in &self.per_uav {
            t.add(&u.weighted);
        }
        t
    }
}

/// Buffers reused across evaluations.
#[derive(Debug, Clone, Default)]
pub struct Scratch {
    /// The plan's waypoint polylines, timed.
    pub timed: TimedPlan,
    /// What is flown ([`World::flies_arcs`]): arcs through the corners, timed.
    pub flown: TimedPlan,
    comm: comm::CommScratch,
    comm_out: Vec<comm::CommOutcome>,
    prox: proximity::ProximityScratch,
    prox_out: Vec<f64>,
    reports: Vec<UavAssessment>,
    /// The UAVs' own violations of a bounded assessment, replayed after the rest.
    deferred: Vec<crate::feasibility::Deferred>,
    /// Each UAV's terms on its waypoints in a bounded assessment, kept for its flown terms.
    on_waypoints: Vec<WaypointTerms>,
    /// Each UAV's geometric terms, kept while its waypoints stay the same.
    own_terms: own_memo::OwnMemo,
}

impl Scratch {
    /// The per-UAV reports of the last assessment made on these buffers.
    #[must_use]
    pub fn reports(&self) -> &[UavAssessment] {
        &self.reports
    }

    /// UAV pairs whose proximity the last assessment swept rather than took from the
    /// previous one's (the rest had not moved; [`proximity::proximity`]).
    #[must_use]
    pub fn pairs_swept(&self) -> usize {
        self.prox.pairs_swept()
    }
}

/// Assesses `plan` (allocating) in full: every violation listed with its place, clearances
/// exact. What `evaluate`, `plan.json` and the exports report.
#[must_use]
pub fn assess(world: &World, plan: &Plan) -> Assessment {
    assess_with(world, plan, true)
}

/// Assesses `plan` (allocating) as the optimizers do ([`assess_into`]): totals without the
/// violation list, clearances from the fast terrain table.
#[must_use]
pub fn assess_as_searched(world: &World, plan: &Plan) -> Assessment {
    assess_with(world, plan, false)
}

fn assess_with(world: &World, plan: &Plan, exact: bool) -> Assessment {
    let mut scratch = Scratch::default();
    let profile = world.spec().planning.profile;
    let mut sink = if exact {
        ViolationSink::collecting(profile)
    } else {
        ViolationSink::new(profile)
    };
    let (total, violation) = assess_into(world, plan, &mut scratch, &mut sink, exact);
    let terms_cost = scratch.reports.iter().map(|r| r.cost).sum::<f64>();
    Assessment {
        per_uav: std::mem::take(&mut scratch.reports),
        terms_cost,
        penalty: penalty(world, violation + sink.soft),
        total,
        violation,
        soft_violation: sink.soft,
        profile,
        violations: sink.list,
    }
}

fn penalty(world: &World, violation: f64) -> f64 {
    let o = &world.spec().objective;
    if o.preset == ObjectivePreset::SpsoMycost || violation == 0.0 {
        0.0
    } else {
        o.violation_penalty * violation
    }
}

/// The hot path: assesses `plan` into `scratch` (per-UAV reports in `scratch.reports`) and
/// returns (total cost, violation measure). `exact` makes clearances exact.
pub fn assess_into(
    world: &World,
    plan: &Plan,
    scratch: &mut Scratch,
    sink: &mut ViolationSink,
    exact: bool,
) -> (f64, f64) {
    assess_bounded(world, plan, scratch, sink, exact, Cutoff::NONE)
        .unwrap_or((f64::INFINITY, f64::INFINITY))
}

/// [`assess_into`], given up (`None`) once the plan is known to exceed `cutoff`. Every
/// violation adds at least 1 to the measure and floating-point addition is monotone in each
/// argument, so a partial sum, or a sum over some of the violations, never exceeds the final
/// one (a sum taken in another order may, by rounding, and is compared with a margin:
/// `staged::reordered_lower_bound`); likewise the total cost with the terms not yet known (none
/// of them negative) at zero, and the penalty of the violations found so far, never exceed
/// the final total. A plan given up would have ended above `cutoff`, so an optimizer that only needs
/// to know whether a candidate beats one at the cutoff (by Deb's rules or by penalised cost)
/// learns that exactly, for less.
///
/// One driver serves every assessment, full or bounded, report or hot path
/// (`cost/staged.rs`): the terms are computed in three phases ([`term::Phase`]), the UAVs' own
/// terms first, into a sink that records their violations: every UAV's terms on its
/// waypoints (threat band, altitude, turns, climb, turning radius; under the `spso-mycost` objective preset
/// and a finite cost cutoff they stop at a collision, which makes the cost +inf), checked
/// against the cutoff after each UAV and for cost after all; then the flown paths are built
/// and every UAV's terms on them (arc threats, clearance, speed, battery), checked
/// likewise; then the fleet's: the communication sweep (checked for violation and cost) and
/// proximity (checked for violation), which the `spso-mycost` objective preset does not have. Then the
/// recorded violations (with their places and details when `sink` keeps a list) are added
/// to `sink` after the fleet's, UAV by UAV, so a plan not given up gets the same bits
/// whatever the cutoff.
pub fn assess_bounded(
    world: &World,
    plan: &Plan,
    scratch: &mut Scratch,
    sink: &mut ViolationSink,
    exact: bool,
    cutoff: Cutoff,
) -> Option<(f64, f64)> {
    let n = plan.uavs.len();
    scratch.own_terms.serve(world.id());
    scratch.timed.fill(world, plan);
    scratch.reports.resize_with(n, UavAssessment::default);
    scratch.comm_out.resize(n, comm::CommOutcome::default());
    scratch.prox_out.resize(n, 0.0);
    if !staged::staged_terms(world, plan, scratch, sink, exact, cutoff) {
        return None;
    }
    let mut terms_cost = 0.0;
    let weights = world.spec().objective.weights();
    for (u, r) in scratch.reports.iter_mut().enumerate() {
        r.raw[TermId::Communication] = scratch.comm_out[u].cost;
        r.raw[TermId::Obstacle] = scratch.prox_out[u];
        r.outage_s = scratch.comm_out[u].outage_s;
        r.weighted = r.raw.weighted(&weights);
        r.cost = r.weighted.sum();
        terms_cost += r.cost;
    }
    let violation = sink.measure;
    // Soft violations (under the `paper` profile) cost as much as hard ones; only the
    // feasibility verdict ignores them.
    let total = terms_cost + penalty(world, violation + sink.soft);
    let total = if total.is_nan() { f64::INFINITY } else { total };
    Some((total, violation))
}

/// What the UAVs fly: the flown paths, built into `flown`, when the world flies arcs
/// ([`World::flies_arcs`]), else the waypoint polylines `timed`.
fn fly<'a>(world: &World, timed: &'a TimedPlan, flown: &'a mut TimedPlan) -> &'a TimedPlan {
    if world.flies_arcs() {
        flown.fill_flown(world, timed);
        flown
    } else {
        timed
    }
}

/// The fleet's terms: the communication sweep, then proximity unless the measure already
/// exceeds `cutoff` or `too_costly` says the plan is out of reach given the sweep's
/// results; false when either stops it, or the measure exceeds `cutoff` after proximity
/// (given up).
fn fleet_terms(
    world: &World,
    plan: &Plan,
    motion: &TimedPlan,
    (comm, comm_out, prox, prox_out): FleetBuffers<'_>,
    sink: &mut ViolationSink,
    cutoff: f64,
    too_costly: impl Fn(&ViolationSink, &[comm::CommOutcome]) -> bool,
) -> bool {
    comm::communication(world, motion, comm, sink, comm_out);
    if sink.measure > cutoff || too_costly(sink, comm_out) {
        return false;
    }
    proximity::proximity(world, plan, motion, prox, sink, prox_out);
    sink.measure <= cutoff
}

/// The buffers of [`fleet_terms`], borrowed from [`Scratch`].
type FleetBuffers<'a> = (
    &'a mut comm::CommScratch,
    &'a mut Vec<comm::CommOutcome>,
    &'a mut proximity::ProximityScratch,
    &'a mut Vec<f64>,
);

/// What a UAV's waypoints alone decide: SPSO's terms, the turn and climb limits and, in a
/// world that flies arcs, the turning radius (whether the corners' arcs fit their
/// segments); what follows the UAV in time and space, in [`flown_terms`], is of what is
/// flown.
#[derive(Debug, Clone, Copy, Default)]
struct WaypointTerms {
    spso: spso::SpsoTerms,
    kin: kinematics::Kinematics,
}

impl WaypointTerms {
    /// The raw terms known from the waypoints alone (the others at zero).
    fn raw(&self) -> Terms {
        let mut raw = Terms::default();
        raw[TermId::Length] = self.spso.length;
        raw[TermId::Threat] = self.spso.threat;
        raw[TermId::Altitude] = self.spso.altitude;
        raw[TermId::Smoothness] = self.spso.smoothness;
        raw[TermId::Turning] = self.kin.turn_sq;
        debug_assert!(raw.zero_after(term::Phase::Waypoints));
        raw
    }
}

/// UAV `u`'s terms and constraints on its waypoints, the first part of its own terms.
/// `flown` holds the turns' tangent lengths when the world flies arcs
/// ([`TimedPlan::fill_tangents`]). `collisions` is [`spso::Collisions::Penalised`] but under
/// the `spso-mycost` objective preset; with [`spso::Collisions::InfiniteAndStop`] a UAV whose SPSO terms
/// are +inf gets nothing more (and nothing is memoised, the terms being cut short).
fn waypoint_terms(
    world: &World,
    u: usize,
    plan: &Plan,
    (timed, flown): (&TimedPlan, Option<&TimedPlan>),
    collisions: spso::Collisions,
    memo: &mut own_memo::OwnMemo,
    sink: &mut ViolationSink,
) -> WaypointTerms {
    let key = (
        u,
        plan.uavs[u].waypoints.as_slice(),
        world.spec().uavs[u].turn_radius,
    );
    let memoise = collisions != spso::Collisions::InfiniteAndStop;
    memo.waypoint_terms(key, memoise, sink, |sink| {
        waypoint_terms_afresh(world, u, plan, (timed, flown), collisions, sink)
    })
}

/// [`waypoint_terms`] without the memo.
fn waypoint_terms_afresh(
    world: &World,
    u: usize,
    plan: &Plan,
    (timed, flown): (&TimedPlan, Option<&TimedPlan>),
    collisions: spso::Collisions,
    sink: &mut ViolationSink,
) -> WaypointTerms {
    let tp = &timed.paths[u];
    let spso = spso::spso_terms(world, u, &plan.uavs[u], tp, collisions, sink);
    if collisions == spso::Collisions::InfiniteAndStop && spso.infinite() {
        return WaypointTerms {
            spso,
            ..WaypointTerms::default()
        };
    }
    let terms = WaypointTerms {
        spso,
        kin: kinematics::kinematics(world, u, tp, sink),
    };
    if let Some(flown) = flown {
        crate::flight::check_turn_radius(
            u,
            &tp.abs,
            |k| tp.time_at(k),
            world.spec().uavs[u].turn_radius,
            &flown.paths[u].tangents,
            sink,
        );
    }
    terms
}

/// The rest of UAV `u`'s own terms and constraints, on what it flies (everything but
/// communication and proximity, whose terms, and the weighted terms and cost,
/// [`assess_bounded`] fills in afterwards). The geometric checks (arc threats, map bounds,
/// clearance) come from `memo` for waypoints it has seen, unless clearances are `exact`.
#[allow(clippy::too_many_arguments)] // the parts of one UAV's assessment, named
fn flown_terms(
    world: &World,
    u: usize,
    plan: &Plan,
    (timed, motion): (&TimedPlan, &TimedPlan),
    (flies_arcs, exact): (bool, bool),
    on_waypoints: WaypointTerms,
    memo: &mut own_memo::OwnMemo,
    sink: &mut ViolationSink,
) -> UavAssessment {
    let path = &plan.uavs[u];
    let tp = &timed.paths[u];
    let fp = &motion.paths[u];
    let kin = &on_waypoints.kin;
    let key = (
        u,
        path.waypoints.as_slice(),
        world.spec().uavs[u].turn_radius,
    );
    let min_clearance = memo.flown_checks(key, !exact, sink, |sink| {
        if flies_arcs {
            crate::flight::check_arc_threats(world, u, fp, sink);
        }
        clearance::check_clearance(world, u, (path, tp), fp, exact, sink)
    });
    let segments = tp.abs.len().saturating_sub(1);
    let safety = safety::safety_term(world, u, fp, segments, sink);
    let vertical = energy::Vertical::of(fp);
    let joules = energy::physical_energy(world, u, fp, vertical, kin);
    let battery_ratio = energy::check_battery(world, u, joules, sink);
    let mut raw = on_waypoints.raw();
    raw[TermId::Safety] = safety;
    raw[TermId::Energy] = energy::energy_term(world, fp, vertical, kin);
    debug_assert!(raw.zero_after(term::Phase::Flown));
    UavAssessment {
        raw,
        length_m: fp.length,
        speed_mps: fp.speed,
        arrival_s: fp.arrival,
        energy_j: joules,
        battery_ratio,
        min_clearance_m: min_clearance,
        ..UavAssessment::default()
    }
}
