//! Round trips through OBJ, STL (ASCII and binary) and GLB: volume and topology kept.
#![allow(clippy::unwrap_used)]

use std::path::PathBuf;

use shatter_geom::io::{self, ExportObject, StlFormat};
use shatter_geom::{DVec3, TriMesh, shapes};

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shatter-io-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Topology of the welded mesh, without the volume.
fn topology(m: &TriMesh) -> (usize, usize, usize, usize, bool) {
    let r = m.check();
    (
        r.vertices,
        r.triangles,
        r.components,
        r.boundary_edges,
        r.is_solid(),
    )
}

#[test]
fn obj_round_trip_is_exact() {
    let dir = temp_dir("obj");
    for name in shapes::NAMES {
        let mesh = shapes::by_name(name).unwrap();
        let path = dir.join(format!("{name}.obj"));
        io::save_obj(&path, &[ExportObject::new(name, &mesh)]).unwrap();
        let back = io::load_mesh(&path).unwrap();
        // Shortest round-trip formatting: every triangle's corners come back bit for bit
        // (tobj may reorder the vertex list).
        assert_eq!(back.triangles.len(), mesh.triangles.len(), "{name}");
        let same = (0..mesh.triangles.len()).all(|t| back.triangle(t) == mesh.triangle(t));
        assert!(same, "{name}: corners differ");
        assert_eq!(topology(&back), topology(&mesh), "{name}");
        let rel = (back.signed_volume() - mesh.signed_volume()).abs() / mesh.volume();
        assert!(rel < 1e-14, "{name}: {rel}");
    }
}

#[test]
fn obj_objects_materials_and_interior_faces() {
    let dir = temp_dir("obj-multi");
    let a = shapes::cube();
    let b = shapes::bird().transformed(DVec3::ONE, DVec3::new(4.0, 0.0, 0.0));
    let flags_a: Vec<bool> = (0..12).map(|t| t < 4).collect();
    let path = dir.join("two.obj");
    io::save_obj(
        &path,
        &[
            ExportObject::new("fragment_0", &a).with_interior(&flags_a),
            ExportObject::new("fragment_1", &b),
        ],
    )
    .unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    assert!(text.contains("mtllib two.mtl\n"));
    assert_eq!(text.matches("\no fragment_").count(), 2);
    assert_eq!(text.matches("usemtl interior").count(), 1);
    assert_eq!(text.matches("usemtl surface").count(), 2);
    // tobj reads the objects back with their materials.
    let (models, materials) = tobj::load_obj(&path, &tobj::GPU_LOAD_OPTIONS).unwrap();
    let materials = materials.unwrap();
    let names: Vec<&str> = materials.iter().map(|m| m.name.as_str()).collect();
    assert_eq!(names, ["surface", "interior"]);
    let interior_id = 1;
    let interior_faces: usize = models
        .iter()
        .filter(|m| m.mesh.material_id == Some(interior_id))
        .map(|m| m.mesh.indices.len() / 3)
        .sum();
    assert_eq!(interior_faces, 4);
    let back = io::load_mesh(&path).unwrap();
    assert_eq!(back.triangles.len(), 12 + 1394);
    assert_eq!(back.check().components, 2);
    assert!((back.volume() - a.volume() - b.volume()).abs() < 1e-12);
}

#[test]
fn stl_round_trip_ascii_and_binary() {
    let dir = temp_dir("stl");
    for format in [StlFormat::Ascii, StlFormat::Binary] {
        for name in shapes::NAMES {
            let mesh = shapes::by_name(name).unwrap();
            let path = dir.join(format!("{name}-{format:?}.stl"));
            io::save_stl(&path, &mesh, format).unwrap();
            let back = io::load_mesh(&path).unwrap();
            assert_eq!(topology(&back), topology(&mesh), "{name} {format:?}");
            // STL is single precision.
            let rel = (back.volume() - mesh.volume()).abs() / mesh.volume();
            assert!(rel < 1e-6, "{name} {format:?}: {rel}");
            // The soup is welded on import.
            assert_eq!(back.positions.len(), mesh.check().vertices);
        }
    }
}

