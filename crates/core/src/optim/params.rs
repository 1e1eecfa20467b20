//! The registry of optimizers and their parameters.
//!
//! [`OptimizerParams`] holds one section per optimizer, so a single file (or CLI default)
//! configures a whole comparison. Every section's `DEFAULT` constant is the paper's setting
//! and feeds `Default` and serde's defaults alike. [`AlgorithmParams::validate`] runs once,
//! up front, so the optimizers' hot paths can stay infallible; [`build`] then makes the
//! optimizer.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::abc::{Abc, AbcParams};
use super::cmaes::{Cmaes, CmaesParams};
use super::cooperative::{CoopParams, Cooperative};
use super::dls_exemplar::{DlsExemplar, DlsExemplarParams};
use super::dls_paper::{DlsPaper, DlsPaperParams};
use super::gwo::{Gwo, GwoParams};
use super::lshade::{Lshade, LshadeParams};
use super::pso::{Pso, PsoParams};
use super::qpso::{Qpso, QpsoParams};
use super::Optimizer;

/// Population sizes every optimizer accepts, from a TOML section or `--population` alike: at
/// least 4 (ABC's two food sources; DE's mutation needs three others), at most 100,000 (the
/// swarm's arrays then stay below a few hundred MB on a 5-UAV plan).
pub const POPULATION_RANGE: std::ops::RangeInclusive<usize> = 4..=100_000;
/// How [`POPULATION_RANGE`] is said in messages.
pub const POPULATION_EXPECTED: &str = "a whole number in [4, 100000]";

/// A parameter with a bad value; `field` is its path (`dls_smpso.pso.velocity_clamp`).
#[derive(Debug, Error, Clone, PartialEq)]
#[error("{field}: expected {expected}, got {got}")]
pub struct ParamsError {
    pub field: String,
    pub expected: String,
    pub got: String,
}

impl ParamsError {
    /// The same error with `section.` prepended to the field path.
    #[must_use]
    pub fn within(mut self, section: &str) -> Self {
        self.field = format!("{section}.{}", self.field);
        self
    }
}

/// `Ok` when `ok`, else an error naming `field`.
pub(crate) fn check(
    ok: bool,
    field: &str,
    expected: &str,
    got: impl fmt::Display,
) -> Result<(), ParamsError> {
    if ok {
        Ok(())
    } else {
        Err(ParamsError {
            field: field.to_owned(),
            expected: expected.to_owned(),
            got: got.to_string(),
        })
    }
}

/// The optimizers, one file each. Adding one is a variant here, its parameter section in
/// [`OptimizerParams`] and a line in each `match` below.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OptimizerKind {
    /// Inertia-weight PSO with SPSO's clamping and mirroring ([`super::pso`]).
    Pso,
    /// DLS-SMPSO as the paper defines it ([`super::dls_paper`]).
    DlsPaper,
    /// DLS-SMPSO with Xu et al.'s exemplars ([`super::dls_exemplar`]).
    DlsExemplar,
    Qpso,
    Gwo,
    Abc,
    /// Cooperative coevolution, feasibility first ([`super::cooperative`]): swarmplan's own.
    Coop,
    /// L-SHADE ([`super::lshade`]): a modern baseline, CEC 2014's winner.
    Lshade,
    /// CMA-ES with IPOP restarts ([`super::cmaes`]): a modern baseline.
    Cmaes,
}

impl OptimizerKind {
    pub const ALL: [Self; 9] = [
        Self::Pso,
        Self::DlsPaper,
        Self::DlsExemplar,
        Self::Qpso,
        Self::Gwo,
        Self::Abc,
        Self::Coop,
        Self::Lshade,
        Self::Cmaes,
    ];

    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Pso => "pso",
            Self::DlsPaper => "dls-paper",
            Self::DlsExemplar => "dls-exemplar",
            Self::Qpso => "qpso",
            Self::Gwo => "gwo",
            Self::Abc => "abc",
            Self::Coop => "coop",
            Self::Lshade => "lshade",
            Self::Cmaes => "cmaes",
        }
    }
}

/// Mean evaluations of a DLS-SMPSO run at the paper's setting (200 iterations of 50), as
/// measured on both paper cases (30 runs each: 38,629 and 38,815; docs/results.md): the
/// equal budget at which methods are compared, and the default budget of optimizers that
/// have no paper setting of their own.
pub const PAPER_EVALUATIONS: u64 = 38_700;

impl OptimizerKind {
    /// The budget a run gets when none is given: the paper's 200 iterations for the paper's
    /// optimizers, [`PAPER_EVALUATIONS`] for `coop` (whose iterations are 10 evaluations).
    #[must_use]
    pub const fn default_budget(self) -> super::Budget {
        match self {
            Self::Coop => super::Budget::evaluations(PAPER_EVALUATIONS),
            _ => super::Budget::DEFAULT,
        }
    }
}

impl fmt::Display for OptimizerKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An optimizer name that is not one of [`OptimizerKind::ALL`].
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[error(
    "unknown optimizer {0:?}; expected one of pso, dls-paper, dls-exemplar, qpso, gwo, abc, coop"
)]
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

