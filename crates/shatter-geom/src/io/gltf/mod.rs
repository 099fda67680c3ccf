//! glTF 2.0 and GLB: the reader (accessors read and checked by hand) and the GLB writer.

mod accessor;
mod container;
mod extension;
mod json;
mod read;
mod write;

pub use extension::{
    BreakThresholds, FRACTURE_EXTENSION, FRACTURE_EXTENSION_VERSION, FractureAssetMeta,
    parse_fracture, read_fracture, save_fracture_glb, write_fracture_glb,
};
pub(crate) use read::read_gltf;
pub use write::{
    GlbBuilder, save_glb, save_glb_with_materials, write_glb, write_glb_with_materials,
};
