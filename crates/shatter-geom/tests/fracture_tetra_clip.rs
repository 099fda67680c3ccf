//! Tetra on concave meshes: each tetrahedron is clipped exactly to the mesh (issue 14
//! part 2), so volumes add up to the mesh's, no fragment leaves it, and a tetrahedron
//! the surface cuts in two gives two fragments.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shapes::*;
use shatter_geom::fracture::{FractureParams, Method, Placement, fracture};
use shatter_geom::{TriMesh, shapes as builtin};

fn tetra(random_vertices: usize, placement: Placement, seed: u64) -> FractureParams {
    FractureParams {
        method: Method::Tetra {
            random_vertices,
            skip: 0,
            center: false,
            placement,
        },
        seed,
    }
}

fn concave() -> Vec<(&'static str, TriMesh)> {
    vec![
        ("l-block", l_block()),
        ("u-block", u_block()),
        ("star", star()),
        ("torus", builtin::torus(0.5, 0.2, 16, 8)),
        ("bird", builtin::bird()),
    ]
}

#[test]
fn concave_meshes_volume_error_and_validate() {
    for (name, mesh) in concave() {
        let volume = mesh.volume();
        for placement in [Placement::Interior, Placement::Thesis] {
            for (n, seed) in [(0, 1), (50, 1), (50, 2)] {
                let what = format!("{name} {placement:?} n={n} seed={seed}");
                let fr = match fracture(&mesh, &tetra(n, placement, seed)) {
                    Ok(fr) => fr,
                    Err(e) => panic!("{what}: {e}"),
                };
                let err = (fr.total_volume() - volume).abs() / volume;
                println!(
                    "{what}: {} fragments, volume error {err:.3e}",
                    fr.fragments.len()
                );
                assert!(err <= 1e-9, "{what}: volume error {err}");
                if let Err(e) = fr.validate(Some(volume)) {
                    panic!("{what}: {e}");
                }
                // Closed, outward, every vertex and face inside the mesh, bonds matching
                // the interior area on both sides.
                check_fracture(&mesh, volume, &fr, 1e-9, &what);
            }
        }
    }
}
