//! Indexed triangle meshes: mass properties, welding, topology checks, validation as a
//! solid, and inside/outside queries by generalized winding number.

mod check;
pub(crate) mod intersect;
mod mass;
pub mod repair;
mod shells;
mod trimesh;
mod validate;
mod weld;
pub(crate) use check::is_degenerate;
pub(crate) use intersect::triangles_meet;
pub(crate) use mass::mass_properties;
pub(crate) use weld::position_key;
pub(crate) use winding::winding_number;
mod winding;

pub use check::MeshReport;
pub use trimesh::TriMesh;
pub use validate::{CROSSING_TOLERANCE, MeshError};
