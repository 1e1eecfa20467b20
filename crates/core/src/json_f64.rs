//! Serde helpers that keep non-finite `f64`s through JSON.
//!
//! JSON has no infinity or NaN: serde_json writes them as `null`, which then fails to
//! deserialize as `f64`. A summary of costs meets `+inf` whenever a run failed, so the
//! statistics structs write non-finite values as the strings `"inf"`, `"-inf"` and
//! `"nan"` (the spellings Python's `float()` and numpy read back) and finite values as
//! plain numbers. Use with `#[serde(with = "json_f64")]`.
//!
//! Deserialization asks the format what it holds (`deserialize_any`), so it needs a
//! self-describing format (JSON, TOML), which is what statistics are written to.

use std::fmt;

use serde::de::{self, Visitor};
use serde::{Deserializer, Serializer};

/// The string written for `value` when it is not finite, `None` when it is finite.
#[must_use]
pub fn non_finite_name(value: f64) -> Option<&'static str> {
    if value.is_finite() {
        None
    } else if value.is_nan() {
        Some("nan")
    } else if value > 0.0 {
        Some("inf")
    } else {
        Some("-inf")
    }
}

/// Writes a finite value as a number, a non-finite one as `"inf"`, `"-inf"` or `"nan"`.
///
/// # Errors
/// Whatever the serializer returns.
pub fn serialize<S: Serializer>(value: &f64, serializer: S) -> Result<S::Ok, S::Error> {
    match non_finite_name(*value) {
        None => serializer.serialize_f64(*value),
        Some(name) => serializer.serialize_str(name),
    }
}

/// Reads a number, or one of the strings `"inf"`, `"-inf"`, `"nan"`.
///
/// # Errors
/// A value that is neither a number nor one of those strings.
pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f64, D::Error> {
    deserializer.deserialize_any(F64Visitor)
}

/// One value written and read as [`serialize`] and [`deserialize`] do, for the
/// collections below.
#[derive(serde::Serialize, serde::Deserialize)]
struct Item(#[serde(with = "self")] f64);

/// The same for every element of a `Vec<f64>`: `#[serde(with = "json_f64::vec")]`.
pub mod vec {
    use serde::{Deserialize, Deserializer, Serializer};

    use super::Item;

    /// Writes each element as [`super::serialize`] does.
    ///
    /// # Errors
    /// Whatever the serializer returns.
    pub fn serialize<S: Serializer>(values: &[f64], serializer: S) -> Result<S::Ok, S::Error> {
        serializer.collect_seq(values.iter().map(|v| Item(*v)))
    }

    /// Reads a sequence of numbers or `"inf"`, `"-inf"`, `"nan"`.
    ///
    /// # Errors
    /// An element that is neither.
    pub fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<Vec<f64>, D::Error> {
        Ok(Vec::<Item>::deserialize(deserializer)?
            .into_iter()
            .map(|i| i.0)
            .collect())
    }
}

/// The same for every value of a map keyed by name: `#[serde(with = "json_f64::map")]`.
pub mod map {
    use std::collections::BTreeMap;

    use serde::{Deserialize, Deserializer, Serializer};

    use super::Item;

    /// Writes each value as [`super::serialize`] does.
    ///
    /// # Errors
    /// Whatever the serializer returns.
    pub fn serialize<S: Serializer>(
        values: &BTreeMap<String, f64>,
        serializer: S,
    ) -> Result<S::Ok, S::Error> {
        serializer.collect_map(values.iter().map(|(k, v)| (k, Item(*v))))
    }

    /// Reads numbers or `"inf"`, `"-inf"`, `"nan"` as the values.
    ///
    /// # Errors
    /// A value that is neither.
    pub fn deserialize<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<BTreeMap<String, f64>, D::Error> {
        Ok(BTreeMap::<String, Item>::deserialize(deserializer)?
            .into_iter()
            .map(|(k, i)| (k, i.0))
            .collect())
    }
}

/// The same for an `Option<f64>`, `None` as `null`: `#[serde(with = "json_f64::option")]`.
pub mod option {
    use serde::{Deserialize, Deserializer, Serializer};

    use super::Item;

    /// Writes `None` as `null` and a value as [`super::serialize`] does.
    ///
    /// # Errors
    /// Whatever the serializer returns.
    pub fn serialize<S: Serializer>(value: &Option<f64>, serializer: S) -> Result<S::Ok, S::Error> {
        match value {
            None => serializer.serialize_none(),
            Some(v) => serializer.serialize_some(&Item(*v)),
        }
    }

    /// Reads `null` as `None`, else a number or `"inf"`, `"-inf"`, `"nan"`.
    ///
    /// # Errors
    /// A value that is none of these.
    pub fn deserialize<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Option<f64>, D::Error> {
        Ok(Option::<Item>::deserialize(deserializer)?.map(|i| i.0))
    }
}

struct F64Visitor;

impl Visitor<'_> for F64Visitor {
    type Value = f64;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(r#"a number or one of "inf", "-inf", "nan""#)
    }

    fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
        Ok(v)
    }

    // Integers are read as the nearest f64, as serde_json itself does for `f64` fields.
    #[allow(clippy::cast_precision_loss)]
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
        Ok(v as f64)
    }

    #[allow(clippy::cast_precision_loss)]
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
        Ok(v as f64)
    }

    fn visit_str<E: de::Error>(self, v: &str) -> Result<f64, E> {
        match v {
            "inf" => Ok(f64::INFINITY),
            "-inf" => Ok(f64::NEG_INFINITY),
            "nan" => Ok(f64::NAN),
            _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
        }
    }
}

