//! A suite at a glance: the performance profile of Dolan & Moré (2002, "Benchmarking
//! optimization software with performance profiles", Math. Program. 91:201-213,
//! doi:10.1007/s101070100263) over the instances of a bench.
//!
//! On each instance every method gets one number, its median cost per UAV over its runs
//! (penalised costs, so an infeasible median is large, not missing), and its ratio to the
//! best method's on that instance. A method's curve is the share of instances on which its
//! ratio is at most tau: at tau = 1 the share it wins, and how fast it rises tells how far
//! behind it is where it does not. A curve that never reaches 1 has instances with no finite
//! median. Unlike average ranks, the profile shows by how much a method loses, not only how
//! often; the table of per-instance values is in `summary.md`.

use plotters::coord::Shift;
use plotters::prelude::*;
use swarmplan_experiment::record::RunRecord;

use crate::axis::{draw_mesh, Axis};
use crate::records::{cost, groups};
use crate::render::{no_data, render, DrawResult, Figure, PlotError, Target, Written};
use crate::stats::{quantile_sorted, sorted};
use crate::style::{self, Scale};

/// Writes the performance profile of every method over the scenarios of `records` to `out`;
/// needs at least two scenarios where two or more methods ran.
pub fn performance_profile(
    records: &[RunRecord],
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    let target = out.into();
    let ratios = ratios(records);
    let instances = ratios.first().map_or(0, |c| c.ratios.len());
    if ratios.len() < 2 || instances < 2 {
        return Err(no_data(
            &target,
            "a performance profile needs two methods on at least two common scenarios",
        ));
    }
    let hi = ratios
        .iter()
        .flat_map(|c| c.ratios.iter().copied())
        .filter(|r| r.is_finite())
        .fold(1.0_f64, f64::max);
    let x = Axis::auto([1.0, hi.max(1.01)], 0.02, false);
    render(&Profile { curves: ratios, x }, &target)
}

/// One method's ratio to the best median on each common instance, sorted.
struct Curve {
    label: String,
    ratios: Vec<f64>,
}

/// Ratios over the scenarios on which every method ran (others are left out).
fn ratios(records: &[RunRecord]) -> Vec<Curve> {
    let mut scenarios: Vec<&str> = records.iter().map(|r| r.scenario.as_str()).collect();
    scenarios.sort_unstable();
    scenarios.dedup();
    // label -> median per scenario (None where the method did not run there)
    let mut labels: Vec<String> = Vec::new();
    let mut medians: Vec<Vec<Option<f64>>> = Vec::new();
    for (i, sc) in scenarios.iter().enumerate() {
        for g in groups(records, sc) {
            let at = labels
                .iter()
                .position(|l| *l == g.label)
                .unwrap_or_else(|| {
                    labels.push(g.label.clone());
                    medians.push(vec![None; scenarios.len()]);
                    labels.len() - 1
                });
            let v = sorted(g.runs.iter().map(|r| cost(r.cost_per_uav)));
            medians[at][i] = Some(quantile_sorted(&v, 0.5));
        }
    }
    let common: Vec<usize> = (0..scenarios.len())
        .filter(|&i| medians.iter().all(|m| m[i].is_some()))
        .collect();
    let mut curves: Vec<Curve> = labels
        .into_iter()
        .map(|label| Curve {
            label,
            ratios: Vec::with_capacity(common.len()),
        })
        .collect();
    for &i in &common {
        let best = medians
            .iter()
            .filter_map(|m| m[i])
            .fold(f64::INFINITY, f64::min);
        for (c, m) in curves.iter_mut().zip(&medians) {
            let v = m[i].unwrap_or(f64::INFINITY);
            let r = if v == best {
                1.0
            } else if best > 0.0 && best.is_finite() {
                v / best
            } else {
                f64::INFINITY
            };
            c.ratios.push(r);
        }
    }
    for c in &mut curves {
        c.ratios.sort_by(f64::total_cmp);
    }
    curves
}

/// The step function of `ratios` (sorted) as line points, from tau = 1 to `x_max`.
fn steps(ratios: &[f64], x_max: f64) -> Vec<(f64, f64)> {
    let n = ratios.len() as f64;
    let at_one = ratios.iter().filter(|r| **r <= 1.0).count();
    let mut pts = vec![(1.0, at_one as f64 / n)];
    for (k, &r) in ratios.iter().enumerate().skip(at_one) {
        if !r.is_finite() || r > x_max {
            break;
        }
        pts.push((r, k as f64 / n));
        pts.push((r, (k + 1) as f64 / n));
    }
    let last = pts.last().map_or(0.0, |p| p.1);
    pts.push((x_max, last));
    pts
}

struct Profile {
    curves: Vec<Curve>,
    x: Axis,
}

impl Figure for Profile {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let n = self.curves.first().map_or(0, |c| c.ratios.len());
        let title = format!("Performance profile over {n} instances (median cost per UAV)");
        let body = root.titled(&title, s.title())?;
        let mut chart = crate::axis::line_chart(&body, s, self.x.clone(), Axis::linear(0.0, 1.02))?;
        let x_desc = if self.x.is_log() {
            "tau: median cost / best median on the instance (log scale)"
        } else {
            "tau: median cost / best median on the instance"
        };
        draw_mesh(
            &mut chart,
            s,
            x_desc,
            "share of instances within tau of the best",
        )?;
        let w = s.px(3.0);
        for (i, c) in self.curves.iter().enumerate() {
            let colour = style::series_colour(i);
            let wins = c.ratios.iter().filter(|r| **r <= 1.0).count();
            let label = format!("{} (best on {wins} of {n})", c.label);
            chart
                .draw_series(LineSeries::new(
                    steps(&c.ratios, self.x.hi()),
                    colour.stroke_width(w),
                ))?
                .label(label)
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 24, y)], colour.stroke_width(3))
                });
        }
        crate::axis::draw_series_key(&mut chart, s, SeriesLabelPosition::LowerRight)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profile_is_the_share_of_instances_within_tau() {
        let pts = steps(&[1.0, 1.0, 1.5, 3.0, f64::INFINITY], 4.0);
        assert_eq!(
            pts,
            [
                (1.0, 0.4),
                (1.5, 0.4),
                (1.5, 0.6),
                (3.0, 0.6),
                (3.0, 0.8),
                (4.0, 0.8)
            ]
        );
    }
}
