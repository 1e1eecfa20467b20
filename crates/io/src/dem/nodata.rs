//! Nodata handling: which samples are nodata, and filling them from the nearest valid
//! cell so that no sentinel (-9999, -3.4e38, NaN) ever reaches a terrain.

/// Not finite, beyond 1e30 in magnitude, or the nodata value within a relative 1e-6 (GDAL
/// prints the float32 minimum as "-3.402823e+38", which is not quite that float).
fn is_nodata(v: f64, nodata: Option<f64>) -> bool {
    !v.is_finite()
        || v.abs() > 1e30
        || nodata.is_some_and(|nd| v == nd || (v - nd).abs() <= 1e-6 * nd.abs().max(1.0))
}

/// Replaces nodata cells by their nearest valid cell: a breadth-first search from all valid
/// cells at once over the 8 neighbours, level by level; within a level, edge neighbours are
/// claimed before corner neighbours, then row-major order decides. Returns how many cells
/// were filled, or None if no cell is valid.
pub(super) fn fill(values: &mut [f64], columns: usize, nodata: Option<f64>) -> Option<usize> {
    const EDGE: [(i64, i64); 4] = [(0, -1), (-1, 0), (1, 0), (0, 1)];
    const CORNER: [(i64, i64); 4] = [(-1, -1), (1, -1), (-1, 1), (1, 1)];
    let mut pending: Vec<bool> = values.iter().map(|v| is_nodata(*v, nodata)).collect();
    let filled = pending.iter().filter(|b| **b).count();
    if filled == 0 {
        return Some(0);
    }
    if filled == values.len() {
        return None;
    }
    let rows = values.len() / columns;
    let mut frontier: Vec<usize> = (0..values.len()).filter(|k| !pending[*k]).collect();
    while !frontier.is_empty() {
        let mut next = Vec::new();
        for steps in [&EDGE, &CORNER] {
            for &k in &frontier {
                let (i, j) = ((k % columns) as i64, (k / columns) as i64);
                for &(di, dj) in steps {
                    let (ni, nj) = (i + di, j + dj);
                    if ni < 0 || nj < 0 || ni >= columns as i64 || nj >= rows as i64 {
                        continue;
                    }
                    let n = nj as usize * columns + ni as usize;
                    if pending[n] {
                        pending[n] = false;
                        values[n] = values[k];
                        next.push(n);
                    }
                }
            }
        }
        frontier = next;
    }
    Some(filled)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fill_takes_the_nearest_valid_cell() {
        let nd = -9999.0;
        #[rustfmt::skip]
        let mut v = vec![
            1.0, nd,  nd,  nd,
            nd,  nd,  nd,  2.0,
            nd,  nd,  nd,  nd,
        ];
        assert_eq!(fill(&mut v, 4, Some(nd)), Some(10));
        #[rustfmt::skip]
        let expected = vec![
            1.0, 1.0, 2.0, 2.0,
            1.0, 1.0, 2.0, 2.0,
            1.0, 1.0, 2.0, 2.0,
        ];
        assert_eq!(v, expected);
    }

    #[test]
    fn sentinels_and_non_finite_values_are_nodata() {
        let mut v = vec![5.0, f64::NAN, f64::from(f32::MIN), f64::INFINITY];
        // GDAL's text for f32::MIN is not exactly f32::MIN.
        assert_eq!(fill(&mut v, 2, Some(-3.402823e38)), Some(3));
        assert_eq!(v, vec![5.0; 4]);
        let mut all = vec![-9999.0; 4];
        assert_eq!(fill(&mut all, 2, Some(-9999.0)), None);
    }
}
