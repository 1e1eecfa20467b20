//! `Problem`: one scenario under one encoding, as a box-bounded minimisation problem that a
//! numpy optimiser can drive: bounds, a batch evaluation (parallel, in Rust), decoding and
//! the full assessment.

use std::path::PathBuf;

use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use rayon::prelude::*;
use swarmplan_core::cost::assess;
use swarmplan_core::cost::coverage::GroundCoverage;
use swarmplan_core::encoding::{EncodingKind, InitKind};
use swarmplan_core::method::Method;
use swarmplan_core::plan::Plan;
use swarmplan_core::planning::PlanningProblem;
use swarmplan_core::problem::{BlockProblem, Bound as VarBound, Problem as _};
use swarmplan_core::rng::rng_from_seed;
use swarmplan_core::world::World;
use swarmplan_io::artifact::AssessmentRecord;
use swarmplan_io::plan_file::{plan_file, read_plan, PlanFileError, Provenance};

use crate::errors::{bad, message, to_py, with_advice};
use crate::{args, scenario};

/// Most values `sample_initial` returns (1 GiB of f64): a larger request is refused, not
/// allocated.
const MAX_SAMPLE_VALUES: usize = 1 << 27;

/// Two arrays of the same length (costs and violations).
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// A scenario's planning problem in one encoding (see the Python class `swarmplan.Problem`).
#[pyclass(module = "swarmplan._native", frozen)]
pub struct Problem {
    world: World,
    method: Method,
    bounds: Vec<VarBound>,
    block_size: usize,
    notes: Vec<String>,
    /// The corridors of the `corridor` initialisation, searched once in `new`.
    corridors: swarmplan_core::encoding::corridor::Corridors,
}

impl Problem {
    fn planning(&self) -> PlanningProblem<'_> {
        PlanningProblem::with_corridors(
            &self.world,
            self.method.encoding,
            self.method.init,
            self.corridors.clone(),
        )
    }

    /// `x` checked (length, finite) and brought into the box as the Rust optimizers bring
    /// their candidates: periodic values wrap, others are clamped.
    fn projected(&self, x: &[f64], row: Option<usize>) -> PyResult<Vec<f64>> {
        if x.len() != self.bounds.len() {
            return Err(bad(format!(
                "x: expected {} values (the problem's dimension), got {}",
                self.bounds.len(),
                x.len()
            )));
        }
        x.iter()
            .zip(&self.bounds)
            .enumerate()
            .map(|(j, (&v, b))| {
                if v.is_finite() {
                    Ok(b.project(v))
                } else {
                    let at = row.map_or(format!("x[{j}]"), |i| format!("X[{i}, {j}]"));
                    // numpy reads None as NaN, so a NaN may have been a None.
                    let hint = if v.is_nan() {
                        " (None reads as NaN)"
                    } else {
                        ""
                    };
                    Err(bad(format!(
                        "{at}: expected a finite number, got {v}{hint}"
                    )))
                }
            })
            .collect()
    }

    /// A plan file read for this scenario (or, when allowed, recorded for another).
    fn read_plan(&self, path: &std::path::Path, allow_other_terrain: bool) -> PyResult<Plan> {
        let provenance = if allow_other_terrain {
            Provenance::AllowOther
        } else {
            Provenance::MustMatch
        };
        read_plan(path, &self.world, provenance).map_err(|e| match e {
            // The CLI's advice, in this method's terms.
            PlanFileError::Provenance { .. } => bad(with_advice(
                message(&e),
                "allow_other_terrain=True assesses it anyway",
            )),
            _ => to_py(e),
        })
    }

    fn json<T: serde::Serialize>(value: &T) -> PyResult<String> {
        serde_json::to_string(value).map_err(to_py)
    }
}

