//! Convergence of one run: the best cost after initialisation (iteration 0) and after each
//! iteration, for the whole plan and, when given, per UAV. Costs of plans with violations
//! carry the penalty and can be orders of magnitude above feasible ones, so the cost axis
//! turns logarithmic when the trace spans more than a factor of 8 (the axis says so).

use std::sync::Arc;

use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;

use crate::axis::{draw_mesh, format_value, Axis};
use crate::decimate::{thins, M4};
use crate::records::cost;
use crate::render::{no_data, render, DrawResult, Figure, PlotError, Target, Written};
use crate::style::{self, Scale};

/// Each UAV's cost in the best plan along a run, as `plan` holds it or as
/// `convergence.csv` gives it back.
#[derive(Debug, Clone, Copy)]
pub enum PerUav<'a> {
    /// No per-UAV lines.
    None,
    /// One series per UAV: `[i][k]` is UAV i's cost at row k of the trace (after
    /// iteration k, or after the k-th of the iteration numbers given).
    Columns(&'a [Vec<f64>]),
    /// One row per row of the trace: `[k][i]`. `plan`'s trace ([`swarmplan_core::run::UavTrace`])
    /// shares a row while the best stands, so drawing from it copies nothing: a column per
    /// UAV would hold 8 bytes per UAV and row (52 MB at 100 UAVs and the 65,537 rows a
    /// thinned trace holds at most).
    Rows(&'a [Arc<[f64]>]),
}

impl<'a> PerUav<'a> {
    /// The longest series' length.
    fn len(self) -> usize {
        (0..self.uavs())
            .map(|i| self.column(i).len())
            .max()
            .unwrap_or(0)
    }

    fn uavs(self) -> usize {
        match self {
            Self::None => 0,
            Self::Columns(c) => c.len(),
            Self::Rows(r) => r
                .iter()
                .find(|row| !row.is_empty())
                .map_or(0, |row| row.len()),
        }
    }

    /// UAV i's series.
    fn column(self, i: usize) -> Column<'a> {
        match self {
            Self::None => Column::Slice(&[]),
            Self::Columns(c) => Column::Slice(&c[i]),
            Self::Rows(r) => Column::OfRows(r, i),
        }
    }
}

/// One line's values, borrowed.
#[derive(Clone, Copy)]
enum Column<'a> {
    Slice(&'a [f64]),
    /// Entry i of every row (NaN, not drawn, where a row is short).
    OfRows(&'a [Arc<[f64]>], usize),
}

impl<'a> Column<'a> {
    fn len(self) -> usize {
        match self {
            Self::Slice(v) => v.len(),
            Self::OfRows(r, _) => r.len(),
        }
    }

    fn values(self) -> Box<dyn Iterator<Item = f64> + 'a> {
        match self {
            Self::Slice(v) => Box::new(v.iter().copied()),
            Self::OfRows(r, i) => Box::new(
                r.iter()
                    .map(move |row| row.get(i).copied().unwrap_or(f64::NAN)),
            ),
        }
    }
}

/// Writes the convergence of one run to `out`: `trace[k]` is the best total cost after
/// iteration `iterations[k]` (0: after initialisation; `None`: after iteration k, every
/// iteration given); `per_uav` gives each UAV's cost in the best plan at the same
/// iterations. A long run's trace is thinned to every s-th iteration
/// (`swarmplan_core::optim::thinned`), hence the iteration numbers. Non-finite values (and
/// `f64::MAX`, which records use for them) are left out of the lines.
pub fn convergence_run(
    iterations: Option<&[usize]>,
    trace: &[f64],
    per_uav: PerUav<'_>,
    title: &str,
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    let target = out.into();
    let all = || {
        trace
            .iter()
            .copied()
            .chain((0..per_uav.uavs()).flat_map(|i| per_uav.column(i).values()))
            .map(cost)
    };
    if all().all(|v| !v.is_finite()) {
        return Err(no_data(&target, "the convergence trace has no finite cost"));
    }
    if let Some(it) = iterations {
        let rows = trace.len().max(per_uav.len());
        if it.len() < rows {
            return Err(no_data(
                &target,
                format!("{} iteration numbers for {rows} rows of costs", it.len()),
            ));
        }
    }
    let fig = ConvergenceRun {
        iterations,
        trace,
        per_uav,
        title,
        y: Axis::auto(all(), 0.05, false),
    };
    render(&fig, &target)
}

struct ConvergenceRun<'a> {
    iterations: Option<&'a [usize]>,
    trace: &'a [f64],
    per_uav: PerUav<'a>,
    title: &'a str,
    y: Axis,
}

/// One line of the figure and its legend row (`name`: none for a UAV of a large fleet
/// other than the first of its colour; `single`: the row names this line alone).
struct Series<'a> {
    name: Option<String>,
    single: bool,
    colour: RGBColor,
    width: u32,
    values: Column<'a>,
}

