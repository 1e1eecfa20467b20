//! Convergence across the runs of a bench: for each algorithm on one scenario, the median
//! best cost per UAV at every iteration with the inter-quartile band (25th to 75th
//! percentile) shaded, all algorithms on one chart.
//!
//! A run that stopped earlier (equal-evaluation budgets give algorithms different iteration
//! counts) keeps its last best cost for the later iterations of its algorithm: the best cost
//! found so far does not change after a run ends. Infinite costs rank above every finite
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
    let bands: Vec<Band> = groups(records, scenario)
        .into_iter()
        .filter_map(|g| {
            let series: Vec<&[f64]> = g
                .runs
                .iter()
                .map(|r| &r.convergence[..])
                .filter(|c| !c.is_empty())
                .collect();
            (!series.is_empty()).then(|| Band::of(g.label, &series))
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
    render(&ConvergenceBench { scenario, bands, y }, &target)
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
}

impl Figure for ConvergenceBench<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let title = format!(
            "Convergence on {}: median and inter-quartile band per algorithm",
            self.scenario
        );
        let body = root.titled(&title, s.title())?;
        let len = self.bands.iter().map(|b| b.median.len()).max().unwrap_or(0);
        let mut chart = ChartBuilder::on(&body)
            .margin(s.px(20.0))
            .margin_right(s.px(40.0))
            .x_label_area_size(s.px(65.0))
            .y_label_area_size(s.px(100.0))
            .build_cartesian_2d(Axis::linear(0.0, (len.max(2) - 1) as f64), self.y.clone())?;
        draw_mesh(
            &mut chart,
            s,
            "iteration (0 = after initialisation)",
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
                .map(|k| (*k as f64, self.y.clamp(b.q75[*k])))
                .collect();
            poly.extend(
                ks.iter()
                    .rev()
                    .map(|k| (*k as f64, self.y.clamp(b.q25[*k]))),
            );
            chart.draw_series(std::iter::once(Polygon::new(poly, c.mix(0.18).filled())))?;
        }
        let w = s.px(3.0);
        let key_len = s.off(24.0);
        for (i, b) in self.bands.iter().enumerate() {
            let c = style::series_colour(i);
            let mut runs = finite_runs(b.median.iter().copied());
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
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .margin(s.px(15.0))
            .label_font(s.legend())
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK.mix(0.5))
            .draw()
    }
}