#[pymethods]
impl Problem {
    #[new]
    #[pyo3(signature = (scenario, terrain=None, method="swarmplan", encoding=None, init=None, profile=None))]
    fn new(
        scenario: &str,
        terrain: Option<PathBuf>,
        method: &str,
        encoding: Option<&str>,
        init: Option<&str>,
        profile: Option<&str>,
    ) -> PyResult<Self> {
        let encoding = encoding
            .map(|e| {
                e.parse::<EncodingKind>().map_err(|_| {
                    bad(format!(
                        "encoding: expected spherical, cartesian or angle, got `{e}`"
                    ))
                })
            })
            .transpose()?;
        let init = init
            .map(|i| {
                i.parse::<InitKind>().map_err(|_| {
                    bad(format!(
                        "init: expected uniform, line, corridor or fan, got `{i}`"
                    ))
                })
            })
            .transpose()?;
        let method = args::method(method)?.with(encoding, init);
        let loaded = scenario::load(scenario, terrain, profile)?;
        let planning = PlanningProblem::new(&loaded.world, method.encoding, method.init);
        let bounds = planning.bounds().to_vec();
        let block_size = planning.block_size();
        let corridors = planning.corridors().to_vec();
        Ok(Self {
            corridors,
            world: loaded.world,
            method,
            bounds,
            block_size,
            notes: loaded.notes,
        })
    }

    /// The scenario's name.
    #[getter]
    fn name(&self) -> String {
        self.world.spec().name.clone()
    }

    /// The method whose encoding and initialisation the problem uses.
    #[getter]
    fn method(&self) -> String {
        self.method.label()
    }

    #[getter]
    fn encoding(&self) -> String {
        self.method.encoding.to_string()
    }

