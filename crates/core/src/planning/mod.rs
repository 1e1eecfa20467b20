//! The planning problem as optimizers see it: a world, an encoding, and an evaluation that
//! decodes a vector into a plan and assesses it.
//!
//! Evaluation is pure but needs buffers; each thread keeps its own (`thread_local!`) so a
//! problem can be shared by reference across threads without locks and without allocating
//! per evaluation.

use std::cell::RefCell;

use crate::cost::{assess, assess_bounded, assess_into, Assessment, Cutoff, Scratch};
use crate::encoding::init::{
    sample_band_plan, sample_corridor_plan, sample_fan_plan, sample_line_plan,
};
use crate::encoding::{self, EncodingKind, InitKind, PathEncoding, PathFrame};
use crate::feasibility::ViolationSink;
use crate::plan::Plan;
use crate::problem::{fill_uniform, BlockProblem, Bound, Evaluation, Problem};
use crate::rng::Rng;
use crate::world::World;

/// A plan that is not of the shape an encoding decodes to.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShapeError {
    /// The plan's number of UAVs differs from the scenario's.
    #[error("the plan has {got} UAVs; the scenario has {expected}")]
    Uavs {
        /// UAVs in the scenario.
        expected: usize,
        /// UAVs in the plan.
        got: usize,
    },
    /// A UAV's number of waypoints differs from what the encoding decodes to.
    #[error(
        "UAV {uav} has {got} waypoints (start and goal included); the scenario's encoding has {expected} (planning.waypoints free ones between start and goal)"
    )]
    Waypoints {
        /// Index of the UAV.
        uav: usize,
        /// Waypoints the encoding gives it, start and goal included.
        expected: usize,
        /// Waypoints the plan gives it, start and goal included.
        got: usize,
    },
}

/// A world with an encoding and an initialisation.
pub struct PlanningProblem<'w> {
    world: &'w World,
    encoding: Box<dyn PathEncoding>,
    kind: EncodingKind,
    init: InitKind,
    frame: PathFrame,
    /// Threat-free corridors per UAV, computed once for the `corridor` initialisation.
    corridors: crate::encoding::corridor::Corridors,
    /// The `band` initialisation's seeds (empty otherwise).
    band: crate::encoding::banded::BandSeeds,
}

/// Slots of [`Problem::evaluate_cost_bounded_in`] with buffers of their own (per thread);
/// higher slots share the thread's common buffers. ABC's default has 25 food sources.
pub const BUFFER_SLOTS: usize = 64;

mod local_moves;

pub use local_moves::{NUDGE_DELAY_SHARE, NUDGE_SEPARATIONS, SHIFT_SEPARATIONS, ZONE_MOVE_SHARE};

thread_local! {
    static BUFFERS: RefCell<(Plan, Scratch)> = RefCell::new((Plan::default(), Scratch::default()));
    static SLOT_BUFFERS: RefCell<Vec<(Plan, Scratch)>> = const { RefCell::new(Vec::new()) };
}

impl<'w> PlanningProblem<'w> {
    /// The problem of `world` in encoding `kind` from initialisation `init` (searching the
    /// corridors when `init` is `corridor`); a free pace or free delays add their variables.
    #[must_use]
    pub fn new(world: &'w World, kind: EncodingKind, init: InitKind) -> Self {
        if init == InitKind::Band {
            let band = encoding::banded::band_seeds(world);
            let climbs = encoding::banded::seeded_climbs(world, &band);
            let mut problem = Self::with_guides(world, kind, init, band.guides.clone(), &climbs);
            problem.band = band;
            return problem;
        }
        let corridors = match init {
            InitKind::Corridor => encoding::corridor::corridors(world),
            InitKind::Route => encoding::routed::route_guides(world),
            _ => Vec::new(),
        };
        Self::with_corridors(world, kind, init, corridors)
    }

    /// [`Self::new`] with the corridors of an earlier problem on the same world
    /// ([`Self::corridors`]), so that a caller that rebuilds the problem (the Python
    /// binding, per call) does not search them again.
    #[must_use]
    pub fn with_corridors(
        world: &'w World,
        kind: EncodingKind,
        init: InitKind,
        corridors: crate::encoding::corridor::Corridors,
    ) -> Self {
        Self::with_guides(world, kind, init, corridors, &[])
    }

