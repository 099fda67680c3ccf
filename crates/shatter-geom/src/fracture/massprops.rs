//! Volume, centroid and inertia of closed triangle meshes, and a generalized winding
//! number for inside tests.
//!
//! Kept here (rather than calling the mesh module) so fracture has exactly the
//! formulas it needs on its welded working pieces.

use glam::{DMat3, DVec3};

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

/// Generalized winding number of the closed surface `tris` over `pos` around `p`
/// (1 inside, 0 outside, ½ on the surface), by the solid-angle formula of Van Oosterom
/// and Strackee.
pub(crate) fn winding_number(pos: &[DVec3], tris: &[[u32; 3]], p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in tris {
        let [a, b, c] = t.map(|i| pos[i as usize] - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let num = a.dot(b.cross(c));
        let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * num.atan2(den);
    }
    total / (4.0 * std::f64::consts::PI)
}
