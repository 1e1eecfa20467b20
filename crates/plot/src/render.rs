//! Where a figure goes and how it gets there: a [`Target`] (file stem and pixel size), the
//! [`Figure`] trait every figure implements once for any plotters backend, and [`render`],
//! which draws it into a PNG and an SVG.
//!
//! Drawing code is generic over the backend so that both files come from the same code and
//! show the same picture; heavy preparation (sampling contact, contours, quantiles) happens
//! once, before either file is drawn.

use std::path::{Path, PathBuf};

use image::ImageEncoder as _;
use plotters::coord::Shift;
use plotters::prelude::*;
use swarmplan_io::atomic::write_atomic;
use thiserror::Error;

use crate::style;

/// Smallest figure the layouts are made for, pixels.
pub const MIN_SIZE: (u32, u32) = (400, 300);

/// Where a figure is written: `STEM.png` and `STEM.svg`, `width` x `height` pixels.
///
/// Anything path-like converts into a target of the default size, so
/// `top_view(&world, &plan, title, "out/top")` writes `out/top.png` and `out/top.svg`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Target {
    /// Path of the files without their extension.
    pub stem: PathBuf,
    /// Width, pixels (1200).
    pub width: u32,
    /// Height, pixels (900).
    pub height: u32,
}

impl Target {
    /// Default size, pixels.
    pub const DEFAULT_SIZE: (u32, u32) = (1200, 900);

    /// A target of the default size.
    #[must_use]
    pub fn new(stem: impl Into<PathBuf>) -> Self {
        Self {
            stem: stem.into(),
            width: Self::DEFAULT_SIZE.0,
            height: Self::DEFAULT_SIZE.1,
        }
    }

    /// The same target at another size (at least `MIN_SIZE`, checked when drawing).
    #[must_use]
    pub fn with_size(mut self, width: u32, height: u32) -> Self {
        self.width = width;
        self.height = height;
        self
    }

    /// `STEM.png` (the extension is appended, so a stem like `run.v2` keeps its dot).
    #[must_use]
    pub fn png(&self) -> PathBuf {
        with_suffix(&self.stem, ".png")
    }

    /// `STEM.svg`.
    #[must_use]
    pub fn svg(&self) -> PathBuf {
        with_suffix(&self.stem, ".svg")
    }
}

fn with_suffix(stem: &Path, suffix: &str) -> PathBuf {
    let mut s = stem.as_os_str().to_owned();
    s.push(suffix);
    PathBuf::from(s)
}

impl From<PathBuf> for Target {
    fn from(stem: PathBuf) -> Self {
        Self::new(stem)
    }
}

impl From<&Path> for Target {
    fn from(stem: &Path) -> Self {
        Self::new(stem)
    }
}

impl From<&PathBuf> for Target {
    fn from(stem: &PathBuf) -> Self {
        Self::new(stem.clone())
    }
}

impl From<&str> for Target {
    fn from(stem: &str) -> Self {
        Self::new(stem)
    }
}

impl From<String> for Target {
    fn from(stem: String) -> Self {
        Self::new(stem)
    }
}

/// The files a figure was written to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    /// Path of the PNG.
    pub png: PathBuf,
    /// Path of the SVG.
    pub svg: PathBuf,
}

/// Why a figure could not be written; every variant names the file.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The folder of the files could not be created.
    #[error("{}: cannot create the folder: {source}", .path.display())]
    Folder {
        /// The figure's PNG.
        path: PathBuf,
        /// The error creating the folder.
        source: std::io::Error,
    },
    /// The font could not be registered or drawing failed.
    #[error("{}: cannot draw: {message}", .path.display())]
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// What went wrong, from the font loader or the backend.
        message: String,
    },
    /// A drawn file could not be written.
    #[error("{}: cannot write: {source}", .path.display())]
    Write {
        /// The file that could not be written.
        path: PathBuf,
        /// The error writing it.
        source: std::io::Error,
    },
    /// The data leave nothing to draw (no finite cost, no runs, ...).
    #[error("{}: nothing to draw: {what}", .path.display())]
    NoData {
        /// The figure's PNG.
        path: PathBuf,
        /// What is missing.
        what: String,
    },
    /// The target is smaller than `MIN_SIZE`.
    #[error(
        "{}: {width} x {height} px is too small; figures need at least {} x {} px",
        .path.display(), MIN_SIZE.0, MIN_SIZE.1
    )]
    TooSmall {
        /// The figure's PNG.
        path: PathBuf,
        /// Width asked for, pixels.
        width: u32,
        /// Height asked for, pixels.
        height: u32,
    },
}

