//! Mesh analysis: mass properties, welding, topology checks and validation errors.
#![allow(clippy::unwrap_used)]

use shatter_geom::mesh::MeshError;
use shatter_geom::{DMat3, DVec3, TriMesh, shapes};

fn two_cubes(offset: DVec3) -> TriMesh {
    let a = shapes::cube();
    let b = a.transformed(DVec3::ONE, offset);
    TriMesh::merge(&[a, b])
}

#[test]
fn open_box_reports_its_boundary() {
    let mut open = shapes::cube();
    // Remove the two triangles of one face (4 boundary edges around the hole).
    open.triangles.drain(0..2);
    let r = open.check();
    assert_eq!(r.boundary_edges, 4);
    assert_eq!(r.non_manifold_edges, 0);
    assert_eq!(r.inconsistent_edges, 0);
    assert!(!r.is_closed());
    assert!(!r.is_outward());
    assert_eq!(open.validate_solid(), Err(MeshError::BoundaryEdges(4)));
    assert_eq!(
        open.validate_solid().unwrap_err().to_string(),
        "4 boundary edges"
    );
}

#[test]
fn cubes_sharing_an_edge_are_non_manifold() {
    let m = two_cubes(DVec3::new(1.0, 1.0, 0.0));
    let r = m.check();
    assert_eq!(r.non_manifold_edges, 1);
    assert_eq!(r.boundary_edges, 0);
    assert_eq!(r.components, 1);
    assert_eq!(m.validate_solid(), Err(MeshError::NonManifoldEdges(1)));
    assert_eq!(
        m.validate_solid().unwrap_err().to_string(),
        "1 non-manifold edges"
    );
}

#[test]
fn fin_on_an_edge_is_non_manifold_and_open() {
    let mut m = shapes::cube().welded();
    let [a, b, _] = m.triangles[0];
    m.positions.push(DVec3::new(3.0, 3.0, 3.0));
    m.triangles.push([a, b, 8]);
    let r = m.check();
    assert_eq!(r.non_manifold_edges, 1);
    assert_eq!(r.boundary_edges, 2);
}

#[test]
fn cubes_sharing_a_corner_touch_themselves() {
    let m = two_cubes(DVec3::ONE);
    let r = m.check();
    assert_eq!(r.boundary_edges, 0);
    assert_eq!(r.non_manifold_edges, 0);
    assert_eq!(r.non_manifold_vertices, 1);
    assert!(r.is_closed());
    assert!(!r.is_solid());
    assert_eq!(m.validate_solid(), Err(MeshError::NonManifoldVertices(1)));
}

#[test]
fn disjoint_cubes_are_two_components_and_a_valid_solid() {
    let m = two_cubes(DVec3::new(3.0, 0.0, 0.0));
    let r = m.check();
    assert_eq!(r.components, 2);
    assert!(r.is_solid());
    assert!((m.volume() - 2.0).abs() < 1e-12);
    assert!((m.centroid() - DVec3::new(1.5, 0.0, 0.0)).length() < 1e-12);
}

#[test]
fn flipped_mesh_is_inward_and_repaired() {
    let mut m = shapes::capsule().flipped();
    let r = m.check();
    assert!(r.is_closed());
    assert!(r.is_consistent());
    assert!(!r.is_outward());
    assert!(r.signed_volume < 0.0);
    assert!(matches!(m.validate_solid(), Err(MeshError::Inward { .. })));
    assert_eq!(m.orient_outward(), Ok(true));
    assert!(m.is_outward());
    assert_eq!(m.validate_solid(), Ok(()));
}

#[test]
fn one_flipped_triangle_gives_three_inconsistent_edges() {
    let mut m = shapes::cube();
    m.triangles[5].swap(0, 1);
    let r = m.check();
    assert_eq!(r.inconsistent_edges, 3);
    assert_eq!(r.boundary_edges, 0);
    assert_eq!(m.validate_solid(), Err(MeshError::InconsistentWinding(3)));
    // Not a repair orient_outward may make: the mesh stays as it was.
    let before = m.clone();
    assert_eq!(m.orient_outward(), Err(MeshError::InconsistentWinding(3)));
    assert_eq!(m, before);
}

#[test]
fn degenerate_triangles_are_counted_exactly() {
    let mut m = shapes::cube();
    let n = m.positions.len() as u32;
    m.positions.extend([
        DVec3::ZERO,
        DVec3::new(1.0, 1.0, 1.0),
        DVec3::new(0.5, 0.5, 0.5),
    ]);
    m.positions.push(DVec3::new(0.5, 0.5, 0.5 + 1e-15));
    m.triangles.push([n, n + 1, n + 2]); // collinear
    m.triangles.push([n, n, n + 1]); // repeated vertex
    m.triangles.push([n, n + 1, n + 3]); // tiny but not zero
    assert_eq!(m.check().degenerate_triangles, 2);
}

