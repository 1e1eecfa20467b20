//! The `band` start's draws on rugged outside terrain fly the seeded way in height (needs
//! `../shared`; required in CI).

#![allow(clippy::unwrap_used)] // tests fail loudly by design

use swarmplan_core::encoding::banded::band_seeds;
use swarmplan_core::encoding::init::CORRIDOR_SPREAD;
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::Problem;
use swarmplan_core::rng::rng_from_seed;
use swarmplan_io::catalog::load_spec;
use swarmplan_io::reference_data::reference_files;
use swarmplan_io::scenario::build_world;

#[test]
fn band_draws_on_outside_6_sit_where_their_seeds_are_but_for_the_bow() {
    // outside-6's way in height runs along slopes where its height above ground changes
    // faster than 45 deg between waypoints; with the spherical encoding's climb bounds at
    // 45 deg those moves were clamped and the decoded waypoints landed 25-34 m off in the
    // plane and 106-153 m off in altitude, with climb violations in every draw.
    let Some(_) = reference_files(&["outside/outside-6.json", "outside/outside-6.asc.gz"]).unwrap()
    else {
        return;
    };
    let world = build_world(&load_spec("outside-6").unwrap(), None).unwrap();
    let seeds = band_seeds(&world);
    let problem = PlanningProblem::new(&world, EncodingKind::Spherical, InitKind::Band);
    let goal = world.goal_at(swarmplan_core::world::DEPARTURE).truncate();
    let mut rng = rng_from_seed(7);
    let mut x = vec![0.0; problem.dimension()];
    for _ in 0..10 {
        problem.sample_initial(&mut rng, &mut x);
        let plan = problem.decode(&x);
        for (u, path) in plan.uavs.iter().enumerate() {
            let seed = &seeds.waypoints[u];
            assert_eq!(seed.len(), path.waypoints.len() - 2, "UAV {u} has a way");
            // The bow moves a waypoint sideways by at most 1.5 times the spread.
            let bow = 1.5 * CORRIDOR_SPREAD * world.start(u).truncate().distance(goal) + 1e-6;
            for (q, s) in path.waypoints[1..].iter().zip(seed) {
                let off = q.truncate().distance(s.truncate());
                assert!(
                    off <= bow,
                    "UAV {u}: {off:.1} m off its seed (bow {bow:.1} m)"
                );
            }
        }
    }
}
