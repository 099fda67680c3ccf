//! Test shapes and invariant checks shared by the fracture tests (included with
//! `#[path]`; also compiled on its own, where it has no tests).
#![allow(dead_code, clippy::unwrap_used)]

use std::collections::HashMap;

use shatter_geom::fracture::{Fracture, Fragment};
use shatter_geom::{DVec3, TriMesh};

/// An axis-aligned box with 24 vertices (4 per face, as Unity's cube).
pub fn box24(lo: DVec3, hi: DVec3) -> TriMesh {
    let c = |i: usize| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    };
    // Faces as corner indices, counter-clockwise from outside.
    let faces = [
        [0, 2, 3, 1], // -z
        [4, 5, 7, 6], // +z
        [0, 1, 5, 4], // -y
        [2, 6, 7, 3], // +y
        [0, 4, 6, 2], // -x
        [1, 3, 7, 5], // +x
    ];
    let mut pos = Vec::new();
    let mut tris = Vec::new();
    for f in faces {
        let b = pos.len() as u32;
        pos.extend(f.map(c));
        tris.push([b, b + 1, b + 2]);
        tris.push([b, b + 2, b + 3]);
    }
    TriMesh::new(pos, tris)
}

/// Extrudes a counter-clockwise simple polygon (triangulated as a fan from vertex
/// `fan`, which must see every other vertex) from `z0` to `z1`.
pub fn extrude(poly: &[(f64, f64)], fan: usize, z0: f64, z1: f64) -> TriMesh {
    let n = poly.len();
    let mut pos: Vec<DVec3> = poly.iter().map(|&(x, y)| DVec3::new(x, y, z0)).collect();
    pos.extend(poly.iter().map(|&(x, y)| DVec3::new(x, y, z1)));
    let mut tris = Vec::new();
    for k in 1..n - 1 {
        let (a, b) = ((fan + k) % n, (fan + k + 1) % n);
        tris.push([fan as u32, b as u32, a as u32]); // bottom, facing -z
        tris.push([(fan + n) as u32, (a + n) as u32, (b + n) as u32]); // top
    }
    for i in 0..n {
        let j = (i + 1) % n;
        let (i, j) = (i as u32, j as u32);
        let m = n as u32;
        tris.push([i, j, j + m]);
        tris.push([i, j + m, i + m]);
    }
    TriMesh::new(pos, tris)
}

