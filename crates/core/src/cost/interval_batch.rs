//! Eq. 8's interval integrals, computed many at a time (issue 47).
//!
//! The pair sweep of proximity (`proximity.rs`) cuts two UAVs' motions into intervals on
//! which both fly straight, and each interval's integral int_0^dt dtau / (|r0 + w tau|^2 + eps)
//! is one arctangent (docs/model.md, "Proximity"). Taken one at a time inside the sweep,
//! libm's `atan` alone was 16 % of an evaluation at five UAVs (`perf` over the `evaluate`
//! benchmark, docs/performance.md): a call per interval, with the branches of its range
//! reduction. Here the sweep only writes each interval's coefficients into arrays, and one
//! loop without data-dependent branches computes every integral, with an arctangent of our
//! own whose range reduction is made of selects, so that the compiler evaluates several
//! intervals per instruction; the sum then adds them in the sweep's order.
//!
//! The arctangent is the rational approximation of Cephes' `atan` (S. L. Moshier, *Methods
//! and Programs for Mathematical Functions*, Ellis Horwood, 1989, ISBN 0-7458-0289-3: a
//! degree 4 / degree 5 rational function in x^2 on |x| <= 0.66 after the reductions
//! x -> -1/x above tan(3 pi / 8) and x -> (x - 1)/(x + 1) between), applied to the ratio
//! p / |q| of the angle's two sides with one division. It uses additions, multiplications,
//! divisions and square roots only, each rounded correctly by IEEE 754 and never fused, so
//! every instruction set gives the same bits; its error is within a few units in the last
//! place of libm's (the tests below).

use glam::DVec3;

/// tan(3 pi / 8): above it the reduction takes -1/x.
const TAN_3PI_8: f64 = 2.414_213_562_373_095;
/// Cephes' bound of the middle reduction, (x - 1)/(x + 1).
const MIDDLE: f64 = 0.66;
/// The part of pi / 2 beyond its nearest double (Cephes' `MOREBITS`).
const PI_2_TAIL: f64 = 6.123_233_995_736_766e-17;
/// Numerator coefficients in x^2, highest degree first (as the source prints them).
#[allow(clippy::excessive_precision)]
const P: [f64; 5] = [
    -8.750_608_600_031_904_122_785e-1,
    -1.615_753_718_733_365_076_637e1,
    -7.500_855_792_314_704_667_340e1,
    -1.228_866_684_490_136_173_410e2,
    -6.485_021_904_942_025_371_773e1,
];
/// Denominator coefficients in x^2 below its leading 1, highest degree first.
#[allow(clippy::excessive_precision)]
const Q: [f64; 5] = [
    2.485_846_490_142_306_297_962e1,
    1.650_270_098_316_988_542_046e2,
    4.328_810_604_912_902_668_951e2,
    4.853_903_996_359_136_964_868e2,
    1.945_506_571_482_613_964_425e2,
];

/// The angle in [0, pi] whose sine has the sign of `p` >= 0 and whose cosine has the
/// sign of `q`: atan2(p, q) for p >= 0, written without branches.
#[inline(always)]
pub(super) fn upper_angle(p: f64, q: f64) -> f64 {
    let aq = q.abs();
    // Cephes' reductions, as selects: above tan(3 pi / 8) atan(x) = pi / 2 + atan(-1 / x),
    // above 0.66 pi / 4 + atan((x - 1) / (x + 1)), each with its share of pi / 2's tail.
    let (num, den, base, tail) = if p > TAN_3PI_8 * aq {
        (-aq, p, std::f64::consts::FRAC_PI_2, PI_2_TAIL)
    } else if p > MIDDLE * aq {
        (p - aq, p + aq, std::f64::consts::FRAC_PI_4, 0.5 * PI_2_TAIL)
    } else {
        (p, aq, 0.0, 0.0)
    };
    let x = num / den;
    let z = x * x;
    let pz = (((P[0] * z + P[1]) * z + P[2]) * z + P[3]) * z + P[4];
    let qz = ((((z + Q[0]) * z + Q[1]) * z + Q[2]) * z + Q[3]) * z + Q[4];
    let half = base + ((x * (z * pz / qz) + x) + tail);
    if q.is_sign_negative() {
        std::f64::consts::PI - half
    } else {
        half
    }
}

