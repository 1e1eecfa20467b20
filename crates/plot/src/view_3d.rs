//! The plan in 3-D: a coarse shaded terrain mesh, the threat cylinders as wireframes, and
//! each UAV's path at absolute altitude (waypoint z above ground plus the ground height),
//! with its shadow draped on the terrain to make the 3-D position readable. The legend says
//! how long each UAV with a departure delay waits at its start.
//!
//! Threat cylinders are of unbounded height in the model; the spec's z is a drawing height
//! only. Cylinders are drawn solid from the ground up to z above the ground at their axis
//! and dashed above that, up to the top of the chart. Horizontal axes keep the map's
//! proportions; altitude is exaggerated (the legend says by how much) so that relief and
//! climbs are visible. Terrain facets are painted from the farthest to the nearest.

use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use swarmplan_core::plan::Plan;
use swarmplan_core::timing::TimedPlan;
use swarmplan_core::world::World;

use crate::axis::{format_value, Axis};
use crate::legend::{self, Entry, Shape};
use crate::render::{render, DrawResult, Figure, PlotError, Target, Written};
use crate::style::{self, Scale, FONT};
use crate::violation_marks::ViolationMarks;

/// Writes the 3-D view of `plan` in `world` to `out` (PNG and SVG).
pub fn view_3d(
    world: &World,
    plan: &Plan,
    title: &str,
    out: impl Into<Target>,
) -> Result<Written, PlotError> {
    render(&View3d::new(world, plan, title), &out.into())
}

/// Terrain mesh cells along the longer side.
const MESH_CELLS: usize = 36;
/// Vertical extent of the chart box relative to its longer horizontal side.
const HEIGHT_SHARE: f64 = 0.42;

/// A terrain facet: four corners (east, altitude, north).
type Quad = [(f64, f64, f64); 4];

struct View3d<'a> {
    world: &'a World,
    plan: &'a Plan,
    title: &'a str,
    /// The waypoints (markers) and what is flown (lines, shadows).
    timed: TimedPlan,
    flown: TimedPlan,
    marks: ViolationMarks,
    x: (f64, f64),
    y: (f64, f64),
    /// Altitude range of the chart.
    alt: (f64, f64),
}

impl<'a> View3d<'a> {
    fn new(world: &'a World, plan: &'a Plan, title: &'a str) -> Self {
        let m = &world.spec().map;
        let (mut x, mut y) = ((m.x[0], m.x[1]), (m.y[0], m.y[1]));
        let timed = TimedPlan::new(world, plan);
        let flown = TimedPlan::flown(world, plan);
        let t = world.terrain();
        let mut alt = (t.min_height(), t.max_height());
        for p in timed.paths.iter().flat_map(|p| p.abs.iter()) {
            if p.is_finite() {
                x = (x.0.min(p.x), x.1.max(p.x));
                y = (y.0.min(p.y), y.1.max(p.y));
                alt = (alt.0.min(p.z), alt.1.max(p.z));
            }
        }
        for th in &world.spec().threats {
            alt.1 = alt.1.max(t.height(th.x, th.y) + th.z);
        }
        let top = alt.1 + 0.08 * (alt.1 - alt.0).max(1.0);
        Self {
            world,
            plan,
            title,
            timed,
            flown,
            marks: ViolationMarks::new(world, plan),
            x,
            y,
            alt: (alt.0, top),
        }
    }

    fn dims(&self) -> (f64, f64) {
        (self.x.1 - self.x.0, self.y.1 - self.y.0)
    }

