//! The cost terms as one list.
//!
//! Names, units, weights, per-UAV values, breakdowns, run records and every renderer come
//! from [`TermId::ALL`], so adding a term is a variant here (name, unit, weight field of the
//! scenario's `[objective]`) and the file that computes it; nothing else lists terms.

use std::ops::{Index, IndexMut};

use serde::de::{MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::world::spec::{ObjectivePreset, ObjectiveSpec};

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

    /// A term of the paper's cooperative model (weight 0 under the `spso` preset).
    #[must_use]
    pub const fn cooperative(self) -> bool {
        !matches!(
            self,
            Self::Length | Self::Threat | Self::Altitude | Self::Smoothness
        )
    }

    /// The term's weight in `objective`.
    #[must_use]
    pub fn weight(self, o: &ObjectiveSpec) -> f64 {
        if self.cooperative() && o.preset == ObjectivePreset::Spso {
            return 0.0;
        }
        match self {
            Self::Length => o.length,
            Self::Threat => o.threat,
            Self::Altitude => o.altitude,
            Self::Smoothness => o.smoothness,
            Self::Safety => o.safety,
            Self::Energy => o.energy,
            Self::Communication => o.communication,
            Self::Turning => o.turning,
            Self::Obstacle => o.obstacle,
        }
    }

    const fn index(self) -> usize {
        self as usize
    }
}

/// One value per term (raw or weighted). Serialised as a map `{name: value}`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Terms([f64; TERM_COUNT]);

impl Terms {
    /// `(term, value)` in report order.
    pub fn iter(&self) -> impl Iterator<Item = (TermId, f64)> + '_ {
        TermId::ALL.iter().map(|&t| (t, self[t]))
    }

    /// The values added up, in term order.
    #[must_use]
    pub fn sum(&self) -> f64 {
        self.0.iter().sum()
    }

    /// Each term times its weight in `objective`.
    #[must_use]
    pub fn weighted(&self, objective: &ObjectiveSpec) -> Self {
        let mut w = *self;
        for t in TermId::ALL {
            w[t] *= t.weight(objective);
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
                    let id = TermId::ALL
                        .into_iter()
                        .find(|t| t.name() == k)
                        .ok_or_else(|| {
                            serde::de::Error::unknown_field(
                                &k,
                                &[
                                    "length",
                                    "threat",
                                    "altitude",
                                    "smoothness",
                                    "safety",
                                    "energy",
                                    "communication",
                                    "turning",
                                    "obstacle",
                                ],
                            )
                        })?;
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
        let mut o = ObjectiveSpec::default();
        let mut raw = Terms::default();
        for t in TermId::ALL {
            raw[t] = 1.0;
        }
        let paper = raw.weighted(&o).sum();
        o.preset = ObjectivePreset::Spso;
        let spso = raw.weighted(&o).sum();
        assert_eq!(spso, o.length + o.threat + o.altitude + o.smoothness);
        assert!(paper > spso);
    }
}
