//! Mass properties of a closed mesh: volume and inertia tensor (unit density).
//!
//! The solid is decomposed into signed tetrahedra, one per triangle, with a common apex
//! at the first vertex (for precision). Each tetrahedron's second moment is integrated
//! exactly, so the results are exact for any closed polyhedron up to rounding.

use glam::{DMat3, DVec3};

use super::TriMesh;

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
        let Some(&o) = self.positions.first() else {
            return DMat3::ZERO;
        };
        let mut cov = DMat3::ZERO;
        let mut v6 = 0.0;
        let mut first = DVec3::ZERO;
        for t in 0..self.triangles.len() {
            let [a, b, c] = self.triangle(t);
            let (a, b, c) = (a - o, b - o, c - o);
            let det = a.dot(b.cross(c));
            v6 += det;
            first += det * (a + b + c);
            // A·M·Aᵀ with M = [[2,1,1],[1,2,1],[1,1,2]] = sum of outer products
            // x xᵀ over the columns plus (a+b+c)(a+b+c)ᵀ.
            let s = a + b + c;
            let amat = outer(a, a) + outer(b, b) + outer(c, c) + outer(s, s);
            cov += amat * (det / 120.0);
        }
        let mass = v6 / 6.0;
        if mass == 0.0 {
            return DMat3::ZERO;
        }
        // First moment: Σ det/6 · (a+b+c)/4 = Σ det (a+b+c) / 24.
        let com = first / 24.0 / mass;
        let centred = cov - outer(com, com) * mass;
        let trace = centred.x_axis.x + centred.y_axis.y + centred.z_axis.z;
        DMat3::from_diagonal(DVec3::splat(trace)) - centred
    }
}

fn outer(a: DVec3, b: DVec3) -> DMat3 {
    DMat3::from_cols(a * b.x, a * b.y, a * b.z)
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
