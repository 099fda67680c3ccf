//! Animated glTF (GLB) export: one node per fragment with its mesh, keyframed over time.

mod glb_writer;
mod scene;

pub use glb_writer::{animated_glb_bytes, write_animated_glb};
pub use scene::{AnimatedNode, AnimatedScene, FragmentMesh, Pose};
