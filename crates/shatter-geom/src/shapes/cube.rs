//! Unity's cube.

use glam::DVec3;

use crate::TriMesh;

/// Unity's cube: unit size, centred at the origin; 24 vertices (each corner split per
/// face, for flat normals) and 12 triangles.
///
/// ```
/// use shatter_geom::shapes;
/// let c = shapes::cube();
/// assert_eq!((c.positions.len(), c.triangles.len()), (24, 12));
/// assert_eq!(c.volume(), 1.0);
/// ```
pub fn cube() -> TriMesh {
    let mut positions = Vec::with_capacity(24);
    let mut triangles = Vec::with_capacity(12);
    // Each face: outward normal n and two in-plane axes u, v with u × v = n, so the
    // corners n/2 ± u/2 ± v/2 in the order (−,−) (+,−) (+,+) (−,+) wind counter-clockwise.
    for axis in 0..3 {
        for sign in [1.0, -1.0] {
            let n = DVec3::AXES[axis] * sign;
            let u = DVec3::AXES[(axis + 1) % 3] * sign;
            let v = n.cross(u);
            let base = positions.len() as u32;
            for (su, sv) in [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)] {
                positions.push((n + u * su + v * sv) * 0.5);
            }
            triangles.push([base, base + 1, base + 2]);
            triangles.push([base, base + 2, base + 3]);
        }
    }
    TriMesh::new(positions, triangles)
}
