//! Parser fuzzing (issue 14 part 7): random bytes and mutated real files (bit flips,
//! truncations, insertions; for glTF, mutations of the JSON fields that locate data:
//! accessor indices, types, component types, strides, offsets, counts, huge counts) fed
//! to the OBJ, MTL, STL, glTF and GLB readers. Each must return a model or an error —
//! never panic — and never allocate from a count in the file before the count is known
//! to fit in the file's bytes (a huge count that were believed would abort the process).
//!
//! Case counts are kept small for CI (about 2,300 cases in all, a few seconds); raise
//! `PROPTEST_CASES` to fuzz longer.
#![allow(clippy::unwrap_used)]

use std::path::Path;

use proptest::prelude::*;
use serde_json::Value;
use shatter_geom::io::{self, MemoryFiles, MeshFormat};

fn corpus(rel: &str) -> Vec<u8> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(rel);
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

fn cases(n: u32) -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(n),
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// Parses `bytes` as `format`, with `files` beside it; the result does not matter, only
/// that there is one (a panic fails the test). A model must pass its own check.
fn parse(bytes: &[u8], format: MeshFormat, name: &str, files: &MemoryFiles) {
    if let Ok(loaded) = io::parse_model_with(bytes, format, name, files) {
        loaded.model.check().unwrap();
        assert!(!loaded.model.mesh.triangles.is_empty());
    }
}

/// A mutation of a valid file.
#[derive(Debug, Clone)]
enum Mutation {
    Flip { at: usize, bit: u8 },
    Truncate { at: usize },
    Insert { at: usize, byte: u8 },
    Overwrite { at: usize, bytes: Vec<u8> },
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), 0u8..8).prop_map(|(at, bit)| Mutation::Flip { at, bit }),
        any::<usize>().prop_map(|at| Mutation::Truncate { at }),
        (any::<usize>(), any::<u8>()).prop_map(|(at, byte)| Mutation::Insert { at, byte }),
        (any::<usize>(), prop::collection::vec(any::<u8>(), 1..8))
            .prop_map(|(at, bytes)| Mutation::Overwrite { at, bytes }),
    ]
}

fn mutate(bytes: &[u8], mutations: &[Mutation]) -> Vec<u8> {
    let mut out = bytes.to_vec();
    for m in mutations {
        if out.is_empty() {
            break;
        }
        match m {
            Mutation::Flip { at, bit } => {
                let i = at % out.len();
                out[i] ^= 1 << bit;
            }
            Mutation::Truncate { at } => out.truncate(at % out.len()),
            Mutation::Insert { at, byte } => {
                let i = at % (out.len() + 1);
                out.insert(i, *byte);
            }
            Mutation::Overwrite { at, bytes } => {
                let i = at % out.len();
                for (k, b) in bytes.iter().enumerate() {
                    if let Some(slot) = out.get_mut(i + k) {
                        *slot = *b;
                    }
                }
            }
        }
    }
    out
}

/// Text-level mutations that matter to OBJ and MTL: numbers, indices, keywords.
fn text_token() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec![
        "nan",
        "inf",
        "-0",
        "1e999",
        ".5",
        "1.",
        "+1",
        "0",
        "-1",
        "-99999",
        "4294967296",
        "99999999999999999999",
        "/",
        "//",
        "1/2/3",
        "f",
        "v",
        "vt",
        "vn",
        "l",
        "p",
        "usemtl",
        "mtllib",
        "newmtl",
        "map_Kd",
        "-bm",
        "\\",
        "\r",
        "\n",
        "\u{FEFF}",
        "#",
        " ",
        "\t",
    ])
}

fn text_mutate(text: &[u8], at: usize, token: &str) -> Vec<u8> {
    let i = at % (text.len() + 1);
    let mut out = text[..i].to_vec();
    out.extend_from_slice(token.as_bytes());
    out.extend_from_slice(&text[i..]);
    out
}