    /// Terrain facets: corners (x, altitude, y) and the facet's colour.
    fn facets(&self) -> Vec<(Quad, RGBColor)> {
        let t = self.world.terrain();
        let (dx, dy) = self.dims();
        let cell = dx.max(dy) / MESH_CELLS as f64;
        let nx = ((dx / cell).ceil() as usize).max(1);
        let ny = ((dy / cell).ceil() as usize).max(1);
        let gx = |i: usize| self.x.0 + dx * i as f64 / nx as f64;
        let gy = |j: usize| self.y.0 + dy * j as f64 / ny as f64;
        let span = (t.max_height() - t.min_height()).max(1e-9);
        let light = glam::DVec3::new(-0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2);
        let mut out = Vec::with_capacity(nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (xa, xb, ya, yb) = (gx(i), gx(i + 1), gy(j), gy(j + 1));
                let h = [
                    t.height(xa, ya),
                    t.height(xb, ya),
                    t.height(xb, yb),
                    t.height(xa, yb),
                ];
                let mean = h.iter().sum::<f64>() / 4.0;
                let dzdx = (h[1] + h[2] - h[0] - h[3]) / (2.0 * (xb - xa));
                let dzdy = (h[2] + h[3] - h[0] - h[1]) / (2.0 * (yb - ya));
                let n = glam::DVec3::new(-dzdx, -dzdy, 1.0).normalize();
                let f = (1.0 + 0.8 * (n.dot(light).max(0.0) - light.z)).clamp(0.6, 1.2);
                let c = style::shade(style::terrain_colour((mean - t.min_height()) / span), f);
                out.push((
                    [
                        (xa, h[0], ya),
                        (xb, h[1], ya),
                        (xb, h[2], yb),
                        (xa, h[3], yb),
                    ],
                    c,
                ));
            }
        }
        out
    }

    fn legend_entries(&self, s: Scale, exaggeration: f64) -> Vec<Entry> {
        let n = self.plan.uavs.len();
        let mut e: Vec<Entry> = (0..n)
            .filter_map(|i| {
                let label = style::uav_label(i, n)?;
                Some(Entry::line(label, style::uav_colour(i), s.px(3.0)))
            })
            .collect();
        e.push(Entry::line(
            "path shadow on the ground",
            RGBColor(120, 120, 120),
            s.px(2.0),
        ));
        e.push(Entry::marker("waypoint", Shape::Dot, RGBColor(90, 90, 90)));
        e.push(Entry::line(
            "threat, up to its drawn z",
            style::THREAT_DARK,
            s.px(2.0),
        ));
        e.push(Entry::dashed(
            "threat above z (unbounded)",
            style::THREAT,
            s.px(1.5),
        ));
        for g in self.world.ground_nodes_at(swarmplan_core::world::DEPARTURE) {
            let shape = if g.name == "GCS" {
                Shape::Triangle
            } else {
                Shape::Square
            };
            e.push(Entry::marker(g.name.clone(), shape, BLACK));
        }
        e.extend(self.marks.legend_entries(s));
        e.push(Entry::Note(String::new()));
        // Departure delays: a UAV hovering at its start is one point here, so say it.
        for (i, p) in self.flown.paths.iter().enumerate() {
            if p.depart > 0.0 && p.depart.is_finite() {
                e.push(Entry::Note(format!(
                    "UAV {i} waits {} s at its start",
                    format_value(p.depart)
                )));
            }
        }
        e.push(Entry::Note("x: east, m; y: north, m".into()));
        e.push(Entry::Note("vertical: altitude above datum, m".into()));
        e.push(Entry::Note(format!(
            "vertical exaggeration x{}",
            format_value((exaggeration * 10.0).round() / 10.0)
        )));
        e
    }
}

impl View3d<'_> {
    /// Axis titles beside the box edges plotters labels: the two front edges of the floor
    /// (the ones lowest on screen) and the leftmost vertical edge.
    fn draw_axis_titles<DB: DrawingBackend, C: CoordTranslate<From = (f64, f64, f64)>>(
        &self,
        root: &DrawingArea<DB, Shift>,
        coord: &C,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let (x, y, a) = (self.x, self.y, self.alt);
        let at = |px: f64, py: f64, pa: f64| coord.translate(&(px, pa, py));
        let mid_x = (x.0 + x.1) / 2.0;
        let mid_y = (y.0 + y.1) / 2.0;
        // Front edges: the floor edge of each axis that is lower on screen.
        let ex = [y.0, y.1].map(|yy| at(mid_x, yy, a.0));
        let ex = if ex[0].1 >= ex[1].1 { ex[0] } else { ex[1] };
        let ey = [x.0, x.1].map(|xx| at(xx, mid_y, a.0));
        let ey = if ey[0].1 >= ey[1].1 { ey[0] } else { ey[1] };
        let corners = [(x.0, y.0), (x.0, y.1), (x.1, y.0), (x.1, y.1)];
        let left = corners
            .iter()
            .map(|(cx, cy)| at(*cx, *cy, a.1))
            .min_by_key(|p| p.0)
            .unwrap_or((0, 0));
        let centre = root.dim_in_pixel();
        let (cx, _) = (centre.0 as i32 / 2, centre.1 as i32 / 2);
        let push = s.off(62.0);
        let style = s.axis_desc().pos(Pos::new(HPos::Center, VPos::Center));
        // Move each floor title away from the box, outwards from the figure's middle.
        let away = |p: (i32, i32)| {
            let dx = if p.0 < cx { -push / 2 } else { push / 2 };
            (p.0 + dx, p.1 + push)
        };
        root.draw(&Text::new("x (east), m", away(ex), style.clone()))?;
        root.draw(&Text::new("y (north), m", away(ey), style.clone()))?;
        let up = s.axis_desc().pos(Pos::new(HPos::Left, VPos::Bottom));
        root.draw(&Text::new(
            "altitude, m",
            ((left.0 - s.off(20.0)).max(s.off(6.0)), left.1 - s.off(22.0)),
            up,
        ))?;
        Ok(())
    }
}

