//! The input triangle nearest a point, through a [`ShellGrid`] of the triangles' bounds.

use glam::DVec3;

use crate::util::ShellGrid;

/// Nearest-triangle queries against a triangle mesh.
pub(crate) struct NearestTriangle {
    tris: Vec<[DVec3; 3]>,
    grid: ShellGrid,
}

impl NearestTriangle {
    /// Buckets the triangles over about one cell per triangle.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> NearestTriangle {
        let tris: Vec<[DVec3; 3]> = triangles
            .iter()
            .map(|t| t.map(|i| positions[i as usize]))
            .collect();
        let mut grid = ShellGrid::over(positions, tris.len() as f64);
        for (t, tri) in tris.iter().enumerate() {
            grid.insert(
                t as u32,
                tri[0].min(tri[1]).min(tri[2]),
                tri[0].max(tri[1]).max(tri[2]),
            );
        }
        NearestTriangle { tris, grid }
    }

    /// The index of the triangle nearest `p` (the first of equals); `None` when there
    /// are none or `p` is not finite.
    pub fn nearest(&self, p: DVec3) -> Option<usize> {
        if self.tris.is_empty() {
            return None;
        }
        self.grid
            .nearest(p, |t| {
                Some((closest_point(self.tris[t as usize], p) - p).length_squared())
            })
            .map(|t| t as usize)
    }
}

/// The point of triangle `[a, b, c]` nearest `p` (Ericson, Real-Time Collision
/// Detection, 5.1.5).
pub(crate) fn closest_point([a, b, c]: [DVec3; 3], p: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE || !denom.is_finite() {
        return a;
    }
    let (v, w) = (vb / denom, vc / denom);
    a + ab * v + ac * w
}
