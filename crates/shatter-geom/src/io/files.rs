//! Where the readers find the files a model refers to: a `.gltf`'s buffers and images, an
//! OBJ's material library and its textures.
//!
//! A reader asks a [`FileSource`] for each file by path (resolved against the main file's
//! folder). [`FileSystem`] reads the disk; [`MemoryFiles`] holds files by name, for a
//! program that has the bytes already (the web page hands over a `.gltf` with its `.bin`
//! and textures, or an OBJ with its MTL and images); [`Layered`] tries one source, then
//! another.
//!
//! ```
//! use shatter_geom::io::{self, MemoryFiles, MeshFormat};
//! let files = MemoryFiles::new();
//! files.insert("box.mtl", b"newmtl red\nKd 1 0 0\n".to_vec());
//! let obj = b"mtllib box.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
//! let loaded = io::parse_model_with(obj, MeshFormat::Obj, "box.obj", &files).unwrap();
//! assert_eq!(loaded.model.materials[0].name, "red");
//! assert_eq!(loaded.model.materials[0].base_color, [1.0, 0.0, 0.0, 1.0]);
//! assert!(loaded.warnings.is_empty());
//! ```

use std::collections::BTreeMap;
use std::path::{Component, Path, PathBuf};
use std::sync::{Arc, PoisonError, RwLock};

/// Something the readers can read files from.
pub trait FileSource {
    /// The bytes of the file at `path`.
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>>;
}

/// The file system.
#[derive(Debug, Clone, Copy, Default)]
pub struct FileSystem;

impl FileSource for FileSystem {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        std::fs::read(path)
    }
}

/// No files at all: every read fails (what [`parse_model`](super::parse_model) uses, so
/// a reference to another file becomes a warning).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoFiles;

impl FileSource for NoFiles {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        Err(not_found(path))
    }
}

/// `first`, and where it has no such file, `second`.
#[derive(Debug, Clone, Copy)]
pub struct Layered<A, B>(pub A, pub B);

impl<A: FileSource, B: FileSource> FileSource for Layered<A, B> {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        match self.0.read(path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => self.1.read(path),
            other => other,
        }
    }
}

impl<T: FileSource + ?Sized> FileSource for &T {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        (**self).read(path)
    }
}

fn not_found(path: &Path) -> std::io::Error {
    std::io::Error::new(
        std::io::ErrorKind::NotFound,
        format!("no file {}", path.display()),
    )
}

/// Files held in memory under their names. A lookup tries the exact path, then the path
/// with `.` components and a leading `./` removed, then the one file of that file name
/// (so a texture the MTL names `textures/wood.jpg` is found when only `wood.jpg` was
/// handed over). Cheap to share: the bytes are reference-counted, and the set can be
/// changed through a shared reference.
#[derive(Debug, Default)]
pub struct MemoryFiles {
    files: RwLock<BTreeMap<PathBuf, Arc<[u8]>>>,
}

impl Clone for MemoryFiles {
    fn clone(&self) -> Self {
        MemoryFiles {
            files: RwLock::new(self.map().clone()),
        }
    }
}

impl MemoryFiles {
    /// No files.
    pub fn new() -> MemoryFiles {
        MemoryFiles::default()
    }

    // A panic while holding the lock cannot leave the map half-updated (every operation
    // is one insert, remove or lookup), so a poisoned lock is still usable.
    fn map(&self) -> std::sync::RwLockReadGuard<'_, BTreeMap<PathBuf, Arc<[u8]>>> {
        self.files.read().unwrap_or_else(PoisonError::into_inner)
    }

    /// Adds (or replaces) the file `name`.
    pub fn insert(&self, name: impl AsRef<Path>, bytes: Vec<u8>) {
        self.files
            .write()
            .unwrap_or_else(PoisonError::into_inner)
            .insert(normalize(name.as_ref()), bytes.into());
    }

    /// Forgets the file `name`; returns whether there was one.
    pub fn remove(&self, name: impl AsRef<Path>) -> bool {
        self.files
            .write()
            .unwrap_or_else(PoisonError::into_inner)
            .remove(&normalize(name.as_ref()))
            .is_some()
    }

    /// The file `name` (exact name after normalisation), if held.
    pub fn get(&self, name: impl AsRef<Path>) -> Option<Arc<[u8]>> {
        self.map().get(&normalize(name.as_ref())).cloned()
    }

    /// Whether the file `name` is held.
    pub fn contains(&self, name: impl AsRef<Path>) -> bool {
        self.get(name).is_some()
    }

    /// The names held, in order.
    pub fn names(&self) -> Vec<PathBuf> {
        self.map().keys().cloned().collect()
    }

    fn find(&self, path: &Path) -> Option<Arc<[u8]>> {
        let map = self.map();
        let key = normalize(path);
        if let Some(bytes) = map.get(&key) {
            return Some(bytes.clone());
        }
        let name = key.file_name()?;
        let mut same_name = map.iter().filter(|(k, _)| k.file_name() == Some(name));
        match (same_name.next(), same_name.next()) {
            (Some((_, bytes)), None) => Some(bytes.clone()),
            _ => None,
        }
    }
}

impl FileSource for MemoryFiles {
    fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.find(path)
            .map(|b| b.to_vec())
            .ok_or_else(|| not_found(path))
    }
}

/// `path` without `.` components (a leading `./` included); `a/../b` is kept as it is.
fn normalize(path: &Path) -> PathBuf {
    path.components()
        .filter(|c| !matches!(c, Component::CurDir))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn memory_files_find_by_normalised_path_then_by_unique_name() {
        let files = MemoryFiles::new();
        files.insert("./models/a.obj", b"a".to_vec());
        files.insert("tex/wood.jpg", b"w".to_vec());
        assert_eq!(
            files.read(Path::new("models/a.obj")).ok(),
            Some(b"a".to_vec())
        );
        assert_eq!(
            files.read(Path::new("other/dir/wood.jpg")).ok(),
            Some(b"w".to_vec())
        );
        files.insert("more/wood.jpg", b"x".to_vec());
        // Two files of that name: ambiguous, so not found.
        let err = files.read(Path::new("other/wood.jpg")).unwrap_err();
        assert_eq!(err.kind(), std::io::ErrorKind::NotFound);
    }

    #[test]
    fn layered_falls_back_only_when_the_first_has_no_file() {
        let a = MemoryFiles::new();
        a.insert("x", b"from a".to_vec());
        let b = MemoryFiles::new();
        b.insert("x", b"from b".to_vec());
        b.insert("y", b"only b".to_vec());
        let both = Layered(&a, &b);
        assert_eq!(both.read(Path::new("x")).ok(), Some(b"from a".to_vec()));
        assert_eq!(both.read(Path::new("y")).ok(), Some(b"only b".to_vec()));
        assert!(both.read(Path::new("z")).is_err());
    }
}