/// The L-shaped block: the L of (0,0)-(2,0)-(2,1)-(1,1)-(1,2)-(0,2), 1 thick.
pub fn l_block() -> TriMesh {
    let l = [
        (0.0, 0.0),
        (2.0, 0.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ];
    extrude(&l, 3, 0.0, 1.0)
}

/// Volume of the L-block.
pub const L_VOLUME: f64 = 3.0;

/// A prism over a plane region from `z0` to `z1`: `points` (the boundary loop, counter-
/// clockwise, is `points[..boundary]`; any further points are inside) and the region's
/// counter-clockwise triangles `caps` over them.
pub fn prism(
    points: &[(f64, f64)],
    boundary: usize,
    caps: &[[u32; 3]],
    z0: f64,
    z1: f64,
) -> TriMesh {
    let n = points.len() as u32;
    let mut pos: Vec<DVec3> = points.iter().map(|&(x, y)| DVec3::new(x, y, z0)).collect();
    pos.extend(points.iter().map(|&(x, y)| DVec3::new(x, y, z1)));
    let mut tris = Vec::new();
    for &[a, b, c] in caps {
        tris.push([a, c, b]); // bottom, facing -z
        tris.push([a + n, b + n, c + n]); // top
    }
    for i in 0..boundary as u32 {
        let j = (i + 1) % boundary as u32;
        tris.push([i, j, j + n]);
        tris.push([i, j + n, i + n]);
    }
    TriMesh::new(pos, tris)
}

/// The U block: a 3 × 3 square without the notch 1 < x < 2, y > 1; 1 thick.
pub fn u_block() -> TriMesh {
    let u = [
        (0.0, 0.0),
        (3.0, 0.0),
        (3.0, 3.0),
        (2.0, 3.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 3.0),
        (0.0, 3.0),
    ];
    let caps = [
        [1, 2, 3],
        [1, 3, 4],
        [0, 1, 4],
        [0, 4, 5],
        [0, 5, 6],
        [0, 6, 7],
    ];
    prism(&u, 8, &caps, 0.0, 1.0)
}

/// Volume of the U block.
pub const U_VOLUME: f64 = 7.0;

/// A five-pointed star (tips at radius 1, inner corners at 0.4), 0.5 thick.
pub fn star() -> TriMesh {
    let mut pts: Vec<(f64, f64)> = (0..10)
        .map(|i| {
            let a = std::f64::consts::FRAC_PI_2 + i as f64 * std::f64::consts::PI / 5.0;
            let r = if i % 2 == 0 { 1.0 } else { 0.4 };
            (r * a.cos(), r * a.sin())
        })
        .collect();
    pts.push((0.0, 0.0));
    let caps: Vec<[u32; 3]> = (0..10).map(|i| [10, i, (i + 1) % 10]).collect();
    prism(&pts, 10, &caps, 0.0, 0.5)
}

/// Volume of the star: ten triangles of sides 1 and 0.4 at 36°, 0.5 thick.
pub fn star_volume() -> f64 {
    10.0 * 0.5 * 0.4 * (std::f64::consts::PI / 5.0).sin() * 0.5
}

/// A torus around the z axis (radii `big`, `small`), `nu × nv` quads.
pub fn torus(big: f64, small: f64, nu: usize, nv: usize) -> TriMesh {
    let mut pos = Vec::new();
    for i in 0..nu {
        let u = i as f64 / nu as f64 * std::f64::consts::TAU;
        for j in 0..nv {
            let v = j as f64 / nv as f64 * std::f64::consts::TAU;
            let r = big + small * v.cos();
            pos.push(DVec3::new(r * u.cos(), r * u.sin(), small * v.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    let mut tris = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            tris.push([a, b, c]);
            tris.push([a, c, d]);
        }
    }
    TriMesh::new(pos, tris)
}

/// Welds a mesh by exact position; returns positions and triangles.
pub fn weld(mesh: &TriMesh) -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let mut map: HashMap<[u64; 3], u32> = HashMap::new();
    let mut pos = Vec::new();
    let remap: Vec<u32> = mesh
        .positions
        .iter()
        .map(|p| {
            let key = [p.x + 0.0, p.y + 0.0, p.z + 0.0].map(f64::to_bits);
            *map.entry(key).or_insert_with(|| {
                pos.push(*p);
                (pos.len() - 1) as u32
            })
        })
        .collect();
    let tris = mesh
        .triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .collect();
    (pos, tris)
}

/// Asserts the mesh (after exact welding) is a closed 2-manifold by edges — every
/// directed edge used exactly once and its reverse exactly once, so every edge has two
/// triangles wound opposite ways — without degenerate (repeated-vertex) triangles, and
/// encloses a positive volume.
pub fn assert_closed_outward(mesh: &TriMesh, what: &str) {
    let (_, tris) = weld(mesh);
    let mut directed: HashMap<(u32, u32), usize> = HashMap::new();
    for t in &tris {
        assert!(
            t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
            "{what}: degenerate triangle {t:?}"
        );
        for k in 0..3 {
            *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
        }
    }
    for (&(a, b), &n) in &directed {
        assert_eq!(
            n, 1,
            "{what}: edge {a}->{b} used {n} times in one direction"
        );
        assert_eq!(
            directed.get(&(b, a)).copied().unwrap_or(0),
            1,
            "{what}: edge {a}->{b} has no reverse"
        );
    }
    assert!(mesh.signed_volume() > 0.0, "{what}: not outward");
}

/// Generalized winding number of a closed mesh around `p`.
pub fn winding(mesh: &TriMesh, p: DVec3) -> f64 {
    let mut total = 0.0;
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t).map(|x| x - p);
        let (la, lb, lc) = (a.length(), b.length(), c.length());
        let num = a.dot(b.cross(c));
        let den = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
        total += 2.0 * num.atan2(den);
    }
    total / (4.0 * std::f64::consts::PI)
}

