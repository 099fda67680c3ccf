//! The mesh files a user picked in the web page, and the files they refer to (a
//! `.gltf`'s `.bin`, an OBJ's `.mtl`, textures).
//!
//! The page hands each file to the binary's `add_mesh`, a browser callback that has no
//! handle on the running app, so the set is one per process and lives here, in the app.
//! The libraries hold no files of their own: the sandbox's world reads from this set
//! ([`shatter_sim::World::set_files`]), and so do the panels' checks
//! ([`crate::sim_bridge::check_custom_mesh`]). A native build never adds to it, and reads
//! the disk alone.

use std::sync::{Arc, OnceLock};

use bevy_shatter::world::MemoryFiles;

/// The picked files (empty in a native build).
pub fn picked_files() -> &'static Arc<MemoryFiles> {
    static FILES: OnceLock<Arc<MemoryFiles>> = OnceLock::new();
    FILES.get_or_init(Arc::default)
}
