//! The map seen from above: terrain as a shaded colour relief with contour lines, threat
//! cylinders as circles in data units (filled hard zone r + size, dashed danger band
//! r + 11 size), interference disks, ground nodes, each UAV's path with its waypoints, and a
//! mark wherever a UAV was out of contact (sampled at every communication step) with the
//! times of each outage, and at its start how long a UAV with a departure delay hovers there
//! ("UAV 4 waits 11.6 s"). When a UAV is out of contact, the places where no UAV links to
//! the ground directly even at the top of the altitude band are hatched
//! ([`GroundCoverage`]): an outage there needs a relay, not another path. A colour bar and
//! the legend sit in a panel to the right.
//!
//! One metre east is one metre north on screen: the chart's margins are computed so that the
//! plotting area has the map's aspect ratio ([`equal_aspect_margins`]).

use plotters::coord::Shift;
use plotters::element::BitMapElement;
use plotters::prelude::*;
use swarmplan_core::cost::comm::Contact;
use swarmplan_core::cost::coverage::GroundCoverage;
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::spec::CommRequirement;
use swarmplan_core::world::World;

use crate::axis::{format_value, Axis};
use crate::contour::{interval, levels, Grid};
use crate::legend::{self, draw_shape, Entry, Shape};
use crate::render::{render, DrawResult, Figure, PlotError, Target, Written};
use crate::sampling::ContactTrace;
use crate::style::{self, Scale, FONT};
use crate::violation_marks::ViolationMarks;

/// Writes the top view of `plan` in `world` to `out` (PNG and SVG). `title` should name the
/// scenario, algorithm and seed.
pub fn top_view(
    world: &World,
    plan: &Plan,
    title: &str,
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    render(&TopView::new(world, plan, title), &out.into())
}

/// The danger band reaches this many drone sizes beyond the hard zone r + size (SPSO's J2).
const DANGER_SIZES: f64 = 10.0;

/// A contour segment, two points in metres.
type Segment = [(f64, f64); 2];

struct TopView<'a> {
    world: &'a World,
    plan: &'a Plan,
    title: &'a str,
    trace: ContactTrace,
    marks: ViolationMarks,
    /// Where no direct ground link exists at the top of the altitude band, when some UAV is
    /// out of contact (else not computed, and nothing hatched).
    dead: Option<GroundCoverage>,
    x: (f64, f64),
    y: (f64, f64),
    /// Terrain height range of the colour map.
    h: (f64, f64),
    step: f64,
    /// (level, segments).
    contours: Vec<(f64, Vec<Segment>)>,
}

impl<'a> TopView<'a> {
    fn new(world: &'a World, plan: &'a Plan, title: &'a str) -> Self {
        let m = &world.spec().map;
        let (mut x, mut y) = ((m.x[0], m.x[1]), (m.y[0], m.y[1]));
        let points = plan
            .uavs
            .iter()
            .flat_map(|p| p.waypoints.iter().map(|w| (w.x, w.y)))
            .chain(
                world
                    .ground_nodes_at(swarmplan_core::world::DEPARTURE)
                    .iter()
                    .map(|g| (g.position.x, g.position.y)),
            );
        for (px, py) in points.filter(|(a, b)| a.is_finite() && b.is_finite()) {
            x = (x.0.min(px), x.1.max(px));
            y = (y.0.min(py), y.1.max(py));
        }
        let t = world.terrain();
        let h = (t.min_height(), t.max_height());
        let step = interval(h.0, h.1);
        let cells = |a: f64, b: f64| (((b - a) / 4.0).ceil() as usize + 1).clamp(2, 260);
        let grid = Grid::sample(x, y, (cells(x.0, x.1), cells(y.0, y.1)), |px, py| {
            t.height(px, py)
        });
        let contours = levels(h.0, h.1, step)
            .into_iter()
            .map(|l| (l, grid.contour(l)))
            .collect();
        let trace = ContactTrace::new(world, plan);
        // Under `relay` contact means a way to the ground; under `neighbour` it does not.
        let relay = world.spec().communication.requirement == CommRequirement::Relay;
        let out = relay && (0..trace.uav_count()).any(|i| trace.seconds(i, Contact::Out) > 0.0);
        Self {
            world,
            plan,
            title,
            dead: out.then(|| GroundCoverage::at_band_top(world)),
            trace,
            marks: ViolationMarks::new(world, plan),
            x,
            y,
            h,
            step,
            contours,
        }
    }

