//! Public result and error types.

use glam::DVec3;

/// Marker in [`Tetrahedralization::neighbors`] for a face on the convex hull.
pub const NO_NEIGHBOR: u32 = u32::MAX;

/// Outward-oriented faces of a positively oriented tetrahedron: `FACES[i]` is the face
/// opposite vertex `i`, wound counter-clockwise when seen from outside.
pub const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// The result of [`tetrahedralize`](super::tetrahedralize).
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
    /// Every merged duplicate as `[index, first occurrence]`, in increasing `index`.
    pub duplicates: Vec<[u32; 2]>,
}

impl Tetrahedralization {
    /// The convex hull's boundary: one triangle per tetrahedron face without a neighbour,
    /// wound counter-clockwise seen from outside (outward normals).
    ///
    /// ```
    /// use shatter_geom::{DVec3, delaunay::tetrahedralize};
    /// let pts = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
    /// let t = tetrahedralize(&pts).expect("a tetrahedron");
    /// assert_eq!(t.hull_faces().len(), 4);
    /// ```
    pub fn hull_faces(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::new();
        for (tet, nb) in self.tetrahedra.iter().zip(&self.neighbors) {
            for (i, face) in FACES.iter().enumerate() {
                if nb[i] == NO_NEIGHBOR {
                    out.push([tet[face[0]], tet[face[1]], tet[face[2]]]);
                }
            }
        }
        out
    }

    /// Sum of the tetrahedra's volumes, computed in `f64` from `points`.
    pub fn volume(&self, points: &[DVec3]) -> f64 {
        self.tetrahedra
            .iter()
            .map(|t| {
                let a = points[t[0] as usize];
                (points[t[1] as usize] - a)
                    .dot((points[t[2] as usize] - a).cross(points[t[3] as usize] - a))
                    / 6.0
            })
            .sum()
    }
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
    /// A coordinate's magnitude is outside the range where the exact predicates stay exact
    /// (non-zero magnitudes must lie in `[1e-40, 1e40]`).
    #[error(
        "point {index} has coordinate {value:e}, outside the exactly supported range \
         (zero or magnitude in [1e-40, 1e40])"
    )]
    OutOfRange {
        /// Index of the offending input point.
        index: usize,
        /// The offending coordinate.
        value: f64,
    },
    /// The tetrahedralization would need more tetrahedra than the index storage holds.
    #[error("{points} points need more than 2^30 tetrahedra")]
    TooLarge {
        /// Number of input points.
        points: usize,
    },
}
