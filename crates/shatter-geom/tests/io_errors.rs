//! Bad mesh files give errors naming the file and the problem, never panics.
#![allow(clippy::unwrap_used)]

use std::path::PathBuf;

use shatter_geom::io::{self, ExportObject, MeshFormat, MeshIoError, StlFormat};
use shatter_geom::shapes;

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("shatter-ioerr-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn missing_file_names_the_file() {
    let path = temp_dir("missing").join("nothing-here.stl");
    let err = io::load_mesh(&path).unwrap_err();
    assert!(matches!(err, MeshIoError::Io { .. }), "{err:?}");
    assert!(err.to_string().contains("nothing-here.stl"), "{err}");
}

#[test]
fn unknown_extension_is_an_error() {
    let dir = temp_dir("ext");
    let path = dir.join("model.fbx");
    std::fs::write(&path, b"whatever").unwrap();
    let err = io::load_mesh(&path).unwrap_err();
    assert!(matches!(err, MeshIoError::UnknownFormat { .. }));
    assert!(err.to_string().contains("model.fbx"));
    assert!(matches!(
        io::load_mesh(dir.join("no_extension")).unwrap_err(),
        MeshIoError::UnknownFormat { .. }
    ));
}

#[test]
fn obj_index_out_of_range_names_the_line() {
    let text = "# a triangle\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 9\n";
    let err = io::parse_mesh(text.as_bytes(), MeshFormat::Obj, "bad.obj").unwrap_err();
    match &err {
        MeshIoError::Obj { line, .. } => assert_eq!(*line, Some(6)),
        other => panic!("{other:?}"),
    }
    assert_eq!(
        err.to_string(),
        "bad.obj: line 6: face references vertex 9 but the file has 3"
    );
}

#[test]
fn obj_parse_errors_name_the_line() {
    let cases: [(&str, usize); 3] = [
        ("v 0 0 0\nv 1 0 0\nv 0 1 x\nf 1 2 3\n", 3),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 three\n", 4),
        ("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", 4),
    ];
    for (text, expected) in cases {
        match io::parse_mesh(text.as_bytes(), MeshFormat::Obj, "x.obj") {
            Err(MeshIoError::Obj { line, .. }) => assert_eq!(line, Some(expected), "{text:?}"),
            other => panic!("{text:?}: {other:?}"),
        }
    }
}

#[test]
fn files_without_triangles_are_errors() {
    for (bytes, format) in [
        (&b""[..], MeshFormat::Obj),
        (&b"v 1 2 3\n"[..], MeshFormat::Obj),
        (&b"solid empty\nendsolid empty\n"[..], MeshFormat::Stl),
    ] {
        let err = io::parse_mesh(bytes, format, "empty").unwrap_err();
        assert!(matches!(err, MeshIoError::NoTriangles { .. }), "{err:?}");
    }
}

#[test]
fn truncated_binary_stl_loads_what_it_holds_with_a_warning() {
    let mut bytes = Vec::new();
    io::write_stl(&mut bytes, &shapes::cube(), StlFormat::Binary).unwrap();
    let cut = &bytes[..84 + 50 * 5 + 10];
    let loaded = io::parse_model(cut, MeshFormat::Stl, "cut.stl").unwrap();
    assert_eq!(loaded.model.mesh.triangles.len(), 5);
    assert_eq!(loaded.warnings.len(), 1);
    assert_eq!(loaded.warnings[0].kind, io::WarningKind::Truncated);
    assert_eq!(
        loaded.warnings[0].to_string(),
        "cut.stl: binary STL header announces 12 triangles (684 bytes) but the file has 344 \
         bytes: read the 5 triangles it holds"
    );
    let err = io::parse_mesh(&bytes[..40], MeshFormat::Stl, "tiny.stl").unwrap_err();
    assert!(err.to_string().contains("needs 84"), "{err}");
}

#[test]
fn garbage_glb_and_gltf_are_errors() {
    let garbage: Vec<u8> = (0..500u32).map(|i| (i * 7919 % 251) as u8).collect();
    let err = io::parse_mesh(&garbage, MeshFormat::Glb, "garbage.glb").unwrap_err();
    assert!(matches!(err, MeshIoError::Gltf { .. }), "{err:?}");
    assert!(err.to_string().starts_with("garbage.glb: "));
    let mut fake = b"glTF".to_vec();
    fake.extend_from_slice(&garbage);
    assert!(io::parse_mesh(&fake, MeshFormat::Glb, "fake.glb").is_err());
    let json = br#"{"asset": {"version": "2.0"}, "meshes": [{"primitives": []}"#;
    assert!(io::parse_mesh(json, MeshFormat::Gltf, "cut.gltf").is_err());
    // A glTF whose external buffer is missing, read from memory (no base directory).
    let external = br#"{"asset": {"version": "2.0"},
        "buffers": [{"uri": "missing.bin", "byteLength": 4}]}"#;
    let err = io::parse_mesh(external, MeshFormat::Gltf, "ext.gltf").unwrap_err();
    assert!(err.to_string().contains("ext.gltf"), "{err}");
}

#[test]
fn export_rejects_mismatched_interior_flags() {
    let cube = shapes::cube();
    let flags = [true; 5];
    let objects = [ExportObject::new("frag", &cube).with_interior(&flags)];
    let err = io::write_glb(Vec::new(), &objects).unwrap_err();
    assert_eq!(
        err.to_string(),
        "object frag: 5 interior flags for 12 triangles"
    );
    assert!(io::write_obj(Vec::new(), &objects, None).is_err());
}

/// Every prefix of valid files (and flipped bytes) loads or fails cleanly.
#[test]
fn truncated_and_corrupted_files_never_panic() {
    let bird = shapes::bird();
    let objects = [ExportObject::new("bird", &bird)];
    let mut glb = Vec::new();
    io::write_glb(&mut glb, &objects).unwrap();
    let mut obj = Vec::new();
    io::write_obj(&mut obj, &objects, None).unwrap();
    // ASCII STL parsing is slow in debug builds: a smaller mesh.
    let cylinder = shapes::cylinder();
    let mut stl_a = Vec::new();
    io::write_stl(&mut stl_a, &cylinder, StlFormat::Ascii).unwrap();
    let mut stl_b = Vec::new();
    io::write_stl(&mut stl_b, &bird, StlFormat::Binary).unwrap();
    for (bytes, format) in [
        (&glb, MeshFormat::Glb),
        (&obj, MeshFormat::Obj),
        (&stl_a, MeshFormat::Stl),
        (&stl_b, MeshFormat::Stl),
    ] {
        let full = io::parse_mesh(bytes, format, "full").unwrap();
        assert!([1394, 80].contains(&full.triangles.len()));
        for k in 1..64 {
            let cut = bytes.len() * k / 64;
            let _ = io::parse_mesh(&bytes[..cut], format, "cut");
            let mut flipped = bytes.clone();
            flipped[cut] ^= 0x5a;
            let _ = io::parse_mesh(&flipped, format, "flipped");
        }
    }
}
