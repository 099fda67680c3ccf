//! The input triangle nearest a point: the triangles bucketed on a uniform 3D grid, a
//! query searching shells of cells outward until no unvisited cell can hold a nearer one.

use glam::DVec3;

/// Nearest-triangle queries against a triangle mesh.
pub(crate) struct NearestTriangle {
    tris: Vec<[DVec3; 3]>,
    lo: DVec3,
    cell: f64,
    dims: [i64; 3],
    /// Per cell (x fastest), the triangles whose bounds overlap it.
    cells: Vec<Vec<u32>>,
}

/// At most this many cells in the grid.
const MAX_CELLS: f64 = (1 << 21) as f64;

impl NearestTriangle {
    /// Buckets the triangles over about one cell per triangle.
    pub fn new(positions: &[DVec3], triangles: &[[u32; 3]]) -> NearestTriangle {
        let tris: Vec<[DVec3; 3]> = triangles
            .iter()
            .map(|t| t.map(|i| positions[i as usize]))
            .collect();
        let (lo, hi) = if tris.is_empty() {
            (DVec3::ZERO, DVec3::ONE)
        } else {
            crate::util::bounds(positions)
        };
        let ext = (hi - lo).max(DVec3::splat(0.0));
        let target = (tris.len() as f64).clamp(1.0, MAX_CELLS);
        let longest = ext.max_element();
        // Cells of edge `cell`: about `target` of them over the bounds (a flat mesh gets
        // one layer).
        let volume = ext.max(DVec3::splat(longest / target)).element_product();
        let mut cell = (volume / target).cbrt();
        if !(cell > 0.0 && cell.is_finite()) {
            cell = if longest > 0.0 { longest } else { 1.0 };
        }
        let count = |e: f64, cell: f64| ((e / cell).ceil() as i64).max(1);
        let dims_of = |cell: f64| [count(ext.x, cell), count(ext.y, cell), count(ext.z, cell)];
        let mut dims = dims_of(cell);
        while dims.iter().map(|&d| d as f64).product::<f64>() > MAX_CELLS {
            cell *= 2.0;
            dims = dims_of(cell);
        }
        let mut grid = NearestTriangle {
            tris: Vec::new(),
            lo,
            cell,
            dims,
            cells: vec![Vec::new(); (dims[0] * dims[1] * dims[2]) as usize],
        };
        for (t, tri) in tris.iter().enumerate() {
            let a = grid.cell_of(tri[0].min(tri[1]).min(tri[2]));
            let b = grid.cell_of(tri[0].max(tri[1]).max(tri[2]));
            for z in a[2]..=b[2] {
                for y in a[1]..=b[1] {
                    for x in a[0]..=b[0] {
                        let i = grid.index([x, y, z]);
                        grid.cells[i].push(t as u32);
                    }
                }
            }
        }
        grid.tris = tris;
        grid
    }

    fn cell_of(&self, p: DVec3) -> [i64; 3] {
        let c = (p - self.lo) / self.cell;
        let clamp = |v: f64, d: i64| (v.floor() as i64).clamp(0, d - 1);
        [
            clamp(c.x, self.dims[0]),
            clamp(c.y, self.dims[1]),
            clamp(c.z, self.dims[2]),
        ]
    }

    fn index(&self, [x, y, z]: [i64; 3]) -> usize {
        ((z * self.dims[1] + y) * self.dims[0] + x) as usize
    }

    /// The index of the triangle nearest `p` (the first of equals); `None` when there
    /// are none or `p` is not finite.
    pub fn nearest(&self, p: DVec3) -> Option<usize> {
        if self.tris.is_empty() || !p.is_finite() {
            return None;
        }
        let c = self.cell_of(p);
        let mut best: Option<(f64, u32)> = None;
        let reach = *self.dims.iter().max().unwrap_or(&1);
        for r in 0..=reach {
            // Cells at Chebyshev distance r from c: every triangle in a farther cell is
            // at least r cell edges from p (p lies in c, or beyond the grid's side).
            if let Some((d2, _)) = best
                && d2.sqrt() <= (r - 1).max(0) as f64 * self.cell
            {
                break;
            }
            for z in (c[2] - r).max(0)..=(c[2] + r).min(self.dims[2] - 1) {
                for y in (c[1] - r).max(0)..=(c[1] + r).min(self.dims[1] - 1) {
                    for x in (c[0] - r).max(0)..=(c[0] + r).min(self.dims[0] - 1) {
                        let shell = (x - c[0]).abs().max((y - c[1]).abs()).max((z - c[2]).abs());
                        if shell != r {
                            continue;
                        }
                        for &t in &self.cells[self.index([x, y, z])] {
                            let d2 = (closest_point(self.tris[t as usize], p) - p).length_squared();
                            if best.is_none_or(|(b, bt)| d2 < b || (d2 == b && t < bt)) {
                                best = Some((d2, t));
                            }
                        }
                    }
                }
            }
        }
        best.map(|(_, t)| t as usize)
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
