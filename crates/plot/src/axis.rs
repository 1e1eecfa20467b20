//! One value axis type for every 2-D chart: linear, base-10 logarithmic, or linear with
//! ticks at given values (categories). Costs of penalised plans span several decades, so
//! cost axes switch to log scale when the data ask for it; making that a value of one type
//! (instead of plotters' separate linear and log coordinate types) keeps each chart's code
//! single.
//!
//! Ticks: linear axes at 1-2-5 steps; log axes at 1-2-5 x 10^k when that gives at least
//! three ticks, else at linear steps (a narrow log axis still gets labels).

use std::ops::Range;

use plotters::coord::ranged1d::{
    KeyPointHint, KeyPointWeight, NoDefaultFormatting, Ranged, ValueFormatter,
};
use plotters::prelude::*;

use crate::render::DrawResult;
use crate::style::{Scale, GRID};

/// Draws the grid, ticks and axis descriptions of a 2-D chart in the house style.
pub(crate) fn draw_mesh<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<Axis, Axis>>,
    s: Scale,
    x_desc: &str,
    y_desc: &str,
) -> DrawResult<(), DB> {
    let x = chart.as_coord_spec().x_spec().clone();
    let y = chart.as_coord_spec().y_spec().clone();
    let fx = |v: &f64| x.label(*v);
    let fy = |v: &f64| y.label(*v);
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.3))
        .bold_line_style(GRID.mix(0.9))
        .label_style(s.tick())
        .axis_desc_style(s.axis_desc())
        .x_labels(10)
        .y_labels(10)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .draw()
}

/// A 2-D line chart on `area` in the house layout (margins, label areas) with axes `x`, `y`;
/// the caller draws the mesh and series.
pub(crate) fn line_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, plotters::coord::Shift>,
    s: Scale,
    x: Axis,
    y: Axis,
) -> DrawResult<ChartContext<'a, DB, Cartesian2d<Axis, Axis>>, DB> {
    ChartBuilder::on(area)
        .margin(s.px(20.0))
        .margin_right(s.px(40.0))
        .x_label_area_size(s.px(65.0))
        .y_label_area_size(s.px(100.0))
        .build_cartesian_2d(x, y)
}

/// Draws the series key (legend box) of `chart` at `position`, in the house style.
pub(crate) fn draw_series_key<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<Axis, Axis>>,
    s: Scale,
    position: SeriesLabelPosition,
) -> DrawResult<(), DB> {
    chart
        .configure_series_labels()
        .position(position)
        .margin(s.px(15.0))
        .label_font(s.legend())
        .background_style(WHITE.mix(0.9))
        .border_style(BLACK.mix(0.5))
        .draw()
}

#[derive(Debug, Clone, PartialEq)]
enum Kind {
    Linear,
    Log10,
    /// Linear, ticks exactly at these values.
    Fixed(Vec<f64>),
}

/// A value axis from `lo` to `hi`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Axis {
    lo: f64,
    hi: f64,
    kind: Kind,
    /// Drawn from `hi` to `lo` (the 3-D view needs a reversed north axis to stay
    /// right-handed).
    reversed: bool,
}

impl Axis {
    /// Linear from `lo` to `hi` (widened when empty).
    pub(crate) fn linear(lo: f64, hi: f64) -> Self {
        let (lo, hi) = widen(lo, hi);
        Self {
            lo,
            hi,
            kind: Kind::Linear,
            reversed: false,
        }
    }

    /// Linear from `lo` to `hi` with ticks at `ticks` only.
    pub(crate) fn fixed(lo: f64, hi: f64, ticks: Vec<f64>) -> Self {
        let (lo, hi) = widen(lo, hi);
        Self {
            lo,
            hi,
            kind: Kind::Fixed(ticks),
            reversed: false,
        }
    }

    /// An axis for `values` (non-finite ones ignored) with a margin of `pad` (share of the
    /// range, or of the decades on a log axis). Log scale when every value is positive and
    /// the largest is more than `log_ratio` times the smallest. `zero` forces a linear axis
    /// to include 0.
    pub(crate) fn auto(values: impl IntoIterator<Item = f64>, pad: f64, zero: bool) -> Self {
        const LOG_RATIO: f64 = 8.0;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values.into_iter().filter(|v| v.is_finite()) {
            lo = lo.min(v);
            hi = hi.max(v);
        }
        if !lo.is_finite() {
            return Self::linear(0.0, 1.0);
        }
        if lo > 0.0 && hi / lo > LOG_RATIO {
            let (a, b) = (lo.log10(), hi.log10());
            let m = (b - a) * pad;
            return Self {
                lo: 10f64.powf(a - m),
                hi: 10f64.powf(b + m),
                kind: Kind::Log10,
                reversed: false,
            };
        }
        if zero {
            lo = lo.min(0.0);
            hi = hi.max(0.0);
        }
        let m = (hi - lo) * pad;
        let lo2 = if zero && lo >= 0.0 { lo } else { lo - m };
        Self::linear(lo2, hi + m)
    }

