//! The fracture methods: each turns the input solid into pieces and their bonds.

pub(crate) mod grid;
pub(crate) mod slice;
pub(crate) mod tetra;
pub(crate) mod voronoi;
