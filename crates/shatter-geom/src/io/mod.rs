//! Mesh and model file import and export.
//!
//! Import: [`load_model`] reads a [`Model`](crate::model::Model) — mesh, UVs, normals,
//! colours, materials and textures — from OBJ (+ MTL), STL (ASCII and binary) and glTF /
//! GLB 2.0, dispatching on the extension, with a list of [`LoadWarning`]s for what it
//! tolerated; [`parse_model`] and [`parse_model_with`] read from memory, with the files
//! the model refers to (MTL, textures, `.bin`) from a [`FileSource`] such as
//! [`MemoryFiles`]. [`load_mesh`], [`load_mesh_from`], [`load_mesh_from_bytes`] and
//! [`parse_mesh`] return the mesh alone. Nothing is global: a program holding files in
//! memory (the web page's picked files) passes them as a [`FileSource`].
//! `docs/formats.md` lists what each reader takes.
//!
//! Export: [`write_obj`] / [`save_obj`] (with an MTL file; `*_with_materials` with the
//! model's materials, textures copied next to the output), [`write_glb`] /
//! [`save_glb`] (`*_with_materials`: images embedded) and [`write_stl`] / [`save_stl`].
//! OBJ and GLB exports take [`ExportObject`]s, whose triangles are flagged surface or
//! interior and may carry materials and corner attributes. [`GlbBuilder`] is the GLB
//! writer's core, for writers that add nodes or animations of their own.
//!
//! Pre-fractured assets: [`write_fracture_glb`] / [`save_fracture_glb`] write a
//! [`Fracture`](crate::fracture::Fracture) as a GLB with the `SHATTER_fracture`
//! extension (convex pieces, mass properties, bonds, anchors, material; see
//! `docs/shatter-fracture-extension.md`), and [`read_fracture`] / [`parse_fracture`]
//! read it back.
//!
//! ```
//! use shatter_geom::{io::{self, ExportObject}, shapes};
//! let dir = std::env::temp_dir().join("shatter-doc-io");
//! std::fs::create_dir_all(&dir).unwrap();
//! let bird = shapes::bird();
//! io::save_glb(dir.join("bird.glb"), &[ExportObject::new("bird", &bird)]).unwrap();
//! let back = io::load_mesh(dir.join("bird.glb")).unwrap();
//! assert_eq!(back.triangles.len(), 1394);
//! assert!(back.check().is_solid());
//! ```

mod context;
mod error;
mod export;
mod files;
mod gltf;
mod image;
mod inspect;
mod load;
mod obj;
mod polygon;
mod stl;
mod warning;

pub use error::MeshIoError;
pub use export::{
    ExportObject, INTERIOR_COLOR, INTERIOR_MATERIAL, INTERIOR_SHADE, SURFACE_COLOR,
    SURFACE_MATERIAL, fragment_names, interior_color_of,
};
pub use files::{FileSource, FileSystem, Layered, MemoryFiles, NoFiles};
pub use gltf::{
    BreakThresholds, FRACTURE_EXTENSION, FRACTURE_EXTENSION_VERSION, FractureAssetMeta, GlbBuilder,
    parse_fracture, read_fracture, save_fracture_glb, save_glb, save_glb_with_materials,
    write_fracture_glb, write_glb, write_glb_with_materials,
};
pub use inspect::{Inspection, MaterialReport, ShellReport, inspect};
pub use load::{
    LoadedModel, MAX_TRIANGLES, MeshFormat, load_mesh, load_mesh_from, load_mesh_from_bytes,
    load_model, load_model_from, parse_mesh, parse_model, parse_model_with,
};
pub use obj::{
    TextureFile, save_obj, save_obj_with_materials, texture_files, write_mtl,
    write_mtl_with_materials, write_obj, write_obj_with_materials,
};
pub use stl::{StlFormat, save_stl, write_stl};
pub use warning::{LoadWarning, WarningKind};

/// Ear clipping on a polygon's best-fit plane, also used by `mesh::repair` for large holes.
pub(crate) use polygon::Triangulator;
