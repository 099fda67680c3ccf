//! The model corpus (`tests/corpus/`, see its `SOURCES.md`): where it is, which files
//! are refused on loading and why, and which hold nothing with a volume.

use std::path::{Path, PathBuf};

/// The path of a corpus file.
pub fn corpus(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/corpus")
        .join(rel)
}

/// Every mesh file of the corpus (OBJ, STL, glTF, GLB; any case), as paths relative to
/// it, sorted.
pub fn mesh_files() -> Vec<String> {
    fn walk(dir: &Path, root: &Path, out: &mut Vec<String>) {
        for entry in std::fs::read_dir(dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display())) {
            let path = entry.expect("a directory entry").path();
            if path.is_dir() {
                walk(&path, root, out);
                continue;
            }
            let ext = path
                .extension()
                .and_then(|e| e.to_str())
                .map(str::to_ascii_lowercase);
            if matches!(ext.as_deref(), Some("obj" | "stl" | "gltf" | "glb")) {
                let rel = path.strip_prefix(root).expect("under the corpus");
                out.push(rel.to_string_lossy().replace('\\', "/"));
            }
        }
    }
    let root = corpus("");
    let mut out = Vec::new();
    walk(&root, &root, &mut out);
    out.sort();
    out
}

/// Files refused, and what the message must say.
pub const REFUSED: &[(&str, &str)] = &[
    (
        "gltf1/BoxTextured_v1.gltf",
        "glTF 1.0 is not supported (this file says version 1.0); convert it to glTF 2.0",
    ),
    (
        "gltf/2CylinderEngine.gltf",
        "requires KHR_draco_mesh_compression",
    ),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_01.gltf",
        "no triangles in the file",
    ),
    (
        "obj/number_formats.obj",
        "line 11: '3.1+e2' is not a number",
    ),
];

/// Files that hold nothing with a volume: repair refuses them, saying what it found.
pub const NO_SOLID: &[(&str, &str)] = &[
    ("obj/concave_polygon.obj", "open sheet"),
    ("stl/triangle_with_two_solids.stl", "open sheet"),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_04.gltf",
        "open sheet",
    ),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_05.gltf",
        "open sheet",
    ),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_06.gltf",
        "open sheet",
    ),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_11.gltf",
        "open sheet",
    ),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_12.gltf",
        "open sheet",
    ),
    (
        "gltf/primitive_modes/Mesh_PrimitiveMode_14.gltf",
        "open sheet",
    ),
];
