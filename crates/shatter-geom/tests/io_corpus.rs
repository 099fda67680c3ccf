//! The corpus of real public models (`tests/corpus/`, see its `SOURCES.md`): every file
//! loads with the triangles, materials and attribute sets it has, or is refused with a
//! message that says why.
//!
//! The expected counts were read off the files independently, with Blender 3.4's own
//! importers (`blender -b --factory-startup --python count.py -- FILES`, where count.py
//! imports each file and sums `len(polygon.vertices) - 2` over its polygons, counts the
//! distinct materials its polygons use, its UV layers and colour attributes). Where this
//! reader's rule differs from Blender's, the test says so.
#![allow(clippy::unwrap_used)]

use shatter_geom::io::{self, WarningKind};

mod support;

use support::corpus::{REFUSED, corpus};

/// What a corpus file must load as.
struct Expect {
    file: &'static str,
    /// Triangles (Blender's count).
    triangles: usize,
    /// Materials the triangles use (Blender's count; a file that names none gets one
    /// default material here, where Blender has none).
    materials: usize,
    uv: bool,
    color: bool,
    /// Distinct texture images among the used materials.
    images: usize,
}

const LOADS: &[Expect] = &[
    Expect {
        file: "obj/spider/spider.obj",
        triangles: 1368,
        materials: 4,
        uv: true,
        color: false,
        images: 4,
    },
    Expect {
        file: "obj/WusonOBJ.obj",
        triangles: 3732,
        materials: 1,
        uv: true,
        color: false,
        images: 0,
    },
    Expect {
        file: "obj/regr01.obj",
        triangles: 2710,
        materials: 12,
        uv: true,
        color: false,
        images: 0,
    },
    Expect {
        file: "obj/box.obj",
        triangles: 12,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    // A closed box of six quads, with `l` and `p` elements beside them.
    Expect {
        file: "obj/testmixed.obj",
        triangles: 12,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "obj/concave_polygon.obj",
        triangles: 64,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "obj/cube_with_vertexcolors.obj",
        triangles: 12,
        materials: 1,
        uv: false,
        color: true,
        images: 0,
    },
    Expect {
        file: "obj/cube_usemtl.obj",
        triangles: 12,
        materials: 3,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "obj/box_UTF16BE.obj",
        triangles: 12,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "stl/3DSMaxExport.STL",
        triangles: 2000,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "stl/sphereWithHole.stl",
        triangles: 285,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    // Blender imports 1312 (it drops degenerate and duplicate faces); the header and the
    // size (84 + 50 × 1368 = 68484 bytes) say 1368, which is what is read.
    Expect {
        file: "stl/Spider_binary.stl",
        triangles: 1368,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "stl/triangle_with_two_solids.stl",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "stl/gearwheel.bin.stl",
        triangles: 2444,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    // A laser scan with five holes in its base (the Stanford bunny); the count is the
    // binary header's, which the file size confirms: (3,472,634 − 84) / 50.
    Expect {
        file: "stl/bunny.bin.stl",
        triangles: 69451,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    // A binary STL whose header announces 66 triangles; its 284 bytes hold 4 (a
    // tetrahedron), which are read, with a warning.
    Expect {
        file: "stl/incorrectFaceCounter.bin.stl",
        triangles: 4,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "gltf/BoxTextured/BoxTextured.gltf",
        triangles: 12,
        materials: 1,
        uv: true,
        color: false,
        images: 1,
    },
    Expect {
        file: "gltf/BoxTextured.glb",
        triangles: 12,
        materials: 1,
        uv: true,
        color: false,
        images: 1,
    },
    Expect {
        file: "gltf/BoxTextured_embedded.gltf",
        triangles: 12,
        materials: 1,
        uv: true,
        color: false,
        images: 1,
    },
    // Blender imports 110342 (it drops degenerate and duplicate faces); the document's
    // 67 mesh instances in the default scene hold 121496 (summed over each instanced
    // primitive's index count / 3 by a 20-line Python walk of the GLB's JSON).
    Expect {
        file: "gltf/engine/2CylinderEngine.glb",
        triangles: 121496,
        materials: 34,
        uv: false,
        color: false,
        images: 0,
    },
    // Blender: 2 triangles each (strip, fan, list, strip and fan with indices, bytes).
    Expect {
        file: "gltf/primitive_modes/Mesh_PrimitiveMode_04.gltf",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "gltf/primitive_modes/Mesh_PrimitiveMode_05.gltf",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "gltf/primitive_modes/Mesh_PrimitiveMode_06.gltf",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "gltf/primitive_modes/Mesh_PrimitiveMode_11.gltf",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "gltf/primitive_modes/Mesh_PrimitiveMode_12.gltf",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
    Expect {
        file: "gltf/primitive_modes/Mesh_PrimitiveMode_14.gltf",
        triangles: 2,
        materials: 1,
        uv: false,
        color: false,
        images: 0,
    },
];

#[test]
fn every_corpus_file_loads_with_its_triangles_materials_and_attributes() {
    for e in LOADS {
        let loaded = io::load_model(corpus(e.file)).unwrap_or_else(|err| panic!("{err}"));
        let m = &loaded.model;
        m.check().unwrap();
        let what = e.file;
        assert_eq!(m.mesh.triangles.len(), e.triangles, "{what}: triangles");
        assert_eq!(m.materials.len(), e.materials, "{what}: materials");
        assert_eq!(m.corners.uv.is_some(), e.uv, "{what}: uv");
        assert_eq!(m.corners.color.is_some(), e.color, "{what}: color");
        let mut images: Vec<*const shatter_geom::model::Image> = m
            .materials
            .iter()
            .filter_map(|m| m.base_color_texture.as_ref())
            .map(|t| std::sync::Arc::as_ptr(&t.image))
            .collect();
        images.sort();
        images.dedup();
        assert_eq!(images.len(), e.images, "{what}: images");
        // Every material a triangle names exists, and every material is used.
        for k in 0..m.materials.len() as u32 {
            assert!(m.material.contains(&k), "{what}: material {k} unused");
        }
    }
}

#[test]
fn refused_corpus_files_say_why() {
    for (file, message) in REFUSED {
        let err = io::load_model(corpus(file)).unwrap_err().to_string();
        assert!(err.contains(message), "{file}: {err}");
        assert!(
            err.contains(
                std::path::Path::new(file)
                    .file_name()
                    .unwrap()
                    .to_str()
                    .unwrap()
            ),
            "{err}"
        );
    }
}

#[test]
fn the_spider_gets_its_textures_through_windows_paths() {
    let loaded = io::load_model(corpus("obj/spider/spider.obj")).unwrap();
    let names: Vec<&str> = loaded
        .model
        .materials
        .iter()
        .map(|m| m.name.as_str())
        .collect();
    // In order of first use in the file.
    assert_eq!(names, ["HLeibTex", "Skin", "BeinTex", "Augentex"]);
    let skin = &loaded.model.materials[1];
    let image = &skin.base_color_texture.as_ref().unwrap().image;
    assert_eq!(image.name, "wal67ar_small.jpg");
    assert_eq!(image.format, shatter_geom::model::ImageFormat::Jpeg);
    assert_eq!(image.bytes.len(), 9287);
    // A texture replaces Kd (0.827451 0.792157 0.772549 in the MTL).
    assert_eq!(skin.base_color, [1.0; 4]);
    // Its normal 488 is `vn 0 0 0`, used by 108 face corners (counted with awk); nothing
    // else is missing.
    let kinds: Vec<(WarningKind, usize)> =
        loaded.warnings.iter().map(|w| (w.kind, w.count)).collect();
    assert_eq!(kinds, [(WarningKind::MissingAttribute, 108)]);
}

#[test]
fn tolerated_files_warn_with_counts() {
    let mixed = io::load_model(corpus("obj/testmixed.obj")).unwrap();
    let kinds: Vec<(WarningKind, usize)> =
        mixed.warnings.iter().map(|w| (w.kind, w.count)).collect();
    // 6 `l` and 6 `p` statements; `usemtl Default` with no material library.
    assert_eq!(
        kinds,
        [
            (WarningKind::SkippedElements, 6),
            (WarningKind::SkippedElements, 6),
            (WarningKind::UnknownMaterial, 1)
        ]
    );
    assert!(
        mixed.warnings[1]
            .message
            .ends_with("skipped 6 point elements (first at line 23)")
    );
    let modes = io::load_model(corpus("gltf/primitive_modes/Mesh_PrimitiveMode_04.gltf")).unwrap();
    assert!(modes.warnings.is_empty(), "{:?}", modes.warnings);
}

#[test]
fn the_engine_instances_its_parts_with_their_transforms() {
    // Blender's importer applies the same node transforms: its bounding box of the
    // imported objects (world space) is the reference.
    let loaded = io::load_model(corpus("gltf/engine/2CylinderEngine.glb")).unwrap();
    let (lo, hi) = loaded.model.mesh.bounds().unwrap();
    let size = hi - lo;
    assert!(size.min_element() > 0.0);
    // The parts are not all at the origin: the engine is several hundred units long.
    assert!(size.max_element() > 100.0, "{size:?}");
}
