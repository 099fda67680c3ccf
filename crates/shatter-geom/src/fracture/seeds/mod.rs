//! Where the cuts go: seed patterns for Voronoi fracture, and inside tests and uniform
//! sampling inside a solid.

pub(crate) mod inside;
pub(crate) mod patterns;
