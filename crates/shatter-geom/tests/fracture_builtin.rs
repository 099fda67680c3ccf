//! Voronoi and slice fracture of the built-in shapes (cube, capsule, cylinder, sphere,
//! torus, bird), and the refusal of bad meshes and parameters.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shapes::check_fracture;
use shatter_geom::fracture::{FractureError, FractureParams, Method, Pattern, Seeds, fracture};
use shatter_geom::mesh::MeshError;
use shatter_geom::{DVec3, TriMesh, shapes as builtin};

fn voronoi(pieces: usize, pattern: Pattern, seed: u64) -> FractureParams {
    FractureParams {
        method: Method::Voronoi {
            seeds: Seeds::Pattern {
                count: pieces,
                pattern,
                impact: None,
            },
        },
        seed,
    }
}

#[test]
fn voronoi_every_pattern_on_every_builtin_shape() {
    for name in builtin::NAMES {
        let mesh = builtin::by_name(name).unwrap();
        let volume = mesh.volume();
        for pattern in [
            Pattern::Uniform,
            Pattern::Clustered,
            Pattern::Radial,
            Pattern::Splinter,
        ] {
            let fr = fracture(&mesh, &voronoi(20, pattern, 9)).unwrap();
            let what = format!("{name} {pattern:?}");
            check_fracture(&mesh, volume, &fr, 1e-6, &what);
            assert!(fr.fragments.len() >= 5, "{what}: {}", fr.fragments.len());
            assert!(fr.warnings.is_empty(), "{what}: {:?}", fr.warnings);
        }
    }
}

#[test]
fn slice_every_builtin_shape() {
    for name in builtin::NAMES {
        let mesh = builtin::by_name(name).unwrap();
        let params = FractureParams {
            method: Method::Slice {
                pieces: 4,
                planes: None,
            },
            seed: 4,
        };
        let fr = fracture(&mesh, &params).unwrap();
        check_fracture(&mesh, mesh.volume(), &fr, 1e-6, &format!("{name} slice"));
        assert!(fr.fragments.len() >= 3, "{name}: {}", fr.fragments.len());
    }
}

#[test]
fn bird_into_a_hundred_cells_keeps_its_concave_parts_apart() {
    let mesh = builtin::bird();
    let fr = fracture(&mesh, &voronoi(100, Pattern::Uniform, 1)).unwrap();
    check_fracture(&mesh, mesh.volume(), &fr, 1e-6, "bird 100");
    // At least 100 cells (a cell the bird's shape cuts in two yields two fragments).
    assert!(fr.fragments.len() >= 100, "{}", fr.fragments.len());
}

#[test]
fn inward_mesh_is_flipped_with_a_warning() {
    let mesh = builtin::cube().flipped();
    let fr = fracture(&mesh, &voronoi(5, Pattern::Uniform, 0)).unwrap();
    assert_eq!(fr.warnings.len(), 1, "{:?}", fr.warnings);
    assert!(fr.warnings[0].contains("inward"));
    check_fracture(&builtin::cube(), 1.0, &fr, 1e-9, "flipped cube");
}

#[test]
fn bad_meshes_are_refused_with_counts() {
    let params = voronoi(5, Pattern::Uniform, 0);
    let mut open = builtin::cube();
    open.triangles.pop();
    let err = fracture(&open, &params).unwrap_err();
    assert_eq!(err, FractureError::Mesh(MeshError::BoundaryEdges(3)));
    assert!(err.to_string().contains("3 boundary edges"), "{err}");

    let mut twisted = builtin::cube();
    twisted.triangles[0].swap(1, 2);
    assert!(matches!(
        fracture(&twisted, &params),
        Err(FractureError::Mesh(MeshError::InconsistentWinding(_)))
    ));

    // Two cubes sharing an edge: non-manifold.
    let a = builtin::cube();
    let b = a.transformed(DVec3::ONE, DVec3::new(1.0, 1.0, 0.0));
    let touching = TriMesh::merge(&[a, b]);
    assert!(matches!(
        fracture(&touching, &params),
        Err(FractureError::Mesh(_))
    ));

    assert_eq!(
        fracture(&TriMesh::default(), &params).unwrap_err(),
        FractureError::Mesh(MeshError::Empty)
    );
    let mut nan = builtin::cube();
    nan.positions[5].y = f64::NAN;
    assert_eq!(
        fracture(&nan, &params).unwrap_err(),
        FractureError::Mesh(MeshError::NonFinite { vertex: 5 })
    );
}

#[test]
fn bad_parameters_are_refused() {
    let cube = builtin::cube();
    assert_eq!(
        fracture(&cube, &voronoi(0, Pattern::Uniform, 0)).unwrap_err(),
        FractureError::TooFewPieces(0)
    );
    let slice0 = FractureParams {
        method: Method::Slice {
            pieces: 0,
            planes: None,
        },
        seed: 0,
    };
    assert_eq!(
        fracture(&cube, &slice0).unwrap_err(),
        FractureError::TooFewPieces(0)
    );
    let bad_seed = FractureParams {
        method: Method::Voronoi {
            seeds: Seeds::Points(vec![DVec3::ZERO, DVec3::new(f64::INFINITY, 0.0, 0.0)]),
        },
        seed: 0,
    };
    assert_eq!(
        fracture(&cube, &bad_seed).unwrap_err(),
        FractureError::BadInput {
            what: "seed",
            index: 1
        }
    );
    let zero_normal = FractureParams {
        method: Method::Slice {
            pieces: 1,
            planes: Some(vec![(DVec3::ZERO, DVec3::ZERO)]),
        },
        seed: 0,
    };
    assert!(matches!(
        fracture(&cube, &zero_normal),
        Err(FractureError::BadInput { what: "plane", .. })
    ));
}

#[test]
fn slivers_without_a_bonded_neighbour_are_merged_too() {
    // Dense radial cells graze the sphere's surface and cut off slivers (down to 1e-19 of
    // its volume) whose shared faces are too small to bond; they are merged into the
    // nearest fragment instead of reaching the physics.
    let mesh = builtin::by_name("sphere").unwrap();
    let fr = fracture(&mesh, &voronoi(250, Pattern::Radial, 6)).unwrap();
    check_fracture(&mesh, mesh.volume(), &fr, 1e-6, "sphere radial 250");
    assert!(fr.warnings.is_empty(), "{:?}", fr.warnings);
}
