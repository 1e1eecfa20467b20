//! Initialisation: where a method's first population comes from.
//!
//! Part of a method's definition, as much as its optimizer and encoding: PSO on waypoint
//! coordinates drawn uniformly in the whole box starts from zig-zag plans that cross the map
//! (about 45 turn violations and 54 threat crossings each on Case 1), which is not how its
//! literature builds it. Phase-angle PSO for UAV routes (Fu, Ding, Zhou 2012, IEEE Trans.
//! Syst. Man Cybern. A 42(2):511-526) places the waypoints on planes across the start-goal
//! line; the `line` initialisation does that with a smooth random bow so each path is
//! flyable-looking from the start. Uniform phases in the angle encoding also pile
//! coordinates at the box edges (sin of a uniform angle has the arcsine law); going through
//! the `line` sampler and [`super::PathEncoding::encode_into`] avoids that too.
//!
//! Every sampler stays inside the decision box and draws only from the `&mut Rng` it is
//! given, so a run is still reproducible from its seed.

use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

use glam::{DVec2, DVec3};
use rand::seq::SliceRandom as _;
use rand::Rng as _;
use serde::{Deserialize, Serialize};

use super::corridor::resample;
use super::PathFrame;
use crate::plan::Plan;
use crate::rng::Rng;

/// How the first population is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum InitKind {
    /// Uniform in the decision box (SPSO's code; the ablation for PSO and APSO).
    Uniform,
    /// Free waypoints on equally spaced planes across each UAV's start-goal line, displaced
    /// sideways by a smooth random bow `a1 sin(pi t) + a2 sin(2 pi t)` with
    /// `|a1| <= LINE_SPREAD L`, `|a2| <= LINE_SPREAD L / 2` (L the start-goal distance), at a
    /// random height above ground held along the path; then encoded.
    Line,
    /// Free waypoints on the UAV's threat-free corridor ([`super::corridor`]; at its corners
    /// and spread by length between them), displaced sideways by the `line` bow scaled to
    /// `CORRIDOR_SPREAD` of the start-goal distance, at a random height above ground held
    /// along the path; then encoded. A UAV without a corridor (walled in) is drawn as `line`.
    Corridor,
    /// Half of the draws are `line` draws; the other half fan the fleet out: the UAVs, in a
    /// random order, get evenly spaced strata of the bow's departure slope and the reverse
    /// strata of its arrival slope (so the paths do not cross), up to `FAN_SPREAD` of the
    /// start-goal distance, each jittered within the middle half of its stratum, at a random
    /// height as in `line`. UAVs that share a start then leave on different bearings instead
    /// of a random few on one. Not swarmplan's default: it helps on the outside instances
    /// with delays and costs paper-case2 contact (docs/results.md, "A fanned start").
    Fan,
    /// As `corridor`, on the route layer's cheapest way by energy over the terrain
    /// ([`super::routed`]) instead of the shortest threat-free corridor.
    Route,
    /// As `corridor`, on the route layer's way in height ([`super::banded`]): its free
    /// waypoints with their heights, displaced sideways by the `corridor` bow and up or down
    /// by a random offset of up to a level's spacing; a UAV whose start has no such way is
    /// drawn as `corridor`.
    Band,
    /// `line`, and when the best plan still has more than [`line_corridor_give_up`]
    /// violations after half the evaluation budget, `corridor` with the other half (a
    /// staged run, [`crate::run`]); a run feasible or nearly so by then is the `line` run,
    /// bit for bit.
    LineCorridor,
    /// As `line-corridor`, with `band` instead of `corridor` after a given-up line run.
    LineBand,
}

/// The violation measure above which a `line-corridor` run leaves its line start for the
/// corridor at half its evaluation budget. Tuned on the development outside instances and
/// the paper cases (docs/results.md, "The route layer and the outside instances"): 5, 10
/// and 20 gave 28, 29 and 30 of 66 development runs feasible and 185, 187 and 198 of 200 on
/// paper-case2 (the line start alone: 20 of 66 and 198).
pub const LINE_CORRIDOR_GIVE_UP: u32 = 20;

/// The threshold of [`line_corridor_give_up`] for a lone UAV: it has no relay, so a line
/// run that still misses contact by a second at half the budget (measure 1) seldom finds
/// it later; the band way that keeps contact is tried instead. 1 gave 39 of 66
/// development runs with one UAV on each of seeds 1 and 2 (4 gave 35 on each; 0 gave 39 on
/// seed 1) and kept 45 of 66 with communication off (docs/results.md, "A lone UAV gives up
/// sooner").
pub const LONE_UAV_GIVE_UP: u32 = 1;

