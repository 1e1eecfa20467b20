//! Figures from what `plan` and `bench` produce: a world with a plan, a convergence trace,
//! and run records. The crate draws; it never runs an optimizer.
//!
//! Every figure is one function that writes the same picture twice, `STEM.png` and
//! `STEM.svg`, at the [`Target`]'s size (1200 x 900 px unless told), and returns the two
//! paths or a [`PlotError`] naming the file it could not write:
//!
//! | function | file | shows |
//! |---|---|---|
//! | [`top_view`] | `top_view.rs` | relief, contours, threats, ground nodes, paths, outages, violations, equal aspect |
//! | [`view_3d`] | `view_3d.rs` | terrain surface, threat cylinders, paths at absolute altitude |
//! | [`convergence_run`] | `convergence_run.rs` | best cost per iteration of one run (total, per UAV) |
//! | [`convergence_bench`] | `convergence_bench.rs` | median and inter-quartile band per algorithm |
//! | [`comm_timeline`] | `comm_timeline.rs` | contact per UAV over time, R(t), interference windows |
//! | [`bench_boxplots`] | `bench_boxplots.rs` | cost per UAV per algorithm, feasible rate per algorithm |
//! | [`performance_profile`] | `performance_profile.rs` | share of a suite's instances within tau of the best median cost, per method |
//!
//! Text is drawn with DejaVu Sans from the `dejavu` crate through plotters' pure-Rust
//! `ab_glyph` path, so figures render the same on machines without any system font or font
//! library. The SVG files name `sans-serif` (DejaVu Sans first) and let the viewer's font
//! draw the text.

mod axis;
mod bench_boxplots;
mod comm_timeline;
mod contour;
mod convergence_bench;
mod convergence_run;
mod decimate;
mod legend;
mod performance_profile;
mod records;
mod render;
mod sampling;
mod stats;
mod style;
mod top_view;
mod view_3d;
mod violation_marks;

pub use bench_boxplots::bench_boxplots;
pub use comm_timeline::comm_timeline;
pub use convergence_bench::convergence_bench;
pub use convergence_run::{convergence_run, PerUav};
pub use performance_profile::performance_profile;
pub use render::{PlotError, Target, Written};
pub use style::uav_colour_hex;
pub use top_view::top_view;
pub use view_3d::view_3d;