/// Every number in a JSON document, by its path.
fn number_paths(v: &Value, path: &mut Vec<Step>, out: &mut Vec<Vec<Step>>) {
    match v {
        Value::Number(_) | Value::String(_) => out.push(path.clone()),
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                path.push(Step::Index(i));
                number_paths(x, path, out);
                path.pop();
            }
        }
        Value::Object(o) => {
            for (k, x) in o {
                path.push(Step::Key(k.clone()));
                number_paths(x, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

#[derive(Debug, Clone)]
enum Step {
    Key(String),
    Index(usize),
}

fn at_path<'v>(v: &'v mut Value, path: &[Step]) -> Option<&'v mut Value> {
    let mut v = v;
    for s in path {
        v = match s {
            Step::Key(k) => v.get_mut(k)?,
            Step::Index(i) => v.get_mut(*i)?,
        };
    }
    Some(v)
}

/// Values that break assumptions about a glTF field.
fn json_value() -> impl Strategy<Value = Value> {
    prop::sample::select(vec![
        Value::from(0),
        Value::from(1),
        Value::from(2),
        Value::from(3),
        Value::from(4),
        Value::from(-1),
        Value::from(255),
        Value::from(65535),
        Value::from(5120),
        Value::from(5125),
        Value::from(5126),
        Value::from(1u64 << 31),
        Value::from(u32::MAX),
        Value::from(1u64 << 40),
        Value::from(u64::MAX),
        Value::from(1.5),
        Value::from(1e300),
        Value::from("VEC3"),
        Value::from("SCALAR"),
        Value::from("MAT4"),
        Value::from("data:application/octet-stream;base64,AAAA"),
        Value::from("missing.bin"),
        Value::from("../../../../etc/passwd"),
        Value::Null,
        Value::Array(vec![]),
    ])
}

/// The BoxTextured glTF (external buffer and texture) with its files in memory.
fn box_gltf() -> (Value, MemoryFiles) {
    let json: Value = serde_json::from_slice(&corpus("gltf/BoxTextured/BoxTextured.gltf")).unwrap();
    let files = MemoryFiles::new();
    files.insert(
        "BoxTextured0.bin",
        corpus("gltf/BoxTextured/BoxTextured0.bin"),
    );
    files.insert(
        "CesiumLogoFlat.png",
        corpus("gltf/BoxTextured/CesiumLogoFlat.png"),
    );
    (json, files)
}

/// A GLB of `json` with `bin` as its binary chunk.
fn glb(json: &Value, bin: &[u8]) -> Vec<u8> {
    let mut j = serde_json::to_vec(json).unwrap();
    while !j.len().is_multiple_of(4) {
        j.push(b' ');
    }
    let mut b = bin.to_vec();
    while !b.len().is_multiple_of(4) {
        b.push(0);
    }
    let total = 12 + 8 + j.len() + 8 + b.len();
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(b.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&b);
    out
}

proptest! {
    #![proptest_config(cases(256))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600), which in 0usize..4) {
        let format = [MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Gltf, MeshFormat::Glb][which];
        parse(&bytes, format, "random", &MemoryFiles::new());
        // The same bytes behind a GLB header and as an MTL.
        let mut fake = b"glTF\x02\0\0\0".to_vec();
        fake.extend_from_slice(&bytes);
        parse(&fake, MeshFormat::Glb, "random.glb", &MemoryFiles::new());
        let files = MemoryFiles::new();
        files.insert("m.mtl", bytes.clone());
        parse(b"mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl a\nf 1 2 3\n", MeshFormat::Obj, "m.obj", &files);
    }

    #[test]
    fn mutated_obj_and_mtl_never_panic(
        which in 0usize..3,
        mutations in prop::collection::vec(mutation(), 1..4),
        tokens in prop::collection::vec((any::<usize>(), text_token()), 0..4),
    ) {
        let (obj, mtl, name) = [
            ("obj/cube_usemtl.obj", "obj/cube_usemtl.mtl", "cube_usemtl.mtl"),
            ("obj/concave_polygon.obj", "obj/concave_polygon.mtl", "concave_polygon.mtl"),
            ("obj/testmixed.obj", "obj/cube_usemtl.mtl", "none.mtl"),
        ][which];
        let mut text = corpus(obj);
        for (at, token) in &tokens {
            text = text_mutate(&text, *at, token);
        }
        let text = mutate(&text, &mutations);
        let files = MemoryFiles::new();
        files.insert(name, mutate(&corpus(mtl), &mutations));
        parse(&text, MeshFormat::Obj, "mutant.obj", &files);
    }

    #[test]
    fn mutated_spider_textures_never_panic(mutations in prop::collection::vec(mutation(), 1..4)) {
        // The spider's MTL, mutated, with its textures (also mutated) beside it.
        let files = MemoryFiles::new();
        files.insert("spider.mtl", mutate(&corpus("obj/spider/spider.mtl"), &mutations));
        for jpg in ["SpiderTex.jpg", "wal67ar_small.jpg"] {
            files.insert(jpg, mutate(&corpus(&format!("obj/spider/{jpg}")), &mutations));
        }
        parse(&corpus("obj/spider/spider.obj"), MeshFormat::Obj, "spider.obj", &files);
    }

    #[test]
    fn mutated_stl_never_panics(which in 0usize..3, mutations in prop::collection::vec(mutation(), 1..4)) {
        let file = ["stl/triangle_with_two_solids.stl", "stl/gearwheel.bin.stl", "stl/sphereWithHole.stl"][which];
        let bytes = mutate(&corpus(file), &mutations);
        parse(&bytes, MeshFormat::Stl, "mutant.stl", &MemoryFiles::new());
        // What loads is repaired without a panic: a model that fits together, or an error.
        if let Ok(loaded) = io::parse_model_with(&bytes, MeshFormat::Stl, "mutant.stl", &MemoryFiles::new()) {
            use shatter_geom::mesh::repair::{repair, RepairOptions};
            if let Ok((fixed, _)) = repair(&loaded.model, &RepairOptions::default()) {
                fixed.check().unwrap();
                assert!(!fixed.mesh.triangles.is_empty());
            }
        }
    }

    #[test]
    fn mutated_glb_bytes_never_panic(mutations in prop::collection::vec(mutation(), 1..4)) {
        parse(&mutate(&corpus("gltf/BoxTextured.glb"), &mutations), MeshFormat::Glb, "mutant.glb", &MemoryFiles::new());
    }

    #[test]
    fn mutated_gltf_fields_never_panic(
        picks in prop::collection::vec((any::<prop::sample::Index>(), json_value()), 1..4),
        as_glb in any::<bool>(),
    ) {
        let (mut json, files) = box_gltf();
        let mut paths = Vec::new();
        number_paths(&json, &mut Vec::new(), &mut paths);
        for (index, value) in &picks {
            let path = index.get(&paths).clone();
            if let Some(slot) = at_path(&mut json, &path) {
                *slot = value.clone();
            }
        }
        if as_glb {
            // The buffer as the GLB's binary chunk.
            if let Some(b) = json.pointer_mut("/buffers/0") {
                b.as_object_mut().map(|o| o.remove("uri"));
            }
            let bin = corpus("gltf/BoxTextured/BoxTextured0.bin");
            parse(&glb(&json, &bin), MeshFormat::Glb, "mutant.glb", &files);
        } else {
            parse(&serde_json::to_vec(&json).unwrap(), MeshFormat::Gltf, "mutant.gltf", &files);
        }
    }
}

