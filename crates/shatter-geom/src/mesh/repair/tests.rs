//! Each repair on small hand-made cases.

use glam::DVec3;

use super::*;
use crate::TriMesh;
use crate::model::Model;
use crate::shapes;

fn run(mesh: TriMesh) -> (Model, RepairReport) {
    repair(&Model::from_mesh(mesh), &RepairOptions::default()).unwrap()
}

#[test]
fn a_solid_needs_no_repair() {
    let (m, r) = run(shapes::cube());
    assert!(r.is_clean(), "{:?}", r.warnings());
    assert!(m.mesh.check().is_solid());
    assert!((m.mesh.volume() - 1.0).abs() < 1e-12);
}

#[test]
fn a_crack_of_1e_7_is_welded_shut() {
    let mut cube = shapes::cube();
    // The +x face's four corners moved 1e-7 outward: after the exact weld that face is
    // a loose square and the rest a box with a square hole.
    for p in &mut cube.positions[0..4] {
        p.x += 1e-7;
    }
    assert!(!cube.check().is_closed());
    let (m, r) = run(cube);
    assert_eq!(r.welded_vertices, 4);
    assert_eq!(r.holes_filled, 0);
    assert!(m.mesh.check().is_solid());
    assert!((m.mesh.volume() - 1.0).abs() < 1e-6);
}

#[test]
fn a_duplicated_triangle_is_dropped_and_an_opposite_pair_cancels() {
    let mut cube = shapes::cube();
    cube.triangles.push(cube.triangles[3]);
    cube.triangles.push(cube.triangles[3]);
    let (m, r) = run(cube.clone());
    assert_eq!(r.duplicate_triangles, 2);
    assert_eq!(m.mesh.triangles.len(), 12);
    assert!(m.mesh.check().is_solid());
    // A triangle and its reverse inside a closed cube: a zero-thickness wall.
    let mut walled = shapes::cube();
    let t = walled.triangles[0];
    walled.triangles.push([t[0], t[2], t[1]]);
    let (m, r) = run(walled);
    assert_eq!(r.opposite_pairs_dropped, 2);
    // The face lost one triangle: its hole is filled again.
    assert_eq!(r.holes_filled, 1);
    assert!(m.mesh.check().is_solid());
    assert!((m.mesh.volume() - 1.0).abs() < 1e-12);
}

#[test]
fn an_inverted_shell_is_flipped_and_a_mixed_winding_made_consistent() {
    let (m, r) = run(shapes::sphere(16, 8).flipped());
    assert_eq!(r.inverted_shells, 1);
    assert!(m.mesh.check().is_solid());
    let mut mixed = shapes::sphere(16, 8);
    for t in mixed.triangles.iter_mut().step_by(7) {
        t.swap(1, 2);
    }
    let n = mixed.triangles.len().div_ceil(7);
    let (m, r) = run(mixed);
    assert_eq!(r.rewound_triangles, n);
    assert_eq!(r.inverted_shells, 0);
    assert!(m.mesh.check().is_solid());
    assert!((m.mesh.volume() - shapes::sphere(16, 8).volume()).abs() < 1e-12);
}

#[test]
fn a_missing_face_is_filled_with_the_attributes_and_material_around_it() {
    let mut model = Model::from_mesh(shapes::cube());
    // UVs: u = x + 0.5, v = y + 0.5 at every corner; two materials by face.
    let uv: Vec<[[f32; 2]; 3]> = model
        .mesh
        .triangles
        .iter()
        .map(|t| {
            t.map(|i| {
                let p = model.mesh.positions[i as usize];
                [(p.x + 0.5) as f32, (p.y + 0.5) as f32]
            })
        })
        .collect();
    model.corners.uv = Some(uv.clone());
    model
        .materials
        .push(crate::model::Material::named("second"));
    model.material = (0..12).map(|t| u32::from(t >= 2)).collect();
    // Drop the +x face (triangles 0 and 1).
    let model = model.select(&(2..12).collect::<Vec<_>>());
    let (m, r) = repair(&model, &RepairOptions::default()).unwrap();
    m.check().unwrap();
    assert_eq!(r.holes_filled, 1);
    assert!(m.mesh.check().is_solid());
    assert!((m.mesh.volume() - 1.0).abs() < 1e-12);
    // The ten kept triangles keep their corners; the patch has the material around it
    // and, at the loop's corners, UVs of the mesh corners there.
    let uvs = m.corners.uv.as_ref().unwrap();
    for t in 0..10 {
        assert_eq!(uvs[t], uv[t + 2]);
        assert_eq!(m.material[t], 1);
    }
    let patch = m.mesh.triangles.iter().zip(uvs).zip(&m.material).skip(10);
    for ((tri, uv), &material) in patch {
        assert_eq!(material, 1);
        for (k, &v) in tri.iter().enumerate() {
            let p = m.mesh.positions[v as usize];
            assert!(
                (p.x - 0.5).abs() < 1e-12,
                "the patch lies on the face's plane"
            );
            let want = [(p.x + 0.5) as f32, (p.y + 0.5) as f32];
            assert!((uv[k][1] - want[1]).abs() < 1e-6, "{:?} {want:?}", uv[k]);
        }
    }
}

