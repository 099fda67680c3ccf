//! `shatter inspect` and batch `shatter fracture`, end to end through the real binary.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::{Path, PathBuf};

use common::shatter;

fn corpus(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(rel)
}

#[test]
fn inspect_reports_shells_holes_materials_and_uvs() {
    let dir = tempfile::tempdir().unwrap();
    let spider = corpus("obj/spider/spider.obj");
    let json = shatter(dir.path(), &["inspect", spider.to_str().unwrap(), "--json"])
        .ok()
        .json();
    assert_eq!(json["triangles"], 1368);
    assert_eq!(json["materials"].as_array().unwrap().len(), 4);
    assert_eq!(json["uv_sets"], 1);
    assert_eq!(json["solid"], false);
    let shells = json["shells"].as_array().unwrap();
    assert_eq!(shells.len(), 18);
    let sphere = corpus("stl/sphereWithHole.stl");
    let text = shatter(dir.path(), &["inspect", sphere.to_str().unwrap()])
        .ok()
        .stdout;
    assert!(
        text.contains("shells: 1 (0 closed, 1 open), 1 hole"),
        "{text}"
    );
    assert!(text.contains("repair: filled 3 holes with"), "{text}");
    let v1 = corpus("gltf1/BoxTextured_v1.gltf");
    shatter(dir.path(), &["inspect", v1.to_str().unwrap()])
        .bad_input(&["glTF 1.0 is not supported"]);
    // A folder is refused as one, not as a file of an unknown format.
    let folder = corpus("obj/spider");
    shatter(dir.path(), &["inspect", folder.to_str().unwrap()])
        .bad_input(&["spider: is a folder: inspect takes one mesh file"]);
}

#[test]
fn a_batch_writes_one_output_per_input_and_goes_on_past_a_failure() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let good = corpus("gltf/BoxTextured.glb");
    // Two flat triangles: nothing with a volume, so repair refuses it.
    let open = corpus("stl/triangle_with_two_solids.stl");
    let args = [
        "fracture",
        good.to_str().unwrap(),
        open.to_str().unwrap(),
        "--pieces",
        "6",
        "--out-dir",
        out.to_str().unwrap(),
        "--json",
    ];
    let run = shatter(dir.path(), &args);
    // One file is a flat sheet: bad input, exit 2, and the other is written.
    assert_eq!(run.code, 2, "{}", run.stderr);
    let summary = run.json();
    assert_eq!(
        (summary["succeeded"].as_u64(), summary["failed"].as_u64()),
        (Some(1), Some(1))
    );
    assert!(
        summary["results"][1]["error"]
            .as_str()
            .unwrap()
            .contains("open sheets and no closed part")
    );
    assert!(out.join("BoxTextured.glb").is_file());
    let on_disk: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(on_disk["exit_code"], 2);
    let back = shatter_geom::io::load_mesh(out.join("BoxTextured.glb")).unwrap();
    assert!(!back.triangles.is_empty());
    // A folder of good files: exit 0, OBJ outputs.
    let input = dir.path().join("in");
    std::fs::create_dir_all(&input).unwrap();
    std::fs::copy(corpus("obj/box.obj"), input.join("box.obj")).unwrap();
    std::fs::copy(good, input.join("box.glb")).unwrap();
    let out2 = dir.path().join("out2");
    shatter(
        dir.path(),
        &[
            "fracture",
            input.to_str().unwrap(),
            "--out-dir",
            out2.to_str().unwrap(),
            "--out-format",
            "obj",
            "--pieces",
            "4",
        ],
    )
    .ok();
    // Two inputs named box: their outputs keep the input's extension apart.
    assert!(out2.join("box_obj.obj").is_file() && out2.join("box_glb.obj").is_file());
    // Several files without --out-dir: refused before any work.
    shatter(dir.path(), &["fracture", input.to_str().unwrap()]).bad_input(&["--out-dir"]);
}

#[test]
fn fracture_repairs_an_open_mesh_unless_strict() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = corpus("stl/sphereWithHole.stl");
    let run = shatter(
        dir.path(),
        &[
            "fracture",
            sphere.to_str().unwrap(),
            "--pieces",
            "6",
            "--json",
        ],
    )
    .ok();
    let json = run.json();
    assert!(json["fragments"].as_u64().unwrap() >= 2);
    let warnings = json["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("filled 3 holes")),
        "{warnings:?}"
    );
    let (v, f) = (
        json["mesh_volume"].as_f64().unwrap(),
        json["fragments_volume"].as_f64().unwrap(),
    );
    assert!((v - f).abs() <= 1e-6 * v, "{v} {f}");
    // --strict: today's refusal.
    shatter(
        dir.path(),
        &["fracture", sphere.to_str().unwrap(), "--strict"],
    )
    .bad_input(&["boundary edges"]);
    // Nothing solid: refused, saying what was found.
    let sheet = corpus("stl/triangle_with_two_solids.stl");
    shatter(dir.path(), &["fracture", sheet.to_str().unwrap()])
        .bad_input(&["open sheets and no closed part"]);
    // Intersecting parts: fractured as their union.
    let spider = corpus("stl/Spider_binary.stl");
    let json = shatter(
        dir.path(),
        &[
            "fracture",
            spider.to_str().unwrap(),
            "--pieces",
            "5",
            "--json",
        ],
    )
    .ok()
    .json();
    let warnings = json["warnings"].as_array().unwrap();
    assert!(
        warnings
            .iter()
            .any(|w| w.as_str().unwrap().contains("replaced by their union")),
        "{warnings:?}"
    );
}
