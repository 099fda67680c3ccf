//! Fracture of closed meshes into bonded fragments.
//!
//! Three methods ([`Method`]): the thesis's Delaunay tetrahedra (`Tetra`), Voronoi cells
//! clipped exactly to the mesh (`Voronoi`, convex or concave meshes) and plane slicing
//! (`Slice`). Every method returns a [`Fracture`]: closed, outward fragments whose
//! triangles are flagged surface or interior, convex pieces for collision, mass
//! properties, and the bond graph of fragments sharing a face.
//!
//! Folders, one per concern: `kernel` (the working solid `Piece`, planes, exact clipping
//! with caps kept as polygons, cap triangulation, the convex decomposition for
//! collision), `methods` (`tetra`, `voronoi`, `slice`), `seeds` (patterns, inside tests
//! and sampling), `bonds` (bonds through matching caps, merging small pieces); beside them
//! `params` and `types` (the public types), `validate` (input checks) and `entry` (the
//! public function).

mod bonds;
mod check;
mod entry;
mod kernel;
mod methods;
pub(crate) mod normalize;
mod params;
mod seeds;
mod types;
mod validate;

pub use check::{InvalidFracture, VOLUME_TOLERANCE};
pub use entry::fracture;
pub use methods::tetra::{SLIVER_QUALITY, SLIVER_VOLUME_FRACTION};
pub use normalize::ANISOTROPY;
pub use params::{FractureError, FractureParams, Method, Pattern, Placement};
pub use types::{Bond, Fracture, Fragment};
