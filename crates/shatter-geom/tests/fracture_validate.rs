//! `Fracture::validate` over every built-in shape and the concave test shapes (L block,
//! U, star) × every method: closed 2-manifold fragments, volumes adding up to the mesh's
//! (relative 1e-9), a well-formed bond graph.
#![allow(clippy::unwrap_used)]

#[path = "fracture_shapes.rs"]
mod shapes;

use shatter_geom::fracture::{
    FractureParams, InvalidFracture, Method, Pattern, Placement, Seeds, fracture,
};
use shatter_geom::{DVec3, TriMesh};

fn mesh(name: &str) -> TriMesh {
    match name {
        "l" => shapes::l_block(),
        "u" => shapes::u_block(),
        "star" => shapes::star(),
        other => shatter_geom::shapes::by_name(other).unwrap(),
    }
}

fn method(name: &str) -> Method {
    let voronoi = |pattern| Method::Voronoi {
        seeds: Seeds::Pattern {
            count: 20,
            pattern,
            impact: None,
        },
    };
    let tetra = |placement| Method::Tetra {
        random_vertices: 50,
        skip: 0,
        center: false,
        placement,
    };
    match name {
        "tetra_interior" => tetra(Placement::Interior),
        "tetra_thesis" => tetra(Placement::Thesis),
        "voronoi_uniform" => voronoi(Pattern::Uniform),
        "voronoi_clustered" => voronoi(Pattern::Clustered),
        "voronoi_radial" => voronoi(Pattern::Radial),
        "voronoi_splinter" => voronoi(Pattern::Splinter),
        "slice" => Method::Slice {
            pieces: 8,
            planes: None,
        },
        _ => unreachable!(),
    }
}

/// Fractures shape `shape` by `method` with seeds 1 and 2 and validates both.
fn run(shape: &str, method_name: &str) {
    let m = mesh(shape);
    for seed in [1, 2] {
        let params = FractureParams {
            method: method(method_name),
            seed,
        };
        let fr = fracture(&m, &params).unwrap();
        if let Err(e) = fr.validate(Some(m.volume())) {
            panic!("{shape} × {method_name}, seed {seed}: {e}");
        }
    }
}

