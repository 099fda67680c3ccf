//! The pre-fractured asset (`SHATTER_fracture`): serde round trip of `Fracture`, GLB
//! write then read back (counts, mass properties, bonds, meshes, materials, convex
//! pieces), the file still an ordinary glTF, every malformed extension a clear error,
//! and the written extension valid against docs/shatter-fracture.schema.json.
#![allow(clippy::unwrap_used)]

#[path = "fracture_asset/errors.rs"]
mod errors;
mod schema;

use errors::split;

use std::path::Path;

use serde_json::{Value, json};
use shatter_geom::fracture::{Fracture, FractureParams, fracture, fracture_model};
use shatter_geom::io::{self, BreakThresholds, ExportObject, FractureAssetMeta, MeshIoError};
use shatter_geom::{DVec3, shapes};

fn voronoi(pieces: usize, seed: u64) -> FractureParams {
    FractureParams::voronoi(pieces, seed)
}

fn bird(pieces: usize) -> Fracture {
    fracture(&shapes::bird(), &voronoi(pieces, 1)).unwrap()
}

fn meta() -> FractureAssetMeta {
    FractureAssetMeta {
        anchors: vec![0, 2],
        material: Some("stone".into()),
        thresholds: Some(BreakThresholds {
            strength: 20_000.0,
            compression: 100e6,
            tension: 6e6,
            shear: 12e6,
            wear: 0.2,
        }),
    }
}

fn write(fr: &Fracture, meta: &FractureAssetMeta) -> Vec<u8> {
    let mut glb = Vec::new();
    io::write_fracture_glb(&mut glb, fr, meta).unwrap();
    glb
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1e-300)
}

fn close3(a: DVec3, b: DVec3) -> bool {
    (0..3).all(|k| (a[k] - b[k]).abs() <= 1e-9 * a.abs().max_element().max(b.abs().max_element()))
}

fn round(p: DVec3) -> [f32; 3] {
    p.as_vec3().to_array()
}

/// Checks that `back` is `fr` as the file stores it: same counts, mass properties and
/// bonds to 1e-9 relative, and each fragment's triangles, materials, interior flags and
/// corner attributes identical once positions are rounded to the file's `f32` and
/// triangles grouped by material (the file's primitives), in order within a material.
fn assert_same(fr: &Fracture, back: &Fracture, what: &str) {
    assert_eq!(back.fragments.len(), fr.fragments.len(), "{what}");
    assert_eq!(back.bonds.len(), fr.bonds.len(), "{what}");
    assert_eq!(back.materials, fr.materials, "{what}");
    for (i, (f, g)) in fr.fragments.iter().zip(&back.fragments).enumerate() {
        let what = format!("{what} fragment {i}");
        assert!(
            close(f.volume, g.volume),
            "{what}: {} {}",
            f.volume,
            g.volume
        );
        assert!(close3(f.centroid, g.centroid), "{what}");
        let (fi, gi) = (f.inertia.to_cols_array(), g.inertia.to_cols_array());
        let scale = fi.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(
            fi.iter()
                .zip(&gi)
                .all(|(x, y)| (x - y).abs() <= 1e-9 * scale),
            "{what}"
        );
        // Meshes: triangle by triangle in the file's order.
        let mut order: Vec<usize> = (0..f.mesh.triangles.len()).collect();
        order.sort_by_key(|&t| f.material[t]);
        assert_eq!(g.mesh.triangles.len(), order.len(), "{what}");
        for (k, &t) in order.iter().enumerate() {
            assert_eq!(
                f.mesh.triangle(t).map(round),
                g.mesh.triangle(k).map(round),
                "{what} triangle {t}"
            );
            assert_eq!(f.material[t], g.material[k], "{what} triangle {t}");
            assert_eq!(f.interior[t], g.interior[k], "{what} triangle {t}");
        }
        let c = f.corners.select(&order);
        assert_eq!(c, g.corners, "{what} corners");
        // Welding by the f32 positions loses no vertex the triangles use.
        let used: std::collections::BTreeSet<u32> =
            f.mesh.triangles.iter().flatten().copied().collect();
        assert_eq!(g.mesh.positions.len(), used.len(), "{what} vertices");
        assert!(g.mesh.check().is_solid(), "{what}: not a closed solid");
        // Convex pieces: the same points, as f32.
        assert_eq!(g.convex_pieces.len(), f.convex_pieces.len(), "{what}");
        for (p, q) in f.convex_pieces.iter().zip(&g.convex_pieces) {
            let p: Vec<[f32; 3]> = p.iter().map(|&v| round(v)).collect();
            let q: Vec<[f32; 3]> = q.iter().map(|&v| round(v)).collect();
            assert_eq!(p, q, "{what} convex piece");
        }
    }
    for (i, (a, b)) in fr.bonds.iter().zip(&back.bonds).enumerate() {
        assert_eq!((a.a, a.b), (b.a, b.b), "{what} bond {i}");
        assert!(close(a.area, b.area), "{what} bond {i}");
        assert!(close3(a.centroid, b.centroid), "{what} bond {i}");
        assert!(close3(a.normal, b.normal), "{what} bond {i}");
    }
}

