//! The cooperative optimizer's switches, one enum per idea instead of a boolean each, so a
//! parameters file and a record say what was chosen (`compare = "penalised-cost"`), and two
//! switches that only make sense together (transplants and shifted copies) are one choice.
//!
//! Parameter files of earlier versions spelled them as booleans (`feasibility_first`,
//! `adaptive_spread`, `decompose`, `synchronous`, `transplant`); those keys and values are
//! still read ([`Switch::ON`], [`Switch::OFF`]). `shifted_copies = false` is now
//! `transplant = "perturbed"`.

use serde::Serialize;

/// How two candidates are compared.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Comparison {
    /// Deb's feasibility rules: a feasible candidate beats an infeasible one, two infeasible
    /// ones compare by violation (the default).
    FeasibilityFirst,
    /// Penalised cost alone (an ablation, docs/results.md).
    PenalisedCost,
}

/// How a block's perturbation spread is chosen per visit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Spread {
    /// Doubled after a visit that improved the context, halved after one that did not (the
    /// default).
    Adaptive,
    /// Always `perturbation` (an ablation).
    Fixed,
}

/// What one block of the search is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Blocks {
    /// One UAV at a time (the problem's block size; the default).
    PerUav,
    /// The whole plan as one block: a restarting PSO on the joint vector (an ablation).
    WholePlan,
}

/// When a sub-swarm's particles are evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Updates {
    /// All of a step's particles together, in parallel, against the gbest and context of
    /// the step's start (the default since issue 12).
    Synchronous,
    /// One after the other, gbest and context following each (the method as measured before
    /// issue 12).
    Sequential,
}

/// Whether a visit of a violating block borrows another block's path, and how.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Transplant {
    /// No transplant (an ablation).
    Off,
    /// Another block's path, perturbed like the other particles.
    Perturbed,
    /// A perturbed path, and after a round without progress a *shifted copy*: the donor's
    /// path moved sideways as a whole (the default).
    ShiftedWhenStuck,
}

impl Transplant {
    /// Whether there is a transplant at all.
    pub fn on(self) -> bool {
        self != Self::Off
    }
}

/// A switch: named values, and the boolean of the old spelling.
pub trait Switch: Sized + Copy + 'static {
    /// Every value with its name in a parameters file.
    const NAMES: &'static [(&'static str, Self)];
    /// The value the old spelling `true` meant.
    const ON: Self;
    /// The value the old spelling `false` meant.
    const OFF: Self;
}

/// Reads a switch from its name or, as earlier files spelled it, a boolean; the error lists
/// the names.
pub(super) fn read<'de, D, T>(d: D) -> Result<T, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Switch,
{
    struct Visitor<T>(std::marker::PhantomData<T>);
    impl<T: Switch> serde::de::Visitor<'_> for Visitor<T> {
        type Value = T;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            let names: Vec<String> = T::NAMES.iter().map(|(n, _)| format!("\"{n}\"")).collect();
            write!(f, "one of {} (or true / false)", names.join(", "))
        }
        fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<T, E> {
            Ok(if v { T::ON } else { T::OFF })
        }
        fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<T, E> {
            T::NAMES
                .iter()
                .find(|(n, _)| *n == v)
                .map(|&(_, t)| t)
                .ok_or_else(|| E::invalid_value(serde::de::Unexpected::Str(v), &self))
        }
    }
    d.deserialize_any(Visitor(std::marker::PhantomData))
}

impl Switch for Comparison {
    const NAMES: &'static [(&'static str, Self)] = &[
        ("feasibility-first", Self::FeasibilityFirst),
        ("penalised-cost", Self::PenalisedCost),
    ];
    const ON: Self = Self::FeasibilityFirst;
    const OFF: Self = Self::PenalisedCost;
}

impl Switch for Spread {
    const NAMES: &'static [(&'static str, Self)] =
        &[("adaptive", Self::Adaptive), ("fixed", Self::Fixed)];
    const ON: Self = Self::Adaptive;
    const OFF: Self = Self::Fixed;
}

impl Switch for Blocks {
    const NAMES: &'static [(&'static str, Self)] =
        &[("per-uav", Self::PerUav), ("whole-plan", Self::WholePlan)];
    const ON: Self = Self::PerUav;
    const OFF: Self = Self::WholePlan;
}

impl Switch for Updates {
    const NAMES: &'static [(&'static str, Self)] = &[
        ("synchronous", Self::Synchronous),
        ("sequential", Self::Sequential),
    ];
    const ON: Self = Self::Synchronous;
    const OFF: Self = Self::Sequential;
}

impl Switch for Transplant {
    const NAMES: &'static [(&'static str, Self)] = &[
        ("off", Self::Off),
        ("perturbed", Self::Perturbed),
        ("shifted-when-stuck", Self::ShiftedWhenStuck),
    ];
    /// `transplant = true` meant transplants with shifted copies (`shifted_copies`' default).
    const ON: Self = Self::ShiftedWhenStuck;
    const OFF: Self = Self::Off;
}
