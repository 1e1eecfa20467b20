//! The registry of optimizers and their parameters.
//!
//! [`OptimizerParams`] holds one section per optimizer, so a single file (or CLI default)
//! configures a whole comparison. Every section's `DEFAULT` constant is the paper's setting
//! and feeds `Default` and serde's defaults alike. [`OptimizerParams::validate`] runs once,
//! up front, so the optimizers' hot paths can stay infallible; [`build`] then makes the
//! optimizer.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::abc::AbcParams;
use super::cmaes::CmaesParams;
use super::cooperative::CoopParams;
use super::dls_exemplar::DlsExemplarParams;
use super::dls_paper::DlsPaperParams;
use super::gwo::GwoParams;
use super::lshade::LshadeParams;
use super::pso::PsoParams;
use super::qpso::QpsoParams;
use super::Optimizer;

pub use super::config::{
    check, OptimizerConfig, ParamsError, POPULATION_EXPECTED, POPULATION_RANGE,
};

/// The one list of optimizers. Each line names the [`OptimizerKind`] variant, its name on
/// the command line and in records, its section in [`OptimizerParams`] (and in a
/// `--params` TOML file), optionally `| "old"` an earlier name of the section that is still
/// read, and the section's type, which implements [`OptimizerConfig`].
/// Everything that enumerates optimizers (the enum, `ALL`, names, the parameter struct,
/// validation, population, [`build`], messages and help texts) is generated from it, so a
/// new optimizer is its own file and one line here (docs/contributing.md).
macro_rules! optimizer_registry {
    ($($(#[$doc:meta])* $kind:ident = $name:literal, $section:ident $(| $old:literal)?: $params:ty;)*) => {
        /// The optimizers, one file each, listed once in the registry of `optim/params.rs`.
        #[derive(
            Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize,
        )]
        pub enum OptimizerKind {
            $($(#[$doc])* #[serde(rename = $name)] $kind,)*
        }

        impl OptimizerKind {
            /// Every optimizer, in the registry's order.
            pub const ALL: [Self; [$(stringify!($kind)),*].len()] = [$(Self::$kind),*];

            /// The name on the command line and in records (`dls-paper`).
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self {
                    $(Self::$kind => $name,)*
                }
            }

            /// The optimizer's section in [`OptimizerParams`] and in a `--params` file
            /// (`dls_paper`).
            #[must_use]
            pub const fn section(self) -> &'static str {
                match self {
                    $(Self::$kind => stringify!($section),)*
                }
            }

            /// The budget a run gets when none is given: the paper's 200 iterations for
            /// the paper's optimizers, [`PAPER_EVALUATIONS`] for `coop` (whose iterations
            /// are 10 evaluations).
            #[must_use]
            pub fn default_budget(self) -> super::Budget {
                match self {
                    $(Self::$kind => <$params>::DEFAULT.default_budget(),)*
                }
            }
        }

        /// Parameters of every optimizer (a section each); the default is the paper's
        /// setting.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub struct OptimizerParams {
            $($(#[$doc])* $(#[serde(alias = $old)])? pub $section: $params,)*
        }

        impl OptimizerParams {
            /// Every section at its default.
            pub const DEFAULT: Self = Self {
                $($section: <$params>::DEFAULT,)*
            };

            /// Checks every section; the error names the first bad field with its section.
            pub fn validate(&self) -> Result<(), ParamsError> {
                $(self.$section.validate().map_err(|e| e.within(stringify!($section)))?;)*
                Ok(())
            }

            /// The population size `kind` will use (for ABC: bees, twice the food sources).
            #[must_use]
            pub fn population(&self, kind: OptimizerKind) -> usize {
                match kind {
                    $(OptimizerKind::$kind => self.$section.population(),)*
                }
            }

            /// Sets the population size of every optimizer (e.g. the population-500 runs).
            pub fn set_population(&mut self, n: usize) {
                $(self.$section.set_population(n);)*
            }
        }

        /// Makes the optimizer `kind`. `params` should have passed
        /// [`OptimizerParams::validate`] (see [`try_build`]); out-of-range sizes are raised
        /// to the smallest workable value rather than panicking.
        #[must_use]
        pub fn build(kind: OptimizerKind, params: &OptimizerParams) -> Box<dyn Optimizer> {
            match kind {
                $(OptimizerKind::$kind => params.$section.build(),)*
            }
        }
    };
}

optimizer_registry! {
    /// Inertia-weight PSO with SPSO's clamping and mirroring ([`super::pso`]); PSO, APSO
    /// and SPSO share it, on whatever encoding the method names.
    Pso = "pso", pso: PsoParams;
    /// DLS-SMPSO as the paper defines it ([`super::dls_paper`]).
    /// Section `dls_paper`, named after the optimizer like every other; files of earlier
    /// versions called it `dls_smpso` (after the method preset), which is still read.
    DlsPaper = "dls-paper", dls_paper | "dls_smpso": DlsPaperParams;
    /// DLS-SMPSO with Xu et al.'s exemplars ([`super::dls_exemplar`]).
    DlsExemplar = "dls-exemplar", dls_exemplar: DlsExemplarParams;
    /// Quantum-behaved PSO ([`super::qpso`]).
    Qpso = "qpso", qpso: QpsoParams;
    /// Grey wolf optimizer ([`super::gwo`]).
    Gwo = "gwo", gwo: GwoParams;
    /// Artificial bee colony ([`super::abc`]).
    Abc = "abc", abc: AbcParams;
    /// Cooperative coevolution, feasibility first ([`super::cooperative`]): swarmplan's own.
    Coop = "coop", coop: CoopParams;
    /// L-SHADE ([`super::lshade`]): a modern baseline, CEC 2014's winner.
    Lshade = "lshade", lshade: LshadeParams;
    /// CMA-ES with IPOP restarts ([`super::cmaes`]): a modern baseline.
    Cmaes = "cmaes", cmaes: CmaesParams;
}

impl OptimizerKind {
    /// Every optimizer's name, comma-separated, for messages and help texts.
    #[must_use]
    pub fn names() -> String {
        Self::ALL.map(Self::name).join(", ")
    }

    /// Every optimizer's parameter section, comma-separated, for messages and help texts.
    #[must_use]
    pub fn sections() -> String {
        Self::ALL.map(Self::section).join(", ")
    }
}

/// Mean evaluations of a DLS-SMPSO run at the paper's setting (200 iterations of 50), as
/// measured on both paper cases (30 runs each: 38,629 and 38,815; docs/results.md): the
/// equal budget at which methods are compared, and the default budget of optimizers that
/// have no paper setting of their own.
pub const PAPER_EVALUATIONS: u64 = 38_700;

impl fmt::Display for OptimizerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An optimizer name that is not one of [`OptimizerKind::ALL`].
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[error("unknown optimizer {0:?}; expected one of {names}", names = OptimizerKind::names())]
pub struct UnknownOptimizer(pub String);

impl FromStr for OptimizerKind {
    type Err = UnknownOptimizer;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| UnknownOptimizer(s.to_owned()))
    }
}