#[test]
fn a_fracture_survives_a_serde_round_trip_exactly() {
    let fr = bird(12);
    let text = serde_json::to_string(&fr).unwrap();
    let back: Fracture = serde_json::from_str(&text).unwrap();
    assert_eq!(back, fr);
    // A textured one too: the image travels by value.
    let model = io::load_model(corpus("gltf/BoxTextured.glb"))
        .unwrap()
        .model;
    let fr = fracture_model(&model, &voronoi(6, 2)).unwrap();
    assert!(fr.materials[0].base_color_texture.is_some());
    let back: Fracture = serde_json::from_str(&serde_json::to_string(&fr).unwrap()).unwrap();
    assert_eq!(back, fr);
}

fn corpus(rel: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(rel)
}

#[test]
fn the_bird_written_and_read_back_is_the_same_fracture() {
    let fr = bird(40);
    assert!(fr.fragments.len() >= 30 && fr.bonds.len() > fr.fragments.len());
    let meta = meta();
    let glb = write(&fr, &meta);
    let (back, meta_back) = io::parse_fracture(&glb, "bird.glb").unwrap();
    assert_eq!(meta_back, meta);
    assert_same(&fr, &back, "bird");
    // Written again, the asset is the same file: nothing is lost on the second trip
    // (the fragments' flat normals are the writer's, recomputed from the same f32
    // positions, so only bytes of those could differ).
    let again = write(&back, &meta_back);
    let (twice, _) = io::parse_fracture(&again, "again.glb").unwrap();
    assert_same(&back, &twice, "bird, second trip");
}

#[test]
fn a_textured_model_keeps_its_uvs_normals_and_texture() {
    for file in ["gltf/BoxTextured.glb", "obj/cube_usemtl.obj"] {
        let model = io::load_model(corpus(file)).unwrap().model;
        let fr = fracture_model(&model, &voronoi(8, 3)).unwrap();
        let glb = write(&fr, &FractureAssetMeta::default());
        let (back, meta) = io::parse_fracture(&glb, file).unwrap();
        assert_eq!(meta, FractureAssetMeta::default());
        assert_same(&fr, &back, file);
    }
}

#[test]
fn the_asset_is_still_an_ordinary_gltf_with_the_same_nodes() {
    let fr = bird(20);
    let glb = write(&fr, &meta());
    let plain = plain_glb(&fr);
    let doc = gltf::Gltf::from_slice(&glb).unwrap();
    let plain_doc = gltf::Gltf::from_slice(&plain).unwrap();
    assert_eq!(doc.nodes().count(), plain_doc.nodes().count());
    assert_eq!(doc.nodes().count(), fr.fragments.len());
    assert_eq!(doc.meshes().count(), plain_doc.meshes().count());
    assert_eq!(
        doc.extensions_used().collect::<Vec<_>>(),
        ["SHATTER_fracture"]
    );
    assert_eq!(doc.extensions_required().count(), 0);
    // shatter's own glTF reader reads the same model from both.
    let a = io::parse_model(&glb, io::MeshFormat::Glb, "a.glb").unwrap();
    let b = io::parse_model(&plain, io::MeshFormat::Glb, "b.glb").unwrap();
    assert_eq!(a.model, b.model);
    assert!(a.warnings.is_empty(), "{:?}", a.warnings);
}

#[test]
fn a_file_saved_to_disk_reads_back() {
    let dir = tempfile_dir("asset-save");
    let path = dir.join("bird.glb");
    let fr = bird(10);
    io::save_fracture_glb(&path, &fr, &meta()).unwrap();
    let (back, _) = io::read_fracture(&path).unwrap();
    assert_same(&fr, &back, "saved");
    let err = io::read_fracture(dir.join("missing.glb")).unwrap_err();
    assert!(matches!(err, MeshIoError::Io { .. }), "{err}");
}

fn tempfile_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("shatter-test-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_writer_refuses_an_anchor_or_bond_to_a_missing_fragment() {
    let fr = bird(6);
    let mut glb = Vec::new();
    let bad = FractureAssetMeta {
        anchors: vec![99],
        ..Default::default()
    };
    let err = io::write_fracture_glb(&mut glb, &fr, &bad).unwrap_err();
    assert!(err.to_string().contains("anchor 99"), "{err}");
    let mut broken = fr.clone();
    broken.bonds[0].b = 77;
    let err = io::write_fracture_glb(&mut glb, &broken, &FractureAssetMeta::default()).unwrap_err();
    assert!(err.to_string().contains("bond 0"), "{err}");
}