/// The threshold of [`LINE_CORRIDOR_GIVE_UP`] for a fleet of `uavs`: 20 was tuned on fleets
/// of five, 4 per UAV, and a fleet smaller than five gets 4 per UAV (one UAV rarely gathers
/// 20 violations, so at 20 it seldom left a line start that had no way through; measured
/// on the development instances, docs/results.md, "A threshold per UAV"). Fleets of five
/// and more keep 20, as measured. A lone UAV gets [`LONE_UAV_GIVE_UP`].
#[must_use]
pub fn line_corridor_give_up(uavs: usize) -> u32 {
    if uavs == 1 {
        return LONE_UAV_GIVE_UP;
    }
    let per_uav = LINE_CORRIDOR_GIVE_UP / 5;
    u32::try_from(uavs)
        .map_or(LINE_CORRIDOR_GIVE_UP, |n| n.saturating_mul(per_uav))
        .min(LINE_CORRIDOR_GIVE_UP)
}

/// Largest sideways bow of a `corridor` path, as a share of its start-goal distance.
pub const CORRIDOR_SPREAD: f64 = 0.01;

/// Largest sideways bow of a `line` path, as a share of its start-goal distance.
pub const LINE_SPREAD: f64 = 0.25;

/// Largest departure (and arrival) slope of a `fan` path, `a1 + 2 a2` (and `2 a2 - a1`) of
/// its bow, as a share of its start-goal distance: the outermost UAVs of a fan leave about
/// 40 degrees off the start-goal bearing at ten free waypoints.
pub const FAN_SPREAD: f64 = 0.3;

impl InitKind {
    /// Every initialisation.
    pub const ALL: [Self; 8] = [
        Self::Uniform,
        Self::Line,
        Self::Corridor,
        Self::Fan,
        Self::Route,
        Self::Band,
        Self::LineCorridor,
        Self::LineBand,
    ];

    /// The start a staged run goes on from after giving its `line` run up, if it is staged
    /// (`line-corridor`, `line-band`; [`crate::run`]).
    #[must_use]
    pub const fn after_line(self) -> Option<Self> {
        match self {
            Self::LineCorridor => Some(Self::Corridor),
            Self::LineBand => Some(Self::Band),
            _ => None,
        }
    }

    /// The name used on the command line and in records (`uniform`, ...).
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Uniform => "uniform",
            Self::Line => "line",
            Self::Corridor => "corridor",
            Self::Fan => "fan",
            Self::Route => "route",
            Self::Band => "band",
            Self::LineCorridor => "line-corridor",
            Self::LineBand => "line-band",
        }
    }
}

impl fmt::Display for InitKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for InitKind {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| {
                format!(
                    "unknown initialisation `{s}`; expected uniform, line, corridor, fan, route, band, line-corridor or line-band"
                )
            })
    }
}

fn uniform(lo: f64, hi: f64, rng: &mut Rng) -> f64 {
    let u: f64 = rng.random();
    lo + u * (hi - lo)
}

/// A plan drawn by the `line` sampler: every UAV's free waypoints near its start-goal line.
pub fn sample_line_plan(frame: &PathFrame, rng: &mut Rng, plan: &mut Plan) {
    sample_bowed_plan(frame, &[], rng, plan);
}

/// A plan drawn by the `fan` sampler ([`InitKind::Fan`]): a `line` plan or a fanned one,
/// with probability 1/2 each.
pub fn sample_fan_plan(frame: &PathFrame, rng: &mut Rng, plan: &mut Plan) {
    if rng.random::<bool>() {
        sample_line_plan(frame, rng, plan);
    } else {
        sample_fanned_plan(frame, rng, plan);
    }
}

/// The fanned half of [`sample_fan_plan`].
fn sample_fanned_plan(frame: &PathFrame, rng: &mut Rng, plan: &mut Plan) {
    frame.prepare(plan);
    let m = plan.uavs.len();
    let mut order: Vec<usize> = (0..m).collect();
    order.shuffle(rng);
    // Stratum k of m, jittered within its middle half, in [-1, 1].
    let stratum = |k: usize, rng: &mut Rng| {
        let u: f64 = rng.random();
        2.0 * (k as f64 + 0.25 + 0.5 * u) / m as f64 - 1.0
    };
    for (i, path) in plan.uavs.iter_mut().enumerate() {
        let s = frame.starts[i];
        let axes = start_goal_axes(s, frame.goal);
        let length = axes.0;
        // The bow's slopes at t = 0 and t = 1 are pi (a1 + 2 a2) and pi (2 a2 - a1).
        let departure = FAN_SPREAD * length * stratum(order[i], rng);
        let arrival = -FAN_SPREAD * length * stratum(order[i], rng);
        let (a1, a2) = (0.5 * (departure - arrival), 0.25 * (departure + arrival));
        let z = uniform(frame.z[0], frame.z[1], rng);
        place_bowed(frame, path, s, axes, (a1, a2, z), None);
    }
}

