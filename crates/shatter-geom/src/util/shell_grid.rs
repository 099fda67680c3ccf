//! Items bucketed on a uniform 3D grid by their bounding boxes, for the item nearest a
//! point: a query searches shells of cells outward until no unvisited cell can hold a
//! nearer one.

use glam::DVec3;

/// At most this many cells in a grid.
const MAX_CELLS: f64 = (1 << 21) as f64;

/// A uniform grid of cells, each listing the items whose bounds overlap it.
pub(crate) struct ShellGrid {
    lo: DVec3,
    cell: f64,
    dims: [i64; 3],
    /// Per cell (x fastest), the items overlapping it.
    cells: Vec<Vec<u32>>,
}

impl ShellGrid {
    /// An empty grid over the box `lo..hi` of about `target` cells (at most 2^21; a flat
    /// box gets one layer).
    fn new(lo: DVec3, hi: DVec3, target: f64) -> ShellGrid {
        let ext = (hi - lo).max(DVec3::ZERO);
        let target = if target.is_finite() {
            target.clamp(1.0, MAX_CELLS)
        } else {
            1.0
        };
        let longest = ext.max_element();
        let volume = ext.max(DVec3::splat(longest / target)).element_product();
        let mut cell = (volume / target).cbrt();
        if !(cell > 0.0 && cell.is_finite()) {
            cell = if longest > 0.0 && longest.is_finite() {
                longest
            } else {
                1.0
            };
        }
        let count = |e: f64, cell: f64| ((e / cell).ceil() as i64).max(1);
        let dims_of = |cell: f64| [count(ext.x, cell), count(ext.y, cell), count(ext.z, cell)];
        let mut dims = dims_of(cell);
        while dims.iter().map(|&d| d as f64).product::<f64>() > MAX_CELLS {
            cell *= 2.0;
            dims = dims_of(cell);
        }
        ShellGrid {
            lo,
            cell,
            dims,
            cells: vec![Vec::new(); (dims[0] * dims[1] * dims[2]) as usize],
        }
    }

    /// An empty grid over the bounds of `points` (the unit box when there are none) of
    /// about `target` cells.
    pub(crate) fn over(points: &[DVec3], target: f64) -> ShellGrid {
        let (lo, hi) = if points.is_empty() {
            (DVec3::ZERO, DVec3::ONE)
        } else {
            super::bounds(points)
        };
        ShellGrid::new(lo, hi, target)
    }

    /// Lists item `id` in every cell its bounds `min..max` overlap.
    pub(crate) fn insert(&mut self, id: u32, min: DVec3, max: DVec3) {
        let (a, b) = (self.cell_of(min), self.cell_of(max));
        for z in a[2]..=b[2] {
            for y in a[1]..=b[1] {
                for x in a[0]..=b[0] {
                    let i = self.index([x, y, z]);
                    self.cells[i].push(id);
                }
            }
        }
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

    /// The item nearest `p`, where `dist2(id)` is an item's squared distance from `p`, or
    /// `None` to pass it over; among equals the smallest id. Every item must lie within
    /// its listed bounds, so that one in a cell `r` cells from `p`'s is at least `r - 1`
    /// cell edges away. `None` when no item is taken or `p` is not finite.
    pub(crate) fn nearest(
        &self,
        p: DVec3,
        mut dist2: impl FnMut(u32) -> Option<f64>,
    ) -> Option<u32> {
        if !p.is_finite() {
            return None;
        }
        let c = self.cell_of(p);
        let mut best: Option<(f64, u32)> = None;
        let reach = *self.dims.iter().max().unwrap_or(&1);
        for r in 0..=reach {
            // Cells at Chebyshev distance r from c: every item in a farther cell is at
            // least r cell edges from p (p lies in c, or beyond the grid's side).
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
                            if best.is_some_and(|(_, bt)| bt == t) {
                                continue;
                            }
                            let Some(d2) = dist2(t) else {
                                continue;
                            };
                            if best.is_none_or(|(b, bt)| d2 < b || (d2 == b && t < bt)) {
                                best = Some((d2, t));
                            }
                        }
                    }
                }
            }
        }
        best.map(|(_, t)| t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Points on a lattice with holes, queried from inside, outside and on the grid's
    /// side: the grid's answer is the brute force's, ties going to the smaller id, and a
    /// passed-over item is never the answer.
    #[test]
    fn the_nearest_item_is_the_brute_force_one() {
        let mut pts = Vec::new();
        for i in 0..1000u32 {
            let (x, y, z) = (i % 10, i / 10 % 10, i / 100);
            if (x * 7 + y * 3 + z) % 4 != 0 {
                pts.push(DVec3::new(x as f64, y as f64 * 0.5, z as f64 * 2.0));
            }
        }
        let mut grid = ShellGrid::over(&pts, pts.len() as f64 / 2.0);
        for (k, &q) in pts.iter().enumerate() {
            grid.insert(k as u32, q, q);
        }
        let skip = |k: u32| k.is_multiple_of(5);
        for i in 0..400 {
            let f = i as f64;
            let p = DVec3::new(
                (f * 0.37) % 14.0 - 2.0,
                (f * 0.61) % 7.0 - 1.0,
                (f * 0.23) % 22.0 - 2.0,
            );
            let got = grid.nearest(p, |k| {
                (!skip(k)).then(|| pts[k as usize].distance_squared(p))
            });
            let want = (0..pts.len() as u32)
                .filter(|&k| !skip(k))
                .min_by(|&a, &b| {
                    let (da, db) = (
                        pts[a as usize].distance_squared(p),
                        pts[b as usize].distance_squared(p),
                    );
                    da.total_cmp(&db).then(a.cmp(&b))
                });
            assert_eq!(got, want, "{p}");
        }
        assert_eq!(grid.nearest(DVec3::NAN, |_| Some(0.0)), None);
        assert_eq!(grid.nearest(DVec3::ZERO, |_| None), None);
    }
}
