//! Wavefront OBJ with MTL material libraries: the reader (hand-written, tolerant) and the
//! writer.

mod lines;
mod mtl;
mod read;
mod write;

pub(crate) use read::read_obj;
pub use write::{
    TextureFile, save_obj, save_obj_with_materials, texture_files, write_mtl,
    write_mtl_with_materials, write_obj, write_obj_with_materials,
};
