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

/// Names accepted by [`by_name`].
pub const NAMES: [&str; 6] = ["cube", "capsule", "cylinder", "sphere", "torus", "bird"];

/// A built-in shape by name, with default parameters: `cube`, `capsule`, `cylinder`,
/// `sphere` (radius 0.5, 24 × 16), `torus` (radii 0.5 and 0.2, 32 × 16) or `bird`.
///
/// ```
/// use shatter_geom::shapes;
/// assert_eq!(shapes::by_name("cube").map(|m| m.positions.len()), Some(24));
/// assert!(shapes::by_name("teapot").is_none());
/// ```
pub fn by_name(name: &str) -> Option<TriMesh> {
    match name {
        "cube" => Some(cube()),
        "capsule" => Some(capsule()),
        "cylinder" => Some(cylinder()),
        "sphere" => Some(sphere(24, 16)),
        "torus" => Some(torus(0.5, 0.2, 32, 16)),
        "bird" => Some(bird()),
        _ => None,
    }
}
