//! Validation of a mesh as a solid, and the one unambiguous repair (flipping an inward
//! mesh).

use thiserror::Error;

use super::TriMesh;
use super::intersect::crossing_depth;
use super::shells::{self, ShellOrientation};
use crate::fracture::normalize::{Frame, ldexp};

/// Why a mesh is not a valid solid. Each variant carries the offending data.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum MeshError {
    /// No vertices or no triangles.
    #[error("mesh is empty")]
    Empty,
    /// A vertex with a NaN or infinite coordinate.
    #[error("vertex {vertex} has a non-finite coordinate")]
    NonFinite {
        /// Index of the first such vertex.
        vertex: usize,
    },
    /// A triangle index past the end of the vertex list.
    #[error("triangle {triangle} references vertex {index} of {vertices}")]
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The offending index.
        index: u32,
        /// Number of vertices.
        vertices: usize,
    },
    /// Edges used by one triangle only: the surface has holes.
    #[error("{0} boundary edges")]
    BoundaryEdges(usize),
    /// Edges shared by more than two triangles.
    #[error("{0} non-manifold edges")]
    NonManifoldEdges(usize),
    /// Edges used twice in the same direction.
    #[error("{0} inconsistently wound edges")]
    InconsistentWinding(usize),
    /// Vertices where the surface touches itself.
    #[error("{0} non-manifold vertices (self-touching surface)")]
    NonManifoldVertices(usize),
    /// Triangles that share no vertex cross deeper than [`CROSSING_TOLERANCE`].
    #[error("{pairs} pairs of triangles intersect (first: triangles {} and {})", first.0, first.1)]
    SelfIntersecting {
        /// Number of pairs crossing deeper than the tolerance.
        pairs: usize,
        /// The first of them.
        first: (u32, u32),
    },
    /// The surface is consistently wound inward; [`TriMesh::orient_outward`] fixes it.
    #[error("mesh is wound inward (signed volume {volume})")]
    Inward {
        /// The (negative) signed volume.
        volume: f64,
    },
    /// Some shells (connected components) are wound against their nesting: a solid
    /// wound inward, or a cavity wound outward, among correctly wound shells.
    #[error("{wrong} of {total} shells are wound the wrong way for their nesting")]
    InwardShells {
        /// Shells in error.
        wrong: usize,
        /// All shells.
        total: usize,
    },
    /// The closed surface encloses no volume.
    #[error("mesh encloses zero volume")]
    ZeroVolume,
}

/// Triangles that cross by at most this fraction of the mesh's bounding-box diagonal
/// (or only touch) do not make it self-intersecting for [`TriMesh::validate_solid`]: the
/// fracture's cut tolerance (1e-10 of the size), below which the fracture does not tell
/// one side of a plane from the other. The union of crossing parts that repair makes
/// rounds each exact vertex to `f64` once, which leaves a few such crossings where parts
/// met face to face (Khronos' 2CylinderEngine: 35 pairs, the deepest 5e-12 of its size).
pub const CROSSING_TOLERANCE: f64 = 1e-10;

impl TriMesh {
    /// Checks that the mesh is a valid solid: non-empty, finite, indices in range, and,
    /// after welding, closed, manifold (edges and vertices), consistently wound, and
    /// outward — each shell (connected component) outward if it is a solid, inward if it is
    /// a cavity inside another shell — without self-intersection: surfaces touching at a
    /// shared vertex position (non-manifold vertices) are refused, and so are triangles
    /// sharing no vertex that cross ([`self_intersections`](TriMesh::self_intersections),
    /// exact) deeper than [`CROSSING_TOLERANCE`] of the size (rounding; triangles that
    /// only touch are accepted); a fold between triangles sharing a vertex is not looked
    /// for. Zero-area triangles are
    /// allowed (they are counted by [`check`](TriMesh::check)).
    ///
    /// ```
    /// use shatter_geom::{mesh::MeshError, shapes};
    /// assert_eq!(shapes::bird().validate_solid(), Ok(()));
    /// let mut open = shapes::cube();
    /// open.triangles.pop();
    /// let err = open.validate_solid().unwrap_err();
    /// assert_eq!(err, MeshError::BoundaryEdges(3));
    /// assert_eq!(err.to_string(), "3 boundary edges");
    /// ```
    ///
    /// Any magnitude: a mesh far from unit size, or very much thinner along one axis than
    /// another, is checked in an exactly rescaled frame (powers of two per axis, which
    /// keep the sign of every exact predicate), so the answer is the same as at unit
    /// size.
    pub fn validate_solid(&self) -> Result<(), MeshError> {
        self.validate_solid_with(true)
    }