#[test]
fn a_sphere_with_a_hole_is_closed_by_a_fair_patch() {
    let sphere = shapes::sphere(24, 12);
    let full = sphere.volume();
    // Remove the triangles around the north pole (the top two rings).
    let keep: Vec<[u32; 3]> = sphere
        .triangles
        .iter()
        .copied()
        .filter(|t| t.iter().all(|&i| sphere.positions[i as usize].y < 0.45))
        .collect();
    let removed = sphere.triangles.len() - keep.len();
    assert!(removed > 24);
    let (m, r) = run(TriMesh::new(sphere.positions.clone(), keep));
    assert_eq!(r.holes_filled, 1);
    assert!(r.fill_triangles > 24, "refinement adds vertices: {r:?}");
    assert!(m.mesh.check().is_solid());
    let v = m.mesh.volume();
    // A membrane over the cap: less than the full sphere, more than the sphere cut flat.
    assert!(v < full && v > 0.9 * full, "{v} of {full}");
    assert!(m.mesh.self_intersections(1).is_empty());
}

#[test]
fn two_intersecting_cubes_become_their_union() {
    let a = shapes::cube();
    let b = a.transformed(DVec3::ONE, DVec3::splat(0.5));
    let (m, r) = run(TriMesh::merge(&[a, b]));
    let u = r.union.expect("a union");
    assert_eq!(u.shells, 2);
    assert!(m.mesh.check().is_solid(), "{:?}", m.mesh.check());
    assert!(
        m.mesh.validate_solid().is_ok(),
        "{:?}",
        m.mesh.validate_solid()
    );
    assert!(
        (m.mesh.volume() - (2.0 - 0.125)).abs() < 1e-9,
        "{}",
        m.mesh.volume()
    );
}

#[test]
fn a_cube_inside_a_cube_is_a_cavity() {
    let outer = shapes::cube().transformed(DVec3::splat(2.0), DVec3::ZERO);
    let inner = shapes::cube();
    let (m, r) = run(TriMesh::merge(&[outer, inner]));
    assert_eq!(r.cavities, 1);
    assert!(r.union.is_none());
    assert!(m.mesh.validate_solid().is_ok());
    assert!((m.mesh.volume() - 7.0).abs() < 1e-12);
}

#[test]
fn a_sheet_alone_is_refused_saying_what_was_found() {
    let mut cube = shapes::cube();
    cube.triangles.truncate(2);
    let err = repair(&Model::from_mesh(cube), &RepairOptions::default()).unwrap_err();
    assert_eq!(err.to_string(), "1 open sheet and no closed part");
    // A sheet beside a closed cube is dropped with a warning.
    let sheet = TriMesh::new(
        vec![
            DVec3::splat(5.0),
            DVec3::new(6.0, 5.0, 5.0),
            DVec3::new(5.0, 6.0, 5.0),
        ],
        vec![[0, 1, 2]],
    );
    let (m, r) = run(TriMesh::merge(&[shapes::cube(), sheet]));
    assert_eq!((r.open_sheets_dropped, r.open_sheet_triangles), (1, 1));
    assert!(r.warnings().iter().any(|w| w.contains("open sheet")));
    assert_eq!(m.mesh.triangles.len(), 12);
}

#[test]
fn a_collinear_triangle_is_dropped_and_its_t_junction_split() {
    // The +x face of the cube split at the midpoint m of its diagonal 0-2: the triangle
    // (0, m, 2) has no area, and triangle (0, 2, 3) across the diagonal has m on its edge.
    let mut cube = shapes::cube();
    let m = cube.positions.len() as u32;
    cube.positions
        .push((cube.positions[0] + cube.positions[2]) / 2.0);
    cube.triangles[0] = [0, 1, m];
    cube.triangles.push([m, 1, 2]);
    cube.triangles.push([0, m, 2]);
    let (out, r) = run(cube);
    assert_eq!((r.degenerate_triangles, r.t_junctions_split), (1, 1));
    assert!(out.mesh.check().is_solid(), "{:?}", out.mesh.check());
    assert!((out.mesh.volume() - 1.0).abs() < 1e-12);
}

