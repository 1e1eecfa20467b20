//! The cost terms as one list.
//!
//! Names, units, weights (the scenario's `[objective]` keys them by [`TermId::name`]),
//! per-UAV values, breakdowns, run records and every renderer come from [`TermId::ALL`],
//! so adding a term is a variant here (name, unit, default weight) and the file that
//! computes it; nothing else lists terms.

use std::ops::{Index, IndexMut};

use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// One term of the objective.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum TermId {
    /// SPSO J1: path length with absolute altitudes.
    Length,
    /// SPSO J2: threat danger band.
    Threat,
    /// SPSO J3: altitude deviation from the band centre.
    Altitude,
    /// SPSO J4: smoothness (turn and climb excess).
    Smoothness,
    /// Eq. 4: speed and payload indicators.
    Safety,
    /// Eq. 5: length + alpha |dz| + beta |d heading|.
    Energy,
    /// Communication outage cost.
    Communication,
    /// Eq. 7: sum of squared heading changes.
    Turning,
    /// Eq. 8 at equal times.
    Obstacle,
}

/// When a term is known in an assessment ([`super::assess_bounded`], one driver for full
/// and bounded assessments): from a UAV's waypoints alone, from the path it flies (arcs and
/// timing), or from the whole fleet flown together. A new term takes the phase of the
/// least it needs, so a bounded assessment can give a plan up before computing it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Phase {
    /// Known from one UAV's waypoints (SPSO's terms, turning).
    Waypoints,
    /// Known from one UAV's flown path (safety, energy).
    Flown,
    /// Known from the fleet flown together (communication, proximity).
    Fleet,
}

/// How many terms there are.
pub const TERM_COUNT: usize = 9;

impl TermId {
    /// Every term, in report order.
    pub const ALL: [Self; TERM_COUNT] = [
        Self::Length,
        Self::Threat,
        Self::Altitude,
        Self::Smoothness,
        Self::Safety,
        Self::Energy,
        Self::Communication,
        Self::Turning,
        Self::Obstacle,
    ];

    /// Name in tables, JSON and the scenario's `[objective]` weight field.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Length => "length",
            Self::Threat => "threat",
            Self::Altitude => "altitude",
            Self::Smoothness => "smoothness",
            Self::Safety => "safety",
            Self::Energy => "energy",
            Self::Communication => "communication",
            Self::Turning => "turning",
            Self::Obstacle => "obstacle",
        }
    }

    /// Unit of the raw (unweighted) value.
    #[must_use]
    pub const fn unit(self) -> &'static str {
        match self {
            Self::Length | Self::Threat | Self::Altitude | Self::Energy => "m",
            Self::Smoothness => "deg",
            Self::Safety => "count",
            Self::Communication => "m-equivalent",
            Self::Turning => "rad^2",
            Self::Obstacle => "1/m^2 s",
        }
    }

    /// A term of the paper's cooperative model (weight 0 under the `spso-mycost` objective preset).
    #[must_use]
    pub const fn cooperative(self) -> bool {
        !matches!(
            self,
            Self::Length | Self::Threat | Self::Altitude | Self::Smoothness
        )
    }

    /// The phase of an assessment in which the term is computed.
    #[must_use]
    pub const fn phase(self) -> Phase {
        match self {
            Self::Length | Self::Threat | Self::Altitude | Self::Smoothness | Self::Turning => {
                Phase::Waypoints
            }
            Self::Safety | Self::Energy => Phase::Flown,
            Self::Communication | Self::Obstacle => Phase::Fleet,
        }
    }

    /// The term's weight by default (SPSO's b1..b4, the paper's w2..w6 as calibrated in
    /// docs/model.md).
    #[must_use]
    pub const fn default_weight(self) -> f64 {
        match self {
            Self::Length => 5.0,
            Self::Threat => 1.0,
            Self::Altitude => 10.0,
            Self::Smoothness => 1.0,
            Self::Safety => 100.0,
            Self::Energy => 0.05,
            Self::Communication => 1.0,
            Self::Turning => 1.0,
            Self::Obstacle => 100.0,
        }
    }

    const fn index(self) -> usize {
        self as usize
    }
}

/// Every term's name, in [`TermId::ALL`]'s order.
pub const NAMES: [&str; TERM_COUNT] = {
    let mut names = [""; TERM_COUNT];
    let mut k = 0;
    while k < TERM_COUNT {
        names[k] = TermId::ALL[k].name();
        k += 1;
    }
    names
};

/// The term named `name`, if any.
#[must_use]
pub fn term_named(name: &str) -> Option<TermId> {
    TermId::ALL.into_iter().find(|t| t.name() == name)
}

