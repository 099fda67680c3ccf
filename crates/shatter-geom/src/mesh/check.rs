//! Topology checks: closed, manifold, consistently wound, outward.

use super::TriMesh;
use crate::util::UnionFind;

/// What [`TriMesh::check`] found, counted on the welded mesh.
///
/// An edge is a pair of welded vertices used by some triangle side. It is a *boundary*
/// edge when one triangle uses it, *non-manifold* when more than two do, and
/// *inconsistently wound* when two triangles use it in the same direction (a closed,
/// consistently wound surface uses each edge once in each direction).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct MeshReport {
    /// Distinct vertex positions (vertices after welding).
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Triangles with an index out of range (left out of every other count).
    pub invalid_triangles: usize,
    /// Vertices with a NaN or infinite coordinate.
    pub non_finite_vertices: usize,
    /// Edges used by exactly one triangle.
    pub boundary_edges: usize,
    /// Edges used by more than two triangles.
    pub non_manifold_edges: usize,
    /// Edges used twice in the same direction.
    pub inconsistent_edges: usize,
    /// Vertices whose triangles form more than one fan: the surface touches itself there
    /// (two solids sharing a corner, or a pinched surface).
    pub non_manifold_vertices: usize,
    /// Triangles of zero area (a repeated vertex, or three collinear corners, decided
    /// exactly).
    pub degenerate_triangles: usize,
    /// Connected components (triangles connected through shared vertices).
    pub components: usize,
    /// Signed volume (positive for an outward closed mesh).
    pub signed_volume: f64,
}

impl MeshReport {
    /// No boundary edges and no non-manifold edges (and at least one triangle).
    pub fn is_closed(&self) -> bool {
        self.triangles > 0
            && self.invalid_triangles == 0
            && self.boundary_edges == 0
            && self.non_manifold_edges == 0
    }

    /// Every edge shared by at most two triangles and every vertex a single fan.
    pub fn is_manifold(&self) -> bool {
        self.non_manifold_edges == 0 && self.non_manifold_vertices == 0
    }

    /// Every shared edge used once in each direction.
    pub fn is_consistent(&self) -> bool {
        self.inconsistent_edges == 0
    }

    /// Closed, consistently wound and enclosing a positive signed volume.
    pub fn is_outward(&self) -> bool {
        self.is_closed() && self.is_consistent() && self.signed_volume > 0.0
    }

    /// Everything a solid needs: finite, closed, manifold (edges and vertices),
    /// consistently wound and outward.
    pub fn is_solid(&self) -> bool {
        self.non_finite_vertices == 0 && self.is_manifold() && self.is_outward()
    }
}

/// A directed use of an undirected edge `(lo, hi)` by one triangle.
#[derive(Clone, Copy)]
struct EdgeUse {
    lo: u32,
    hi: u32,
    /// Corner index (`3·triangle + k`) of `lo` and of `hi` in the using triangle.
    corner_lo: u32,
    corner_hi: u32,
    /// The triangle walks the edge from `lo` to `hi`.
    forward: bool,
}

/// Whether the triangle `a b c` has zero area, decided exactly: it does when its
/// projections onto the three coordinate planes all have zero signed area.
pub(crate) fn is_degenerate(a: glam::DVec3, b: glam::DVec3, c: glam::DVec3) -> bool {
    use robust::{Coord, orient2d};
    let proj = |p: glam::DVec3, i: usize, j: usize| Coord { x: p[i], y: p[j] };
    [(0, 1), (1, 2), (2, 0)]
        .iter()
        .all(|&(i, j)| orient2d(proj(a, i, j), proj(b, i, j), proj(c, i, j)) == 0.0)
}