/// A plan drawn by the `corridor` sampler: every UAV's free waypoints near its corridor
/// (`corridors[i]`, from [`super::corridor::corridors`]; an empty one means the line).
pub fn sample_corridor_plan(
    frame: &PathFrame,
    corridors: &[Vec<DVec2>],
    rng: &mut Rng,
    plan: &mut Plan,
) {
    sample_bowed_plan(frame, corridors, rng, plan);
}

/// A plan drawn by the `band` sampler ([`InitKind::Band`]): each seeded UAV's absolute
/// waypoints bowed sideways, held at their altitude over the `ground` below their new
/// place, and shifted up or down together by as much as keeps them in the band (at most a
/// level's spacing; clamped into the band where no shift can).
///
/// UAVs that share a seeded way (a shared start) are coordinated in height (issue 46, item
/// 2): in a random order, each takes its own stratum of the shifts that keep the way in the
/// band (as far as the band allows, uncapped), jittered within the middle half of it, so that
/// the fleet flies the way in layers; alone, a UAV draws its shift as before, bit for bit.
pub fn sample_band_plan(
    frame: &PathFrame,
    seeds: &super::banded::BandSeeds,
    ground: &dyn Fn(DVec2) -> f64,
    rng: &mut Rng,
    plan: &mut Plan,
) {
    sample_bowed_plan(frame, &seeds.guides, rng, plan);
    let level = (frame.z[1] - frame.z[0]) / (crate::band_route::LEVELS - 1) as f64;
    let layers = Layers::draw(seeds, frame.n, rng);
    for (i, path) in plan.uavs.iter_mut().enumerate() {
        let Some(points) = seeds.waypoints.get(i).filter(|w| w.len() == frame.n) else {
            continue;
        };
        let axes = start_goal_axes(frame.starts[i], frame.goal);
        let h = CORRIDOR_SPREAD * axes.0;
        let a1 = uniform(-h, h, rng);
        let a2 = uniform(-0.5 * h, 0.5 * h, rng);
        let u: f64 = rng.random();
        let placed: Vec<(DVec2, f64)> = points
            .iter()
            .enumerate()
            .map(|(k, p)| {
                let t = (k + 1) as f64 / (frame.n + 1) as f64;
                let bow = a1 * (PI * t).sin() + a2 * (2.0 * PI * t).sin();
                let q = p.truncate() + axes.2 * bow;
                let q = DVec2::new(
                    q.x.clamp(frame.x[0], frame.x[1]),
                    q.y.clamp(frame.y[0], frame.y[1]),
                );
                (q, p.z - ground(q))
            })
            .collect();
        // The shift keeps every waypoint in the band where it can (a waypoint clamped alone
        // would bend the way up or down steeply), within a level's spacing alone and as far
        // as the band allows in a layer.
        let layer = layers.of(i);
        let cap = if layer.is_some() {
            f64::INFINITY
        } else {
            level
        };
        let lower = placed
            .iter()
            .fold(-cap, |m, &(_, agl)| m.max(frame.z[0] - agl));
        let upper = placed
            .iter()
            .fold(cap, |m, &(_, agl)| m.min(frame.z[1] - agl));
        let share = layer.map_or(u, |(stratum, of)| {
            (stratum as f64 + 0.25 + 0.5 * u) / of as f64
        });
        let dz = if lower <= upper {
            lower + share * (upper - lower)
        } else {
            0.0
        };
        for (k, (q, agl)) in placed.into_iter().enumerate() {
            path.waypoints[k + 1] = DVec3::new(q.x, q.y, (agl + dz).clamp(frame.z[0], frame.z[1]));
        }
    }
}

/// The height strata of UAVs sharing a seeded way: per UAV, `(stratum, of)`, or `None`
/// for a UAV whose way no other shares.
struct Layers(Vec<Option<(usize, usize)>>);

