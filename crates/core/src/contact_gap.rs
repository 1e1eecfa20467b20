//! Whether one UAV alone can keep direct ground contact on any way the route layer in
//! height holds: its way with the fewest metres out of contact, and that way's longest
//! stretch without it against the outage the scenario tolerates (issue 46, "honest
//! outcomes").
//!
//! Why: on the outside benchmark's instances 2 and 9 every plan of one UAV fails on a single
//! communication violation, and nothing told the user whether another way would keep
//! contact or none can. Measured with this module, the way that keeps contact best still
//! flies hundreds of metres out of it in one stretch, tens of seconds against the 5 s
//! tolerated: only relays through other UAVs can close that gap (docs/results.md, "Where
//! one UAV cannot keep contact").
//!
//! Two questions, in turn. First, line of sight alone: the way with the fewest metres that
//! no ground node sees over the terrain, whatever the range. If even that way is unseen
//! for longer than tolerated at the top speed, a lone UAV cannot keep direct contact on
//! any way of the grid, whatever the channel does. Otherwise, contact at the nominal range
//! R0 ([`crate::cost::coverage::direct_ground_link`]): the shadowing moves the range around
//! R0 over time (and a plan may meet it where it is long), so these figures explain a
//! failure and are not a verdict. Either way the grid's resolution bounds them, and the
//! outcome says "none found", never "no plan exists", on them.

use crate::band_route::contact_way_weighted;
use crate::cost::coverage::blind_stretches;
use crate::world::World;

/// How much a metre out of direct contact weighs against a metre of cruise in the search
/// for the way with the fewest such metres: enough that energy only breaks ties.
const FEWEST_OUT_WEIGHT: f64 = 100.0;

/// Spacing of the contact samples along the way, m.
const SAMPLE_STEP_M: f64 = 5.0;

/// The route layer's way that keeps direct ground contact best, for one UAV.
#[derive(Debug, Clone, PartialEq)]
pub struct ContactGap {
    /// Metres of the way out of direct ground contact, in all.
    pub out_m: f64,
    /// Its longest stretch out of contact, m (0 when it keeps contact all along).
    pub longest_m: f64,
    /// How many stretches out of contact it has.
    pub stretches: usize,
    /// The UAV's top speed, m/s.
    pub top_speed: f64,
    /// The longest outage the scenario tolerates (`communication.max_outage_s`), s.
    pub tolerated_s: f64,
    /// The range contact was read at, m: infinite for line of sight alone, else the
    /// nominal range R0 (`communication.range`).
    pub range: f64,
}

impl ContactGap {
    /// The shortest time the longest stretch takes to fly, at the top speed, s.
    #[must_use]
    pub fn longest_s(&self) -> f64 {
        self.longest_m / self.top_speed
    }

    /// Whether the UAV alone stays out of contact longer than tolerated even on this way.
    #[must_use]
    pub fn needs_relays(&self) -> bool {
        self.longest_s() > self.tolerated_s
    }

    /// One clause for humans.
    #[must_use]
    pub fn sentence(&self) -> String {
        let sight_only = self.range.is_infinite();
        let basis = if sight_only {
            "direct ground contact (line of sight alone, at any range)".to_string()
        } else {
            format!(
                "direct ground contact at the nominal range of {:.0} m (the shadowing moves it over time; no relays)",
                self.range
            )
        };
        if self.stretches == 0 {
            return format!("{basis} holds all along the way that keeps it best");
        }
        let verdict = match (self.needs_relays(), sight_only) {
            (true, true) => ": alone, a UAV is out of every ground node's sight there for longer than tolerated, so only a relay through another UAV bridges it (on this grid)",
            (true, false) => ": at the nominal range a lone UAV is out of contact there for longer than tolerated",
            (false, _) => "",
        };
        format!(
            "{basis}: the way that keeps it best still flies {:.0} m without it in {} stretch{}, the longest {:.0} m, {:.1} s at the top speed of {} m/s against the {} s tolerated{verdict}",
            self.out_m,
            self.stretches,
            if self.stretches == 1 { "" } else { "es" },
            self.longest_m,
            self.longest_s(),
            crate::world::validate::number(self.top_speed),
            crate::world::validate::number(self.tolerated_s),
        )
    }
}

