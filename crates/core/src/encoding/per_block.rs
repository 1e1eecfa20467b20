//! What the encodings that add one value after each UAV's block share ([`super::paced`],
//! [`super::delayed`]): the widened bounds, and decoding and encoding through the inner
//! encoding with that value split off.

use std::cell::RefCell;

use super::PathEncoding;
use crate::plan::Plan;
use crate::problem::Bound;

thread_local! {
    /// Buffers of the inner vectors, one per wrapper in a nest (a paced and delayed
    /// encoding decodes through two), reused across calls.
    static BUFFERS: RefCell<Vec<Vec<f64>>> = const { RefCell::new(Vec::new()) };
}

/// `inner` with `extra` after each block of `block` values.
pub(crate) fn bounds_with_extra(inner: &[Bound], block: usize, extra: Bound) -> Vec<Bound> {
    let mut bounds = Vec::with_capacity(inner.len() + inner.len() / block.max(1));
    for b in inner.chunks(block.max(1)) {
        bounds.extend_from_slice(b);
        bounds.push(extra);
    }
    bounds
}

/// Decodes `x` (blocks of `block` + 1 values) through `inner` without the last value of
/// each block.
pub(crate) fn decode_inner(inner: &dyn PathEncoding, block: usize, x: &[f64], plan: &mut Plan) {
    let mut buf = BUFFERS.with(|b| b.borrow_mut().pop()).unwrap_or_default();
    buf.clear();
    for b in x.chunks(block + 1) {
        buf.extend_from_slice(&b[..block]);
    }
    inner.decode_into(&buf, plan);
    BUFFERS.with(|b| b.borrow_mut().push(buf));
}

/// Encodes `plan` through `inner` into `out` (blocks of `block` + 1 values for `uavs` UAVs),
/// the last value of UAV u's block being `extra(u)`.
pub(crate) fn encode_with_extra(
    inner: &dyn PathEncoding,
    block: usize,
    uavs: usize,
    plan: &Plan,
    out: &mut [f64],
    extra: impl Fn(usize) -> f64,
) {
    let mut values = vec![0.0; block * uavs];
    inner.encode_into(plan, &mut values);
    for (u, (o, i)) in out
        .chunks_mut(block + 1)
        .zip(values.chunks(block.max(1)))
        .enumerate()
    {
        o[..block].copy_from_slice(i);
        o[block] = extra(u);
    }
}