/// The result of drawing on backend `DB`.
pub(crate) type DrawResult<T, DB> =
    Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A figure, drawable on any plotters backend.
pub(crate) trait Figure {
    /// Draws the whole figure on `root` (already filled white).
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB>;
}

/// Draws `figure` into `target`'s PNG and SVG.
pub(crate) fn render(figure: &impl Figure, target: &Target) -> Result<Written, PlotError> {
    let png = target.png();
    let svg = target.svg();
    let size = (target.width, target.height);
    if size.0 < MIN_SIZE.0 || size.1 < MIN_SIZE.1 {
        return Err(PlotError::TooSmall {
            path: png,
            width: size.0,
            height: size.1,
        });
    }
    if let Some(dir) = png.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| PlotError::Folder {
            path: png.clone(),
            source,
        })?;
    }
    style::register_font().map_err(|message| PlotError::Draw {
        path: png.clone(),
        message,
    })?;
    let draw_err = |path: &Path| {
        let path = path.to_path_buf();
        move |e: String| PlotError::Draw {
            path: path.clone(),
            message: e,
        }
    };
    // Drawn in memory and written atomically, so a full disk or a kill never leaves a
    // truncated figure, and a write error is an I/O error naming the file.
    let (w, h) = (size.0 as usize, size.1 as usize);
    let mut rgb = vec![0_u8; w * h * 3];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
        draw_on(figure, &root).map_err(draw_err(&png))?;
    }
    let mut png_bytes = Vec::new();
    image::codecs::png::PngEncoder::new(&mut png_bytes)
        .write_image(&rgb, size.0, size.1, image::ColorType::Rgb8)
        .map_err(|e| draw_err(&png)(e.to_string()))?;
    let mut svg_text = String::new();
    {
        let root = SVGBackend::with_string(&mut svg_text, size).into_drawing_area();
        draw_on(figure, &root).map_err(draw_err(&svg))?;
    }
    let svg_text = fix_embedded_images(svg_text);
    for (path, bytes) in [(&png, png_bytes.as_slice()), (&svg, svg_text.as_bytes())] {
        write_atomic(path, bytes).map_err(|source| PlotError::Write {
            path: path.clone(),
            source,
        })?;
    }
    Ok(Written { png, svg })
}

/// plotters-svg 0.3.7 embeds bitmaps as `data:png;base64,...`, which is not a MIME type;
/// strict viewers refuse it. Rewrites those to `data:image/png`.
fn fix_embedded_images(text: String) -> String {
    const BAD: &str = "href=\"data:png;base64,";
    if text.contains(BAD) {
        text.replace(BAD, "href=\"data:image/png;base64,")
    } else {
        text
    }
}

fn draw_on<DB: DrawingBackend>(
    figure: &impl Figure,
    root: &DrawingArea<DB, Shift>,
) -> Result<(), String> {
    let run = || -> DrawResult<(), DB> {
        root.fill(&WHITE)?;
        figure.draw(root)?;
        root.present()
    };
    run().map_err(|e| e.to_string())
}

/// The error of a figure with nothing to draw, named after `target`'s PNG.
pub(crate) fn no_data(target: &Target, what: impl Into<String>) -> PlotError {
    PlotError::NoData {
        path: target.png(),
        what: what.into(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suffixes_are_appended_not_substituted() {
        let t = Target::new("out/run.v2");
        assert_eq!(t.png(), PathBuf::from("out/run.v2.png"));
        assert_eq!(t.svg(), PathBuf::from("out/run.v2.svg"));
        assert_eq!((t.width, t.height), Target::DEFAULT_SIZE);
        let t = Target::from("a/b").with_size(640, 480);
        assert_eq!((t.width, t.height), (640, 480));
    }

    #[test]
    fn errors_name_the_file() {
        let e = PlotError::TooSmall {
            path: PathBuf::from("x/top.png"),
            width: 10,
            height: 10,
        };
        assert!(e
            .to_string()
            .starts_with("x/top.png: 10 x 10 px is too small"));
    }
}