/// Maximal runs of finite values of `v` as (iteration, value) polylines.
pub(crate) fn finite_runs(v: impl IntoIterator<Item = f64>) -> Vec<Vec<(f64, f64)>> {
    thinned_finite_runs(None, v, None::<&fn(f64, f64) -> i32>)
}

/// [`finite_runs`] at `iterations` (value k at iteration k when `None`), each run thinned
/// by M4 ([`crate::decimate`]) on the pixel columns `column_of(x, y)` when given; the full
/// runs are never held.
fn thinned_finite_runs<F: Fn(f64, f64) -> i32>(
    iterations: Option<&[usize]>,
    v: impl IntoIterator<Item = f64>,
    column_of: Option<&F>,
) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut cur: Option<Open<'_, F>> = None;
    for (k, x) in v.into_iter().enumerate() {
        let x = cost(x);
        if x.is_finite() {
            let at = iterations.map_or(k, |it| it[k]);
            cur.get_or_insert_with(|| match column_of {
                Some(f) => Open::Thinned(M4::new(f)),
                None => Open::Every(Vec::new()),
            })
            .push(k, (at as f64, x));
        } else if let Some(run) = cur.take() {
            out.push(run.finish());
        }
    }
    if let Some(run) = cur {
        out.push(run.finish());
    }
    out
}

/// The run being collected: every vertex, or M4's.
enum Open<'f, F> {
    Every(Vec<(f64, f64)>),
    Thinned(M4<&'f F>),
}

impl<F: Fn(f64, f64) -> i32> Open<'_, F> {
    fn push(&mut self, k: usize, p: (f64, f64)) {
        match self {
            Self::Every(v) => v.push(p),
            Self::Thinned(m) => m.push(k, p),
        }
    }

    fn finish(self) -> Vec<(f64, f64)> {
        match self {
            Self::Every(v) => v,
            Self::Thinned(m) => m.finish(),
        }
    }
}

/// The y description of a cost axis.
pub(crate) fn cost_desc(what: &str, y: &Axis) -> String {
    if y.is_log() {
        format!("{what} (log scale)")
    } else {
        what.to_string()
    }
}

impl Figure for ConvergenceRun<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let body = root.titled(self.title, s.title())?;
        let n = self.per_uav.uavs();
        let len = self.per_uav.len().max(self.trace.len());
        let last = match (self.iterations, len) {
            (Some(it), 1..) => it[len - 1].max(1),
            _ => len.max(2) - 1,
        };
        let mut chart =
            crate::axis::line_chart(&body, s, Axis::linear(0.0, last as f64), self.y.clone())?;
        draw_mesh(
            &mut chart,
            s,
            "iteration (0 = after initialisation)",
            &cost_desc("best cost (lower is better)", &self.y),
        )?;

        // A large fleet's UAVs share one legend row per colour (`style::uav_label`),
        // without a final value.
        let mut series: Vec<Series> = (0..n)
            .map(|i| Series {
                name: style::uav_label(i, n),
                single: n <= style::UAV_LEGEND_ROWS,
                colour: style::uav_colour(i),
                width: s.px(2.0),
                values: self.per_uav.column(i),
            })
            .collect();
        if !self.trace.is_empty() {
            series.push(Series {
                name: Some("total".to_string()),
                single: true,
                colour: BLACK,
                width: s.px(3.0),
                values: Column::Slice(self.trace),
            });
        }
        let key_len = s.off(24.0);
        // The pixel column a vertex is drawn in, for thinning long series (a copy of the
        // chart's mapping, so the chart stays free to draw).
        let columns = chart.plotting_area().dim_in_pixel().0;
        let coord = chart.as_coord_spec().clone();
        let column_of = |x: f64, y: f64| coord.translate(&(x, y)).0;
        for series in series {
            let Series {
                name,
                single,
                colour: c,
                width: w,
                values,
            } = series;
            let thin = thins(values.len(), columns).then_some(&column_of);
            let mut runs = thinned_finite_runs(self.iterations, values.values(), thin);
            let label = match (name, runs.last().and_then(|r| r.last())) {
                (Some(name), Some(p)) if single => {
                    Some(format!("{name} (final {})", format_value(p.1)))
                }
                (name, _) => name,
            };
            if runs.is_empty() {
                runs.push(Vec::new());
            }
            for (k, r) in runs.into_iter().enumerate() {
                let anno = chart.draw_series(LineSeries::new(r, c.stroke_width(w)))?;
                if let (0, Some(label)) = (k, &label) {
                    anno.label(label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + key_len, y)], c.stroke_width(w))
                    });
                }
            }
        }
        crate::axis::draw_series_key(&mut chart, s, SeriesLabelPosition::UpperRight)
    }
}