impl Layers {
    /// Groups the UAVs by their seeded way and draws each group's order (no draw at all
    /// when no way is shared).
    fn draw(seeds: &super::banded::BandSeeds, n: usize, rng: &mut Rng) -> Self {
        let ways = &seeds.waypoints;
        let mut out = vec![None; ways.len()];
        for i in 0..ways.len() {
            if out[i].is_some() || ways[i].len() != n {
                continue;
            }
            let group: Vec<usize> = (i..ways.len()).filter(|&j| ways[j] == ways[i]).collect();
            if group.len() < 2 {
                continue;
            }
            let mut order: Vec<usize> = (0..group.len()).collect();
            rand::seq::SliceRandom::shuffle(order.as_mut_slice(), rng);
            for (&j, &stratum) in group.iter().zip(&order) {
                out[j] = Some((stratum, group.len()));
            }
        }
        Self(out)
    }

    fn of(&self, uav: usize) -> Option<(usize, usize)> {
        self.0.get(uav).copied().flatten()
    }
}

/// Free waypoints along each UAV's guide (its corridor, resampled with its corners, when it has one of at
/// least two points, else the start-goal line), bowed sideways, at one random height.
fn sample_bowed_plan(frame: &PathFrame, corridors: &[Vec<DVec2>], rng: &mut Rng, plan: &mut Plan) {
    frame.prepare(plan);
    for (i, (path, s)) in plan.uavs.iter_mut().zip(&frame.starts).enumerate() {
        let axes = start_goal_axes(*s, frame.goal);
        let guide = corridors.get(i).filter(|c| c.len() >= 2);
        let spread = if guide.is_some() {
            CORRIDOR_SPREAD
        } else {
            LINE_SPREAD
        };
        let h = spread * axes.0;
        let a1 = uniform(-h, h, rng);
        let a2 = uniform(-0.5 * h, 0.5 * h, rng);
        let z = uniform(frame.z[0], frame.z[1], rng);
        let guided = guide.map(|c| resample(c, frame.n));
        place_bowed(frame, path, *s, axes, (a1, a2, z), guided.as_deref());
    }
}

/// The start-goal distance in the plane, its direction and the direction to its left (the
/// x and y axes for a UAV that starts at the goal).
fn start_goal_axes(start: DVec3, goal: DVec3) -> (f64, DVec2, DVec2) {
    let d = (goal - start).truncate();
    let length = d.length();
    if length > 0.0 {
        let u = d / length;
        (length, u, DVec2::new(-u.y, u.x))
    } else {
        (length, DVec2::X, DVec2::Y)
    }
}

