//! Checks shared by the fracture tests, written independently of the library's own:
//! triangle corners, barycentric coordinates, interior UVs across bonds, closedness on
//! welded positions, and overlap by sampled winding numbers.
#![allow(dead_code, clippy::unwrap_used)]

pub mod corpus;

use std::collections::HashMap;

use shatter_geom::fracture::{Fracture, Fragment};
use shatter_geom::{DVec3, TriMesh};

/// The corners of triangle `t`.
pub fn tri(mesh: &TriMesh, t: usize) -> [DVec3; 3] {
    mesh.triangles[t].map(|i| mesh.positions[i as usize])
}

/// Barycentric coordinates of `p` in `[a, b, c]` (plain solve, independent of the
/// library's).
pub fn bary([a, b, c]: [DVec3; 3], p: DVec3) -> [f64; 3] {
    let (v0, v1, v2) = (b - a, c - a, p - a);
    let (d00, d01, d11) = (v0.dot(v0), v0.dot(v1), v1.dot(v1));
    let (d20, d21) = (v2.dot(v0), v2.dot(v1));
    let den = d00 * d11 - d01 * d01;
    let v = (d11 * d20 - d01 * d21) / den;
    let w = (d00 * d21 - d01 * d20) / den;
    [1.0 - v - w, v, w]
}

/// `Σ wₖ·vₖ` of three corner values.
pub fn lerp<const N: usize>(v: &[[f32; N]; 3], w: [f64; 3]) -> [f64; N] {
    std::array::from_fn(|i| (0..3).map(|k| f64::from(v[k][i]) * w[k]).sum())
}

/// The UV of `uv` (per corner of `p`) at point `q` of the triangle.
pub fn uv_at(p: [DVec3; 3], uv: &[[f32; 2]; 3], q: DVec3) -> [f64; 2] {
    lerp(uv, bary(p, q))
}

/// The square of a triangle's longest edge.
fn longest_squared(p: [DVec3; 3]) -> f64 {
    (p[1] - p[0])
        .length_squared()
        .max((p[2] - p[1]).length_squared())
        .max((p[0] - p[2]).length_squared())
}

/// `2·area / longest²`: 0 for a sliver, about 0.87 for an equilateral triangle.
pub fn shape_quality(p: [DVec3; 3]) -> f64 {
    (p[1] - p[0]).cross(p[2] - p[0]).length() / longest_squared(p)
}

/// How many times `eps` a cap triangle's least altitude must be for
/// [`interior_uvs_agree`] to take its plane as known: at this size, a triangle within
/// `eps` of another's plane is tilted from it by at most 5e-4 rad, half the angle under
/// which the library gives two cap planes one UV basis (1e-3).
pub const PLANE_SIZE: f64 = 4e3;

/// A triangle's least altitude: twice its area over its longest edge.
pub fn least_altitude(p: [DVec3; 3]) -> f64 {
    (p[1] - p[0]).cross(p[2] - p[0]).length() / longest_squared(p).sqrt()
}

/// Whether [`interior_uvs_agree`] compares a cap triangle: not a sliver (shape quality
/// at least 1e-3) and wide enough for `eps` to fix its plane ([`PLANE_SIZE`]).
fn comparable(p: [DVec3; 3], eps: f64) -> bool {
    !(shape_quality(p) < 1e-3 || least_altitude(p) < PLANE_SIZE * eps)
}

/// Interior UVs across bonds: for every bond, every pair of cap triangles of its two
/// fragments that lie in one plane (within `eps`, normals opposite within 1.4e-4 rad)
/// facing each other, the UV both give
/// at the centroid of the first (where it is well inside the second) must agree within
/// `tol`. Slivers (shape quality below 1e-3) are left out on both sides: interpolating
/// `f32` UVs over a triangle a millionth as wide as it is long only measures rounding.
/// So are triangles whose least altitude is under [`PLANE_SIZE`] times `eps`: lying in
/// one plane within `eps` says which plane only for a triangle well wider than `eps` (on
/// the tetra method's engine, triangles 2e-5 wide, 30 `eps`, about a cluster of points
/// a rounding error apart, tilted 0.2 rad off their own cap's plane, lay within `eps`
/// of a cap of another plane, facing it). Panics naming
/// the bond otherwise; returns (points compared, bonds with at least one point compared).
pub fn interior_uvs_agree(fr: &Fracture, eps: f64, tol: f64, what: &str) -> (usize, usize) {
    let caps = |f: &Fragment| -> Vec<usize> {
        (0..f.mesh.triangles.len())
            .filter(|&t| f.interior[t])
            .collect()
    };
    let (mut compared, mut bonds_seen) = (0usize, 0usize);
    for bond in &fr.bonds {
        let (fa, fb) = (
            &fr.fragments[bond.a as usize],
            &fr.fragments[bond.b as usize],
        );
        let (uva, uvb) = (
            fa.corners.uv.as_ref().unwrap(),
            fb.corners.uv.as_ref().unwrap(),
        );
        let cb = caps(fb);
        let mut here = 0;
        for ta in caps(fa) {
            let pa = tri(&fa.mesh, ta);
            if !comparable(pa, eps) {
                continue;
            }
            let na = (pa[1] - pa[0]).cross(pa[2] - pa[0]);
            let Some(na) = na.try_normalize() else {
                continue;
            };
            let centre = (pa[0] + pa[1] + pa[2]) / 3.0;
            for &tb in &cb {
                let pb = tri(&fb.mesh, tb);
                let coplanar = pb.iter().all(|&q| na.dot(q - pa[0]).abs() <= eps);
                // Facing each other: opposite normals (not merely within `eps` of one
                // plane, which any triangles a few `eps` across are).
                let nb = (pb[1] - pb[0]).cross(pb[2] - pb[0]).normalize_or_zero();
                if !coplanar || nb.dot(na) > -(1.0 - 1e-8) || !comparable(pb, eps) {
                    continue;
                }
                let w = bary(pb, centre);
                if w.iter().any(|&x| x < 1e-6) {
                    continue;
                }
                let from_a = uv_at(pa, &uva[ta], centre);
                let from_b = uv_at(pb, &uvb[tb], centre);
                assert!(
                    (from_a[0] - from_b[0]).abs() < tol && (from_a[1] - from_b[1]).abs() < tol,
                    "{what}: bond {}-{}: {from_a:?} on one side (triangle {ta}: {pa:?}, \
                     UVs {:?}), {from_b:?} on the other (triangle {tb}: {pb:?}, UVs {:?})",
                    bond.a,
                    bond.b,
                    uva[ta],
                    uvb[tb]
                );
                here += 1;
            }
        }
        compared += here;
        bonds_seen += usize::from(here > 0);
    }
    (compared, bonds_seen)
}

