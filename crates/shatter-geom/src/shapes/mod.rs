//! Built-in shapes: Unity's primitives with their vertex counts (cube 24, capsule 550,
//! cylinder 88), a UV sphere, a torus, and the bird (the thesis's concave test model).
//!
//! Like Unity's, the meshes split vertices at seams and hard edges, so they are
//! closed only after welding ([`TriMesh::welded`]); every check in
//! [`crate::mesh`] welds first. All shapes are wound outward and centred near the origin
//! with `+y` up.
//!
//! ```
//! use shatter_geom::shapes;
//! for name in shapes::NAMES {
//!     let mesh = shapes::by_name(name).expect("built-in");
//!     assert!(mesh.check().is_solid(), "{name}");
//! }
//! ```

mod bird;
mod cube;
mod lathe;
mod revolved;

pub use bird::bird;
pub use cube::cube;
pub use lathe::{capsule, cylinder};
pub use revolved::{sphere, torus};

use crate::TriMesh;

crate::vocabulary! {
    /// A built-in shape.
    ///
    /// ```
    /// use shatter_geom::shapes::Shape;
    /// let cube: Shape = "cube".parse().expect("a shape");
    /// assert_eq!(cube.mesh().positions.len(), 24);
    /// ```
    pub enum Shape: "shape" {
        /// Unity's cube: 24 vertices (8 corners split per face), side 1.
        Cube = "cube",
        /// Unity's capsule: 550 vertices.
        Capsule = "capsule",
        /// Unity's cylinder: 88 vertices.
        Cylinder = "cylinder",
        /// A UV sphere (radius 0.5).
        Sphere = "sphere",
        /// A torus (not simply connected).
        Torus = "torus",
        /// The bundled concave low-poly bird (about 958 vertices, 1394 triangles).
        Bird = "bird",
    }
}

impl Shape {
    /// The shape's mesh, with default parameters: `sphere` radius 0.5, 24 × 16; `torus`
    /// radii 0.5 and 0.2, 32 × 16.
    pub fn mesh(self) -> TriMesh {
        match self {
            Shape::Cube => cube(),
            Shape::Capsule => capsule(),
            Shape::Cylinder => cylinder(),
            Shape::Sphere => sphere(24, 16),
            Shape::Torus => torus(0.5, 0.2, 32, 16),
            Shape::Bird => bird(),
        }
    }
}

/// Names accepted by [`by_name`] (the words of [`Shape`]).
pub const NAMES: &[&str] = Shape::NAMES;

/// A built-in shape by name, with default parameters (see [`Shape::mesh`]).
///
/// ```
/// use shatter_geom::shapes;
/// assert_eq!(shapes::by_name("cube").map(|m| m.positions.len()), Some(24));
/// assert!(shapes::by_name("teapot").is_none());
/// ```
pub fn by_name(name: &str) -> Option<TriMesh> {
    name.parse::<Shape>().ok().map(Shape::mesh)
}
