//! Why a fracture fails: [`FractureError`], and [`InvalidFracture`], the invariant a
//! result broke (found by [`Fracture::validate`](super::Fracture::validate)).

use glam::DVec3;

use crate::delaunay::DelaunayError;
use crate::mesh::MeshError;
use crate::model::ModelError;

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
    /// A grid with no cell along an axis, or more cells than fragment indices hold.
    #[error(
        "the grid needs at least 1 cell along each axis and fewer than 2^32 in all \
         (got {}×{}×{})",
        cells[0],
        cells[1],
        cells[2]
    )]
    BadGrid {
        /// The cells asked for along x, y and z.
        cells: [u32; 3],
    },
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
    /// A result the mesh's size puts beyond `f64`: a volume (size³), inertia tensor
    /// (size⁵) or bond area (size²) that would overflow to infinity or fall below the
    /// smallest full-precision value (`f64::MIN_POSITIVE`, about 2.2e-308).
    #[error(
        "{what} would be about 1e{log10}, outside the range f64 holds at full precision \
         (2.2e-308 to 1.8e308); rescale the mesh nearer to unit size"
    )]
    OutOfRange {
        /// The quantity ("the mesh's volume", "a fragment's inertia tensor", ...).
        what: &'static str,
        /// Its order of magnitude (base 10).
        log10: i32,
    },
    /// The mesh's volume is lost in rounding: its signed parts cancel about `10^log10`-
    /// fold, so no volume, mass or inertia computed in `f64` would be right (a part of
    /// the mesh vastly larger than the rest, e.g. a vertex moved 1e33 away into a flat
    /// fin).
    #[error(
        "the mesh's volume is lost in rounding: its signed parts cancel about 1e{log10}-fold \
         (is one part of the mesh vastly larger than the rest, e.g. a stray vertex?)"
    )]
    VolumeLost {
        /// Order of magnitude (base 10) of the cancellation.
        log10: i32,
    },
    /// The fragments' volumes do not add up to the mesh's (relative error above 1e-6):
    /// the mesh has features far below the cut tolerance (1e-10 of its size per axis),
    /// so the cut could not follow them.
    #[error(
        "the fragments' volumes add up to {ratio:.6} times the mesh's: the mesh has \
         features far below the cut tolerance (1e-10 of its extent along an axis)"
    )]
    VolumeMismatch {
        /// Sum of the fragments' volumes over the mesh's.
        ratio: f64,
    },
    /// The fracture's own result failed [`Fracture::validate`](super::Fracture::validate)
    /// (a fragment not closed, two triangles back to back, a bad bond): an error in
    /// shatter, refused rather than returned. Every result is checked before it is
    /// returned.
    #[error(
        "the fracture made an invalid result ({0}); this is a bug in shatter: please \
         report it with the mesh"
    )]
    Invalid(#[from] InvalidFracture),
    /// An explicit seed, plane point or impact point so far from the mesh that the
    /// fracture's local frame (the mesh's box scaled to unit size) cannot hold it: a
    /// coordinate more than [`FAR_LIMIT`](super::FAR_LIMIT) (2^64) of the
    /// mesh's half size from it.
    #[error(
        "{what} {index} is too far from the mesh: more than 1.8e19 times its size away, \
         where the cut's arithmetic would overflow"
    )]
    TooFar {
        /// What it is ("seed", "plane", "impact point").
        what: &'static str,
        /// Its index in the given list.
        index: usize,
    },
    /// A [`Roughness`](super::Roughness) value out of range.
    #[error("roughness {field} must be {expected} (got {value})")]
    BadRoughness {
        /// The field ("amplitude", "frequency", "octaves").
        field: &'static str,
        /// Its value.
        value: f64,
        /// What it must be.
        expected: &'static str,
    },
    /// A fragment of a fracture given to [`roughen`](super::roughen) whose parts do not
    /// fit together (an index past its vertices, a non-finite vertex, per-triangle lists
    /// of the wrong length).
    #[error("fragment {fragment}: {reason}")]
    BadFragment {
        /// The fragment.
        fragment: usize,
        /// What is wrong.
        reason: &'static str,
    },
}

