//! Mass properties of a closed mesh: volume and inertia tensor (unit density).
//!
//! The solid is decomposed into signed tetrahedra, one per triangle, with a common apex
//! at the first vertex (for precision). Each tetrahedron's second moment is integrated
//! exactly, so the results are exact for any closed polyhedron up to rounding.

use glam::{DMat3, DVec3};

use super::TriMesh;

/// Volume, centroid and inertia tensor (about the centroid, unit density) of the solid
/// bounded by `tris` over `pos` (closed, outward).
pub(crate) fn mass_properties(pos: &[DVec3], tris: &[[u32; 3]]) -> (f64, DVec3, DMat3) {
    let Some(&o) = pos.first() else {
        return (0.0, DVec3::ZERO, DMat3::ZERO);
    };
    // Pass 1: volume and centroid, with the first vertex as origin for precision.
    let mut v6 = 0.0;
    let mut acc = DVec3::ZERO;
    for t in tris {
        let [a, b, c] = t.map(|i| pos[i as usize] - o);
        let d = a.dot(b.cross(c));
        v6 += d;
        acc += d * (a + b + c);
    }
    if v6 == 0.0 {
        let mean = pos.iter().copied().sum::<DVec3>() / pos.len() as f64;
        return (0.0, mean, DMat3::ZERO);
    }
    let centroid = o + acc / (4.0 * v6);
    // Pass 2: covariance about the centroid, summing signed tetrahedra (centroid, a, b, c):
    // C = det/120 · (Σ pᵢpᵢᵀ + (Σ pᵢ)(Σ pᵢ)ᵀ) with p the three corners.
    let mut cov = DMat3::ZERO;
    for t in tris {
        let [a, b, c] = t.map(|i| pos[i as usize] - centroid);
        let d = a.dot(b.cross(c));
        let s = a + b + c;
        let outer = |x: DVec3, y: DVec3| DMat3::from_cols(x * y.x, x * y.y, x * y.z);
        cov += (outer(a, a) + outer(b, b) + outer(c, c) + outer(s, s)) * (d / 120.0);
    }
    let tr = cov.x_axis.x + cov.y_axis.y + cov.z_axis.z;
    let inertia = DMat3::from_diagonal(DVec3::splat(tr)) - cov;
    (v6 / 6.0, centroid, inertia)
}

impl TriMesh {
    /// Volume enclosed by a closed mesh: the absolute value of
    /// [`signed_volume`](TriMesh::signed_volume).
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// assert_eq!(shapes::cube().volume(), 1.0);
    /// ```
    pub fn volume(&self) -> f64 {
        self.signed_volume().abs()
    }

    /// Inertia tensor about the centroid for unit density (multiply by the density for a
    /// real material). Exact polyhedral integration: each triangle with the apex forms a
    /// tetrahedron whose covariance `det(A)/120 · A·M·Aᵀ` (`M` = 1 + identity) is summed,
    /// shifted to the centroid by the parallel-axis theorem, and turned into the inertia
    /// `tr(C)·I − C`. An inward mesh gives the negated tensor.
    ///
    /// ```
    /// use shatter_geom::{DVec3, shapes};
    /// // A 2 × 1 × 1 box: Ixx = m(b² + c²)/12 with m = 2.
    /// let b = shapes::cube().transformed(DVec3::new(2.0, 1.0, 1.0), DVec3::ZERO);
    /// let i = b.inertia();
    /// assert!((i.x_axis.x - 2.0 * 2.0 / 12.0).abs() < 1e-12);
    /// assert!((i.y_axis.y - 2.0 * 5.0 / 12.0).abs() < 1e-12);
    /// ```
    pub fn inertia(&self) -> DMat3 {
        mass_properties(&self.positions, &self.triangles).2
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_tetrahedron_inertia_is_symmetric_and_positive() {
        let m = TriMesh::new(
            vec![DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z],
            vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]],
        );
        let i = m.inertia();
        // Known values for the unit corner tetrahedron about its centroid:
        // Ixx = 1/80 (mass 1/6), products = 1/480.
        assert!((i.x_axis.x - 1.0 / 80.0).abs() < 1e-14, "{i:?}");
        assert!((i.y_axis.x - 1.0 / 480.0).abs() < 1e-14, "{i:?}");
        assert_eq!(i, i.transpose());
    }
}
