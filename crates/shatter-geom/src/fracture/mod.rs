//! Fracture of closed meshes into bonded fragments.
//!
//! Three methods ([`Method`]): the thesis's Delaunay tetrahedra (`Tetra`), Voronoi cells
//! clipped exactly to the mesh (`Voronoi`, convex or concave meshes) and plane slicing
//! (`Slice`). Every method returns a [`Fracture`]: closed, outward fragments whose
//! triangles are flagged surface or interior, convex pieces for collision, mass
//! properties, and the bond graph of fragments sharing a face.
//!
//! Files, one per step: `validate` (input checks), `piece` (working solid), `clip` and
//! `cap` (plane clipping with capping), `seeds`, `voronoi`, `slice`, `tetra`, `bonds`
//! (cap overlap), `convex` (collision pieces), `massprops`, `entry` (the public function).

mod bonds;
mod cap;
mod clip;
mod convex;
mod entry;
mod inside;
mod massprops;
mod merge;
mod params;
mod piece;
mod seeds;
mod slice;
mod tetra;
mod types;
mod validate;
mod voronoi;

#[cfg(test)]
mod face_tests;
#[cfg(test)]
mod fast_path_tests;

pub use entry::fracture;
pub use params::{FractureError, FractureParams, Method, Pattern, Placement};
pub use tetra::{SLIVER_QUALITY, SLIVER_VOLUME_FRACTION};
pub use types::{Bond, Fracture, Fragment};
