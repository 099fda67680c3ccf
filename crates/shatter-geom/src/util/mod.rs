//! Small shared pieces with no geometry of their own: disjoint sets, fast hashing of
//! integer keys, bounds of point sets, a grid for nearest-item queries. A leaf: it uses
//! nothing else of the crate.

mod bounds;
mod fast_hash;
mod shell_grid;
mod union_find;

pub(crate) use bounds::bounds;
pub use bounds::box_corners;
pub(crate) use fast_hash::{FastMap, FastSet};
pub(crate) use shell_grid::ShellGrid;
pub use union_find::UnionFind;
