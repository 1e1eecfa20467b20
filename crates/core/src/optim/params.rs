//! Which algorithm to run and with which parameters.
//!
//! [`AlgorithmParams`] holds one section per algorithm, so a single file (or CLI default)
//! configures a whole comparison. Every section's `DEFAULT` constant is the paper's setting
//! and feeds `Default` and serde's defaults alike. [`AlgorithmParams::validate`] runs once,
//! up front, so the optimizers' hot paths can stay infallible; [`build`] then makes the
//! optimizer.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};
use thiserror::Error;

use super::abc::{Abc, AbcParams};
use super::dls::{DlsParams, DlsSmpso};
use super::gwo::{Gwo, GwoParams};
use super::pso::{Pso, PsoParams};
use super::qpso::{Qpso, QpsoParams};
use super::Optimizer;

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

/// The optimizers of the comparison (serde and CLI names in kebab-case).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Algorithm {
    Pso,
    Apso,
    Spso,
    DlsSmpso,
    Qpso,
    Gwo,
    Abc,
}

impl Algorithm {
    pub const ALL: [Self; 7] = [
        Self::Pso,
        Self::Apso,
        Self::Spso,
        Self::DlsSmpso,
        Self::Qpso,
        Self::Gwo,
        Self::Abc,
    ];

    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Self::Pso => "pso",
            Self::Apso => "apso",
            Self::Spso => "spso",
            Self::DlsSmpso => "dls-smpso",
            Self::Qpso => "qpso",
            Self::Gwo => "gwo",
            Self::Abc => "abc",
        }
    }
}

impl fmt::Display for Algorithm {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// An algorithm name that is not one of [`Algorithm::ALL`].
#[derive(Debug, Error, Clone, PartialEq, Eq)]
#[error("unknown algorithm {0:?}; expected one of pso, apso, spso, dls-smpso, qpso, gwo, abc")]
pub struct UnknownAlgorithm(pub String);

impl FromStr for Algorithm {
    type Err = UnknownAlgorithm;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|a| a.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| UnknownAlgorithm(s.to_owned()))
    }
}

/// Parameters of every algorithm; the default is the paper's setting for each.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct AlgorithmParams {
    /// PSO on the cartesian encoding.
    pub pso: PsoParams,
    /// APSO (theta-PSO): PSO on the angle encoding.
    pub apso: PsoParams,
    /// SPSO: PSO on the spherical motion encoding.
    pub spso: PsoParams,
    pub dls_smpso: DlsParams,
    pub qpso: QpsoParams,
    pub gwo: GwoParams,
    pub abc: AbcParams,
}

impl AlgorithmParams {
    pub const DEFAULT: Self = Self {
        pso: PsoParams::DEFAULT,
        apso: PsoParams::DEFAULT,
        spso: PsoParams::DEFAULT,
        dls_smpso: DlsParams::DEFAULT,
        qpso: QpsoParams::DEFAULT,
        gwo: GwoParams::DEFAULT,
        abc: AbcParams::DEFAULT,
    };

    /// Checks every section; the error names the first bad field with its section.
    pub fn validate(&self) -> Result<(), ParamsError> {
        self.pso.validate().map_err(|e| e.within("pso"))?;
        self.apso.validate().map_err(|e| e.within("apso"))?;
        self.spso.validate().map_err(|e| e.within("spso"))?;
        self.dls_smpso
            .validate()
            .map_err(|e| e.within("dls_smpso"))?;
        self.qpso.validate().map_err(|e| e.within("qpso"))?;
        self.gwo.validate().map_err(|e| e.within("gwo"))?;
        self.abc.validate().map_err(|e| e.within("abc"))
    }

    /// The population size `alg` will use (for ABC: bees, twice the food sources).
    #[must_use]
    pub fn population(&self, alg: Algorithm) -> usize {
        match alg {
            Algorithm::Pso => self.pso.population,
            Algorithm::Apso => self.apso.population,
            Algorithm::Spso => self.spso.population,
            Algorithm::DlsSmpso => self.dls_smpso.pso.population,
            Algorithm::Qpso => self.qpso.population,
            Algorithm::Gwo => self.gwo.population,
            Algorithm::Abc => self.abc.population,
        }
    }

