//! Communication over the mission, in two panels on one time axis. Top: one row per UAV,
//! coloured by its status at every communication step (in direct contact with a ground
//! node, relayed through other UAVs, out of contact), with a thin bar under the row while
//! the UAV is inside an active interference disk and one over it while it waits at its start
//! before departing (a departure delay). Bottom: the range R(t) after shadowing,
//! the nominal range R0, and the shrunken range of links with an end inside each window.
//! Interference windows are shaded in both panels. A side panel holds the legend and each
//! UAV's seconds relayed and out of contact.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use swarmplan_core::cost::comm::Contact;
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::channel::loss_factor;
use swarmplan_core::world::World;

use crate::axis::{draw_mesh, format_value, Axis};
use crate::legend::{self, Entry};
use crate::render::{render, DrawResult, Figure, PlotError, Target, Written};
use crate::sampling::ContactTrace;
use crate::style::{self, Scale, GRID};

/// Writes the communication timeline of `plan` in `world` to `out` (PNG and SVG).
pub fn comm_timeline(
    world: &World,
    plan: &Plan,
    title: &str,
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    render(
        &CommTimeline {
            world,
            title,
            trace: ContactTrace::new(world, plan),
            departures: TimedPlan::flown(world, plan)
                .paths
                .iter()
                .map(|p| p.depart)
                .collect(),
        },
        &out.into(),
    )
}

struct CommTimeline<'a> {
    world: &'a World,
    title: &'a str,
    trace: ContactTrace,
    /// Per UAV, when it leaves its start (0 without a departure delay).
    departures: Vec<f64>,
}

fn status_colour(c: Contact) -> RGBColor {
    match c {
        Contact::Direct => style::DIRECT,
        Contact::Relayed => style::RELAYED,
        Contact::Out => style::OUT,
    }
}