/// A violated invariant, found by [`Fracture::validate`](super::Fracture::validate). Fragments,
/// triangles and bonds are indices into the [`Fracture`](super::Fracture); edges are given by
/// their two end positions.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InvalidFracture {
    /// The fracture has no fragment.
    #[error("no fragments")]
    Empty,
    /// A triangle index past the fragment's vertices, or a non-finite coordinate.
    #[error(
        "fragment {fragment}: triangle {triangle} has a vertex index out of range or a non-finite vertex"
    )]
    Malformed {
        /// The fragment.
        fragment: usize,
        /// The triangle.
        triangle: usize,
    },
    /// `interior` does not have one flag per triangle.
    #[error("fragment {fragment}: {flags} interior flags for {triangles} triangles")]
    InteriorFlags {
        /// The fragment.
        fragment: usize,
        /// Length of `interior`.
        flags: usize,
        /// Number of triangles.
        triangles: usize,
    },
    /// A triangle of zero area (a repeated position, or collinear corners, exactly).
    #[error("fragment {fragment}: triangle {triangle} is degenerate")]
    Degenerate {
        /// The fragment.
        fragment: usize,
        /// The triangle.
        triangle: usize,
    },
    /// Two triangles on the same three positions (equal or opposite winding: a double
    /// face left inside the fragment).
    #[error(
        "fragment {fragment}: triangles {first} and {second} have the same corners ({})",
        if *.opposite { "a back-to-back pair" } else { "a duplicate" }
    )]
    DuplicateTriangles {
        /// The fragment.
        fragment: usize,
        /// The first triangle.
        first: usize,
        /// The second triangle.
        second: usize,
        /// Wound opposite ways.
        opposite: bool,
    },
    /// An edge not used by exactly two triangles: a hole (1) or a non-manifold edge (3+).
    #[error("fragment {fragment}: edge {a} – {b} is used by {uses} triangles, not 2")]
    EdgeUses {
        /// The fragment.
        fragment: usize,
        /// One end of the edge.
        a: DVec3,
        /// The other end.
        b: DVec3,
        /// Triangles using it.
        uses: usize,
    },
    /// An edge whose two triangles walk it the same way (inconsistent winding).
    #[error("fragment {fragment}: edge {a} – {b} is walked the same way by both its triangles")]
    Winding {
        /// The fragment.
        fragment: usize,
        /// One end of the edge.
        a: DVec3,
        /// The other end.
        b: DVec3,
    },
    /// A fragment volume that is not positive, or that disagrees with its mesh's volume
    /// (an inward or broken mesh).
    #[error("fragment {fragment}: volume {volume:e}, its mesh encloses {mesh:e}")]
    Volume {
        /// The fragment.
        fragment: usize,
        /// Its `volume` field.
        volume: f64,
        /// The signed volume its mesh encloses.
        mesh: f64,
    },
    /// `convex_hulls` is neither empty nor one list per convex piece, or a hull triangle
    /// names a point its piece does not have.
    #[error("fragment {fragment}: convex piece {piece}'s hull {reason}")]
    ConvexHull {
        /// The fragment.
        fragment: usize,
        /// The convex piece (the number of pieces when the lists do not match them).
        piece: usize,
        /// What is wrong.
        reason: &'static str,
    },
    /// The fragments' volumes do not add up to the expected volume.
    #[error("the fragments' volumes add up to {total:e}, not {expected:e} (relative error {:e})", (total - expected).abs() / expected.abs())]
    TotalVolume {
        /// Sum of the fragments' volumes.
        total: f64,
        /// The mesh's volume.
        expected: f64,
    },
    /// A bond out of order, out of range, repeated, or with a bad area, normal or
    /// centroid.
    #[error("bond {bond} ({a}–{b}): {reason}")]
    Bond {
        /// The bond.
        bond: usize,
        /// Its first fragment.
        a: u32,
        /// Its second fragment.
        b: u32,
        /// What is wrong.
        reason: &'static str,
    },
}