/// Parameters of every optimizer (a section each); the default is the paper's setting.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OptimizerParams {
    /// PSO on whatever encoding the method names (PSO, APSO and SPSO share it).
    pub pso: PsoParams,
    /// DLS-SMPSO, paper mode.
    pub dls_smpso: DlsPaperParams,
    /// DLS-SMPSO, exemplar mode.
    pub dls_exemplar: DlsExemplarParams,
    pub qpso: QpsoParams,
    pub gwo: GwoParams,
    pub abc: AbcParams,
    /// swarmplan's cooperative optimizer.
    pub coop: CoopParams,
    pub lshade: LshadeParams,
    pub cmaes: CmaesParams,
}

impl OptimizerParams {
    pub const DEFAULT: Self = Self {
        pso: PsoParams::DEFAULT,
        dls_smpso: DlsPaperParams::DEFAULT,
        dls_exemplar: DlsExemplarParams::DEFAULT,
        qpso: QpsoParams::DEFAULT,
        gwo: GwoParams::DEFAULT,
        abc: AbcParams::DEFAULT,
        coop: CoopParams::DEFAULT,
        lshade: LshadeParams::DEFAULT,
        cmaes: CmaesParams::DEFAULT,
    };

    /// Checks every section; the error names the first bad field with its section.
    pub fn validate(&self) -> Result<(), ParamsError> {
        self.pso.validate().map_err(|e| e.within("pso"))?;
        self.dls_smpso
            .validate()
            .map_err(|e| e.within("dls_smpso"))?;
        self.dls_exemplar
            .validate()
            .map_err(|e| e.within("dls_exemplar"))?;
        self.qpso.validate().map_err(|e| e.within("qpso"))?;
        self.gwo.validate().map_err(|e| e.within("gwo"))?;
        self.abc.validate().map_err(|e| e.within("abc"))?;
        self.coop.validate().map_err(|e| e.within("coop"))?;
        self.lshade.validate().map_err(|e| e.within("lshade"))?;
        self.cmaes.validate().map_err(|e| e.within("cmaes"))
    }

    /// The population size `kind` will use (for ABC: bees, twice the food sources).
    #[must_use]
    pub fn population(&self, kind: OptimizerKind) -> usize {
        match kind {
            OptimizerKind::Pso => self.pso.population,
            OptimizerKind::DlsPaper => self.dls_smpso.pso.population,
            OptimizerKind::DlsExemplar => self.dls_exemplar.pso.population,
            OptimizerKind::Qpso => self.qpso.population,
            OptimizerKind::Gwo => self.gwo.population,
            OptimizerKind::Abc => self.abc.population,
            OptimizerKind::Coop => self.coop.population,
            OptimizerKind::Lshade => self.lshade.max_population,
            OptimizerKind::Cmaes => self.cmaes.population,
        }
    }

    /// Sets the population size of every optimizer (e.g. the population-500 runs).
    pub fn set_population(&mut self, n: usize) {
        self.pso.population = n;
        self.dls_smpso.pso.population = n;
        self.dls_exemplar.pso.population = n;
        self.qpso.population = n;
        self.gwo.population = n;
        self.abc.population = n;
        self.coop.population = n;
        self.lshade.max_population = n.max(self.lshade.min_population);
        self.cmaes.population = n.max(4);
    }
}

impl Default for OptimizerParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Makes the optimizer `kind`. `params` should have passed [`OptimizerParams::validate`]
/// (see [`try_build`]); out-of-range sizes are raised to the smallest workable value rather
/// than panicking.
#[must_use]
pub fn build(kind: OptimizerKind, params: &OptimizerParams) -> Box<dyn Optimizer> {
    match kind {
        OptimizerKind::Pso => Box::new(Pso::new(params.pso)),
        OptimizerKind::DlsPaper => Box::new(DlsPaper::new(params.dls_smpso)),
        OptimizerKind::DlsExemplar => Box::new(DlsExemplar::new(params.dls_exemplar)),
        OptimizerKind::Qpso => Box::new(Qpso::new(params.qpso)),
        OptimizerKind::Gwo => Box::new(Gwo::new(params.gwo)),
        OptimizerKind::Abc => Box::new(Abc::new(params.abc)),
        OptimizerKind::Coop => Box::new(Cooperative::new(params.coop)),
        OptimizerKind::Lshade => Box::new(Lshade::new(params.lshade)),
        OptimizerKind::Cmaes => Box::new(Cmaes::new(params.cmaes)),
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
        assert_eq!(p.dls_smpso.lambda, 0.5);
        assert_eq!(p.gwo, GwoParams::DEFAULT);
        assert!(serde_json::from_str::<OptimizerParams>(r#"{"pso": {"inertai": 1}}"#).is_err());
        assert!(serde_json::from_str::<OptimizerParams>(r#"{"sps": {}}"#).is_err());
    }

    #[test]
    fn validation_names_the_field() {
        let mut p = OptimizerParams::default();
        p.dls_smpso.pso.velocity_clamp = -1.0;
        let e = p.validate().expect_err("negative clamp");
        assert_eq!(e.field, "dls_smpso.pso.velocity_clamp");
        assert!(e
            .to_string()
            .starts_with("dls_smpso.pso.velocity_clamp: expected"));
        let mut p = OptimizerParams::default();
        p.abc.population = 3;
        assert_eq!(
            p.validate().expect_err("too few bees").field,
            "abc.population"
        );
        assert!(try_build(OptimizerKind::Abc, &p).is_err());
    }
}
