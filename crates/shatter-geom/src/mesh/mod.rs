//! Indexed triangle meshes.

mod trimesh;

pub use trimesh::TriMesh;
