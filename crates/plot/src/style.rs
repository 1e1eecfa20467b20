//! The look shared by every figure: the font, sizes that scale with the figure, colours
//! (UAVs, algorithms, contact states, terrain colour map) and small geometry helpers
//! (circles and dashes in data units).
//!
//! Sizes are given for the default 1200 x 900 px figure and scaled with the figure's
//! smaller relative side, so a smaller PNG keeps the same proportions.

use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::FontStyle;

/// The family every text uses. plotters' `ab_glyph` engine looks fonts up by this name,
/// and the SVG files name it too.
pub(crate) const FONT: &str = "sans-serif";

/// Registers DejaVu Sans (regular and bold) under [`FONT`], once per process.
pub(crate) fn register_font() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        let fonts: [(FontStyle, &'static [u8]); 2] = [
            (FontStyle::Normal, dejavu::sans::regular()),
            (FontStyle::Bold, dejavu::sans::bold()),
        ];
        for (style, bytes) in fonts {
            plotters::style::register_font(FONT, style, bytes).map_err(|_| {
                format!(
                    "the embedded DejaVu Sans ({}) is not a readable font",
                    style.as_str()
                )
            })?;
        }
        Ok(())
    })
    .clone()
}

/// Scales sizes given for a 1200 x 900 px figure to the actual one.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Scale(f64);

impl Scale {
    pub(crate) fn of(size: (u32, u32)) -> Self {
        Self((f64::from(size.0) / 1200.0).min(f64::from(size.1) / 900.0))
    }

    /// A length in pixels (at least 1).
    pub(crate) fn px(self, v: f64) -> u32 {
        (v * self.0).round().max(1.0) as u32
    }

    /// A signed pixel offset.
    pub(crate) fn off(self, v: f64) -> i32 {
        (v * self.0).round() as i32
    }

    /// A font size in pixels (at least 9, so that small figures stay legible).
    pub(crate) fn font(self, v: f64) -> f64 {
        (v * self.0).max(9.0)
    }

    pub(crate) fn title(self) -> TextStyle<'static> {
        (FONT, self.font(28.0)).into_font().into()
    }
    pub(crate) fn subtitle(self) -> TextStyle<'static> {
        (FONT, self.font(21.0)).into_font().into()
    }
    pub(crate) fn axis_desc(self) -> TextStyle<'static> {
        (FONT, self.font(19.0)).into_font().into()
    }
    pub(crate) fn tick(self) -> TextStyle<'static> {
        (FONT, self.font(16.0)).into_font().into()
    }
    pub(crate) fn legend(self) -> TextStyle<'static> {
        (FONT, self.font(16.0)).into_font().into()
    }
    pub(crate) fn heading(self) -> TextStyle<'static> {
        (FONT, self.font(17.0), FontStyle::Bold).into_font().into()
    }
    pub(crate) fn note(self) -> TextStyle<'static> {
        (FONT, self.font(14.0)).into_font().into()
    }
}

/// Strong, mutually distinct colours for UAV paths, chosen to stand out on the light
/// terrain colours and to differ from the threat red.
const UAV_COLOURS: [RGBColor; 8] = [
    RGBColor(0, 82, 204),
    RGBColor(230, 110, 0),
    RGBColor(150, 40, 190),
    RGBColor(0, 150, 160),
    RGBColor(215, 25, 140),
    RGBColor(30, 30, 30),
    RGBColor(120, 95, 0),
    RGBColor(20, 160, 60),
];

/// Colour of UAV `i` (0-based).
pub(crate) fn uav_colour(i: usize) -> RGBColor {
    UAV_COLOURS[i % UAV_COLOURS.len()]
}

/// A legend names each UAV up to this many; a larger fleet gets one row per colour.
pub(crate) const UAV_LEGEND_ROWS: usize = 2 * UAV_COLOURS.len();

/// The legend label of UAV `i` in a fleet of `n`: "UAV i" while each UAV fits a row of its
/// own; above [`UAV_LEGEND_ROWS`] the first UAV of each colour speaks for every UAV of that
/// colour ("UAVs 2, 10, ..., 98") and the others get none, so a 100-UAV legend stays 8 rows
/// instead of running off the figure.
pub(crate) fn uav_label(i: usize, n: usize) -> Option<String> {
    let k = UAV_COLOURS.len();
    if n <= UAV_LEGEND_ROWS {
        Some(format!("UAV {i}"))
    } else if i < k {
        let same: Vec<usize> = (i..n).step_by(k).collect();
        let names: Vec<String> = if same.len() <= 3 {
            same.iter().map(usize::to_string).collect()
        } else {
            vec![
                i.to_string(),
                (i + k).to_string(),
                "...".into(),
                same[same.len() - 1].to_string(),
            ]
        };
        Some(format!("UAVs {}", names.join(", ")))
    } else {
        None
    }
}