#[test]
fn glb_round_trip_keeps_volume_topology_nodes_and_materials() {
    let dir = temp_dir("glb");
    let bird = shapes::bird();
    let capsule = shapes::capsule().transformed(DVec3::splat(0.5), DVec3::new(0.0, 3.0, 0.0));
    let flags: Vec<bool> = (0..capsule.triangles.len()).map(|t| t % 3 == 0).collect();
    let path = dir.join("objects.glb");
    io::save_glb(
        &path,
        &[
            ExportObject::new("bird", &bird),
            ExportObject::new("capsule", &capsule).with_interior(&flags),
        ],
    )
    .unwrap();
    let bytes = std::fs::read(&path).unwrap();
    let gltf = gltf::Gltf::from_slice(&bytes).unwrap();
    let nodes: Vec<String> = gltf
        .nodes()
        .map(|n| n.name().unwrap_or("").to_string())
        .collect();
    assert_eq!(nodes, ["bird", "capsule"]);
    let materials: Vec<&str> = gltf.materials().map(|m| m.name().unwrap_or("")).collect();
    assert_eq!(materials, ["surface", "interior"]);
    let capsule_mesh = gltf.meshes().nth(1).unwrap();
    let counts: Vec<(Option<usize>, usize)> = capsule_mesh
        .primitives()
        .map(|p| (p.material().index(), p.indices().unwrap().count() / 3))
        .collect();
    let interior = flags.iter().filter(|&&f| f).count();
    assert_eq!(
        counts,
        [(Some(0), flags.len() - interior), (Some(1), interior)]
    );
    // No normals given: no NORMAL (a client computes flat ones), and a vertex shared by
    // the triangles around it, so a primitive has no more vertices than its positions.
    let (doc, buffers, _) = gltf::import(&path).unwrap();
    for (mesh, source) in doc.meshes().zip([&bird, &capsule]) {
        for p in mesh.primitives() {
            assert!(p.get(&gltf::Semantic::Normals).is_none());
            let r = p.reader(|b| Some(&buffers[b.index()]));
            let positions: Vec<[f32; 3]> = r.read_positions().unwrap().collect();
            let mut distinct: Vec<[u32; 3]> =
                positions.iter().map(|p| p.map(f32::to_bits)).collect();
            distinct.sort_unstable();
            distinct.dedup();
            assert_eq!(distinct.len(), positions.len());
            assert!(positions.len() <= source.positions.len());
        }
    }
    let back = io::load_mesh(&path).unwrap();
    let merged = TriMesh::merge(&[bird.clone(), capsule.clone()]);
    assert_eq!(topology(&back), topology(&merged));
    let rel = (back.volume() - merged.volume()).abs() / merged.volume();
    assert!(rel < 1e-6, "{rel}");
}