impl TriMesh {
    /// Counts the mesh's topological problems on the welded mesh (see
    /// [`welded`](TriMesh::welded)). Never panics, whatever the input.
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// let r = shapes::cube().check();
    /// assert_eq!((r.vertices, r.triangles, r.components), (8, 12, 1));
    /// assert!(r.is_solid());
    /// // Remove a face: 4 boundary edges.
    /// let mut open = shapes::cube();
    /// open.triangles.truncate(10);
    /// assert_eq!(open.check().boundary_edges, 4);
    /// assert!(!open.check().is_closed());
    /// ```
    pub fn check(&self) -> MeshReport {
        let mesh = self.welded();
        let n = mesh.positions.len();
        let mut report = MeshReport {
            vertices: n,
            triangles: mesh.triangles.len(),
            non_finite_vertices: mesh.positions.iter().filter(|p| !p.is_finite()).count(),
            ..MeshReport::default()
        };
        let mut uses = Vec::with_capacity(3 * mesh.triangles.len());
        let mut vertex_sets = UnionFind::new(n);
        let mut used = vec![false; n];
        let mut valid = Vec::with_capacity(mesh.triangles.len());
        for (t, tri) in mesh.triangles.iter().enumerate() {
            if tri.iter().any(|&i| i as usize >= n) {
                report.invalid_triangles += 1;
                continue;
            }
            valid.push(t);
            let [a, b, c] = mesh.triangle(t);
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
                report.degenerate_triangles += 1;
                continue;
            }
            if is_degenerate(a, b, c) {
                report.degenerate_triangles += 1;
            }
            for k in 0..3 {
                let (u, v) = (tri[k], tri[(k + 1) % 3]);
                let (cu, cv) = (3 * t as u32 + k as u32, 3 * t as u32 + ((k + 1) % 3) as u32);
                uses.push(if u < v {
                    EdgeUse {
                        lo: u,
                        hi: v,
                        corner_lo: cu,
                        corner_hi: cv,
                        forward: true,
                    }
                } else {
                    EdgeUse {
                        lo: v,
                        hi: u,
                        corner_lo: cv,
                        corner_hi: cu,
                        forward: false,
                    }
                });
                used[u as usize] = true;
                vertex_sets.union(u as usize, v as usize);
            }
        }
        uses.sort_unstable_by_key(|e| (e.lo, e.hi));
        // Corners of the same vertex joined across shared edges: a vertex whose corners end
        // up in several groups has several fans.
        let mut corner_sets = UnionFind::new(3 * mesh.triangles.len());
        for group in uses.chunk_by(|a, b| (a.lo, a.hi) == (b.lo, b.hi)) {
            match group.len() {
                1 => report.boundary_edges += 1,
                2 => {
                    if group[0].forward == group[1].forward {
                        report.inconsistent_edges += 1;
                    }
                }
                _ => report.non_manifold_edges += 1,
            }
            for other in &group[1..] {
                corner_sets.union(group[0].corner_lo as usize, other.corner_lo as usize);
                corner_sets.union(group[0].corner_hi as usize, other.corner_hi as usize);
            }
        }
        let mut fan_of_vertex: Vec<Option<u32>> = vec![None; n];
        let mut non_manifold = vec![false; n];
        for &t in &valid {
            let tri = mesh.triangles[t];
            if tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] {
                continue;
            }
            for (k, &v) in tri.iter().enumerate() {
                let root = corner_sets.find(3 * t + k) as u32;
                match fan_of_vertex[v as usize] {
                    None => fan_of_vertex[v as usize] = Some(root),
                    Some(r) if r != root => non_manifold[v as usize] = true,
                    Some(_) => {}
                }
            }
        }
        report.non_manifold_vertices = non_manifold.iter().filter(|&&b| b).count();
        report.components = (0..n as u32)
            .filter(|&v| used[v as usize] && vertex_sets.find(v as usize) == v as usize)
            .count();
        if report.invalid_triangles == 0 {
            report.signed_volume = mesh.signed_volume();
        }
        report
    }

    /// Closed: no boundary and no non-manifold edges after welding.
    pub fn is_closed(&self) -> bool {
        self.check().is_closed()
    }

    /// Closed, consistently wound, with a positive signed volume.
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// assert!(shapes::sphere(16, 8).is_outward());
    /// assert!(!shapes::sphere(16, 8).flipped().is_outward());
    /// ```
    pub fn is_outward(&self) -> bool {
        self.check().is_outward()
    }
}
