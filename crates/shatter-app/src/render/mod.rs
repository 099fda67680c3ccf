//! The stage the simulation is drawn on (its pieces are drawn by bevy_shatter).

pub mod scene;

pub use bevy_shatter::world::RenderStats;
pub use scene::SceneRenderPlugin;
