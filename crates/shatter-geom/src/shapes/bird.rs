//! The bird: the thesis's concave custom test model (there a 958-vertex, 1394-triangle
//! Unity import), rebuilt procedurally.
//!
//! Construction: a loft along `x` (tail at −x, beak at +x) of 41 cross-sections, each a
//! star-shaped polygon of 17 samples around a centre, closed by a pointed tip at each end.
//! Wings and tail are pulled out of the sections at the two near-horizontal samples. Such
//! a loft (sections in distinct parallel planes, star-shaped about their centres, angles
//! shared) is always a closed, manifold, non-self-intersecting genus-0 surface: the
//! section of every band at any `x` is again a star-shaped polygon, so no two triangles
//! cross. That gives 17·41 + 2 = 699 distinct vertices and 2·17·41 = 1394 triangles.
//! Like a Unity import, vertices are then split between the parts (tail, body, wings,
//! head, beak) for separate smoothing groups, which brings the count near 958.

use std::collections::HashMap;
use std::f64::consts::PI;

use glam::DVec3;

use crate::TriMesh;

/// Sample angles around a section, in degrees from `+y` towards `+z`; mirror-symmetric
/// about the `xy` plane. Samples 88° and 92° (and 268°, 272°) carry the wings and tail.
const ANGLES: [f64; 17] = [
    0.0, 25.0, 50.0, 70.0, 88.0, 92.0, 112.0, 138.0, 162.0, 198.0, 222.0, 248.0, 268.0, 272.0,
    290.0, 310.0, 335.0,
];
/// Indices into [`ANGLES`] of the near-horizontal samples.
const SIDE_SAMPLES: [usize; 4] = [4, 5, 12, 13];

