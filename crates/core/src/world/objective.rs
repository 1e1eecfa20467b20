//! The objective's settings, `[objective]` of a scenario: which objective, each cost term's
//! weight, Eq. 8's epsilon and the penalty on hard violations.
//!
//! The weights are keyed by term ([`TermId`]): `[objective]` names each by
//! [`TermId::name`] (`length = 5`, `obstacle = 100`, as it always has), and a new term is
//! read, written, defaulted and validated here without a field of its own.

use std::fmt;

use serde::de::{self, MapAccess, Visitor};
use serde::ser::SerializeStruct;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::cost::term::{term_named, TermId, Terms, NAMES, TERM_COUNT};

/// Which objective is minimised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ObjectivePreset {
    /// The DLS-SMPSO paper's Eq. 2: SPSO's terms per UAV plus the cooperative terms, hard
    /// violations penalised (`cooperative`; `paper` in files before issue 44, still read).
    #[default]
    #[serde(alias = "paper")]
    Cooperative,
    /// SPSO's `MyCost.m` exactly (collisions cost +inf); single-UAV cross-checks
    /// (`spso-mycost`; `spso` in files before issue 44, still read).
    #[serde(alias = "spso")]
    SpsoMycost,
}

/// Weights of Eq. 2 (the paper's w1..w6) on top of SPSO's per-UAV terms.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObjectiveSpec {
    /// Which objective is minimised (`paper`).
    pub preset: ObjectivePreset,
    /// Each term's weight as the scenario gives it ([`TermId::default_weight`] where it
    /// does not); what the cost uses is [`ObjectiveSpec::weights`].
    pub weights: Terms,
    /// epsilon of Eq. 8, m^2 (1).
    pub obstacle_epsilon: f64,
    /// Penalty per unit of hard-constraint violation (1000); 0 drops the penalty.
    pub violation_penalty: f64,
}

impl Default for ObjectiveSpec {
    fn default() -> Self {
        Self {
            preset: ObjectivePreset::Cooperative,
            weights: Terms::new(TermId::ALL.map(TermId::default_weight)),
            obstacle_epsilon: 1.0,
            violation_penalty: 1000.0,
        }
    }
}

impl ObjectiveSpec {
    /// The weight the cost gives term `t`: its weight, but 0 for a cooperative term under
    /// the `spso-mycost` objective preset (SPSO's MyCost has only its own four terms).
    #[must_use]
    pub fn weight(&self, t: TermId) -> f64 {
        if t.cooperative() && self.preset == ObjectivePreset::SpsoMycost {
            0.0
        } else {
            self.weights[t]
        }
    }

    /// Every term's weight as the cost gives it ([`ObjectiveSpec::weight`]).
    #[must_use]
    pub fn weights(&self) -> Terms {
        Terms::new(TermId::ALL.map(|t| self.weight(t)))
    }
}

/// `[objective]`'s keys other than the terms'.
const PRESET: &str = "preset";
const EPSILON: &str = "obstacle_epsilon";
const PENALTY: &str = "violation_penalty";

/// Every key of `[objective]`, in the order they are written.
const FIELDS: [&str; TERM_COUNT + 3] = {
    let mut fields = [""; TERM_COUNT + 3];
    fields[0] = PRESET;
    let mut k = 0;
    while k < TERM_COUNT {
        fields[k + 1] = NAMES[k];
        k += 1;
    }
    fields[TERM_COUNT + 1] = EPSILON;
    fields[TERM_COUNT + 2] = PENALTY;
    fields
};

impl Serialize for ObjectiveSpec {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut o = s.serialize_struct("ObjectiveSpec", FIELDS.len())?;
        o.serialize_field(PRESET, &self.preset)?;
        for (t, w) in self.weights.iter() {
            o.serialize_field(t.name(), &w)?;
        }
        o.serialize_field(EPSILON, &self.obstacle_epsilon)?;
        o.serialize_field(PENALTY, &self.violation_penalty)?;
        o.end()
    }
}

/// A key of `[objective]`, as its index in [`FIELDS`]; an unknown key is refused while it
/// is read, so the error points at it.
struct Key(usize);

impl<'de> Deserialize<'de> for Key {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct KeyVisitor;
        impl Visitor<'_> for KeyVisitor {
            type Value = Key;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a field of [objective]")
            }

            fn visit_str<E: de::Error>(self, v: &str) -> Result<Key, E> {
                FIELDS
                    .iter()
                    .position(|f| *f == v)
                    .map(Key)
                    .ok_or_else(|| E::unknown_field(v, &FIELDS))
            }
        }
        d.deserialize_identifier(KeyVisitor)
    }
}

impl<'de> Deserialize<'de> for ObjectiveSpec {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct ObjectiveVisitor;
        impl<'de> Visitor<'de> for ObjectiveVisitor {
            type Value = ObjectiveSpec;

            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("struct ObjectiveSpec")
            }

            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<ObjectiveSpec, A::Error> {
                let mut o = ObjectiveSpec::default();
                let mut seen = [false; TERM_COUNT + 3];
                while let Some(Key(slot)) = map.next_key::<Key>()? {
                    if std::mem::replace(&mut seen[slot], true) {
                        return Err(de::Error::duplicate_field(FIELDS[slot]));
                    }
                    let key = FIELDS[slot];
                    match term_named(key) {
                        Some(t) => o.weights[t] = map.next_value()?,
                        None if key == PRESET => o.preset = map.next_value()?,
                        None if key == EPSILON => o.obstacle_epsilon = map.next_value()?,
                        None => o.violation_penalty = map.next_value()?,
                    }
                }
                Ok(o)
            }
        }
        d.deserialize_struct("ObjectiveSpec", &FIELDS, ObjectiveVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn objective_toml_is_keyed_by_term_name_with_defaults_and_refuses_unknown_keys() {
        let o: ObjectiveSpec = toml::from_str("length = 2.5\nobstacle = 7\n").expect("parses");
        assert_eq!(o.weights[TermId::Length], 2.5);
        assert_eq!(o.weights[TermId::Obstacle], 7.0);
        assert_eq!(o.weights[TermId::Energy], TermId::Energy.default_weight());
        assert_eq!(o.violation_penalty, 1000.0);
        let e = toml::from_str::<ObjectiveSpec>("lenght = 1\n").expect_err("misspelt");
        assert!(
            e.to_string()
                .contains("unknown field `lenght`, expected one of `preset`, `length`"),
            "{e}"
        );
        assert!(toml::from_str::<ObjectiveSpec>("length = \"x\"\n").is_err());
        let text = toml::to_string(&ObjectiveSpec::default()).expect("writes");
        assert!(
            text.starts_with("preset = \"cooperative\"\nlength = 5.0\nthreat = 1.0\n"),
            "{text}"
        );
        // The names of files written before issue 44 are still read.
        for (old, preset) in [
            ("paper", ObjectivePreset::Cooperative),
            ("spso", ObjectivePreset::SpsoMycost),
        ] {
            let spec: ObjectiveSpec =
                toml::from_str(&format!("preset = \"{old}\"\n")).expect("an old name");
            assert_eq!(spec.preset, preset);
        }
        assert_eq!(
            toml::from_str::<ObjectiveSpec>(&text).expect("reads back"),
            ObjectiveSpec::default()
        );
    }
}