/// The 3-D chart: (east, altitude, north) in metres.
type SceneChart<'a, DB> =
    ChartContext<'a, DB, plotters::coord::ranged3d::Cartesian3d<Axis, Axis, Axis>>;

impl Figure for View3d<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let s = Scale::of(root.dim_in_pixel());
        let body = root.titled(self.title, s.title())?;
        let (w, _) = body.dim_in_pixel();
        let side_w = s.px(300.0).min(w / 3);
        let (plot, side) = body.split_horizontally(w - side_w);

        let mut chart = ChartBuilder::on(&plot)
            .margin(s.px(10.0))
            .build_cartesian_3d(
                Axis::linear(self.x.0, self.x.1),
                Axis::linear(self.alt.0, self.alt.1),
                // plotters' (x, y, z) frame is right-handed; (east, up, north) is not, so
                // north runs along reversed z, or the map would be drawn mirrored.
                Axis::linear(self.y.0, self.y.1).reversed(),
            )?;
        let (pw, ph) = plot.dim_in_pixel();
        let (dx, dy) = self.dims();
        let base = f64::from(pw.min(ph)) * 0.78;
        let long = dx.max(dy);
        let size = (
            (base * dx / long).round() as i32,
            (base * HEIGHT_SHARE).round() as i32,
            (base * dy / long).round() as i32,
        );
        chart.set_3d_pixel_range(size);
        chart.with_projection(|mut pb| {
            pb.yaw = 0.6;
            pb.pitch = 0.55;
            pb.scale = 0.95;
            pb.into_matrix()
        });
        let exaggeration =
            (f64::from(size.1) / (self.alt.1 - self.alt.0)) / (f64::from(size.0) / dx);

        chart
            .configure_axes()
            .label_style(s.tick())
            .light_grid_style(BLACK.mix(0.06))
            .bold_grid_style(BLACK.mix(0.15))
            .max_light_lines(1)
            .x_labels(6)
            .y_labels(5)
            .z_labels(6)
            .draw()?;

        self.draw_terrain(&mut chart)?;
        self.draw_shadows(&mut chart, s)?;
        self.draw_threats(&mut chart, s)?;
        self.draw_paths(&mut chart, s)?;
        self.draw_marks(root, &chart, s)?;
        self.draw_axis_titles(root, chart.as_coord_spec(), s)?;
        legend::draw(&side, &self.legend_entries(s, exaggeration), s.off(30.0), s)
    }
}