/// The three glTF panics issue 14 found, and counts no file could back: each is an
/// error naming the problem (a count believed would abort the process instead).
#[test]
fn malformed_gltf_accessors_are_errors_not_panics() {
    let (base, files) = box_gltf();
    let with = |pointer: &str, value: Value| {
        let mut json = base.clone();
        *json.pointer_mut(pointer).unwrap() = value;
        let bytes = serde_json::to_vec(&json).unwrap();
        io::parse_model_with(&bytes, MeshFormat::Gltf, "bad.gltf", &files)
            .unwrap_err()
            .to_string()
    };
    let position = base["meshes"][0]["primitives"][0]["attributes"]["POSITION"]
        .as_u64()
        .unwrap() as usize;
    let indices = base["meshes"][0]["primitives"][0]["indices"]
        .as_u64()
        .unwrap() as usize;
    let view = base["accessors"][position]["bufferView"].as_u64().unwrap() as usize;

    let err = with(
        "/meshes/0/primitives/0/attributes/POSITION",
        Value::from(99),
    );
    assert!(
        err.contains("POSITION names accessor 99, but the file has 4 accessors"),
        "{err}"
    );

    // `indices` naming a float VEC3 accessor (the positions).
    let err = with("/meshes/0/primitives/0/indices", Value::from(position));
    assert!(err.contains("indices (accessor"), "{err}");
    assert!(
        err.contains(
            "is a VEC3 of FLOAT; expected SCALAR of UNSIGNED_BYTE, UNSIGNED_SHORT, UNSIGNED_INT"
        ),
        "{err}"
    );

    let err = with(&format!("/bufferViews/{view}/byteStride"), Value::from(4));
    assert!(
        err.contains("has byteStride 4, smaller than the 12-byte element"),
        "{err}"
    );

    let err = with(
        &format!("/accessors/{indices}/count"),
        Value::from(1u64 << 40),
    );
    assert!(err.contains("1099511627776 elements"), "{err}");
    let err = with(
        &format!("/accessors/{position}/count"),
        Value::from(u64::MAX),
    );
    assert!(err.contains("elements of 12 bytes"), "{err}");
    let err = with("/buffers/0/uri", Value::from("nowhere.bin"));
    assert!(err.contains("cannot read nowhere.bin"), "{err}");
}

