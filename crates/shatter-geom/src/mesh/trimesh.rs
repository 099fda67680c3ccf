//! The indexed triangle mesh type.

use glam::DVec3;

/// An indexed triangle mesh.
///
/// Convention: triangles are wound counter-clockwise when seen from outside, so the
/// right-hand normal `(b - a) × (c - a)` points out of a closed, outward mesh and its
/// signed volume is positive.
///
/// ```
/// use shatter_geom::{DVec3, TriMesh};
/// // A unit right tetrahedron, wound outward.
/// let mesh = TriMesh::new(
///     vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
///     vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
/// );
/// assert!((mesh.signed_volume() - 1.0 / 6.0).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    /// Vertex positions.
    pub positions: Vec<DVec3>,
    /// Triangles as three indices into `positions`.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// A mesh from positions and triangles (not validated; see the checks in this module).
    pub fn new(positions: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Self {
        Self {
            positions,
            triangles,
        }
    }

    /// The three corner positions of triangle `t`.
    pub fn triangle(&self, t: usize) -> [DVec3; 3] {
        let [a, b, c] = self.triangles[t];
        [
            self.positions[a as usize],
            self.positions[b as usize],
            self.positions[c as usize],
        ]
    }

    /// Signed volume enclosed by the mesh (positive for a closed outward mesh).
    pub fn signed_volume(&self) -> f64 {
        // Sum of signed tetrahedra (origin shifted to the first vertex for precision).
        let Some(&o) = self.positions.first() else {
            return 0.0;
        };
        let mut v = 0.0;
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.triangle(t);
            v += (a - o).dot((b - o).cross(c - o));
        }
        v / 6.0
    }

    /// Centroid of the enclosed solid (of a closed mesh). Falls back to the vertex mean
    /// when the volume is zero.
    pub fn centroid(&self) -> DVec3 {
        let Some(&o) = self.positions.first() else {
            return DVec3::ZERO;
        };
        let mut v6 = 0.0;
        let mut acc = DVec3::ZERO;
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.triangle(t);
            let d = (a - o).dot((b - o).cross(c - o));
            v6 += d;
            acc += d * (a + b + c - 3.0 * o) / 4.0;
        }
        if v6.abs() > 0.0 {
            o + acc / v6
        } else {
            self.positions.iter().copied().sum::<DVec3>() / self.positions.len() as f64
        }
    }

    /// Axis-aligned bounds `(min, max)`, or `None` for a mesh without vertices.
    pub fn bounds(&self) -> Option<(DVec3, DVec3)> {
        let first = *self.positions.first()?;
        Some(
            self.positions
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }
}