/// One value per term (raw or weighted). Serialised as a map `{name: value}`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Terms([f64; TERM_COUNT]);

impl Terms {
    /// Whether every term after `phase` is zero (nothing computed ahead of its phase).
    #[must_use]
    pub fn zero_after(&self, phase: Phase) -> bool {
        TermId::ALL
            .iter()
            .all(|&t| t.phase() <= phase || self[t] == 0.0)
    }

    /// The values of the terms in [`TermId::ALL`]'s order.
    #[must_use]
    pub const fn new(values: [f64; TERM_COUNT]) -> Self {
        Self(values)
    }

    /// `(term, value)` in report order.
    pub fn iter(&self) -> impl Iterator<Item = (TermId, f64)> + '_ {
        TermId::ALL.iter().map(|&t| (t, self[t]))
    }

    /// The values added up, in term order.
    #[must_use]
    pub fn sum(&self) -> f64 {
        self.0.iter().sum()
    }

    /// Each term times its weight in `weights` (an objective's effective weights:
    /// `ObjectiveSpec::weights`).
    #[must_use]
    pub fn weighted(&self, weights: &Self) -> Self {
        let mut w = *self;
        for t in TermId::ALL {
            w[t] *= weights[t];
        }
        w
    }

    /// Adds `other` term by term.
    pub fn add(&mut self, other: &Self) {
        for (a, b) in self.0.iter_mut().zip(other.0) {
            *a += b;
        }
    }
}

impl Index<TermId> for Terms {
    type Output = f64;
    fn index(&self, t: TermId) -> &f64 {
        &self.0[t.index()]
    }
}

impl IndexMut<TermId> for Terms {
    fn index_mut(&mut self, t: TermId) -> &mut f64 {
        &mut self.0[t.index()]
    }
}

impl Serialize for Terms {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(TERM_COUNT))?;
        for (t, v) in self.iter() {
            m.serialize_entry(t.name(), &v)?;
        }
        m.end()
    }
}

impl<'de> Deserialize<'de> for Terms {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> Visitor<'de> for V {
            type Value = Terms;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("a map from term name to number")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Terms, A::Error> {
                let mut t = Terms::default();
                while let Some(k) = map.next_key::<String>()? {
                    let id = term_named(&k)
                        .ok_or_else(|| serde::de::Error::unknown_field(&k, &NAMES))?;
                    t[id] = map.next_value()?;
                }
                Ok(t)
            }
        }
        d.deserialize_map(V)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_term_set_ahead_of_its_phase_is_caught() {
        let mut t = Terms::default();
        t[TermId::Length] = 1.0;
        assert!(t.zero_after(Phase::Waypoints));
        t[TermId::Energy] = 1.0;
        assert!(!t.zero_after(Phase::Waypoints));
        assert!(t.zero_after(Phase::Flown));
        t[TermId::Obstacle] = 1.0;
        assert!(!t.zero_after(Phase::Flown));
        assert!(t.zero_after(Phase::Fleet));
    }

    #[test]
    fn names_are_distinct_and_json_round_trips() {
        let mut t = Terms::default();
        for (k, id) in TermId::ALL.into_iter().enumerate() {
            t[id] = k as f64 + 0.5;
            assert_eq!(id.index(), k);
        }
        let json = serde_json::to_string(&t).expect("serialises");
        assert!(json.starts_with(r#"{"length":0.5,"threat":1.5"#), "{json}");
        assert_eq!(serde_json::from_str::<Terms>(&json).expect("parses"), t);
        assert!(serde_json::from_str::<Terms>(r#"{"lenght": 1}"#).is_err());
    }

    #[test]
    fn the_spso_preset_drops_the_cooperative_terms() {
        use crate::world::spec::{ObjectivePreset, ObjectiveSpec};
        let mut o = ObjectiveSpec::default();
        let raw = Terms::new([1.0; TERM_COUNT]);
        let paper = raw.weighted(&o.weights()).sum();
        o.preset = ObjectivePreset::SpsoMycost;
        let spso = raw.weighted(&o.weights()).sum();
        let own = [
            TermId::Length,
            TermId::Threat,
            TermId::Altitude,
            TermId::Smoothness,
        ];
        assert_eq!(spso, own.iter().map(|&t| o.weight(t)).sum::<f64>());
        assert_eq!(spso, 5.0 + 1.0 + 10.0 + 1.0);
        assert!(paper > spso);
        assert_eq!(NAMES[0], "length");
        assert_eq!(term_named("obstacle"), Some(TermId::Obstacle));
    }
}
