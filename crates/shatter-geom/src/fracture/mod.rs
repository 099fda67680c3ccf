//! Fracture of closed meshes into bonded fragments.
//!
//! Four methods ([`Method`]): the thesis's Delaunay tetrahedra (`Tetra`), Voronoi cells
//! clipped exactly to the mesh (`Voronoi`, convex or concave meshes), plane slicing
//! (`Slice`) and a grid of cells along the axes (`Grid`, bricks of a box). Every method returns a [`Fracture`]: closed, outward fragments whose
//! triangles are flagged surface or interior (with the input's UVs, normals, colours and
//! materials through [`fracture_model`]), convex pieces for collision, mass
//! properties, and the bond graph of fragments sharing a face.
//!
//! Folders, one per concern: `kernel` (the working solid `Piece`, planes, exact clipping
//! with caps kept as polygons, cap triangulation, the convex decomposition for
//! collision), `methods` (`tetra`, `voronoi`, `slice`, `grid`), `seeds` (patterns, inside tests
//! and sampling), `bonds` (bonds through matching caps, merging small pieces); beside them
//! `params` and `types` (the public types), `validate` (input checks), `attributes`
//! (UVs, normals, colours and materials of the fragments, from their positions and the
//! kernel's tags), `entry` (the public functions) and `rough` (the [`roughen`] post-pass
//! that displaces the cut faces by fractal noise, [`Roughness`]).

mod attributes;
mod bonds;
mod check;
mod entry;
mod error;
mod kernel;
mod methods;
pub(crate) mod normalize;
mod params;
mod rough;
mod seeds;
mod types;
mod validate;

pub use attributes::interior_material;
pub use check::VOLUME_TOLERANCE;
pub use entry::{fracture, fracture_fragment, fracture_model, fracture_model_surfaces, intact};
pub use error::{FractureError, InvalidFracture};
pub(crate) use methods::grid::fills_box;
pub use methods::tetra::{SLIVER_QUALITY, SLIVER_VOLUME_FRACTION};
pub use normalize::{ANISOTROPY, FAR_LIMIT};
pub use params::{FractureParams, Method, MethodKind, Pattern, Placement, Seeds};
pub use rough::{RoughReport, Roughness, roughen};
pub use types::{Bond, Fracture, Fragment};