/// A hand-made glTF with an external buffer, one mesh instanced twice (once mirrored),
/// and a triangle strip.
#[test]
fn gltf_node_transforms_mirrors_and_strips() {
    let dir = temp_dir("gltf");
    // A tetrahedron as a triangle list, and a unit square (two triangles) as a strip.
    let tet: [[f32; 3]; 4] = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let tet_indices: [u16; 12] = [0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3];
    let strip: [[f32; 3]; 4] = [
        [0.0, 0.0, 5.0],
        [1.0, 0.0, 5.0],
        [0.0, 1.0, 5.0],
        [1.0, 1.0, 5.0],
    ];
    let mut bin = Vec::new();
    for p in tet.iter().chain(&strip) {
        for c in p {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in tet_indices {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    std::fs::write(dir.join("tet.bin"), &bin).unwrap();
    let json = format!(
        r#"{{
  "asset": {{"version": "2.0"}},
  "scene": 0,
  "scenes": [{{"nodes": [0, 1, 2]}}],
  "nodes": [
    {{"mesh": 0, "translation": [10, 0, 0]}},
    {{"mesh": 0, "scale": [-1, 1, 1], "children": [3]}},
    {{"mesh": 1}},
    {{"mesh": 0, "translation": [0, 20, 0]}}
  ],
  "meshes": [
    {{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 2}}]}},
    {{"primitives": [{{"attributes": {{"POSITION": 1}}, "mode": 5}}]}}
  ],
  "buffers": [{{"uri": "tet.bin", "byteLength": {len}}}],
  "bufferViews": [
    {{"buffer": 0, "byteOffset": 0, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 48, "byteLength": 48}},
    {{"buffer": 0, "byteOffset": 96, "byteLength": 24}}
  ],
  "accessors": [
    {{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [0, 0, 0], "max": [1, 1, 1]}},
    {{"bufferView": 1, "componentType": 5126, "count": 4, "type": "VEC3",
      "min": [0, 0, 5], "max": [1, 1, 5]}},
    {{"bufferView": 2, "componentType": 5123, "count": 12, "type": "SCALAR"}}
  ]
}}"#,
        len = bin.len()
    );
    let path = dir.join("scene.gltf");
    std::fs::write(&path, json).unwrap();
    let m = io::load_mesh(&path).unwrap();
    // Three tetrahedra (translated, mirrored, child of the mirrored node) + 2 strip
    // triangles.
    assert_eq!(m.triangles.len(), 3 * 4 + 2);
    let tets = TriMesh::new(m.positions.clone(), m.triangles[..12].to_vec());
    // Mirrored instances stay outward: each tetrahedron adds +1/6.
    assert!((tets.signed_volume() - 3.0 / 6.0).abs() < 1e-12);
    assert_eq!(tets.check().components, 3);
    assert!(tets.check().is_solid());
    // The child node inherits the mirror and adds its own translation.
    let corners: Vec<DVec3> = (0..12).flat_map(|t| tets.triangle(t)).collect();
    let (lo, hi) = TriMesh::new(corners, vec![]).bounds().unwrap();
    assert_eq!(
        (lo, hi),
        (DVec3::new(-1.0, 0.0, 0.0), DVec3::new(11.0, 21.0, 1.0))
    );
    // The strip's triangles both face +z.
    for t in 12..14 {
        assert_eq!(m.triangle_normal(t), DVec3::Z);
    }
}

/// Smooth normals are written, and a vertex is shared where position and attributes
/// agree: a UV sphere with its own normals has one vertex per position but at its seam.
#[test]
fn glb_writes_smooth_normals_and_shares_vertices_where_attributes_agree() {
    use shatter_geom::model::Model;
    let sphere = shapes::sphere(24, 12);
    let mut model = Model::from_mesh(sphere.clone());
    // Smooth normals: the direction from the centre. UVs: longitude and latitude, so
    // the corners at longitude 0 differ between the two sides of the seam.
    let corner = |p: DVec3| p.normalize();
    model.corners.normal = Some(
        sphere
            .triangles
            .iter()
            .map(|t| t.map(|i| corner(sphere.positions[i as usize]).as_vec3().to_array()))
            .collect(),
    );
    let dir = temp_dir("glb_smooth");
    let path = dir.join("sphere.glb");
    let fracture = shatter_geom::fracture::intact(&model).unwrap();
    io::save_glb_with_materials(
        &path,
        &[ExportObject::new("sphere", &fracture.fragments[0].mesh)
            .with_corners(&fracture.fragments[0].corners)],
        &fracture.materials,
    )
    .unwrap();
    let (doc, buffers, _) = gltf::import(&path).unwrap();
    let p = doc.meshes().next().unwrap().primitives().next().unwrap();
    let r = p.reader(|b| Some(&buffers[b.index()]));
    let normals: Vec<[f32; 3]> = r
        .read_normals()
        .expect("smooth normals are written")
        .collect();
    let positions: Vec<[f32; 3]> = r.read_positions().unwrap().collect();
    for (n, q) in normals.iter().zip(&positions) {
        let want = corner(DVec3::from(q.map(f64::from)));
        assert!((DVec3::from(n.map(f64::from)) - want).length() < 1e-5);
    }
    // The sphere has UVs (a box projection, made by the fracture): seams split a few
    // positions, but far fewer than the three per triangle a per-corner writer makes.
    let triangles = p.indices().unwrap().count() / 3;
    assert_eq!(triangles, sphere.triangles.len());
    assert!(positions.len() >= sphere.positions.len());
    assert!(
        positions.len() < 2 * sphere.positions.len(),
        "{}",
        positions.len()
    );
    let back = io::load_model(&path).unwrap().model;
    assert_eq!(back.mesh.triangles.len(), sphere.triangles.len());
    assert!(back.corners.normal.is_some());
}
