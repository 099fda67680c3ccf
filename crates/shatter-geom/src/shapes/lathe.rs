//! Unity's capsule and cylinder: surfaces of revolution about `y` with Unity's vertex
//! layout (seams and caps split, so the vertex counts match Unity's primitives).

use std::f64::consts::PI;

use glam::DVec3;

use crate::TriMesh;

/// Point at radius `r`, height `y` and angular step `i` of `segments`. The angle is taken
/// from `i % segments`, so a seam column is bit-identical to column 0 and welds with it.
pub(super) fn ring_point(r: f64, y: f64, i: usize, segments: usize) -> DVec3 {
    let phi = 2.0 * PI * (i % segments) as f64 / segments as f64;
    DVec3::new(r * phi.cos(), y, r * phi.sin())
}

/// Pushes a ring of `segments + 1` vertices (the last one repeats the first: a UV seam)
/// and returns the index of its first vertex.
pub(super) fn push_ring(positions: &mut Vec<DVec3>, r: f64, y: f64, segments: usize) -> u32 {
    let start = positions.len() as u32;
    positions.extend((0..=segments).map(|i| ring_point(r, y, i, segments)));
    start
}

/// Triangles of the band between two seam-split rings (`upper` above `lower`), wound
/// outward.
pub(super) fn push_band(triangles: &mut Vec<[u32; 3]>, upper: u32, lower: u32, segments: u32) {
    for i in 0..segments {
        let (a, b) = (upper + i, upper + i + 1);
        let (c, d) = (lower + i, lower + i + 1);
        triangles.push([a, b, c]);
        triangles.push([b, d, c]);
    }
}

/// Unity's capsule: radius 0.5, total height 2 (a unit-height cylinder between two
/// hemispheres), centred at the origin; 550 vertices like Unity's.
///
/// Layout: 22 segments around; each hemisphere has 11 rings down to its equator (23
/// vertices each, split at the seam) and a pole row of 22 vertices (one per pole
/// triangle); 968 triangles.
///
/// ```
/// use shatter_geom::shapes;
/// let c = shapes::capsule();
/// assert_eq!(c.positions.len(), 550);
/// let exact = std::f64::consts::PI * (0.25 + 0.5_f64.powi(3) * 4.0 / 3.0);
/// assert!((c.volume() - exact).abs() < 0.02 * exact);
/// ```
pub fn capsule() -> TriMesh {
    const SEGMENTS: usize = 22;
    const RINGS: usize = 11; // per hemisphere, the equator included
    let (radius, half) = (0.5, 0.5);
    let mut positions = Vec::with_capacity(550);
    let mut triangles = Vec::with_capacity(968);
    let top_pole = positions.len() as u32;
    positions.extend(std::iter::repeat_n(
        DVec3::new(0.0, half + radius, 0.0),
        SEGMENTS,
    ));
    let mut rings = Vec::with_capacity(2 * RINGS);
    for j in 1..=RINGS {
        let alpha = (PI / 2.0) * j as f64 / RINGS as f64;
        let (r, y) = (radius * alpha.sin(), half + radius * alpha.cos());
        rings.push(push_ring(&mut positions, r, y, SEGMENTS));
    }
    for j in 0..RINGS {
        let alpha = (PI / 2.0) * j as f64 / RINGS as f64;
        let (r, y) = (radius * alpha.cos(), -half - radius * alpha.sin());
        rings.push(push_ring(&mut positions, r, y, SEGMENTS));
    }
    let bottom_pole = positions.len() as u32;
    positions.extend(std::iter::repeat_n(
        DVec3::new(0.0, -half - radius, 0.0),
        SEGMENTS,
    ));

    let s = SEGMENTS as u32;
    for i in 0..s {
        triangles.push([top_pole + i, rings[0] + i + 1, rings[0] + i]);
    }
    for pair in rings.windows(2) {
        push_band(&mut triangles, pair[0], pair[1], s);
    }
    let last = rings[rings.len() - 1];
    for i in 0..s {
        triangles.push([last + i, last + i + 1, bottom_pole + i]);
    }
    TriMesh::new(positions, triangles)
}

/// Unity's cylinder: radius 0.5, height 2, centred at the origin; 88 vertices and 80
/// triangles like Unity's.
///
/// Layout: 20 segments; the side is two seam-split rings (42 vertices); each cap is a fan
/// of 20 triangles around a centre vertex with its own rim vertices, the rim split in two
/// halves (22 + 1 vertices per cap), so side and caps have separate normals.
///
/// ```
/// use shatter_geom::shapes;
/// let c = shapes::cylinder();
/// assert_eq!((c.positions.len(), c.triangles.len()), (88, 80));
/// // A prism: height × area of the regular 20-gon.
/// let exact = 2.0 * 10.0 * 0.25 * (std::f64::consts::PI / 10.0).sin();
/// assert!((c.volume() - exact).abs() < 1e-12);
/// ```
pub fn cylinder() -> TriMesh {
    const SEGMENTS: usize = 20;
    const HALF: usize = SEGMENTS / 2;
    let (radius, half) = (0.5, 1.0);
    let s = SEGMENTS as u32;
    let mut positions = Vec::with_capacity(88);
    let mut triangles = Vec::with_capacity(80);
    let top = push_ring(&mut positions, radius, half, SEGMENTS);
    let bottom = push_ring(&mut positions, radius, -half, SEGMENTS);
    push_band(&mut triangles, top, bottom, s);
    for (y, upward) in [(half, true), (-half, false)] {
        let centre = positions.len() as u32;
        positions.push(DVec3::new(0.0, y, 0.0));
        let first_half = positions.len() as u32;
        positions.extend((0..=HALF).map(|i| ring_point(radius, y, i, SEGMENTS)));
        let second_half = positions.len() as u32;
        positions.extend((HALF..=SEGMENTS).map(|i| ring_point(radius, y, i, SEGMENTS)));
        let rim = |i: usize| {
            if i <= HALF {
                first_half + i as u32
            } else {
                second_half + (i - HALF) as u32
            }
        };
        for i in 0..SEGMENTS {
            // Both corners of a cap triangle come from the same half.
            let (a, b) = if i < HALF {
                (rim(i), rim(i + 1))
            } else {
                (
                    second_half + (i - HALF) as u32,
                    second_half + (i + 1 - HALF) as u32,
                )
            };
            triangles.push(if upward {
                [centre, b, a]
            } else {
                [a, b, centre]
            });
        }
    }
    TriMesh::new(positions, triangles)
}