    /// The same axis drawn from high to low.
    pub(crate) fn reversed(mut self) -> Self {
        self.reversed = !self.reversed;
        self
    }

    /// A tick label: scientific notation for every label of an axis reaching 1e5, so
    /// that one axis never mixes `50000` and `1e5`.
    pub(crate) fn label(&self, v: f64) -> String {
        if self.lo.abs().max(self.hi.abs()) >= 1e5 && v != 0.0 && v.is_finite() {
            scientific(v)
        } else {
            format_value(v)
        }
    }

    pub(crate) fn is_log(&self) -> bool {
        self.kind == Kind::Log10
    }

    #[cfg(test)]
    pub(crate) fn lo(&self) -> f64 {
        self.lo
    }

    pub(crate) fn hi(&self) -> f64 {
        self.hi
    }

    /// `v` clamped into the axis (non-finite values go to the nearer end: +inf to the top).
    pub(crate) fn clamp(&self, v: f64) -> f64 {
        if v.is_nan() {
            self.lo
        } else {
            v.clamp(self.lo, self.hi)
        }
    }

    /// Position of `v` in [0, 1] along the axis.
    fn fraction(&self, v: f64) -> f64 {
        let f = self.fraction_up(v);
        if self.reversed {
            1.0 - f
        } else {
            f
        }
    }

    fn fraction_up(&self, v: f64) -> f64 {
        match self.kind {
            Kind::Log10 => {
                let v = if v > 0.0 { v } else { self.lo };
                (v.log10() - self.lo.log10()) / (self.hi.log10() - self.lo.log10())
            }
            _ => (v - self.lo) / (self.hi - self.lo),
        }
    }

    /// Ticks: at most `max`; `light` ones subdivide the step of at most `bold` bold ones.
    fn ticks(&self, max: usize, bold: usize, light: bool) -> Vec<f64> {
        if max == 0 {
            return Vec::new();
        }
        match &self.kind {
            Kind::Fixed(t) => {
                if light {
                    Vec::new()
                } else {
                    t.clone()
                }
            }
            Kind::Linear if light => match nice_step(self.lo, self.hi, bold) {
                Some(step) => {
                    let digit = (step / 10f64.powf(step.log10().floor())).round();
                    let sub = step / if digit == 2.0 { 4.0 } else { 5.0 };
                    let t = multiples(self.lo, self.hi, sub, max);
                    if t.len() <= max {
                        t
                    } else {
                        Vec::new()
                    }
                }
                None => Vec::new(),
            },
            Kind::Linear => linear_ticks(self.lo, self.hi, max),
            Kind::Log10 => log_ticks(self.lo, self.hi, max, light),
        }
    }
}

fn widen(lo: f64, hi: f64) -> (f64, f64) {
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    if hi > lo {
        (lo, hi)
    } else {
        let m = if lo == 0.0 { 1.0 } else { lo.abs() * 0.05 };
        (lo - m, lo + m)
    }
}

/// The 1-2-5 step that puts at most `max` ticks in [lo, hi].
fn nice_step(lo: f64, hi: f64, max: usize) -> Option<f64> {
    if max == 0 || hi.partial_cmp(&lo) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let raw = (hi - lo) / max as f64;
    let mag = 10f64.powf(raw.log10().floor());
    Some(
        [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * mag)
            .find(|s| *s >= raw)
            .unwrap_or(10.0 * mag),
    )
}

/// Multiples of `step` within [lo, hi] (at most `max` + 1, to tell "too many").
fn multiples(lo: f64, hi: f64, step: f64, max: usize) -> Vec<f64> {
    let first = (lo / step - 1e-9).ceil();
    let last = (hi / step + 1e-9).floor();
    let mut out = Vec::new();
    let mut k = first;
    while k <= last && out.len() <= max {
        // Snap tiny rounding residue so labels print as 0.3, not 0.30000000000000004.
        let v = k * step;
        out.push(if v.abs() < step * 1e-9 { 0.0 } else { v });
        k += 1.0;
    }
    out
}

/// Ticks at multiples of the 1-2-5 step of at most `max` intervals within [lo, hi] (so
/// up to `max` + 1 ticks when both ends fall on the step).
pub(crate) fn linear_ticks(lo: f64, hi: f64, max: usize) -> Vec<f64> {
    nice_step(lo, hi, max).map_or_else(Vec::new, |step| multiples(lo, hi, step, max))
}

fn log_ticks(lo: f64, hi: f64, max: usize, light: bool) -> Vec<f64> {
    let (a, b) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    let within = |v: &f64| *v >= lo * (1.0 - 1e-12) && *v <= hi * (1.0 + 1e-12);
    let decades = |mults: &[f64], every: i32| -> Vec<f64> {
        (a..=b)
            .filter(|e| (e - a) % every == 0)
            .flat_map(|e| mults.iter().map(move |m| m * 10f64.powi(e)))
            .filter(within)
            .collect()
    };
    if light {
        let t = decades(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 1);
        return if t.len() <= max { t } else { Vec::new() };
    }
    for mults in [&[1.0, 2.0, 5.0][..], &[1.0][..]] {
        let t = decades(mults, 1);
        if t.len() >= 3 && t.len() <= max {
            return t;
        }
        if t.len() < 3 {
            // Too narrow for decade ticks: linear steps label it better.
            return linear_ticks(lo, hi, max.min(6));
        }
    }
    let every = ((b - a) as usize).div_ceil(max.max(1)).max(1) as i32;
    decades(&[1.0], every)
}