    /// [`validate_solid`](TriMesh::validate_solid), without the self-intersection search
    /// unless `crossings` (for a fragment the fracture cut exactly from a checked solid,
    /// which cannot cross itself: see [`TriMesh::is_fracture_fragment`]).
    pub(crate) fn validate_solid_with(&self, crossings: bool) -> Result<(), MeshError> {
        self.validate_indices()?;
        let frame = Frame::of(self);
        if frame.is_plain() {
            return self.validate_solid_here(crossings);
        }
        match frame.mesh_to_local(self).validate_solid_here(crossings) {
            Err(MeshError::Inward { volume }) => Err(MeshError::Inward {
                volume: ldexp(volume, frame.volume_exp2()),
            }),
            r => r,
        }
    }

    /// [`validate_solid`](TriMesh::validate_solid) on the coordinates as they are
    /// (indices already checked).
    fn validate_solid_here(&self, crossings: bool) -> Result<(), MeshError> {
        // The topology and the self-intersection search are independent, so they run at
        // once (rayon); a topology error still comes first.
        let (r, crossing) = rayon::join(
            || self.check(),
            || {
                if crossings {
                    self.self_intersections(usize::MAX)
                } else {
                    Vec::new()
                }
            },
        );
        if r.boundary_edges > 0 {
            return Err(MeshError::BoundaryEdges(r.boundary_edges));
        }
        if r.non_manifold_edges > 0 {
            return Err(MeshError::NonManifoldEdges(r.non_manifold_edges));
        }
        if r.inconsistent_edges > 0 {
            return Err(MeshError::InconsistentWinding(r.inconsistent_edges));
        }
        if r.non_manifold_vertices > 0 {
            return Err(MeshError::NonManifoldVertices(r.non_manifold_vertices));
        }
        // Pairs that only touch, or cross by no more than rounding, are accepted.
        let tolerance = self
            .bounds()
            .map_or(0.0, |(lo, hi)| CROSSING_TOLERANCE * (hi - lo).length());
        let deep: Vec<(u32, u32)> = crossing
            .into_iter()
            .filter(|&(a, b)| {
                crossing_depth(self.triangle(a as usize), self.triangle(b as usize)) > tolerance
            })
            .collect();
        if let Some(&first) = deep.first() {
            return Err(MeshError::SelfIntersecting {
                pairs: deep.len(),
                first,
            });
        }
        if r.components == 1 {
            if r.signed_volume == 0.0 || r.signed_volume.is_nan() {
                return Err(MeshError::ZeroVolume);
            }
            return if r.signed_volume < 0.0 {
                Err(MeshError::Inward {
                    volume: r.signed_volume,
                })
            } else {
                Ok(())
            };
        }
        match shells::orientation(&self.welded()) {
            ShellOrientation::Outward => Ok(()),
            ShellOrientation::Inward => Err(MeshError::Inward {
                volume: r.signed_volume,
            }),
            ShellOrientation::Mixed { wrong, total } => {
                Err(MeshError::InwardShells { wrong, total })
            }
        }
    }

    /// The checks that need no topology: non-empty, finite coordinates, indices in range.
    ///
    /// ```
    /// use shatter_geom::{DVec3, TriMesh};
    /// let m = TriMesh::new(vec![DVec3::ZERO; 3], vec![[0, 1, 99]]);
    /// assert_eq!(
    ///     m.validate_indices().unwrap_err().to_string(),
    ///     "triangle 0 references vertex 99 of 3"
    /// );
    /// ```
    pub fn validate_indices(&self) -> Result<(), MeshError> {
        if self.positions.is_empty() || self.triangles.is_empty() {
            return Err(MeshError::Empty);
        }
        if let Some(vertex) = self.positions.iter().position(|p| !p.is_finite()) {
            return Err(MeshError::NonFinite { vertex });
        }
        let vertices = self.positions.len();
        for (triangle, tri) in self.triangles.iter().enumerate() {
            if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertices) {
                return Err(MeshError::IndexOutOfRange {
                    triangle,
                    index,
                    vertices,
                });
            }
        }
        Ok(())
    }

    /// Repairs the one unambiguous defect: a closed, consistently wound mesh with a
    /// negative signed volume is flipped in place. Returns `Ok(true)` if it flipped,
    /// `Ok(false)` if the mesh was already outward, and the validation error otherwise
    /// (the mesh is then unchanged). With several shells, the mesh is flipped only when
    /// every shell is wrong and flipping them all fixes every one (solids outward,
    /// cavities inward); a mix of right and wrong shells is an error.
    ///
    /// ```
    /// use shatter_geom::shapes;
    /// let mut m = shapes::cylinder().flipped();
    /// assert_eq!(m.orient_outward(), Ok(true));
    /// assert!(m.is_outward());
    /// assert_eq!(m.orient_outward(), Ok(false));
    /// ```
    pub fn orient_outward(&mut self) -> Result<bool, MeshError> {
        match self.validate_solid() {
            Ok(()) => Ok(false),
            Err(MeshError::Inward { .. }) => {
                for t in &mut self.triangles {
                    t.swap(1, 2);
                }
                Ok(true)
            }
            Err(e) => Err(e),
        }
    }
}
