//! Bond models: the thesis's breakable joints and cluster bodies with a bond graph.

pub(crate) mod clusters;
pub(crate) mod held;
pub(crate) mod joints;
pub(crate) mod live;
pub(crate) mod split;
pub(crate) mod tags;
