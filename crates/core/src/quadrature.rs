//! Adaptive Simpson quadrature: the slow reference that the closed forms are held to.
//!
//! Eq. 8's integral is computed in closed form on every interval (`cost/interval_batch.rs`),
//! and issue 47 asks every such term to agree with a slow reference within 1e-9 relative.
//! This is that reference: adaptive Simpson's rule with Richardson's correction (Lyness,
//! "Notes on the adaptive Simpson quadrature routine", J. ACM 16(3):483-495, 1969; its DOI
//! not confirmed, docs/references.md), which shares nothing with the closed form. It is used by the
//! tests (the interval integral in `cost/proximity.rs`, the whole pair integral in
//! `crates/io/tests/proximity_reference.rs`), never on the hot path.

/// The integral of `f` over [a, b] (0 when b <= a), halving every piece whose two halves
/// differ from it by more than 15 times its share of `relative_tolerance` x the first
/// estimate, at most `max_depth` halvings deep.
#[must_use]
pub fn adaptive_simpson(
    f: &dyn Fn(f64) -> f64,
    (a, b): (f64, f64),
    relative_tolerance: f64,
    max_depth: u32,
) -> f64 {
    if b <= a {
        return 0.0;
    }
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    let whole = simpson(a, b, (fa, fm, fb));
    let tolerance = relative_tolerance * whole.abs().max(1e-300);
    refine(f, (a, b), (fa, fm, fb), whole, tolerance, max_depth)
}

/// Simpson's rule on [a, b] from f at a, the middle and b.
fn simpson(a: f64, b: f64, (fa, fm, fb): (f64, f64, f64)) -> f64 {
    (b - a) / 6.0 * (fa + 4.0 * fm + fb)
}

fn refine(
    f: &dyn Fn(f64) -> f64,
    (a, b): (f64, f64),
    (fa, fm, fb): (f64, f64, f64),
    whole: f64,
    tolerance: f64,
    depth: u32,
) -> f64 {
    let m = 0.5 * (a + b);
    let (lm, rm) = (f(0.5 * (a + m)), f(0.5 * (m + b)));
    let (left, right) = (simpson(a, m, (fa, lm, fm)), simpson(m, b, (fm, rm, fb)));
    let error = left + right - whole;
    // A NaN estimate stops here rather than halving 2^depth times.
    if depth == 0 || error.is_nan() || error.abs() <= 15.0 * tolerance {
        left + right + error / 15.0
    } else {
        refine(f, (a, m), (fa, lm, fm), left, 0.5 * tolerance, depth - 1)
            + refine(f, (m, b), (fm, rm, fb), right, 0.5 * tolerance, depth - 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integrates_known_functions_to_the_tolerance() {
        let pi = adaptive_simpson(&|x: f64| 4.0 / (1.0 + x * x), (0.0, 1.0), 1e-13, 50);
        assert!((pi - std::f64::consts::PI).abs() < 1e-12, "{pi}");
        let peak = adaptive_simpson(&|x: f64| 1.0 / (x * x + 1e-4), (-1.0, 1.0), 1e-12, 60);
        let exact = 2.0 * 100.0 * (100.0f64).atan();
        assert!((peak - exact).abs() < 1e-9 * exact, "{peak} {exact}");
        assert_eq!(adaptive_simpson(&|_| 1.0, (2.0, 1.0), 1e-12, 10), 0.0);
        // A NaN integrand ends at once (NaN), where it would have halved 2^50 times.
        let calls = std::cell::Cell::new(0u32);
        let nan = adaptive_simpson(
            &|_| {
                calls.set(calls.get() + 1);
                f64::NAN
            },
            (0.0, 1.0),
            1e-12,
            50,
        );
        assert!(
            nan.is_nan() && calls.get() == 5,
            "{nan} after {} calls",
            calls.get()
        );
    }
}