    /// RGB pixels of the shaded relief for a plotting area of `w` x `h` pixels.
    fn relief(&self, w: usize, h: usize) -> Vec<u8> {
        let t = self.world.terrain();
        let (dx, dy) = (self.x.1 - self.x.0, self.y.1 - self.y.0);
        let heights: Vec<f64> = (0..h)
            .flat_map(|j| {
                let py = self.y.1 - (j as f64 + 0.5) / h as f64 * dy;
                (0..w).map(move |i| (self.x.0 + (i as f64 + 0.5) / w as f64 * dx, py))
            })
            .map(|(px, py)| t.height(px, py))
            .collect();
        let (sx, sy) = (dx / w as f64, dy / h as f64);
        let span = (self.h.1 - self.h.0).max(1e-9);
        // Light from the north-west, 45 degrees up; flat ground keeps its colour.
        let light = glam::DVec3::new(-0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2);
        let mut buf = Vec::with_capacity(w * h * 3);
        for j in 0..h {
            for i in 0..w {
                let at = |a: usize, b: usize| heights[b * w + a];
                let (il, ir) = (i.saturating_sub(1), (i + 1).min(w - 1));
                let (jn, js) = (j.saturating_sub(1), (j + 1).min(h - 1));
                let dzdx = (at(ir, j) - at(il, j)) / (sx * (ir - il).max(1) as f64);
                // Rows run southwards, so north is towards smaller j.
                let dzdy = (at(i, jn) - at(i, js)) / (sy * (js - jn).max(1) as f64);
                let n = glam::DVec3::new(-dzdx, -dzdy, 1.0).normalize();
                let lambert = n.dot(light).max(0.0);
                let f = (1.0 + 0.6 * (lambert - light.z)).clamp(0.7, 1.15);
                let mut c = style::shade(style::terrain_colour((at(i, j) - self.h.0) / span), f);
                if let Some(dead) = &self.dead {
                    let px = self.x.0 + (i as f64 + 0.5) * sx;
                    let py = self.y.1 - (j as f64 + 0.5) * sy;
                    if !dead.linked(px, py) {
                        // Hatched: grey stripes rising to the right over a dimmed relief.
                        c = if (i + j) % 9 < 3 {
                            style::DEAD_HATCH
                        } else {
                            style::shade(c, 0.8)
                        };
                    }
                }
                buf.extend_from_slice(&[c.0, c.1, c.2]);
            }
        }
        buf
    }

    fn legend_entries(&self, s: Scale) -> Vec<Entry> {
        let w = s.px(3.0);
        let n = self.plan.uavs.len();
        let mut e: Vec<Entry> = (0..n)
            .filter_map(|i| {
                Some(Entry::line(
                    style::uav_label(i, n)?,
                    style::uav_colour(i),
                    w,
                ))
            })
            .collect();
        e.push(Entry::marker("waypoint", Shape::Dot, RGBColor(90, 90, 90)));
        e.push(Entry::marker(
            "out of contact (t, s)",
            Shape::RingCross,
            RGBColor(60, 60, 60),
        ));
        e.extend(self.marks.legend_entries(s));
        if let Some(dead) = &self.dead {
            e.push(Entry::patch(
                format!("no ground link at {} m AGL", format_value(dead.agl)),
                style::DEAD_HATCH.mix(0.8),
                style::DEAD_HATCH,
            ));
        }
        e.push(Entry::patch(
            "threat: r + size",
            style::THREAT.mix(0.35),
            style::THREAT_DARK,
        ));
        e.push(Entry::dashed(
            "danger band: r + 11 size",
            style::THREAT_DARK,
            s.px(2.0),
        ));
        if !self.world.channel().interference().is_empty() {
            e.push(Entry::dashed(
                "interference window",
                style::INTERFERENCE,
                s.px(2.0),
            ));
        }
        for g in self.world.ground_nodes_at(swarmplan_core::world::DEPARTURE) {
            e.push(Entry::marker(g.name.clone(), node_shape(&g.name), BLACK));
        }
        e.push(Entry::line(
            format!("contour, every {} m", format_value(self.step)),
            RGBColor(90, 70, 50),
            1,
        ));
        e
    }