/// Colour of UAV `i` as CSS hex (`#rrggbb`), for pages that show the same fleet.
#[must_use]
pub fn uav_colour_hex(i: usize) -> String {
    let RGBColor(r, g, b) = uav_colour(i);
    format!("#{r:02x}{g:02x}{b:02x}")
}

/// Colour of the `i`-th series of a comparison (algorithms): the ten "tab10" colours, so
/// every preset of a full bench has its own.
pub(crate) fn series_colour(i: usize) -> RGBColor {
    const C: [RGBColor; 10] = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(90, 90, 90),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    C[i % C.len()]
}

pub(crate) const THREAT: RGBColor = RGBColor(200, 0, 0);
pub(crate) const THREAT_DARK: RGBColor = RGBColor(140, 0, 0);
pub(crate) const INTERFERENCE: RGBColor = RGBColor(120, 60, 200);
/// A UAV waiting at its start before departing (communication timeline).
pub(crate) const WAITING: RGBColor = RGBColor(110, 110, 110);
/// Stripes of the places without a direct ground link (top view).
pub(crate) const DEAD_HATCH: RGBColor = RGBColor(70, 70, 80);
pub(crate) const DIRECT: RGBColor = RGBColor(60, 170, 80);
pub(crate) const RELAYED: RGBColor = RGBColor(240, 180, 30);
pub(crate) const OUT: RGBColor = RGBColor(215, 40, 40);
/// Violated constraints: signal yellow outlined in near black, unlike any UAV, threat or
/// terrain colour.
pub(crate) const VIOLATION: RGBColor = RGBColor(255, 214, 0);
pub(crate) const VIOLATION_TEXT: RGBColor = RGBColor(40, 30, 0);
pub(crate) const GRID: RGBColor = RGBColor(200, 200, 200);

/// The terrain colour map at `t` in [0, 1] (low to high): muted green, sand, light brown,
/// near white. Light on purpose, so paths and threats drawn over it stay visible.
pub(crate) fn terrain_colour(t: f64) -> RGBColor {
    const STOPS: [(f64, [f64; 3]); 5] = [
        (0.0, [118.0, 166.0, 112.0]),
        (0.25, [172.0, 200.0, 132.0]),
        (0.5, [224.0, 214.0, 154.0]),
        (0.75, [196.0, 164.0, 118.0]),
        (1.0, [246.0, 242.0, 236.0]),
    ];
    let t = if t.is_finite() {
        t.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let k = STOPS
        .windows(2)
        .position(|w| t <= w[1].0)
        .unwrap_or(STOPS.len() - 2);
    let (t0, a) = STOPS[k];
    let (t1, b) = STOPS[k + 1];
    let f = (t - t0) / (t1 - t0);
    let c = |i: usize| (a[i] + (b[i] - a[i]) * f).round() as u8;
    RGBColor(c(0), c(1), c(2))
}

/// `c` with each channel multiplied by `f` (shading), clamped.
pub(crate) fn shade(c: RGBColor, f: f64) -> RGBColor {
    let s = |v: u8| (f64::from(v) * f).round().clamp(0.0, 255.0) as u8;
    RGBColor(s(c.0), s(c.1), s(c.2))
}

/// `n` points on the circle of radius `r` around (cx, cy), closed (first point repeated).
pub(crate) fn circle(cx: f64, cy: f64, r: f64, n: usize) -> Vec<(f64, f64)> {
    (0..=n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            (cx + r * a.cos(), cy + r * a.sin())
        })
        .collect()
}

/// `pts` with every point moved into the view `x` by `y` widened by its larger side on
/// each edge. A threat or an interference disk far larger than the map (a radius of 1e8 m
/// is a valid scenario) would otherwise reach the drawing backend as a polygon millions of
/// pixels high, whose fill allocates per pixel row (gigabytes), and as outlines cut into
/// millions of dashes. The part inside the view keeps its shape as far as the circle's
/// vertices resolve it; the rest is off the figure.
pub(crate) fn within_view(pts: Vec<(f64, f64)>, x: (f64, f64), y: (f64, f64)) -> Vec<(f64, f64)> {
    let span = (x.1 - x.0).max(y.1 - y.0).max(0.0);
    let (xl, xh, yl, yh) = (x.0 - span, x.1 + span, y.0 - span, y.1 + span);
    pts.into_iter()
        .map(|(a, b)| (a.clamp(xl, xh), b.clamp(yl, yh)))
        .collect()
}

/// At most this many dashes in one dashed line: longer ones get proportionally longer
/// dashes and gaps.
const MAX_DASHES: f64 = 4096.0;