impl View3d<'_> {
    /// The terrain's facets, farthest first (painter's order).
    fn draw_terrain<DB: DrawingBackend>(
        &self,
        chart: &mut SceneChart<'_, DB>,
    ) -> DrawResult<(), DB> {
        // Painter's order: farthest facets first.
        let mut facets: Vec<(i32, Quad, RGBColor)> = {
            let coord = chart.as_coord_spec();
            self.facets()
                .into_iter()
                .map(|(q, c)| {
                    let cx = (q[0].0 + q[2].0) / 2.0;
                    let cy = (q[0].1 + q[1].1 + q[2].1 + q[3].1) / 4.0;
                    let cz = (q[0].2 + q[2].2) / 2.0;
                    (coord.projected_depth(&cx, &cy, &cz), q, c)
                })
                .collect()
        };
        facets.sort_by_key(|f| std::cmp::Reverse(f.0));
        let edge = BLACK.mix(0.12).stroke_width(1);
        for (_, q, c) in &facets {
            chart.draw_series(std::iter::once(Polygon::new(q.to_vec(), c.filled())))?;
            let mut ring = q.to_vec();
            ring.push(q[0]);
            chart.draw_series(std::iter::once(PathElement::new(ring, edge)))?;
        }
        Ok(())
    }

    /// Each UAV's flown path's shadow, draped on the ground.
    fn draw_shadows<DB: DrawingBackend>(
        &self,
        chart: &mut SceneChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let t = self.world.terrain();
        for (i, p) in self.flown.paths.iter().enumerate() {
            let c = style::uav_colour(i);
            let mut shadow = Vec::new();
            for w in p.abs.windows(2) {
                let n = ((w[1].truncate().distance(w[0].truncate())) / 10.0)
                    .ceil()
                    .max(1.0) as usize;
                for k in 0..=n {
                    let q = w[0].lerp(w[1], k as f64 / n as f64);
                    shadow.push((q.x, t.height(q.x, q.y) + 1.0, q.y));
                }
            }
            chart.draw_series(std::iter::once(PathElement::new(
                shadow,
                style::shade(c, 0.7).mix(0.55).stroke_width(s.px(2.0)),
            )))?;
        }
        Ok(())
    }

    /// Threat cylinders: footprint on the ground, a ring at the drawn height, struts, and
    /// dashes above it (the cylinder goes on).
    fn draw_threats<DB: DrawingBackend>(
        &self,
        chart: &mut SceneChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let t = self.world.terrain();
        let size_of = |i: usize| self.world.spec().uavs.get(i).map_or(1.0, |u| u.size);
        let drone = (0..self.world.uav_count()).map(size_of).fold(0.0, f64::max);
        for th in &self.world.spec().threats {
            let r = th.r + drone;
            let ground = t.height(th.x, th.y);
            let drawn = ground + th.z;
            let ring = style::within_view(style::circle(th.x, th.y, r, 48), self.x, self.y);
            let solid = style::THREAT_DARK.stroke_width(s.px(2.0));
            // The footprint follows the ground; rings at constant altitude above it.
            chart.draw_series(std::iter::once(PathElement::new(
                ring.iter()
                    .map(|(a, b)| (*a, t.height(*a, *b), *b))
                    .collect::<Vec<_>>(),
                solid,
            )))?;
            chart.draw_series(std::iter::once(PathElement::new(
                ring.iter()
                    .map(|(a, b)| (*a, drawn, *b))
                    .collect::<Vec<_>>(),
                solid,
            )))?;
            for (a, b) in ring.iter().step_by(6) {
                let g = t.height(*a, *b);
                chart.draw_series(std::iter::once(PathElement::new(
                    vec![(*a, g, *b), (*a, drawn.max(g), *b)],
                    style::THREAT_DARK.mix(0.7).stroke_width(s.px(1.5)),
                )))?;
                // Above the drawn height: dashed, the cylinder goes on.
                let (lo, hi) = (drawn.max(g), self.alt.1);
                let n = 8;
                for k in 0..n {
                    let z0 = lo + (hi - lo) * (2 * k) as f64 / (2 * n) as f64;
                    let z1 = lo + (hi - lo) * (2 * k + 1) as f64 / (2 * n) as f64;
                    chart.draw_series(std::iter::once(PathElement::new(
                        vec![(*a, z0, *b), (*a, z1, *b)],
                        style::THREAT.mix(0.45).stroke_width(1),
                    )))?;
                }
            }
        }
        Ok(())
    }

    /// Violating segments' halos, then each UAV's flown path and its waypoints.
    fn draw_paths<DB: DrawingBackend>(
        &self,
        chart: &mut SceneChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        for seg in &self.marks.segments {
            let ends: Vec<(f64, f64, f64)> = seg.ends.iter().map(|q| (q.x, q.z, q.y)).collect();
            chart.draw_series(std::iter::once(PathElement::new(
                ends.clone(),
                style::VIOLATION_TEXT.stroke_width(s.px(12.0)),
            )))?;
            chart.draw_series(std::iter::once(PathElement::new(
                ends,
                style::VIOLATION.stroke_width(s.px(8.0)),
            )))?;
        }

        for (i, (p, f)) in self.timed.paths.iter().zip(&self.flown.paths).enumerate() {
            let c = style::uav_colour(i);
            let line: Vec<(f64, f64, f64)> = f.abs.iter().map(|q| (q.x, q.z, q.y)).collect();
            chart.draw_series(std::iter::once(PathElement::new(
                line,
                c.stroke_width(s.px(3.0)),
            )))?;
            chart.draw_series(
                p.abs
                    .iter()
                    .map(|q| Circle::new((q.x, q.z, q.y), s.px(4.0), c.filled())),
            )?;
        }
        Ok(())
    }

    /// Ground nodes with their names, and a diamond with its kind at every violation that
    /// has a place.
    fn draw_marks<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        chart: &SceneChart<'_, DB>,
        s: Scale,
    ) -> DrawResult<(), DB> {
        let text = (FONT, s.font(17.0))
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Bottom));
        for g in self.world.ground_nodes_at(swarmplan_core::world::DEPARTURE) {
            let p = (g.position.x, g.position.z, g.position.y);
            let at = chart.as_coord_spec().translate(&p);
            let shape = if g.name == "GCS" {
                Shape::Triangle
            } else {
                Shape::Square
            };
            legend::draw_shape(root, at, s.off(8.0), shape, BLACK, s)?;
            root.draw(&Text::new(
                g.name.clone(),
                (at.0 + s.off(10.0), at.1 - s.off(6.0)),
                text.clone(),
            ))?;
        }

        let label = (FONT, s.font(15.0))
            .into_font()
            .color(&style::VIOLATION_TEXT)
            .pos(Pos::new(HPos::Left, VPos::Bottom));
        for place in &self.marks.places {
            let at = chart
                .as_coord_spec()
                .translate(&(place.at.x, place.at.z, place.at.y));
            legend::draw_shape(root, at, s.off(7.0), Shape::Diamond, style::VIOLATION, s)?;
            root.draw(&Text::new(
                place.label.clone(),
                (at.0 + s.off(9.0), at.1 - s.off(5.0)),
                label.clone(),
            ))?;
        }
        Ok(())
    }
}
