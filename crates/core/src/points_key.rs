//! Point lists as bits: the keys of the evaluation's memos (flown arcs, pair sweeps, each
//! UAV's own terms), which must serve a result only for inputs identical bit for bit
//! (-0.0 and 0.0, or two NaNs, are told apart), so that a memo never changes a result.

use glam::DVec3;

fn bits(v: DVec3) -> [u64; 3] {
    [v.x.to_bits(), v.y.to_bits(), v.z.to_bits()]
}

/// The bits of a list of points, kept to recognise the same list later.
#[derive(Debug, Clone, Default)]
pub(crate) struct PointsKey(Vec<[u64; 3]>);

impl PointsKey {
    /// Whether `points` are bit for bit the list kept.
    pub(crate) fn matches(&self, points: &[DVec3]) -> bool {
        self.0.len() == points.len() && self.0.iter().zip(points).all(|(k, p)| *k == bits(*p))
    }

    /// Keeps `points` instead.
    pub(crate) fn set(&mut self, points: &[DVec3]) {
        self.0.clear();
        self.0.extend(points.iter().map(|p| bits(*p)));
    }
}

/// Whether two lists of points are the same bits.
pub(crate) fn same_points(a: &[DVec3], b: &[DVec3]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| bits(*p) == bits(*q))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_same_bits_match() {
        let points = [DVec3::new(1.0, 0.0, 2.0), DVec3::new(3.0, 4.0, 5.0)];
        let mut key = PointsKey::default();
        assert!(!key.matches(&points));
        key.set(&points);
        assert!(key.matches(&points));
        assert!(!key.matches(&points[..1]));
        let negative_zero = [DVec3::new(1.0, -0.0, 2.0), points[1]];
        assert!(!key.matches(&negative_zero));
        assert!(same_points(&points, &points));
        assert!(!same_points(&points, &negative_zero));
        let nan = [DVec3::new(f64::NAN, 0.0, 0.0)];
        assert!(same_points(&nan, &nan));
    }
}