    #[getter]
    fn profile(&self) -> &'static str {
        self.world.spec().planning.profile.name()
    }

    #[getter]
    fn dimension(&self) -> usize {
        self.bounds.len()
    }

    #[getter]
    fn uav_count(&self) -> usize {
        self.world.uav_count()
    }

    /// Values per UAV (one UAV's path is one block of the vector).
    #[getter]
    fn block_size(&self) -> usize {
        self.block_size
    }

    #[getter]
    fn notes(&self) -> Vec<String> {
        self.notes.clone()
    }

    /// Lower bounds, upper bounds and the periodic mask, as three arrays.
    #[allow(clippy::type_complexity)]
    fn bounds<'py>(
        &self,
        py: Python<'py>,
    ) -> (
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<f64>>,
        Bound<'py, PyArray1<bool>>,
    ) {
        let lo: Vec<f64> = self.bounds.iter().map(|b| b.lo).collect();
        let hi: Vec<f64> = self.bounds.iter().map(|b| b.hi).collect();
        let periodic: Vec<bool> = self.bounds.iter().map(|b| b.periodic).collect();
        (
            lo.into_pyarray(py),
            hi.into_pyarray(py),
            periodic.into_pyarray(py),
        )
    }

    /// Costs and violation measures of every row of `x` (shape (population, dimension)),
    /// evaluated in parallel with the interpreter released. Row results do not depend on
    /// the thread count: each evaluation is pure.
    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray2<'py, f64>,
    ) -> PyResult<ArrayPair<'py>> {
        let view = x.as_array();
        let dim = self.bounds.len();
        if view.ncols() != dim {
            return Err(bad(format!(
                "X: expected {dim} columns (the problem's dimension), got {}",
                view.ncols()
            )));
        }
        let mut flat = Vec::with_capacity(view.len());
        for (i, row) in view.rows().into_iter().enumerate() {
            let row: Vec<f64> = row.iter().copied().collect();
            flat.extend(self.projected(&row, Some(i))?);
        }
        let evals: Vec<(f64, f64)> = py.detach(|| {
            let planning = self.planning();
            flat.par_chunks(dim.max(1))
                .map(|r| {
                    let e = planning.evaluate(r);
                    (e.cost, e.violation)
                })
                .collect()
        });
        let (cost, violation): (Vec<f64>, Vec<f64>) = evals.into_iter().unzip();
        Ok((cost.into_pyarray(py), violation.into_pyarray(py)))
    }

    /// `count` starting points drawn as the method's initialisation draws them, from `seed`.
    fn sample_initial<'py>(
        &self,
        py: Python<'py>,
        count: i128,
        seed: i128,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let count: usize = args::positive("count", count)?;
        let seed = args::seed("seed", seed)?;
        let dim = self.bounds.len();
        if count.saturating_mul(dim.max(1)) > MAX_SAMPLE_VALUES {
            return Err(bad(format!(
                "count: expected at most {} rows of {dim} values, got {count}",
                MAX_SAMPLE_VALUES / dim.max(1)
            )));
        }
        let planning = self.planning();
        let mut rng = rng_from_seed(seed);
        let mut flat = vec![0.0; count * dim];
        for row in flat.chunks_mut(dim.max(1)) {
            planning.sample_initial(&mut rng, row);
        }
        let a = Array2::from_shape_vec((count, dim), flat).map_err(to_py)?;
        Ok(a.into_pyarray(py))
    }

    /// The plan file (JSON, as `plan.json`) of the plan that `x` decodes to.
    fn decode(&self, x: PyReadonlyArray1<'_, f64>) -> PyResult<String> {
        let x = self.projected(x.as_slice()?, None)?;
        Self::json(&plan_file(&self.world, &self.planning().decode(&x)))
    }

    /// The full assessment (JSON, as `evaluate --json` prints it) of the plan `x` decodes to.
    fn assess(&self, x: PyReadonlyArray1<'_, f64>) -> PyResult<String> {
        let x = self.projected(x.as_slice()?, None)?;
        let plan = self.planning().decode(&x);
        Self::json(&AssessmentRecord::of(&assess(&self.world, &plan)))
    }

    /// `evaluate --json` of a plan file.
    #[pyo3(signature = (path, allow_other_terrain=false))]
    fn evaluate_plan(&self, path: PathBuf, allow_other_terrain: bool) -> PyResult<String> {
        let plan = self.read_plan(&path, allow_other_terrain)?;
        Self::json(&AssessmentRecord::of(&assess(&self.world, &plan)))
    }

    /// What a flight replay needs of a plan file (JSON, `replay::FlightPlan`): each
    /// UAV's flown path, time-stamped, in the scenario's frame, and the limits it is judged by.
    #[pyo3(signature = (path, allow_other_terrain=false))]
    fn flight_plan(&self, path: PathBuf, allow_other_terrain: bool) -> PyResult<String> {
        let plan = self.read_plan(&path, allow_other_terrain)?;
        Self::json(&crate::replay::flight_plan(&self.world, &plan))
    }

    /// The terrain's height (m above the datum) at each (x, y), as the model interpolates it.
    fn terrain_heights<'py>(
        &self,
        py: Python<'py>,
        x: PyReadonlyArray1<'_, f64>,
        y: PyReadonlyArray1<'_, f64>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let (x, y) = (x.as_slice()?, y.as_slice()?);
        if x.len() != y.len() {
            return Err(bad(format!(
                "x and y: expected arrays of one length, got {} and {}",
                x.len(),
                y.len()
            )));
        }
        let terrain = self.world.terrain();
        let h: Vec<f64> = x
            .iter()
            .zip(y)
            .map(|(&x, &y)| terrain.height(x, y))
            .collect();
        Ok(h.into_pyarray(py))
    }

    /// Where a UAV `agl` metres above ground (default: the top of the altitude band) links
    /// directly to a ground node (nominal range, line of sight): the flags (rows along y),
    /// the first cell's corner (x, y), the cell size, the height used and the share of cells
    /// without a link.
    #[pyo3(signature = (agl=None))]
    #[allow(clippy::type_complexity)]
    fn ground_coverage<'py>(
        &self,
        py: Python<'py>,
        agl: Option<f64>,
    ) -> PyResult<(Bound<'py, PyArray2<bool>>, (f64, f64), f64, f64, f64)> {
        let map = match agl {
            None => GroundCoverage::at_band_top(&self.world),
            Some(h) if h.is_finite() && h >= 0.0 => {
                GroundCoverage::new(&self.world, h, GroundCoverage::default_cell(&self.world))
            }
            Some(h) => {
                return Err(bad(format!(
                    "agl: expected a finite height above ground >= 0 m, got {h}"
                )))
            }
        };
        let (nx, ny) = map.shape();
        let a = Array2::from_shape_vec((ny, nx), map.flags().to_vec()).map_err(to_py)?;
        Ok((
            a.into_pyarray(py),
            map.origin(),
            map.cell(),
            map.agl,
            map.dead_share(),
        ))
    }

    /// The decision vector nearest to a plan file's plan in this encoding.
    #[pyo3(signature = (path, allow_other_terrain=false))]
    fn encode_plan<'py>(
        &self,
        py: Python<'py>,
        path: PathBuf,
        allow_other_terrain: bool,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let plan = self.read_plan(&path, allow_other_terrain)?;
        let planning = self.planning();
        planning
            .check_shape(&plan)
            .map_err(|e| bad(format!("{}: {e}", path.display())))?;
        Ok(planning.encode(&plan).into_pyarray(py))
    }
}