/// Smoothstep of `x` from `a` to `b`.
fn smoothstep(a: f64, b: f64, x: f64) -> f64 {
    let t = ((x - a) / (b - a)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// Cross-section at `x`: centre height, vertical and horizontal semi-axes, and how far the
/// side samples reach beyond the ellipse (wings and tail).
struct Section {
    centre_y: f64,
    semi_y: f64,
    semi_z: f64,
    side_reach: f64,
}

fn section(x: f64) -> Section {
    // Body: an ellipsoid from x = −1.0 to 0.7.
    let body = (1.0 - ((x + 0.15) / 0.85).powi(2)).max(0.0).sqrt();
    // Head: a ball of radius 0.24 at x = 0.95, raised.
    let head = 0.24 * (1.0 - ((x - 0.95) / 0.24).powi(2)).max(0.0).sqrt();
    // Beak: a cone from x = 1.1.
    let beak = if x > 1.05 {
        0.1 - 0.25 * (x - 1.05)
    } else {
        0.0
    };
    // Neck and tail keep a minimum thickness.
    let neck = 0.12;
    let tail = 0.045;
    let minimum = if x < -0.8 { tail } else { neck };
    let semi_y = (0.32 * body).max(head).max(beak).max(minimum);
    let semi_z = (0.37 * body).max(head).max(0.8 * beak).max(minimum * 1.4);
    let centre_y = 0.28 * smoothstep(0.45, 0.85, x) - 0.03 * smoothstep(1.15, 1.45, x)
        + 0.06 * smoothstep(-0.9, -1.5, x);
    // Wings: swept-back planform over x ∈ [−0.55, 0.35], reach up to 1.25.
    let wing = if (-0.55..=0.35).contains(&x) {
        let u = (x + 0.55) / 0.9;
        1.25 * (PI * u.powf(0.7)).sin().max(0.0).powf(0.8)
    } else {
        0.0
    };
    // Tail: a fan widening towards the back from x = −0.85.
    let tail_fan = if x < -0.85 {
        0.12 + 0.4 * ((-0.85 - x) / 0.7).min(1.0)
    } else {
        0.0
    };
    Section {
        centre_y,
        semi_y,
        semi_z,
        side_reach: wing + tail_fan,
    }
}

/// The `x` of every section: tail, body (with the wings), neck and head, beak.
fn stations() -> Vec<f64> {
    let mut xs = Vec::with_capacity(41);
    let mut span = |from: f64, to: f64, n: usize| {
        xs.extend((0..n).map(|i| from + (to - from) * i as f64 / (n - 1) as f64));
    };
    span(-1.55, -0.95, 7);
    span(-0.85, 0.55, 19);
    span(0.65, 1.15, 10);
    span(1.22, 1.46, 5);
    xs
}

/// Part labels for splitting vertices like an imported model's smoothing groups.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
enum Part {
    /// Tail, body, head and beak are each split into their `+z` (0) and `−z` (1) halves
    /// along the top and bottom centre lines, like a mirrored UV layout.
    Tail(u8),
    Body(u8),
    /// A wing surface: side (0 = +z, 1 = −z) and face (0 upper, 1 tip, 2 lower).
    Wing(u8, u8),
    Head(u8),
    /// Beak half and jaw (0 upper, 1 lower: samples 88° to 272°).
    Beak(u8, u8),
}

/// Which jaw (upper 0, lower 1) a beak triangle starting at sample `k` belongs to.
fn jaw(k: u32) -> u8 {
    u8::from((4..13).contains(&k))
}

/// Which half (`+z` = 0, `−z` = 1) a triangle starting at sample `k` lies in.
fn half(k: u32) -> u8 {
    u8::from(k >= 9)
}

/// The bird: a closed, concave low-poly bird (body, head with beak, two swept wings, a
/// fan tail), about 3 units long and 3 wide, facing `+x` with `+y` up; 1394 triangles
/// and 699 distinct vertex positions, split between its parts into 956 vertices
/// (the thesis's model has 958 / 1394).
///
/// ```
/// use shatter_geom::{DVec3, shapes};
/// let bird = shapes::bird();
/// assert_eq!(bird.triangles.len(), 1394);
/// assert!(bird.check().is_solid());
/// // Concave: between a wing and the tail is outside the bird.
/// assert!(!bird.contains(DVec3::new(-0.7, 0.0, 0.8)));
/// assert!(bird.contains(DVec3::new(0.0, 0.0, 0.0)));
/// ```
pub fn bird() -> TriMesh {
    let xs = stations();
    let n = ANGLES.len();
    let mut positions = Vec::with_capacity(xs.len() * n + 2);
    let mut rings = Vec::with_capacity(xs.len());
    for &x in &xs {
        let s = section(x);
        rings.push(positions.len() as u32);
        for (k, deg) in ANGLES.iter().enumerate() {
            let theta = deg.to_radians();
            let (c, sn) = (theta.cos(), theta.sin());
            let ellipse = 1.0 / ((c / s.semi_y).powi(2) + (sn / s.semi_z).powi(2)).sqrt();
            let reach = if SIDE_SAMPLES.contains(&k) {
                s.side_reach
            } else {
                0.0
            };
            let r = ellipse + reach;
            positions.push(DVec3::new(x, s.centre_y + r * c, r * sn));
        }
    }
    let tail_tip = positions.len() as u32;
    positions.push(DVec3::new(-1.65, section(-1.55).centre_y, 0.0));
    let beak_tip = positions.len() as u32;
    positions.push(DVec3::new(1.6, section(1.46).centre_y, 0.0));

    let wing_rings = xs
        .iter()
        .map(|&x| (-0.55..=0.35).contains(&x))
        .collect::<Vec<_>>();
    let ring_part = |i: usize, k: u32| match i {
        0..=6 => Part::Tail(half(k)),
        7..=25 => Part::Body(half(k)),
        26..=35 => Part::Head(half(k)),
        _ => Part::Beak(half(k), jaw(k)),
    };
    let mut triangles = Vec::with_capacity(2 * n * xs.len());
    let mut parts = Vec::with_capacity(2 * n * xs.len());
    let n32 = n as u32;
    for k in 0..n32 {
        let k1 = (k + 1) % n32;
        triangles.push([tail_tip, rings[0] + k1, rings[0] + k]);
        parts.push(Part::Tail(half(k)));
    }
    for i in 0..xs.len() - 1 {
        let (up, lo) = (rings[i], rings[i + 1]);
        for k in 0..n32 {
            let k1 = (k + 1) % n32;
            let part = if wing_rings[i] && wing_rings[i + 1] {
                match k {
                    3 => Part::Wing(0, 0),
                    4 => Part::Wing(0, 1),
                    5 => Part::Wing(0, 2),
                    11 => Part::Wing(1, 2),
                    12 => Part::Wing(1, 1),
                    13 => Part::Wing(1, 0),
                    _ => ring_part(i, k),
                }
            } else {
                ring_part(i, k)
            };
            triangles.push([up + k, up + k1, lo + k]);
            triangles.push([up + k1, lo + k1, lo + k]);
            parts.extend([part, part]);
        }
    }
    let last = rings[xs.len() - 1];
    for k in 0..n32 {
        let k1 = (k + 1) % n32;
        triangles.push([last + k, last + k1, beak_tip]);
        parts.push(Part::Beak(half(k), jaw(k)));
    }
    split_by_part(&positions, &triangles, &parts)
}

/// Gives each part its own copy of every vertex it uses.
fn split_by_part(positions: &[DVec3], triangles: &[[u32; 3]], parts: &[Part]) -> TriMesh {
    let mut copies: HashMap<(u32, Part), u32> = HashMap::new();
    let mut out = TriMesh::default();
    for (tri, &part) in triangles.iter().zip(parts) {
        let t = tri.map(|v| {
            *copies.entry((v, part)).or_insert_with(|| {
                out.positions.push(positions[v as usize]);
                (out.positions.len() - 1) as u32
            })
        });
        out.triangles.push(t);
    }
    out
}
