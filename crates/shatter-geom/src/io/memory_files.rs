//! Mesh files held in memory under a name, which [`load_mesh`](super::load_mesh) reads
//! before the file system: how the web build, which has no file system, takes meshes the
//! user picked in the page (and how a program can hand meshes to scene files without
//! writing them to disk).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};

fn files() -> MutexGuard<'static, BTreeMap<PathBuf, Arc<[u8]>>> {
    static FILES: OnceLock<Mutex<BTreeMap<PathBuf, Arc<[u8]>>>> = OnceLock::new();
    // A panic while holding the lock cannot leave the map half-updated (every operation
    // is a single insert, remove or lookup), so a poisoned lock is still usable.
    FILES
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Registers `bytes` as the content of the file `name` (replacing an earlier one).
///
/// ```
/// use shatter_geom::io;
/// let obj = b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
/// io::add_memory_file("picked/tet.obj", obj.to_vec());
/// let tet = io::load_mesh("picked/tet.obj").expect("read from memory");
/// assert_eq!(tet.triangles.len(), 4);
/// assert!(io::remove_memory_file("picked/tet.obj"));
/// assert!(io::load_mesh("picked/tet.obj").is_err());
/// ```
pub fn add_memory_file(name: impl AsRef<Path>, bytes: Vec<u8>) {
    files().insert(name.as_ref().to_path_buf(), bytes.into());
}

/// Forgets the in-memory file `name`; returns whether there was one.
pub fn remove_memory_file(name: impl AsRef<Path>) -> bool {
    files().remove(name.as_ref()).is_some()
}

/// The content of the in-memory file `name`, if registered.
pub fn memory_file(name: impl AsRef<Path>) -> Option<Arc<[u8]>> {
    files().get(name.as_ref()).cloned()
}

/// Names of the in-memory files, in order.
pub fn memory_file_names() -> Vec<PathBuf> {
    files().keys().cloned().collect()
}