    fn draw_colour_bar<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let mut bar = ChartBuilder::on(area)
            .margin_top(s.px(30.0))
            .margin_bottom(s.px(10.0))
            .margin_left(s.px(30.0))
            .margin_right(s.px(10.0))
            .right_y_label_area_size(s.px(110.0))
            .build_cartesian_2d(Axis::linear(0.0, 1.0), Axis::linear(self.h.0, self.h.1))?;
        bar.configure_mesh()
            .disable_x_mesh()
            .disable_y_mesh()
            .disable_x_axis()
            .y_labels(8)
            .label_style(s.tick())
            .axis_desc_style(s.axis_desc())
            .y_desc("terrain height, m")
            .draw()?;
        let n = 120;
        let span = self.h.1 - self.h.0;
        bar.draw_series((0..n).map(|k| {
            let a = self.h.0 + span * k as f64 / n as f64;
            let b = self.h.0 + span * (k + 1) as f64 / n as f64;
            let c = style::terrain_colour((k as f64 + 0.5) / n as f64);
            Rectangle::new([(0.0, a), (1.0, b)], c.filled())
        }))?;
        bar.draw_series(self.contours.iter().map(|(l, _)| {
            PathElement::new(
                vec![(0.0, *l), (1.0, *l)],
                RGBColor(90, 70, 50).stroke_width(1),
            )
        }))?;
        Ok(())
    }
}

fn node_shape(name: &str) -> Shape {
    match name {
        "GCS" => Shape::Triangle,
        "UGV0" => Shape::Square,
        _ => Shape::Dot,
    }
}

/// Margins (left, right, top, bottom) of a chart on a `w` x `h` px area whose plotting area
/// shows `dx` x `dy` data units at one scale, given the left and bottom label areas `yl` and
/// `xl` and a least margin `m` on every side.
pub(crate) fn equal_aspect_margins(
    (w, h): (u32, u32),
    (dx, dy): (f64, f64),
    (yl, xl): (u32, u32),
    m: u32,
) -> [u32; 4] {
    let aw = f64::from(w.saturating_sub(yl + 2 * m));
    let ah = f64::from(h.saturating_sub(xl + 2 * m));
    if !(dx > 0.0 && dy > 0.0 && aw > 0.0 && ah > 0.0) {
        return [m; 4];
    }
    let s = (aw / dx).min(ah / dy);
    let ew = (aw - (dx * s).round()).max(0.0) as u32;
    let eh = (ah - (dy * s).round()).max(0.0) as u32;
    [m + ew / 2, m + ew - ew / 2, m + eh / 2, m + eh - eh / 2]
}

/// The map's chart: x and y in metres at equal scale.
type MapChart<'a, DB> = ChartContext<'a, DB, Cartesian2d<Axis, Axis>>;

impl Figure for TopView<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let body = root.titled(self.title, s.title())?;
        let (w, _) = body.dim_in_pixel();
        let side_w = s.px(290.0).min(w / 3);
        let (map_area, side) = body.split_horizontally(w - side_w);
        let (yl, xl) = (s.px(85.0), s.px(65.0));
        let [ml, mr, mt, mb] = equal_aspect_margins(
            map_area.dim_in_pixel(),
            (self.x.1 - self.x.0, self.y.1 - self.y.0),
            (yl, xl),
            s.px(12.0),
        );
        let mut chart = ChartBuilder::on(&map_area)
            .margin_left(ml)
            .margin_right(mr)
            .margin_top(mt)
            .margin_bottom(mb)
            .y_label_area_size(yl)
            .x_label_area_size(xl)
            .build_cartesian_2d(
                Axis::linear(self.x.0, self.x.1),
                Axis::linear(self.y.0, self.y.1),
            )?;

        self.draw_ground(&mut chart, s)?;
        self.draw_hazards(&mut chart, s)?;
        let flown = self.draw_paths(&mut chart, s)?;
        let mut labels = self.draw_marks(root, &chart, s)?;
        self.label_departures(root, &chart, &flown, &mut labels, s)?;
        self.draw_outages(root, &chart, &mut labels, s)?;
        self.label_windows(root, &chart, &mut labels, s)?;
        // Side panel: colour bar above, legend below.
        let (_, sh) = side.dim_in_pixel();
        let (bar, rest) = side.split_vertically(sh * 2 / 5);
        self.draw_colour_bar(&bar, s)?;
        legend::draw(&rest, &self.legend_entries(s), s.off(10.0), s)
    }
}

