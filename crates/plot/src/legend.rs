//! A legend drawn in its own panel beside a chart, so it never hides data (plotters'
//! built-in legend sits inside the plotting area). Entries are a line, a marker or a filled
//! patch with a label; a heading and free notes may be mixed in.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::render::DrawResult;
use crate::style::Scale;

/// Marker shapes of the legend (drawn the same way in the charts).
#[derive(Debug, Clone, Copy)]
pub(crate) enum Shape {
    Dot,
    Triangle,
    Square,
    /// A circle outline with a cross inside (out-of-contact mark).
    RingCross,
    /// A filled diamond with a dark outline (a violated constraint).
    Diamond,
}

/// One row of a legend.
#[derive(Debug, Clone)]
pub(crate) enum Entry {
    /// A line, optionally dashed.
    Line {
        label: String,
        colour: RGBColor,
        width: u32,
        dashed: bool,
    },
    Marker {
        label: String,
        shape: Shape,
        colour: RGBColor,
    },
    /// A filled swatch with an outline.
    Patch {
        label: String,
        fill: RGBAColor,
        outline: RGBColor,
    },
    /// A bold heading.
    Heading(String),
    /// Plain text.
    Note(String),
}

impl Entry {
    pub(crate) fn line(label: impl Into<String>, colour: RGBColor, width: u32) -> Self {
        Self::Line {
            label: label.into(),
            colour,
            width,
            dashed: false,
        }
    }
    pub(crate) fn dashed(label: impl Into<String>, colour: RGBColor, width: u32) -> Self {
        Self::Line {
            label: label.into(),
            colour,
            width,
            dashed: true,
        }
    }
    pub(crate) fn marker(label: impl Into<String>, shape: Shape, colour: RGBColor) -> Self {
        Self::Marker {
            label: label.into(),
            shape,
            colour,
        }
    }
    pub(crate) fn patch(label: impl Into<String>, fill: RGBAColor, outline: RGBColor) -> Self {
        Self::Patch {
            label: label.into(),
            fill,
            outline,
        }
    }
}

/// Draws `shape` centred at pixel `c` with half-size `r`.
pub(crate) fn draw_shape<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    c: (i32, i32),
    r: i32,
    shape: Shape,
    colour: RGBColor,
    s: Scale,
) -> DrawResult<(), DB> {
    let w = s.px(2.5);
    match shape {
        Shape::Dot => area.draw(&Circle::new(c, r, colour.filled())),
        Shape::Triangle => area.draw(&TriangleMarker::new(c, r + 2, colour.filled())),
        Shape::Square => area.draw(&Rectangle::new(
            [(c.0 - r, c.1 - r), (c.0 + r, c.1 + r)],
            colour.filled(),
        )),
        Shape::RingCross => {
            area.draw(&Circle::new(c, r + 2, crate::style::OUT.stroke_width(w)))?;
            area.draw(&Cross::new(c, r - 1, colour.stroke_width(w)))
        }
        Shape::Diamond => {
            let pts = vec![
                (c.0, c.1 - r),
                (c.0 + r, c.1),
                (c.0, c.1 + r),
                (c.0 - r, c.1),
            ];
            area.draw(&Polygon::new(pts.clone(), colour.filled()))?;
            let mut ring = pts;
            ring.push((c.0, c.1 - r));
            area.draw(&PathElement::new(
                ring,
                crate::style::VIOLATION_TEXT.stroke_width(s.px(1.5)),
            ))
        }
    }
}

/// Draws `entries` top-down in `area`, starting `top` pixels from its top.
pub(crate) fn draw<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[Entry],
    top: i32,
    s: Scale,
) -> DrawResult<(), DB> {
    // Rows shrink (down to 18 px at full size) when many entries share the panel.
    let avail = area.dim_in_pixel().1 as i32 - top;
    let row = (avail / entries.len().max(1) as i32).clamp(s.off(18.0), s.off(30.0));
    let x0 = s.off(12.0);
    let sym_w = s.off(44.0);
    let text_x = x0 + sym_w + s.off(10.0);
    let left = s.legend().pos(Pos::new(HPos::Left, VPos::Center));
    let mut y = top + row / 2;
    for e in entries {
        let cy = y;
        match e {
            Entry::Line {
                label,
                colour,
                width,
                dashed,
            } => {
                let style = colour.stroke_width(*width);
                if *dashed {
                    let n = 3;
                    let seg = sym_w / (2 * n - 1);
                    for k in 0..n {
                        let a = x0 + 2 * k * seg;
                        area.draw(&PathElement::new(vec![(a, cy), (a + seg, cy)], style))?;
                    }
                } else {
                    area.draw(&PathElement::new(vec![(x0, cy), (x0 + sym_w, cy)], style))?;
                }
                area.draw(&Text::new(label.clone(), (text_x, cy), left.clone()))?;
            }
            Entry::Marker {
                label,
                shape,
                colour,
            } => {
                draw_shape(area, (x0 + sym_w / 2, cy), s.off(7.0), *shape, *colour, s)?;
                area.draw(&Text::new(label.clone(), (text_x, cy), left.clone()))?;
            }
            Entry::Patch {
                label,
                fill,
                outline,
            } => {
                let h = s.off(9.0);
                let rect = [(x0, cy - h), (x0 + sym_w, cy + h)];
                area.draw(&Rectangle::new(rect, fill.filled()))?;
                area.draw(&Rectangle::new(rect, outline.stroke_width(s.px(1.5))))?;
                area.draw(&Text::new(label.clone(), (text_x, cy), left.clone()))?;
            }
            Entry::Heading(text) => {
                let bold = s.heading().pos(Pos::new(HPos::Left, VPos::Center));
                area.draw(&Text::new(text.clone(), (x0, cy), bold))?;
            }
            Entry::Note(text) => {
                let note = s.note().pos(Pos::new(HPos::Left, VPos::Center));
                area.draw(&Text::new(text.clone(), (x0, cy), note))?;
            }
        }
        y += row;
    }
    Ok(())
}
