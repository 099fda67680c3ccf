//! A hollow solid (a closed outer shell and a cavity's shell wound inward, as repair
//! makes of a shell nested in another) fractures into closed fragments whose volumes add
//! up to the solid's: a fragment that holds the whole cavity keeps the cavity's wall as
//! a second shell of its own, never as a fragment of negative volume. Every method.
#![allow(clippy::unwrap_used)]

mod support;

use shatter_geom::fracture::{self, FractureParams, Method, Placement, Seeds};
use shatter_geom::{DVec3, TriMesh, shapes};

/// A 2 m cube centred at the origin with a 0.2 m cubic cavity centred at (0.5, 0.5, 0.5).
fn hollow_cube() -> TriMesh {
    let outer = shapes::cube().transformed(DVec3::splat(2.0), DVec3::ZERO);
    let cavity = shapes::cube()
        .transformed(DVec3::splat(0.2), DVec3::splat(0.5))
        .flipped();
    TriMesh::merge(&[outer, cavity])
}

fn methods() -> Vec<(&'static str, Method)> {
    vec![
        (
            "voronoi",
            // Two cells split at x = 0: the cavity lies wholly in the second.
            Method::Voronoi {
                seeds: Seeds::Points(vec![DVec3::new(-0.5, 0.0, 0.0), DVec3::new(0.5, 0.0, 0.0)]),
            },
        ),
        (
            "slice",
            Method::Slice {
                pieces: 0,
                planes: Some(vec![(DVec3::ZERO, DVec3::X)]),
            },
        ),
        (
            "grid",
            Method::Grid {
                cells: [2, 1, 1],
                voids: Vec::new(),
            },
        ),
        (
            "tetra",
            Method::Tetra {
                random_vertices: 4,
                skip: 0,
                center: false,
                placement: Placement::Interior,
            },
        ),
    ]
}

#[test]
fn a_cavity_inside_one_fragment_is_that_fragments_second_shell() {
    let mesh = hollow_cube();
    let solid = 8.0 - 0.008;
    assert!((mesh.volume() - solid).abs() < 1e-12);
    for (name, method) in methods() {
        let fr = fracture::fracture(&mesh, &FractureParams { method, seed: 3 })
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut total = 0.0;
        for (i, f) in fr.fragments.iter().enumerate() {
            let v = f.mesh.volume();
            eprintln!(
                "{name}: fragment {i}: volume {v}, {} triangles",
                f.mesh.triangles.len()
            );
            assert!(v > 0.0, "{name}: fragment {i} has volume {v}");
            assert_eq!(
                support::closed_defect(&f.mesh),
                None,
                "{name}: fragment {i}"
            );
            total += v;
        }
        assert!(
            (total - solid).abs() <= 1e-9 * solid,
            "{name}: {total} against {solid}"
        );
        // The cavity is empty: its centre is in no fragment, a point beside it in one.
        let centre = DVec3::splat(0.5);
        let claims = |p: DVec3| {
            fr.fragments
                .iter()
                .filter(|f| support::winding(&f.mesh, p) > 0.5)
                .count()
        };
        assert_eq!(claims(centre), 0, "{name}: the cavity is filled");
        assert_eq!(claims(DVec3::new(0.5, 0.5, 0.75)), 1, "{name}");
        support::no_overlap_no_gap(&mesh, &fr, 100, name);
    }
}