#[cfg(test)]
mod tests {
    use serde::{Deserialize, Serialize};

    #[derive(Debug, Serialize, Deserialize)]
    struct Wrapped {
        #[serde(with = "super")]
        v: f64,
    }

    fn round_trip(v: f64) -> (String, f64) {
        let json = serde_json::to_string(&Wrapped { v }).unwrap();
        let back: Wrapped = serde_json::from_str(&json).unwrap();
        (json, back.v)
    }

    #[test]
    fn maps_keep_their_non_finite_values_as_strings() {
        #[derive(Debug, Serialize, Deserialize)]
        struct Terms {
            #[serde(with = "super::map")]
            terms: std::collections::BTreeMap<String, f64>,
        }
        let terms = [("a".to_string(), 2.0), ("b".to_string(), f64::INFINITY)].into();
        let json = serde_json::to_string(&Terms { terms }).unwrap();
        assert_eq!(json, r#"{"terms":{"a":2.0,"b":"inf"}}"#);
        let back: Terms = serde_json::from_str(&json).unwrap();
        assert_eq!(back.terms["b"], f64::INFINITY);
    }

    #[test]
    fn finite_values_are_numbers() {
        assert_eq!(round_trip(1.5), (r#"{"v":1.5}"#.to_owned(), 1.5));
        assert_eq!(round_trip(-0.25).1, -0.25);
    }

    #[test]
    fn non_finite_values_are_strings() {
        assert_eq!(
            round_trip(f64::INFINITY),
            (r#"{"v":"inf"}"#.to_owned(), f64::INFINITY)
        );
        assert_eq!(round_trip(f64::NEG_INFINITY).0, r#"{"v":"-inf"}"#);
        assert_eq!(round_trip(f64::NEG_INFINITY).1, f64::NEG_INFINITY);
        let (json, back) = round_trip(f64::NAN);
        assert_eq!(json, r#"{"v":"nan"}"#);
        assert!(back.is_nan());
    }

    #[test]
    fn integers_are_accepted_and_other_strings_refused() {
        let w: Wrapped = serde_json::from_str(r#"{"v":3}"#).unwrap();
        assert_eq!(w.v, 3.0);
        let w: Wrapped = serde_json::from_str(r#"{"v":-3}"#).unwrap();
        assert_eq!(w.v, -3.0);
        assert!(serde_json::from_str::<Wrapped>(r#"{"v":"Infinity"}"#).is_err());
        assert!(serde_json::from_str::<Wrapped>(r#"{"v":null}"#).is_err());
    }
}