    /// [`Self::with_corridors`] with the climb angles of seeded moves that the encoding
    /// must be able to express ([`encoding::build_along`]).
    fn with_guides(
        world: &'w World,
        kind: EncodingKind,
        init: InitKind,
        corridors: crate::encoding::corridor::Corridors,
        climbs: &[Vec<f64>],
    ) -> Self {
        let mut path_encoding = encoding::build_along(kind, world, &corridors, climbs);
        let timing = &world.spec().timing;
        if timing.pace_is_free() {
            path_encoding = Box::new(encoding::paced::Paced::new(
                path_encoding,
                world.uav_count(),
                timing.pace,
            ));
        }
        if timing.delay_is_free() {
            path_encoding = Box::new(encoding::delayed::Delayed::new(
                path_encoding,
                world.uav_count(),
                timing.max_delay,
            ));
        }
        Self {
            world,
            encoding: path_encoding,
            kind,
            init,
            frame: PathFrame::of(world),
            corridors,
            band: crate::encoding::banded::BandSeeds::default(),
        }
    }

    /// How its starting points are drawn.
    #[must_use]
    pub fn init(&self) -> InitKind {
        self.init
    }

    /// The threat-free corridors the `corridor` initialisation follows (empty otherwise).
    #[must_use]
    pub fn corridors(&self) -> &[Vec<glam::DVec2>] {
        &self.corridors
    }

    /// Whether `plan` has the shape this encoding decodes to (its UAV count and each UAV's
    /// number of waypoints, start and goal included), as [`Self::encode`] needs.
    pub fn check_shape(&self, plan: &Plan) -> Result<(), ShapeError> {
        let lower: Vec<f64> = self.encoding.bounds().iter().map(|b| b.lo).collect();
        let shape = self.encoding.decode(&lower);
        if plan.uavs.len() != shape.uavs.len() {
            return Err(ShapeError::Uavs {
                expected: shape.uavs.len(),
                got: plan.uavs.len(),
            });
        }
        for (uav, (p, s)) in plan.uavs.iter().zip(&shape.uavs).enumerate() {
            if p.waypoints.len() != s.waypoints.len() {
                return Err(ShapeError::Waypoints {
                    uav,
                    expected: s.waypoints.len(),
                    got: p.waypoints.len(),
                });
            }
        }
        Ok(())
    }

    /// The decision vector nearest to `plan` in this encoding; `plan` must have its shape
    /// ([`Self::check_shape`]).
    #[must_use]
    pub fn encode(&self, plan: &Plan) -> Vec<f64> {
        let mut x = vec![0.0; self.encoding.bounds().len()];
        self.encoding.encode_into(plan, &mut x);
        x
    }

    /// Block `block` of `plan`'s encoding, written into `out` (the moves of
    /// [`Problem::nudge`] and [`Problem::shifted_copy`] edit a decoded plan).
    fn write_block(&self, plan: &Plan, block: usize, out: &mut [f64]) {
        let size = self.block_size();
        let encoded = self.encode(plan);
        out.copy_from_slice(&encoded[block * size..(block + 1) * size]);
    }

    /// The world it plans in.
    #[must_use]
    pub fn world(&self) -> &World {
        self.world
    }

    /// The encoding its decision vectors are in.
    #[must_use]
    pub fn encoding(&self) -> EncodingKind {
        self.kind
    }

    /// The plan that `x` decodes to.
    #[must_use]
    pub fn decode(&self, x: &[f64]) -> Plan {
        self.encoding.decode(x)
    }

    /// Full assessment (with the violation list) of the plan that `x` decodes to.
    #[must_use]
    pub fn assess(&self, x: &[f64]) -> Assessment {
        assess(self.world, &self.decode(x))
    }
}

