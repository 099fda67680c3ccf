//! Which tetrahedra the surface enters: the mesh's triangles on a grid, each tested
//! against the tetrahedron's shrunk face planes.

use glam::DVec3;

use crate::fracture::kernel::Piece;
use crate::fracture::kernel::convex::TET_FACES;
use crate::util::bounds;

/// The mesh's triangles bucketed on a 3D grid by their bounds.
pub(super) struct TriangleGrid {
    lo: DVec3,
    cell: DVec3,
    n: usize,
    buckets: Vec<Vec<u32>>,
}

impl TriangleGrid {
    pub(super) fn new(mesh: &Piece) -> Self {
        let (lo, hi) = bounds(&mesh.pos);
        let n = ((mesh.tris.len() as f64 / 4.0).cbrt().ceil() as usize).clamp(1, 48);
        let cell = ((hi - lo) / n as f64).max(DVec3::splat(f64::MIN_POSITIVE));
        let mut grid = Self {
            lo,
            cell,
            n,
            buckets: vec![Vec::new(); n * n * n],
        };
        for (t, tri) in mesh.tris.iter().enumerate() {
            let [a, b, c] = tri.map(|i| mesh.pos[i as usize]);
            let (i0, i1) = (grid.index(a.min(b).min(c)), grid.index(a.max(b).max(c)));
            for x in i0[0]..=i1[0] {
                for y in i0[1]..=i1[1] {
                    for z in i0[2]..=i1[2] {
                        grid.buckets[(z * n + y) * n + x].push(t as u32);
                    }
                }
            }
        }
        grid
    }

    fn index(&self, p: DVec3) -> [usize; 3] {
        let q = (p - self.lo) / self.cell;
        let k = |v: f64| (v.max(0.0) as usize).min(self.n - 1);
        [k(q.x), k(q.y), k(q.z)]
    }

    /// Whether a triangle of `mesh` comes into tetrahedron `c` (positively oriented)
    /// shrunk by `margin`: then the surface may cut it.
    pub(super) fn enters(&self, mesh: &Piece, c: [DVec3; 4], margin: f64) -> bool {
        let mut planes = [(DVec3::ZERO, 0.0); 4];
        for (f, face) in TET_FACES.iter().enumerate() {
            let [a, b, cc] = face.map(|i| c[i]);
            let n = (b - a).cross(cc - a).normalize_or_zero();
            if n == DVec3::ZERO {
                return false;
            }
            planes[f] = (n, n.dot(a) - margin);
        }
        let (lo, hi) = (
            c[0].min(c[1]).min(c[2]).min(c[3]),
            c[0].max(c[1]).max(c[2]).max(c[3]),
        );
        let (i0, i1) = (self.index(lo), self.index(hi));
        let n = self.n;
        let mut seen: Vec<u32> = Vec::new();
        for x in i0[0]..=i1[0] {
            for y in i0[1]..=i1[1] {
                for z in i0[2]..=i1[2] {
                    seen.extend(&self.buckets[(z * n + y) * n + x]);
                }
            }
        }
        seen.sort_unstable();
        seen.dedup();
        seen.iter().any(|&t| {
            let tri = mesh.tris[t as usize].map(|i| mesh.pos[i as usize]);
            triangle_enters(tri, &planes)
        })
    }
}

/// Whether some point of triangle `tri` lies on the negative side of all `planes`
/// (`n · x <= d`): the triangle clipped by each in turn (Sutherland–Hodgman) keeps
/// something.
fn triangle_enters(tri: [DVec3; 3], planes: &[(DVec3, f64); 4]) -> bool {
    let mut poly: Vec<DVec3> = tri.to_vec();
    for &(n, d) in planes {
        let s: Vec<f64> = poly.iter().map(|&p| n.dot(p) - d).collect();
        if s.iter().all(|&v| v > 0.0) {
            return false;
        }
        if s.iter().all(|&v| v <= 0.0) {
            continue;
        }
        let mut next = Vec::with_capacity(poly.len() + 1);
        for i in 0..poly.len() {
            let j = (i + 1) % poly.len();
            if s[i] <= 0.0 {
                next.push(poly[i]);
            }
            if (s[i] <= 0.0) != (s[j] <= 0.0) {
                let t = s[i] / (s[i] - s[j]);
                next.push(poly[i] + (poly[j] - poly[i]) * t);
            }
        }
        poly = next;
        if poly.is_empty() {
            return false;
        }
    }
    !poly.is_empty()
}
