//! Fracture parameters and errors.

use glam::DVec3;

use crate::delaunay::DelaunayError;
use crate::mesh::MeshError;
use crate::model::ModelError;

/// How the random points of the [`Method::Tetra`] method are placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Placement {
    /// Uniform inside the mesh (rejection sampling with the winding number).
    #[default]
    Interior,
    /// The thesis's scheme: pick a random point `p` of the growing list, draw
    /// `d = uniform(0, |p − c|)` and add `c + unit(c − p)·d` (`c` = centre of mass).
    /// A point outside the mesh (possible for concave meshes, e.g. a torus, whose
    /// centre is in the hole) is redrawn.
    Thesis,
}

/// Seed distribution of the [`Method::Voronoi`] method.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Pattern {
    /// Uniform inside the mesh.
    #[default]
    Uniform,
    /// Gaussian clusters around a few random centres inside the mesh.
    Clustered,
    /// Dense near the impact point and coarser outward (glass).
    Radial,
    /// Cells stretched along the mesh's longest axis (wood).
    Splinter,
}

/// A fracture method.
#[derive(Debug, Clone, PartialEq)]
pub enum Method {
    /// The thesis's method: a Delaunay tetrahedralization of surface vertices and random
    /// points, each tetrahedron a fragment (slivers merged into a neighbour).
    Tetra {
        /// Number of random points to add.
        random_vertices: usize,
        /// Take every `(skip + 1)`-th surface vertex.
        skip: usize,
        /// Also add the centre of mass.
        center: bool,
        /// Where the random points go.
        placement: Placement,
    },
    /// Voronoi cells of `pieces` seeds clipped to the mesh.
    Voronoi {
        /// Number of seeds (ignored when `seeds` is given).
        pieces: usize,
        /// Seed distribution.
        pattern: Pattern,
        /// Impact point for [`Pattern::Radial`] (default: a random surface vertex).
        impact: Option<DVec3>,
        /// Explicit seeds (e.g. read from a file); overrides `pieces` and `pattern`.
        seeds: Option<Vec<DVec3>>,
    },
    /// Cuts by `pieces` planes, each cutting every current piece.
    Slice {
        /// Number of random planes (ignored when `planes` is given).
        pieces: usize,
        /// Explicit planes as `(point, normal)`.
        planes: Option<Vec<(DVec3, DVec3)>>,
    },
}

impl Default for Method {
    fn default() -> Self {
        Method::Voronoi {
            pieces: 20,
            pattern: Pattern::Uniform,
            impact: None,
            seeds: None,
        }
    }
}

/// Parameters of [`fracture`](super::fracture).
///
/// ```
/// use shatter_geom::fracture::{FractureParams, Method, Placement};
/// let params = FractureParams {
///     method: Method::Tetra { random_vertices: 50, skip: 0, center: true, placement: Placement::Thesis },
///     seed: 7,
/// };
/// assert_eq!(params.seed, 7);
/// assert!(matches!(FractureParams::default().method, Method::Voronoi { pieces: 20, .. }));
/// ```
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FractureParams {
    /// The method and its parameters.
    pub method: Method,
    /// Random seed: the same seed gives the same fracture.
    pub seed: u64,
}

/// Why a mesh cannot be fractured.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FractureError {
    /// The mesh is not a valid solid (empty, non-finite, open, non-manifold,
    /// self-touching, inconsistently wound or without volume); the message has counts.
    #[error("invalid mesh: {0}")]
    Mesh(#[from] MeshError),
    /// The model's attributes do not fit its mesh (see [`crate::model::Model::check`]).
    #[error("invalid model: {0}")]
    Model(#[from] ModelError),
    /// A fragment count below one.
    #[error("the number of pieces must be at least 1 (got {0})")]
    TooFewPieces(usize),
    /// An explicit seed or plane is not finite, or a plane normal is zero.
    #[error("{what} {index} is not finite or degenerate")]
    BadInput {
        /// What it is ("seed", "plane", "impact point").
        what: &'static str,
        /// Its index in the given list.
        index: usize,
    },
    /// The tetrahedralization failed (too few distinct or only coplanar points).
    #[error("tetrahedralization failed: {0}")]
    Delaunay(#[from] DelaunayError),
    /// No fragment was produced (e.g. every seed was far outside the mesh).
    #[error("no fragment was produced")]
    NoFragments,
}