/// Places a path's free waypoints on planes across its start-goal line (or at the points of
/// `guided`), displaced sideways by the bow `a1 sin(pi t) + a2 sin(2 pi t)`, at height `z`,
/// clamped into the box.
fn place_bowed(
    frame: &PathFrame,
    path: &mut crate::plan::Path,
    start: DVec3,
    (length, dir, side): (f64, DVec2, DVec2),
    (a1, a2, z): (f64, f64, f64),
    guided: Option<&[DVec2]>,
) {
    let n = frame.n;
    for k in 1..=n {
        let t = k as f64 / (n + 1) as f64;
        let bow = a1 * (PI * t).sin() + a2 * (2.0 * PI * t).sin();
        let on = guided.map_or_else(|| start.truncate() + dir * (t * length), |g| g[k - 1]);
        let p = on + side * bow;
        path.waypoints[k] = DVec3::new(
            p.x.clamp(frame.x[0], frame.x[1]),
            p.y.clamp(frame.y[0], frame.y[1]),
            z,
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::rng_from_seed;

    #[test]
    fn a_lone_uav_gives_its_line_up_sooner_and_fleets_of_five_and_more_keep_twenty() {
        assert_eq!(line_corridor_give_up(1), LONE_UAV_GIVE_UP);
        assert_eq!(line_corridor_give_up(2), 8);
        assert_eq!(line_corridor_give_up(4), 16);
        assert_eq!(line_corridor_give_up(5), LINE_CORRIDOR_GIVE_UP);
        assert_eq!(line_corridor_give_up(100), LINE_CORRIDOR_GIVE_UP);
    }

    fn frame() -> PathFrame {
        PathFrame {
            starts: vec![DVec3::new(100.0, 100.0, 150.0); 2],
            goal: DVec3::new(900.0, 700.0, 150.0),
            x: [0.0, 1000.0],
            y: [0.0, 800.0],
            z: [100.0, 200.0],
            n: 8,
        }
    }

    #[test]
    fn line_paths_stay_near_the_start_goal_line_and_in_the_box() {
        let f = frame();
        let mut plan = Plan::default();
        let mut rng = rng_from_seed(4);
        for _ in 0..50 {
            sample_line_plan(&f, &mut rng, &mut plan);
            for path in &plan.uavs {
                assert_eq!(path.waypoints.len(), f.n + 2);
                for (k, w) in path.waypoints.iter().enumerate().skip(1).take(f.n) {
                    assert!((0.0..=1000.0).contains(&w.x) && (0.0..=800.0).contains(&w.y));
                    assert!((100.0..=200.0).contains(&w.z));
                    // Distance from the line is at most the bow's amplitude (1.5 h).
                    let along = (k as f64) / (f.n + 1) as f64;
                    let on_line =
                        f.starts[0].truncate() + (f.goal - f.starts[0]).truncate() * along;
                    assert!((w.truncate() - on_line).length() <= 1.5 * LINE_SPREAD * 1000.0);
                }
            }
        }
    }

    /// Five UAVs from one start (`frame`'s, 1000 m from the goal, 8 free waypoints).
    fn five_from_one_start() -> PathFrame {
        PathFrame {
            starts: vec![DVec3::new(100.0, 100.0, 150.0); 5],
            ..frame()
        }
    }

    /// Whether the UAVs of `plan` (drawn on `f`) leave in the order they arrive and at least
    /// 15 m apart sideways at the first free waypoint.
    fn leaves_fanned(f: &PathFrame, plan: &Plan) -> bool {
        let (length, dir, side) = start_goal_axes(f.starts[0], f.goal);
        let lateral = |w: DVec3, t: f64| {
            let on = f.starts[0].truncate() + dir * (t * length);
            (w.truncate() - on).dot(side)
        };
        let t_last = f.n as f64 / (f.n + 1) as f64;
        let sorted = |k: usize, t: f64| {
            let mut v: Vec<(f64, usize)> = (0..plan.uavs.len())
                .map(|u| (lateral(plan.uavs[u].waypoints[k], t), u))
                .collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
        let departure = sorted(1, 1.0 / (f.n + 1) as f64);
        let arrival = sorted(f.n, t_last);
        let order = |v: &[(f64, usize)]| v.iter().map(|p| p.1).collect::<Vec<_>>();
        order(&departure) == order(&arrival)
            && departure.windows(2).all(|p| p[1].0 - p[0].0 >= 15.0)
    }

    /// A fanned plan's UAVs leave in the order they arrive (the paths do not cross) and at
    /// least 15 m apart sideways at the first free waypoint (strata 60 m apart in departure
    /// slope, jittered within their middle half).
    #[test]
    fn a_fanned_fleet_leaves_and_arrives_spread_in_one_order() {
        let f = five_from_one_start();
        let mut plan = Plan::default();
        let mut rng = rng_from_seed(9);
        for _ in 0..50 {
            sample_fanned_plan(&f, &mut rng, &mut plan);
            assert!(leaves_fanned(&f, &plan), "{plan:?}");
        }
    }

    /// About half of the `fan` draws are fanned; a `line` draw of five UAVs rarely is.
    #[test]
    fn half_of_the_fan_draws_are_fanned() {
        let f = five_from_one_start();
        let mut plan = Plan::default();
        let (mut fan, mut line) = (0, 0);
        let mut rng = rng_from_seed(5);
        for _ in 0..200 {
            sample_fan_plan(&f, &mut rng, &mut plan);
            fan += usize::from(leaves_fanned(&f, &plan));
            sample_line_plan(&f, &mut rng, &mut plan);
            line += usize::from(leaves_fanned(&f, &plan));
        }
        assert!((70..=150).contains(&fan), "fan: {fan} of 200 fanned");
        assert!(line < 30, "line: {line} of 200 fanned");
    }

    #[test]
    fn only_the_staged_starts_go_on_after_a_line_run() {
        assert_eq!(
            InitKind::LineCorridor.after_line(),
            Some(InitKind::Corridor)
        );
        assert_eq!(InitKind::LineBand.after_line(), Some(InitKind::Band));
        let staged = InitKind::ALL
            .into_iter()
            .filter(|k| k.after_line().is_some())
            .count();
        assert_eq!(staged, 2);
    }

    #[test]
    fn names_round_trip() {
        for k in InitKind::ALL {
            assert_eq!(k.name().parse::<InitKind>(), Ok(k));
        }
        assert!("box".parse::<InitKind>().is_err());
    }
}
