//! Convergence across the runs of a bench: for each algorithm on one scenario, the median
//! best cost per UAV over the evaluations spent, with the inter-quartile band (25th to 75th
//! percentile) shaded, all algorithms on one chart.
//!
//! Over evaluations, not iterations: methods spend different evaluations per iteration
//! (ABC two per bee, DLS-SMPSO its probes, swarmplan 10 per sub-swarm step), so only the
//! evaluation axis compares them at equal effort. Each run's best cost is read as a step
//! function of its evaluations on a grid of [`GRID`] points up to the largest count; a run
//! keeps its last best cost after it ends. Records without evaluation counts (written
//! before they were stored) fall back to an iteration axis. Infinite costs rank above every finite
//! one; a median that is still infinite is not drawn, an infinite upper quartile is clipped
//! to the top of the chart.

use plotters::coord::Shift;
use plotters::prelude::*;
use swarmplan_experiment::record::RunRecord;

use crate::axis::{draw_mesh, Axis};
use crate::convergence_run::{cost_desc, finite_runs};
use crate::records::{cost, groups};
use crate::render::{no_data, render, DrawResult, Figure, PlotError, Target, Written};
use crate::stats::{quantile_sorted, sorted};
use crate::style::{self, Scale};

/// Writes the bench convergence figure of `scenario` from `records` (other scenarios'
/// records are ignored) to `out`.
pub fn convergence_bench(
    records: &[RunRecord],
    scenario: &str,
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    let target = out.into();
    let groups = groups(records, scenario);
    let runs = || groups.iter().flat_map(|g| g.runs.iter());
    let by_evaluations = runs().all(|r| {
        !r.convergence.is_empty() && r.convergence_evaluations.len() == r.convergence.len()
    });
    let max_evaluations = runs()
        .filter_map(|r| r.convergence_evaluations.last().copied())
        .max()
        .unwrap_or(0);
    let grid: Vec<f64> = (0..GRID)
        .map(|k| max_evaluations as f64 * k as f64 / (GRID - 1) as f64)
        .collect();
    let bands: Vec<Band> = groups
        .iter()
        .filter_map(|g| {
            let series: Vec<Vec<f64>> = g
                .runs
                .iter()
                .filter(|r| !r.convergence.is_empty())
                .map(|r| {
                    if by_evaluations {
                        on_grid(&r.convergence_evaluations, &r.convergence, &grid)
                    } else {
                        r.convergence.clone()
                    }
                })
                .collect();
            let refs: Vec<&[f64]> = series.iter().map(Vec::as_slice).collect();
            (!refs.is_empty()).then(|| Band::of(g.label.clone(), &refs))
        })
        .collect();
    if bands.is_empty() {
        return Err(no_data(
            &target,
            format!("no run of scenario `{scenario}` has a convergence trace"),
        ));
    }
    let values = bands
        .iter()
        .flat_map(|b| b.q25.iter().chain(&b.median).chain(&b.q75).copied());
    let y = Axis::auto(values, 0.05, false);
    let x = if by_evaluations {
        XAxis::Evaluations(grid)
    } else {
        XAxis::Iterations
    };
    render(
        &ConvergenceBench {
            scenario,
            bands,
            y,
            x,
        },
        &target,
    )
}

/// Points of the evaluation grid.
const GRID: usize = 200;

/// The best cost of a run (`costs[k]` after `evaluations[k]`) at each grid point: the last
/// record at or before it (the first record before the first).
fn on_grid(evaluations: &[u64], costs: &[f64], grid: &[f64]) -> Vec<f64> {
    let mut k = 0;
    grid.iter()
        .map(|&e| {
            while k + 1 < evaluations.len() && evaluations[k + 1] as f64 <= e {
                k += 1;
            }
            costs[k]
        })
        .collect()
}

/// What the horizontal axis counts.
enum XAxis {
    /// Evaluations at each grid point.
    Evaluations(Vec<f64>),
    Iterations,
}

/// Quartiles per iteration of one algorithm's runs.
struct Band {
    label: String,
    runs: usize,
    q25: Vec<f64>,
    median: Vec<f64>,
    q75: Vec<f64>,
}