/// A compact label: integers as such up to 99 999, then 1.5e6 style; small values with
/// up to three significant digits.
pub(crate) fn format_value(v: f64) -> String {
    if !v.is_finite() {
        return if v > 0.0 { "inf".into() } else { "-inf".into() };
    }
    let a = v.abs();
    if a == 0.0 {
        return "0".into();
    }
    if !(1e-2..1e5).contains(&a) {
        return scientific(v);
    }
    if (v - v.round()).abs() < 1e-9 * a.max(1.0) {
        return format!("{}", v.round() as i64);
    }
    let decimals = (2 - a.log10().floor() as i32).clamp(0, 4) as usize;
    trim(format!("{v:.decimals$}"))
}

/// `v` as `2.5e6`.
fn scientific(v: f64) -> String {
    let mut e = v.abs().log10().floor() as i32;
    let mut m = ((v / 10f64.powi(e)) * 100.0).round() / 100.0;
    if m.abs() >= 10.0 {
        m /= 10.0;
        e += 1;
    }
    format!("{}e{e}", trim(format!("{m:.2}")))
}

fn trim(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

impl Ranged for Axis {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let f = self.fraction(*value);
        let f = if f.is_finite() {
            f.clamp(-1.0, 2.0)
        } else {
            0.0
        };
        (f64::from(limit.0) + f * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        let light = matches!(hint.weight(), KeyPointWeight::Any);
        self.ticks(hint.max_num_points(), hint.bold_points(), light)
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for Axis {
    fn format(value: &f64) -> String {
        format_value(*value)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_round() {
        assert_eq!(
            linear_ticks(0.0, 10.0, 5),
            vec![0.0, 2.0, 4.0, 6.0, 8.0, 10.0]
        );
        assert_eq!(linear_ticks(0.0, 1000.0, 10)[1], 100.0);
        assert!(linear_ticks(1.0, 1.0, 5).is_empty());
    }

    #[test]
    fn auto_switches_to_log_for_wide_ranges() {
        let a = Axis::auto([5000.0, 2.0e6], 0.05, false);
        assert!(a.is_log());
        assert!(a.lo() < 5000.0 && a.hi() > 2.0e6);
        let b = Axis::auto([5000.0, 7000.0], 0.05, false);
        assert!(!b.is_log());
        let c = Axis::auto([f64::INFINITY], 0.05, false);
        assert_eq!((c.lo(), c.hi()), (0.0, 1.0));
    }

    #[test]
    fn log_axis_maps_decades_evenly_and_has_ticks() {
        let a = Axis::auto([10.0, 1.0e4], 0.0, false);
        assert_eq!(a.map(&10.0, (0, 300)), 0);
        assert_eq!(a.map(&100.0, (0, 300)), 100);
        assert_eq!(a.map(&1.0e4, (0, 300)), 300);
        let t = a.ticks(10, 10, false);
        assert!(t.contains(&100.0) && t.contains(&1000.0), "{t:?}");
        // Narrow log axis: linear steps, not nothing.
        let n = Axis {
            lo: 4000.0,
            hi: 9000.0,
            kind: Kind::Log10,
            reversed: false,
        };
        assert!(n.ticks(10, 10, false).len() >= 3);
    }

    #[test]
    fn light_ticks_subdivide_bold_ones() {
        let a = Axis::linear(0.0, 100.0);
        assert_eq!(a.ticks(10, 10, false).len(), 11);
        let light = a.ticks(100, 10, true);
        assert_eq!(light.len(), 51, "{light:?}");
        assert!(light.contains(&2.0) && light.contains(&98.0));
    }

    #[test]
    fn reversed_axes_map_high_to_the_start() {
        let a = Axis::linear(0.0, 10.0).reversed();
        assert_eq!(a.map(&10.0, (0, 100)), 0);
        assert_eq!(a.map(&0.0, (0, 100)), 100);
    }

    #[test]
    fn one_axis_one_notation() {
        let a = Axis::linear(0.0, 2.0e5);
        assert_eq!(a.label(50_000.0), "5e4");
        assert_eq!(a.label(0.0), "0");
        assert_eq!(Axis::linear(0.0, 900.0).label(500.0), "500");
        assert_eq!(format_value(9.999e6), "1e7");
    }

    #[test]
    fn labels_are_compact() {
        assert_eq!(format_value(5000.0), "5000");
        assert_eq!(format_value(2.5e6), "2.5e6");
        assert_eq!(format_value(0.25), "0.25");
        assert_eq!(format_value(12.5), "12.5");
        assert_eq!(format_value(0.0), "0");
        assert_eq!(format_value(1.0e5), "1e5");
    }
}