    /// Sets the population size of every algorithm (e.g. the population-500 runs).
    pub fn set_population(&mut self, n: usize) {
        self.pso.population = n;
        self.apso.population = n;
        self.spso.population = n;
        self.dls_smpso.pso.population = n;
        self.qpso.population = n;
        self.gwo.population = n;
        self.abc.population = n;
    }
}

impl Default for AlgorithmParams {
    fn default() -> Self {
        Self::DEFAULT
    }
}

/// Makes the optimizer for `alg`. `params` should have passed
/// [`AlgorithmParams::validate`] (see [`try_build`]); out-of-range sizes are raised to the
/// smallest workable value rather than panicking.
#[must_use]
pub fn build(alg: Algorithm, params: &AlgorithmParams) -> Box<dyn Optimizer> {
    match alg {
        Algorithm::Pso => Box::new(Pso::new(params.pso)),
        Algorithm::Apso => Box::new(Pso::new(params.apso)),
        Algorithm::Spso => Box::new(Pso::new(params.spso)),
        Algorithm::DlsSmpso => Box::new(DlsSmpso::new(params.dls_smpso)),
        Algorithm::Qpso => Box::new(Qpso::new(params.qpso)),
        Algorithm::Gwo => Box::new(Gwo::new(params.gwo)),
        Algorithm::Abc => Box::new(Abc::new(params.abc)),
    }
}

/// Validates `params`, then [`build`]s.
pub fn try_build(
    alg: Algorithm,
    params: &AlgorithmParams,
) -> Result<Box<dyn Optimizer>, ParamsError> {
    params.validate()?;
    Ok(build(alg, params))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::optim::DlsMode;

    #[test]
    fn algorithm_names_round_trip() {
        for a in Algorithm::ALL {
            assert_eq!(a.to_string().parse::<Algorithm>(), Ok(a));
            let json = serde_json::to_string(&a).expect("serialises");
            assert_eq!(json, format!("\"{a}\""));
        }
        assert_eq!("DLS-SMPSO".parse::<Algorithm>(), Ok(Algorithm::DlsSmpso));
        assert!("dls".parse::<Algorithm>().is_err());
    }

    #[test]
    fn defaults_are_the_paper_settings_and_valid() {
        let p = AlgorithmParams::default();
        p.validate().expect("defaults are valid");
        for a in Algorithm::ALL {
            assert_eq!(p.population(a), 50);
        }
        assert_eq!(p.spso.inertia, 1.0);
        assert_eq!(p.spso.cognitive, 1.5);
        assert_eq!(p.spso.social, 1.5);
        assert_eq!(p.dls_smpso.mode, DlsMode::Paper);
    }

    #[test]
    fn serde_fills_defaults_and_rejects_unknown_fields() {
        let p: AlgorithmParams = serde_json::from_str(
            r#"{"dls_smpso": {"mode": "exemplar", "pso": {"population": 20}}}"#,
        )
        .expect("parses");
        assert_eq!(p.dls_smpso.mode, DlsMode::Exemplar);
        assert_eq!(p.dls_smpso.pso.population, 20);
        assert_eq!(p.dls_smpso.lambda, 0.5);
        assert_eq!(p.gwo, GwoParams::DEFAULT);
        assert!(serde_json::from_str::<AlgorithmParams>(r#"{"spso": {"inertai": 1}}"#).is_err());
        assert!(serde_json::from_str::<AlgorithmParams>(r#"{"sps": {}}"#).is_err());
    }

    #[test]
    fn validation_names_the_field() {
        let mut p = AlgorithmParams::default();
        p.dls_smpso.pso.velocity_clamp = -1.0;
        let e = p.validate().expect_err("negative clamp");
        assert_eq!(e.field, "dls_smpso.pso.velocity_clamp");
        assert!(e
            .to_string()
            .starts_with("dls_smpso.pso.velocity_clamp: expected"));
        let mut p = AlgorithmParams::default();
        p.abc.population = 3;
        assert_eq!(
            p.validate().expect_err("too few bees").field,
            "abc.population"
        );
        assert!(try_build(Algorithm::Abc, &p).is_err());
    }
}