/// Distance from `p` to triangle `abc`.
pub fn point_triangle_distance(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let n = (b - a).cross(c - a);
    let inside = [(a, b), (b, c), (c, a)]
        .iter()
        .all(|&(u, v)| (v - u).cross(p - u).dot(n) >= 0.0);
    if inside && n.length_squared() > 0.0 {
        return (p - a).dot(n).abs() / n.length();
    }
    [(a, b), (b, c), (c, a)]
        .iter()
        .map(|&(u, v)| {
            let d = v - u;
            let t = if d.length_squared() > 0.0 {
                ((p - u).dot(d) / d.length_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p - (u + d * t)).length()
        })
        .fold(f64::INFINITY, f64::min)
}

/// Is `p` inside `mesh` or within `tol` of its surface?
pub fn inside_or_on(mesh: &TriMesh, p: DVec3, tol: f64) -> bool {
    if winding(mesh, p) > 0.5 {
        return true;
    }
    (0..mesh.triangles.len()).any(|t| {
        let [a, b, c] = mesh.triangle(t);
        point_triangle_distance(p, a, b, c) <= tol
    })
}

/// Bounding-box diagonal.
pub fn diag(mesh: &TriMesh) -> f64 {
    let (lo, hi) = mesh.bounds().unwrap();
    (hi - lo).length()
}

/// Area of the interior-flagged triangles of a fragment.
pub fn interior_area(f: &Fragment) -> f64 {
    (0..f.mesh.triangles.len())
        .filter(|&t| f.interior[t])
        .map(|t| {
            let [a, b, c] = f.mesh.triangle(t);
            (b - a).cross(c - a).length() / 2.0
        })
        .sum()
}

/// Checks every invariant of a fracture of `mesh` (volume `volume`): closed, outward
/// fragments; volumes adding up within `vol_tol` (relative); vertices and face centroids
/// inside the mesh; nothing below the sliver threshold; convex pieces with volume;
/// bonds sorted, unique, with positive area equal to the interior area on both sides.
pub fn check_fracture(mesh: &TriMesh, volume: f64, fr: &Fracture, vol_tol: f64, what: &str) {
    check_fracture_with(mesh, volume, fr, vol_tol, true, what);
}

/// [`check_fracture`], with the test of face centroids optional (tetrahedra of a
/// concave mesh keep their vertices inside, but a face may cut a concave corner).
pub fn check_fracture_with(
    mesh: &TriMesh,
    volume: f64,
    fr: &Fracture,
    vol_tol: f64,
    faces_inside: bool,
    what: &str,
) {
    use shatter_geom::fracture::SLIVER_VOLUME_FRACTION;
    assert!(!fr.fragments.is_empty(), "{what}: no fragments");
    let d = diag(mesh);
    let mut total = 0.0;
    for (i, f) in fr.fragments.iter().enumerate() {
        let w = format!("{what}: fragment {i}");
        assert_eq!(f.interior.len(), f.mesh.triangles.len(), "{w}: flags");
        assert_closed_outward(&f.mesh, &w);
        let v = f.mesh.signed_volume();
        assert!(
            (v - f.volume).abs() <= 1e-9 * volume,
            "{w}: volume field {} vs {v}",
            f.volume
        );
        assert!(
            f.volume >= SLIVER_VOLUME_FRACTION * volume,
            "{w}: volume {} below the sliver threshold",
            f.volume
        );
        total += f.volume;
        for &p in &f.mesh.positions {
            assert!(
                inside_or_on(mesh, p, 1e-7 * d),
                "{w}: vertex {p} outside the mesh"
            );
        }
        for t in 0..f.mesh.triangles.len() {
            if !faces_inside {
                break;
            }
            let [a, b, c] = f.mesh.triangle(t);
            let g = (a + b + c) / 3.0;
            assert!(
                inside_or_on(mesh, g, 1e-7 * d),
                "{w}: face {t} outside the mesh"
            );
        }
        assert!(!f.convex_pieces.is_empty(), "{w}: no convex piece");
        for (k, piece) in f.convex_pieces.iter().enumerate() {
            assert!(
                piece.len() >= 4,
                "{w}: convex piece {k} has {} points",
                piece.len()
            );
            assert!(
                spread_volume(piece) > 1e-9 * volume,
                "{w}: convex piece {k} is flat"
            );
        }
        assert!(f.inertia.determinant() > 0.0, "{w}: inertia not positive");
    }
    assert!(
        (total - volume).abs() <= vol_tol * volume,
        "{what}: fragment volumes sum to {total}, mesh volume {volume}"
    );
    // Bonds: sorted, unique, a < b, valid indices, positive area, unit normal.
    for w in fr.bonds.windows(2) {
        assert!(
            (w[0].a, w[0].b) < (w[1].a, w[1].b),
            "{what}: bonds unsorted or repeated"
        );
    }
    let n = fr.fragments.len() as u32;
    let mut bonded_area = vec![0.0; fr.fragments.len()];
    for b in &fr.bonds {
        assert!(b.a < b.b && b.b < n, "{what}: bad bond {b:?}");
        assert!(b.area > 0.0, "{what}: bond without area");
        assert!(
            (b.normal.length() - 1.0).abs() < 1e-9,
            "{what}: bond normal"
        );
        bonded_area[b.a as usize] += b.area;
        bonded_area[b.b as usize] += b.area;
    }
    // Every interior face is shared: each side's interior area equals its bonds' area,
    // so every bond's area matches on both sides.
    // (A fragment of several shells — a sliver merged into the piece nearest to it —
    // may have caps facing a neighbour over less than the bonds' area threshold: there,
    // bonds cover at most its interior area.)
    for (i, f) in fr.fragments.iter().enumerate() {
        let ia = interior_area(f);
        let tol = 1e-6 * ia.max(d * d * 1e-6);
        assert!(
            !has_back_to_back(f),
            "{what}: fragment {i} has interior faces back to back"
        );
        if shells(&f.mesh) > 1 {
            assert!(
                bonded_area[i] <= ia + tol,
                "{what}: fragment {i} over-bonded"
            );
            continue;
        }
        assert!(
            (ia - bonded_area[i]).abs() <= tol,
            "{what}: fragment {i} interior area {ia} vs bonded area {}",
            bonded_area[i]
        );
    }
}

/// A lower bound of the volume spanned by a point cloud: the largest tetrahedron from
/// the first point and two extreme points (enough to tell flat from solid).
pub fn spread_volume(pts: &[DVec3]) -> f64 {
    let mut best: f64 = 0.0;
    let p0 = pts[0];
    let far = pts
        .iter()
        .copied()
        .max_by(|a, b| {
            (*a - p0)
                .length_squared()
                .total_cmp(&(*b - p0).length_squared())
        })
        .unwrap();
    let line = far - p0;
    let third = pts
        .iter()
        .copied()
        .max_by(|a, b| {
            line.cross(*a - p0)
                .length_squared()
                .total_cmp(&line.cross(*b - p0).length_squared())
        })
        .unwrap();
    let nrm = line.cross(third - p0);
    for &q in pts {
        best = best.max((q - p0).dot(nrm).abs() / 6.0);
    }
    best
}

/// Number of edge-connected shells of a mesh (after exact welding).
pub fn shells(mesh: &TriMesh) -> usize {
    let (_, tris) = weld(mesh);
    let mut parent: Vec<usize> = (0..tris.len()).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            p[x] = p[p[x]];
            x = p[x];
        }
        x
    }
    let mut owner: HashMap<(u32, u32), usize> = HashMap::new();
    for (t, tri) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (tri[k], tri[(k + 1) % 3]);
            if let Some(&o) = owner.get(&(a.min(b), a.max(b))) {
                let (ra, rb) = (find(&mut parent, o), find(&mut parent, t));
                parent[ra] = rb;
            } else {
                owner.insert((a.min(b), a.max(b)), t);
            }
        }
    }
    (0..tris.len())
        .filter(|&t| find(&mut parent, t) == t)
        .count()
}

