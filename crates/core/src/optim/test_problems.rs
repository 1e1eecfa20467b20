//! Small problems the optimizers' unit tests share (the conformance harness in
//! `tests/conformance.rs` has the full set).

use crate::problem::{Bound, Evaluation, Problem};

/// Sum of squares on a box.
pub(crate) struct Sphere(pub Vec<Bound>);

impl Problem for Sphere {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, x: &[f64]) -> Evaluation {
        Evaluation::new(x.iter().map(|v| v * v).sum(), 0.0)
    }
}

/// The same cost everywhere: nothing ever improves.
pub(crate) struct Flat(pub Vec<Bound>);

impl Problem for Flat {
    fn bounds(&self) -> &[Bound] {
        &self.0
    }
    fn evaluate(&self, _: &[f64]) -> Evaluation {
        Evaluation::new(1.0, 0.0)
    }
}
