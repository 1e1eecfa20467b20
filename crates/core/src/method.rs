//! A method is data: an optimizer, an encoding and an initialisation.
//!
//! The first build named algorithms and let the encoding follow from the name, which hid
//! that PSO, APSO and SPSO are one optimizer: with `--encoding spherical` PSO *was* SPSO,
//! bit for bit. Here the three parts are explicit and every record, summary, figure and
//! `plan` output names all three. A [`Method`] whose parts match a named preset is labelled
//! by the preset's name (so PSO on the spherical encoding from a uniform box is visibly
//! `spso`); any other combination is labelled `optimizer/encoding/init`, which parses back.
//!
//! | preset | optimizer | encoding | init | source |
//! |---|---|---|---|---|
//! | `pso` | pso | cartesian | line | Kennedy & Eberhart 1995; init on planes across the start-goal line (Fu et al. 2012) |
//! | `apso` | pso | angle | line | Zhong, Li, Qian 2008; Fu, Ding, Zhou 2012 |
//! | `spso` | pso | spherical | uniform | Phung & Ha 2021 |
//! | `dls-smpso` | dls-paper | spherical | uniform | the DLS-SMPSO paper |
//! | `dls-smpso-exemplar` | dls-exemplar | spherical | uniform | Xu et al. 2019 exemplars on SPSO |
//! | `qpso` | qpso | spherical | uniform | Sun, Feng, Xu 2004 |
//! | `gwo` | gwo | spherical | uniform | Mirjalili et al. 2014 |
//! | `abc` | abc | spherical | uniform | Karaboga 2005 |
//! | `pso-uniform`, `apso-uniform` | pso | cartesian / angle | uniform | ablations: the first build's PSO and APSO |
//! | `swarmplan` | coop | spherical | line-band | swarmplan's own: cooperative coevolution, feasibility first, from bowed start-goal lines, going on from the route layer's way in height at half the budget when more than 20 violations are left (issue 46) |
//! | `swarmplan-uniform` | coop | spherical | uniform | ablation: swarmplan's method from a uniform box (its default before; docs/results.md) |
//! | `lshade` | lshade | spherical | uniform | Tanabe & Fukunaga 2014 (a modern baseline, on the encoding the paper's methods use) |
//! | `cmaes` | cmaes | spherical | uniform | Hansen & Ostermeier 2001 with IPOP restarts (Auger & Hansen 2005) |
//!
//! The paper does not say what QPSO, GWO and ABC search over; its Tables 4-5 put them within
//! 30 % of DLS-SMPSO, which on this problem only the motion encoding comes near (on
//! coordinates their best plans cost 30-80 times more, docs/results.md), so they use it.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Deserializer, Serialize, Serializer};
use thiserror::Error;

use crate::encoding::{EncodingKind, InitKind};
use crate::optim::OptimizerKind;

/// An optimizer on an encoding from an initialisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Method {
    /// The search algorithm.
    pub optimizer: OptimizerKind,
    /// How a point of the search space maps to paths.
    pub encoding: EncodingKind,
    /// How starting points are drawn.
    pub init: InitKind,
}

/// A named method.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Preset {
    /// Its name on the command line and in records (`pso`, `spso`, ...).
    pub name: &'static str,
    /// The optimizer, encoding and initialisation it names.
    pub method: Method,
    /// Whether it is one of the paper's rows (Tables 4-5) or SPSO, its DLS ablation.
    pub paper: bool,
}

const fn preset(
    name: &'static str,
    optimizer: OptimizerKind,
    encoding: EncodingKind,
    init: InitKind,
    paper: bool,
) -> Preset {
    Preset {
        name,
        method: Method {
            optimizer,
            encoding,
            init,
        },
        paper,
    }
}

/// Every named method, the paper's first, in table order.
pub const PRESETS: [Preset; 14] = [
    preset(
        "pso",
        OptimizerKind::Pso,
        EncodingKind::Cartesian,
        InitKind::Line,
        true,
    ),
    preset(
        "apso",
        OptimizerKind::Pso,
        EncodingKind::Angle,
        InitKind::Line,
        true,
    ),
    preset(
        "qpso",
        OptimizerKind::Qpso,
        EncodingKind::Spherical,
        InitKind::Uniform,
        true,
    ),
    preset(
        "gwo",
        OptimizerKind::Gwo,
        EncodingKind::Spherical,
        InitKind::Uniform,
        true,
    ),
    preset(
        "abc",
        OptimizerKind::Abc,
        EncodingKind::Spherical,
        InitKind::Uniform,
        true,
    ),
    preset(
        "spso",
        OptimizerKind::Pso,
        EncodingKind::Spherical,
        InitKind::Uniform,
        true,
    ),
    preset(
        "dls-smpso",
        OptimizerKind::DlsPaper,
        EncodingKind::Spherical,
        InitKind::Uniform,
        true,
    ),
    preset(
        "dls-smpso-exemplar",
        OptimizerKind::DlsExemplar,
        EncodingKind::Spherical,
        InitKind::Uniform,
        false,
    ),
    preset(
        "pso-uniform",
        OptimizerKind::Pso,
        EncodingKind::Cartesian,
        InitKind::Uniform,
        false,
    ),
    preset(
        "apso-uniform",
        OptimizerKind::Pso,
        EncodingKind::Angle,
        InitKind::Uniform,
        false,
    ),
    preset(
        "swarmplan",
        OptimizerKind::Coop,
        EncodingKind::Spherical,
        InitKind::LineBand,
        false,
    ),
    preset(
        "swarmplan-uniform",
        OptimizerKind::Coop,
        EncodingKind::Spherical,
        InitKind::Uniform,
        false,
    ),
    preset(
        "lshade",
        OptimizerKind::Lshade,
        EncodingKind::Spherical,
        InitKind::Uniform,
        false,
    ),
    preset(
        "cmaes",
        OptimizerKind::Cmaes,
        EncodingKind::Spherical,
        InitKind::Uniform,
        false,
    ),
];