#[test]
fn validation_names_empty_non_finite_and_out_of_range() {
    assert_eq!(TriMesh::default().validate_solid(), Err(MeshError::Empty));
    assert_eq!(
        TriMesh::default().validate_solid().unwrap_err().to_string(),
        "mesh is empty"
    );
    let mut m = shapes::cube();
    m.positions[7].y = f64::NAN;
    assert_eq!(
        m.validate_solid().unwrap_err().to_string(),
        "vertex 7 has a non-finite coordinate"
    );
    let mut m = shapes::cube();
    m.triangles[5] = [0, 1, 99];
    let err = m.validate_solid().unwrap_err();
    assert_eq!(
        err,
        MeshError::IndexOutOfRange {
            triangle: 5,
            index: 99,
            vertices: 24
        }
    );
    assert_eq!(err.to_string(), "triangle 5 references vertex 99 of 24");
    // check() never panics on it either.
    assert_eq!(m.check().invalid_triangles, 1);
}

#[test]
fn welding_merges_exactly_equal_positions_only() {
    let cube = shapes::cube();
    let w = cube.welded();
    assert_eq!(w.positions.len(), 8);
    assert_eq!(w.triangles.len(), 12);
    assert_eq!(w.signed_volume(), cube.signed_volume());
    let nudged = {
        let mut c = cube.clone();
        c.positions[0].x += 1e-12;
        c
    };
    assert_eq!(nudged.welded().positions.len(), 9);
    assert!(nudged.check().boundary_edges > 0);
}

#[test]
fn box_inertia_matches_the_analytic_tensor() {
    let (a, b, c) = (2.0, 0.5, 3.0);
    let m = shapes::cube().transformed(DVec3::new(a, b, c), DVec3::new(5.0, -7.0, 11.0));
    let mass = a * b * c;
    let expected = DMat3::from_diagonal(DVec3::new(
        mass * (b * b + c * c) / 12.0,
        mass * (a * a + c * c) / 12.0,
        mass * (a * a + b * b) / 12.0,
    ));
    let i = m.inertia();
    for col in 0..3 {
        let d = i.col(col) - expected.col(col);
        assert!(d.length() < 1e-10, "{i:?} vs {expected:?}");
    }
}

#[test]
fn sphere_inertia_tends_to_two_fifths_m_r_squared() {
    let s = shapes::sphere(128, 64);
    let m = s.volume();
    let i = s.inertia();
    let expected = 0.4 * m * 0.25;
    for k in 0..3 {
        assert!((i.col(k)[k] - expected).abs() < 2e-3 * expected);
    }
    assert!(i.x_axis.y.abs() < 1e-9 && i.x_axis.z.abs() < 1e-9 && i.y_axis.z.abs() < 1e-9);
}

#[test]
fn winding_number_is_one_inside_zero_outside_half_on_a_face() {
    let cube = shapes::cube();
    assert!((cube.winding_number(DVec3::new(0.3, -0.2, 0.1)) - 1.0).abs() < 1e-12);
    assert!(cube.winding_number(DVec3::new(0.7, 0.0, 0.0)).abs() < 1e-12);
    assert!((cube.winding_number(DVec3::new(0.5, 0.1, 0.2)) - 0.5).abs() < 1e-9);
    assert!((cube.flipped().winding_number(DVec3::ZERO) + 1.0).abs() < 1e-12);
    assert!(cube.contains(DVec3::ZERO));
    assert!(!cube.contains(DVec3::splat(0.51)));
}

#[test]
fn mirroring_keeps_the_mesh_outward() {
    let m = shapes::bird().transformed(DVec3::new(-1.0, 2.0, 1.0), DVec3::ZERO);
    assert!(m.is_outward());
    assert!((m.volume() - 2.0 * shapes::bird().volume()).abs() < 1e-12);
}

#[test]
fn surface_area_and_normals() {
    let cube = shapes::cube();
    assert!((cube.surface_area() - 6.0).abs() < 1e-12);
    for t in 0..cube.triangles.len() {
        let n = cube.triangle_normal(t);
        let [a, b, c] = cube.triangle(t);
        // Outward: the normal points away from the centre.
        assert!(n.dot((a + b + c) / 3.0) > 0.0);
        assert!((n.length() - 1.0).abs() < 1e-12);
    }
    let s = shapes::sphere(128, 64);
    let exact = std::f64::consts::PI; // 4π r², r = 0.5
    assert!((s.surface_area() - exact).abs() < 2e-3 * exact);
}

#[test]
fn merge_offsets_indices_and_adds_volumes() {
    let parts = [
        shapes::cube(),
        shapes::cylinder().transformed(DVec3::ONE, DVec3::new(5.0, 0.0, 0.0)),
    ];
    let merged = TriMesh::merge(&parts);
    assert_eq!(merged.positions.len(), 24 + 88);
    assert_eq!(merged.triangles.len(), 12 + 80);
    assert!((merged.volume() - parts[0].volume() - parts[1].volume()).abs() < 1e-12);
    assert_eq!(merged.validate_solid(), Ok(()));
}

