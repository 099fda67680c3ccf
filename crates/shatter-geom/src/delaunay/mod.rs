//! Exact 3D Delaunay tetrahedralization.
//!
//! API contract (fixed; the implementation fills it in):
//! - [`tetrahedralize`] takes any slice of points and returns a [`Tetrahedralization`]
//!   or a typed [`DelaunayError`].
//! - Every tetrahedron `[a, b, c, d]` is positively oriented:
//!   `(b - a) · ((c - a) × (d - a)) > 0` (exactly, by `robust::orient3d`).
//! - `neighbors[t][i]` is the tetrahedron across the face opposite vertex `i` of `t`,
//!   or [`NO_NEIGHBOR`] on the convex hull.
//! - Indices refer to the input slice; a duplicate point maps to its first occurrence.

use glam::DVec3;

/// Marker in [`Tetrahedralization::neighbors`] for a face on the convex hull.
pub const NO_NEIGHBOR: u32 = u32::MAX;

/// The result of [`tetrahedralize`].
#[derive(Debug, Clone, Default)]
pub struct Tetrahedralization {
    /// Positively oriented tetrahedra, four indices into the input points each.
    pub tetrahedra: Vec<[u32; 4]>,
    /// `neighbors[t][i]`: the tetrahedron sharing the face opposite vertex `i`.
    pub neighbors: Vec<[u32; 4]>,
    /// For every input point, the index of the first input point at the same position.
    pub representative: Vec<u32>,
    /// Number of distinct input points.
    pub unique_points: usize,
}

/// Why a point set cannot be tetrahedralized.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DelaunayError {
    /// A coordinate is NaN or infinite.
    #[error("point {index} has a non-finite coordinate")]
    NonFinite {
        /// Index of the offending input point.
        index: usize,
    },
    /// Fewer than four distinct points.
    #[error("only {distinct} distinct points; a tetrahedralization needs at least 4")]
    TooFewPoints {
        /// How many distinct points there were.
        distinct: usize,
    },
    /// All points lie on one plane (or one line).
    #[error("all {distinct} distinct points are coplanar")]
    AllCoplanar {
        /// How many distinct points there were.
        distinct: usize,
    },
}

/// Delaunay tetrahedralization of `points`.
pub fn tetrahedralize(points: &[DVec3]) -> Result<Tetrahedralization, DelaunayError> {
    let _ = points;
    todo!("the delaunay module is being written")
}