impl TopView<'_> {
    /// Relief, then axes, then contours: the ground everything else is drawn on.
    fn draw_ground<DB: DrawingBackend>(
        &self,
        chart: &mut MapChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        // Relief first, then axes, then everything else on top.
        let (px, py) = chart.plotting_area().get_pixel_range();
        let (pw, ph) = ((px.end - px.start).max(1), (py.end - py.start).max(1));
        let relief = BitMapElement::with_owned_buffer(
            (self.x.0, self.y.1),
            (pw as u32, ph as u32),
            self.relief(pw as usize, ph as usize),
        )
        .expect("the relief buffer holds width x height RGB pixels");
        chart.plotting_area().draw(&relief)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .disable_y_mesh()
            .x_labels(10)
            .y_labels(10)
            .label_style(s.tick())
            .axis_desc_style(s.axis_desc())
            .x_desc("x (east), m")
            .y_desc("y (north), m")
            .draw()?;

        let contour_colour = RGBColor(90, 70, 50);
        for (l, segs) in &self.contours {
            // Every fourth level (100 m at 25 m spacing) is an index contour, drawn bolder.
            let index = ((l / self.step).round() as i64) % 4 == 0;
            let style = if index {
                contour_colour.mix(0.8).stroke_width(s.px(1.6))
            } else {
                contour_colour.mix(0.45).stroke_width(1)
            };
            chart.draw_series(segs.iter().map(|q| PathElement::new(q.to_vec(), style)))?;
        }
        Ok(())
    }

    /// Interference disks and threats (hard zone filled, danger band dashed), then the
    /// halo of every violating segment, drawn before the paths.
    fn draw_hazards<DB: DrawingBackend>(
        &self,
        chart: &mut MapChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let span = (self.x.1 - self.x.0).max(self.y.1 - self.y.0);
        let (dash, gap) = (span / 120.0, span / 200.0);
        for win in self.world.channel().interference() {
            let ring = style::circle(win.center[0], win.center[1], win.radius, 120);
            let ring = style::within_view(ring, self.x, self.y);
            chart.draw_series(
                style::dashes(&ring, dash * 0.6, gap)
                    .into_iter()
                    .map(|d| PathElement::new(d, style::INTERFERENCE.stroke_width(s.px(2.5)))),
            )?;
        }

        let size = |i: usize| self.world.spec().uavs.get(i).map_or(1.0, |u| u.size);
        let drone = (0..self.world.uav_count()).map(size).fold(0.0, f64::max);
        for th in &self.world.spec().threats {
            let hard = style::circle(th.x, th.y, th.r + drone, 96);
            let hard = style::within_view(hard, self.x, self.y);
            let band = style::circle(th.x, th.y, th.r + (1.0 + DANGER_SIZES) * drone, 96);
            let band = style::within_view(band, self.x, self.y);
            chart.draw_series(style::dashes(&band, dash, gap).into_iter().map(|d| {
                PathElement::new(d, style::THREAT_DARK.mix(0.9).stroke_width(s.px(2.0)))
            }))?;
            chart.draw_series(std::iter::once(Polygon::new(
                hard.clone(),
                style::THREAT.mix(0.35).filled(),
            )))?;
            chart.draw_series(std::iter::once(PathElement::new(
                hard,
                style::THREAT_DARK.stroke_width(s.px(2.0)),
            )))?;
        }

        // Violating segments: a wide halo under the path, drawn before the paths.
        for seg in &self.marks.segments {
            let [a, b] = seg.ends;
            let ends = vec![(a.x, a.y), (b.x, b.y)];
            chart.draw_series(std::iter::once(PathElement::new(
                ends.clone(),
                style::VIOLATION_TEXT.stroke_width(s.px(14.0)),
            )))?;
            chart.draw_series(std::iter::once(PathElement::new(
                ends,
                style::VIOLATION.stroke_width(s.px(10.0)),
            )))?;
        }
        Ok(())
    }

    /// Each UAV's flown path and its waypoints; returns what is flown.
    fn draw_paths<DB: DrawingBackend>(
        &self,
        chart: &mut MapChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<TimedPlan, DB> {
        // The line is what is flown (arcs through the corners under the strict profile),
        // the dots are the waypoints.
        let flown = TimedPlan::flown(self.world, self.plan);
        for (i, (path, f)) in self.plan.uavs.iter().zip(&flown.paths).enumerate() {
            let c = style::uav_colour(i);
            let line: Vec<(f64, f64)> = f.abs.iter().map(|p| (p.x, p.y)).collect();
            chart.draw_series(std::iter::once(PathElement::new(
                line,
                c.stroke_width(s.px(3.0)),
            )))?;
            let pts: Vec<(f64, f64)> = path.waypoints.iter().map(|p| (p.x, p.y)).collect();
            chart.draw_series(pts.iter().map(|p| Circle::new(*p, s.px(4.5), c.filled())))?;
        }
        Ok(flown)
    }

    /// Ground nodes with their names, and a diamond with its kind at every violation that
    /// has a place; returns the label placer with their room reserved.
    fn draw_marks<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &MapChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<Labels, DB> {
        // Ground nodes, their labels reserved before any outage label is placed.
        let (bx, by) = chart.plotting_area().get_pixel_range();
        let mut labels = Labels::new([bx.start, by.start, bx.end, by.end]);
        let node_text: TextStyle = (FONT, s.font(18.0)).into_font().color(&BLACK);
        for g in self.world.ground_nodes_at(swarmplan_core::world::DEPARTURE) {
            let at = chart.backend_coord(&(g.position.x, g.position.y));
            draw_shape(root, at, s.off(9.0), node_shape(&g.name), BLACK, s)?;
            let (w, h) = root.estimate_text_size(&g.name, &node_text)?;
            let tl = (at.0 + s.off(11.0), at.1 + s.off(4.0));
            labels.reserve([
                at.0 - s.off(10.0),
                at.1 - s.off(10.0),
                at.0 + s.off(10.0),
                at.1 + s.off(10.0),
            ]);
            labels.reserve([tl.0, tl.1, tl.0 + w as i32, tl.1 + h as i32]);
            root.draw(&Text::new(g.name.clone(), tl, node_text.clone()))?;
        }

        // Other violations with a place: a diamond and its kind, labelled where free.
        for place in &self.marks.places {
            let at = chart.backend_coord(&(place.at.x, place.at.y));
            draw_shape(root, at, s.off(7.0), Shape::Diamond, style::VIOLATION, s)?;
            labels.reserve([
                at.0 - s.off(8.0),
                at.1 - s.off(8.0),
                at.0 + s.off(8.0),
                at.1 + s.off(8.0),
            ]);
        }
        for place in &self.marks.places {
            let at = chart.backend_coord(&(place.at.x, place.at.y));
            let text: TextStyle = (FONT, s.font(15.0))
                .into_font()
                .color(&style::VIOLATION_TEXT);
            let (w, h) = root.estimate_text_size(&place.label, &text)?;
            if let Some(tl) = labels.place(at, (w as i32, h as i32), s) {
                boxed_label(root, tl, (w, h), place.label.clone(), text, s)?;
            }
        }
        Ok(labels)
    }

    /// Departure delays: a UAV that hovers at its start before it leaves, labelled there.
    fn label_departures<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &MapChart<'_, DB>,
        flown: &TimedPlan,
        labels: &mut Labels,
        s: Scale,
    ) -> DrawResult<(), DB> {
        for (i, f) in flown.paths.iter().enumerate() {
            if f.depart <= 0.0 || !f.depart.is_finite() {
                continue;
            }
            let Some(p) = f.abs.first() else { continue };
            let at = chart.backend_coord(&(p.x, p.y));
            let label = format!("UAV {i} waits {} s", format_value(f.depart));
            let c = style::shade(style::uav_colour(i), 0.85);
            let text: TextStyle = (FONT, s.font(15.0)).into_font().color(&c);
            let (w, h) = root.estimate_text_size(&label, &text)?;
            if let Some(tl) = labels.place(at, (w as i32, h as i32), s) {
                boxed_label(root, tl, (w, h), label, text, s)?;
            }
        }
        Ok(())
    }

    /// Outages: a mark at every step out of contact; one label per outage with its
    /// times, placed where it hides no other label (a leader line when moved away).
    fn draw_outages<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &MapChart<'_, DB>,
        labels: &mut Labels,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let mut outages = Vec::new();
        for i in 0..self.trace.uav_count() {
            let c = style::uav_colour(i);
            for run in self.trace.runs(i) {
                if run.status != Contact::Out {
                    continue;
                }
                for k in run.first..=run.last {
                    let p = self.trace.positions[k][i];
                    let at = chart.backend_coord(&(p.x, p.y));
                    draw_shape(root, at, s.off(4.5), Shape::RingCross, c, s)?;
                }
                outages.push((i, run));
            }
        }
        for (i, run) in outages {
            let c = style::shade(style::uav_colour(i), 0.85);
            let p = self.trace.positions[run.first][i];
            let at = chart.backend_coord(&(p.x, p.y));
            let (t0, t1) = (self.trace.times[run.first], self.trace.times[run.last]);
            let label = if run.first == run.last {
                format!("{} s", format_value(t0))
            } else {
                format!("{}-{} s", format_value(t0), format_value(t1))
            };
            let text: TextStyle = (FONT, s.font(15.0)).into_font().color(&c);
            let (w, h) = root.estimate_text_size(&label, &text)?;
            let Some(tl) = labels.place(at, (w as i32, h as i32), s) else {
                continue;
            };
            let pad = s.off(2.0);
            let rect = [
                (tl.0 - pad, tl.1 - pad),
                (tl.0 + w as i32 + pad, tl.1 + h as i32 + pad),
            ];
            let near = (
                at.0.clamp(rect[0].0, rect[1].0),
                at.1.clamp(rect[0].1, rect[1].1),
            );
            if (near.0 - at.0).abs() + (near.1 - at.1).abs() > s.off(14.0) {
                root.draw(&PathElement::new(
                    vec![at, near],
                    c.mix(0.8).stroke_width(1),
                ))?;
            }
            root.draw(&Rectangle::new(rect, WHITE.mix(0.8).filled()))?;
            root.draw(&Rectangle::new(rect, c.mix(0.6).stroke_width(1)))?;
            root.draw(&Text::new(label, tl, text))?;
        }
        Ok(())
    }

    /// Interference windows: a label above each disk, on a white ground.
    fn label_windows<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &MapChart<'_, DB>,
        labels: &mut Labels,
        s: Scale,
    ) -> DrawResult<(), DB> {
        for (k, win) in self.world.channel().interference().iter().enumerate() {
            let label = format!(
                "W{}: {}-{} s, {} dB",
                k + 1,
                format_value(win.time[0]),
                format_value(win.time[1]),
                format_value(win.loss_db)
            );
            let text: TextStyle = (FONT, s.font(15.0)).into_font().color(&style::INTERFERENCE);
            let (w, h) = root.estimate_text_size(&label, &text)?;
            let top = chart.backend_coord(&(win.center[0], win.center[1] + win.radius));
            if let Some(tl) = labels.place(top, (w as i32, h as i32), s) {
                boxed_label(root, tl, (w, h), label, text, s)?;
            }
        }
        Ok(())
    }
}

