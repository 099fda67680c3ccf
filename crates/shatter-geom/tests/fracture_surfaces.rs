//! A surfaces-only fracture (`fracture_model_surfaces`): for every method, the same
//! fragments, attributes and bonds as `fracture_model`, without convex pieces; the
//! fragments closed and outward (checked here by edges), their volumes adding up; and
//! roughening works on it as on the full fracture.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shapes::{assert_closed_outward, diag};
use shatter_geom::fracture::{
    FractureParams, Method, Placement, Roughness, fracture_model, fracture_model_surfaces, roughen,
};
use shatter_geom::model::Model;
use shatter_geom::shapes as builtin;

fn methods() -> Vec<(&'static str, Method)> {
    vec![
        ("voronoi", Method::voronoi(30, Default::default())),
        ("tetra", Method::tetra(20, Placement::Interior)),
        (
            "slice",
            Method::Slice {
                pieces: 5,
                planes: None,
            },
        ),
        (
            "grid",
            Method::Grid {
                cells: [3, 2, 2],
                voids: Vec::new(),
            },
        ),
    ]
}

#[test]
fn every_method_gives_the_same_fracture_but_for_the_convex_pieces() {
    for (shape, mesh) in [("bird", builtin::bird()), ("cube", builtin::cube())] {
        let model = Model::from_mesh(mesh.clone());
        let volume = mesh.signed_volume();
        for (name, method) in methods() {
            let what = format!("{shape} {name}");
            let params = FractureParams { method, seed: 4 };
            let surfaces = fracture_model_surfaces(&model, &params).unwrap();
            let mut full = fracture_model(&model, &params).unwrap();
            assert!(surfaces.fragments.len() > 1, "{what}");
            for (i, f) in surfaces.fragments.iter().enumerate() {
                assert!(f.convex_pieces.is_empty(), "{what} fragment {i}");
                assert!(f.convex_hulls.is_empty(), "{what} fragment {i}");
                assert_closed_outward(&f.mesh, &format!("{what} fragment {i}"));
            }
            let total = surfaces.total_volume();
            assert!(
                ((total - volume) / volume).abs() <= 1e-9,
                "{what}: {total} of {volume}"
            );
            surfaces.validate(Some(volume)).unwrap();
            for (i, f) in full.fragments.iter_mut().enumerate() {
                assert!(!f.convex_pieces.is_empty(), "{what} fragment {i}");
                f.convex_pieces.clear();
                f.convex_hulls.clear();
            }
            assert_eq!(surfaces, full, "{what}");
        }
    }
}

#[test]
fn a_surfaces_only_fracture_can_be_roughened() {
    let mesh = builtin::bird();
    let d = diag(&mesh);
    let r = Roughness {
        amplitude: 0.01 * d,
        frequency: Roughness::STONE.frequency / d,
        seed: 2,
        ..Roughness::STONE
    };
    let params = FractureParams::voronoi(30, 5);
    let model = Model::from_mesh(mesh.clone());
    let mut surfaces = fracture_model_surfaces(&model, &params).unwrap();
    let mut full = fracture_model(&model, &params).unwrap();
    let report = roughen(&mut surfaces, &r).unwrap();
    let full_report = roughen(&mut full, &r).unwrap();
    // The caps are displaced as on the full fracture: no cap is refused for the pieces
    // the fragments do not have.
    assert!(report.caps > 10, "{report:?}");
    assert_eq!(report, full_report);
    for (i, (a, b)) in surfaces.fragments.iter().zip(&full.fragments).enumerate() {
        assert!(a.convex_pieces.is_empty(), "fragment {i}");
        assert_eq!(a.mesh, b.mesh, "fragment {i}");
        assert_closed_outward(&a.mesh, &format!("rough fragment {i}"));
    }
    surfaces.validate(Some(mesh.signed_volume())).unwrap();
}