#[test]
fn the_written_extension_follows_the_json_schema() {
    let schema: Value = serde_json::from_str(
        &std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/shatter-fracture.schema.json"),
        )
        .unwrap(),
    )
    .unwrap();
    for (what, fr, meta) in [
        ("bird", bird(12), meta()),
        ("bare", bird(4), FractureAssetMeta::default()),
    ] {
        let (json, _) = split(&write(&fr, &meta));
        let root = &json["extensions"]["SHATTER_fracture"];
        schema::validate(&schema, "#/$defs/root", root).unwrap_or_else(|e| panic!("{what}: {e}"));
        for (n, node) in json["nodes"].as_array().unwrap().iter().enumerate() {
            let ext = &node["extensions"]["SHATTER_fracture"];
            schema::validate(&schema, "#/$defs/fragment", ext)
                .unwrap_or_else(|e| panic!("{what} node {n}: {e}"));
        }
        // The validator does reject what the schema forbids.
        let mut broken = root.clone();
        broken.as_object_mut().unwrap().remove("bonds");
        assert!(schema::validate(&schema, "#/$defs/root", &broken).is_err());
        let mut broken = root.clone();
        broken["bonds"][0]["centroid"] = json!([1.0]);
        assert!(schema::validate(&schema, "#/$defs/root", &broken).is_err());
        let mut broken = json["nodes"][0]["extensions"]["SHATTER_fracture"].clone();
        broken["volume"] = json!("big");
        assert!(schema::validate(&schema, "#/$defs/fragment", &broken).is_err());
    }
}

/// The extension's cost in bytes on the bird cut into 100 Voronoi cells (as
/// `shatter fracture --shape bird --pieces 100 --out bird.glb` does): printed with
/// `--nocapture`, and bounded (under the plain file's size, whose vertices are shared
/// where position and attributes agree) so that it cannot quietly grow.
#[test]
fn the_extension_costs_less_than_the_plain_file() {
    let model = shatter_geom::model::Model::from_mesh(shapes::bird());
    let fr = fracture_model(&model, &voronoi(100, 0)).unwrap();
    let asset = write(&fr, &FractureAssetMeta::default());
    let plain = plain_glb(&fr);
    let (json, _) = split(&asset);
    let ext_json = serde_json::to_vec(&json["extensions"]).unwrap().len()
        + json["nodes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| serde_json::to_vec(&n["extensions"]).unwrap().len())
            .sum::<usize>();
    let points: usize = fr
        .fragments
        .iter()
        .flat_map(|f| &f.convex_pieces)
        .map(Vec::len)
        .sum();
    println!(
        "bird voronoi 100: {} fragments, {} bonds, {points} convex-piece points; plain GLB {} bytes, with SHATTER_fracture {} bytes (+{}, +{:.1} %; extension JSON {ext_json} bytes, points {} bytes)",
        fr.fragments.len(),
        fr.bonds.len(),
        plain.len(),
        asset.len(),
        asset.len() - plain.len(),
        100.0 * (asset.len() - plain.len()) as f64 / plain.len() as f64,
        12 * points,
    );
    assert!(asset.len() > plain.len());
    assert!(asset.len() - plain.len() < plain.len());
    let (back, _) = io::parse_fracture(&asset, "bird100.glb").unwrap();
    assert_same(&fr, &back, "bird voronoi 100");
}

#[test]
fn the_writer_refuses_interior_faces_it_could_not_tell_apart() {
    // An interior triangle under a surface material: a reader could not recover the
    // interior flags from the materials, so the writer says so instead of writing.
    let mut fr = bird(6);
    let f = &mut fr.fragments[0];
    let t = f.interior.iter().position(|&i| i).unwrap();
    f.material[t] = 0;
    let mut glb = Vec::new();
    let err = io::write_fracture_glb(&mut glb, &fr, &FractureAssetMeta::default()).unwrap_err();
    assert!(err.to_string().contains("interior"), "{err}");
    // Interior faces under two materials: refused too.
    let mut fr = bird(6);
    fr.materials
        .push(shatter_geom::model::Material::named("second interior"));
    let f = &mut fr.fragments[1];
    let t = f.interior.iter().position(|&i| i).unwrap();
    f.material[t] = fr.materials.len() as u32 - 1;
    let err = io::write_fracture_glb(&mut glb, &fr, &FractureAssetMeta::default()).unwrap_err();
    assert!(err.to_string().contains("2 materials"), "{err}");
}

/// The same fragments as an ordinary GLB (no extension), as the writers export them.
fn plain_glb(fr: &Fracture) -> Vec<u8> {
    let names = io::fragment_names(fr.fragments.len());
    let objects = ExportObject::of_fragments(&fr.fragments, &names);
    let mut plain = Vec::new();
    io::write_glb_with_materials(&mut plain, &objects, &fr.materials).unwrap();
    plain
}
