//! Threats: vertical cylinders of unbounded height (the paper's Tables 2-3; the z column is
//! kept for drawing only, as in SPSO). Hard zone: within r + drone size of the axis.
//! Soft zone (SPSO J2): a danger band of `danger_factor` x drone size beyond that.

use serde::{Deserialize, Serialize};

/// A threat: a vertical cylinder of unbounded height.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Threat {
    /// Axis position, metres east.
    pub x: f64,
    /// Axis position, metres north.
    pub y: f64,
    /// Height of the drawn cylinder (drawing only).
    #[serde(default = "default_draw_height")]
    pub z: f64,
    /// Radius, metres.
    pub r: f64,
}

fn default_draw_height() -> f64 {
    150.0
}

/// Whether the horizontal bounding box of segment a-b misses the square of half-width
/// `reach` around the axis of `t` (then the segment is farther than `reach` from it).
#[must_use]
pub fn segment_box_misses(t: &Threat, a: glam::DVec3, b: glam::DVec3, reach: f64) -> bool {
    a.x.min(b.x) > t.x + reach
        || a.x.max(b.x) < t.x - reach
        || a.y.min(b.y) > t.y + reach
        || a.y.max(b.y) < t.y - reach
}

/// Distance from point p to the segment a-b in the plane (SPSO's `DistP2S`, written so that
/// a degenerate segment gives the distance to its point).
#[must_use]
pub fn point_segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (abx, aby) = (b.0 - a.0, b.1 - a.1);
    let (apx, apy) = (p.0 - a.0, p.1 - a.1);
    let len2 = abx * abx + aby * aby;
    if len2 == 0.0 {
        return (apx * apx + apy * apy).sqrt();
    }
    let (bpx, bpy) = (p.0 - b.0, p.1 - b.1);
    // Inside the slab of the segment: perpendicular distance; else nearest end (as DistP2S).
    if (abx * apx + aby * apy) >= 0.0 && (-abx * bpx - aby * bpy) >= 0.0 {
        (abx * apy - aby * apx).abs() / len2.sqrt()
    } else {
        (apx * apx + apy * apy)
            .sqrt()
            .min((bpx * bpx + bpy * bpy).sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_to_segment_cases() {
        // Perpendicular foot inside the segment.
        assert!((point_segment_distance((5.0, 3.0), (0.0, 0.0), (10.0, 0.0)) - 3.0).abs() < 1e-12);
        // Beyond an end: distance to that end.
        assert!((point_segment_distance((13.0, 4.0), (0.0, 0.0), (10.0, 0.0)) - 5.0).abs() < 1e-12);
        // Degenerate segment.
        assert!((point_segment_distance((3.0, 4.0), (0.0, 0.0), (0.0, 0.0)) - 5.0).abs() < 1e-12);
    }
}