#[test]
fn a_binary_stl_announcing_four_billion_triangles_reads_the_one_it_holds() {
    let mut bytes = corpus("stl/gearwheel.bin.stl")[..84 + 50].to_vec();
    bytes[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    let loaded = io::parse_model(&bytes, MeshFormat::Stl, "huge.stl").unwrap();
    assert_eq!(loaded.model.mesh.triangles.len(), 1);
    assert!(
        loaded.warnings[0]
            .message
            .contains("announces 4294967295 triangles")
    );
}

#[test]
fn a_node_cycle_and_a_deep_chain_are_handled() {
    let (mut json, files) = box_gltf();
    // Node 0 becomes its own grandchild.
    let nodes = json["nodes"].as_array().unwrap().len();
    json["nodes"][nodes - 1]["children"] = Value::from(vec![0]);
    let bytes = serde_json::to_vec(&json).unwrap();
    let err = io::parse_model_with(&bytes, MeshFormat::Gltf, "cycle.gltf", &files).unwrap_err();
    assert!(err.to_string().contains("is its own ancestor"), "{err}");
    // A chain of 100,000 nodes (recursion would overflow the stack).
    let (mut json, files) = box_gltf();
    let n = 100_000;
    let mut chain: Vec<Value> = (0..n)
        .map(|i| serde_json::json!({ "children": [i + 1] }))
        .collect();
    chain.push(serde_json::json!({ "mesh": 0 }));
    json["nodes"] = Value::Array(chain);
    json["scenes"] = serde_json::json!([{ "nodes": [0] }]);
    json["scene"] = Value::from(0);
    let bytes = serde_json::to_vec(&json).unwrap();
    let loaded = io::parse_model_with(&bytes, MeshFormat::Gltf, "chain.gltf", &files).unwrap();
    assert_eq!(loaded.model.mesh.triangles.len(), 12);
    // A doubling tree: 2^30 instances of nothing, refused.
    let mut tree: Vec<Value> = (0..30)
        .map(|i| serde_json::json!({ "children": [i + 1, i + 1] }))
        .collect();
    tree.push(serde_json::json!({ "mesh": 0 }));
    json["nodes"] = Value::Array(tree);
    let bytes = serde_json::to_vec(&json).unwrap();
    let err = io::parse_model_with(&bytes, MeshFormat::Gltf, "tree.gltf", &files).unwrap_err();
    assert!(err.to_string().contains("more than"), "{err}");
}
