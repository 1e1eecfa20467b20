//! A flight margin: the scenario to plan on so that an aircraft that strays from its plan by
//! up to a given distance still keeps every hard geometric limit of the scenario it flies in.
//!
//! Why: flown in a flight-dynamics model (docs/flight.md, issue 48), swarmplan's plans for
//! the paper cases stray 1-2.5 m from the planned path, and the plans leave no room for
//! that: they graze the threats' hard zones, put UAVs exactly `timing.separation` apart
//! where the fleet fans out, and run along the map box's edge, so 19 of 20 lost a limit by
//! 0.01-1.73 m as flown. The model is not changed to suit an airframe; instead `plan
//! --flight-margin M` plans on a copy of the scenario whose limits are M metres tighter and
//! judges the plan against the original, which it keeps with at least M metres to spare.
//! The margin is the airframe's and autopilot's tracking error, which swarmplan does not
//! know: it is 0 unless asked for.
//!
//! Tightened by M: each UAV's `size` (the distance kept from every threat's hard zone and
//! the danger zone's inner edge), `timing.separation`, `map.clearance` over the terrain, and
//! the map box on each side in x and y. The altitude band (a band for the free waypoints,
//! not a limit the aircraft flies against), speeds, turns, climbs and energy are unchanged.

use thiserror::Error;

use super::spec::ScenarioSpec;
use super::{World, WorldError};

/// Why a flight margin cannot be applied.
#[derive(Debug, Error)]
pub enum FlightMarginError {
    /// The margin is negative, infinite or NaN.
    #[error("flight margin {0}: expected a finite distance of at least 0 m")]
    NotADistance(f64),
    /// The map box shrunk by the margin on both sides has no width left.
    #[error(
        "flight margin {margin} m: the map box's {axis} range [{lo}, {hi}] shrunk by {margin} m on each side is empty"
    )]
    BoxTooSmall {
        /// The margin, metres.
        margin: f64,
        /// `x` or `y`.
        axis: &'static str,
        /// The box's range on that axis, metres.
        lo: f64,
        /// Upper end of the range.
        hi: f64,
    },
    /// The tightened scenario is not a valid world (a start outside the shrunk box, ...).
    #[error("flight margin {margin} m: the scenario with every limit {margin} m tighter is not valid: {source}")]
    Invalid {
        /// The margin, metres.
        margin: f64,
        /// Why the world refused it.
        source: WorldError,
    },
}

/// `world` with every hard geometric limit tightened by `margin` metres, on the same
/// terrain; `None` for a margin of 0 (search on `world` itself).
///
/// # Errors
/// As [`with_flight_margin`], or the tightened scenario is not a valid world.
pub fn grown_world(world: &World, margin: f64) -> Result<Option<World>, FlightMarginError> {
    if margin == 0.0 {
        return Ok(None);
    }
    let spec = with_flight_margin(world.spec(), margin)?;
    World::new(spec, world.terrain().clone())
        .map(Some)
        .map_err(|source| FlightMarginError::Invalid { margin, source })
}

/// `spec` with every hard geometric limit tightened by `margin` metres (module docs); the
/// same spec for a margin of 0.
///
/// # Errors
/// A margin that is not a finite distance >= 0, or one that leaves the map box empty.
pub fn with_flight_margin(
    spec: &ScenarioSpec,
    margin: f64,
) -> Result<ScenarioSpec, FlightMarginError> {
    if !(margin.is_finite() && margin >= 0.0) {
        return Err(FlightMarginError::NotADistance(margin));
    }
    let mut grown = spec.clone();
    if margin == 0.0 {
        return Ok(grown);
    }
    let map = &mut grown.map;
    for (axis, range) in [("x", &mut map.x), ("y", &mut map.y)] {
        let [lo, hi] = *range;
        if hi - lo <= 2.0 * margin {
            return Err(FlightMarginError::BoxTooSmall {
                margin,
                axis,
                lo,
                hi,
            });
        }
        *range = [lo + margin, hi - margin];
    }
    map.clearance += margin;
    grown.timing.separation += margin;
    for uav in &mut grown.uavs {
        uav.size += margin;
    }
    Ok(grown)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::test_spec::one_uav_spec;

    fn spec() -> ScenarioSpec {
        let mut spec = one_uav_spec("margin", Vec::new(), [800.0, 800.0, 0.0]);
        spec.map.x = [1.0, 1045.0];
        spec.map.y = [1.0, 879.0];
        spec
    }

    #[test]
    fn every_hard_geometric_limit_is_tightened_by_the_margin() {
        let spec = spec();
        let grown = with_flight_margin(&spec, 2.5).unwrap();
        assert_eq!(grown.map.x, [spec.map.x[0] + 2.5, spec.map.x[1] - 2.5]);
        assert_eq!(grown.map.y, [spec.map.y[0] + 2.5, spec.map.y[1] - 2.5]);
        assert_eq!(grown.map.clearance, spec.map.clearance + 2.5);
        assert_eq!(grown.timing.separation, spec.timing.separation + 2.5);
        for (g, u) in grown.uavs.iter().zip(&spec.uavs) {
            assert_eq!(g.size, u.size + 2.5);
            assert_eq!(g.max_turn_deg, u.max_turn_deg);
        }
        assert_eq!(grown.map.z_agl, spec.map.z_agl);
        assert_eq!(grown.energy, spec.energy);
        let same = with_flight_margin(&spec, 0.0).unwrap();
        assert_eq!(same, spec);
    }

    #[test]
    fn a_margin_that_is_no_distance_or_empties_the_box_is_refused() {
        let spec = spec();
        for bad in [-1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                with_flight_margin(&spec, bad),
                Err(FlightMarginError::NotADistance(_))
            ));
        }
        let err = with_flight_margin(&spec, 500.0).unwrap_err();
        assert_eq!(
            err.to_string(),
            "flight margin 500 m: the map box's y range [1, 879] shrunk by 500 m on each side is empty"
        );
    }
}
