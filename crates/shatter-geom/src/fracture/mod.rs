//! Fracture of closed meshes into bonded fragments.
//!
//! Shared result types (fixed; the methods fill them in).

use glam::{DMat3, DVec3};

use crate::TriMesh;

/// One piece of a fractured object.
#[derive(Debug, Clone)]
pub struct Fragment {
    /// Closed, outward-wound surface of the fragment, in the object's frame.
    pub mesh: TriMesh,
    /// Per triangle of `mesh`: `true` for an interior (cut) face, `false` for a face on
    /// the original surface.
    pub interior: Vec<bool>,
    /// Convex pieces for collision: each a point cloud whose convex hull has a
    /// non-degenerate volume. Their union approximates the fragment.
    pub convex_pieces: Vec<Vec<DVec3>>,
    /// Volume of the fragment.
    pub volume: f64,
    /// Centre of mass (uniform density).
    pub centroid: DVec3,
    /// Inertia tensor about the centroid for unit density.
    pub inertia: DMat3,
}

/// A bond between two fragments that share a face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bond {
    /// First fragment (index into [`Fracture::fragments`]), `a < b`.
    pub a: u32,
    /// Second fragment.
    pub b: u32,
    /// Area of the shared face.
    pub area: f64,
    /// Centroid of the shared face.
    pub centroid: DVec3,
    /// Unit normal of the shared face, pointing from `a` to `b`.
    pub normal: DVec3,
}

/// A fractured object: fragments and the bond graph between them.
#[derive(Debug, Clone, Default)]
pub struct Fracture {
    /// The fragments.
    pub fragments: Vec<Fragment>,
    /// Bonds between fragments sharing a face, sorted by `(a, b)`, each pair once.
    pub bonds: Vec<Bond>,
}