/// Whether `mesh` is a closed 2-manifold in the sense the project uses: on positions
/// welded by their exact bits, every directed edge occurs exactly once and its reverse
/// exactly once (so each edge has two triangles wound opposite ways), and no triangle
/// repeats a corner. Returns the first defect.
pub fn closed_defect(mesh: &TriMesh) -> Option<String> {
    let mut id: HashMap<[u64; 3], u32> = HashMap::new();
    let welded: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let next = id.len() as u32;
            *id.entry([p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
                .or_insert(next)
        })
        .collect();
    let mut directed: HashMap<(u32, u32), u32> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let v = tri.map(|i| welded[i as usize]);
        if v[0] == v[1] || v[1] == v[2] || v[0] == v[2] {
            return Some(format!("triangle {t} repeats a corner"));
        }
        for k in 0..3 {
            *directed.entry((v[k], v[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        if n != 1 {
            return Some(format!("edge {a}->{b} occurs {n} times"));
        }
        if directed.get(&(b, a)) != Some(&1) {
            return Some(format!("edge {a}->{b} has no reverse"));
        }
    }
    None
}

/// Generalized winding number of `mesh` at `p` (solid angles, Van Oosterom–Strackee),
/// written here rather than taken from the library.
pub fn winding(mesh: &TriMesh, p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = tri(mesh, t).map(|q| q - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let num = a.dot(b.cross(c));
        let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * num.atan2(den);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Samples points (a fixed sequence): `n` in the bounds of `solid`, and `n` more in the
/// bounds of fragments (spread over them), where a thin model's solid is; checks that no
/// point is inside two fragments, that a point clearly inside the solid is inside one,
/// and that a point outside it is in none. Points within a winding number of 0.02 of a
/// boundary are skipped. Returns how many points were inside the solid; panics on an
/// overlap, a gap or a fragment outside the solid.
pub fn no_overlap_no_gap(solid: &TriMesh, fr: &Fracture, n: usize, what: &str) -> usize {
    let bounds = |m: &TriMesh| {
        m.positions.iter().fold(
            (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
            |(lo, hi), &p| (lo.min(p), hi.max(p)),
        )
    };
    let (lo, hi) = bounds(solid);
    let boxes: Vec<(DVec3, DVec3)> = fr.fragments.iter().map(|f| bounds(&f.mesh)).collect();
    let mut state = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut inside = 0;
    for i in 0..2 * n {
        let (lo, hi) = if i < n || boxes.is_empty() {
            (lo, hi)
        } else {
            boxes[(i - n) * boxes.len() / n]
        };
        let p = lo + (hi - lo) * DVec3::new(next(), next(), next());
        let ws = winding(solid, p);
        if (ws - 0.5).abs() < 0.48 {
            continue;
        }
        let mut claims = 0;
        let mut ambiguous = false;
        for (f, (blo, bhi)) in fr.fragments.iter().zip(&boxes) {
            if p.cmplt(*blo).any() || p.cmpgt(*bhi).any() {
                continue;
            }
            let w = winding(&f.mesh, p);
            if (w - 0.5).abs() < 0.48 {
                ambiguous = true;
            } else if w > 0.5 {
                claims += 1;
            }
        }
        if ambiguous {
            continue;
        }
        assert!(
            claims <= 1,
            "{what}: point {p} is inside {claims} fragments"
        );
        if ws > 0.5 {
            inside += 1;
            assert_eq!(
                claims, 1,
                "{what}: point {p} inside the solid is in no fragment"
            );
        } else {
            assert_eq!(
                claims, 0,
                "{what}: point {p} outside the solid is in a fragment"
            );
        }
    }
    inside
}
