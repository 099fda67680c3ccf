//! Writers with materials: a textured model written as OBJ + MTL (textures copied next to
//! it) and as GLB (images embedded) reads back with the same materials, images, UVs,
//! normals and colours, by shatter's reader and by independent ones (`tobj`, `gltf`).
#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};

use shatter_geom::io::{self, ExportObject};
use shatter_geom::model::Model;

fn corpus(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(rel)
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shatter-iomat-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Per triangle, its corners' positions, UVs and normals and its material's name and
/// image bytes: what must survive a round trip (positions to f32 for GLB), sorted (the
/// writers group triangles by material).
fn signature(m: &Model, f32_positions: bool) -> Vec<String> {
    let mut s: Vec<String> = (0..m.mesh.triangles.len())
        .map(|t| {
            let p = m.mesh.triangle(t).map(|p| {
                if f32_positions {
                    p.as_vec3().as_dvec3()
                } else {
                    p
                }
            });
            let material = &m.materials[m.material[t] as usize];
            let image = material
                .base_color_texture
                .as_ref()
                .map(|t| t.image.bytes.len());
            format!(
                "{p:?} {:?} {:?} {:?} {} {:?} {:?}",
                m.corners.uv.as_ref().map(|u| u[t]),
                m.corners.normal.as_ref().map(|n| n[t]),
                m.corners.color.as_ref().map(|c| c[t]),
                material.name,
                material.base_color,
                image
            )
        })
        .collect();
    s.sort();
    s
}

/// Asserts equal signatures, printing only the first difference.
fn same(a: &[String], b: &[String], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}: triangles");
    if let Some(i) = (0..a.len()).find(|&i| a[i] != b[i]) {
        panic!("{what}: triangle {i} differs:\n{}\n{}", a[i], b[i]);
    }
}

#[test]
fn a_textured_obj_round_trips_through_obj_with_its_textures_copied() {
    let spider = io::load_model(corpus("obj/spider/spider.obj"))
        .unwrap()
        .model;
    let dir = temp_dir("obj");
    let out = dir.join("spider out.obj");
    let object = ExportObject::of_model("spider", &spider);
    io::save_obj_with_materials(&out, &[object], &spider.materials).unwrap();
    // The four used textures, copied next to the output.
    let mut copied: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".jpg"))
        .collect();
    copied.sort();
    assert_eq!(
        copied,
        [
            "spider_out_SpiderTex.jpg",
            "spider_out_drkwood2.jpg",
            "spider_out_engineflare1.jpg",
            "spider_out_wal67ar_small.jpg"
        ]
    );
    let back = io::load_model(&out).unwrap();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    let back = back.model;
    // The writer adds an `interior` material that no triangle uses; the reader keeps
    // only used ones.
    assert_eq!(back.materials.len(), spider.materials.len());
    // Zero normals came in as the face's normal and go out as it: equal.
    same(
        &signature(&back, false),
        &signature(&spider, false),
        "spider",
    );
    for (a, b) in back.materials.iter().zip(&spider.materials) {
        assert_eq!(
            a.base_color_texture.as_ref().map(|t| &t.image.bytes),
            b.base_color_texture.as_ref().map(|t| &t.image.bytes)
        );
    }
    // tobj reads the same materials and texture names.
    let (models, materials) = tobj::load_obj(&out, &tobj::GPU_LOAD_OPTIONS).unwrap();
    let materials = materials.unwrap();
    let textured = materials
        .iter()
        .filter(|m| m.diffuse_texture.is_some())
        .count();
    assert_eq!(textured, 4);
    let faces: usize = models.iter().map(|m| m.mesh.indices.len() / 3).sum();
    assert_eq!(faces, spider.mesh.triangles.len());
    assert!(models.iter().all(|m| !m.mesh.texcoords.is_empty()));
}

#[test]
fn a_textured_glb_round_trips_through_glb_with_its_image_embedded() {
    let boxed = io::load_model(corpus("gltf/BoxTextured/BoxTextured.gltf"))
        .unwrap()
        .model;
    let mut glb = Vec::new();
    let object = ExportObject::of_model("box", &boxed);
    io::write_glb_with_materials(&mut glb, &[object], &boxed.materials).unwrap();
    let back = io::parse_model(&glb, io::MeshFormat::Glb, "box.glb").unwrap();
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    same(
        &signature(&back.model, true),
        &signature(&boxed, true),
        "box",
    );
    let png = std::fs::read(corpus("gltf/BoxTextured/CesiumLogoFlat.png")).unwrap();
    let image = &back.model.materials[0]
        .base_color_texture
        .as_ref()
        .unwrap()
        .image;
    assert_eq!(image.bytes, png);
    // The gltf crate sees one textured material, the interior material, TEXCOORD_0.
    let (doc, buffers, images) = gltf::import_slice(&glb).unwrap();
    assert_eq!(doc.materials().count(), 2);
    let m = doc.materials().next().unwrap();
    assert!(m.pbr_metallic_roughness().base_color_texture().is_some());
    assert_eq!(images.len(), 1);
    assert_eq!((images[0].width, images[0].height), (211, 211));
    let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|b| Some(&buffers[b.index()].0[..]));
    // 12 triangles on 24 vertices, four per face, as in the file read: a vertex is
    // shared where position, normal and UV agree.
    assert_eq!(reader.read_indices().unwrap().into_u32().count(), 36);
    assert_eq!(reader.read_tex_coords(0).unwrap().into_f32().count(), 24);
}

#[test]
fn vertex_colours_and_several_materials_survive_obj_and_glb() {
    for file in ["obj/cube_with_vertexcolors.obj", "obj/cube_usemtl.obj"] {
        let model = io::load_model(corpus(file)).unwrap().model;
        let dir = temp_dir("colours");
        let out = dir.join("out.obj");
        let object = ExportObject::of_model("m", &model);
        io::save_obj_with_materials(&out, &[object], &model.materials).unwrap();
        let back = io::load_model(&out).unwrap().model;
        same(&signature(&back, false), &signature(&model, false), file);
        let mut glb = Vec::new();
        io::write_glb_with_materials(&mut glb, &[object], &model.materials).unwrap();
        let back = io::parse_model(&glb, io::MeshFormat::Glb, "m.glb")
            .unwrap()
            .model;
        assert_eq!(back.materials.len(), model.materials.len(), "{file}");
        assert_eq!(
            back.corners.color.is_some(),
            model.corners.color.is_some(),
            "{file}"
        );
        assert_eq!(signature(&back, true).len(), model.mesh.triangles.len());
    }
}

#[test]
fn export_objects_with_bad_materials_or_corners_are_refused() {
    let model = io::load_model(corpus("obj/cube_usemtl.obj")).unwrap().model;
    let too_few = &model.materials[..1];
    let object = ExportObject::of_model("cube", &model);
    let err = io::write_glb_with_materials(Vec::new(), &[object], too_few).unwrap_err();
    assert!(
        err.to_string().starts_with("object cube: triangle"),
        "{err}"
    );
    let mut short = model.corners.clone();
    short.normal.as_mut().unwrap().pop();
    let object = ExportObject::of_model("cube", &model).with_corners(&short);
    let err = io::write_obj_with_materials(Vec::new(), &[object], Some(&model.materials), None)
        .unwrap_err();
    assert_eq!(
        err.to_string(),
        "object cube: 11 normal entries for 12 triangles"
    );
}
