//! Generalized winding number (Jacobson et al. 2013) by solid angles.

use glam::DVec3;

use super::TriMesh;

/// Solid angle subtended by triangle `a b c` seen from the origin (signed: positive when
/// the triangle is wound counter-clockwise seen from the origin's outside, i.e. its
/// right-hand normal points away from the origin). Van Oosterom–Strackee formula.
pub(crate) fn solid_angle(a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let numerator = a.dot(b.cross(c));
    if numerator == 0.0 {
        // Seen edge-on (the point in the triangle's plane): no solid angle. On the
        // triangle itself this takes the mean of the limits ±2π from either side.
        return 0.0;
    }
    let denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
    2.0 * numerator.atan2(denominator)
}

/// Generalized winding number of the surface `tris` over `pos` around `p` (see
/// [`TriMesh::winding_number`]).
pub(crate) fn winding_number(pos: &[DVec3], tris: &[[u32; 3]], p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in tris {
        let [a, b, c] = t.map(|i| pos[i as usize] - p);
        total += solid_angle(a, b, c);
    }
    total / (4.0 * std::f64::consts::PI)
}

impl TriMesh {
    /// Generalized winding number of `p`: the solid angle the outward surface subtends at
    /// `p`, over 4π. For a closed outward mesh it is 1 inside, 0 outside (½ on the
    /// surface where the point's coplanarity with its triangle is computed exactly; on
    /// other surface points it is either value), and it degrades gracefully on meshes with small holes. Cost: one
    /// `atan2` per triangle.
    ///
    /// ```
    /// use shatter_geom::{DVec3, shapes};
    /// let cube = shapes::cube();
    /// assert!((cube.winding_number(DVec3::ZERO) - 1.0).abs() < 1e-9);
    /// assert!(cube.winding_number(DVec3::splat(2.0)).abs() < 1e-9);
    /// ```
    pub fn winding_number(&self, p: DVec3) -> f64 {
        winding_number(&self.positions, &self.triangles, p)
    }

    /// Whether `p` is inside: winding number above ½.
    ///
    /// ```
    /// use shatter_geom::{DVec3, shapes};
    /// let torus = shapes::torus(1.0, 0.25, 32, 12);
    /// assert!(torus.contains(DVec3::new(1.0, 0.0, 0.0)));
    /// assert!(!torus.contains(DVec3::ZERO)); // the hole
    /// ```
    pub fn contains(&self, p: DVec3) -> bool {
        self.winding_number(p) > 0.5
    }
}
