//! Geometry for shatter: triangle meshes, an exact 3D Delaunay tetrahedralization and
//! fracture of closed meshes into bonded fragments.
//!
//! This crate knows no physics and no rendering. All coordinates are `f64`
//! ([`glam::DVec3`]); every topological decision goes through exact predicates.

#![cfg_attr(test, allow(clippy::unwrap_used))]

pub mod budget;
pub mod delaunay;
pub mod fracture;
pub mod io;
pub mod mesh;
pub mod model;
pub mod progress;
pub mod sampling;
pub mod shapes;
pub mod util;
pub mod vocab;

pub use glam::{DMat3, DVec3};
pub use mesh::TriMesh;
