//! Every fragment of every cut method is a closed 2-manifold, also after small pieces
//! were merged into a neighbour (issue 14 part 1: the faces two merged pieces share
//! must cancel, not stay inside the fragment back to back), on concave meshes where
//! merging happens most.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shapes::*;
use shatter_geom::fracture::{FractureParams, Method, Pattern, Seeds, fracture};
use shatter_geom::{TriMesh, shapes as builtin};

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
                        seeds: Seeds::Pattern {
                            count: pieces,
                            pattern,
                            impact: None,
                        },
                    },
                    seed,
                    &format!("{name} voronoi {pattern:?} seed {seed}"),
                );
            }
        }
    }
}
