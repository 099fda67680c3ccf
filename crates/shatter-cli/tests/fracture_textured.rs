//! `shatter fracture` of a textured model (issue 13): the fragments keep the model's UVs,
//! materials and texture in OBJ+MTL (texture copied next to it) and GLB (embedded).
#![allow(clippy::unwrap_used)]

mod common;

use std::path::PathBuf;

use common::shatter;
use shatter_geom::io;

fn box_textured() -> String {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus/gltf/BoxTextured.glb")
        .display()
        .to_string()
}

#[test]
fn a_textured_box_fractures_into_textured_fragments_in_obj_and_glb() {
    let dir = tempfile::tempdir().unwrap();
    for method in ["voronoi", "slice", "tetra"] {
        for ext in ["obj", "glb"] {
            let out = format!("{method}.{ext}");
            let input = box_textured();
            let mut args = vec!["fracture", &input, "--method", method, "--out", &out];
            if method != "tetra" {
                args.extend(["--pieces", "6"]);
            }
            shatter(dir.path(), &args).ok();
            let back = io::load_model(dir.path().join(&out)).unwrap().model;
            let what = format!("{method} {ext}");
            let uv = back
                .corners
                .uv
                .as_ref()
                .unwrap_or_else(|| panic!("{what}: no UVs"));
            assert_eq!(uv.len(), back.mesh.triangles.len(), "{what}");
            let textured: Vec<_> = back
                .materials
                .iter()
                .filter(|m| m.base_color_texture.is_some())
                .collect();
            assert_eq!(textured.len(), 1, "{what}: {:?}", back.materials);
            assert!(
                back.materials.iter().any(|m| m.name == "interior"),
                "{what}"
            );
            // Both kinds of faces are there: the texture's and the interior's.
            let interior = back
                .materials
                .iter()
                .position(|m| m.name == "interior")
                .unwrap();
            assert!(back.material.contains(&(interior as u32)), "{what}");
            assert!(
                back.material.iter().any(|&m| m as usize != interior),
                "{what}"
            );
        }
        // The OBJ's texture sits next to it, named in the MTL.
        let mtl = std::fs::read_to_string(dir.path().join(format!("{method}.mtl"))).unwrap();
        let map = mtl
            .lines()
            .find_map(|l| l.strip_prefix("map_Kd "))
            .unwrap_or_else(|| panic!("{method}: no map_Kd in\n{mtl}"));
        let png = std::fs::read(dir.path().join(map)).unwrap();
        assert_eq!(&png[1..4], b"PNG", "{method}: {map}");
    }
}
