//! The bond graph: bonds through matching caps, and merging small pieces into bonded
//! neighbours.

pub(crate) mod caps;
pub(crate) mod merge;