/// One interval's integral from a = |w|^2, b = 2 r0 . w, c = |r0|^2 + eps, the squared
/// cross product |w x r0|^2, eps and dt: (2 / sqrt D) atan2(dt sqrt D, 2c + b dt) with
/// D = 4 (|w x r0|^2 + eps a) (equal to 4ac - b^2 without its cancellation); dt / c for a
/// pair at rest relative to each other (a <= 1e-12). Both are computed and one is chosen,
/// so that a loop of them has no branch.
#[inline(always)]
pub(super) fn interval_integral(a: f64, b: f64, c: f64, cross: f64, dt: f64, eps: f64) -> f64 {
    let d = (4.0 * (cross + eps * a)).max(1e-300);
    let root = d.sqrt();
    let moving = 2.0 / root * upper_angle(dt * root, 2.0 * c + b * dt);
    let still = dt / c;
    if a <= 1e-12 {
        still
    } else {
        moving
    }
}

/// The intervals of one pair sweep as arrays, one entry per interval: what the merge gives
/// (start, length, the segments flown, relative position at the start and relative
/// velocity), then what [`Self::compute`] derives (the integral, and the closest approach's
/// squared distance and time after the start).
#[derive(Debug, Clone, Default)]
pub(super) struct IntervalBatch {
    t0: Vec<f64>,
    dt: Vec<f64>,
    segments: Vec<(usize, usize)>,
    r: [Vec<f64>; 3],
    w: [Vec<f64>; 3],
    integral: Vec<f64>,
    dmin2: Vec<f64>,
    tau: Vec<f64>,
    /// How many intervals the buffers hold (they keep their length).
    n: usize,
    /// The instruction sets found on this CPU.
    arch: pulp::Arch,
    dispatch: Dispatch,
}

/// Which code the kernel runs: what the CPU offers, or the baseline x86-64 code (for the
/// tests that check both give the same bits).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub(super) enum Dispatch {
    #[default]
    Detected,
    // Only the tests choose it.
    #[cfg_attr(not(test), allow(dead_code))]
    Baseline,
}

/// Writes intervals into an [`IntervalBatch`]'s buffers (see [`IntervalBatch::fill`]).
pub(super) struct Filler<'a> {
    t0: &'a mut [f64],
    dt: &'a mut [f64],
    segments: &'a mut [(usize, usize)],
    r: [&'a mut [f64]; 3],
    w: [&'a mut [f64]; 3],
    n: usize,
}

impl Filler<'_> {
    /// Adds an interval from `t0`, `dt` long, on `segments`, with relative position `r0` at
    /// its start and relative velocity `w`.
    #[inline]
    pub(super) fn push(&mut self, t0: f64, dt: f64, segments: (usize, usize), r0: DVec3, w: DVec3) {
        let i = self.n;
        self.t0[i] = t0;
        self.dt[i] = dt;
        self.segments[i] = segments;
        for k in 0..3 {
            self.r[k][i] = r0[k];
            self.w[k][i] = w[k];
        }
        self.n = i + 1;
    }
}