/// Does the fragment have interior faces back to back (two interior triangles on the
/// same plane facing opposite ways, whose areas overlap)? That is what merging a small
/// piece into a neighbour left when the faces they shared were kept.
pub fn has_back_to_back(f: &Fragment) -> bool {
    let tris: Vec<(DVec3, f64, [DVec3; 3])> = (0..f.mesh.triangles.len())
        .filter(|&t| f.interior[t])
        .filter_map(|t| {
            let [a, b, c] = f.mesh.triangle(t);
            let n = (b - a).cross(c - a);
            (n.length() > 0.0).then(|| (n.normalize(), n.normalize().dot(a), [a, b, c]))
        })
        .collect();
    tris.iter().enumerate().any(|(i, &(n, d, p))| {
        tris[i + 1..].iter().any(|&(m, e, q)| {
            (n + m).length() < 1e-9 && (d + e).abs() < 1e-9 && overlap_2d(n, p, q)
        })
    })
}

/// Whether two triangles of one plane (normal `n`) overlap with positive area: no edge
/// direction of either separates them by more than rounding.
fn overlap_2d(n: DVec3, p: [DVec3; 3], q: [DVec3; 3]) -> bool {
    let u = n.any_orthonormal_vector();
    let v = n.cross(u);
    let flat = |t: [DVec3; 3]| t.map(|x| (x.dot(u), x.dot(v)));
    let (p, q) = (flat(p), flat(q));
    let size = p
        .iter()
        .chain(&q)
        .map(|&(x, y)| x.abs().max(y.abs()))
        .fold(0.0, f64::max);
    let tol = 1e-9 * size.max(1e-300);
    for t in [p, q] {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let axis = (b.1 - a.1, a.0 - b.0);
            let len = (axis.0 * axis.0 + axis.1 * axis.1).sqrt();
            if len == 0.0 {
                continue;
            }
            let proj = |s: &[(f64, f64); 3]| {
                s.iter()
                    .map(|&(x, y)| (x * axis.0 + y * axis.1) / len)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), w| {
                        (lo.min(w), hi.max(w))
                    })
            };
            let (a0, a1) = proj(&p);
            let (b0, b1) = proj(&q);
            if a1 <= b0 + tol || b1 <= a0 + tol {
                return false;
            }
        }
    }
    true
}

/// Per-corner UVs of `mesh`, each corner's `uv(position)` (a planar projection).
pub fn corner_uvs(mesh: &TriMesh, uv: impl Fn(DVec3) -> [f32; 2]) -> Vec<[[f32; 2]; 3]> {
    mesh.triangles
        .iter()
        .map(|t| t.map(|i| uv(mesh.positions[i as usize])))
        .collect()
}
