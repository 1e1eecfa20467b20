//! A bench on one scenario at a glance, in two panels: box plots of the cost per UAV of
//! every run per algorithm (the paper's Tables 4-5 as distributions), and the feasible rate
//! (FR, share of runs whose best plan violates nothing) per algorithm as bars.
//!
//! Boxes are Tukey's: quartiles, median, whiskers to the most extreme run within 1.5 IQR of
//! the box, the rest as outlier dots. Runs with an infinite cost cannot be placed on the
//! axis; their number is written above the algorithm's box.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use swarmplan_experiment::record::RunRecord;

use crate::axis::{format_value, Axis};
use crate::convergence_run::cost_desc;
use crate::records::{cost, groups};
use crate::render::{no_data, render, DrawResult, Figure, PlotError, Target, Written};
use crate::stats::BoxStats;
use crate::style::{self, Scale, GRID};

/// Writes the box plots and feasible-rate bars of `scenario` from `records` (other
/// scenarios' records are ignored) to `out`.
pub fn bench_boxplots(
    records: &[RunRecord],
    scenario: &str,
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    let target = out.into();
    let columns: Vec<Column> = groups(records, scenario)
        .into_iter()
        .map(|g| {
            let costs: Vec<f64> = g.runs.iter().map(|r| cost(r.cost_per_uav)).collect();
            Column {
                infinite: costs.iter().filter(|c| !c.is_finite()).count(),
                boxes: BoxStats::of(&costs),
                feasible: g.runs.iter().filter(|r| r.feasible).count(),
                runs: g.runs.len(),
                label: g.label,
            }
        })
        .collect();
    if columns.is_empty() {
        return Err(no_data(
            &target,
            format!("no run of scenario `{scenario}` in the records"),
        ));
    }
    let values = columns
        .iter()
        .filter_map(|c| c.boxes.as_ref())
        .flat_map(|b| {
            [b.whisker_lo, b.whisker_hi]
                .into_iter()
                .chain(b.outliers.iter().copied())
        });
    let y = Axis::auto(values, 0.08, false);
    render(
        &BenchBoxplots {
            scenario,
            columns,
            y,
        },
        &target,
    )
}

struct Column {
    label: String,
    runs: usize,
    feasible: usize,
    infinite: usize,
    boxes: Option<BoxStats>,
}

struct BenchBoxplots<'a> {
    scenario: &'a str,
    columns: Vec<Column>,
    y: Axis,
}

