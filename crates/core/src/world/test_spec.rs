//! A scenario for unit tests: one default UAV over a 1000 m square with the given threats
//! and goal, every other section at its default, so that a test states only what it is
//! about.

use super::spec::{GoalSpec, ScenarioSpec, UavSpec};
use super::threat::Threat;

/// One default UAV, `threats`, UGV0 at `goal`, a map of [0, 1000] m in x and y.
pub(crate) fn one_uav_spec(name: &str, threats: Vec<Threat>, goal: [f64; 3]) -> ScenarioSpec {
    let mut spec = ScenarioSpec {
        name: name.into(),
        description: String::new(),
        terrain: Default::default(),
        geo: None,
        map: Default::default(),
        threats,
        goal: GoalSpec {
            position: goal,
            antenna: 2.0,
        },
        uavs: vec![UavSpec::default()],
        communication: Default::default(),
        energy: Default::default(),
        objective: Default::default(),
        timing: Default::default(),
        planning: Default::default(),
    };
    spec.map.x = [0.0, 1000.0];
    spec.map.y = [0.0, 1000.0];
    spec
}
