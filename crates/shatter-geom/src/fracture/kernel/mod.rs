//! The cutting kernel: the working solid ([`Piece`]), oriented planes, exact clipping
//! with capping (caps kept as polygons, [`Face`], until a cell is done), cap
//! triangulation, and the convex decomposition for collision pieces.

pub(crate) mod cap;
pub(crate) mod clip;
pub(crate) mod convex;
mod edges;
mod face;
mod hull;
pub(crate) mod inherit;
mod piece;
mod plane;
pub(crate) mod polytope;
mod solids;
pub(crate) mod union;

#[cfg(test)]
mod face_tests;
#[cfg(test)]
pub(crate) mod fast_path_tests;

pub(crate) use face::Face;
pub(crate) use piece::{Piece, SURFACE, is_surface, mesh_scale, source_triangle};
pub(crate) use plane::Plane;
pub(crate) use solids::with_cavities;