impl BenchBoxplots<'_> {
    fn categories(&self) -> Axis {
        let n = self.columns.len();
        Axis::fixed(-0.5, n as f64 - 0.5, (0..n).map(|k| k as f64).collect())
    }

    fn label_of(&self, v: f64) -> String {
        let k = v.round();
        if (v - k).abs() < 1e-6 && k >= 0.0 {
            self.columns
                .get(k as usize)
                .map(|c| c.label.clone())
                .unwrap_or_default()
        } else {
            String::new()
        }
    }

    fn draw_boxes<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let mut chart = ChartBuilder::on(area)
            .caption("cost per UAV of each run", s.subtitle())
            .margin(s.px(15.0))
            .x_label_area_size(s.px(55.0))
            .y_label_area_size(s.px(100.0))
            .build_cartesian_2d(self.categories(), self.y.clone())?;
        let fmt = |v: &f64| self.label_of(*v);
        let fy = |v: &f64| self.y.label(*v);
        chart
            .configure_mesh()
            .disable_x_mesh()
            .light_line_style(GRID.mix(0.3))
            .bold_line_style(GRID.mix(0.9))
            .label_style(s.tick())
            .axis_desc_style(s.axis_desc())
            .x_label_formatter(&fmt)
            .y_label_formatter(&fy)
            .y_labels(10)
            .x_desc("algorithm")
            .y_desc(cost_desc("cost per UAV", &self.y))
            .draw()?;
        let half = 0.3;
        for (i, col) in self.columns.iter().enumerate() {
            let c = style::series_colour(i);
            let x = i as f64;
            let line = c.stroke_width(s.px(2.0));
            if let Some(b) = &col.boxes {
                chart.draw_series([
                    Rectangle::new([(x - half, b.q1), (x + half, b.q3)], c.mix(0.3).filled()),
                    Rectangle::new([(x - half, b.q1), (x + half, b.q3)], line),
                ])?;
                chart.draw_series([
                    PathElement::new(vec![(x, b.q3), (x, b.whisker_hi)], line),
                    PathElement::new(vec![(x, b.q1), (x, b.whisker_lo)], line),
                    PathElement::new(
                        vec![
                            (x - half / 2.0, b.whisker_hi),
                            (x + half / 2.0, b.whisker_hi),
                        ],
                        line,
                    ),
                    PathElement::new(
                        vec![
                            (x - half / 2.0, b.whisker_lo),
                            (x + half / 2.0, b.whisker_lo),
                        ],
                        line,
                    ),
                    PathElement::new(
                        vec![(x - half, b.median), (x + half, b.median)],
                        BLACK.stroke_width(s.px(3.0)),
                    ),
                ])?;
                chart.draw_series(
                    b.outliers
                        .iter()
                        .map(|v| Circle::new((x, *v), s.px(3.5), c.stroke_width(s.px(1.5)))),
                )?;
            }
            if col.infinite > 0 {
                let text = s
                    .note()
                    .color(&style::OUT)
                    .pos(Pos::new(HPos::Center, VPos::Top));
                chart.draw_series(std::iter::once(Text::new(
                    format!("{} inf", col.infinite),
                    (x, self.y.hi()),
                    text,
                )))?;
            }
        }
        Ok(())
    }

    /// Feasible rate as horizontal bars, so that algorithm names have room.
    fn draw_rates<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let mut chart = ChartBuilder::on(area)
            .caption("feasible rate (FR)", s.subtitle())
            .margin(s.px(15.0))
            .margin_right(s.px(25.0))
            .x_label_area_size(s.px(65.0))
            .y_label_area_size(s.px(105.0))
            .build_cartesian_2d(
                // Room right of a full bar for its label; grid and ticks stop at 100 %.
                Axis::fixed(0.0, 125.0, (0..=5).map(|k| 20.0 * f64::from(k)).collect()),
                self.categories().reversed(),
            )?;
        let fmt = |v: &f64| self.label_of(*v);
        let pct = |v: &f64| format_value(*v);
        chart
            .configure_mesh()
            .disable_y_mesh()
            .light_line_style(GRID.mix(0.3))
            .bold_line_style(GRID.mix(0.9))
            .label_style(s.tick())
            .axis_desc_style(s.axis_desc())
            .y_label_formatter(&fmt)
            .x_label_formatter(&pct)
            .x_desc("feasible runs, %")
            .draw()?;
        let text = s.note().pos(Pos::new(HPos::Left, VPos::Center));
        for (i, col) in self.columns.iter().enumerate() {
            let c = style::series_colour(i);
            let y = i as f64;
            let fr = 100.0 * col.feasible as f64 / col.runs.max(1) as f64;
            chart.draw_series([
                Rectangle::new([(0.0, y - 0.32), (fr, y + 0.32)], c.mix(0.75).filled()),
                Rectangle::new([(0.0, y - 0.32), (fr, y + 0.32)], c.stroke_width(s.px(1.5))),
            ])?;
            chart.draw_series(std::iter::once(
                EmptyElement::at((fr, y))
                    + Text::new(
                        format!(
                            "{} % ({}/{})",
                            format_value((fr * 10.0).round() / 10.0),
                            col.feasible,
                            col.runs
                        ),
                        (s.off(6.0), 0),
                        text.clone(),
                    ),
            ))?;
        }
        Ok(())
    }
}

impl Figure for BenchBoxplots<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let runs: usize = self.columns.iter().map(|c| c.runs).sum();
        let title = format!(
            "Bench on {}: {} runs of {} algorithms",
            self.scenario,
            runs,
            self.columns.len()
        );
        let body = root.titled(&title, s.title())?;
        let (w, _) = body.dim_in_pixel();
        let (left, right) = body.split_horizontally(w * 3 / 5);
        self.draw_boxes(&left, s)?;
        self.draw_rates(&right, s)
    }
}
