//! UV sphere and torus.

use std::f64::consts::PI;

use glam::DVec3;

use super::lathe::{push_band, push_ring};
use crate::TriMesh;

/// UV sphere of radius 0.5 (Unity's sphere size) centred at the origin: `segments`
/// around (at least 3) and `rings` bands from pole to pole (at least 2). Single pole
/// vertices; rings split at the seam: `2 + (segments + 1)(rings − 1)` vertices,
/// `2·segments·(rings − 1)` triangles.
///
/// ```
/// use shatter_geom::shapes;
/// let s = shapes::sphere(64, 32);
/// assert_eq!(s.positions.len(), 2 + 65 * 31);
/// let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
/// assert!((s.volume() - exact).abs() < 0.01 * exact);
/// ```
pub fn sphere(segments: usize, rings: usize) -> TriMesh {
    let (segments, rings) = (segments.max(3), rings.max(2));
    let radius = 0.5;
    let mut positions = Vec::with_capacity(2 + (segments + 1) * (rings - 1));
    let mut triangles = Vec::with_capacity(2 * segments * (rings - 1));
    positions.push(DVec3::new(0.0, radius, 0.0));
    let starts: Vec<u32> = (1..rings)
        .map(|j| {
            let theta = PI * j as f64 / rings as f64;
            push_ring(
                &mut positions,
                radius * theta.sin(),
                radius * theta.cos(),
                segments,
            )
        })
        .collect();
    let bottom = positions.len() as u32;
    positions.push(DVec3::new(0.0, -radius, 0.0));
    let s = segments as u32;
    let (first, last) = (starts[0], starts[starts.len() - 1]);
    for i in 0..s {
        triangles.push([0, first + i + 1, first + i]);
        triangles.push([last + i, last + i + 1, bottom]);
    }
    for pair in starts.windows(2) {
        push_band(&mut triangles, pair[0], pair[1], s);
    }
    TriMesh::new(positions, triangles)
}

/// Torus about the `y` axis centred at the origin: tube centre-line radius `major`, tube
/// radius `minor` (`minor < major` for a valid solid), `major_segments` around the axis
/// and `minor_segments` around the tube (each at least 3), seams split:
/// `(major_segments + 1)(minor_segments + 1)` vertices. Its volume tends to
/// `2π²·major·minor²`.
///
/// ```
/// use shatter_geom::shapes;
/// let t = shapes::torus(1.0, 0.25, 64, 32);
/// let exact = 2.0 * std::f64::consts::PI.powi(2) * 0.0625;
/// assert!((t.volume() - exact).abs() < 0.01 * exact);
/// assert!(t.check().is_solid());
/// ```
pub fn torus(major: f64, minor: f64, major_segments: usize, minor_segments: usize) -> TriMesh {
    let (nu, nv) = (major_segments.max(3), minor_segments.max(3));
    let mut positions = Vec::with_capacity((nu + 1) * (nv + 1));
    let mut triangles = Vec::with_capacity(2 * nu * nv);
    // Rows run over the tube angle (from the outer equator over the top), each row a
    // seam-split ring about the axis, so the band helper winds them as for a lathe.
    let starts: Vec<u32> = (0..=nv)
        .map(|j| {
            let theta = 2.0 * PI * (j % nv) as f64 / nv as f64;
            let r = major + minor * theta.cos();
            let y = -minor * theta.sin();
            push_ring(&mut positions, r, y, nu)
        })
        .collect();
    for pair in starts.windows(2) {
        push_band(&mut triangles, pair[0], pair[1], nu as u32);
    }
    TriMesh::new(positions, triangles)
}