impl Method {
    /// The method of the preset `name`.
    pub fn preset(name: &str) -> Result<Self, UnknownMethod> {
        PRESETS
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(name))
            .map(|p| p.method)
            .ok_or_else(|| UnknownMethod(name.to_owned()))
    }

    /// The paper's methods (Tables 4-5) and SPSO, in table order.
    #[must_use]
    pub fn paper_methods() -> Vec<Self> {
        PRESETS
            .iter()
            .filter(|p| p.paper)
            .map(|p| p.method)
            .collect()
    }

    /// The preset this method is, if any.
    #[must_use]
    pub fn preset_name(&self) -> Option<&'static str> {
        PRESETS.iter().find(|p| p.method == *self).map(|p| p.name)
    }

    /// The preset's name, else `optimizer/encoding/init`.
    #[must_use]
    pub fn label(&self) -> String {
        self.preset_name().map_or_else(
            || format!("{}/{}/{}", self.optimizer, self.encoding, self.init),
            str::to_owned,
        )
    }

    /// This method with some parts replaced.
    #[must_use]
    pub fn with(self, encoding: Option<EncodingKind>, init: Option<InitKind>) -> Self {
        Self {
            encoding: encoding.unwrap_or(self.encoding),
            init: init.unwrap_or(self.init),
            ..self
        }
    }
}

impl fmt::Display for Method {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.label())
    }
}

/// Every preset's name, comma-separated in table order, for messages and help texts.
#[must_use]
pub fn preset_names() -> String {
    PRESETS.map(|p| p.name).join(", ")
}

/// A method name that is neither a preset nor `optimizer/encoding/init`.
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[error("unknown method {0:?}; expected a preset ({presets}) or optimizer/encoding/init such as pso/spherical/line", presets = preset_names())]
pub struct UnknownMethod(pub String);

impl FromStr for Method {
    type Err = UnknownMethod;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        if let Ok(m) = Self::preset(s) {
            return Ok(m);
        }
        let bad = || UnknownMethod(s.to_owned());
        let mut parts = s.split('/');
        let (Some(o), Some(e), Some(i), None) =
            (parts.next(), parts.next(), parts.next(), parts.next())
        else {
            return Err(bad());
        };
        Ok(Self {
            optimizer: o.parse().map_err(|_| bad())?,
            encoding: e.parse().map_err(|_| bad())?,
            init: i.parse().map_err(|_| bad())?,
        })
    }
}

/// Serialised as its label, so files say `"spso"` or `"pso/spherical/line"`.
impl Serialize for Method {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.label())
    }
}

impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn presets_are_distinct_and_labels_round_trip() {
        for (i, a) in PRESETS.iter().enumerate() {
            for b in &PRESETS[i + 1..] {
                assert_ne!(a.method, b.method, "{} and {}", a.name, b.name);
                assert_ne!(a.name, b.name);
            }
            assert_eq!(a.method.label(), a.name);
            assert_eq!(a.name.parse::<Method>(), Ok(a.method));
        }
        for o in OptimizerKind::ALL {
            for e in EncodingKind::ALL {
                for i in InitKind::ALL {
                    let m = Method {
                        optimizer: o,
                        encoding: e,
                        init: i,
                    };
                    assert_eq!(m.label().parse::<Method>(), Ok(m));
                    let json = serde_json::to_string(&m).expect("serialises");
                    assert_eq!(serde_json::from_str::<Method>(&json).expect("parses"), m);
                }
            }
        }
    }

    #[test]
    fn pso_on_the_spherical_encoding_is_labelled_spso() {
        let pso = Method::preset("pso").expect("preset");
        assert_eq!(
            pso.with(Some(EncodingKind::Spherical), Some(InitKind::Uniform))
                .label(),
            "spso"
        );
        assert_eq!(
            pso.with(Some(EncodingKind::Spherical), None).label(),
            "pso/spherical/line"
        );
        assert!("pso/spherical".parse::<Method>().is_err());
        assert!("nope".parse::<Method>().is_err());
    }

    #[test]
    fn the_paper_rows_come_first_in_table_order() {
        let labels: Vec<String> = Method::paper_methods().iter().map(Method::label).collect();
        assert_eq!(
            labels,
            ["pso", "apso", "qpso", "gwo", "abc", "spso", "dls-smpso"]
        );
    }
}
