//! Mesh file import and export.
//!
//! Import: [`load_mesh`] reads OBJ (`tobj`), STL ASCII and binary (`stl_io`) and glTF /
//! GLB (`gltf`), dispatching on the extension; [`parse_mesh`] reads from memory, and
//! [`add_memory_file`] registers named in-memory files that [`load_mesh`] reads first.
//! Export: [`write_obj`] / [`save_obj`] (with an MTL file), [`write_glb`] /
//! [`save_glb`] and [`write_stl`] / [`save_stl`]. OBJ and GLB exports take
//! [`ExportObject`]s, whose triangles are flagged surface or interior and get the
//! `surface` and `interior` materials.
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

mod error;
mod export;
mod glb_write;
mod gltf_read;
mod load;
mod memory_files;
mod obj_read;
mod obj_write;
mod stl;

pub use error::MeshIoError;
pub use export::{
    ExportObject, INTERIOR_COLOR, INTERIOR_MATERIAL, SURFACE_COLOR, SURFACE_MATERIAL,
};
pub use glb_write::{save_glb, write_glb};
pub use load::{MeshFormat, load_mesh, parse_mesh};
pub use memory_files::{add_memory_file, memory_file, memory_file_names, remove_memory_file};
pub use obj_write::{save_obj, write_mtl, write_obj};
pub use stl::{StlFormat, save_stl, write_stl};