/// `label` with its top left at `tl` (`size` its text's pixels), on a white ground.
fn boxed_label<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    tl: (i32, i32),
    (w, h): (u32, u32),
    label: String,
    text: TextStyle,
    s: Scale,
) -> DrawResult<(), DB> {
    let pad = s.off(2.0);
    let rect = [
        (tl.0 - pad, tl.1 - pad),
        (tl.0 + w as i32 + pad, tl.1 + h as i32 + pad),
    ];
    root.draw(&Rectangle::new(rect, WHITE.mix(0.8).filled()))?;
    root.draw(&Text::new(label, tl, text))
}

/// Pixel boxes already taken by labels, and the search for a free place for a new one.
struct Labels {
    /// [x0, y0, x1, y1] the labels must stay in.
    bounds: [i32; 4],
    taken: Vec<[i32; 4]>,
}

impl Labels {
    fn new(bounds: [i32; 4]) -> Self {
        Self {
            bounds,
            taken: Vec::new(),
        }
    }

    fn reserve(&mut self, r: [i32; 4]) {
        self.taken.push(r);
    }

    /// Top-left corner of a free `w` x `h` box near `at` (nearest candidates first), taken.
    fn place(&mut self, at: (i32, i32), (w, h): (i32, i32), s: Scale) -> Option<(i32, i32)> {
        let pad = s.off(3.0);
        for d in [8.0, 20.0, 34.0, 52.0, 75.0, 100.0, 130.0] {
            let d = s.off(d);
            let candidates = [
                (d, -d - h),
                (d, d),
                (-d - w, -d - h),
                (-d - w, d),
                (d, -h / 2),
                (-d - w, -h / 2),
                (-w / 2, -d - h),
                (-w / 2, d),
            ];
            for (dx, dy) in candidates {
                let r = [
                    at.0 + dx - pad,
                    at.1 + dy - pad,
                    at.0 + dx + w + pad,
                    at.1 + dy + h + pad,
                ];
                let inside = r[0] >= self.bounds[0]
                    && r[1] >= self.bounds[1]
                    && r[2] <= self.bounds[2]
                    && r[3] <= self.bounds[3];
                let free = self
                    .taken
                    .iter()
                    .all(|t| r[2] <= t[0] || r[0] >= t[2] || r[3] <= t[1] || r[1] >= t[3]);
                if inside && free {
                    self.taken.push(r);
                    return Some((at.0 + dx, at.1 + dy));
                }
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn margins_make_the_plotting_area_proportional() {
        let [l, r, t, b] = equal_aspect_margins((900, 800), (1045.0, 879.0), (80, 60), 10);
        let pw = 900 - 80 - l - r;
        let ph = 800 - 60 - t - b;
        let ratio = f64::from(pw) / f64::from(ph);
        assert!((ratio - 1045.0 / 879.0).abs() < 0.005, "{pw} x {ph}");
        // A tall map in a wide area: the width shrinks instead.
        let [l, r, _, _] = equal_aspect_margins((900, 800), (100.0, 400.0), (80, 60), 10);
        assert!(l > 100 && r > 100);
    }

    #[test]
    fn the_chart_keeps_the_computed_aspect() {
        let (w, h) = (1000u32, 700u32);
        let mut buf = vec![0u8; (w * h * 3) as usize];
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        let (dx, dy) = (1045.0, 879.0);
        let [ml, mr, mt, mb] = equal_aspect_margins((w, h), (dx, dy), (80, 60), 10);
        let chart = ChartBuilder::on(&root)
            .margin_left(ml)
            .margin_right(mr)
            .margin_top(mt)
            .margin_bottom(mb)
            .y_label_area_size(80)
            .x_label_area_size(60)
            .build_cartesian_2d(Axis::linear(0.0, dx), Axis::linear(0.0, dy))
            .unwrap();
        // One metre is the same number of pixels along both axes.
        let (a, b) = (
            chart.backend_coord(&(0.0, 0.0)),
            chart.backend_coord(&(dx, dy)),
        );
        let sx = f64::from(b.0 - a.0) / dx;
        let sy = f64::from(a.1 - b.1) / dy;
        assert!((sx / sy - 1.0).abs() < 0.005, "sx {sx} sy {sy}");
    }
}