impl Default for OptimizerParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Validates `params`, then [`build`]s.
pub fn try_build(
    kind: OptimizerKind,
    params: &OptimizerParams,
) -> Result<Box<dyn Optimizer>, ParamsError> {
    params.validate()?;
    Ok(build(kind, params))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn optimizer_names_round_trip() {
        for a in OptimizerKind::ALL {
            assert_eq!(a.to_string().parse::<OptimizerKind>(), Ok(a));
            let json = serde_json::to_string(&a).expect("serialises");
            assert_eq!(json, format!("\"{a}\""));
        }
        assert_eq!(
            "DLS-Paper".parse::<OptimizerKind>(),
            Ok(OptimizerKind::DlsPaper)
        );
        assert!("dls".parse::<OptimizerKind>().is_err());
    }

    #[test]
    fn defaults_are_the_paper_settings_and_valid() {
        let p = OptimizerParams::default();
        p.validate().expect("defaults are valid");
        for a in OptimizerKind::ALL {
            let want = match a {
                OptimizerKind::Coop => 10,
                // L-SHADE's initial population cap; it shrinks to 4 over the run.
                OptimizerKind::Lshade => 100,
                // CMA-ES: 0 = 4 + floor(3 ln n), from the dimension.
                OptimizerKind::Cmaes => 0,
                _ => 50,
            };
            assert_eq!(p.population(a), want, "{a}");
        }
        assert_eq!(p.pso.inertia, 1.0);
        assert_eq!(p.pso.cognitive, 1.5);
        assert_eq!(p.pso.social, 1.5);
    }

    #[test]
    fn serde_fills_defaults_and_rejects_unknown_fields() {
        let p: OptimizerParams =
            serde_json::from_str(r#"{"dls_exemplar": {"pso": {"population": 20}}}"#)
                .expect("parses");
        assert_eq!(p.dls_exemplar.pso.population, 20);
        assert_eq!(p.dls_paper.lambda, 0.5);
        assert_eq!(p.gwo, GwoParams::DEFAULT);
        assert!(serde_json::from_str::<OptimizerParams>(r#"{"pso": {"inertai": 1}}"#).is_err());
        assert!(serde_json::from_str::<OptimizerParams>(r#"{"sps": {}}"#).is_err());
        // The section's old name is still read.
        let old: OptimizerParams =
            serde_json::from_str(r#"{"dls_smpso": {"lambda": 0.25}}"#).expect("old section");
        assert_eq!(old.dls_paper.lambda, 0.25);
    }

    #[test]
    fn validation_names_the_field() {
        let mut p = OptimizerParams::default();
        p.dls_paper.pso.velocity_clamp = -1.0;
        let e = p.validate().expect_err("negative clamp");
        assert_eq!(e.field, "dls_paper.pso.velocity_clamp");
        assert!(e
            .to_string()
            .starts_with("dls_paper.pso.velocity_clamp: expected"));
        let mut p = OptimizerParams::default();
        p.abc.population = 3;
        assert_eq!(
            p.validate().expect_err("too few bees").field,
            "abc.population"
        );
        assert!(try_build(OptimizerKind::Abc, &p).is_err());
    }
}
