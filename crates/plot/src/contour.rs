//! Contour lines by marching squares on a regular grid, and the choice of contour levels.
//!
//! The grid is coarse (a few metres per cell is plenty for a map of a kilometre), so lines
//! are returned as loose two-point segments: drawing them needs no joining into polylines.
//! Saddle cells are resolved by the cell's centre value.

/// A sampled field: `values[j * xs.len() + i]` at (xs[i], ys[j]).
pub(crate) struct Grid {
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    pub values: Vec<f64>,
}

impl Grid {
    /// Samples `f` on `nx` x `ny` nodes spanning [x0, x1] x [y0, y1].
    pub(crate) fn sample(
        (x0, x1): (f64, f64),
        (y0, y1): (f64, f64),
        (nx, ny): (usize, usize),
        f: impl Fn(f64, f64) -> f64,
    ) -> Self {
        let axis = |a: f64, b: f64, n: usize| -> Vec<f64> {
            let n = n.max(2);
            (0..n)
                .map(|k| a + (b - a) * k as f64 / (n - 1) as f64)
                .collect()
        };
        let xs = axis(x0, x1, nx);
        let ys = axis(y0, y1, ny);
        let values = ys
            .iter()
            .flat_map(|y| xs.iter().map(|x| f(*x, *y)).collect::<Vec<_>>())
            .collect();
        Self { xs, ys, values }
    }

    fn at(&self, i: usize, j: usize) -> f64 {
        self.values[j * self.xs.len() + i]
    }

    /// Segments of the iso-line `level`.
    pub(crate) fn contour(&self, level: f64) -> Vec<[(f64, f64); 2]> {
        let mut out = Vec::new();
        let (nx, ny) = (self.xs.len(), self.ys.len());
        for j in 0..ny.saturating_sub(1) {
            for i in 0..nx.saturating_sub(1) {
                // Corners counter-clockwise from bottom-left.
                let p = [
                    (self.xs[i], self.ys[j]),
                    (self.xs[i + 1], self.ys[j]),
                    (self.xs[i + 1], self.ys[j + 1]),
                    (self.xs[i], self.ys[j + 1]),
                ];
                let v = [
                    self.at(i, j),
                    self.at(i + 1, j),
                    self.at(i + 1, j + 1),
                    self.at(i, j + 1),
                ];
                if v.iter().any(|x| !x.is_finite()) {
                    continue;
                }
                let above = v.map(|x| x > level);
                // Crossing on edge e (corner e to corner e + 1): bottom, right, top, left.
                let cross = |e: usize| -> Option<(f64, f64)> {
                    let (a, b) = (e, (e + 1) % 4);
                    if above[a] == above[b] {
                        return None;
                    }
                    // Interpolate from the same end in both cells sharing the edge, so
                    // their crossing points are bit-identical.
                    let (a, b) = if p[a] <= p[b] { (a, b) } else { (b, a) };
                    let t = (level - v[a]) / (v[b] - v[a]);
                    Some((
                        p[a].0 + (p[b].0 - p[a].0) * t,
                        p[a].1 + (p[b].1 - p[a].1) * t,
                    ))
                };
                let c: Vec<(usize, (f64, f64))> =
                    (0..4).filter_map(|e| cross(e).map(|q| (e, q))).collect();
                match c.len() {
                    2 => out.push([c[0].1, c[1].1]),
                    4 => {
                        let get = |e: usize| c[e].1;
                        let centre_above = v.iter().sum::<f64>() / 4.0 > level;
                        if above[0] != centre_above {
                            // Corners 0 and 2 are cut off: (bottom, left), (right, top).
                            out.push([get(0), get(3)]);
                            out.push([get(1), get(2)]);
                        } else {
                            // Corners 1 and 3 are cut off: (bottom, right), (top, left).
                            out.push([get(0), get(1)]);
                            out.push([get(2), get(3)]);
                        }
                    }
                    _ => {}
                }
            }
        }
        out
    }
}

/// Contour interval for heights from `lo` to `hi`: 25 m when that gives at most 16 levels,
/// else the first of 50, 100, 250, 500, 1000, ... that does.
pub(crate) fn interval(lo: f64, hi: f64) -> f64 {
    let span = (hi - lo).max(0.0);
    let mut step = 25.0;
    let mut k = 0;
    while span / step > 16.0 {
        step *= if k % 3 == 2 { 2.5 } else { 2.0 };
        k += 1;
    }
    step
}

/// Levels at multiples of `step` strictly inside (lo, hi).
pub(crate) fn levels(lo: f64, hi: f64, step: f64) -> Vec<f64> {
    let mut out = Vec::new();
    let mut l = (lo / step).floor() * step + step;
    while l < hi {
        out.push(l);
        l += step;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_gives_a_straight_contour() {
        let g = Grid::sample((0.0, 10.0), (0.0, 5.0), (11, 6), |x, _| x);
        let segs = g.contour(4.5);
        assert_eq!(segs.len(), 5);
        for s in &segs {
            assert!((s[0].0 - 4.5).abs() < 1e-12 && (s[1].0 - 4.5).abs() < 1e-12);
        }
    }

    #[test]
    fn a_cone_gives_a_closed_ring_at_the_right_radius() {
        let g = Grid::sample((-10.0, 10.0), (-10.0, 10.0), (81, 81), |x, y| x.hypot(y));
        let segs = g.contour(5.1);
        assert!(!segs.is_empty());
        for s in &segs {
            for p in s {
                assert!((p.0.hypot(p.1) - 5.1).abs() < 0.1);
            }
        }
        // Every end point is shared by exactly two segments on a closed curve.
        let key = |p: (f64, f64)| ((p.0 * 1e6).round() as i64, (p.1 * 1e6).round() as i64);
        let mut count = std::collections::HashMap::new();
        for s in &segs {
            for p in s {
                *count.entry(key(*p)).or_insert(0) += 1;
            }
        }
        assert!(count.values().all(|c| *c == 2));
    }

    #[test]
    fn saddles_give_two_segments() {
        let g = Grid {
            xs: vec![0.0, 1.0],
            ys: vec![0.0, 1.0],
            values: vec![1.0, 0.0, 0.0, 1.0],
        };
        assert_eq!(g.contour(0.5).len(), 2);
    }

    #[test]
    fn intervals_and_levels() {
        assert_eq!(interval(50.0, 300.0), 25.0);
        assert_eq!(interval(0.0, 1000.0), 100.0);
        assert_eq!(levels(50.0, 150.0, 25.0), vec![75.0, 100.0, 125.0]);
    }
}
