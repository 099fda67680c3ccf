//! Public result and error types.

use glam::DVec3;

use super::packed::Tets;

/// Marker in [`Tetrahedralization::neighbors`] for a face on the convex hull.
pub const NO_NEIGHBOR: u32 = u32::MAX;

/// Outward-oriented faces of a positively oriented tetrahedron: `FACES[i]` is the face
/// opposite vertex `i`, wound counter-clockwise when seen from outside.
pub const FACES: [[usize; 3]; 4] = [[1, 2, 3], [0, 3, 2], [0, 1, 3], [0, 2, 1]];

/// The result of [`tetrahedralize`](super::tetrahedralize).
///
/// The tetrahedra and their face adjacency are stored bit-packed (24 bytes per
/// tetrahedron for up to about two million points, where two `[u32; 4]` arrays take 32)
/// and read through [`tetrahedron`](Self::tetrahedron), [`tetrahedra`](Self::tetrahedra) and
/// [`neighbors`](Self::neighbors).
///
/// ```
/// use shatter_geom::delaunay::{NO_NEIGHBOR, tetrahedralize};
/// use shatter_geom::sampling::uniform;
/// let pts = uniform(200, 3);
/// let t = tetrahedralize(&pts).expect("points in general position");
/// for (i, tet) in t.tetrahedra().enumerate() {
///     for (face, n) in t.neighbors(i).into_iter().enumerate() {
///         if n != NO_NEIGHBOR {
///             // The neighbour shares the three vertices of the face opposite `face`.
///             let other = t.tetrahedron(n as usize);
///             assert!((0..4).filter(|&k| k != face).all(|k| other.contains(&tet[k])));
///         }
///     }
/// }
/// ```
#[derive(Debug, Clone, Default)]
pub struct Tetrahedralization {
    pub(crate) tets: Tets,
    /// For every input point, the index of the first input point at the same position.
    pub representative: Vec<u32>,
    /// Number of distinct input points.
    pub unique_points: usize,
    /// Every merged duplicate as `[index, first occurrence]`, in increasing `index`.
    pub duplicates: Vec<[u32; 2]>,
}

impl Tetrahedralization {
    pub(crate) fn from_parts(
        tets: Tets,
        representative: Vec<u32>,
        unique_points: usize,
        duplicates: Vec<[u32; 2]>,
    ) -> Self {
        Self {
            tets,
            representative,
            unique_points,
            duplicates,
        }
    }

    /// Number of tetrahedra.
    pub fn len(&self) -> usize {
        self.tets.len()
    }

    /// Whether there are no tetrahedra (never, for a successful [`tetrahedralize`](super::tetrahedralize)).
    pub fn is_empty(&self) -> bool {
        self.tets.len() == 0
    }

    /// Tetrahedron `t`: four indices into the input points, positively oriented.
    ///
    /// # Panics
    /// If `t >= self.len()`.
    #[inline]
    pub fn tetrahedron(&self, t: usize) -> [u32; 4] {
        assert!(t < self.len(), "tetrahedron {t} of {}", self.len());
        self.tets.verts(t as u32)
    }

    /// Every tetrahedron in order, as [`tetrahedron`](Self::tetrahedron) gives them.
    pub fn tetrahedra(&self) -> impl ExactSizeIterator<Item = [u32; 4]> + '_ {
        (0..self.len() as u32).map(|t| self.tets.verts(t))
    }

    /// `neighbors(t)[i]`: the tetrahedron sharing the face opposite vertex `i` of `t`, or
    /// [`NO_NEIGHBOR`] when that face is on the convex hull.
    ///
    /// # Panics
    /// If `t >= self.len()`.
    #[inline]
    pub fn neighbors(&self, t: usize) -> [u32; 4] {
        assert!(t < self.len(), "tetrahedron {t} of {}", self.len());
        std::array::from_fn(|i| self.tets.neighbor(t as u32, i).unwrap_or(NO_NEIGHBOR))
    }

    /// Replaces tetrahedron `t`'s vertices (for tools that edit a result, and for testing
    /// [`validate`](Self::validate)).
    ///
    /// # Panics
    /// If `t >= self.len()` or a vertex is not below the number of input points.
    pub fn set_tetrahedron(&mut self, t: usize, verts: [u32; 4]) {
        assert!(t < self.len(), "tetrahedron {t} of {}", self.len());
        let n = self.representative.len();
        assert!(
            verts.iter().all(|&v| (v as usize) < n),
            "vertices {verts:?} of {n} points"
        );
        self.tets.set_verts(t as u32, verts);
    }

    /// Replaces `neighbors(t)[face]` by `other` (a tetrahedron or [`NO_NEIGHBOR`]).
    ///
    /// # Panics
    /// If `t` or `other` is out of range, or `face > 3`.
    pub fn set_neighbor(&mut self, t: usize, face: usize, other: u32) {
        assert!(t < self.len() && face < 4, "face {face} of tetrahedron {t}");
        let other = (other != NO_NEIGHBOR).then(|| {
            assert!(
                (other as usize) < self.len(),
                "neighbour {other} of {}",
                self.len()
            );
            other
        });
        self.tets.set_neighbor(t as u32, face, other);
    }

    /// Heap bytes the result has allocated: the packed tetrahedra (with the capacity the
    /// construction reserved, about 7 per point, of which only what was used is ever
    /// resident), `representative` and `duplicates`.
    pub fn heap_bytes(&self) -> usize {
        self.tets.heap_bytes() + self.representative.capacity() * 4 + self.duplicates.capacity() * 8
    }

    /// Gives back the storage the construction used beyond the final tetrahedra: the
    /// infinite ones on the hull, freed slots and the unused reservation. Not done by
    /// [`tetrahedralize`](super::tetrahedralize) itself, because with some allocators
    /// (mimalloc) shrinking copies the tetrahedra, which would raise the peak memory by
    /// the result's size. Worth it when many points are on the hull (points on a sphere
    /// leave about 40% of the slots to infinite tetrahedra).
    ///
    /// ```
    /// use shatter_geom::delaunay::tetrahedralize;
    /// use shatter_geom::sampling::sphere;
    /// let pts = sphere(2000, 1);
    /// let mut t = tetrahedralize(&pts).expect("points on a sphere");
    /// let before = t.heap_bytes();
    /// let first = t.tetrahedron(0);
    /// t.shrink_to_fit();
    /// assert!(t.heap_bytes() < before);
    /// assert_eq!(t.tetrahedron(0), first);
    /// t.validate(&pts).expect("still Delaunay");
    /// ```
    pub fn shrink_to_fit(&mut self) {
        self.tets.shrink_to_fit();
        self.representative.shrink_to_fit();
        self.duplicates.shrink_to_fit();
    }

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
        for (t, tet) in self.tetrahedra().enumerate() {
            let nb = self.neighbors(t);
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
        self.tetrahedra()
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
