//! Where the Scene field's Save and Load keep scene files: the file system on the
//! desktop; the browser's `localStorage` in the web build (a page cannot write files),
//! keyed by the name typed in the field.

use std::path::{Path, PathBuf};

use thiserror::Error;

/// Why a scene could not be saved or read. Its `Display` is the message the user sees.
#[derive(Debug, Error)]
pub enum StoreError {
    /// The folder a scene would be saved in does not exist (desktop).
    #[error("folder '{}' does not exist", dir.display())]
    NoFolder {
        /// The folder.
        dir: PathBuf,
    },
    /// The scene file could not be written (desktop).
    #[error("cannot write '{}': {source}", path.display())]
    Write {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The scene file could not be read (desktop).
    #[error("cannot read '{}': {source}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
    /// The browser gives the page no `localStorage` (web).
    #[error("this browser gives the page no localStorage")]
    NoLocalStorage,
    /// `localStorage` refused the scene (web).
    #[error("cannot save '{}' (storage full?)", path.display())]
    StorageFull {
        /// The scene's name.
        path: PathBuf,
    },
    /// No scene of this name was saved (web).
    #[error("no saved scene '{}'", path.display())]
    NotSaved {
        /// The scene's name.
        path: PathBuf,
    },
}

/// Whether a scene of this name can be loaded.
pub fn exists(path: &Path) -> bool {
    imp::exists(path)
}

/// Whether a scene of this name could be saved (its folder exists).
pub fn can_save(path: &Path) -> Result<(), StoreError> {
    imp::can_save(path)
}

/// Saves the scene text.
pub fn write(path: &Path, text: &str) -> Result<(), StoreError> {
    imp::write(path, text)
}

/// Reads a scene's text.
pub fn read(path: &Path) -> Result<String, StoreError> {
    imp::read(path)
}

#[cfg(not(target_arch = "wasm32"))]
mod imp {
    use std::path::{Path, PathBuf};

    use super::StoreError;

    pub fn exists(path: &Path) -> bool {
        path.is_file()
    }

    pub fn can_save(path: &Path) -> Result<(), StoreError> {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        if dir.is_dir() {
            Ok(())
        } else {
            Err(StoreError::NoFolder { dir })
        }
    }

    pub fn write(path: &Path, text: &str) -> Result<(), StoreError> {
        std::fs::write(path, text).map_err(|source| StoreError::Write {
            path: path.to_path_buf(),
            source,
        })
    }

    pub fn read(path: &Path) -> Result<String, StoreError> {
        std::fs::read_to_string(path).map_err(|source| StoreError::Read {
            path: path.to_path_buf(),
            source,
        })
    }
}

#[cfg(target_arch = "wasm32")]
mod imp {
    use std::path::Path;

    use super::StoreError;

    fn key(path: &Path) -> String {
        format!("shatter-scene:{}", path.display())
    }

    fn storage() -> Result<web_sys::Storage, StoreError> {
        web_sys::window()
            .and_then(|w| w.local_storage().ok().flatten())
            .ok_or(StoreError::NoLocalStorage)
    }

    pub fn exists(path: &Path) -> bool {
        storage()
            .ok()
            .and_then(|s| s.get_item(&key(path)).ok().flatten())
            .is_some()
    }

    pub fn can_save(_path: &Path) -> Result<(), StoreError> {
        storage().map(|_| ())
    }

    pub fn write(path: &Path, text: &str) -> Result<(), StoreError> {
        storage()?
            .set_item(&key(path), text)
            .map_err(|_| StoreError::StorageFull {
                path: path.to_path_buf(),
            })
    }

    pub fn read(path: &Path) -> Result<String, StoreError> {
        storage()?
            .get_item(&key(path))
            .ok()
            .flatten()
            .ok_or_else(|| StoreError::NotSaved {
                path: path.to_path_buf(),
            })
    }
}