/// Cuts the polyline `pts` into dashes `dash` long with gaps `gap` (same units as the
/// points), for dashed outlines in data units; no dashes for a line of no finite length.
pub(crate) fn dashes(pts: &[(f64, f64)], dash: f64, gap: f64) -> Vec<Vec<(f64, f64)>> {
    let mut out = Vec::new();
    if pts.len() < 2 || dash <= 0.0 || gap < 0.0 {
        return out;
    }
    let total: f64 = pts
        .windows(2)
        .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
        .sum();
    if !total.is_finite() {
        return out;
    }
    let stretch = (total / (dash + gap) / MAX_DASHES).max(1.0);
    let (dash, gap) = (dash * stretch, gap * stretch);
    let period = dash + gap;
    let mut cur: Vec<(f64, f64)> = vec![pts[0]];
    // Position within the current period at the start of each segment.
    let mut phase = 0.0;
    for w in pts.windows(2) {
        let (a, b) = (w[0], w[1]);
        let len = (b.0 - a.0).hypot(b.1 - a.1);
        let at = |s: f64| {
            let f = if len > 0.0 { s / len } else { 0.0 };
            (a.0 + (b.0 - a.0) * f, a.1 + (b.1 - a.1) * f)
        };
        let mut s = 0.0;
        while s < len {
            let drawing = phase < dash;
            let left = if drawing {
                dash - phase
            } else {
                period - phase
            };
            let step = left.min(len - s);
            s += step;
            phase += step;
            if drawing {
                cur.push(at(s));
                if phase >= dash {
                    out.push(std::mem::take(&mut cur));
                }
            } else if phase >= period {
                phase = 0.0;
                cur = vec![at(s)];
            }
        }
    }
    if cur.len() >= 2 && phase < dash {
        out.push(cur);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_map_ends_and_clamps() {
        assert_eq!(terrain_colour(0.0), RGBColor(118, 166, 112));
        assert_eq!(terrain_colour(1.0), RGBColor(246, 242, 236));
        assert_eq!(terrain_colour(-3.0), terrain_colour(0.0));
        assert_eq!(terrain_colour(f64::NAN), terrain_colour(0.0));
    }

    #[test]
    fn dashes_cover_the_dash_share_of_a_line() {
        let d = dashes(&[(0.0, 0.0), (10.0, 0.0), (10.0, 10.0)], 2.0, 1.0);
        let drawn: f64 = d
            .iter()
            .map(|p| {
                p.windows(2)
                    .map(|w| (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1))
                    .sum::<f64>()
            })
            .sum();
        // 20 units: six full periods (12 drawn) and a last dash of 2.
        assert!((drawn - 14.0).abs() < 1e-9, "drawn {drawn}");
        assert_eq!(d.len(), 7);
    }

    #[test]
    fn a_huge_circle_is_drawn_within_the_view_in_a_bounded_number_of_dashes() {
        let ring = within_view(circle(0.0, 0.0, 1e12, 96), (0.0, 1000.0), (0.0, 500.0));
        assert!(ring
            .iter()
            .all(|&(a, b)| (-1000.0..=2000.0).contains(&a) && (-1000.0..=1500.0).contains(&b)));
        let d = dashes(&ring, 1000.0 / 120.0, 1000.0 / 200.0);
        assert!(
            !d.is_empty() && d.len() as f64 <= MAX_DASHES + 1.0,
            "{}",
            d.len()
        );
        // A line of no finite length gets no dashes rather than an endless loop.
        assert!(dashes(&[(0.0, 0.0), (f64::INFINITY, 0.0)], 1.0, 1.0).is_empty());
        let long = dashes(&[(0.0, 0.0), (1e9, 0.0)], 1.0, 1.0);
        assert!(long.len() as f64 <= MAX_DASHES + 1.0, "{}", long.len());
    }

    #[test]
    fn scale_keeps_fonts_legible() {
        let s = Scale::of((400, 300));
        assert!(s.font(16.0) >= 9.0);
        assert_eq!(Scale::of((1200, 900)).px(10.0), 10);
    }

    #[test]
    fn a_large_fleet_gets_one_legend_row_per_colour() {
        assert_eq!(uav_label(15, UAV_LEGEND_ROWS).as_deref(), Some("UAV 15"));
        let labels: Vec<String> = (0..100).filter_map(|i| uav_label(i, 100)).collect();
        assert_eq!(labels.len(), 8);
        assert_eq!(labels[0], "UAVs 0, 8, ..., 96");
        assert_eq!(labels[7], "UAVs 7, 15, ..., 95");
        // A colour with two or three UAVs names them all.
        assert_eq!(uav_label(1, 17).as_deref(), Some("UAVs 1, 9"));
        assert_eq!(uav_label(0, 17).as_deref(), Some("UAVs 0, 8, 16"));
        assert_eq!(uav_label(8, 17), None);
    }
}
