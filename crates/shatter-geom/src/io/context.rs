//! What every reader works with: the main file's name and folder, the files it may read
//! (a [`FileSource`]), the warnings so far; and the readers' size limit.

use std::path::{Path, PathBuf};

use super::files::FileSource;
use super::{LoadWarning, WarningKind};

/// The most triangles a file may produce (after triangulating polygons and instancing
/// glTF meshes at every node that uses them): a model of this many triangles with every
/// attribute takes about 2.5 GB.
pub const MAX_TRIANGLES: usize = 20_000_000;

/// What a reader works with: the file's name, where its references are resolved, the
/// files it may read, and the warnings so far.
pub(crate) struct ReadContext<'a> {
    /// The main file's name (as given), for messages.
    pub path: &'a Path,
    /// The folder references are resolved against.
    pub dir: PathBuf,
    files: &'a dyn FileSource,
    pub warnings: Vec<LoadWarning>,
}

impl<'a> ReadContext<'a> {
    /// A context for the file `path`, its references resolved against its folder and
    /// read from `files`.
    pub fn new(path: &'a Path, files: &'a dyn FileSource) -> ReadContext<'a> {
        let dir = match path.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::new(),
        };
        ReadContext {
            path,
            dir,
            files,
            warnings: Vec::new(),
        }
    }

    /// The path of a file referenced as `reference` (relative to the main file's folder).
    pub fn resolve(&self, reference: &Path) -> PathBuf {
        if reference.is_absolute() {
            reference.to_path_buf()
        } else {
            self.dir.join(reference)
        }
    }

    /// Reads a referenced file.
    pub fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        self.files.read(path)
    }

    /// Records a warning, its message prefixed with the main file's name.
    pub fn warn(&mut self, kind: WarningKind, count: usize, message: impl AsRef<str>) {
        let message = format!("{}: {}", self.path.display(), message.as_ref());
        self.warnings.push(LoadWarning::new(kind, count, message));
    }
}