/// The kernel's inputs, as slices of one length.
struct Inputs<'a> {
    dt: &'a [f64],
    r: [&'a [f64]; 3],
    w: [&'a [f64]; 3],
    eps: f64,
}

/// Every interval's integral, squared closest distance and its time, into `integral`,
/// `dmin2` and `tau`.
#[inline(always)]
fn kernel(x: &Inputs<'_>, (integral, dmin2, tau): (&mut [f64], &mut [f64], &mut [f64])) {
    let n = x.dt.len();
    let (integral, dmin2, tau) = (&mut integral[..n], &mut dmin2[..n], &mut tau[..n]);
    let ([rx, ry, rz], [wx, wy, wz]) = (x.r, x.w);
    let (rx, ry, rz, wx, wy, wz) = (&rx[..n], &ry[..n], &rz[..n], &wx[..n], &wy[..n], &wz[..n]);
    for i in 0..n {
        let r0 = DVec3::new(rx[i], ry[i], rz[i]);
        let w = DVec3::new(wx[i], wy[i], wz[i]);
        let dt = x.dt[i];
        let a = w.length_squared();
        let b = 2.0 * r0.dot(w);
        let c = r0.length_squared();
        let t = if a > 0.0 {
            (-b / (2.0 * a)).max(0.0).min(dt)
        } else {
            0.0
        };
        tau[i] = t;
        dmin2[i] = (a * t + b) * t + c;
        let cross = w.cross(r0).length_squared();
        integral[i] = interval_integral(a, b, c + x.eps, cross, dt, x.eps);
    }
}

impl IntervalBatch {
    /// Runs the kernel as `dispatch` says.
    #[cfg(test)]
    fn with_dispatch(dispatch: Dispatch) -> Self {
        Self {
            dispatch,
            ..Self::default()
        }
    }

    /// Replaces the intervals by those `f` pushes, at most `cap` of them (more panics).
    #[inline]
    pub(super) fn fill(&mut self, cap: usize, f: impl FnOnce(&mut Filler<'_>)) {
        // The buffers only grow, so a sweep writes its intervals without reallocating.
        if self.t0.len() < cap {
            self.t0.resize(cap, 0.0);
            self.dt.resize(cap, 0.0);
            self.segments.resize(cap, (0, 0));
            self.r
                .iter_mut()
                .chain(&mut self.w)
                .for_each(|v| v.resize(cap, 0.0));
        }
        let [rx, ry, rz] = &mut self.r;
        let [wx, wy, wz] = &mut self.w;
        let mut filler = Filler {
            t0: &mut self.t0[..cap],
            dt: &mut self.dt[..cap],
            segments: &mut self.segments[..cap],
            r: [&mut rx[..cap], &mut ry[..cap], &mut rz[..cap]],
            w: [&mut wx[..cap], &mut wy[..cap], &mut wz[..cap]],
            n: 0,
        };
        f(&mut filler);
        self.n = filler.n;
    }

    /// How many intervals it holds.
    #[inline]
    pub(super) fn len(&self) -> usize {
        self.n
    }

    /// Interval i's start and segments.
    #[inline]
    pub(super) fn start(&self, i: usize) -> (f64, (usize, usize)) {
        (self.t0[i], self.segments[i])
    }

    /// Interval i's closest approach after [`Self::compute`]: squared distance and time
    /// after its start.
    #[inline]
    pub(super) fn closest(&self, i: usize) -> (f64, f64) {
        (self.dmin2[i], self.tau[i])
    }

    /// Computes every interval's integral and closest approach, with `eps` the integrand's
    /// epsilon: one loop without data-dependent branches, compiled for each instruction set
    /// `pulp` dispatches to (SSE2, and AVX2 where the CPU has it), with the same bits on
    /// each (no instruction is fused).
    pub(super) fn compute(&mut self, eps: f64) {
        let n = self.len();
        self.integral.resize(n, 0.0);
        self.dmin2.resize(n, 0.0);
        self.tau.resize(n, 0.0);
        let inputs = Inputs {
            dt: &self.dt[..n],
            r: [&self.r[0][..n], &self.r[1][..n], &self.r[2][..n]],
            w: [&self.w[0][..n], &self.w[1][..n], &self.w[2][..n]],
            eps,
        };
        let outputs = (
            &mut self.integral[..n],
            &mut self.dmin2[..n],
            &mut self.tau[..n],
        );
        match self.dispatch {
            Dispatch::Detected => self.arch.dispatch(|| kernel(&inputs, outputs)),
            Dispatch::Baseline => kernel(&inputs, outputs),
        }
    }

    /// The sum of every interval's integral after [`Self::compute`], added in the order the
    /// intervals were pushed.
    pub(super) fn sum(&self) -> f64 {
        self.integral[..self.len()]
            .iter()
            .fold(0.0, |sum, v| sum + v)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// A vector with each coordinate uniform in (-s, s).
    fn random_vector(rng: &mut ChaCha8Rng, s: f64) -> DVec3 {
        DVec3::new(
            rng.random_range(-s..s),
            rng.random_range(-s..s),
            rng.random_range(-s..s),
        )
    }

    /// An interval as the merge gives it: t0, dt, segments, r0, w.
    type Interval = (f64, f64, (usize, usize), DVec3, DVec3);

    /// Fills `batch` with `intervals`.
    fn fill(batch: &mut IntervalBatch, intervals: &[Interval]) {
        batch.fill(intervals.len(), |f| {
            for &(t0, dt, s, r0, w) in intervals {
                f.push(t0, dt, s, r0, w);
            }
        });
    }

    /// Units in the last place between two doubles of the same sign.
    fn ulps(a: f64, b: f64) -> u64 {
        a.to_bits().abs_diff(b.to_bits())
    }

    #[test]
    fn the_angle_is_within_two_ulps_of_libm_atan2_everywhere() {
        let mut rng = ChaCha8Rng::seed_from_u64(47);
        let mut worst = 0;
        for k in 0..200_000 {
            // Magnitudes across twelve decades, and ratios near every reduction bound.
            let p = 10f64.powf(rng.random_range(-6.0..6.0));
            let q = match k % 4 {
                0 => 10f64.powf(rng.random_range(-6.0..6.0)),
                1 => p / (TAN_3PI_8 * (1.0 + rng.random_range(-1e-6..1e-6))),
                2 => p / (MIDDLE * (1.0 + rng.random_range(-1e-6..1e-6))),
                _ => p * rng.random_range(0.0..3.0),
            };
            for q in [q, -q] {
                let (got, want) = (upper_angle(p, q), p.atan2(q));
                worst = worst.max(ulps(got, want));
                assert!(
                    ulps(got, want) <= 2,
                    "atan2({p}, {q}): {got} against {want}"
                );
            }
        }
        assert!(worst >= 1, "the approximation is not libm's bit for bit");
    }

    #[test]
    fn the_angle_at_its_edges() {
        use std::f64::consts::{FRAC_PI_2, PI};
        assert_eq!(upper_angle(1.0, 0.0), FRAC_PI_2);
        assert_eq!(upper_angle(1.0, -0.0), FRAC_PI_2);
        assert_eq!(upper_angle(0.0, 1.0), 0.0);
        assert_eq!(upper_angle(0.0, -1.0), PI);
        assert!((upper_angle(1.0, 1.0) - PI / 4.0).abs() <= f64::EPSILON);
    }

    #[test]
    fn the_batch_adds_in_order_what_one_interval_at_a_time_gives() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let mut batch = IntervalBatch::default();
        let mut want = 0.0;
        let mut intervals = Vec::new();
        for k in 0..37 {
            let r0 = random_vector(&mut rng, 300.0);
            let w = if k % 5 == 0 {
                DVec3::ZERO
            } else {
                random_vector(&mut rng, 30.0)
            };
            let dt = rng.random_range(0.01..20.0);
            intervals.push((0.0, dt, (0, 0), r0, w));
            let (a, b, c) = (w.length_squared(), 2.0 * r0.dot(w), r0.length_squared());
            want += interval_integral(a, b, c + 1.0, w.cross(r0).length_squared(), dt, 1.0);
        }
        fill(&mut batch, &intervals);
        batch.compute(1.0);
        assert_eq!(batch.sum().to_bits(), want.to_bits());
        fill(&mut batch, &[]);
        batch.compute(1.0);
        assert_eq!(batch.sum(), 0.0);
    }

    #[test]
    fn every_dispatch_path_gives_the_same_bits() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let mut detected = IntervalBatch::with_dispatch(Dispatch::Detected);
        let mut baseline = IntervalBatch::with_dispatch(Dispatch::Baseline);
        // Lengths that leave every remainder of a vector's lanes.
        for len in [1, 2, 3, 4, 5, 7, 8, 9, 31, 200] {
            let mut intervals = Vec::new();
            for k in 0..len {
                let r0 = random_vector(&mut rng, [3.0, 60.0, 900.0][k % 3]);
                let w = if k % 7 == 0 {
                    DVec3::ZERO
                } else {
                    random_vector(&mut rng, 40.0)
                };
                let dt = rng.random_range(1e-3..30.0);
                intervals.push((k as f64, dt, (k, k), r0, w));
            }
            fill(&mut detected, &intervals);
            fill(&mut baseline, &intervals);
            detected.compute(1.0);
            baseline.compute(1.0);
            for i in 0..len {
                assert_eq!(
                    detected.integral[i].to_bits(),
                    baseline.integral[i].to_bits()
                );
                let (d, b) = (detected.closest(i), baseline.closest(i));
                assert_eq!(
                    (d.0.to_bits(), d.1.to_bits()),
                    (b.0.to_bits(), b.1.to_bits())
                );
            }
        }
    }
}