impl Band {
    fn of(label: String, series: &[&[f64]]) -> Self {
        let len = series.iter().map(|s| s.len()).max().unwrap_or(0);
        let (mut q25, mut median, mut q75) = (vec![], vec![], vec![]);
        for k in 0..len {
            let v = sorted(series.iter().map(|s| cost(s[k.min(s.len() - 1)])));
            q25.push(quantile_sorted(&v, 0.25));
            median.push(quantile_sorted(&v, 0.5));
            q75.push(quantile_sorted(&v, 0.75));
        }
        Self {
            label,
            runs: series.len(),
            q25,
            median,
            q75,
        }
    }
}

struct ConvergenceBench<'a> {
    scenario: &'a str,
    bands: Vec<Band>,
    y: Axis,
    x: XAxis,
}

impl ConvergenceBench<'_> {
    /// The x value of point `k`.
    fn x_at(&self, k: usize) -> f64 {
        match &self.x {
            XAxis::Evaluations(grid) => grid[k.min(grid.len() - 1)],
            XAxis::Iterations => k as f64,
        }
    }
}

impl Figure for ConvergenceBench<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let title = format!(
            "Convergence on {}: median and inter-quartile band per method",
            self.scenario
        );
        let body = root.titled(&title, s.title())?;
        let len = self.bands.iter().map(|b| b.median.len()).max().unwrap_or(0);
        let (x_max, x_desc) = match &self.x {
            XAxis::Evaluations(grid) => {
                (grid.last().copied().unwrap_or(1.0).max(1.0), "evaluations")
            }
            XAxis::Iterations => (
                (len.max(2) - 1) as f64,
                "iteration (0 = after initialisation)",
            ),
        };
        let mut chart =
            crate::axis::line_chart(&body, s, Axis::linear(0.0, x_max), self.y.clone())?;
        draw_mesh(
            &mut chart,
            s,
            x_desc,
            &cost_desc("best cost per UAV", &self.y),
        )?;
        // Bands first, so every median line stays visible above all of them.
        for (i, b) in self.bands.iter().enumerate() {
            let c = style::series_colour(i);
            let ks: Vec<usize> = (0..b.q25.len()).filter(|k| b.q25[*k].is_finite()).collect();
            if ks.len() < 2 {
                continue;
            }
            let mut poly: Vec<(f64, f64)> = ks
                .iter()
                .map(|k| (self.x_at(*k), self.y.clamp(b.q75[*k])))
                .collect();
            poly.extend(
                ks.iter()
                    .rev()
                    .map(|k| (self.x_at(*k), self.y.clamp(b.q25[*k]))),
            );
            chart.draw_series(std::iter::once(Polygon::new(poly, c.mix(0.18).filled())))?;
        }
        let w = s.px(3.0);
        let key_len = s.off(24.0);
        for (i, b) in self.bands.iter().enumerate() {
            let c = style::series_colour(i);
            // finite_runs numbers the points; put them at their x.
            let mut runs: Vec<Vec<(f64, f64)>> = finite_runs(b.median.iter().copied())
                .into_iter()
                .map(|r| {
                    r.into_iter()
                        .map(|(k, v)| (self.x_at(k as usize), v))
                        .collect()
                })
                .collect();
            if runs.is_empty() {
                runs.push(Vec::new());
            }
            let label = format!("{} (n = {})", b.label, b.runs);
            for (k, r) in runs.into_iter().enumerate() {
                let anno = chart.draw_series(LineSeries::new(r, c.stroke_width(w)))?;
                if k == 0 {
                    anno.label(label.clone()).legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + Rectangle::new(
                                [(0, -key_len / 4), (key_len, key_len / 4)],
                                c.mix(0.25).filled(),
                            )
                            + PathElement::new(vec![(0, 0), (key_len, 0)], c.stroke_width(w))
                    });
                }
            }
        }
        crate::axis::draw_series_key(&mut chart, s, SeriesLabelPosition::UpperRight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_is_read_as_a_step_function_of_its_evaluations() {
        let grid = [0.0, 50.0, 100.0, 150.0, 250.0];
        let v = on_grid(&[10, 100, 200], &[9.0, 5.0, 2.0], &grid);
        // Before the first record: its value; a record counts from its evaluation on; after
        // the run's end: its last value.
        assert_eq!(v, [9.0, 9.0, 5.0, 5.0, 2.0]);
    }
}
