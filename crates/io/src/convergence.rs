//! `convergence.csv` of a plan folder: one typed row per kept iteration of the run, written
//! by `plan`, read back by `plot` and `report`, and handed to Python as the same rows.
//!
//! Columns: `iteration,evaluations,best_cost,best_cost_per_uav,best_violation`, then one
//! `uavI_cost` per UAV (that UAV's weighted terms in the best plan after the iteration).
//! Non-finite numbers are written as Rust prints them (`inf`, `NaN`) and read back.
//! A long run keeps every s-th iteration past `TRACE_CAP` rows
//! (`swarmplan_core::optim::thinned`), so the iteration column is read, not assumed.

use std::path::{Path, PathBuf};

use serde::Serialize;
use swarmplan_core::cost::cost_per_uav;
use swarmplan_core::optim::IterationRecord;
use thiserror::Error;

use crate::atomic::write_atomic_with;

/// The columns every row has, before the per-UAV costs.
pub const HEADER: &str = "iteration,evaluations,best_cost,best_cost_per_uav,best_violation";

/// One row of `convergence.csv` without its per-UAV costs (which follow it in the file).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ConvergenceRow {
    /// 0 after initialisation, then the number of steps taken.
    pub iteration: usize,
    /// Evaluations spent so far, initialisation included.
    pub evaluations: u64,
    /// Total cost of the best plan so far (penalty included).
    pub best_cost: f64,
    /// `best_cost` over the number of UAVs, as the paper's tables report it.
    pub best_cost_per_uav: f64,
    /// Violation measure of the best plan so far (0 when feasible).
    pub best_violation: f64,
}

impl ConvergenceRow {
    /// The row of `record` in a plan of `uavs` UAVs.
    #[must_use]
    pub fn of(record: &IterationRecord, uavs: usize) -> Self {
        Self {
            iteration: record.iteration,
            evaluations: record.evaluations,
            best_cost: record.best_cost,
            best_cost_per_uav: cost_per_uav(record.best_cost, uavs),
            best_violation: record.best_violation,
        }
    }
}

/// What `plot` draws from a `convergence.csv`: its columns as series.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ConvergenceColumns {
    /// The iteration column, when the file has one (files of early builds had none).
    pub iterations: Option<Vec<usize>>,
    /// The best_cost column.
    pub total: Vec<f64>,
    /// One series per `uavI_cost` column, in file order (empty when there are none).
    pub per_uav: Vec<Vec<f64>>,
}

/// A `convergence.csv` that cannot be written or read.
#[derive(Debug, Error)]
pub enum ConvergenceError {
    /// The file could not be read or written.
    #[error("{}: cannot {action}: {source}", .path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// `read` or `write`.
        action: &'static str,
        /// What the system said.
        source: std::io::Error,
    },
    /// The header has no `best_cost` column.
    #[error("{}: no best_cost column in the header", .path.display())]
    NoBestCost {
        /// The file.
        path: PathBuf,
    },
    /// A cell is not a number of its column's kind, or iterations do not increase.
    #[error("{}: line {line}: {message}", .path.display())]
    Row {
        /// The file.
        path: PathBuf,
        /// Line number, 1 for the header.
        line: usize,
        /// What is wrong there.
        message: String,
    },
}

/// Writes `trace` (the run's kept iterations) with `uav_costs[k]` (each UAV's cost after
/// `trace[k]`; missing rows leave the columns empty) into `path`, atomically and streamed:
/// a long run's trace can hold many thousand rows.
pub fn write_convergence(
    path: &Path,
    uavs: usize,
    trace: &[IterationRecord],
    uav_costs: &[impl AsRef<[f64]>],
) -> Result<(), ConvergenceError> {
    write_atomic_with(path, |csv| {
        write!(csv, "{HEADER}")?;
        for i in 0..uavs {
            write!(csv, ",uav{i}_cost")?;
        }
        writeln!(csv)?;
        for (k, record) in trace.iter().enumerate() {
            let r = ConvergenceRow::of(record, uavs);
            write!(
                csv,
                "{},{},{},{},{}",
                r.iteration, r.evaluations, r.best_cost, r.best_cost_per_uav, r.best_violation
            )?;
            for c in uav_costs.get(k).map_or(&[][..], AsRef::as_ref) {
                write!(csv, ",{c}")?;
            }
            writeln!(csv)?;
        }
        Ok(())
    })
    .map_err(|source| ConvergenceError::Io {
        path: path.to_path_buf(),
        action: "write",
        source,
    })
}