#[test]
fn a_union_keeps_the_materials_and_interpolates_the_uvs_of_the_faces_it_lies_on() {
    // Two crossing cubes, UV = (x, z) on every corner, material 0 and 1 by cube.
    let a = shapes::cube();
    let b = a.transformed(DVec3::ONE, DVec3::new(0.5, 0.3, 0.2));
    let mesh = TriMesh::merge(&[a, b]);
    let mut model = Model::from_mesh(mesh);
    let planar = |p: DVec3| [p.x as f32, p.z as f32];
    model.corners.uv = Some(
        model
            .mesh
            .triangles
            .iter()
            .map(|t| t.map(|i| planar(model.mesh.positions[i as usize])))
            .collect(),
    );
    model.materials.push(crate::model::Material::named("b"));
    model.material = (0..24).map(|t| u32::from(t >= 12)).collect();
    let (m, r) = repair(&model, &RepairOptions::default()).unwrap();
    assert!(r.union.is_some());
    m.check().unwrap();
    let uvs = m.corners.uv.as_ref().unwrap();
    let mut seen = [false; 2];
    for (t, tri) in m.mesh.triangles.iter().enumerate() {
        let c = (0..3)
            .map(|k| m.mesh.positions[tri[k] as usize])
            .sum::<DVec3>()
            / 3.0;
        // No faces of the two cubes are coplanar: a triangle on cube a's surface has
        // a's material, every other one b's.
        let on_a = (c.abs().max_element() - 0.5).abs() < 1e-9;
        let material = m.material[t];
        seen[material as usize] = true;
        assert_eq!(material, u32::from(!on_a), "{c}");
        for k in 0..3 {
            let want = planar(m.mesh.positions[tri[k] as usize]);
            assert!((uvs[t][k][0] - want[0]).abs() < 1e-5 && (uvs[t][k][1] - want[1]).abs() < 1e-5);
        }
    }
    assert_eq!(seen, [true, true]);
}

#[test]
fn parts_meeting_face_to_face_a_rounding_error_apart_become_one_solid() {
    // Two boxes side by side along x, the second's touching face 1e-12 inside the
    // first (a 32-bit coordinate through a transform does this).
    let a = shapes::cube();
    let mut b = a.transformed(DVec3::ONE, DVec3::new(1.0, 0.25, 0.25));
    for p in &mut b.positions {
        if p.x < 0.75 {
            p.x -= 1e-12;
        }
    }
    let (m, r) = run(TriMesh::merge(&[a, b]));
    assert!(r.union.is_some());
    assert_eq!(m.mesh.validate_solid(), Ok(()));
    assert!((m.mesh.volume() - 2.0).abs() < 1e-9, "{}", m.mesh.volume());
}

#[test]
fn coordinates_a_rounding_error_apart_are_snapped_axis_by_axis() {
    let mut soup = soup::Soup::from_model(&Model::from_mesh(shapes::cube()));
    // x: 0.5 and 0.5 + 1e-9 join (a run starts at its lowest value); 0.5 + 3e-9 is more
    // than the tolerance beyond its neighbour and stays.
    soup.pos[0].x = 0.5;
    soup.pos[1].x = 0.5 + 1e-9;
    soup.pos[2].x = 0.5 + 3e-9;
    let before: Vec<DVec3> = soup.pos.clone();
    let changed = weld::coordinates(&mut soup, 1.5e-9);
    assert_eq!(soup.pos[1].x, 0.5);
    assert_eq!(soup.pos[2].x, 0.5 + 3e-9);
    // Nothing else moved: the cube's other coordinates are ±0.5 exactly, or equal.
    assert_eq!(changed, 1);
    for (p, q) in soup.pos.iter().zip(&before).skip(3) {
        assert_eq!(p, q);
    }
    // A run never spans more than four tolerances: a chain 0, 1, 2, … 9 (step 1 with
    // tolerance 1.5) is cut into runs each starting at its first value.
    let mut chain = soup::Soup::from_model(&Model::from_mesh(shapes::cube()));
    for (k, p) in chain.pos.iter_mut().enumerate().take(10) {
        p.y = 10.0 + k as f64;
    }
    weld::coordinates(&mut chain, 1.5);
    let ys: Vec<f64> = chain.pos.iter().take(10).map(|p| p.y).collect();
    assert!(ys.windows(2).all(|w| w[1] >= w[0]));
    for (k, y) in ys.iter().enumerate() {
        assert!(10.0 + k as f64 - y <= 6.0 + 1e-12, "{ys:?}");
    }
    assert!(
        ys.iter().any(|&y| y > 10.0),
        "one run swallowed the chain: {ys:?}"
    );
}
