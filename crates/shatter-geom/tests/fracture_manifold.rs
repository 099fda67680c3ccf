//! Every fragment of every cut method is a closed 2-manifold, also after small pieces
//! were merged into a neighbour (issue 14 part 1: the faces two merged pieces share
//! must cancel, not stay inside the fragment back to back), on concave meshes where
//! merging happens most.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shapes::*;
use shatter_geom::fracture::{FractureParams, Method, Pattern, fracture};
use shatter_geom::{TriMesh, shapes as builtin};

/// A U: a 3 × 2 block with a 1 × 1 notch, 1 thick.
fn u_block() -> TriMesh {
    let u = [
        (0.0, 0.0),
        (3.0, 0.0),
        (3.0, 2.0),
        (2.0, 2.0),
        (2.0, 1.0),
        (1.0, 1.0),
        (1.0, 2.0),
        (0.0, 2.0),
    ];
    extrude_star_free(&u)
}

/// Extrudes a simple polygon by ear clipping (the shared `extrude` needs a fan vertex
/// that sees all others, which a U or a star does not have).
fn extrude_star_free(poly: &[(f64, f64)]) -> TriMesh {
    use shatter_geom::DVec3;
    let n = poly.len();
    let mut idx: Vec<usize> = (0..n).collect();
    let mut caps: Vec<[usize; 3]> = Vec::new();
    let cross = |o: (f64, f64), a: (f64, f64), b: (f64, f64)| {
        (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
    };
    while idx.len() > 3 {
        let m = idx.len();
        let ear = (0..m)
            .find(|&k| {
                let (a, b, c) = (idx[(k + m - 1) % m], idx[k], idx[(k + 1) % m]);
                cross(poly[a], poly[b], poly[c]) > 0.0
                    && idx.iter().all(|&o| {
                        o == a
                            || o == b
                            || o == c
                            || !(cross(poly[a], poly[b], poly[o]) >= 0.0
                                && cross(poly[b], poly[c], poly[o]) >= 0.0
                                && cross(poly[c], poly[a], poly[o]) >= 0.0)
                    })
            })
            .unwrap();
        caps.push([idx[(ear + m - 1) % m], idx[ear], idx[(ear + 1) % m]]);
        idx.remove(ear);
    }
    caps.push([idx[0], idx[1], idx[2]]);
    let mut pos: Vec<DVec3> = poly.iter().map(|&(x, y)| DVec3::new(x, y, 0.0)).collect();
    pos.extend(poly.iter().map(|&(x, y)| DVec3::new(x, y, 1.0)));
    let mut tris = Vec::new();
    for [a, b, c] in caps {
        let (a, b, c) = (a as u32, b as u32, c as u32);
        let m = n as u32;
        tris.push([a, c, b]);
        tris.push([a + m, b + m, c + m]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        let (i, j, m) = (i as u32, j as u32, n as u32);
        tris.push([i, j, j + m]);
        tris.push([i, j + m, i + m]);
    }
    TriMesh::new(pos, tris)
}

/// A five-pointed star prism (radii 2 and 0.8), 1 thick.
fn star() -> TriMesh {
    let pts: Vec<(f64, f64)> = (0..10)
        .map(|k| {
            let a = std::f64::consts::PI * k as f64 / 5.0;
            let r = if k % 2 == 0 { 2.0 } else { 0.8 };
            (r * a.cos(), r * a.sin())
        })
        .collect();
    extrude_star_free(&pts)
}

fn concave_meshes() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("L block", l_block()),
        ("U block", u_block()),
        ("star", star()),
        ("torus", torus(1.0, 0.35, 24, 12)),
        ("bird", builtin::bird()),
    ]
}

fn run(mesh: &TriMesh, method: Method, seed: u64, what: &str) -> usize {
    let params = FractureParams { method, seed };
    let fr = fracture(mesh, &params).unwrap();
    let volume = mesh.signed_volume();
    check_fracture(mesh, volume, &fr, 1e-9, what);
    fr.fragments.len()
}

#[test]
fn slices_of_concave_meshes_are_closed_2_manifolds_without_inner_faces() {
    for (name, mesh) in concave_meshes() {
        for seed in 0..3 {
            run(
                &mesh,
                Method::Slice {
                    pieces: 12,
                    planes: None,
                },
                seed,
                &format!("{name} slice seed {seed}"),
            );
        }
    }
}

#[test]
fn clustered_voronoi_of_concave_meshes_is_closed_2_manifolds() {
    for (name, mesh) in concave_meshes() {
        for (pattern, pieces) in [(Pattern::Clustered, 40), (Pattern::Uniform, 40)] {
            for seed in 0..2 {
                run(
                    &mesh,
                    Method::Voronoi {
                        pieces,
                        pattern,
                        impact: None,
                        seeds: None,
                    },
                    seed,
                    &format!("{name} voronoi {pattern:?} seed {seed}"),
                );
            }
        }
    }
}