/// Reads the iteration and best_cost columns of `path` and, when present, one `uavI_cost`
/// column per UAV.
pub fn read_convergence(path: &Path) -> Result<ConvergenceColumns, ConvergenceError> {
    let text = std::fs::read_to_string(path).map_err(|source| ConvergenceError::Io {
        path: path.to_path_buf(),
        action: "read",
        source,
    })?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or_default().split(',').collect();
    let col = header
        .iter()
        .position(|h| *h == "best_cost")
        .ok_or_else(|| ConvergenceError::NoBestCost {
            path: path.to_path_buf(),
        })?;
    let iteration_col = header.iter().position(|h| *h == "iteration");
    let uav_cols: Vec<usize> = (0..header.len())
        .filter(|c| header[*c].starts_with("uav") && header[*c].ends_with("_cost"))
        .collect();
    let mut out = ConvergenceColumns {
        iterations: iteration_col.map(|_| Vec::new()),
        total: Vec::new(),
        per_uav: vec![Vec::new(); uav_cols.len()],
    };
    for (i, l) in lines.enumerate() {
        let fields: Vec<&str> = l.split(',').collect();
        let line = i + 2;
        let bad = |message: String| ConvergenceError::Row {
            path: path.to_path_buf(),
            line,
            message,
        };
        let num = |c: usize| {
            fields
                .get(c)
                .and_then(|v| v.parse::<f64>().ok())
                .ok_or_else(|| bad(format!("expected a number in column {}", header[c])))
        };
        if let (Some(c), Some(its)) = (iteration_col, out.iterations.as_mut()) {
            let k = fields
                .get(c)
                .and_then(|v| v.parse::<usize>().ok())
                .ok_or_else(|| bad("expected a whole number in column iteration".into()))?;
            if let Some(&before) = its.last() {
                if k <= before {
                    return Err(bad(format!(
                        "iteration {k} does not follow iteration {before}"
                    )));
                }
            }
            its.push(k);
        }
        out.total.push(num(col)?);
        for (series, c) in out.per_uav.iter_mut().zip(&uav_cols) {
            series.push(num(*c)?);
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_rows_read_back_as_columns() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("convergence.csv");
        let trace = [
            IterationRecord {
                iteration: 0,
                evaluations: 50,
                best_cost: f64::INFINITY,
                best_violation: 3.0,
            },
            IterationRecord {
                iteration: 4,
                evaluations: 250,
                best_cost: 1200.5,
                best_violation: 0.0,
            },
        ];
        let uav_costs = vec![vec![600.0, f64::INFINITY], vec![600.25, 600.25]];
        write_convergence(&path, 2, &trace, &uav_costs).expect("written");
        let text = std::fs::read_to_string(&path).expect("read");
        assert_eq!(
            text,
            "iteration,evaluations,best_cost,best_cost_per_uav,best_violation,uav0_cost,uav1_cost\n\
             0,50,inf,inf,3,600,inf\n4,250,1200.5,600.25,0,600.25,600.25\n"
        );
        let cols = read_convergence(&path).expect("parsed");
        assert_eq!(cols.iterations, Some(vec![0, 4]));
        assert_eq!(cols.total, vec![f64::INFINITY, 1200.5]);
        assert_eq!(cols.per_uav[1], vec![f64::INFINITY, 600.25]);
    }

    #[test]
    fn a_bad_row_is_named_by_line_and_column() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("convergence.csv");
        std::fs::write(&path, "iteration,best_cost\n0,5\n0,4\n").expect("written");
        let e = read_convergence(&path).expect_err("repeated iteration");
        assert!(
            e.to_string()
                .ends_with("line 3: iteration 0 does not follow iteration 0"),
            "{e}"
        );
        std::fs::write(&path, "iteration,best_cost\n0,x\n").expect("written");
        let e = read_convergence(&path).expect_err("not a number");
        assert!(
            e.to_string()
                .ends_with("line 2: expected a number in column best_cost"),
            "{e}"
        );
    }
}