macro_rules! cases {
    ($($(#[$attr:meta])* $test:ident: $shape:literal, $method:literal;)*) => {
        $(
            #[test]
            $(#[$attr])*
            fn $test() {
                run($shape, $method);
            }
        )*
    };
}

cases! {
    cube_tetra_interior: "cube", "tetra_interior";
    cube_tetra_thesis: "cube", "tetra_thesis";
    cube_voronoi_uniform: "cube", "voronoi_uniform";
    cube_voronoi_clustered: "cube", "voronoi_clustered";
    cube_voronoi_radial: "cube", "voronoi_radial";
    cube_voronoi_splinter: "cube", "voronoi_splinter";
    cube_slice: "cube", "slice";
    capsule_tetra_interior: "capsule", "tetra_interior";
    capsule_tetra_thesis: "capsule", "tetra_thesis";
    capsule_voronoi_uniform: "capsule", "voronoi_uniform";
    capsule_voronoi_clustered: "capsule", "voronoi_clustered";
    capsule_voronoi_radial: "capsule", "voronoi_radial";
    capsule_voronoi_splinter: "capsule", "voronoi_splinter";
    capsule_slice: "capsule", "slice";
    cylinder_tetra_interior: "cylinder", "tetra_interior";
    cylinder_tetra_thesis: "cylinder", "tetra_thesis";
    cylinder_voronoi_uniform: "cylinder", "voronoi_uniform";
    cylinder_voronoi_clustered: "cylinder", "voronoi_clustered";
    cylinder_voronoi_radial: "cylinder", "voronoi_radial";
    cylinder_voronoi_splinter: "cylinder", "voronoi_splinter";
    cylinder_slice: "cylinder", "slice";
    sphere_tetra_interior: "sphere", "tetra_interior";
    sphere_tetra_thesis: "sphere", "tetra_thesis";
    sphere_voronoi_uniform: "sphere", "voronoi_uniform";
    sphere_voronoi_clustered: "sphere", "voronoi_clustered";
    sphere_voronoi_radial: "sphere", "voronoi_radial";
    sphere_voronoi_splinter: "sphere", "voronoi_splinter";
    sphere_slice: "sphere", "slice";
    torus_tetra_interior: "torus", "tetra_interior";
    torus_tetra_thesis: "torus", "tetra_thesis";
    torus_voronoi_uniform: "torus", "voronoi_uniform";
    torus_voronoi_clustered: "torus", "voronoi_clustered";
    torus_voronoi_radial: "torus", "voronoi_radial";
    torus_voronoi_splinter: "torus", "voronoi_splinter";
    torus_slice: "torus", "slice";
    bird_tetra_interior: "bird", "tetra_interior";
    bird_tetra_thesis: "bird", "tetra_thesis";
    bird_voronoi_uniform: "bird", "voronoi_uniform";
    bird_voronoi_clustered: "bird", "voronoi_clustered";
    bird_voronoi_radial: "bird", "voronoi_radial";
    bird_voronoi_splinter: "bird", "voronoi_splinter";
    bird_slice: "bird", "slice";
    l_tetra_interior: "l", "tetra_interior";
    l_tetra_thesis: "l", "tetra_thesis";
    l_voronoi_uniform: "l", "voronoi_uniform";
    l_voronoi_clustered: "l", "voronoi_clustered";
    l_voronoi_radial: "l", "voronoi_radial";
    l_voronoi_splinter: "l", "voronoi_splinter";
    l_slice: "l", "slice";
    u_tetra_interior: "u", "tetra_interior";
    u_tetra_thesis: "u", "tetra_thesis";
    u_voronoi_uniform: "u", "voronoi_uniform";
    u_voronoi_clustered: "u", "voronoi_clustered";
    u_voronoi_radial: "u", "voronoi_radial";
    u_voronoi_splinter: "u", "voronoi_splinter";
    u_slice: "u", "slice";
    star_tetra_interior: "star", "tetra_interior";
    star_tetra_thesis: "star", "tetra_thesis";
    star_voronoi_uniform: "star", "voronoi_uniform";
    star_voronoi_clustered: "star", "voronoi_clustered";
    star_voronoi_radial: "star", "voronoi_radial";
    star_voronoi_splinter: "star", "voronoi_splinter";
    star_slice: "star", "slice";
}

#[test]
fn test_shapes_are_valid_solids_of_the_stated_volume() {
    for (name, m, v) in [
        ("l", shapes::l_block(), shapes::L_VOLUME),
        ("u", shapes::u_block(), shapes::U_VOLUME),
        ("star", shapes::star(), shapes::star_volume()),
    ] {
        assert_eq!(m.validate_solid(), Ok(()), "{name}");
        assert!(
            (m.volume() - v).abs() < 1e-12 * v,
            "{name}: {} vs {v}",
            m.volume()
        );
    }
}

/// A fracture of two half cubes, to break in the tests below.
fn halves() -> shatter_geom::fracture::Fracture {
    let params = FractureParams {
        method: Method::Slice {
            pieces: 0,
            planes: Some(vec![(DVec3::ZERO, DVec3::X)]),
        },
        seed: 0,
    };
    fracture(&shatter_geom::shapes::cube(), &params).unwrap()
}

#[test]
fn validate_finds_each_kind_of_defect() {
    let good = halves();
    assert_eq!(good.validate(Some(1.0)), Ok(()));
    assert!(matches!(
        good.validate(Some(1.1)),
        Err(InvalidFracture::TotalVolume { .. })
    ));

    // A back-to-back pair of triangles inside fragment 1 (the merge defect).
    let mut f = good.clone();
    let g = &mut f.fragments[1];
    let [a, b, c] = g.mesh.triangles[0];
    g.mesh
        .triangles
        .extend([[a, b, c], [a, c, b]].map(|t| t.map(|i| i)));
    g.interior.extend([true, true]);
    match f.validate(None) {
        Err(InvalidFracture::DuplicateTriangles { fragment: 1, .. }) => {}
        other => panic!("{other:?}"),
    }
    let mut f = good.clone();
    let g = &mut f.fragments[1];
    let [a, b, c] = g.mesh.triangles[0];
    g.mesh.triangles.push([a, c, b]);
    g.interior.push(true);
    match f.validate(None) {
        Err(InvalidFracture::DuplicateTriangles {
            fragment: 1,
            opposite: true,
            ..
        }) => {}
        other => panic!("{other:?}"),
    }

    // One triangle flipped: its edges are walked twice the same way.
    let mut f = good.clone();
    f.fragments[0].mesh.triangles[0].swap(1, 2);
    assert!(matches!(
        f.validate(None),
        Err(InvalidFracture::Winding { fragment: 0, .. })
    ));

    // A degenerate triangle.
    let mut f = good.clone();
    let t = f.fragments[0].mesh.triangles[0];
    f.fragments[0].mesh.triangles[0] = [t[0], t[0], t[1]];
    assert!(matches!(
        f.validate(None),
        Err(InvalidFracture::Degenerate {
            fragment: 0,
            triangle: 0
        })
    ));

    // Interior flags of the wrong length.
    let mut f = good.clone();
    f.fragments[0].interior.pop();
    assert!(matches!(
        f.validate(None),
        Err(InvalidFracture::InteriorFlags { fragment: 0, .. })
    ));

    // A volume field that is not what the mesh encloses.
    let mut f = good.clone();
    f.fragments[1].volume *= 2.0;
    assert!(matches!(
        f.validate(None),
        Err(InvalidFracture::Volume { fragment: 1, .. })
    ));

    // An out-of-range index.
    let mut f = good.clone();
    f.fragments[0].mesh.triangles[0][0] = 999;
    assert!(matches!(
        f.validate(None),
        Err(InvalidFracture::Malformed { fragment: 0, .. })
    ));

    // Bonds: reversed, out of range, repeated, zero area.
    let bond = good.bonds[0];
    for (bonds, reason) in [
        (
            vec![shatter_geom::fracture::Bond { a: 1, b: 0, ..bond }],
            "a is not below b",
        ),
        (
            vec![shatter_geom::fracture::Bond { b: 2, ..bond }],
            "fragment index out of range",
        ),
        (
            vec![bond, bond],
            "not after the previous bond in (a, b) order (unsorted or repeated)",
        ),
        (
            vec![shatter_geom::fracture::Bond { area: 0.0, ..bond }],
            "area not positive and finite",
        ),
    ] {
        let mut f = good.clone();
        f.bonds = bonds;
        match f.validate(None) {
            Err(InvalidFracture::Bond { reason: r, .. }) => assert_eq!(r, reason),
            other => panic!("{reason}: {other:?}"),
        }
    }
}
