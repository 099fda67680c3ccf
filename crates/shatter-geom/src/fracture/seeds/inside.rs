//! Fast inside tests for a closed mesh: parity of a vertical ray's crossings, with the
//! triangles bucketed on a 2D grid so a query looks at a few of them; queries whose ray
//! passes too close to an edge fall back to the generalized winding number.

use glam::{DVec2, DVec3};

use rand::Rng;
use rand_chacha::ChaCha8Rng;

use crate::fracture::kernel::Piece;
use crate::mesh::winding_number;
use crate::util::bounds;

/// Inside tests against one closed, outward solid.
pub(crate) struct InsideTester<'a> {
    piece: &'a Piece,
    lo: DVec3,
    hi: DVec3,
    n: usize,
    cell: DVec2,
    /// The triangles of each grid cell, cell after cell: cell `k` holds
    /// `triangles[start[k]..start[k + 1]]`.
    start: Vec<u32>,
    triangles: Vec<u32>,
}

impl<'a> InsideTester<'a> {
    /// Buckets the triangles of `piece` over a grid of about one cell per two triangles.
    pub fn new(piece: &'a Piece) -> Self {
        let (lo, hi) = bounds(&piece.pos);
        let n = ((piece.tris.len() as f64 / 2.0).sqrt().ceil() as usize).clamp(1, 128);
        let ext = DVec2::new(hi.x - lo.x, hi.y - lo.y).max(DVec2::splat(f64::MIN_POSITIVE));
        let cell = ext / n as f64;
        let idx = |v: f64, o: f64, c: f64| (((v - o) / c) as usize).min(n - 1);
        // Each triangle's range of grid cells; counted, then filled in (no list per cell).
        let ranges: Vec<[usize; 4]> = piece
            .tris
            .iter()
            .map(|tri| {
                let [a, b, c] = tri.map(|i| piece.pos[i as usize]);
                let (tlo, thi) = (a.min(b).min(c), a.max(b).max(c));
                [
                    idx(tlo.x, lo.x, cell.x),
                    idx(thi.x, lo.x, cell.x),
                    idx(tlo.y, lo.y, cell.y),
                    idx(thi.y, lo.y, cell.y),
                ]
            })
            .collect();
        let mut start = vec![0u32; n * n + 1];
        for &[i0, i1, j0, j1] in &ranges {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    start[j * n + i + 1] += 1;
                }
            }
        }
        for k in 0..n * n {
            start[k + 1] += start[k];
        }
        let mut fill: Vec<u32> = start[..n * n].to_vec();
        let mut triangles = vec![0u32; start[n * n] as usize];
        for (t, &[i0, i1, j0, j1]) in ranges.iter().enumerate() {
            for j in j0..=j1 {
                for i in i0..=i1 {
                    let slot = &mut fill[j * n + i];
                    triangles[*slot as usize] = t as u32;
                    *slot += 1;
                }
            }
        }
        Self {
            piece,
            lo,
            hi,
            n,
            cell,
            start,
            triangles,
        }
    }

    /// Bounds of the solid.
    pub fn bounds(&self) -> (DVec3, DVec3) {
        (self.lo, self.hi)
    }

    /// Is `p` inside the solid? (Points on the surface may go either way.)
    pub fn contains(&self, p: DVec3) -> bool {
        if !(p.cmpge(self.lo).all() && p.cmple(self.hi).all()) {
            return false;
        }
        let i = (((p.x - self.lo.x) / self.cell.x) as usize).min(self.n - 1);
        let j = (((p.y - self.lo.y) / self.cell.y) as usize).min(self.n - 1);
        let q = DVec2::new(p.x, p.y);
        let mut crossings = 0u32;
        // Distinct triangles may share the ray's hit on an edge: too close is ambiguous.
        let tol = 1e-9;
        let k = j * self.n + i;
        for &t in &self.triangles[self.start[k] as usize..self.start[k + 1] as usize] {
            let [a, b, c] = self.piece.tris[t as usize].map(|k| self.piece.pos[k as usize]);
            let (a2, b2, c2) = (a.truncate(), b.truncate(), c.truncate());
            let area = (b2 - a2).perp_dot(c2 - a2);
            if area == 0.0 {
                continue;
            }
            let w0 = (b2 - q).perp_dot(c2 - q) / area;
            let w1 = (c2 - q).perp_dot(a2 - q) / area;
            let w2 = 1.0 - w0 - w1;
            if w0 < -tol || w1 < -tol || w2 < -tol {
                continue;
            }
            if w0 < tol || w1 < tol || w2 < tol {
                return self.winding(p);
            }
            let z = w0 * a.z + w1 * b.z + w2 * c.z;
            if z > p.z {
                crossings += 1;
            }
        }
        crossings % 2 == 1
    }

    fn winding(&self, p: DVec3) -> bool {
        winding_number(&self.piece.pos, &self.piece.tris, p) > 0.5
    }
}

/// Tries per wanted point before sampling gives up on the inside test.
const TRIES_PER_POINT: usize = 200;

/// Samples inside a closed solid by rejection from its bounds.
pub(crate) struct InsideSampler<'a> {
    tester: InsideTester<'a>,
    lo: DVec3,
    hi: DVec3,
}

impl<'a> InsideSampler<'a> {
    pub fn new(piece: &'a Piece) -> Self {
        let tester = InsideTester::new(piece);
        let (lo, hi) = tester.bounds();
        Self { tester, lo, hi }
    }

    /// Is `p` inside the solid?
    pub fn contains(&self, p: DVec3) -> bool {
        self.tester.contains(p)
    }

    /// A uniform point of the bounding box.
    pub fn in_box(&self, rng: &mut ChaCha8Rng) -> DVec3 {
        let t = DVec3::new(rng.random(), rng.random(), rng.random());
        self.lo + (self.hi - self.lo) * t
    }

    /// Draws from `draw` until the point is inside (bounded tries; the last draw is
    /// returned if none was inside, which the caller's cells tolerate).
    pub fn inside_from(
        &self,
        rng: &mut ChaCha8Rng,
        mut draw: impl FnMut(&mut ChaCha8Rng) -> DVec3,
    ) -> DVec3 {
        let mut p = draw(rng);
        for _ in 0..TRIES_PER_POINT {
            if self.contains(p) {
                return p;
            }
            p = draw(rng);
        }
        p
    }

    /// A uniform point inside the solid.
    pub fn uniform(&self, rng: &mut ChaCha8Rng) -> DVec3 {
        self.inside_from(rng, |r| self.in_box(r))
    }

    pub fn bounds(&self) -> (DVec3, DVec3) {
        (self.lo, self.hi)
    }
}
