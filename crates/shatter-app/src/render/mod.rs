//! Drawing the simulation: fragment meshes and the scene around them.

pub mod fragment_mesh;
pub mod scene;

pub use scene::SceneRenderPlugin;