impl CommTimeline<'_> {
    fn t_end(&self) -> f64 {
        self.trace.times.last().copied().unwrap_or(0.0).max(1.0)
    }

    /// Row position of UAV i (UAV 1 on top).
    fn row(&self, i: usize) -> f64 {
        (self.trace.uav_count() - 1 - i) as f64
    }

    fn draw_windows<DB: DrawingBackend>(
        &self,
        chart: &mut ChartContext<'_, DB, Cartesian2d<Axis, Axis>>,
        lo: f64,
        hi: f64,
        labels: bool,
        s: Scale,
    ) -> DrawResult<(), DB> {
        for (k, w) in self.world.channel().interference().iter().enumerate() {
            let (a, b) = (w.time[0].max(0.0), w.time[1].min(self.t_end()));
            if a >= b {
                continue;
            }
            chart.draw_series(std::iter::once(Rectangle::new(
                [(a, lo), (b, hi)],
                style::INTERFERENCE.mix(0.12).filled(),
            )))?;
            if labels {
                let text = s
                    .note()
                    .color(&style::INTERFERENCE)
                    .pos(Pos::new(HPos::Left, VPos::Top));
                // One line per window, so that overlapping windows keep readable labels.
                chart.draw_series(std::iter::once(
                    EmptyElement::at((a, hi))
                        + Text::new(
                            format!(
                                "W{}: {}-{} s, {} dB",
                                k + 1,
                                format_value(w.time[0]),
                                format_value(w.time[1]),
                                format_value(w.loss_db)
                            ),
                            (s.off(4.0), s.off(3.0) + k as i32 * s.off(17.0)),
                            text,
                        ),
                ))?;
            }
        }
        Ok(())
    }

    fn draw_rows<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let n = self.trace.uav_count();
        let rows = Axis::fixed(-0.5, n as f64 - 0.5, (0..n).map(|k| k as f64).collect());
        let mut chart = ChartBuilder::on(area)
            .caption("contact per UAV", s.subtitle())
            .margin(s.px(12.0))
            .margin_right(s.px(25.0))
            .x_label_area_size(s.px(45.0))
            .y_label_area_size(s.px(100.0))
            .build_cartesian_2d(Axis::linear(0.0, self.t_end()), rows)?;
        // At most about 20 row labels, so a large fleet's names do not overprint.
        let every = n.div_ceil(MAX_ROW_LABELS).max(1);
        let name = |v: &f64| {
            let k = v.round();
            if (v - k).abs() < 1e-6 && k >= 0.0 && (k as usize) < n {
                let uav = n - 1 - k as usize;
                if uav.is_multiple_of(every) {
                    return format!("UAV {uav}");
                }
            }
            String::new()
        };
        chart
            .configure_mesh()
            .disable_y_mesh()
            .light_line_style(GRID.mix(0.35))
            .bold_line_style(GRID.mix(0.9))
            .label_style(s.tick())
            .axis_desc_style(s.axis_desc())
            .y_label_formatter(&name)
            .x_labels(12)
            .max_light_lines(5)
            .x_desc("time, s")
            .draw()?;
        self.draw_windows(&mut chart, -0.5, n as f64 - 0.5, false, s)?;
        let dt = self.trace.dt;
        let t_end = self.t_end();
        for i in 0..n {
            let y = self.row(i);
            chart.draw_series(self.trace.runs(i).into_iter().map(|r| {
                let a = (self.trace.times[r.first] - dt / 2.0).max(0.0);
                let b = (self.trace.times[r.last] + dt / 2.0).min(t_end);
                Rectangle::new(
                    [(a, y - 0.3), (b, y + 0.3)],
                    status_colour(r.status).filled(),
                )
            }))?;
            // Over the row: while the UAV waits at its start.
            let depart = self.departures.get(i).copied().unwrap_or(0.0);
            if depart > 0.0 && depart.is_finite() {
                chart.draw_series(std::iter::once(Rectangle::new(
                    [(0.0, y + 0.34), (depart.min(t_end), y + 0.42)],
                    style::WAITING.filled(),
                )))?;
            }
            // Under the row: while the UAV is inside an active interference disk.
            let ch = self.world.channel();
            let inside: Vec<bool> = self
                .trace
                .times
                .iter()
                .zip(&self.trace.positions)
                .map(|(t, p)| ch.interference_db(*t, p[i].x, p[i].y) > 0.0)
                .collect();
            chart.draw_series(
                inside
                    .iter()
                    .enumerate()
                    .filter(|(_, b)| **b)
                    .map(|(k, _)| {
                        let t = self.trace.times[k];
                        Rectangle::new(
                            [
                                ((t - dt / 2.0).max(0.0), y - 0.42),
                                ((t + dt / 2.0).min(t_end), y - 0.34),
                            ],
                            style::INTERFERENCE.filled(),
                        )
                    }),
            )?;
        }
        Ok(())
    }

    fn draw_range<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let ch = self.world.channel();
        let range: Vec<(f64, f64)> = self
            .trace
            .times
            .iter()
            .enumerate()
            .map(|(k, t)| (*t, ch.base_range(k)))
            .collect();
        let r0 = ch.nominal_range();
        let windows = ch.interference().len() as f64;
        let top = range.iter().map(|p| p.1).fold(r0, f64::max) * (1.1 + 0.07 * windows);
        let mut chart = ChartBuilder::on(area)
            .caption("radio range", s.subtitle())
            .margin(s.px(12.0))
            .margin_right(s.px(25.0))
            .x_label_area_size(s.px(65.0))
            .y_label_area_size(s.px(100.0))
            .build_cartesian_2d(Axis::linear(0.0, self.t_end()), Axis::linear(0.0, top))?;
        draw_mesh(&mut chart, s, "time, s", "range, m")?;
        self.draw_windows(&mut chart, 0.0, top, true, s)?;
        let dashed = |pts: Vec<(f64, f64)>, c: RGBColor, w: u32| {
            // Dashes in time units: about 1/100 of the axis.
            let d = self.t_end() / 100.0;
            let scale_y = self.t_end() / top;
            let scaled: Vec<(f64, f64)> = pts.iter().map(|(x, y)| (*x, y * scale_y)).collect();
            style::dashes(&scaled, d, d * 0.7)
                .into_iter()
                .map(move |p| {
                    PathElement::new(
                        p.into_iter()
                            .map(|(x, y)| (x, y / scale_y))
                            .collect::<Vec<_>>(),
                        c.stroke_width(w),
                    )
                })
                .collect::<Vec<_>>()
        };
        chart.draw_series(dashed(
            vec![(0.0, r0), (self.t_end(), r0)],
            RGBColor(120, 120, 120),
            s.px(2.0),
        ))?;
        for w in ch.interference() {
            let f = loss_factor(w.loss_db);
            let pts: Vec<(f64, f64)> = range
                .iter()
                .filter(|(t, _)| *t >= w.time[0] && *t <= w.time[1])
                .map(|(t, r)| (*t, r * f))
                .collect();
            if pts.len() >= 2 {
                chart.draw_series(dashed(pts, style::INTERFERENCE, s.px(2.5)))?;
            }
        }
        chart.draw_series(LineSeries::new(
            range,
            RGBColor(0, 82, 204).stroke_width(s.px(2.5)),
        ))?;
        Ok(())
    }

    fn legend_entries(&self, s: Scale) -> Vec<Entry> {
        let mut e = vec![
            Entry::Heading("contact".into()),
            Entry::patch(
                "direct to a ground node",
                style::DIRECT.mix(1.0),
                style::DIRECT,
            ),
            Entry::patch("relayed via UAVs", style::RELAYED.mix(1.0), style::RELAYED),
            Entry::patch("out of contact", style::OUT.mix(1.0), style::OUT),
            Entry::line("inside interference disk", style::INTERFERENCE, s.px(5.0)),
            Entry::patch(
                "interference window",
                style::INTERFERENCE.mix(0.12),
                style::INTERFERENCE,
            ),
            Entry::Heading("range".into()),
            Entry::line("R(t), shadowing", RGBColor(0, 82, 204), s.px(2.5)),
            Entry::dashed("R0, nominal", RGBColor(120, 120, 120), s.px(2.0)),
            Entry::dashed("R(t) in a window", style::INTERFERENCE, s.px(2.5)),
            Entry::Heading("seconds relayed / out".into()),
        ];
        if self.departures.iter().any(|d| *d > 0.0) {
            // Right after the interference disk's bar, the other thin bar of a row.
            e.insert(
                5,
                Entry::line("waiting at its start", style::WAITING, s.px(5.0)),
            );
        }
        let n = self.trace.uav_count();
        let line = |i: usize| {
            Entry::Note(format!(
                "UAV {}: {} s / {} s",
                i,
                format_value(self.trace.seconds(i, Contact::Relayed)),
                format_value(self.trace.seconds(i, Contact::Out)),
            ))
        };
        if n <= style::UAV_LEGEND_ROWS {
            e.extend((0..n).map(line));
            return e;
        }
        // A large fleet: its totals, then the UAVs out of contact longest (then relayed
        // longest), as many as a panel holds.
        let total = |c: Contact| (0..n).map(|i| self.trace.seconds(i, c)).sum::<f64>();
        e.push(Entry::Note(format!(
            "all {n} UAVs: {} s / {} s",
            format_value(total(Contact::Relayed)),
            format_value(total(Contact::Out)),
        )));
        // Each UAV's seconds counted once (a count walks the whole timeline).
        let keys: Vec<(f64, f64)> = (0..n)
            .map(|i| {
                (
                    self.trace.seconds(i, Contact::Out),
                    self.trace.seconds(i, Contact::Relayed),
                )
            })
            .collect();
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by(|&a, &b| {
            let (ka, kb) = (keys[a], keys[b]);
            kb.0.total_cmp(&ka.0)
                .then(kb.1.total_cmp(&ka.1))
                .then(a.cmp(&b))
        });
        e.push(Entry::Note("longest out, then relayed:".into()));
        e.extend(order.into_iter().take(style::UAV_LEGEND_ROWS / 2).map(line));
        e
    }
}

/// Row labels of the contact chart, at most (every k-th UAV above this many).
const MAX_ROW_LABELS: usize = 20;

impl Figure for CommTimeline<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let body = root.titled(self.title, s.title())?;
        let (w, h) = body.dim_in_pixel();
        let side_w = s.px(290.0).min(w / 3);
        let (charts, side) = body.split_horizontally(w - side_w);
        let (top, bottom) = charts.split_vertically(h * 11 / 20);
        if self.trace.uav_count() > 0 {
            self.draw_rows(&top, s)?;
        }
        self.draw_range(&bottom, s)?;
        legend::draw(&side, &self.legend_entries(s), s.off(30.0), s)
    }
}