impl PlanningProblem<'_> {
    /// [`Problem::evaluate_cost_bounded`] on the given buffers.
    fn cost_bounded_on(
        &self,
        x: &[f64],
        cutoff: f64,
        plan: &mut Plan,
        scratch: &mut Scratch,
    ) -> Option<Evaluation> {
        self.encoding.decode_into(x, plan);
        let mut sink = ViolationSink::new(self.world.spec().planning.profile);
        assess_bounded(
            self.world,
            plan,
            scratch,
            &mut sink,
            false,
            Cutoff::cost(cutoff),
        )
        .map(|(cost, violation)| Evaluation::new(cost, violation))
    }

    /// A pace uniform in the scenario's range when it is free (no draw otherwise, so runs
    /// on a fixed pace keep their random streams).
    fn draw_pace(&self, rng: &mut Rng, plan: &mut Plan) {
        let [lo, hi] = self.world.spec().timing.pace;
        if self.world.spec().timing.pace_is_free() {
            let u: f64 = rand::Rng::random(rng);
            plan.pace = lo + u * (hi - lo);
        }
    }

    /// Each UAV's departure delay uniform in [0, max_delay] when delays are free (no draw
    /// otherwise).
    fn draw_delays(&self, rng: &mut Rng, plan: &mut Plan) {
        let timing = &self.world.spec().timing;
        plan.delays.clear();
        if timing.delay_is_free() {
            for _ in 0..self.world.uav_count() {
                let u: f64 = rand::Rng::random(rng);
                plan.delays.push(u * timing.max_delay);
            }
        }
    }
}

impl Problem for PlanningProblem<'_> {
    fn bounds(&self) -> &[Bound] {
        self.encoding.bounds()
    }

    fn evaluate(&self, x: &[f64]) -> Evaluation {
        BUFFERS.with(|b| {
            let mut b = b.borrow_mut();
            let (plan, scratch) = &mut *b;
            self.encoding.decode_into(x, plan);
            let mut sink = ViolationSink::new(self.world.spec().planning.profile);
            let (cost, violation) = assess_into(self.world, plan, scratch, &mut sink, false);
            Evaluation::new(cost, violation)
        })
    }

    /// Gives up once the total cost is known to pass `cutoff` ([`crate::cost::assess_bounded`]).
    fn evaluate_cost_bounded(&self, x: &[f64], cutoff: f64) -> Option<Evaluation> {
        BUFFERS.with(|b| {
            let mut b = b.borrow_mut();
            let (plan, scratch) = &mut *b;
            self.cost_bounded_on(x, cutoff, plan, scratch)
        })
    }

    /// The slot's buffers keep the flown arcs and the pair terms of its last point, so a
    /// candidate that changes one UAV of it rebuilds one path and sweeps n - 1 pairs
    /// (the same bits: the caches are pure functions of their inputs).
    fn evaluate_cost_bounded_in(&self, x: &[f64], cutoff: f64, slot: usize) -> Option<Evaluation> {
        if slot >= BUFFER_SLOTS {
            return self.evaluate_cost_bounded(x, cutoff);
        }
        SLOT_BUFFERS.with(|b| {
            let mut slots = b.borrow_mut();
            if slots.len() <= slot {
                slots.resize_with(slot + 1, Default::default);
            }
            let (plan, scratch) = &mut slots[slot];
            self.cost_bounded_on(x, cutoff, plan, scratch)
        })
    }

    fn sample_initial(&self, rng: &mut Rng, out: &mut [f64]) {
        let mut plan = Plan::default();
        match self.init {
            InitKind::Uniform => return fill_uniform(self.encoding.bounds(), rng, out),
            InitKind::Line | InitKind::LineCorridor | InitKind::LineBand => {
                sample_line_plan(&self.frame, rng, &mut plan);
            }
            InitKind::Corridor | InitKind::Route => {
                sample_corridor_plan(&self.frame, &self.corridors, rng, &mut plan);
            }
            InitKind::Fan => sample_fan_plan(&self.frame, rng, &mut plan),
            InitKind::Band => {
                let terrain = self.world.terrain();
                let ground = |q: glam::DVec2| terrain.height(q.x, q.y);
                sample_band_plan(&self.frame, &self.band, &ground, rng, &mut plan);
            }
        }
        self.draw_pace(rng, &mut plan);
        self.draw_delays(rng, &mut plan);
        self.encoding.encode_into(&plan, out);
    }
    fn blocks(&self) -> Option<&dyn BlockProblem> {
        Some(self)
    }
}
