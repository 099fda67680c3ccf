//! The fracture result types.

use glam::{DMat3, DVec3};
use serde::{Deserialize, Serialize};

use crate::TriMesh;
use crate::model::{Corners, Material};

/// One piece of a fractured object.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fragment {
    /// Closed, outward-wound surface of the fragment, in the object's frame.
    pub mesh: TriMesh,
    /// Per triangle of `mesh`: `true` for an interior (cut) face, `false` for a face on
    /// the original surface.
    pub interior: Vec<bool>,
    /// Per triangle corner of `mesh`: UVs, normals and colours, present when the input
    /// had them (see [`fracture_model`](super::fracture_model)). Surface corners carry
    /// the input's values interpolated at their positions; interior corners a planar
    /// projection (UVs), the face's normal and white.
    pub corners: Corners,
    /// Per triangle of `mesh`: its material, an index into [`Fracture::materials`]
    /// (surface triangles keep the input's; interior ones have the `interior` material).
    pub material: Vec<u32>,
    /// Convex pieces for collision: each a point cloud whose convex hull has a
    /// non-degenerate volume. Their union approximates the fragment.
    pub convex_pieces: Vec<Vec<DVec3>>,
    /// Per convex piece, when known, the triangles of its hull: indices into the piece's
    /// points, wound counter-clockwise seen from outside (a closed convex surface). A
    /// collider then needs no hull computation, and a runtime cut clips the piece again
    /// ([`fracture_fragment`](super::fracture_fragment)). Empty when no piece's hull is
    /// known; otherwise one list per piece, empty for a piece whose hull is not known
    /// (it is then computed from the points).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub convex_hulls: Vec<Vec<[u32; 3]>>,
    /// Volume of the fragment.
    pub volume: f64,
    /// Centre of mass (uniform density).
    pub centroid: DVec3,
    /// Inertia tensor about the centroid for unit density.
    pub inertia: DMat3,
}

/// A bond between two fragments that share a face.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
///
/// `Fracture` (with its fragments, bonds and materials) is serialisable with serde; a
/// JSON round trip gives back an equal fracture. For a file a game loads, prefer the
/// GLB with the `SHATTER_fracture` extension
/// ([`write_fracture_glb`](crate::io::write_fracture_glb),
/// [`read_fracture`](crate::io::read_fracture)), which viewers open too.
///
/// ```
/// use shatter_geom::fracture::{fracture, FractureParams, Method};
/// use shatter_geom::shapes;
///
/// let params = FractureParams {
///     method: Method::Slice { pieces: 0, planes: Some(vec![(Default::default(), shatter_geom::DVec3::X)]) },
///     seed: 0,
/// };
/// let result = fracture(&shapes::cube(), &params)?;
/// // The plane x = 0 halves the cube: two fragments, one bond across the cut.
/// assert_eq!(result.fragments.len(), 2);
/// assert_eq!(result.bonds.len(), 1);
/// assert_eq!(result.bonds_of(0).count(), 1);
/// assert!((result.bonds[0].area - 1.0).abs() < 1e-12);
/// assert!((result.total_volume() - 1.0).abs() < 1e-12);
/// // A bare mesh: a `surface` material, then `interior` for the cut faces.
/// assert_eq!(result.materials.len(), 2);
/// assert_eq!(result.materials[1].name, "interior");
/// let f = &result.fragments[0];
/// assert!(f.material.iter().zip(&f.interior).all(|(&m, &i)| (m == 1) == i));
/// # Ok::<(), shatter_geom::fracture::FractureError>(())
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Fracture {
    /// The fragments.
    pub fragments: Vec<Fragment>,
    /// Bonds between fragments sharing a face, sorted by `(a, b)`, each pair once.
    pub bonds: Vec<Bond>,
    /// The materials [`Fragment::material`] indexes: the input's (one default
    /// `surface` material for a bare mesh), then `interior` for the cut faces.
    pub materials: Vec<Material>,
    /// Repairs and losses worth telling the user about (an inward mesh flipped, tiny
    /// isolated tetrahedra dropped, ...). Empty when there was nothing to say.
    pub warnings: Vec<String>,
}

impl Fracture {
    /// Sum of the fragments' volumes.
    pub fn total_volume(&self) -> f64 {
        self.fragments.iter().map(|f| f.volume).sum()
    }

    /// The fragments that touch the object's lowest plane: those with a vertex within
    /// 1e-6 of the object's height above its lowest point (`y` is up). This is the rule
    /// `shatter-sim` applies to an `anchored` object, written as a list of fragment
    /// indices for a pre-fractured asset's anchors.
    ///
    /// ```
    /// use shatter_geom::fracture::{fracture, FractureParams, Method};
    /// use shatter_geom::{shapes, DVec3};
    /// // The cube cut at y = 0: only the lower half touches the ground.
    /// let params = FractureParams {
    ///     method: Method::Slice { pieces: 0, planes: Some(vec![(DVec3::ZERO, DVec3::Y)]) },
    ///     seed: 0,
    /// };
    /// let halves = fracture(&shapes::cube(), &params)?;
    /// let lowest = halves.lowest_fragments();
    /// assert_eq!(lowest.len(), 1);
    /// assert!(halves.fragments[lowest[0] as usize].centroid.y < 0.0);
    /// # Ok::<(), shatter_geom::fracture::FractureError>(())
    /// ```
    pub fn lowest_fragments(&self) -> Vec<u32> {
        let ys = |f: &Fragment| {
            f.mesh
                .positions
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p.y), hi.max(p.y))
                })
        };
        let (lo, hi) = self
            .fragments
            .iter()
            .map(ys)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (a, b)| {
                (lo.min(a), hi.max(b))
            });
        let eps = 1e-6 * (hi - lo).abs().max(1e-9);
        (0..self.fragments.len() as u32)
            .filter(|&i| ys(&self.fragments[i as usize]).0 <= lo + eps)
            .collect()
    }

    /// The bonds of fragment `i` (either side), in bond order.
    pub fn bonds_of(&self, i: u32) -> impl Iterator<Item = &Bond> {
        self.bonds.iter().filter(move |b| b.a == i || b.b == i)
    }
}