/// What the route layer's grid in height (`cells` along the longer side, `levels`
/// heights) says of UAV `uav` keeping direct ground contact (module docs): the way with the
/// fewest metres out of every ground node's sight when even it is unseen for longer than
/// tolerated, else the way with the fewest metres out of contact at the nominal range,
/// whatever their energy; `None` when the grid holds no way.
#[must_use]
pub fn contact_gap(world: &World, uav: usize, cells: usize, levels: usize) -> Option<ContactGap> {
    let sight = gap_at(world, uav, cells, levels, f64::INFINITY)?;
    if sight.needs_relays() {
        return Some(sight);
    }
    gap_at(world, uav, cells, levels, world.channel().nominal_range())
}

/// The way with the fewest metres out of contact within `range`, and its stretches.
fn gap_at(
    world: &World,
    uav: usize,
    cells: usize,
    levels: usize,
    range: f64,
) -> Option<ContactGap> {
    let (_, way) = contact_way_weighted(world, uav, cells, levels, FEWEST_OUT_WEIGHT, range)?;
    let stretches = blind_stretches(world, &way, SAMPLE_STEP_M, range);
    let spec = world.spec();
    Some(ContactGap {
        out_m: stretches.iter().sum(),
        longest_m: stretches.iter().copied().fold(0.0, f64::max),
        stretches: stretches.len(),
        top_speed: spec.uavs[uav].speed[1],
        tolerated_s: spec.communication.max_outage_s,
        range,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::world::terrain::Terrain;

    /// One UAV from (100, 500) to (900, 500) on flat ground, the station at its start and
    /// UGV0 at its goal, range `range`.
    fn world(range: f64) -> World {
        let mut spec =
            crate::world::test_spec::one_uav_spec("gap", Vec::new(), [900.0, 500.0, 150.0]);
        spec.uavs[0].start = [100.0, 500.0, 150.0];
        spec.communication.range = range;
        World::new(spec, Terrain::flat(1000.0, 1000.0, 0.0)).unwrap()
    }

    #[test]
    fn a_gap_no_way_can_close_is_measured_and_said() {
        // Range 250 m: from the band's floor (antennas 2 m up) the station and UGV0 reach
        // `reach` metres horizontally, so the middle 800 - 2 reach metres of the straight
        // way, the least any way flies out of contact, are out of reach of both.
        let w = world(250.0);
        let floor = w.spec().map.z_agl[0];
        let reach = (250.0_f64.powi(2) - (floor - 2.0).powi(2)).sqrt();
        let least = 800.0 - 2.0 * reach;
        let gap = contact_gap(&w, 0, 20, 3).unwrap();
        assert_eq!(gap.stretches, 1, "{gap:?}");
        assert!(
            gap.longest_m > least - 10.0 && gap.longest_m < least + 60.0,
            "{gap:?}, least {least}"
        );
        assert!(gap.needs_relays());
        let said = gap.sentence();
        assert!(
            said.contains(
                "at the nominal range a lone UAV is out of contact there for longer than tolerated"
            ),
            "{said}"
        );
        assert!(
            said.starts_with("direct ground contact at the nominal range of 250 m"),
            "{said}"
        );
    }

    /// Ground heights along x: a plain, and a plateau 200 m high for x in [200, 800].
    pub(crate) fn plateau(x: f64) -> f64 {
        if (200.0..=800.0).contains(&x) {
            200.0
        } else {
            0.0
        }
    }

    #[test]
    fn a_plateau_that_hides_its_middle_from_both_nodes_needs_relays_at_any_range() {
        // The station at (100, 500) and UGV0 at (900, 500) stand on a plain, a plateau 200 m
        // high between x = 200 and 800. Each sees over the plateau's edge only about 100 m
        // onto it from 200 m above it, so some 400 m in the middle are out of both sights
        // however long the range: 16 s at 25 m/s against the 5 s tolerated.
        let w = crate::band_route::tests::world(10, crate::band_route::tests::terrain(plateau));
        let gap = contact_gap(&w, 0, 20, 3).unwrap();
        assert!(gap.range.is_infinite(), "{gap:?}");
        assert!(gap.needs_relays() && gap.longest_m > 300.0, "{gap:?}");
        let said = gap.sentence();
        assert!(
            said.starts_with("direct ground contact (line of sight alone, at any range)")
                && said.ends_with("so only a relay through another UAV bridges it (on this grid)"),
            "{said}"
        );
    }

    #[test]
    fn a_way_in_range_all_along_is_said_to_keep_contact() {
        let gap = contact_gap(&world(900.0), 0, 20, 3).unwrap();
        assert_eq!((gap.stretches, gap.longest_m), (0, 0.0), "{gap:?}");
        assert!(!gap.needs_relays());
        assert!(gap
            .sentence()
            .ends_with("holds all along the way that keeps it best"));
    }
}