#[test]
fn overlapping_cubes_are_self_intersecting() {
    let m = two_cubes(DVec3::splat(0.5));
    // Topologically fine: two closed components.
    let r = m.check();
    assert!(r.is_solid());
    let pairs = m.self_intersections(usize::MAX);
    assert!(!pairs.is_empty());
    match m.validate_solid() {
        Err(MeshError::SelfIntersecting { pairs: n, first }) => {
            // Pairs that only touch (on the cubes' edges) are not counted.
            assert!(n > 0 && n <= pairs.len(), "{n} of {}", pairs.len());
            assert!(pairs.contains(&first));
            // Every reported pair: one triangle from each cube.
            assert!(pairs.iter().all(|&(a, b)| a < 12 && b >= 12));
        }
        other => panic!("{other:?}"),
    }
    // Cubes that only touch face to face (no shared vertex position) touch too.
    let touching = two_cubes(DVec3::new(1.0, 0.5, 0.5));
    assert!(!touching.self_intersections(1).is_empty());
    // Apart by a hair: clean.
    let apart = two_cubes(DVec3::new(1.0 + 1e-12, 0.5, 0.5));
    assert!(apart.self_intersections(1).is_empty());
}

#[test]
fn builtin_shapes_do_not_self_intersect() {
    for name in shapes::NAMES {
        let m = shapes::by_name(name).unwrap();
        assert_eq!(m.self_intersections(usize::MAX), [], "{name}");
    }
}

#[test]
fn self_intersection_with_a_huge_triangle_among_small_ones() {
    // One huge triangle slicing through a fine sphere: found, and the grid stays small.
    let sphere = shapes::sphere(64, 32);
    let slab = TriMesh::new(
        vec![
            DVec3::new(-1e6, 0.1, -1e6),
            DVec3::new(1e6, 0.1, -1e6),
            DVec3::new(0.0, 0.1, 1e6),
        ],
        vec![[0, 2, 1]],
    );
    let m = TriMesh::merge(&[sphere, slab]);
    let pairs = m.self_intersections(usize::MAX);
    // The plane y = 0.1 crosses one band of the sphere: every pair involves the slab.
    let slab_index = m.triangles.len() as u32 - 1;
    assert!(pairs.len() >= 64, "{}", pairs.len());
    assert!(pairs.iter().all(|&(_, b)| b == slab_index));
    // A limit returns that many.
    assert_eq!(m.self_intersections(3).len(), 3);
}

fn ball(radius: f64) -> TriMesh {
    shapes::sphere(24, 12).transformed(DVec3::splat(2.0 * radius), DVec3::ZERO)
}

#[test]
fn hollow_ball_needs_an_inward_cavity() {
    let hollow = TriMesh::merge(&[ball(1.0), ball(0.5).flipped()]);
    assert_eq!(hollow.validate_solid(), Ok(()));
    let expected = ball(1.0).volume() - ball(0.5).volume();
    assert!((hollow.volume() - expected).abs() < 1e-12);
    // A point in the cavity is outside the solid.
    assert!(!hollow.contains(DVec3::ZERO));
    assert!(hollow.contains(DVec3::new(0.75, 0.0, 0.0)));

    // Cavity wound outward: one shell wrong.
    let wrong = TriMesh::merge(&[ball(1.0), ball(0.5)]);
    assert_eq!(
        wrong.validate_solid(),
        Err(MeshError::InwardShells { wrong: 1, total: 2 })
    );
    assert_eq!(
        wrong.validate_solid().unwrap_err().to_string(),
        "1 of 2 shells are wound the wrong way for their nesting"
    );

    // Everything flipped: the unambiguous repair.
    let mut inverted = hollow.flipped();
    assert!(matches!(
        inverted.validate_solid(),
        Err(MeshError::Inward { .. })
    ));
    assert_eq!(inverted.orient_outward(), Ok(true));
    assert_eq!(inverted.validate_solid(), Ok(()));
}

#[test]
fn ball_in_a_cavity_is_outward_again() {
    let m = TriMesh::merge(&[ball(1.0), ball(0.6).flipped(), ball(0.3)]);
    assert_eq!(m.validate_solid(), Ok(()));
    assert!(m.contains(DVec3::ZERO));
    assert!(!m.contains(DVec3::new(0.45, 0.0, 0.0)));
}

#[test]
fn one_flipped_shell_among_outward_ones_is_refused() {
    let a = shapes::cube();
    let b = shapes::cube()
        .transformed(DVec3::ONE, DVec3::new(3.0, 0.0, 0.0))
        .flipped();
    let mut m = TriMesh::merge(&[a, b]);
    let err = m.validate_solid().unwrap_err();
    assert_eq!(err, MeshError::InwardShells { wrong: 1, total: 2 });
    // Not flipped by the repair either: flipping all would break the other shell.
    assert_eq!(m.orient_outward(), Err(err));
}
